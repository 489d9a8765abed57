//! Accuracy metrics between two RGB8 frames of the same size.
//!
//! Conventions:
//!
//! * Frames are row-major `[u8; 3]` pixels plus a coverage mask (and,
//!   optionally, the id of the visible object per pixel), see [`FrameView`].
//! * Errors are absolute differences in 8-bit levels, per channel.
//! * `max_abs_error`, `mean_abs_error` and `share_over_1` only look at
//!   pixels covered in *both* frames; when there are none they are `0`.
//! * `psnr_db` looks at every channel of every pixel, covered or not, with
//!   peak 255: `10 * log10(255^2 / MSE)`. It is `+inf` when the frames are
//!   identical (or empty); in serialised form `+inf` is written as `null`
//!   and `null` reads back as `+inf`.

use std::fmt;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A borrowed frame to compare.
#[derive(Clone, Copy, Debug)]
pub struct FrameView<'a> {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels, row-major.
    pub rgb: &'a [[u8; 3]],
    /// `width * height` coverage flags.
    pub covered: &'a [bool],
    /// Optional `width * height` ids of the visible object.
    pub object: Option<&'a [Option<usize>]>,
}

/// Comparison results; the field names are part of the report format.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// Pixels covered in exactly one of the two frames.
    pub coverage_mismatch: u64,
    /// Largest channel difference over pixels covered in both, in levels.
    pub max_abs_error: u8,
    /// Mean channel difference over pixels covered in both (all three
    /// channels of each), in levels.
    pub mean_abs_error: f64,
    /// Peak signal-to-noise ratio over the whole frame in dB; `+inf` when
    /// identical, serialised as `null`.
    #[serde(serialize_with = "psnr_out", deserialize_with = "psnr_in")]
    pub psnr_db: f64,
    /// Share (0 to 1) of pixels covered in both whose largest channel
    /// difference exceeds 1 level.
    pub share_over_1: f64,
    /// Pixels covered in both whose visible object differs; `None` unless
    /// both frames carry object ids.
    pub depth_order_disagreements: Option<u64>,
}

/// Writes a finite PSNR as a number and `+inf` as `null`.
fn psnr_out<S: Serializer>(psnr: &f64, s: S) -> Result<S::Ok, S::Error> {
    if psnr.is_finite() {
        s.serialize_some(psnr)
    } else {
        s.serialize_none()
    }
}

/// Reads `null` as `+inf`.
fn psnr_in<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::INFINITY))
}

/// Why two frames could not be compared.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MetricsError {
    /// The frames have different sizes.
    SizeMismatch {
        /// Size of the first frame.
        a: (u32, u32),
        /// Size of the second frame.
        b: (u32, u32),
    },
    /// A buffer's length is not `width * height`.
    BufferLength {
        /// Which buffer, e.g. `"a.rgb"`.
        buffer: &'static str,
        /// `width * height`.
        expected: usize,
        /// Actual length.
        actual: usize,
    },
}

impl fmt::Display for MetricsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::SizeMismatch { a, b } => {
                write!(f, "frame sizes differ: {}x{} vs {}x{}", a.0, a.1, b.0, b.1)
            }
            Self::BufferLength {
                buffer,
                expected,
                actual,
            } => write!(f, "{buffer} has {actual} entries, expected {expected}"),
        }
    }
}

impl std::error::Error for MetricsError {}

/// Checks a buffer's length.
fn check_len(buffer: &'static str, expected: usize, actual: usize) -> Result<(), MetricsError> {
    if expected == actual {
        Ok(())
    } else {
        Err(MetricsError::BufferLength {
            buffer,
            expected,
            actual,
        })
    }
}

/// Checks both frames' sizes and buffer lengths; returns the pixel count.
pub(crate) fn check(a: &FrameView<'_>, b: &FrameView<'_>) -> Result<usize, MetricsError> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(MetricsError::SizeMismatch {
            a: (a.width, a.height),
            b: (b.width, b.height),
        });
    }
    let n = usize::try_from(u64::from(a.width) * u64::from(a.height)).unwrap_or(usize::MAX);
    check_len("a.rgb", n, a.rgb.len())?;
    check_len("b.rgb", n, b.rgb.len())?;
    check_len("a.covered", n, a.covered.len())?;
    check_len("b.covered", n, b.covered.len())?;
    if let Some(ids) = a.object {
        check_len("a.object", n, ids.len())?;
    }
    if let Some(ids) = b.object {
        check_len("b.object", n, ids.len())?;
    }
    Ok(n)
}

/// Largest absolute channel difference between two pixels.
pub(crate) fn pixel_max_diff(p: [u8; 3], q: [u8; 3]) -> u8 {
    (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0)
}

/// Compares two frames; see the module docs for the definitions.
pub fn compare(a: &FrameView<'_>, b: &FrameView<'_>) -> Result<Metrics, MetricsError> {
    let n = check(a, b)?;
    let mut coverage_mismatch = 0u64;
    let mut both = 0u64;
    let mut over_1 = 0u64;
    let mut max_abs_error = 0u8;
    let mut abs_sum = 0u64;
    let mut sq_sum = 0u64;
    let mut disagreements = 0u64;
    for i in 0..n {
        let (p, q) = (a.rgb[i], b.rgb[i]);
        for c in 0..3 {
            let d = u64::from(p[c].abs_diff(q[c]));
            sq_sum += d * d;
        }
        if a.covered[i] != b.covered[i] {
            coverage_mismatch += 1;
        }
        if !(a.covered[i] && b.covered[i]) {
            continue;
        }
        both += 1;
        let m = pixel_max_diff(p, q);
        max_abs_error = max_abs_error.max(m);
        over_1 += u64::from(m > 1);
        abs_sum += (0..3).map(|c| u64::from(p[c].abs_diff(q[c]))).sum::<u64>();
        if let (Some(ia), Some(ib)) = (a.object, b.object) {
            disagreements += u64::from(ia[i] != ib[i]);
        }
    }
    let ratio = |num: u64, den: u64| {
        if den == 0 {
            0.0
        } else {
            num as f64 / den as f64
        }
    };
    let psnr_db = if sq_sum == 0 {
        f64::INFINITY
    } else {
        let mse = sq_sum as f64 / (3.0 * n as f64);
        10.0 * (255.0 * 255.0 / mse).log10()
    };
    Ok(Metrics {
        coverage_mismatch,
        max_abs_error,
        mean_abs_error: ratio(abs_sum, 3 * both),
        psnr_db,
        share_over_1: ratio(over_1, both),
        depth_order_disagreements: (a.object.is_some() && b.object.is_some())
            .then_some(disagreements),
    })
}

//! PNG input/output, difference heat maps and reference-image checks.
//!
//! Images are row-major `[u8; 3]` RGB pixels, row 0 at the top.
//!
//! Heat map colours ([`diff_heatmap`]), per pixel:
//!
//! * black `(0, 0, 0)`: identical colour and coverage;
//! * magenta `(255, 0, 255)`: covered in one frame only;
//! * otherwise a viridis-like ramp by `e`, the largest channel difference
//!   in levels (1 to 255), on a log scale `t = ln(e) / ln(255)` so that
//!   1-level errors are visible: `t = 0` dark purple `(68, 1, 84)`,
//!   `0.25` blue `(59, 82, 139)`, `0.5` teal `(33, 145, 140)`, `0.75` green
//!   `(94, 201, 98)`, `1` yellow `(253, 231, 37)`, linear in between.
//!   Perceptually ordered and free of magenta.
//!
//! Reference images ([`check_reference`]) live in
//! `host-tests/tests/images/NAME.png`; mismatches are written to
//! `host-tests/tests/diff/NAME.png` (git-ignored) as three panels side by
//! side: expected | differing pixels in white on black | actual.

use std::fmt;
use std::fs::File;
use std::io::{self, BufReader, Write};
use std::path::{Path, PathBuf};

use crate::metrics::{pixel_max_diff, FrameView, MetricsError};

/// A decoded 8-bit RGB image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels, row-major.
    pub pixels: Vec<[u8; 3]>,
}

/// An `InvalidInput` I/O error with a message.
fn invalid(msg: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, msg)
}

/// `width * height` as `usize`, if it fits.
fn pixel_count(width: u32, height: u32) -> Option<usize> {
    usize::try_from(u64::from(width) * u64::from(height)).ok()
}

/// Encodes `rgb` as an 8-bit RGB PNG into `out`.
fn encode(out: impl Write, width: u32, height: u32, rgb: &[[u8; 3]]) -> io::Result<()> {
    let mut encoder = png::Encoder::new(out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(rgb.as_flattened())?;
    writer.finish()?;
    Ok(())
}

/// Writes an 8-bit RGB PNG atomically
/// ([`write_atomically`](crate::output::write_atomically)): no half-written
/// file is ever left at `path`. Fails with `InvalidInput` if `rgb.len()` is not
/// `width * height` or the size is zero (PNG cannot store empty images).
pub fn write_png(
    path: impl AsRef<Path>,
    width: u32,
    height: u32,
    rgb: &[[u8; 3]],
) -> io::Result<()> {
    let path = path.as_ref();
    if width == 0 || height == 0 || pixel_count(width, height) != Some(rgb.len()) {
        return Err(invalid(format!(
            "{} pixels do not make a non-empty {width}x{height} image",
            rgb.len()
        )));
    }
    crate::output::write_atomically(path, |out| encode(out, width, height, rgb))
}

/// Reads a PNG of any colour type and bit depth as 8-bit RGB (palettes and
/// grey are expanded, 16-bit samples reduced to 8 bits, alpha dropped).
/// Decoding errors come back as `InvalidData`.
pub fn read_png(path: impl AsRef<Path>) -> io::Result<RgbImage> {
    let mut decoder = png::Decoder::new(BufReader::new(File::open(path)?));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().map_err(io::Error::from)?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| invalid("PNG too large".into()))?;
    let mut buf = vec![0; size];
    let info = reader.next_frame(&mut buf).map_err(io::Error::from)?;
    let channels = match info.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                "palette was not expanded",
            ))
        }
    };
    if info.line_size == 0 {
        return Err(io::Error::new(io::ErrorKind::InvalidData, "empty PNG rows"));
    }
    let mut pixels = Vec::with_capacity(info.width as usize * info.height as usize);
    for row in buf.chunks(info.line_size).take(info.height as usize) {
        for px in row.chunks_exact(channels).take(info.width as usize) {
            pixels.push(if channels < 3 {
                [px[0]; 3]
            } else {
                [px[0], px[1], px[2]]
            });
        }
    }
    Ok(RgbImage {
        width: info.width,
        height: info.height,
        pixels,
    })
}

/// The heat map ramp's control points (see the module docs).
const RAMP: [[u8; 3]; 5] = [
    [68, 1, 84],
    [59, 82, 139],
    [33, 145, 140],
    [94, 201, 98],
    [253, 231, 37],
];

/// Heat map colour for a largest channel difference `e` (0 is black).
pub fn heat_color(e: u8) -> [u8; 3] {
    if e == 0 {
        return [0, 0, 0];
    }
    let t = f64::from(e).ln() / 255f64.ln() * (RAMP.len() - 1) as f64;
    let k = (t.floor() as usize).min(RAMP.len() - 2);
    let f = t - k as f64;
    let (a, b) = (RAMP[k], RAMP[k + 1]);
    std::array::from_fn(|c| {
        (f64::from(a[c]) + (f64::from(b[c]) - f64::from(a[c])) * f).round() as u8
    })
}

/// Colour marking a pixel covered in only one frame.
pub const COVERAGE_MISMATCH_COLOR: [u8; 3] = [255, 0, 255];

/// Per-pixel difference picture of two frames (see the module docs for the
/// colours). Fails if the frames' sizes or buffer lengths disagree.
pub fn diff_heatmap(a: &FrameView<'_>, b: &FrameView<'_>) -> Result<Vec<[u8; 3]>, MetricsError> {
    crate::metrics::check(a, b)?;
    Ok((0..a.rgb.len())
        .map(|i| {
            if a.covered[i] != b.covered[i] {
                COVERAGE_MISMATCH_COLOR
            } else {
                heat_color(pixel_max_diff(a.rgb[i], b.rgb[i]))
            }
        })
        .collect())
}

/// Why a reference-image check failed.
#[derive(Debug)]
pub enum ReferenceError {
    /// The name is empty or has characters other than ASCII letters,
    /// digits, `_` and `-`.
    InvalidName(String),
    /// `rgb.len()` is not `width * height`, or the image is empty.
    BadImage(String),
    /// Reading or writing a file failed.
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: io::Error,
    },
    /// There is no reference image yet.
    Missing(PathBuf),
    /// The reference has a different size; the actual image was written
    /// to `diff`.
    SizeMismatch {
        /// Reference size.
        expected: (u32, u32),
        /// Actual size.
        actual: (u32, u32),
        /// Where the actual image was written.
        diff: PathBuf,
    },
    /// Some pixels differ; the three-panel image was written to `diff`.
    Mismatch {
        /// Where the three-panel image was written.
        diff: PathBuf,
        /// Number of differing pixels.
        differing: usize,
    },
}

impl fmt::Display for ReferenceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidName(n) => write!(f, "invalid reference image name {n:?}"),
            Self::BadImage(m) => write!(f, "bad image: {m}"),
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Missing(p) => write!(
                f,
                "{} is missing; run with MAKE_REF=1 to create it",
                p.display()
            ),
            Self::SizeMismatch {
                expected,
                actual,
                diff,
            } => write!(
                f,
                "reference is {}x{} but the image is {}x{}; actual image written to {}",
                expected.0,
                expected.1,
                actual.0,
                actual.1,
                diff.display()
            ),
            Self::Mismatch { diff, differing } => write!(
                f,
                "{differing} pixels differ from the reference; see {}",
                diff.display()
            ),
        }
    }
}

impl std::error::Error for ReferenceError {}

/// Wraps an I/O error with its path.
fn io_at(path: &Path) -> impl FnOnce(io::Error) -> ReferenceError + '_ {
    move |source| ReferenceError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Compares `rgb` with `host-tests/tests/images/NAME.png`. With the
/// environment variable `MAKE_REF=1` it (re)writes the reference instead.
/// See [`check_reference_in`].
pub fn check_reference(
    name: &str,
    width: u32,
    height: u32,
    rgb: &[[u8; 3]],
) -> Result<(), ReferenceError> {
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let make_ref = std::env::var_os("MAKE_REF").is_some_and(|v| v == "1");
    check_reference_in(
        &tests.join("images"),
        &tests.join("diff"),
        name,
        width,
        height,
        rgb,
        make_ref,
    )
}

/// Compares `rgb` exactly with `images/NAME.png`.
///
/// * `make_ref`: write `rgb` as the reference (creating `images`) and
///   succeed.
/// * Match: succeed and remove a stale `diffs/NAME.png`.
/// * Mismatch: write `diffs/NAME.png` (expected | mask | actual, the mask
///   white where pixels differ) and return [`ReferenceError::Mismatch`]
///   naming it and the count of differing pixels.
pub fn check_reference_in(
    images: &Path,
    diffs: &Path,
    name: &str,
    width: u32,
    height: u32,
    rgb: &[[u8; 3]],
    make_ref: bool,
) -> Result<(), ReferenceError> {
    let valid = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
    if name.is_empty() || !name.chars().all(valid) {
        return Err(ReferenceError::InvalidName(name.into()));
    }
    let bad =
        || ReferenceError::BadImage(format!("{} pixels for a {width}x{height} image", rgb.len()));
    let Some(panels_width) = width.checked_mul(3) else {
        return Err(bad());
    };
    if width == 0 || height == 0 || pixel_count(width, height) != Some(rgb.len()) {
        return Err(bad());
    }
    let file = format!("{name}.png");
    let reference = images.join(&file);
    let diff = diffs.join(&file);
    if make_ref {
        std::fs::create_dir_all(images).map_err(io_at(images))?;
        return write_png(&reference, width, height, rgb).map_err(io_at(&reference));
    }
    if !reference.exists() {
        return Err(ReferenceError::Missing(reference));
    }
    let expected = read_png(&reference).map_err(io_at(&reference))?;
    let write_diff = |w: u32, pixels: &[[u8; 3]]| -> Result<(), ReferenceError> {
        std::fs::create_dir_all(diffs).map_err(io_at(diffs))?;
        write_png(&diff, w, height, pixels).map_err(io_at(&diff))
    };
    if (expected.width, expected.height) != (width, height) {
        write_diff(width, rgb)?;
        return Err(ReferenceError::SizeMismatch {
            expected: (expected.width, expected.height),
            actual: (width, height),
            diff,
        });
    }
    let differing = expected
        .pixels
        .iter()
        .zip(rgb)
        .filter(|(e, a)| e != a)
        .count();
    if differing == 0 {
        // Best effort: there is usually no stale diff to remove.
        let _ = std::fs::remove_file(&diff);
        return Ok(());
    }
    let w = width as usize;
    let mut panels = Vec::with_capacity(3 * rgb.len());
    for (e_row, a_row) in expected.pixels.chunks(w).zip(rgb.chunks(w)) {
        panels.extend_from_slice(e_row);
        panels.extend(
            e_row
                .iter()
                .zip(a_row)
                .map(|(e, a)| if e == a { [0; 3] } else { [255; 3] }),
        );
        panels.extend_from_slice(a_row);
    }
    write_diff(panels_width, &panels)?;
    Err(ReferenceError::Mismatch { diff, differing })
}

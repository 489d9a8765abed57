//! Errors reported by the ideal renderer for invalid input.

use std::fmt;

/// Why a scene (or raster input) was rejected. No public function of the
/// ideal renderer panics on bad input; it returns one of these instead.
#[derive(Clone, Debug, PartialEq)]
pub enum IdealError {
    /// A value was NaN or infinite; the string names it, e.g.
    /// `objects[0].triangles[3][1].position`.
    NonFinite(String),
    /// The vertical field of view (degrees) was not strictly inside `(0, 180)`.
    FieldOfView(f64),
    /// The near plane distance was not `> 0`.
    Near(f64),
    /// The far plane distance was not `> near`.
    Far {
        /// The near distance.
        near: f64,
        /// The offending far distance.
        far: f64,
    },
    /// The camera's eye and target coincide, so there is no view direction.
    EyeAtTarget,
    /// The camera's up vector is zero or parallel to the view direction.
    UpParallel,
    /// The directional light with this index has a zero direction.
    ZeroLightDirection(usize),
    /// An object's specular exponent was negative.
    Shininess {
        /// Index of the object.
        object: usize,
        /// The offending exponent.
        value: f64,
    },
    /// The frame has more than [`super::MAX_PIXELS`] pixels.
    FrameTooLarge {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
    },
    /// Finite input overflowed `f64` during projection or shading (for
    /// example coordinates near `1e300`).
    Overflow,
}

impl fmt::Display for IdealError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite(what) => write!(f, "{what} is NaN or infinite"),
            Self::FieldOfView(v) => {
                write!(f, "vertical field of view {v} deg is not in (0, 180)")
            }
            Self::Near(v) => write!(f, "near plane distance {v} is not > 0"),
            Self::Far { near, far } => {
                write!(f, "far plane distance {far} is not > near ({near})")
            }
            Self::EyeAtTarget => write!(f, "camera eye and target coincide"),
            Self::UpParallel => {
                write!(
                    f,
                    "camera up vector is zero or parallel to the view direction"
                )
            }
            Self::ZeroLightDirection(i) => write!(f, "directional light {i} has zero direction"),
            Self::Shininess { object, value } => {
                write!(f, "object {object} has negative shininess {value}")
            }
            Self::FrameTooLarge { width, height } => {
                write!(f, "frame {width}x{height} exceeds the pixel limit")
            }
            Self::Overflow => write!(f, "arithmetic overflow while rendering"),
        }
    }
}

impl std::error::Error for IdealError {}

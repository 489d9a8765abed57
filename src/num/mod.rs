//! Number formats and conversions.

//! Screen-space triangle rasterization.

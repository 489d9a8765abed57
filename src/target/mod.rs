//! Pixel formats, frame buffers, depth buffers and bands.

//! Host harness for `fixshade`.
#![forbid(unsafe_code)]
#![deny(missing_docs)]
pub mod bake;
pub mod builtin;
pub mod cli;
pub mod compare;
pub mod core_render;
pub mod firmware_scenes;

pub mod ideal;
pub mod image;
pub mod metrics;
pub mod output;
pub mod report;
pub mod scene_file;

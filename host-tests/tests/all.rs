//! The host crate's integration tests in one test binary: a module per
//! file of this folder, so each test keeps its file's name as its path
//! (`cargo test -p fixshade-host --test all bands::`, or
//! `cargo test -p fixshade-host --test all -- extreme_scene::`). One
//! binary links the host crate and its dependencies once instead of once
//! per file, and its tests share the machine's cores (a long one, such
//! as the firmware measurement of `cli_firmware`, runs beside the others
//! instead of before them).
//!
//! The tests that regenerate committed files keep binaries of their own
//! under the names their regeneration commands give
//! (`MAKE_DOCS=1 cargo test -p fixshade-host --test docs_tables`,
//! `MAKE_FIRMWARE_SCENES=1 ... --test firmware_scenes`,
//! `MAKE_MESHES=1 ... --test mesh_data`): see `host-tests/Cargo.toml`.

mod support;

mod bands;
mod budgets;
mod cli;
mod cli_animate;
mod cli_firmware;
mod cli_render;
mod clipping;
mod extreme_raster;
mod extreme_scene;
mod ideal;
mod metrics;
mod perspective;
mod prop_raster;
mod prop_scene;
mod reference_images;
mod report;
mod scene_file;
mod scene_scale;

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

mod accuracy_phong;
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

/// Every `.rs` file of this folder runs: it is a module above or a test
/// target of its own in `host-tests/Cargo.toml` (`autotests = false`:
/// cargo would not pick up a new file by itself).
#[test]
fn every_test_file_is_a_module_or_a_test_target() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let all = std::fs::read_to_string(root.join("tests/all.rs")).unwrap();
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    let mut files = 0;
    for entry in std::fs::read_dir(root.join("tests")).unwrap() {
        let path = entry.unwrap().path();
        let Some(stem) = path
            .extension()
            .filter(|e| *e == "rs")
            .and(path.file_stem())
            .and_then(|s| s.to_str())
        else {
            continue;
        };
        files += 1;
        if stem == "all" {
            continue;
        }
        assert!(
            all.contains(&format!("\nmod {stem};\n"))
                || manifest.contains(&format!("path = \"tests/{stem}.rs\"")),
            "host-tests/tests/{stem}.rs runs in no test binary: add `mod {stem};` to tests/all.rs"
        );
    }
    // all.rs, its 18 modules and the 3 test targets of their own, today:
    // the folder was read.
    assert!(files >= 22, "{files} test files");
}

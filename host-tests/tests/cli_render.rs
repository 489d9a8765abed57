//! `fixshade render` and `fixshade compare` as a user runs them.

use crate::support::{fixshade, TempDir};
use fixshade_host::builtin::load_builtin;
use fixshade_host::core_render::{crc32, render_core, CoreProfile};

#[test]
fn render_prints_the_crc_of_the_frame_bytes() {
    let dir = TempDir::new("render-crc");
    let out = fixshade(
        &dir,
        &[
            "render",
            "--scene",
            "dodeca-gouraud-n100",
            "--out",
            "f.png",
            "--profile",
            "fast",
            "--crc",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let desc = load_builtin("dodeca-gouraud-n100").unwrap();
    let frame = render_core(&desc, Some(CoreProfile::Fast)).unwrap();
    assert_eq!(
        frame.bytes.len(),
        160 * 160 * 2,
        "RGB565: two bytes a pixel"
    );
    assert!(
        text.contains(&format!("crc32 {:08x}", crc32(&frame.bytes))),
        "{text}"
    );
    let png = fixshade_host::image::read_png(dir.join("f.png")).unwrap();
    assert_eq!((png.width, png.height), (160, 160));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn compare_writes_frames_diff_and_metrics() {
    let dir = TempDir::new("render-cmp");
    let out = fixshade(
        &dir,
        &[
            "compare",
            "--scene",
            "grid-hotspot-phong",
            "--out",
            "cmp",
            "--profile",
            "precise",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in [
        "fixed.png",
        "float.png",
        "ideal.png",
        "diff.png",
        "metrics.json",
    ] {
        assert!(dir.join("cmp").join(f).is_file(), "{f} missing");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("cmp/metrics.json")).unwrap())
            .unwrap();
    for side in ["vs_float", "vs_ideal"] {
        for key in [
            "coverage_mismatch",
            "max_abs_error",
            "mean_abs_error",
            "psnr_db",
            "share_over_1",
        ] {
            assert!(json[side].get(key).is_some(), "{side}.{key} missing");
        }
    }
    // precise covers exactly its twin's pixels and is within a level.
    assert_eq!(json["vs_float"]["coverage_mismatch"], 0);
    assert!(json["vs_float"]["max_abs_error"].as_u64().unwrap() <= 1);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_render_input_exits_2_and_writes_nothing() {
    let dir = TempDir::new("render-bad");
    std::fs::write(dir.join("keep.png"), b"old").unwrap();
    for args in [
        vec![
            "render",
            "--scene",
            "dodeca-gouraud-n100",
            "--out",
            "keep.png",
            "--profile",
            "slow",
        ],
        vec!["render", "--scene", "no-such-scene", "--out", "keep.png"],
        vec!["render", "missing.toml", "--out", "keep.png"],
        vec!["compare", "--scene", "no-such-scene", "--out", "cmp"],
    ] {
        let out = fixshade(&dir, &args);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(!String::from_utf8_lossy(&out.stderr).is_empty());
    }
    assert_eq!(std::fs::read(dir.join("keep.png")).unwrap(), b"old");
    assert!(!dir.join("cmp").exists());
    // A folder that cannot be created: status 1.
    std::fs::write(dir.join("file"), b"x").unwrap();
    let out = fixshade(
        &dir,
        &["compare", "--scene", "big-face-phong", "--out", "file/sub"],
    );
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

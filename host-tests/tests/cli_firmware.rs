//! A user's scene measured on a chip (`fixshade measure-firmware --scene`,
//! the machinery of `report SCENE.toml --measure-firmware` and `pick
//! --scene SCENE.toml --measure-firmware`): the firmware generated for a
//! small scene with an OBJ mesh, built for the Cortex-M4F and run under
//! QEMU, when `qemu-system-arm`, `gcc` and the `thumbv7em-none-eabihf`
//! target are installed (else the test says why it skips). One profile,
//! one target: one firmware build (about 30 s on 2 cores when the core is
//! cached in the measurement's target folder).

use crate::support::{fixshade, TempDir};
use std::path::Path;
use std::process::Command;

/// A regular tetrahedron, counter-clockwise outwards: convex.
const TETRA: &str =
    "v 1 1 1\nv -1 -1 1\nv -1 1 -1\nv 1 -1 -1\nf 1 2 4\nf 1 4 3\nf 1 3 2\nf 2 3 4\n";

fn scene(width: u32) -> String {
    format!(
        "width = {width}\nheight = 48\npixel_format = \"rgb565\"\nbackground = [0, 0, 0]\n\n\
         [camera]\neye = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_deg = 40.0\n\n\
         [lighting]\nambient = 0.2\n\n\
         [[light]]\ntype = \"directional\"\ndirection = [0.3, 0.4, 1.0]\nintensity = 1.0\n\n\
         [[object]]\nmesh = \"tetra.obj\"\nshading = \"phong\"\ncrease_angle_deg = 30.0\n\
         rotate_deg = [20.0, 30.0, 0.0]\ncull_backfaces = true\n\
         material = {{ color = [0.9, 0.6, 0.3], ka = 0.2, kd = 0.6, ks = 0.4, shininess = 20.0 }}\n"
    )
}

/// A fresh temporary folder holding `tetra.obj`.
fn temp_dir(tag: &str) -> TempDir {
    let dir = TempDir::new(&format!("fw-{tag}"));
    dir.write("tetra.obj", TETRA);
    dir
}

/// Why the measurement cannot run here, if it cannot.
fn missing_tools() -> Option<String> {
    for tool in ["qemu-system-arm", "gcc"] {
        if Command::new(tool).arg("--version").output().is_err() {
            return Some(format!("{tool} is not installed"));
        }
    }
    let sysroot = Command::new("rustc")
        .args(["--print", "sysroot"])
        .output()
        .ok()?;
    let sysroot = String::from_utf8_lossy(&sysroot.stdout).trim().to_string();
    let lib = Path::new(&sysroot).join("lib/rustlib/thumbv7em-none-eabihf");
    if !lib.is_dir() {
        return Some("the thumbv7em-none-eabihf target is not installed".into());
    }
    None
}

#[test]
fn a_scene_the_firmware_cannot_take_is_bad_input_before_any_build() {
    let dir = temp_dir("bad");
    std::fs::write(dir.join("wide.toml"), scene(400)).unwrap();
    let out = fixshade(
        &dir,
        &[
            "measure-firmware",
            "--scene",
            "wide.toml",
            "--write",
            "m.json",
        ],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("wide.toml: the firmware cannot render this scene")
            && err.contains("400x48 is larger than the firmware's 240x240"),
        "{err}"
    );
    assert!(!dir.join("m.json").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_user_scene_with_an_obj_mesh_is_measured_on_the_cortex_m4f() {
    if let Some(why) = missing_tools() {
        println!("skipped: {why}: the firmware cannot be measured here");
        return;
    }
    let dir = temp_dir("m4f");
    std::fs::write(dir.join("tetra.toml"), scene(64)).unwrap();
    let out = fixshade(
        &dir,
        &[
            "measure-firmware",
            "--scene",
            "tetra.toml",
            "--profiles",
            "fast",
            "--targets",
            "thumbv7em-none-eabihf",
            "--write",
            "m.json",
        ],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("m.json")).unwrap()).unwrap();
    let results = m["results"].as_array().unwrap();
    let builds = m["builds"].as_array().unwrap();
    assert_eq!(builds.len(), 1);
    let build = &builds[0];
    assert_eq!(build["target"], "thumbv7em-none-eabihf");
    assert_eq!(
        build["softfloat_routines"], 0,
        "fast on the M4F: no soft-float"
    );
    let names: Vec<&str> = results
        .iter()
        .map(|r| r["scene"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["tetra-flat", "tetra-gouraud", "tetra-phong"]);
    // The host's frame of the scene file (Phong, fast profile), from the
    // scene file itself: the chip's CRC must be its.
    let render = fixshade(
        &dir,
        &[
            "render",
            "tetra.toml",
            "--profile",
            "fast",
            "--out",
            "t.png",
            "--crc",
        ],
    );
    assert!(render.status.success());
    let host_phong = String::from_utf8_lossy(&render.stdout);
    let u = |r: &serde_json::Value, k: &str| r[k].as_u64().unwrap();
    let mut insns = Vec::new();
    for r in results {
        let name = r["scene"].as_str().unwrap();
        assert_eq!(r["profile"], "fast");
        assert_eq!(r["mode"], name.trim_start_matches("tetra-"));
        assert!(
            u(r, "insns_geometry") > 0 && u(r, "insns_raster") > 0,
            "{r}"
        );
        assert_eq!(u(r, "insns"), u(r, "insns_geometry") + u(r, "insns_raster"));
        assert!(r["cycles"].is_null(), "no cycle model on the M4F");
        assert_eq!(r["crc"], r["host_crc"]);
        assert_eq!(r["crc_equal"], true);
        // The tetrahedron covers the middle of the 64 x 48 frame.
        assert!(u(r, "covered") > 200 && u(r, "covered") < 64 * 48, "{r}");
        // One convex object, back faces culled: no depth band; each pixel
        // drawn once.
        assert_eq!(u(r, "depth_bytes"), 0);
        assert_eq!(u(r, "drawn"), u(r, "covered"));
        assert_eq!(u(r, "band_bytes"), 64 * 16 * 2);
        // RAM as the firmware reports it: its bands, storage, pool and
        // stack, within the build's static RAM plus the stack.
        let (ram, stack) = (u(r, "ram"), u(r, "stack"));
        assert!(stack > 0 && ram > stack + u(r, "band_bytes"), "{r}");
        assert!(ram <= u(r, "static_ram") + stack, "{r}");
        assert_eq!(u(r, "static_ram"), u(build, "static_ram_bytes"));
        assert_eq!(u(r, "flash"), u(build, "flash_bytes"));
        insns.push(u(r, "insns"));
    }
    let phong_crc = results[2]["crc"].as_str().unwrap();
    assert!(
        host_phong.contains(&format!("crc32 {}", phong_crc.trim_start_matches("0x"))),
        "chip {phong_crc}, host render: {host_phong}"
    );
    // Flat costs less than Gouraud, Gouraud less than Phong.
    assert!(insns[0] < insns[1] && insns[1] < insns[2], "{insns:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

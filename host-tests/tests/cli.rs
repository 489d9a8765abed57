//! The `fixshade` command, run as a real process in temporary folders:
//! exit statuses, one-line error messages naming file and field, output
//! files left untouched on error, and the outputs of `scenes`, `bake` and
//! `ideal`.

use crate::support::{fixshade, TempDir};
use std::path::Path;
use std::process::Output;

use fixshade_host::builtin::builtin_scenes;
use fixshade_host::image::read_png;

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn bad_scene_files_exit_2_and_leave_the_output_alone() {
    let dir = TempDir::new("cli-bad");
    dir.write("index.obj", &format!("{TRIANGLE}f 1 2 9\n"));
    dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    let object = |extra: &str| format!("[[object]]\nmesh = \"cube\"\n[[object]]\n{extra}");
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "syntax",
            "width = 240\n[camera]\neye = [0, 0\n".to_string(),
            "camera.eye: TOML syntax error: unclosed array, expected `]` (line 3, column 12)",
        ),
        (
            "unknown-field",
            object("mesh = \"cube\"\ncolour = 3\n"),
            "object[1].colour: unknown field `colour`, expected one of",
        ),
        (
            "unknown-mesh",
            object("mesh = \"teapot\"\n"),
            "object[1].mesh: unknown mesh `teapot`: expected one of cube, dodecahedron",
        ),
        (
            "wrong-type",
            "[camera]\nfov_y_deg = \"wide\"\n".to_string(),
            "camera.fov_y_deg: invalid type: string \"wide\", expected f64 (line 2, column 13)",
        ),
        (
            "out-of-range",
            object("mesh = \"cube\"\nmaterial = { ks = 1.5 }\n"),
            "object[1].material.ks: must be in [0, 1], got 1.5",
        ),
        (
            "missing-obj",
            object("mesh = \"missing.obj\"\n"),
            "object[1].mesh: OBJ file `",
        ),
        (
            "bad-index",
            object("mesh = \"index.obj\"\n"),
            "index.obj`: line 4: face vertex index `9` is out of range",
        ),
        (
            "nan",
            object("mesh = \"nan.obj\"\n"),
            "nan.obj`: line 2: vertex position has `nan`, which is not finite",
        ),
    ];
    for (name, text, expected) in &cases {
        let scene = dir.write(&format!("{name}.toml"), text);
        let out = dir.write("out.png", "old contents");
        let result = fixshade(
            &dir.0,
            &[
                "ideal",
                scene.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ],
        );
        assert_eq!(result.status.code(), Some(2), "{name}: {}", stderr(&result));
        let message = stderr(&result);
        assert_eq!(message.lines().count(), 1, "{name}: one line: {message}");
        let prefix = format!("error: {}: ", scene.display());
        assert!(message.starts_with(&prefix), "{name}: {message}");
        assert!(
            message.contains(expected),
            "{name}: {message}\nlacks {expected}"
        );
        assert_eq!(
            std::fs::read_to_string(&out).unwrap(),
            "old contents",
            "{name}"
        );
        assert!(result.stdout.is_empty(), "{name}");
    }
    // The missing OBJ is named with its path and the OS error.
    let missing = fixshade(&dir.0, &["ideal", "missing-obj.toml", "--out", "out.png"]);
    let message = stderr(&missing);
    assert!(
        message.contains("missing-obj.toml: object[1].mesh: OBJ file `missing.obj`: cannot read: "),
        "{message}"
    );
    // A missing scene file is bad input too.
    let absent = fixshade(&dir.0, &["ideal", "absent.toml", "--out", "out.png"]);
    assert_eq!(absent.status.code(), Some(2));
    assert!(stderr(&absent).starts_with("error: absent.toml: cannot read scene file: "));
    // No temporary or other stray file was left behind.
    let mut expected: Vec<String> = cases.iter().map(|(n, _, _)| format!("{n}.toml")).collect();
    expected.extend(["index.obj", "nan.obj", "out.png"].map(String::from));
    expected.sort();
    assert_eq!(dir.files(), expected);
}

#[test]
fn usage_errors_exit_2() {
    let dir = TempDir::new("cli-usage");
    for args in [
        &[][..],
        &["render"][..],
        &["ideal", "--out", "x.png"][..],
        &["ideal", "a.toml", "--scene", "bunny-flat", "--out", "x.png"][..],
        &["bake", "m.obj"][..],
        &["bake", "m.obj", "--out", "m.rs", "--scale", "big"][..],
    ] {
        let out = fixshade(&dir.0, args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        // Without arguments clap prints the help, otherwise an error.
        let message = stderr(&out);
        assert!(
            message.starts_with("error: ") || (args.is_empty() && message.contains("Usage:")),
            "{args:?}: {message}"
        );
    }
    let unknown = fixshade(&dir.0, &["ideal", "--scene", "nope", "--out", "x.png"]);
    assert_eq!(unknown.status.code(), Some(2));
    assert!(
        stderr(&unknown).starts_with("error: builtin:nope: no such built-in scene; known scenes: ")
    );
    assert!(dir.files().is_empty());
    let help = fixshade(&dir.0, &["--help"]);
    assert_eq!(help.status.code(), Some(0));
    for sub in ["scenes", "bake", "ideal"] {
        assert!(stdout(&help).contains(sub));
    }
}

#[test]
fn write_failures_exit_1() {
    let dir = TempDir::new("cli-io");
    let out = fixshade(
        &dir.0,
        &["ideal", "--scene", "can-flat", "--out", "no/such/dir/x.png"],
    );
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).starts_with("error: no/such/dir/x.png: "),
        "{}",
        stderr(&out)
    );
    dir.write("tri.obj", &format!("{TRIANGLE}f 1 2 3\n"));
    let out = fixshade(&dir.0, &["bake", "tri.obj", "--out", "no/such/dir/x.rs"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).starts_with("error: no/such/dir/x.rs: cannot write: "));
    assert_eq!(dir.files(), ["tri.obj"]);
}

#[test]
fn scenes_lists_every_builtin() {
    let out = fixshade(&std::env::temp_dir(), &["scenes"]);
    assert_eq!(out.status.code(), Some(0));
    let text = stdout(&out);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), builtin_scenes().len());
    for ((name, description, _), line) in builtin_scenes().iter().zip(&lines) {
        let mut words = line.splitn(2, ' ');
        assert_eq!(words.next(), Some(*name));
        assert_eq!(words.next().map(str::trim_start), Some(*description));
    }
    assert!(lines.iter().any(|l| l.starts_with("bunny-gouraud ")));
    assert!(lines.iter().any(|l| l.starts_with("dodeca-phong-n100 ")));
}

/// The entries of the constant table `name` in baked source.
fn table_rows(text: &str, name: &str) -> usize {
    let start = text
        .find(&format!("const {name}: "))
        .unwrap_or_else(|| panic!("no table {name}"));
    let body = &text[start..];
    let end = body.find("];").expect("table end");
    body[..end].matches("],").count()
}

#[test]
fn bake_writes_the_counts() {
    let dir = TempDir::new("cli-bake");
    // A cube of side 4 centred on (1, 2, 3), as quads with normals.
    let mut cube = String::new();
    for i in 0..8 {
        let c = |bit: usize, centre: f64| centre + if i >> bit & 1 == 1 { 2.0 } else { -2.0 };
        cube.push_str(&format!("v {} {} {}\n", c(0, 1.0), c(1, 2.0), c(2, 3.0)));
    }
    cube.push_str("f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n");
    dir.write("my cube.obj", &cube);
    let out = fixshade(&dir.0, &["bake", "my cube.obj", "--out", "cube.rs"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(
        stdout(&out),
        "wrote cube.rs: 8 vertices, 12 triangles, 8 normals\n"
    );
    let text = std::fs::read_to_string(dir.path("cube.rs")).unwrap();
    assert!(text.starts_with("//! Mesh `MY_CUBE`, baked by `fixshade bake` from `my cube.obj`"));
    assert!(text.contains("use fixshade::mesh::Mesh;"));
    assert!(text.contains("pub const MY_CUBE: Mesh<'static>"));
    assert!(text.contains("/// Baked from `my cube.obj`: 8 vertices, 12 triangles, 8 normals."));
    assert!(text.contains("/// Positions centred on (1, 2, 3) and scaled by 0.5"));
    assert_eq!(table_rows(&text, "POSITIONS"), 8);
    assert_eq!(table_rows(&text, "TRIANGLES"), 12);
    assert_eq!(table_rows(&text, "NORMALS"), 8);
    assert_eq!(table_rows(&text, "FACE_NORMALS"), 12);
    // Corners at (±1, ±1, ±1) in Q1.14; smooth normals along the diagonals.
    assert!(text.contains("[-16384, -16384, -16384], [-16384, 16384, -16384],"));
    assert!(text.contains("[-9459, -9459, -9459],"));

    // With a crease angle: flat faces, three normals at each corner.
    let out = fixshade(
        &dir.0,
        &[
            "bake",
            "my cube.obj",
            "--out",
            "flat.rs",
            "--crease-angle",
            "30",
            "--scale",
            "0.5",
            "--name",
            "FLAT_CUBE",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = std::fs::read_to_string(dir.path("flat.rs")).unwrap();
    assert!(text.contains("pub const FLAT_CUBE: Mesh<'static>"));
    assert!(text.contains("8 vertices, 12 triangles, 24 normals"));
    // Welded: a vertex per corner of each face (8 positions × 3 normals).
    assert!(text.contains("[-8192, -8192, -8192],"));
    assert_eq!(table_rows(&text, "POSITIONS"), 24);
    assert_eq!(table_rows(&text, "NORMALS"), 24);
    assert_eq!(table_rows(&text, "FACE_NORMALS"), 12);
    assert!(!text.contains("NORMAL_INDICES"));

    // Bad input: exit 2, named, nothing written.
    let old = dir.write("old.rs", "old");
    let bad_obj = dir.write("bad.obj", &format!("{TRIANGLE}f 1 2 5\n"));
    for (args, expected) in [
        (
            vec!["bake", "bad.obj", "--out", "old.rs"],
            "error: bad.obj: line 4: face vertex index `5` is out of range".to_string(),
        ),
        (
            vec!["bake", "absent.obj", "--out", "old.rs"],
            "error: absent.obj: cannot read: ".to_string(),
        ),
        (
            vec!["bake", "my cube.obj", "--out", "old.rs", "--scale", "2"],
            "error: --scale: must be in (0, 1.999], got 2".to_string(),
        ),
        (
            vec![
                "bake",
                "my cube.obj",
                "--out",
                "old.rs",
                "--crease-angle",
                "200",
            ],
            "error: --crease-angle: must be in [0, 180] degrees, got 200".to_string(),
        ),
        (
            vec!["bake", "my cube.obj", "--out", "old.rs", "--name", "cube"],
            "error: --name: `cube` is not an upper-case Rust constant name".to_string(),
        ),
    ] {
        let out = fixshade(&dir.0, &args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(
            stderr(&out).starts_with(&expected),
            "{args:?}: {}",
            stderr(&out)
        );
        assert_eq!(std::fs::read_to_string(&old).unwrap(), "old");
    }
    assert!(bad_obj.exists());
    assert_eq!(
        dir.files(),
        ["bad.obj", "cube.rs", "flat.rs", "my cube.obj", "old.rs"]
    );
}

#[test]
fn bake_reproduces_the_builtin_bunny() {
    let dir = TempDir::new("cli-bunny");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let obj = root.join("assets/bunny.obj");
    let out = fixshade(
        &dir.0,
        &["bake", obj.to_str().unwrap(), "--out", "bunny.rs"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(
        stdout(&out),
        "wrote bunny.rs: 1839 vertices, 3674 triangles, 1839 normals\n"
    );
    let baked = std::fs::read_to_string(dir.path("bunny.rs")).unwrap();
    let core = std::fs::read_to_string(root.join("src/mesh/shapes/bunny.rs")).unwrap();
    // Same tables, byte for byte, as the core's generated BUNNY.
    let tables = |s: &str| s[s.find("const POSITIONS").expect("tables")..].to_string();
    assert!(
        tables(&baked) == tables(&core),
        "baked tables differ from BUNNY"
    );
}

#[test]
fn ideal_writes_a_png_of_the_scene_size() {
    let dir = TempDir::new("cli-ideal");
    dir.write(
        "wide.toml",
        "width = 64\nheight = 48\n[[light]]\ntype = \"point\"\nposition = [0, 0, 5]\n[[object]]\nmesh = \"sphere\"\nshading = \"phong\"\n",
    );
    let out = fixshade(&dir.0, &["ideal", "wide.toml", "--out", "wide.png"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stdout(&out).starts_with("wrote wide.png: 64x48, "));
    let image = read_png(dir.path("wide.png")).unwrap();
    assert_eq!((image.width, image.height), (64, 48));
    // The sphere is in the middle on black.
    assert_eq!(image.pixels[0], [0, 0, 0]);
    assert_ne!(image.pixels[24 * 64 + 32], [0, 0, 0]);

    dir.write("bunny.png", "old");
    let out = fixshade(
        &dir.0,
        &["ideal", "--scene", "bunny-gouraud", "--out", "bunny.png"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(
        stdout(&out),
        "wrote bunny.png: 240x240, 14905 covered pixels\n"
    );
    let image = read_png(dir.path("bunny.png")).unwrap();
    assert_eq!((image.width, image.height), (240, 240));
    assert_eq!(dir.files(), ["bunny.png", "wide.png", "wide.toml"]);
}

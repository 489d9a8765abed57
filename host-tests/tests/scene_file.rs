//! Scene files: the documented format, defaults, every kind of error with
//! its message, built-in and OBJ meshes, the conversion to the ideal
//! scene, and the built-in scenes rendered by the ideal reference.

use crate::support::TempDir;
use std::path::Path;

use fixshade::mesh::{DODECAHEDRON, SPHERE};
use fixshade_host::builtin::{builtin_scenes, load_builtin};
use fixshade_host::ideal::{self, LightKind, Shading, SpecularModel};
use fixshade_host::scene_file::{
    crease_from_degrees, PixelFormat, Profile, SceneDesc, SceneError, SceneMesh, Transform,
};

/// The example of the format, exactly as specified.
const EXAMPLE: &str = r#"
width = 240
height = 240
pixel_format = "rgb565"        # gray8 | rgb565 | rgb888
profile = "precise"            # fast | precise | f32 | f64
background = [0, 0, 0]
[camera]
eye = [0.0, 0.0, 6.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_y_deg = 40.0
[lighting]
ambient = 0.2                  # Ia
specular = "phong"             # phong (R·V) | blinn (N·H)
[[light]]
type = "point"                 # point | directional
position = [0.0, 0.0, 20.0]    # directional: `direction`, pointing towards the light
intensity = 1.0                # Ip
[[object]]
mesh = "dodecahedron"          # a built-in name, or an .obj path relative to the scene file
shading = "phong"              # flat | gouraud | phong
crease_angle_deg = 180.0
scale = 1.0
rotate_deg = [0.0, 30.0, 0.0]  # about X, then Y, then Z
translate = [0.0, 0.0, 0.0]
cull_backfaces = true
material = { color = [1.0, 0.3, 0.2], ka = 0.2, kd = 0.5, ks = 0.5, shininess = 100.0 }
"#;

fn parse(text: &str) -> Result<SceneDesc, SceneError> {
    SceneDesc::from_toml(text, "s.toml", Some(Path::new(".")))
}

fn error(text: &str) -> String {
    parse(text).expect_err("must be rejected").to_string()
}

#[test]
fn the_example_parses_to_its_values() {
    let s = parse(EXAMPLE).unwrap();
    assert_eq!((s.width, s.height), (240, 240));
    assert_eq!(s.pixel_format, PixelFormat::Rgb565);
    assert_eq!(s.profile, Profile::Precise);
    assert_eq!(s.background, [0, 0, 0]);
    assert_eq!(s.camera.eye, [0.0, 0.0, 6.0]);
    assert_eq!(s.camera.fov_y_deg, 40.0);
    assert_eq!((s.camera.near, s.camera.far), (0.1, None));
    assert_eq!(s.ambient, 0.2);
    assert_eq!(s.specular, SpecularModel::Phong);
    assert_eq!(s.lights.len(), 1);
    assert_eq!(
        s.lights[0].kind,
        LightKind::Point {
            position: [0.0, 0.0, 20.0]
        }
    );
    assert_eq!((s.lights[0].intensity, s.lights[0].color), (1.0, [1.0; 3]));
    let o = &s.objects[0];
    assert_eq!(o.shading, Shading::Phong);
    assert!(o.cull_backfaces);
    assert_eq!(o.crease_angle_deg, Some(180.0));
    assert_eq!(o.material.color, [1.0, 0.3, 0.2]);
    assert_eq!(
        (
            o.material.ka,
            o.material.kd,
            o.material.ks,
            o.material.shininess
        ),
        (0.2, 0.5, 0.5, 100.0)
    );
    assert_eq!(o.transform.scale, [1.0; 3]);
    assert_eq!(o.transform.rotation_rad, [0.0, 30f64.to_radians(), 0.0]);
    assert_eq!(o.transform.translation, [0.0; 3]);
    // Crease 180: the dodecahedron becomes smooth, one normal per vertex:
    // the built-in's 60 face corners welded back to its 20 positions.
    let mesh = o.mesh.mesh();
    assert!(matches!(o.mesh, SceneMesh::Owned(_)));
    assert_eq!(mesh.triangle_count(), DODECAHEDRON.triangle_count());
    for t in 0..mesh.triangle_count() {
        assert_eq!(
            mesh.triangle_positions(t),
            DODECAHEDRON.triangle_positions(t)
        );
    }
    assert_eq!((DODECAHEDRON.normal_count(), mesh.normal_count()), (60, 20));
}

#[test]
fn defaults() {
    let s = parse("[[object]]\nmesh = \"cube\"\n").unwrap();
    assert_eq!((s.width, s.height), (240, 240));
    assert_eq!(
        (s.pixel_format, s.profile, s.background),
        (PixelFormat::Rgb565, Profile::Precise, [0, 0, 0])
    );
    assert_eq!(
        (s.camera.eye, s.camera.target, s.camera.up),
        ([0.0, 0.0, 6.0], [0.0; 3], [0.0, 1.0, 0.0])
    );
    assert_eq!(
        (s.camera.fov_y_deg, s.camera.near, s.camera.far),
        (40.0, 0.1, None)
    );
    assert_eq!((s.ambient, s.specular), (0.2, SpecularModel::Phong));
    assert!(s.lights.is_empty());
    let o = &s.objects[0];
    assert_eq!(
        (o.shading, o.cull_backfaces, o.crease_angle_deg),
        (Shading::Gouraud, true, None)
    );
    assert_eq!(
        o.transform,
        Transform {
            scale: [1.0; 3],
            rotation_rad: [0.0; 3],
            translation: [0.0; 3]
        }
    );
    let m = &o.material;
    assert_eq!(
        (m.color, m.ka, m.kd, m.ks, m.shininess),
        ([1.0; 3], 0.2, 0.5, 0.5, 100.0)
    );
    // Without a crease angle the built-in mesh keeps its own normals.
    assert!(matches!(o.mesh, SceneMesh::BuiltIn { name: "cube", .. }));
    assert_eq!(o.mesh.mesh().normal_count(), 24);
}

#[test]
fn other_names_and_additions() {
    let s = parse(
        r#"
        pixel_format = "gray8"
        profile = "fast"
        background = [1, 2, 255]
        [camera]
        near = 0.5
        far = 50
        [lighting]
        specular = "blinn"
        [[light]]
        type = "directional"
        direction = [1, 1, 1]
        color = [1.0, 0.5, 0.0]
        intensity = 0
        [[object]]
        mesh = "sphere"
        shading = "flat"
        cull_backfaces = false
        crease_angle_deg = 0
        "#,
    )
    .unwrap();
    assert_eq!(
        (s.pixel_format, s.profile),
        (PixelFormat::Gray8, Profile::Fast)
    );
    assert_eq!(s.background, [1, 2, 255]);
    assert_eq!((s.camera.near, s.camera.far), (0.5, Some(50.0)));
    assert_eq!(s.specular, SpecularModel::Blinn);
    assert_eq!(
        s.lights[0].kind,
        LightKind::Directional {
            direction: [1.0; 3]
        }
    );
    assert_eq!(
        (s.lights[0].intensity, s.lights[0].color),
        (0.0, [1.0, 0.5, 0.0])
    );
    let o = &s.objects[0];
    assert_eq!((o.shading, o.cull_backfaces), (Shading::Flat, false));
    // Crease 0 on the sphere: flat normals, regenerated. Fewer than one per
    // corner (3 x 420): the two triangles of a band's quad are coplanar, and
    // where their Q1.14 face normals come out equal their common corners
    // share one normal.
    assert_eq!(SPHERE.normal_count(), 212);
    assert_eq!(o.mesh.mesh().normal_count(), 1166);
    for p in ["f32", "f64", "precise"] {
        let s = parse(&format!("profile = \"{p}\"\npixel_format = \"rgb888\"")).unwrap();
        assert_eq!(s.profile.name(), p);
        assert_eq!(s.pixel_format, PixelFormat::Rgb888);
    }
}

#[test]
fn error_messages_name_file_field_and_problem() {
    let cases: &[(&str, &str)] = &[
        // Syntax, with the key guessed from the line and the position.
        (
            "width = \n",
            "s.toml: width: TOML syntax error: string values must be quoted, expected literal string (line 1, column 9)",
        ),
        (
            "[[object]]\nmesh = \"cube\"\n[[object]]\nmesh = \"cube\"\nmaterial = { ks = }\n",
            "s.toml: object[1].material: TOML syntax error: invalid literal string, expected `'` (line 5, column 19)",
        ),
        (
            "= 3\n",
            "s.toml: line 1, column 1: TOML syntax error: unquoted keys cannot be empty, expected letters, numbers, `-`, `_`",
        ),
        // Unknown fields.
        (
            "widht = 3\n",
            "s.toml: widht: unknown field `widht`, expected one of `width`, `height`, `pixel_format`, `profile`, `background`, `camera`, `lighting`, `light`, `object` (line 1, column 1)",
        ),
        (
            "[[object]]\nmesh = \"cube\"\n[[object]]\nmesh = \"cube\"\nmaterial = { kz = 1 }\n",
            "s.toml: object[1].material.kz: unknown field `kz`, expected one of `color`, `ka`, `kd`, `ks`, `shininess` (line 5, column 14)",
        ),
        // Wrong types and shapes.
        (
            "width = \"big\"\n",
            "s.toml: width: invalid type: string \"big\", expected i64 (line 1, column 9)",
        ),
        (
            "width = 240.0\n",
            "s.toml: width: invalid type: floating point `240.0`, expected i64 (line 1, column 9)",
        ),
        (
            "[[object]]\nmesh = \"cube\"\n[[object]]\nmesh = \"cube\"\nmaterial = { ks = \"x\" }\n",
            "s.toml: object[1].material.ks: invalid type: string \"x\", expected f64 (line 5, column 19)",
        ),
        (
            "[camera]\neye = [0, 0]\n",
            "s.toml: camera.eye: invalid length 2, expected an array of length 3 (line 2, column 7)",
        ),
        (
            "[lighting]\nspecular = 3\n",
            "s.toml: lighting.specular: invalid type: expected a name in quotes (line 2, column 12)",
        ),
        // Unknown names and missing fields.
        (
            "profile = \"turbo\"\n",
            "s.toml: profile: unknown variant `turbo`, expected one of `fast`, `precise`, `f32`, `f64` (line 1, column 11)",
        ),
        (
            "pixel_format = \"rgb444\"\n",
            "s.toml: pixel_format: unknown variant `rgb444`, expected one of `gray8`, `rgb565`, `rgb888` (line 1, column 16)",
        ),
        (
            "[[object]]\nmesh = \"cube\"\nshading = \"toon\"\n",
            "s.toml: object[0].shading: unknown variant `toon`, expected one of `flat`, `gouraud`, `phong` (line 3, column 11)",
        ),
        (
            "[[light]]\ntype = \"spot\"\n",
            "s.toml: light[0].type: unknown variant `spot`, expected `point` or `directional` (line 2, column 8)",
        ),
        (
            "[[object]]\nmesh = \"teapot\"\n",
            "s.toml: object[0].mesh: unknown mesh `teapot`: expected one of cube, dodecahedron, sphere, can, grid, bunny or a path to an .obj file",
        ),
        (
            "[[object]]\nshading = \"flat\"\n",
            "s.toml: object[0]: missing field `mesh` (line 1, column 1)",
        ),
        (
            "[[light]]\ntype = \"point\"\n",
            "s.toml: light[0].position: missing: a point light needs a position",
        ),
        (
            "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\ndirection = [0, 0, 1]\n",
            "s.toml: light[0].direction: only directional lights have a direction (point lights have a position)",
        ),
        (
            "[[light]]\ntype = \"directional\"\n",
            "s.toml: light[0].direction: missing: a directional light needs a direction",
        ),
        // Out of range.
        ("width = 0\n", "s.toml: width: must be in 1..=4096, got 0"),
        ("height = 4097\n", "s.toml: height: must be in 1..=4096, got 4097"),
        (
            "background = [0, -1, 0]\n",
            "s.toml: background: levels must be in 0..=255, got [0, -1, 0]",
        ),
        (
            "[camera]\nfov_y_deg = 180\n",
            "s.toml: camera.fov_y_deg: must be in (0, 180) degrees, got 180",
        ),
        (
            "[camera]\nnear = 0\n",
            "s.toml: camera.near: must be > 0 and at most 1e6, got 0",
        ),
        (
            "[camera]\nnear = nan\n",
            "s.toml: camera.near: must be > 0 and at most 1e6, got NaN",
        ),
        (
            "[camera]\nnear = 2\nfar = 2\n",
            "s.toml: camera.far: must be finite and > camera.near (2), got 2",
        ),
        (
            "[camera]\neye = [0, 0, inf]\n",
            "s.toml: camera.eye: must be finite numbers of magnitude at most 1e6, got [0.0, 0.0, inf]",
        ),
        (
            "[camera]\ntarget = [0, 0, 6]\n",
            "s.toml: camera.target: equals camera.eye: no view direction",
        ),
        (
            "[camera]\nup = [0, 0, -2]\n",
            "s.toml: camera.up: is zero or parallel to the view direction (target - eye)",
        ),
        (
            "[lighting]\nambient = -0.1\n",
            "s.toml: lighting.ambient: must be a finite number >= 0, got -0.1",
        ),
        (
            "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = -1\n",
            "s.toml: light[0].intensity: must be a finite number >= 0, got -1",
        ),
        (
            "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\ncolor = [1, 2, 0]\n",
            "s.toml: light[0].color: components must be in [0, 1], got [1.0, 2.0, 0.0]",
        ),
        (
            "[[light]]\ntype = \"directional\"\ndirection = [0, 0, 0]\n",
            "s.toml: light[0].direction: must not be zero",
        ),
        (
            "[[object]]\nmesh = \"cube\"\n[[object]]\nmesh = \"cube\"\nmaterial = { ks = 1.5 }\n",
            "s.toml: object[1].material.ks: must be in [0, 1], got 1.5",
        ),
        (
            "[[object]]\nmesh = \"cube\"\nmaterial = { ka = -0.5 }\n",
            "s.toml: object[0].material.ka: must be in [0, 1], got -0.5",
        ),
        (
            "[[object]]\nmesh = \"cube\"\nmaterial = { kd = nan }\n",
            "s.toml: object[0].material.kd: must be in [0, 1], got NaN",
        ),
        (
            "[[object]]\nmesh = \"cube\"\nmaterial = { shininess = 10001 }\n",
            "s.toml: object[0].material.shininess: must be in [0, 10000], got 10001",
        ),
        (
            "[[object]]\nmesh = \"cube\"\nmaterial = { color = [0.5, 0.5, -0.1] }\n",
            "s.toml: object[0].material.color: components must be in [0, 1], got [0.5, 0.5, -0.1]",
        ),
        (
            "[[object]]\nmesh = \"cube\"\nscale = 0\n",
            "s.toml: object[0].scale: must be > 0 and at most 1e6, got 0",
        ),
        (
            "[[object]]\nmesh = \"cube\"\nscale = inf\n",
            "s.toml: object[0].scale: must be > 0 and at most 1e6, got inf",
        ),
        (
            "[[object]]\nmesh = \"cube\"\ncrease_angle_deg = 181\n",
            "s.toml: object[0].crease_angle_deg: must be in [0, 180], got 181",
        ),
        (
            "[[object]]\nmesh = \"cube\"\nrotate_deg = [0, nan, 0]\n",
            "s.toml: object[0].rotate_deg: must be finite angles of magnitude at most 1e6, got [0.0, NaN, 0.0]",
        ),
        (
            "[[object]]\nmesh = \"cube\"\ntranslate = [0, 0, 1e7]\n",
            "s.toml: object[0].translate: must be finite numbers of magnitude at most 1e6, got [0.0, 0.0, 10000000.0]",
        ),
    ];
    for (text, expected) in cases {
        assert_eq!(&error(text), expected, "for {text:?}");
    }
    let lights = "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\n".repeat(9);
    assert_eq!(
        error(&lights),
        "s.toml: light: at most 8 lights are allowed, got 9"
    );
    let objects = "[[object]]\nmesh = \"cube\"\n".repeat(33);
    assert_eq!(
        error(&objects),
        "s.toml: object: at most 32 objects are allowed, got 33"
    );
    assert_eq!(
        parse(&objects[..objects.len() / 33 * 32])
            .unwrap()
            .objects
            .len(),
        32
    );
}

#[test]
fn load_reads_files_and_reports_missing_ones() {
    let dir = TempDir::new("scene-file-load");
    let path = dir.join("scene.toml");
    std::fs::write(&path, "width = 32\nheight = 16\n").unwrap();
    let s = SceneDesc::load(&path).unwrap();
    assert_eq!((s.width, s.height), (32, 16));
    assert_eq!(s.source, path.display().to_string());
    let missing = dir.join("missing.toml");
    let e = SceneDesc::load(&missing).unwrap_err();
    assert_eq!(e.file, missing.display().to_string());
    assert_eq!(e.field, None);
    assert!(e.problem.starts_with("cannot read scene file: "), "{e}");
    // OBJ files are rejected where there is no folder (built-in scenes).
    let e = SceneDesc::from_toml("[[object]]\nmesh = \"a.obj\"\n", "builtin:x", None).unwrap_err();
    assert_eq!(
        e.to_string(),
        "builtin:x: object[0].mesh: OBJ files cannot be used here (built-in scene)"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A tetrahedron far from the origin, 4 units wide, counter-clockwise
/// outwards, optionally with a normal per corner.
fn tetra_obj(with_normals: bool) -> String {
    let mut s = String::from("# tetrahedron\nv 10 20 30\nv 14 20 30\nv 10 23 30\nv 10 20 32\n");
    if with_normals {
        s.push_str("vn 0 0 -5\nvn 0 -1 0\nvn -1 0 0\nvn 1 1 1\n");
        s.push_str("f 1//1 3//1 2//1\nf 1//2 2//2 4//2\nf 1//3 4//3 3//3\nf 2//4 3//4 4//4\n");
    } else {
        s.push_str("f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    }
    s
}

#[test]
fn obj_meshes_keep_world_geometry_and_their_normals() {
    let dir = TempDir::new("scene-file-obj");
    std::fs::write(dir.join("tetra.obj"), tetra_obj(true)).unwrap();
    let scene = "[[object]]\nmesh = \"tetra.obj\"\nscale = 0.5\nrotate_deg = [0, 0, 90]\ntranslate = [1, 2, 3]\n";
    std::fs::write(dir.join("s.toml"), scene).unwrap();
    let s = SceneDesc::load(&dir.join("s.toml")).unwrap();
    let o = &s.objects[0];
    let SceneMesh::Owned(owned) = &o.mesh else {
        panic!("an OBJ gives an owned mesh")
    };
    assert_eq!(owned.origin(), "tetra.obj");
    // Centre (12, 21.5, 31), largest extent 4: factor 1/2; positions in
    // Q1.14, in order of first use (file vertices 1, 3, 2, 4).
    assert_eq!(owned.positions()[0], [-16384, -12288, -8192]);
    assert_eq!(owned.positions()[1], [-16384, 12288, -8192]);
    assert_eq!(owned.positions()[2], [16384, -12288, -8192]);
    // The fold: scale 0.5 / 0.5 = 1; translation (1, 2, 3) + 0.5 R(12, 21.5, 31).
    assert_eq!(o.transform.scale, [1.0; 3]);
    let t = o.transform.translation;
    let expected = [1.0 - 0.5 * 21.5, 2.0 + 0.5 * 12.0, 3.0 + 0.5 * 31.0];
    for k in 0..3 {
        assert!((t[k] - expected[k]).abs() < 1e-12, "{t:?} vs {expected:?}");
    }
    // The ideal scene has the file's geometry, transformed as the scene
    // says: world = (1, 2, 3) + Rz(90) (0.5 p), Rz(90)(x, y, z) = (-y, x, z).
    let ideal = s.to_ideal();
    let tri = &ideal.objects[0].triangles;
    assert_eq!(tri.len(), 4);
    let world = |p: [f64; 3]| [1.0 - 0.5 * p[1], 2.0 + 0.5 * p[0], 3.0 + 0.5 * p[2]];
    let corners = [
        (tri[0][0].position, world([10.0, 20.0, 30.0])),
        (tri[0][1].position, world([10.0, 23.0, 30.0])),
        (tri[0][2].position, world([14.0, 20.0, 30.0])),
        (tri[1][2].position, world([10.0, 20.0, 32.0])),
    ];
    for (got, want) in corners {
        for k in 0..3 {
            assert!((got[k] - want[k]).abs() < 1e-12, "{got:?} vs {want:?}");
        }
    }
    // The file's normals, normalised to Q1.14 and rotated: (0, 0, -5) ->
    // (0, 0, -1); (1, 1, 1) -> Rz(90) normalize(1, 1, 1).
    assert_eq!(owned.normals()[0], [0, 0, -16384]);
    assert_eq!(tri[0][0].normal, [0.0, 0.0, -1.0]);
    let n = tri[3][0].normal;
    let c = 9459.0 / 16384.0; // round(16384 / sqrt 3) = 9459
    assert!((n[0] + c).abs() < 1e-15 && (n[1] - c).abs() < 1e-15 && (n[2] - c).abs() < 1e-15);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn obj_without_normals_gets_generated_ones() {
    let dir = TempDir::new("scene-file-objgen");
    std::fs::write(dir.join("tetra.obj"), tetra_obj(false)).unwrap();
    let load = |crease: &str| {
        let text = format!("[[object]]\nmesh = \"tetra.obj\"\n{crease}");
        SceneDesc::from_toml(&text, "s.toml", Some(&dir)).unwrap()
    };
    // Default crease 180: smooth, one normal per vertex.
    let smooth = load("");
    assert_eq!(smooth.objects[0].mesh.mesh().normal_count(), 4);
    // Crease 60: the tetrahedron's faces meet at more than 60 deg: flat.
    let flat = load("crease_angle_deg = 60\n");
    assert_eq!(flat.objects[0].mesh.mesh().normal_count(), 12);
    let mesh = flat.objects[0].mesh.mesh();
    assert_eq!(mesh.corner_normal(0, 0), Some([0, 0, -16384]));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn obj_errors_name_the_object_and_the_problem() {
    let dir = TempDir::new("scene-file-objerr");
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    let files = [
        ("index.obj", format!("{tri}f 1 2 9\n")),
        ("zero.obj", format!("{tri}f 0 1 2\n")),
        (
            "nan.obj",
            "v 0 0 0\nv 1 NaN 0\nv 0 1 0\nf 1 2 3\n".to_string(),
        ),
        ("normal.obj", format!("{tri}vn 0 inf 1\nf 1//1 2//1 3//1\n")),
        ("lines.obj", format!("{tri}l 1 2\n")),
        (
            "point.obj",
            "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n".to_string(),
        ),
        ("words.obj", format!("{tri}f 1 2 three\n")),
    ];
    for (name, text) in &files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let expected = [
        (
            "index.obj",
            "line 4: face vertex index `9` is out of range: 3 vertex(s) defined before this face",
        ),
        (
            "zero.obj",
            "line 4: face vertex index `0` is 0 (indices start at 1)",
        ),
        (
            "nan.obj",
            "line 2: vertex position has `NaN`, which is not finite",
        ),
        (
            "normal.obj",
            "line 4: normal has `inf`, which is not finite",
        ),
        ("lines.obj", "no triangles (no face with 3 or more corners)"),
        (
            "point.obj",
            "vertex positions have no extent (all equal) or an extent too large for f64",
        ),
        (
            "words.obj",
            "line 4: face vertex index `three` is not an integer",
        ),
        ("missing.obj", "cannot read: "),
    ];
    for (name, problem) in expected {
        let text = format!("[[object]]\nmesh = \"cube\"\n[[object]]\nmesh = \"{name}\"\n");
        let e = SceneDesc::from_toml(&text, "s.toml", Some(&dir)).unwrap_err();
        let prefix = format!(
            "s.toml: object[1].mesh: OBJ file `{}`: {problem}",
            dir.join(name).display()
        );
        assert!(e.to_string().starts_with(&prefix), "{e}\nexpected {prefix}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn obj_with_too_many_vertices() {
    let dir = TempDir::new("scene-file-objbig");
    // 65538 distinct vertices in 21846 triangles.
    let mut text = String::with_capacity(2_000_000);
    for i in 0..65538u32 {
        text.push_str(&format!("v {} {} 0\n", i % 256, i / 256));
    }
    for t in 0..21846u32 {
        text.push_str(&format!("f {} {} {}\n", 3 * t + 1, 3 * t + 2, 3 * t + 3));
    }
    std::fs::write(dir.join("big.obj"), text).unwrap();
    let e =
        SceneDesc::from_toml("[[object]]\nmesh = \"big.obj\"\n", "s.toml", Some(&dir)).unwrap_err();
    assert!(
        e.to_string().ends_with(
            "big.obj`: more than 65535 vertices (distinct position/texcoord/normal triples)"
        ),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn rotation_is_x_then_y_then_z() {
    let deg = |x: f64, y: f64, z: f64| Transform {
        scale: [2.0; 3],
        rotation_rad: [x.to_radians(), y.to_radians(), z.to_radians()],
        translation: [10.0, 20.0, 30.0],
    };
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12);
    // Rx(90) (0, 1, 0) = (0, 0, 1); then Ry(90) (0, 0, 1) = (1, 0, 0).
    assert!(close(
        deg(90.0, 90.0, 0.0).rotate([0.0, 1.0, 0.0]),
        [1.0, 0.0, 0.0]
    ));
    // Ry(90) (1, 0, 0) = (0, 0, -1); then Rz(90) leaves it.
    assert!(close(
        deg(0.0, 90.0, 90.0).rotate([1.0, 0.0, 0.0]),
        [0.0, 0.0, -1.0]
    ));
    // Rz(90) (1, 0, 0) = (0, 1, 0); scale then translation.
    assert!(close(
        deg(0.0, 0.0, 90.0).apply_point([1.0, 0.0, 0.0]),
        [10.0, 22.0, 30.0]
    ));
}

#[test]
fn to_ideal_transforms_builtin_meshes() {
    let s = parse(
        "background = [255, 0, 51]\n[[object]]\nmesh = \"cube\"\nscale = 0.5\nrotate_deg = [0, 90, 0]\ntranslate = [0, 1, 0]\n",
    )
    .unwrap();
    let ideal = s.to_ideal();
    assert_eq!(ideal.background, [1.0, 0.0, 0.2]);
    let o = &ideal.objects[0];
    assert_eq!(o.triangles.len(), 12);
    // Every world corner is (±0.5, 1 ± 0.5, ±0.5) and every normal is a
    // unit axis vector, rotated by Ry(90): (x, y, z) -> (z, y, -x).
    let cube = fixshade::mesh::CUBE;
    for (t, tri) in o.triangles.iter().enumerate() {
        let p = cube.triangle_positions(t).unwrap();
        for c in 0..3 {
            let q = p[c].map(|v| f64::from(v) / 16384.0);
            let want = [0.5 * q[2], 1.0 + 0.5 * q[1], -0.5 * q[0]];
            let got = tri[c].position;
            assert!((0..3).all(|k| (got[k] - want[k]).abs() < 1e-15), "{got:?}");
            let n = cube
                .corner_normal(t, c)
                .unwrap()
                .map(|v| f64::from(v) / 16384.0);
            let want = [n[2], n[1], -n[0]];
            let got = tri[c].normal;
            assert!((0..3).all(|k| (got[k] - want[k]).abs() < 1e-15), "{got:?}");
        }
    }
    assert_eq!(o.shading, Shading::Gouraud);
    assert!(o.cull_backfaces);
}

#[test]
fn crease_degrees() {
    assert_eq!(crease_from_degrees(180.0), fixshade::mesh::Crease::SMOOTH);
    assert_eq!(crease_from_degrees(0.0), fixshade::mesh::Crease::FLAT);
    assert_eq!(crease_from_degrees(60.0).cos_q14(), 8192);
    assert_eq!(crease_from_degrees(60.5).cos_q14(), 8068);
    assert_eq!(
        crease_from_degrees(f64::NAN),
        fixshade::mesh::Crease::SMOOTH
    );
}

/// Measured on the ideal reference: `(name, covered pixels, covered rows
/// (top..=bottom), brightest channel level over covered pixels)`.
const MEASURED: &[(&str, usize, (usize, usize), u8)] = &[
    ("dodeca-phong-n1", 6764, (33, 126), 255),
    ("dodeca-phong-n10", 6764, (33, 126), 255),
    ("dodeca-phong-n25", 6764, (33, 126), 255),
    ("dodeca-phong-n100", 6764, (33, 126), 255),
    ("dodeca-phong-n800", 6764, (33, 126), 243),
    ("dodeca-gouraud-n100", 6764, (33, 126), 78),
    ("dodeca-gouraud-n800", 6764, (33, 126), 78),
    ("dodeca-flat-n100", 6764, (33, 126), 186),
    ("dodeca-phong-light-2-2-2", 6764, (33, 126), 240),
    ("dodeca-phong-light-20-0-20", 6764, (33, 126), 252),
    ("dodeca-phong-light-2-0-2", 6764, (33, 126), 246),
    ("can-flat", 5501, (34, 131), 140),
    ("can-smooth", 5501, (34, 131), 155),
    ("grid-hotspot-gouraud", 12076, (35, 140), 95),
    ("grid-hotspot-phong", 12076, (35, 140), 255),
    ("big-face-gouraud", 12100, (25, 134), 21),
    ("big-face-phong", 12100, (25, 134), 248),
    ("cubes-and-sphere", 10131, (31, 113), 255),
    ("bunny-gouraud", 14905, (52, 202), 254),
    ("bunny-flat", 14905, (52, 202), 255),
];

#[test]
fn builtin_scenes_render_as_measured() {
    let names: Vec<&str> = builtin_scenes().iter().map(|(n, _, _)| *n).collect();
    let measured: Vec<&str> = MEASURED.iter().map(|m| m.0).collect();
    assert_eq!(names, measured);
    for &(name, covered, rows, brightest) in MEASURED {
        let scene = load_builtin(name).unwrap();
        assert_eq!(scene.source, format!("builtin:{name}"));
        assert!(scene.width <= 240 && scene.height <= 240, "{name} is small");
        let frame = ideal::render(&scene.to_ideal()).unwrap();
        let w = frame.width as usize;
        let covered_rows: Vec<usize> = (0..frame.covered.len())
            .filter(|&i| frame.covered[i])
            .map(|i| i / w)
            .collect();
        let top = *covered_rows.iter().min().unwrap();
        let bottom = *covered_rows.iter().max().unwrap();
        let rgb = frame.to_rgb8();
        let max = (0..rgb.len())
            .filter(|&i| frame.covered[i])
            .map(|i| *rgb[i].iter().max().unwrap())
            .max()
            .unwrap();
        assert_eq!(
            (frame.covered_count(), (top, bottom), max),
            (covered, rows, brightest),
            "{name}"
        );
    }
    let e = load_builtin("nope").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("builtin:nope: no such built-in scene; known scenes: dodeca-phong-n1, "),
        "{e}"
    );
}

#[test]
fn bunny_benchmark_scene() {
    let s = load_builtin("bunny-gouraud").unwrap();
    assert_eq!(
        (s.width, s.height, s.pixel_format),
        (240, 240, PixelFormat::Rgb565)
    );
    assert_eq!(s.background, [0, 0, 0]);
    assert_eq!(
        (s.camera.eye, s.camera.target, s.camera.up),
        ([0.0, 0.0, 3.922], [0.0; 3], [0.0, 1.0, 0.0])
    );
    assert_eq!(
        (s.camera.fov_y_deg, s.camera.near, s.camera.far),
        (45.0, 1.0, Some(10.0))
    );
    let o = &s.objects[0];
    assert!(matches!(o.mesh, SceneMesh::BuiltIn { name: "bunny", .. }));
    assert_eq!((o.shading, o.cull_backfaces), (Shading::Gouraud, true));
    assert_eq!(o.transform.scale, [1.0; 3]);
    let flat = load_builtin("bunny-flat").unwrap();
    assert_eq!(flat.objects[0].shading, Shading::Flat);

    // I = Ia ka C + Ip kd max(0, N.L) C = 0.2 + 0.8 max(0, N.L), no specular.
    let ideal = s.to_ideal();
    let l = [1.0 / 3f64.sqrt(); 3];
    let material = &ideal.objects[0].material;
    let normals: [[f64; 3]; 5] = [
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [-1.0, 0.0, 0.0],
        [0.3, -0.2, 0.9],
        [0.0, 1.0, 0.0],
    ];
    for n in normals {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let n_dot_l = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len;
        let want = 0.2 + 0.8 * n_dot_l.max(0.0);
        let got = ideal::illuminate(&ideal, material, [0.1, 0.2, 0.3], n);
        for c in got {
            assert!((c - want).abs() < 1e-15, "{got:?} vs {want}");
        }
    }

    // About 62% of the frame height and ~14,300-15,000 covered pixels.
    let frame = ideal::render(&ideal).unwrap();
    let rows: Vec<usize> = (0..frame.covered.len())
        .filter(|&i| frame.covered[i])
        .map(|i| i / 240)
        .collect();
    let height = rows.iter().max().unwrap() - rows.iter().min().unwrap() + 1;
    assert_eq!(height, 151); // 62.9%
    assert!((14_300..=15_000).contains(&frame.covered_count()));
    // The darkest covered pixels are the ambient 0.2 -> level 51.
    let rgb = frame.to_rgb8();
    let darkest = (0..rgb.len())
        .filter(|&i| frame.covered[i])
        .map(|i| rgb[i][0])
        .min()
        .unwrap();
    assert_eq!(darkest, 51);
}

#[test]
fn hot_spots_appear_with_phong_only() {
    // The brightest covered level of the hot-spot and big-face scenes:
    // Gouraud misses the highlight that Phong shows.
    let brightest = |name: &str| {
        let frame = ideal::render(&load_builtin(name).unwrap().to_ideal()).unwrap();
        frame
            .to_rgb8()
            .iter()
            .zip(&frame.covered)
            .filter(|(_, &c)| c)
            .map(|(p, _)| p[2])
            .max()
            .unwrap()
    };
    assert_eq!(brightest("grid-hotspot-gouraud"), 95);
    assert_eq!(brightest("grid-hotspot-phong"), 255);
    assert_eq!(brightest("big-face-gouraud"), 13);
    assert_eq!(brightest("big-face-phong"), 183);
}

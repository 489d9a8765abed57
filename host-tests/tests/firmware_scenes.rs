//! The firmware's generated scenes (`examples/firmware/scenes/src/generated.rs`):
//! regenerated from the built-in scenes and compared byte for byte with the
//! committed file (`MAKE_FIRMWARE_SCENES=1` rewrites it), and checked to
//! render, from the generated Q16 values into the recorded workspace, the
//! frame the host renders from the scene file with the `fast` profile.

use fixshade::render::{Part, Reach, RenderError};
use fixshade_host::core_render::{crc32, render_core, CoreProfile};
use fixshade_host::firmware_scenes::{
    generate, generated_path, Capacity, FirmwareScene, FirmwareSceneError, FIRMWARE_SCENES,
    MAX_WIDTH,
};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
fn committed_file_is_generator_output() {
    let text = generate().expect("the firmware scenes generate");
    let path = generated_path(&root());
    if std::env::var("MAKE_FIRMWARE_SCENES").is_ok_and(|v| v == "1") {
        std::fs::write(&path, &text).expect("write the generated scenes");
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == text,
        "{} differs from the generator output; run MAKE_FIRMWARE_SCENES=1 cargo test -p fixshade-host --test firmware_scenes",
        path.display()
    );
}

#[test]
fn generated_values_render_the_hosts_fast_frame() {
    for name in FIRMWARE_SCENES {
        let s = FirmwareScene::load(name).unwrap();
        let f = s.render_crc().unwrap();
        let host = render_core(&s.desc, Some(CoreProfile::Fast)).unwrap();
        // The same bytes, also where the depth band is left out.
        assert_eq!(f.crc, crc32(&host.bytes), "{name}");
        let covered = host.covered.iter().filter(|&&c| c).count();
        assert_eq!(f.covered as usize, covered, "{name}");
        // The storage is the core's bound: every mesh vertex, every mesh
        // triangle (the view keeps fewer), the layout's values.
        let c = s.capacity;
        let mesh_v: usize = s
            .desc
            .objects
            .iter()
            .map(|o| o.mesh.mesh().vertex_count())
            .sum();
        let mesh_t: usize = s
            .desc
            .objects
            .iter()
            .map(|o| o.mesh.mesh().triangle_count())
            .sum();
        assert!(s.rooms.iter().all(|r| r.reach == Reach::Inside), "{name}");
        assert_eq!((c.vertices, c.triangles), (mesh_v, mesh_t), "{name}");
        assert!(
            f.vertices <= c.vertices && f.triangles <= c.triangles,
            "{name}"
        );
        s.prepare_with(c).unwrap();
        // The vertex pass takes room for every mesh vertex and its values:
        // one less fails, naming the part.
        for (m, part) in [
            (
                Capacity {
                    vertices: c.vertices - 1,
                    ..c
                },
                Part::Vertices,
            ),
            (
                Capacity {
                    packed_values: c.packed_values - 1,
                    ..c
                },
                Part::Values,
            ),
            (
                Capacity {
                    triangles: f.triangles - 1,
                    ..c
                },
                Part::Triangles,
            ),
        ] {
            assert!(
                matches!(s.prepare_with(m), Err(RenderError::Capacity { part: p, object: _ }) if p == part),
                "{name}: {m:?}"
            );
        }
    }
}

#[test]
fn the_depth_band_is_left_out_for_one_convex_culled_object() {
    use fixshade::mesh::{BUNNY, CUBE, DODECAHEDRON, SPHERE};
    use fixshade_host::firmware_scenes::convex;
    assert_eq!(
        [convex(&CUBE), convex(&DODECAHEDRON), convex(&SPHERE)],
        [true; 3]
    );
    assert!(!convex(&BUNNY));
    let depth: Vec<(&str, bool)> = FIRMWARE_SCENES
        .iter()
        .map(|n| (*n, FirmwareScene::load(n).unwrap().depth))
        .collect();
    assert_eq!(
        depth,
        [
            ("dodeca-flat-n100", false),
            ("dodeca-gouraud-n100", false),
            ("dodeca-phong-n100", false),
            ("bunny-gouraud", true),
            ("bunny-flat", true),
            ("cubes-and-sphere", true),
        ]
    );
}

#[test]
fn refused_scenes_are_error_values() {
    let err = FirmwareScene::load("no-such-scene").err();
    assert!(matches!(err, Some(FirmwareSceneError::Load(_))), "{err:?}");
    let mut desc = FirmwareScene::load("bunny-gouraud").unwrap().desc;
    desc.width = MAX_WIDTH + 1;
    let err = FirmwareScene::new("wide".into(), desc).err();
    assert!(
        matches!(
            &err,
            Some(FirmwareSceneError::TooLarge { scene, width: 241, height: 240 }) if scene == "wide"
        ),
        "{err:?}"
    );
    assert_eq!(
        err.map(|e| e.to_string()).unwrap_or_default(),
        "wide: 241x240 is larger than the firmware's 240x240"
    );
}

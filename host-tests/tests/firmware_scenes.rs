//! The firmware's generated scenes (`examples/firmware/scenes/src/generated.rs`):
//! regenerated from the built-in scenes and compared byte for byte with the
//! committed file (`MAKE_FIRMWARE_SCENES=1` rewrites it), and checked to
//! render, from the generated Q16 values into the recorded workspace, the
//! frame the host renders from the scene file with the `fast` profile.

use fixshade::render::{Part, RenderError};
use fixshade_host::core_render::{crc32, render_core, CoreProfile};
use fixshade_host::firmware_scenes::{
    generate, generated_path, FirmwareScene, Needs, FIRMWARE_SCENES,
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
        let (crc, covered) = s.render_crc().unwrap();
        let host = render_core(&s.desc, Some(CoreProfile::Fast)).unwrap();
        assert_eq!(crc, crc32(&host.bytes), "{name}");
        assert_eq!(
            covered as usize,
            host.covered.iter().filter(|&&c| c).count(),
            "{name}"
        );
        // The recorded workspace is the smallest: one less of any part fails.
        let n = s.needs;
        assert!(n.vertices > 0 && n.values > 0 && n.triangles > 0);
        // No scratch: the smallest workspace is the prepared frame.
        assert_eq!(n.prepared_bytes, n.workspace_bytes());
        s.prepare_with(n).unwrap();
        let less = [
            Needs {
                vertices: n.vertices - 1,
                ..n
            },
            Needs {
                values: n.values - 1,
                ..n
            },
            Needs {
                triangles: n.triangles - 1,
                ..n
            },
        ];
        for (m, part) in less
            .into_iter()
            .zip([Part::Vertices, Part::Values, Part::Triangles])
        {
            assert!(
                matches!(s.prepare_with(m), Err(RenderError::Capacity { part: p, object: _ }) if p == part),
                "{name}: {m:?}"
            );
        }
    }
}

//! Band rendering gives the very bytes of a full-frame render, for every
//! built-in scene and band heights 1, 7, 16 and the full height.

use fixshade_host::builtin::{builtin_scenes, load_builtin};
use fixshade_host::core_render::{render_core_rows, CoreProfile};

#[test]
fn every_builtin_scene_renders_identically_in_bands() {
    for &(name, _, _) in builtin_scenes() {
        let desc = load_builtin(name).unwrap();
        for p in [CoreProfile::Fast, CoreProfile::Precise, CoreProfile::F64Pc] {
            let full = render_core_rows(&desc, Some(p), desc.height).unwrap();
            assert!(full.pixels_drawn > 1000, "{name}: something is drawn");
            for rows in [1, 7, 16] {
                let banded = render_core_rows(&desc, Some(p), rows).unwrap();
                assert!(
                    banded.bytes == full.bytes,
                    "{name} {} rows {rows}: bytes differ",
                    p.name()
                );
                assert_eq!(
                    banded.covered,
                    full.covered,
                    "{name} {} rows {rows}",
                    p.name()
                );
            }
        }
    }
}

//! Reference images: every built-in scene, reduced to 64 pixels on its
//! longer side, rendered by the core with the fixed profiles, compared
//! exactly (bit for bit: fixed point is the same on every machine) with
//! `tests/images/core-SCENE-PROFILE.png`. `MAKE_REF=1 cargo test -p
//! fixshade-host --test all reference_images` rewrites them; a mismatch
//! writes expected | mask | actual to `tests/diff/` (ignored by git).

use fixshade_host::builtin::{builtin_scenes, load_builtin};
use fixshade_host::core_render::{render_core, CoreProfile};
use fixshade_host::image::check_reference;

#[test]
fn fixed_profiles_match_the_reference_images() {
    let mut failures = vec![];
    for &(name, _, _) in builtin_scenes() {
        let mut desc = load_builtin(name).unwrap();
        let k = 64.0 / desc.width.max(desc.height) as f64;
        desc.width = (desc.width as f64 * k).round() as u32;
        desc.height = (desc.height as f64 * k).round() as u32;
        for p in [CoreProfile::Fast, CoreProfile::Precise] {
            let f = render_core(&desc, Some(p)).unwrap();
            assert!(
                f.covered.iter().filter(|&&c| c).count() > 100,
                "{name} {}: too little drawn",
                p.name()
            );
            if let Err(e) = check_reference(
                &format!("core-{name}-{}", p.name()),
                f.width,
                f.height,
                &f.rgb,
            ) {
                failures.push(e.to_string());
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

//! The documentation's tables, generated (no figure copied by hand).
//!
//! `README.md` and `docs/accuracy.md` hold blocks between
//!
//! ```text
//! <!-- fixshade-docs NAME: generated, do not edit ... -->
//! ...
//! <!-- fixshade-docs NAME end -->
//! ```
//!
//! whose text is [`block`]`(NAME)`: the chip tables from the committed
//! firmware measurements ([`super::chips`]), the accuracy table from the
//! host's renders of every built-in scene with every profile. The test
//! `host-tests/tests/docs_tables.rs` fails when a block differs, and
//! rewrites them with `MAKE_DOCS=1` (run by CI through `cargo test`).

use std::collections::BTreeMap;

use crate::builtin::{builtin_scenes, load_builtin};
use crate::cli::CliError;
use crate::compare::metrics_of;
use crate::core_render::CoreProfile;
use crate::ideal::Shading;

use super::chips::{ChipResult, Measurements};

/// The blocks: (file relative to the repository root, block name).
pub const BLOCKS: [(&str, &str); 3] = [
    ("README.md", "chip-fast"),
    ("README.md", "chip-profiles"),
    ("docs/accuracy.md", "accuracy"),
];

/// The command that rewrites every block.
pub const REGENERATE: &str = "MAKE_DOCS=1 cargo test -p fixshade-host --test docs_tables";

fn begin(name: &str) -> String {
    format!("<!-- fixshade-docs {name}: generated, do not edit; `{REGENERATE}` rewrites it -->")
}

fn end(name: &str) -> String {
    format!("<!-- fixshade-docs {name} end -->")
}

/// The text between a block's markers in `text`, if both are there.
pub fn find_block<'a>(text: &'a str, name: &str) -> Option<&'a str> {
    let (b, e) = (begin(name), end(name));
    let start = text.find(&b)? + b.len();
    let stop = start + text[start..].find(&e)?;
    Some(&text[start..stop])
}

/// `text` with the block's contents replaced by `body` (`None` when the
/// markers are missing).
pub fn replace_block(text: &str, name: &str, body: &str) -> Option<String> {
    let old = find_block(text, name)?;
    let start = old.as_ptr() as usize - text.as_ptr() as usize;
    Some(format!(
        "{}{}{}",
        &text[..start],
        body,
        &text[start + old.len()..]
    ))
}

/// A block as it should be: its markers' inner text (starting and ending
/// with a newline).
///
/// # Errors
/// An unknown block name, or a scene a renderer refuses (bad input).
pub fn block(name: &str, ms: &Measurements) -> Result<String, CliError> {
    let body = match name {
        "chip-fast" => chip_fast(ms),
        "chip-profiles" => chip_profiles(ms),
        "accuracy" => accuracy()?,
        _ => return Err(CliError::input(format!("no docs block `{name}`"))),
    };
    Ok(format!("\n{body}"))
}

/// Rewrites every block of [`BLOCKS`] under `root` from `ms`; returns the
/// files changed. A file without a block's markers is left alone.
///
/// # Errors
/// A file that cannot be read or written, or a block that cannot be
/// computed.
pub fn write_blocks(
    root: &std::path::Path,
    ms: &Measurements,
) -> Result<Vec<std::path::PathBuf>, CliError> {
    let mut changed = Vec::new();
    for (file, name) in BLOCKS {
        let path = root.join(file);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| CliError::input(format!("{}: cannot read: {e}", path.display())))?;
        let Some(have) = find_block(&text, name) else {
            continue;
        };
        let want = block(name, ms)?;
        if have != want {
            if let Some(new) = replace_block(&text, name, &want) {
                crate::cli::write_atomically(&path, |out| out.write_all(new.as_bytes()))?;
                if !changed.contains(&path) {
                    changed.push(path);
                }
            }
        }
    }
    Ok(changed)
}

/// Markers and all, for a file that lacks them.
pub fn with_markers(name: &str, body: &str) -> String {
    format!("{}{body}{}", begin(name), end(name))
}

fn mi(x: u64) -> String {
    format!("{:.2} M", x as f64 / 1e6)
}

fn thousands(x: u64) -> String {
    let s = x.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(' ');
        }
        out.push(c);
    }
    out
}

fn find<'a>(ms: &'a Measurements, t: &str, p: &str, s: &str) -> Option<&'a ChipResult> {
    ms.results
        .iter()
        .find(|r| r.target == t && r.profile == p && r.scene == s)
}

const M0: &str = "thumbv6m-none-eabi";
const M4: &str = "thumbv7em-none-eabihf";

/// The `fast` profile per firmware scene on both chips.
fn chip_fast(ms: &Measurements) -> String {
    let mut s = String::from(
        "| scene | thumbv6m insns (est. M0 cycles) | thumbv7em insns | covered px |\n|---|---:|---:|---:|\n",
    );
    for r in ms
        .results
        .iter()
        .filter(|r| r.target == M0 && r.profile == "fast")
    {
        let m4 = find(ms, M4, "fast", &r.scene);
        s += &format!(
            "| {}, {}×{} | {} ({}) | {} | {} |\n",
            r.scene,
            r.width,
            r.height,
            mi(r.insns),
            r.cycles.map_or("–".into(), mi),
            m4.map_or("–".into(), |m| mi(m.insns)),
            thousands(r.covered)
        );
    }
    s
}

/// Every profile on both chips: the bunny (Gouraud) and the Phong
/// dodecahedron, flash and RAM.
fn chip_profiles(ms: &Measurements) -> String {
    let mut s = String::from(
        "| profile | bunny Gouraud: est. M0 cycles | M4F insns | dodeca Phong: est. M0 cycles | M4F insns | M0 flash B | static RAM B | soft-float routines (M0 / M4F) |\n|---|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for p in CoreProfile::ALL {
        let c = |t: &str, sc: &str| find(ms, t, p.name(), sc);
        let build = |t: &str| {
            ms.builds
                .iter()
                .find(|b| b.target == t && b.profile == p.name())
        };
        let (Some(b0), Some(b4)) = (build(M0), build(M4)) else {
            continue;
        };
        s += &format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} / {} |\n",
            p.name(),
            c(M0, "bunny-gouraud")
                .and_then(|r| r.cycles)
                .map_or("–".into(), mi),
            c(M4, "bunny-gouraud").map_or("–".into(), |r| mi(r.insns)),
            c(M0, "dodeca-phong-n100")
                .and_then(|r| r.cycles)
                .map_or("–".into(), mi),
            c(M4, "dodeca-phong-n100").map_or("–".into(), |r| mi(r.insns)),
            thousands(b0.flash_bytes),
            thousands(b0.static_ram_bytes),
            b0.softfloat_routines,
            b4.softfloat_routines
        );
    }
    s
}

/// Per profile and scene group (with or without a Phong object), the
/// maxima over the built-in scenes of the errors against the twin and
/// the ideal (`docs/accuracy.md`).
fn accuracy() -> Result<String, CliError> {
    use rayon::prelude::*;
    let names: Vec<&str> = builtin_scenes().iter().map(|&(n, _, _)| n).collect();
    // Per scene: the ideal frame and both twins once, then every profile.
    let per_scene: Vec<Vec<(bool, CoreProfile, [f64; 6])>> = names
        .par_iter()
        .map(|&name| {
            let desc = load_builtin(name)?;
            let phong = desc.objects.iter().any(|o| o.shading == Shading::Phong);
            let ideal = super::sweep::ideal_frame(&desc)?;
            let twins = [
                super::sweep::rgb_frame(&desc, CoreProfile::F64)?,
                super::sweep::rgb_frame(&desc, CoreProfile::F64Pc)?,
            ];
            CoreProfile::ALL
                .into_iter()
                .map(|p| {
                    let twin = &twins[usize::from(p.perspective())];
                    let fixed = super::sweep::rgb_frame(&desc, p)?;
                    let m = metrics_of(&fixed, twin, &ideal)
                        .map_err(|e| CliError::input(format!("{name}: {e}")))?;
                    let (f, i) = (&m.vs_float, &m.vs_ideal);
                    Ok((
                        phong,
                        p,
                        [
                            f.coverage_mismatch as f64,
                            f64::from(f.max_abs_error),
                            f.mean_abs_error,
                            i.coverage_mismatch as f64,
                            i.mean_abs_error,
                            i.share_over_1,
                        ],
                    ))
                })
                .collect()
        })
        .collect::<Result<_, CliError>>()?;
    let rows = per_scene.into_iter().flatten();
    let mut max: BTreeMap<(CoreProfile, bool), ([f64; 6], usize)> = BTreeMap::new();
    for (phong, p, v) in rows {
        let e = max.entry((p, phong)).or_insert(([0.0; 6], 0));
        for (m, x) in e.0.iter_mut().zip(v) {
            *m = m.max(x);
        }
        e.1 += 1;
    }
    let mut s = String::from(
        "| profile | scenes | vs twin: coverage mismatches | max | mean | vs ideal: coverage mismatches | mean | share>1 |\n|---|---|---:|---:|---:|---:|---:|---:|\n",
    );
    for p in CoreProfile::ALL {
        for phong in [false, true] {
            let Some((v, n)) = max.get(&(p, phong)) else {
                continue;
            };
            s += &format!(
                "| {} | {} ({n}) | {} | {} | {:.4} | {} | {:.3} | {:.4} |\n",
                p.name(),
                if phong { "Phong" } else { "Gouraud/flat" },
                v[0],
                v[1],
                v[2],
                v[3],
                v[4],
                v[5]
            );
        }
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn write_blocks_rewrites_stale_blocks_and_leaves_the_rest() {
        let root = std::env::temp_dir().join(format!("fixshade-docs-{}", std::process::id()));
        std::fs::create_dir_all(root.join("docs")).unwrap();
        let readme = format!("# x\n{}\ntail\n", with_markers("chip-fast", "\nold\n"));
        std::fs::write(root.join("README.md"), &readme).unwrap();
        // No markers: left alone (and the accuracy block not computed).
        std::fs::write(root.join("docs/accuracy.md"), "no markers\n").unwrap();
        let ms = super::super::chips::load(
            &super::super::chips::repo_root().join(super::super::chips::DEFAULT_PATH),
        )
        .unwrap();
        let changed = write_blocks(&root, &ms).unwrap();
        assert_eq!(changed, [root.join("README.md")]);
        let text = std::fs::read_to_string(root.join("README.md")).unwrap();
        assert_eq!(
            find_block(&text, "chip-fast").unwrap(),
            block("chip-fast", &ms).unwrap()
        );
        assert!(text.starts_with("# x\n") && text.ends_with("\ntail\n"));
        assert_eq!(
            std::fs::read_to_string(root.join("docs/accuracy.md")).unwrap(),
            "no markers\n"
        );
        // Current blocks: nothing to write.
        assert!(write_blocks(&root, &ms).unwrap().is_empty());
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn blocks_are_found_and_replaced() {
        let text = format!("a\n{}\nb\n", with_markers("x", "\nold\n"));
        assert_eq!(find_block(&text, "x"), Some("\nold\n"));
        let new = replace_block(&text, "x", "\nnew\n").unwrap();
        assert_eq!(new, format!("a\n{}\nb\n", with_markers("x", "\nnew\n")));
        assert_eq!(find_block(&text, "y"), None);
        assert_eq!(thousands(80480), "80 480");
        assert_eq!(thousands(141_788), "141 788");
        assert_eq!(thousands(999), "999");
    }
}

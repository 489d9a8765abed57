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

use super::Error;
use crate::builtin::{builtin_scenes, load_builtin};
use crate::compare::metrics_of;
use crate::core_render::CoreProfile;
use crate::ideal::Shading;
use crate::output::write_atomically;

use super::chips::{ChipResult, Measurements};

/// The blocks: (file relative to the repository root, block name).
pub const BLOCKS: [(&str, &str); 9] = [
    ("README.md", "chip-fast"),
    ("README.md", "chip-budgets"),
    ("README.md", "chip-spans"),
    ("README.md", "chip-memory"),
    ("README.md", "chip-profiles"),
    ("docs/accuracy.md", "accuracy"),
    ("examples/firmware/README.md", "chip-split"),
    ("examples/firmware/README.md", "chip-spans"),
    ("examples/firmware/README.md", "chip-memory"),
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
pub fn block(name: &str, ms: &Measurements) -> Result<String, Error> {
    let body = match name {
        "chip-fast" => chip_fast(ms),
        "chip-profiles" => chip_profiles(ms),
        "chip-budgets" => chip_budgets(ms),
        "chip-spans" => chip_spans(ms),
        "chip-memory" => chip_memory(ms),
        "chip-split" => chip_split(ms),
        "accuracy" => accuracy()?,
        _ => return Err(Error::input(format!("no docs block `{name}`"))),
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
) -> Result<Vec<std::path::PathBuf>, Error> {
    let mut changed = Vec::new();
    for (file, name) in BLOCKS {
        let path = root.join(file);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| Error::input(format!("{}: cannot read: {e}", path.display())))?;
        let Some(have) = find_block(&text, name) else {
            continue;
        };
        let want = block(name, ms)?;
        if have != want {
            if let Some(new) = replace_block(&text, name, &want) {
                write_atomically(&path, |out| out.write_all(new.as_bytes()))
                    .map_err(|e| Error::write(&path, e))?;
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

/// Each scene's `fast` result on the M0, with the same scene's on the M4.
fn fast_scenes(ms: &Measurements) -> impl Iterator<Item = (&ChipResult, Option<&ChipResult>)> {
    ms.results
        .iter()
        .filter(|r| r.target == M0 && r.profile == "fast")
        .map(|r| (r, find(ms, M4, "fast", &r.scene)))
}

const M0: &str = "thumbv6m-none-eabi";
const M4: &str = "thumbv7em-none-eabihf";

/// The `fast` profile per firmware scene on both chips.
fn chip_fast(ms: &Measurements) -> String {
    let mut s = String::from(
        "| scene | thumbv6m insns (est. M0 cycles) | thumbv7em insns | covered px |\n|---|---:|---:|---:|\n",
    );
    for (r, m4) in fast_scenes(ms) {
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

/// A span loop's instructions per pixel (`fast` build) on `t`.
fn span_px(ms: &Measurements, t: &str, kernel: &str) -> Option<f64> {
    ms.builds
        .iter()
        .filter(|b| b.target == t)
        .flat_map(|b| &b.spans)
        .find(|s| s.kernel == kernel)
        .map(|s| s.insns_per_px())
}

/// small3dlib's bunny frame (no subpixel precision, no top-left rule),
/// instructions, from the benchmark scene's notes: thumbv6m, thumbv7em.
pub const SMALL3DLIB_BUNNY: [(&str, u64); 2] = [(M0, 10_550_000), (M4, 4_380_000)];

/// The cost budgets of the issues, checked against the measurements:
/// (what, target, measured, budget text, met).
fn budget_rows(ms: &Measurements) -> Vec<(String, &'static str, String, String, bool)> {
    let fast = |t: &str, sc: &str| find(ms, t, "fast", sc);
    let mut rows = Vec::new();
    let mut cost = |what: &str, t: &'static str, v: Option<u64>, budget: u64| {
        if let Some(v) = v {
            rows.push((
                what.to_string(),
                t,
                mi(v),
                format!("≤ {}", mi(budget)),
                v <= budget,
            ));
        }
    };
    for (t, geo, ras, frame) in [
        (M0, 800_000, 2_400_000, 3_500_000),
        (M4, 400_000, 1_000_000, 1_500_000),
    ] {
        let b = fast(t, "bunny-gouraud");
        cost(
            "bunny Gouraud geometry",
            t,
            b.map(|r| r.insns_geometry),
            geo,
        );
        cost("bunny Gouraud raster", t, b.map(|r| r.insns_raster), ras);
        cost("bunny Gouraud frame", t, b.map(|r| r.insns), frame);
    }
    for t in [M0, M4] {
        if let (Some(f), Some(g)) = (fast(t, "bunny-flat"), fast(t, "bunny-gouraud")) {
            rows.push((
                "bunny flat frame".into(),
                t,
                mi(f.insns),
                format!("< Gouraud {}", mi(g.insns)),
                f.insns < g.insns,
            ));
        }
        if let (Some(p), Some(g)) = (fast(t, "dodeca-phong-n100"), fast(t, "dodeca-gouraud-n100")) {
            rows.push((
                "dodecahedron Phong frame".into(),
                t,
                mi(p.insns),
                format!("≤ 3 × Gouraud = {}", mi(3 * g.insns)),
                p.insns <= 3 * g.insns,
            ));
        }
    }
    // Memory (issue 13): the prepared bunny Gouraud frame, and the
    // static RAM and stack of the bunny firmware (`--features bunny`: the
    // bunny Gouraud scene alone, its storage, pool and bands sized for it),
    // the build the budget is about. (The default build, which holds every
    // built-in scene, is in the memory table.) The stack stays at or below
    // its figure when the budget was set.
    let kb = |b: u64| format!("{} B", thousands(b));
    for (t, stack_then) in [(M0, BUNNY_STACK_M0), (M4, BUNNY_STACK_M4)] {
        let alone = ms
            .alone
            .iter()
            .find(|a| a.target == t && a.features == "bunny");
        if let Some(b) = fast(t, "bunny-gouraud") {
            rows.push((
                "bunny Gouraud prepared frame".into(),
                t,
                kb(b.prepared_bytes),
                format!("≤ 24 KB = {}", kb(24 * 1024)),
                b.prepared_bytes <= 24 * 1024,
            ));
            // A file measured before the bunny firmware was: the default
            // build's, named as such.
            if alone.is_none() {
                rows.push((
                    "static RAM of the default firmware (every built-in scene)".into(),
                    t,
                    kb(b.static_ram),
                    format!("≤ 40 KB = {}", kb(40 * 1024)),
                    b.static_ram <= 40 * 1024,
                ));
            }
        }
        if let Some(a) = alone {
            rows.push((
                "static RAM of the bunny firmware (`--features bunny`)".into(),
                t,
                kb(a.static_ram_bytes),
                format!("≤ 40 KB = {}", kb(40 * 1024)),
                a.static_ram_bytes <= 40 * 1024,
            ));
            rows.push((
                "stack of the bunny firmware".into(),
                t,
                kb(a.stack),
                format!("≤ {}", kb(stack_then)),
                a.stack <= stack_then,
            ));
        }
    }
    let px = |v: f64| format!("{v:.2} /px");
    for (what, t, kernel, budget) in [
        ("flat span", M4, "flat", 8.0),
        ("Gouraud span", M4, "gouraud", 12.0),
        ("Gouraud span", M0, "gouraud", 18.0),
        ("Phong span, 1 directional light", M4, "phong-k1", 60.0),
        (
            "Phong span, 1 point light, local viewer",
            M4,
            "phong-kpoint",
            90.0,
        ),
    ] {
        if let Some(v) = span_px(ms, t, kernel) {
            rows.push((what.into(), t, px(v), format!("≤ {budget}"), v <= budget));
        }
    }
    for kernel in ["phong-k1", "phong-kpoint"] {
        if let (Some(m0), Some(m4)) = (span_px(ms, M0, kernel), span_px(ms, M4, kernel)) {
            rows.push((
                format!("Phong span `{kernel}`"),
                M0,
                px(m0),
                format!("≤ 2.5 × thumbv7em = {:.1}", 2.5 * m4),
                m0 <= 2.5 * m4,
            ));
        }
    }
    rows
}

/// The bunny Gouraud scene's stack on thumbv6m when its memory budget was
/// set (issue 13: "stack as now or less", at commit e5e2812), bytes.
const BUNNY_STACK_M0: u64 = 5_908;
/// The same on thumbv7em, bytes.
const BUNNY_STACK_M4: u64 = 5_564;

/// The budgets table: measured against each budget, and the bunny frame
/// against small3dlib's.
fn chip_budgets(ms: &Measurements) -> String {
    let mut s =
        String::from("| budget | target | measured | budget | met |\n|---|---|---:|---:|---|\n");
    for (what, t, v, b, met) in budget_rows(ms) {
        s += &format!(
            "| {what} | {t} | {v} | {b} | {} |\n",
            if met { "yes" } else { "**no**" }
        );
    }
    for (t, peer) in SMALL3DLIB_BUNNY {
        if let Some(r) = find(ms, t, "fast", "bunny-gouraud") {
            s += &format!(
                "\nbunny Gouraud frame on {t}: {} = {:.2} × small3dlib's {} (which has no subpixel precision and no top-left rule).\n",
                mi(r.insns),
                r.insns as f64 / peer as f64,
                mi(peer)
            );
        }
    }
    s
}

/// The span loops alone, per pixel, on both chips (`fast` build).
fn chip_spans(ms: &Measurements) -> String {
    let mut s =
        String::from("| span loop | thumbv7em insns/px | thumbv6m insns/px |\n|---|---:|---:|\n");
    let kernels: Vec<&str> = ms
        .builds
        .iter()
        .filter(|b| b.target == M4)
        .flat_map(|b| b.spans.iter().map(|s| s.kernel.as_str()))
        .collect();
    for k in kernels {
        let cell = |t: &str| span_px(ms, t, k).map_or("–".into(), |v| format!("{v:.2}"));
        s += &format!("| {k} | {} | {} |\n", cell(M4), cell(M0));
    }
    s
}

/// Memory of the `fast` firmware: flash and static RAM per chip, and per
/// scene the prepared frame, the bands and the stack.
fn chip_memory(ms: &Measurements) -> String {
    let mut s = String::from(
        "| `fast` firmware | flash B | code B | read-only data B | static RAM B |\n|---|---:|---:|---:|---:|\n",
    );
    for t in [M0, M4] {
        if let Some(b) = ms
            .builds
            .iter()
            .find(|b| b.target == t && b.profile == "fast")
        {
            s += &format!(
                "| {t} | {} | {} | {} | {} |\n",
                thousands(b.flash_bytes),
                thousands(b.text_bytes),
                thousands(b.rodata_bytes),
                thousands(b.static_ram_bytes)
            );
        }
    }
    s += "\n| scene | prepared frame B | colour + depth band B | stack B (thumbv6m / thumbv7em) |\n|---|---:|---:|---:|\n";
    for (r, m4) in fast_scenes(ms) {
        s += &format!(
            "| {} | {} | {} | {} / {} |\n",
            r.scene,
            thousands(r.prepared_bytes),
            thousands(r.band_bytes + r.depth_bytes),
            thousands(r.stack),
            m4.map_or("–".into(), |m| thousands(m.stack))
        );
    }
    s
}

/// The `fast` profile per firmware scene on both chips, geometry and
/// raster apart, and per covered pixel.
fn chip_split(ms: &Measurements) -> String {
    let mut s = String::from(
        "| scene | M0 insns: frame (geometry + raster) | est. M0 cycles | M4 insns: frame (geometry + raster) | M0 / M4 insns per covered px | setups |\n|---|---:|---:|---:|---:|---:|\n",
    );
    let split = |r: &ChipResult| {
        format!(
            "{} ({:.3} + {:.3})",
            mi(r.insns),
            r.insns_geometry as f64 / 1e6,
            r.insns_raster as f64 / 1e6
        )
    };
    let per_px = |r: &ChipResult| r.insns / r.covered.max(1);
    for (r, m4) in fast_scenes(ms) {
        s += &format!(
            "| {} | {} | {} | {} | {} / {} | {} |\n",
            r.scene,
            split(r),
            r.cycles.map_or("–".into(), mi),
            m4.map_or("–".into(), split),
            thousands(per_px(r)),
            m4.map_or("–".into(), |m| thousands(per_px(m))),
            thousands(r.setups)
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
fn accuracy() -> Result<String, Error> {
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
                        .map_err(|e| Error::input(format!("{name}: {e}")))?;
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
        .collect::<Result<_, Error>>()?;
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
    use super::super::chips::AloneBuild;
    use super::*;

    #[test]
    fn write_blocks_rewrites_stale_blocks_and_leaves_the_rest() {
        let root = std::env::temp_dir().join(format!("fixshade-docs-{}", std::process::id()));
        std::fs::create_dir_all(root.join("docs")).unwrap();
        let readme = format!("# x\n{}\ntail\n", with_markers("chip-fast", "\nold\n"));
        std::fs::write(root.join("README.md"), &readme).unwrap();
        // No markers: left alone (and the accuracy block not computed).
        std::fs::write(root.join("docs/accuracy.md"), "no markers\n").unwrap();
        std::fs::create_dir_all(root.join("examples/firmware")).unwrap();
        std::fs::write(root.join("examples/firmware/README.md"), "no markers\n").unwrap();
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
    fn the_ram_budget_rows_show_the_bunny_firmware() {
        let mut ms = super::super::chips::load(
            &super::super::chips::repo_root().join(super::super::chips::DEFAULT_PATH),
        )
        .unwrap();
        let ram_rows = |ms: &Measurements| -> Vec<(String, &str, String, String, bool)> {
            budget_rows(ms)
                .into_iter()
                .filter(|r| r.0.starts_with("static RAM") || r.0.starts_with("stack"))
                .collect()
        };
        // Measured before the bunny firmware was: the default build's,
        // named as such.
        ms.alone.clear();
        let old = ram_rows(&ms);
        assert_eq!(old.len(), 2, "{old:?}");
        for (r, t) in old.iter().zip([M0, M4]) {
            assert_eq!(
                r.0,
                "static RAM of the default firmware (every built-in scene)"
            );
            assert_eq!(r.1, t);
            let b = find(&ms, t, "fast", "bunny-gouraud").unwrap();
            assert_eq!(r.2, format!("{} B", thousands(b.static_ram)));
        }
        // With the bunny firmware: its static RAM and its stack.
        let alone = |target: &str, ram: u64, stack: u64| AloneBuild {
            target: target.into(),
            features: "bunny".into(),
            scenes: vec!["bunny-gouraud".into()],
            flash_bytes: 90_000,
            static_ram_bytes: ram,
            stack,
        };
        ms.alone = vec![alone(M0, 40_616, 5_908), alone(M4, 41_000, 5_600)];
        let rows = ram_rows(&ms);
        let want = [
            (
                "static RAM of the bunny firmware (`--features bunny`)",
                M0,
                "40 616 B",
                "≤ 40 KB = 40 960 B",
                true,
            ),
            (
                "stack of the bunny firmware",
                M0,
                "5 908 B",
                "≤ 5 908 B",
                true,
            ),
            (
                "static RAM of the bunny firmware (`--features bunny`)",
                M4,
                "41 000 B",
                "≤ 40 KB = 40 960 B",
                false,
            ),
            (
                "stack of the bunny firmware",
                M4,
                "5 600 B",
                "≤ 5 564 B",
                false,
            ),
        ];
        assert_eq!(rows.len(), want.len(), "{rows:?}");
        for (r, w) in rows.iter().zip(want) {
            assert_eq!((r.0.as_str(), r.1, r.2.as_str(), r.3.as_str(), r.4), w);
        }
        let table = chip_budgets(&ms);
        assert!(table.contains("| static RAM of the bunny firmware (`--features bunny`) | thumbv6m-none-eabi | 40 616 B | ≤ 40 KB = 40 960 B | yes |\n"), "{table}");
        assert!(!table.contains("default firmware"), "{table}");
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

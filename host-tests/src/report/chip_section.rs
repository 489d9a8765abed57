//! The report's chip section, first on the page: what a configuration
//! costs on a Cortex-M0 and a Cortex-M4F (the committed firmware
//! measurements, [`super::chips`]), the picks for common parts, fps at
//! their clocks for every firmware scene, fixed point against soft-float
//! on the M0, flash and RAM per build, and the plots of error against
//! cycles and RAM per chip with the Pareto front. HTML by `maud`
//! (escaped by construction). Host time appears nowhere here.

use std::collections::BTreeMap;

use maud::{html, Markup, PreEscaped};
use serde::{Deserialize, Serialize};

use crate::core_render::CoreProfile;

use super::chips::Measurements;
use super::embedded::Target;
use super::picks::{
    candidates, choose_scenes, find_chip, pick, unit, Budget, Candidate, Outcome, SceneChoice,
    TABLE_CHIPS,
};
use super::plot::scatter_svg;
use super::summary::Point;

/// The frame rate of the picks table.
pub const TABLE_FPS: f64 = 10.0;

/// A table: head and rows of text.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table {
    /// Column titles.
    pub head: Vec<String>,
    /// Rows.
    pub rows: Vec<Vec<String>>,
}

/// Everything the chip section shows (in `results.json` as `chips`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChipSection {
    /// The measurements file.
    pub file: String,
    /// Toolchain and source fingerprint of the figures.
    pub provenance: String,
    /// Whether the figures were measured from other sources (only with
    /// `--allow-stale`).
    pub stale: bool,
    /// The scenes the picks and plots use.
    pub scenes: Vec<String>,
    /// Picks for common parts at `TABLE_FPS` (10 fps).
    pub picks: Table,
    /// fps at the parts' clocks, every firmware scene and profile.
    pub fps: Table,
    /// Fixed point against soft-float on the M0.
    pub m0_float: Table,
    /// Flash and static RAM per build.
    pub builds: Table,
    /// Float profiles' CRCs against the host's.
    pub crc_notes: Vec<String>,
    /// The user's scenes: the RAM each needs per profile and mode against
    /// the parts' RAM (empty for the built-in sweep).
    #[serde(default)]
    pub user_ram: Option<Table>,
    /// The user's scenes measured on the chips (`--measure-firmware`):
    /// instructions, est. M0 cycles, RAM, stack and flash per scene ×
    /// mode × profile × target, and whether each part holds and runs it
    /// (`None`: not measured, the note says so).
    #[serde(default)]
    pub user_measured: Option<Table>,
    /// Per chip: (title, error vs cycles SVG, error vs RAM SVG).
    #[serde(skip)]
    pub plots: Vec<(String, String, String)>,
}

fn m(x: u64) -> String {
    format!("{:.3} M", x as f64 / 1e6)
}

fn point(c: &Candidate, cost: f64) -> Option<Point> {
    Some(Point {
        mode: c.mode?,
        profile: c.profile,
        cost,
        vs_ideal: c.error,
        vs_twin: 0.0,
        vs_phong: c.error,
    })
}

impl ChipSection {
    /// Builds the section from the measurements and the host errors of
    /// every firmware scene and profile ([`super::picks::host_errors`]).
    pub fn new(
        ms: &Measurements,
        file: &str,
        stale: bool,
        errors: &BTreeMap<(String, CoreProfile), f64>,
    ) -> Self {
        let choice = choose_scenes(ms, None).unwrap_or(SceneChoice {
            name: String::new(),
            scenes: Vec::new(),
        });
        let cands: BTreeMap<Target, Vec<Candidate>> = Target::ALL
            .into_iter()
            .map(|t| (t, candidates(ms, t, &choice.scenes, errors)))
            .collect();

        // Picks for common parts.
        let mut picks = Vec::new();
        for name in TABLE_CHIPS {
            let Some(chip) = find_chip(name) else {
                continue;
            };
            let b = Budget {
                target: chip.target,
                mhz: chip.mhz,
                fps: TABLE_FPS,
                ram_bytes: chip.ram_kb * 1024.0,
            };
            let cs = &cands[&chip.target];
            let row = |c: &Candidate| {
                format!(
                    "{} ({:.3} levels, {}, {:.1} fps, {} B)",
                    c.label(),
                    c.error,
                    m(c.cycles),
                    c.fps(b.mhz),
                    c.ram
                )
            };
            let (p, r) = match pick(cs, &b) {
                Outcome::Fit { chosen, runner_up } => (
                    row(&cs[chosen]),
                    runner_up.map_or("–".into(), |i| row(&cs[i])),
                ),
                Outcome::NoFit { closest } => (
                    format!(
                        "nothing fits; closest {} is {:.2}× over",
                        row(&cs[closest]),
                        cs[closest].over(&b)
                    ),
                    "–".into(),
                ),
                Outcome::Empty => ("no measurements".into(), "–".into()),
            };
            picks.push(vec![
                chip.title.to_string(),
                format!("{} {}", m(b.cycles() as u64), unit(chip.target)),
                p,
                r,
            ]);
        }

        // fps at the parts' clocks.
        let clocks: Vec<(&str, Target, f64)> = TABLE_CHIPS
            .iter()
            .filter_map(|n| find_chip(n))
            .map(|c| (c.name, c.target, c.mhz))
            .collect();
        let mut head = vec!["scene".to_string(), "profile".to_string()];
        head.push("M0 est. cycles".into());
        head.push("M4F instructions".into());
        for (n, t, mhz) in &clocks {
            head.push(format!("fps {n} {mhz} MHz ({})", t.name()));
        }
        head.push("RAM M0 B".into());
        let mut fps_rows = Vec::new();
        let find = |t: &str, p: &str, s: &str| {
            ms.results
                .iter()
                .find(|r| r.target == t && r.profile == p && r.scene == s)
        };
        let mut scene_names: Vec<&str> = Vec::new();
        for r in &ms.results {
            if !scene_names.contains(&r.scene.as_str()) {
                scene_names.push(&r.scene);
            }
        }
        for s in &scene_names {
            for p in CoreProfile::ALL {
                let m0 = find("thumbv6m-none-eabi", p.name(), s);
                let m4 = find("thumbv7em-none-eabihf", p.name(), s);
                if m0.is_none() && m4.is_none() {
                    continue;
                }
                let mut row = vec![s.to_string(), p.name().to_string()];
                row.push(m0.map_or("–".into(), |r| m(r.frame_cycles())));
                row.push(m4.map_or("–".into(), |r| m(r.frame_cycles())));
                for (_, t, mhz) in &clocks {
                    let r = if *t == Target::M0 { m0 } else { m4 };
                    row.push(r.map_or("–".into(), |r| {
                        format!("{:.1}", mhz * 1e6 / r.frame_cycles().max(1) as f64)
                    }));
                }
                row.push(m0.map_or("–".into(), |r| r.ram.to_string()));
                fps_rows.push(row);
            }
        }

        // Fixed point against soft-float on the M0.
        let m0_head: Vec<String> = [
            "scene",
            "fast est. cycles",
            "precise",
            "f32 (soft-float)",
            "f64 (soft-float)",
            "f32 ÷ fast",
            "fast error",
            "f32 error",
            "fast flash B",
            "f32 flash B",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let flash = |p: &str| {
            ms.builds
                .iter()
                .find(|b| b.target == "thumbv6m-none-eabi" && b.profile == p)
                .map_or("–".into(), |b| b.flash_bytes.to_string())
        };
        let err = |s: &str, p: CoreProfile| {
            errors
                .get(&(s.to_string(), p))
                .map_or("–".into(), |e| format!("{e:.3}"))
        };
        let m0_rows = scene_names
            .iter()
            .map(|s| {
                let c = |p: &str| find("thumbv6m-none-eabi", p, s).map(|r| r.frame_cycles());
                vec![
                    s.to_string(),
                    c("fast").map_or("–".into(), m),
                    c("precise").map_or("–".into(), m),
                    c("f32").map_or("–".into(), m),
                    c("f64").map_or("–".into(), m),
                    match (c("f32"), c("fast")) {
                        (Some(a), Some(b)) if b > 0 => format!("{:.1}×", a as f64 / b as f64),
                        _ => "–".into(),
                    },
                    err(s, CoreProfile::Fast),
                    err(s, CoreProfile::F32),
                    flash("fast"),
                    flash("f32"),
                ]
            })
            .collect();

        // Builds.
        let builds = Table {
            head: [
                "target",
                "profile",
                "flash B",
                "code B",
                "rodata B",
                "static RAM B",
                "soft-float routines",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect(),
            rows: ms
                .builds
                .iter()
                .map(|b| {
                    vec![
                        b.target.clone(),
                        b.profile.clone(),
                        b.flash_bytes.to_string(),
                        b.text_bytes.to_string(),
                        b.rodata_bytes.to_string(),
                        b.static_ram_bytes.to_string(),
                        b.softfloat_routines.to_string(),
                    ]
                })
                .collect(),
        };

        // CRCs of the float profiles.
        let mut crc_notes = Vec::new();
        for p in CoreProfile::ALL {
            for t in ["thumbv6m-none-eabi", "thumbv7em-none-eabihf"] {
                let rs: Vec<_> = ms
                    .results
                    .iter()
                    .filter(|r| r.profile == p.name() && r.target == t)
                    .collect();
                if rs.is_empty() {
                    continue;
                }
                let equal = rs.iter().filter(|r| r.crc_equal).count();
                let differ: Vec<String> = rs
                    .iter()
                    .filter(|r| !r.crc_equal)
                    .map(|r| format!("{} (chip {}, host {})", r.scene, r.crc, r.host_crc))
                    .collect();
                crc_notes.push(format!(
                    "{} on {t}: {equal} of {} frames bit-identical to the host's{}{}",
                    p.name(),
                    rs.len(),
                    if p.is_fixed() { " (required)" } else { "" },
                    if differ.is_empty() {
                        String::new()
                    } else {
                        format!("; differ: {}", differ.join(", "))
                    }
                ));
            }
        }

        // Plots per chip.
        let mut plots: Vec<(String, String, String)> = Target::ALL
            .into_iter()
            .map(|t| {
                let cs = &cands[&t];
                let by_cycles: Vec<Point> = cs
                    .iter()
                    .filter_map(|c| point(c, c.cycles as f64))
                    .collect();
                let by_ram: Vec<Point> = cs.iter().filter_map(|c| point(c, c.ram as f64)).collect();
                let title = format!("{} ({})", t.title(), choice.name);
                (
                    title.clone(),
                    scatter_svg(
                        &format!("{title}: error vs cycles"),
                        &format!("{} per frame", unit(t)),
                        "mean error vs ideal Phong (levels)",
                        &by_cycles,
                        |p| p.vs_phong,
                    ),
                    scatter_svg(
                        &format!("{title}: error vs RAM"),
                        "RAM bytes (bands + prepared frame + stack)",
                        "mean error vs ideal Phong (levels)",
                        &by_ram,
                        |p| p.vs_phong,
                    ),
                )
            })
            .collect();
        // Fixed point and soft-float on the M0, side by side (same axes:
        // each plot is drawn on its own, so read the cycle scales).
        {
            let m0 = &cands[&Target::M0];
            let side = |fixed: bool| -> Vec<Point> {
                m0.iter()
                    .filter(|c| c.profile.is_fixed() == fixed)
                    .filter_map(|c| point(c, c.cycles as f64))
                    .collect()
            };
            let t = format!(
                "Cortex-M0: fixed point against soft-float ({})",
                choice.name
            );
            plots.push((
                t,
                scatter_svg(
                    "M0, fixed point (fast, precise, -pc)",
                    "est. M0 cycles per frame",
                    "mean error vs ideal Phong (levels)",
                    &side(true),
                    |p| p.vs_phong,
                ),
                scatter_svg(
                    "M0, soft-float (f32, f64, -pc)",
                    "est. M0 cycles per frame",
                    "mean error vs ideal Phong (levels)",
                    &side(false),
                    |p| p.vs_phong,
                ),
            ));
        }

        Self {
            file: file.to_string(),
            provenance: format!(
                "{}; {}; sources {}; opt-level {}; {} rows per band, {}-bit depth",
                ms.toolchain,
                ms.qemu,
                ms.source_fingerprint,
                ms.opt_level,
                ms.band_rows,
                ms.depth_bits
            ),
            stale,
            scenes: choice.scenes,
            picks: Table {
                head: vec![
                    "part".into(),
                    format!("budget per frame at {TABLE_FPS} fps"),
                    "pick (error vs ideal Phong, cost, fps, RAM)".into(),
                    "runner-up".into(),
                ],
                rows: picks,
            },
            fps: Table {
                head,
                rows: fps_rows,
            },
            m0_float: Table {
                head: m0_head,
                rows: m0_rows,
            },
            builds,
            crc_notes,
            user_ram: None,
            user_measured: None,
            plots,
        }
    }

    /// Adds the table of the user's scenes: per scene, mode and profile,
    /// the RAM it needs (the host's prepared frame, the same bytes as on
    /// the chips, + colour and 16-bit depth band + the largest stack
    /// measured on that chip with that profile) against each part's RAM.
    /// Cycles are not measured for them: the firmware holds the built-in
    /// scenes only.
    pub fn add_user_scenes(&mut self, ms: &Measurements, records: &[super::Record]) {
        let parts: Vec<&'static super::picks::Chip> =
            TABLE_CHIPS.iter().filter_map(|n| find_chip(n)).collect();
        let mut head: Vec<String> = ["scene", "mode", "profile", "prepared + bands B"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        for c in &parts {
            head.push(format!("{} ({:.0} KiB)", c.name, c.ram_kb));
        }
        let stack = |chip: Target, p: &str| {
            ms.of(chip)
                .filter(|r| r.profile == p)
                .map(|r| r.stack)
                .max()
        };
        let rows = records
            .iter()
            .map(|r| {
                let mut row = vec![
                    r.scene.clone(),
                    r.mode.title().to_string(),
                    r.profile.clone(),
                    r.memory.ram_bytes.to_string(),
                ];
                for c in &parts {
                    row.push(match stack(c.target, &r.profile) {
                        Some(st) => {
                            let need = r.memory.ram_bytes as u64 + st;
                            let have = (c.ram_kb * 1024.0) as u64;
                            if need <= have {
                                format!("fits ({need} B)")
                            } else {
                                format!("too big: needs {need} B, {} over", need - have)
                            }
                        }
                        None => "–".into(),
                    });
                }
                row
            })
            .collect();
        self.user_ram = Some(Table { head, rows });
    }

    /// The user's scenes as measured on the chips (`um`: from
    /// [`super::measure::measure_user_scenes`]): one row per scene × mode
    /// × profile × target with the measured figures, and per part of that
    /// target whether its RAM holds the scene (else the bytes it needs)
    /// and the frames per second at its clock.
    pub fn add_user_measured(&mut self, um: &Measurements) {
        let parts: Vec<&'static super::picks::Chip> =
            TABLE_CHIPS.iter().filter_map(|n| find_chip(n)).collect();
        let head: Vec<String> = [
            "scene",
            "mode",
            "profile",
            "target",
            "instructions (geometry + raster)",
            "est. M0 cycles",
            "RAM B",
            "stack B",
            "flash B",
            "CRC = host",
            "on the parts",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let rows = um
            .results
            .iter()
            .map(|r| {
                let on: Vec<String> = parts
                    .iter()
                    .filter(|c| r.chip() == Some(c.target))
                    .map(|c| {
                        let have = (c.ram_kb * 1024.0) as u64;
                        if r.ram <= have {
                            format!(
                                "{}: fits, {:.1} fps at {} MHz",
                                c.name,
                                c.mhz * 1e6 / r.frame_cycles().max(1) as f64,
                                c.mhz
                            )
                        } else {
                            format!(
                                "{}: too big: needs {} B, {} over its {} KiB",
                                c.name,
                                r.ram,
                                r.ram - have,
                                c.ram_kb
                            )
                        }
                    })
                    .collect();
                vec![
                    r.scene.clone(),
                    r.mode.map_or("–".into(), |m| m.title().to_string()),
                    r.profile.clone(),
                    r.target.clone(),
                    format!("{} ({} + {})", r.insns, r.insns_geometry, r.insns_raster),
                    r.cycles.map_or("–".into(), |c| c.to_string()),
                    r.ram.to_string(),
                    r.stack.to_string(),
                    r.flash.to_string(),
                    if r.crc_equal {
                        "yes".into()
                    } else {
                        format!("no ({} / {})", r.crc, r.host_crc)
                    },
                    on.join("; "),
                ]
            })
            .collect();
        self.user_measured = Some(Table { head, rows });
    }

    /// The section's head: picks, plots, fixed against soft-float.
    pub fn html(&self) -> Markup {
        html! {
            h2 id="chips" { "On the chips: picks and costs" }
            @if self.stale {
                p.note { strong { "Stale figures: " } "measured from other sources than this tree's (--allow-stale)." }
            }
            p.note {
                "Chip costs from " code { (self.file) } " (" (self.provenance) "). Instructions counted exactly under QEMU; Cortex-M0 cycles are an estimate (ARM DDI 0432C table 3-1, zero wait states); the Cortex-M4F has no cycle model here: its instruction count stands for cycles (CPI 1, a lower bound). Errors: mean absolute error in 8-bit levels against the ideal Phong frame, on the host (the fixed profiles compute the same bytes on the chips). Configurations: profile × mode, 16-row bands, 16-bit depth. Picks and plots use the scenes " (self.scenes.join(", ")) " (worst case)."
            }
            h3 { "Picks for common parts at " (TABLE_FPS) " fps" }
            (table(&self.picks))
            @for (title, cycles, ram) in &self.plots {
                h3 { (title) }
                div.plots { (PreEscaped(svg_body(cycles))) (PreEscaped(svg_body(ram))) }
            }
            @if let Some(t) = &self.user_measured {
                h3 { "Your scenes on the chips: measured" }
                p.note { "The firmware generated for your scenes (each in every mode, meshes baked into flash, storage sized by the compiler) and run under QEMU (--measure-firmware): instructions counted exactly, Cortex-M0 cycles estimated; RAM = colour band + depth band (none for one convex object with back faces culled) + storage + active-triangle pool + stack, as the firmware reports it. A part too small for a scene says how many bytes it needs." }
                (table(t))
            }
            @if let Some(t) = &self.user_ram {
                h3 { "Your scenes on the parts: RAM" }
                @if self.user_measured.is_none() {
                    p.note { "RAM each of your scenes needs (prepared frame, colour and 16-bit depth band of 16 rows, and the largest stack measured on that chip with that profile) against each part's RAM. Cycles are not measured for your scenes here: run with --measure-firmware to build the firmware for them and measure them under QEMU; the figures above are the built-in scenes'." }
                } @else {
                    p.note { "The host's estimate (prepared frame, bands, the largest stack measured for the built-in scenes), beside the measured figures above." }
                }
                (table(t))
            }
            h3 { "Fixed point against soft-float on the Cortex-M0" }
            (table(&self.m0_float))
            p.note { "Per scene and profile figures: " a href="#chip-tables" { "the chip tables" } ", after the host's." }
        }
    }

    /// The section's long tables (at the end of the page).
    pub fn html_tables(&self) -> Markup {
        html! {
            h2 id="chip-tables" { "On the chips: every scene and profile" }
            h3 { "Frames per second at the parts' clocks" }
            (table(&self.fps))
            h3 { "Flash and static RAM per firmware build" }
            p.note { "Static RAM: the measured firmware's workspace for its largest scene (the bunny) plus the bands." }
            (table(&self.builds))
            h3 { "The chips' frames against the host's" }
            ul { @for n in &self.crc_notes { li { (n) } } }
        }
    }

    /// The section in Markdown.
    pub fn markdown(&self) -> String {
        let mut s = format!(
            "## On the chips: picks and costs\n\nChip costs from `{}` ({}). Cortex-M0 cycles are an estimate (zero wait states); Cortex-M4F: instructions (CPI 1, a lower bound). Errors against the ideal Phong frame, in levels. Picks use {}.\n\n### Picks for common parts at {TABLE_FPS} fps\n\n",
            self.file,
            self.provenance,
            self.scenes.join(", ")
        );
        s += &md(&self.picks);
        if let Some(t) = &self.user_measured {
            s += "\n### Your scenes on the chips: measured\n\nThe firmware generated for your scenes, run under QEMU (--measure-firmware): instructions exact, M0 cycles estimated; RAM = bands + storage + pool + stack as the firmware reports it.\n\n";
            s += &md(t);
        }
        if let Some(t) = &self.user_ram {
            s += "\n### Your scenes on the parts: RAM\n\nPrepared frame + bands + the largest stack measured on the chip with the profile";
            s += if self.user_measured.is_none() {
                "; cycles are not measured for your scenes (run with --measure-firmware to measure them).\n\n"
            } else {
                " (the host's estimate).\n\n"
            };
            s += &md(t);
        }
        s += "\n### Fixed point against soft-float on the Cortex-M0\n\n";
        s += &md(&self.m0_float);
        s += "\n### Frames per second at the parts' clocks\n\n";
        s += &md(&self.fps);
        s += "\n### Flash and static RAM per firmware build\n\n";
        s += &md(&self.builds);
        s += "\n";
        for n in &self.crc_notes {
            s += &format!("- {n}\n");
        }
        s
    }
}

fn svg_body(svg: &str) -> &str {
    svg.find("<svg").map_or(svg, |i| &svg[i..])
}

/// A table as HTML.
pub fn table(t: &Table) -> Markup {
    html! {
        table {
            tr { @for h in &t.head { th { (h) } } }
            @for r in &t.rows { tr { @for c in r { td { (c) } } } }
        }
    }
}

/// A table as Markdown.
pub fn md(t: &Table) -> String {
    let cell = |c: &str| c.replace('|', "\\|");
    let mut s = format!(
        "| {} |\n|{}\n",
        t.head
            .iter()
            .map(|h| cell(h))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(t.head.len())
    );
    for r in &t.rows {
        s += &format!(
            "| {} |\n",
            r.iter().map(|c| cell(c)).collect::<Vec<_>>().join(" | ")
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_escape_by_construction() {
        let t = Table {
            head: vec!["a<b".into()],
            rows: vec![vec!["<script>x</script> & y".into()]],
        };
        let h = table(&t).into_string();
        assert_eq!(
            h,
            "<table><tr><th>a&lt;b</th></tr><tr><td>&lt;script&gt;x&lt;/script&gt; &amp; y</td></tr></table>"
        );
        assert_eq!(md(&t), "| a<b |\n|---|\n| <script>x</script> & y |\n");
    }
}

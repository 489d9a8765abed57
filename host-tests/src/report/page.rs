//! The pages: `index.html` (with the frames in `img/`) and `report.md`.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use maud::{html, Markup, PreEscaped, DOCTYPE};
use std::path::Path;

use super::Error;
use crate::compare::{metrics_of, Comparison};
use crate::core_render::CoreProfile;
use crate::image::write_png;

use super::plot::scatter_svg;
use super::summary::{Aggregate, CostSource, Point, Summary, MODE_TOLERANCE, QUALITY_TOLERANCE};
use super::sweep::{ideal_frame, rgb_frame, SweepScene};
use super::{Mode, Record, ReportData};

/// The frames shown for one scene and mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Frames {
    /// The profile shown.
    pub profile: CoreProfile,
    /// `(caption, path relative to the page)`.
    pub images: Vec<(String, String)>,
}

/// Frames per scene and mode.
pub type FrameIndex = BTreeMap<(String, Mode), Frames>;

/// Renders and writes, for every scene and mode, the representative
/// profile's frame, its twin, the ideal and the two heat-maps into
/// `out/img/`.
pub fn write_frames(
    out: &Path,
    scenes: &[SweepScene],
    summary: &Summary,
) -> Result<FrameIndex, Error> {
    let mut index = FrameIndex::new();
    for s in scenes {
        for mode in Mode::ALL {
            let profile = summary
                .representative
                .get(&mode)
                .copied()
                .unwrap_or(CoreProfile::Fast);
            let desc = s.with_mode(mode);
            let fixed = rgb_frame(&desc, profile)?;
            let float = rgb_frame(&desc, profile.twin())?;
            let ideal = ideal_frame(&desc)?;
            let metrics = metrics_of(&fixed, &float, &ideal)
                .map_err(|e| Error::input(format!("{}: {e}", desc.source)))?;
            let c = Comparison {
                profile,
                fixed,
                float,
                ideal,
                metrics,
            };
            let (w, h) = (c.fixed.width, c.fixed.height);
            let images = [
                (profile.name().to_string(), "fixed", c.fixed.rgb.clone()),
                (
                    format!("{} twin", profile.twin().name()),
                    "twin",
                    c.float.rgb.clone(),
                ),
                ("ideal".to_string(), "ideal", c.ideal.to_rgb8()),
                ("diff vs ideal".to_string(), "diff-ideal", c.diff_vs_ideal()),
                ("diff vs twin".to_string(), "diff-twin", c.diff_vs_float()),
            ];
            let mut list = Vec::new();
            for (caption, kind, rgb) in images {
                let rel = format!("img/{}-{}-{kind}.png", s.name, mode.name());
                let path = out.join(&rel);
                write_png(&path, w, h, &rgb).map_err(|e| Error::write(&path, e))?;
                list.push((caption, rel));
            }
            index.insert(
                (s.name.clone(), mode),
                Frames {
                    profile,
                    images: list,
                },
            );
        }
    }
    Ok(index)
}

fn psnr(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.1}")
    } else {
        "∞".into()
    }
}

fn kib(b: usize) -> String {
    format!("{:.1}", b as f64 / 1024.0)
}

/// Whether `name` is an executable file on `PATH`.
fn on_path(name: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|p| std::env::split_paths(&p).any(|d| d.join(name).is_file()))
}

const RECORD_HEAD: [&str; 19] = [
    "mode",
    "profile",
    "ideal: cov",
    "max",
    "mean",
    "PSNR dB",
    "share>1",
    "twin: cov",
    "max",
    "mean",
    "PSNR dB",
    "share>1",
    "Phong ideal: mean",
    "median ms",
    "runs",
    "Mpx/s",
    "RAM prep. KiB",
    "bands KiB",
    "mesh flash KiB",
];

fn record_row(r: &Record) -> Vec<String> {
    vec![
        r.mode.title().into(),
        r.profile.clone(),
        r.vs_ideal.coverage_mismatch.to_string(),
        r.vs_ideal.max_abs_error.to_string(),
        format!("{:.3}", r.vs_ideal.mean_abs_error),
        psnr(r.vs_ideal.psnr_db),
        format!("{:.4}", r.vs_ideal.share_over_1),
        r.vs_twin.coverage_mismatch.to_string(),
        r.vs_twin.max_abs_error.to_string(),
        format!("{:.4}", r.vs_twin.mean_abs_error),
        psnr(r.vs_twin.psnr_db),
        format!("{:.4}", r.vs_twin.share_over_1),
        format!("{:.3}", r.vs_ideal_phong.mean_abs_error),
        format!("{:.3}", r.host.median_ms),
        r.host.runs.to_string(),
        format!("{:.1}", r.host.pixels_per_s / 1e6),
        kib(r.memory.prepared_bytes),
        kib(r.memory.band_bytes + r.memory.depth_band_bytes),
        kib(r.memory.mesh_flash_bytes),
    ]
}

const AGG_HEAD: [&str; 11] = [
    "mode",
    "profile",
    "ideal: mean",
    "max share>1",
    "twin: mean",
    "max",
    "cov (all)",
    "Phong ideal: mean",
    "host ms (mean)",
    "Mpx/s",
    "RAM max KiB",
];

fn agg_row(a: &Aggregate) -> Vec<String> {
    vec![
        a.mode.title().into(),
        a.profile.name().into(),
        format!("{:.3}", a.vs_ideal_mean),
        format!("{:.4}", a.vs_ideal_share_max),
        format!("{:.4}", a.vs_twin_mean),
        a.vs_twin_max.to_string(),
        a.vs_twin_coverage.to_string(),
        format!("{:.3}", a.vs_phong_mean),
        format!("{:.3}", a.host_ms),
        format!("{:.1}", a.pixels_per_s / 1e6),
        kib(a.ram_max),
    ]
}

fn html_table(head: &[&str], rows: &[Vec<String>]) -> Markup {
    html! {
        table {
            thead { tr { @for h in head { th { (h) } } } }
            tbody {
                @for r in rows {
                    tr {
                        @for (i, c) in r.iter().enumerate() {
                            @if i < 2 { td { (c) } } @else { td.n { (c) } }
                        }
                    }
                }
            }
        }
    }
}

fn md_table(head: &[&str], rows: &[Vec<String>]) -> String {
    let mut s = format!("| {} |\n|", head.join(" | "));
    for i in 0..head.len() {
        s.push_str(if i < 2 { "---|" } else { "---:|" });
    }
    s.push('\n');
    for r in rows {
        let _ = writeln!(s, "| {} |", r.join(" | "));
    }
    s
}

/// What was run, one paragraph.
fn run_text(data: &ReportData) -> String {
    let m = &data.meta;
    let build = if m.debug_build {
        "a debug build (times are several times longer than in a release build: run `cargo run --release -p fixshade-host -- report` for representative host costs)"
    } else {
        "a release build"
    };
    let sweep = if m.quick {
        format!(
            "quick sweep (--quick): {} of the base scenes at half width and height, {} timed runs per record",
            m.scenes.len(),
            m.min_runs
        )
    } else {
        format!(
            "full sweep: every base scene at its own size, at least {} timed runs and {} ms per record",
            m.min_runs, m.min_time_ms
        )
    };
    format!(
        "Measured by `fixshade report` in {build}; {sweep}. {} scenes × {} modes × {} profiles = {} records in {:.1} s.",
        m.scenes.len(),
        m.modes.len(),
        m.profiles.len(),
        data.records.len(),
        m.elapsed_s
    )
}

fn embedded_text(data: &ReportData, summary: &Summary) -> (String, Vec<Vec<String>>) {
    if !data.embedded_available {
        let qemu = if on_path("qemu-system-arm") {
            "qemu-system-arm is installed here: run the firmware example (`.ci/firmware`, see examples/firmware/README.md) and give its results with `--firmware-results FILE`."
        } else {
            "qemu-system-arm is not installed here, so the firmware example cannot count instructions on this machine."
        };
        return (
            format!("Embedded figures are not available: no firmware results were given (`--firmware-results FILE`, `RESULT key=value` lines or JSON). The report does not estimate them, and host time never stands in for a chip: the Cortex-M0 and Cortex-M4F picks have no candidates. {qemu}"),
            Vec::new(),
        );
    }
    let rows = data
        .embedded
        .iter()
        .map(|e| {
            let o = |v: Option<u64>| v.map_or("–".to_string(), |v| v.to_string());
            vec![
                e.target.title().to_string(),
                e.scene.clone(),
                e.profile.clone().unwrap_or_else(|| "–".into()),
                e.mode.map_or("–".into(), |m| m.title().to_string()),
                o(e.insns),
                o(e.cycles),
                o(e.covered),
                o(e.stack),
                o(e.static_ram),
                o(e.flash),
            ]
        })
        .collect();
    let paired: usize = summary
        .embedded_points
        .iter()
        .map(|(_, p, _)| p.len())
        .sum();
    (
        format!(
            "Embedded figures from {} ({} results). {paired} mode × profile combination(s) have a mode and a profile and are plotted against the host sweep's errors (the targets compute the same bytes); results without both are listed only.",
            data.meta.firmware_results.as_deref().unwrap_or("?"),
            data.embedded.len()
        ),
        rows,
    )
}

const EMB_HEAD: [&str; 10] = [
    "target",
    "scene",
    "profile",
    "mode",
    "insns",
    "est. cycles",
    "covered",
    "stack B",
    "static RAM B",
    "flash B",
];

const Y_DESC: &str = "levels (0 drawn at 0.0001)";

/// The plots: per target, error against the ideal, against the twin and
/// against the ideal Phong frame.
fn plots(summary: &Summary) -> Vec<(String, Vec<String>)> {
    let mut out = Vec::new();
    let mut add = |title: String, unit: &str, points: &[Point]| {
        let x = format!("cost ({unit})");
        let svgs = vec![
            scatter_svg("mean abs error vs ideal", &x, Y_DESC, points, |p| {
                p.vs_ideal
            }),
            scatter_svg("mean abs error vs f64 twin", &x, Y_DESC, points, |p| {
                p.vs_twin
            }),
            scatter_svg("mean abs error vs ideal Phong", &x, Y_DESC, points, |p| {
                p.vs_phong
            }),
        ];
        out.push((title, svgs));
    };
    let host = &summary.picks[0];
    add(
        "Host".into(),
        "median ms per frame, mean over scenes",
        &host.points,
    );
    for (target, points, unit) in &summary.embedded_points {
        let scaled: Vec<Point> = points
            .iter()
            .map(|p| Point {
                cost: p.cost / 1e6,
                ..p.clone()
            })
            .collect();
        add(
            target.title().into(),
            &format!("M {unit} per frame"),
            &scaled,
        );
    }
    out
}

const CSS: &str = "body{font:14px/1.45 system-ui,sans-serif;margin:2em auto;max-width:1400px;padding:0 1em;color:#222}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;margin-top:2em}
table{border-collapse:collapse;margin:.6em 0;font-size:12px}th,td{border:1px solid #ddd;padding:2px 6px}
th{background:#f4f4f4}td.n{text-align:right;font-variant-numeric:tabular-nums}
.plots{display:flex;flex-wrap:wrap;gap:8px}.plots svg{border:1px solid #eee}
.frames{display:flex;flex-wrap:wrap;gap:6px}.frames figure{margin:0}
.frames img{image-rendering:pixelated;width:200px;border:1px solid #ccc}
figcaption{font-size:12px;text-align:center}.note{color:#555}.summary li{margin:.4em 0}
";

/// `index.html`: built with `maud`, so every text is escaped by
/// construction; only the SVG plots (drawn by plotters, from numbers and
/// fixed labels) and the constant method text go in unescaped.
pub fn html(data: &ReportData, summary: &Summary, frames: &FrameIndex) -> String {
    let n_picks = summary.picks.len();
    let (picks, findings) = data.summary.split_at(n_picks.min(data.summary.len()));
    let (emb, emb_rows) = embedded_text(data, summary);
    let agg_rows: Vec<Vec<String>> = summary.aggregates.iter().map(agg_row).collect();
    let page = html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                title { "fixshade: accuracy versus speed" }
                style { (PreEscaped(CSS)) }
            }
            body {
                h1 { "fixshade: accuracy versus speed" }
                p.note { (run_text(data)) }
                @if let Some(chips) = &data.chips { (chips.html()) }
                @if let Some(knobs) = &data.knobs { (knobs.html()) }
                @if let Some(tables) = &data.tables { (tables.html()) }
                h2 id="summary" { "Summary" }
                ul.summary { @for line in picks { li { (line) } } }
                h3 { "Where the fixed profiles lose accuracy" }
                ul.summary { @for line in findings { li { (line) } } }
                p.note {
                    "How the picks are made: a pick is the cheapest candidate whose mean error against the ideal Phong frame of each scene is within " (QUALITY_TOLERANCE) " levels of the best candidate's (so the shading mode counts: flat and Gouraud lose highlights); per mode, the cheapest within " (MODE_TOLERANCE) " levels of that mode's best against its own ideal. Errors are in 8-bit levels, means over the scenes."
                }
                h2 id="embedded" { "Embedded figures" }
                p { (emb) }
                @if !emb_rows.is_empty() { (html_table(&EMB_HEAD, &emb_rows)) }
                h2 id="plots" { "Error against cost" }
                p.note { "One point per mode × profile (colour: mode; filled: fixed point, ring: float), errors averaged over the scenes. The black line and rings mark the Pareto front: no other point is both cheaper and more accurate. Against the ideal each mode is compared with the ideal frame of the same mode, so flat shading looks accurate there; against the ideal Phong frame (third plot) the mode's own loss counts too, which is what the picks use. Log scales." }
                @for (title, svgs) in plots(summary) {
                    h3 { (title) }
                    div.plots {
                        @for svg in &svgs {
                            // plotters writes an XML declaration first;
                            // inline SVG does not want it.
                            (PreEscaped(svg.find("<svg").map_or(svg.as_str(), |i| &svg[i..])))
                        }
                    }
                }
                h2 id="modes" { "Per mode and profile, over all scenes" }
                (html_table(&AGG_HEAD, &agg_rows))
                @if let Some(chips) = &data.chips { (chips.html_tables()) }
                h2 id="scenes" { "Scenes" }
                p {
                    @for (i, sc) in data.meta.scenes.iter().enumerate() {
                        @if i > 0 { " · " }
                        a href={ "#s-" (sc.name) } { (sc.name) }
                    }
                }
                p.note { "Heat-maps: black identical, magenta covered in one frame only, otherwise dark purple (1 level) to yellow (255 levels) on a log scale." }
                @for sc in &data.meta.scenes {
                    h3 id={ "s-" (sc.name) } { (sc.name) }
                    p { (sc.description) " (" (sc.width) "×" (sc.height) "; built-in scenes: " (sc.sources.join(", ")) ")" }
                    @for mode in Mode::ALL {
                        @if let Some(f) = frames.get(&(sc.name.clone(), mode)) {
                            p { b { (mode.title()) } " with " (f.profile.name()) ":" }
                            div.frames {
                                @for (caption, path) in &f.images {
                                    figure { img src=(path) alt=(caption); figcaption { (caption) } }
                                }
                            }
                        }
                    }
                    (html_table(&RECORD_HEAD, &data.records.iter().filter(|r| r.scene == sc.name).map(record_row).collect::<Vec<_>>()))
                }
                (PreEscaped(METHOD_HTML))
            }
        }
    };
    page.into_string() + "\n"
}

const METHOD_HTML: &str = "<h2 id=\"method\">Method</h2>\n<ul>
<li>Each built-in scene is rendered with every object's shading set to each mode; scenes equal after that are merged into one base scene.</li>
<li>Errors compare 8-bit RGB frames: <i>vs twin</i> is the same core with f64 (or f64-pc for a -pc profile): quantization alone; <i>vs ideal</i> is the independent f64 reference renderer with the same shading mode: everything (subpixel snapping, affine interpolation, quantization); <i>vs ideal Phong</i> compares with the ideal Phong frame whatever the mode. cov: pixels covered in one frame only; max/mean: absolute channel difference over pixels covered in both; share>1: share of those more than a level off; PSNR over the whole frame.</li>
<li>Host time: one frame = prepare + for each 16-row band clear colour and depth and rasterize, in the scene's pixel format (RGB565), with a workspace allocated once; median over the timed runs after a warm-up run. The timed frame is checked to equal render_core's bytes.</li>
<li>Memory: prepared frame (CoreFrame::prepared_bytes), colour band width × 16 × bytes per pixel, depth band width × 16 × 2; mesh flash: positions, triangles, normals and normal indices at 6 bytes each, distinct meshes.</li>
<li>Not measured: instructions per frame on the host (valgrind), and embedded figures unless given by a firmware results file.</li>
</ul>\n";

/// `report.md`.
pub fn markdown(data: &ReportData, summary: &Summary) -> String {
    let mut s = format!(
        "# fixshade: accuracy versus speed\n\n{}\n\n",
        run_text(data)
    );
    if let Some(chips) = &data.chips {
        s.push_str(&chips.markdown());
        s.push('\n');
    }
    if let Some(knobs) = &data.knobs {
        s.push_str(&knobs.markdown());
        s.push('\n');
    }
    if let Some(tables) = &data.tables {
        s.push_str(&tables.markdown());
        s.push('\n');
    }
    s.push_str("## Summary\n\n");
    for (i, line) in data.summary.iter().enumerate() {
        if i == summary.picks.len() {
            s.push_str("\n### Where the fixed profiles lose accuracy\n\n");
        }
        let _ = writeln!(s, "- {line}");
    }
    let (emb, rows) = embedded_text(data, summary);
    let _ = write!(s, "\n## Embedded figures\n\n{emb}\n\n");
    if !rows.is_empty() {
        s.push_str(&md_table(&EMB_HEAD, &rows));
        s.push('\n');
    }
    s.push_str("## Per mode and profile, over all scenes\n\n");
    let rows: Vec<Vec<String>> = summary.aggregates.iter().map(agg_row).collect();
    s.push_str(&md_table(&AGG_HEAD, &rows));
    s.push_str("\n## Scenes\n");
    for sc in &data.meta.scenes {
        let _ = write!(
            s,
            "\n### {}\n\n{} ({}×{}; built-in scenes: {})\n\n",
            sc.name,
            sc.description,
            sc.width,
            sc.height,
            sc.sources.join(", ")
        );
        let rows: Vec<Vec<String>> = data
            .records
            .iter()
            .filter(|r| r.scene == sc.name)
            .map(record_row)
            .collect();
        s.push_str(&md_table(&RECORD_HEAD, &rows));
    }
    let source = summary
        .picks
        .iter()
        .any(|p| p.source == CostSource::HostProxy);
    if source {
        s.push_str("\nCosts for the Cortex-M0 and Cortex-M4F picks are host times standing in for embedded figures.\n");
    }
    s
}

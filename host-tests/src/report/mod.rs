//! The accuracy-versus-speed report (`fixshade report`).
//!
//! [`run_report`] sweeps the built-in scenes × shading modes × profiles,
//! measures for every combination the error against the f64 twin and the
//! ideal reference, the host time per frame and the memory, reads the
//! embedded figures when a firmware results file is given, and writes
//! into the output folder:
//!
//! * `index.html`: one page (inline CSS and SVG; the frames are PNGs in
//!   `img/` beside it, referenced relatively; no network): a summary
//!   derived from the figures, the plots of error against cost with the
//!   Pareto front per target, the tables, and per scene the frames side by
//!   side;
//! * `report.md`: the summary and the tables in Markdown;
//! * `results.json`: every figure, one record per scene × mode × profile
//!   ([`ReportData`]).
//!
//! # The sweep
//!
//! Every object of a built-in scene gets each shading mode in turn
//! ([`Mode`]). Scenes that become identical once the shading is
//! overridden (`dodeca-phong-n100` and `dodeca-gouraud-n100`) are one
//! *base scene*, named after the built-in name without its shading word
//! (`dodeca-n100`), see [`sweep_scenes`]. So there is one record per base
//! scene, mode and profile.
//!
//! `--quick` sweeps [`QUICK_SCENES`] at half the width and height with
//! [`Repeats::QUICK`] timed runs; the page says so.
//!
//! # Errors and files
//!
//! The output folder is created and checked for writing before any work
//! (an I/O error, exit status 1), and a firmware results file is read and
//! checked first too (bad input, exit status 2). Every file is written to
//! a temporary name and renamed, `index.html` last: an interrupted run
//! leaves no half-written page.

mod chip_section;
pub mod chips;
pub mod docs_tables;
mod embedded;
mod error;
mod knob_section;
pub mod measure;
mod page;
pub mod picks;
mod plot;
mod summary;
mod sweep;
pub mod table_sweep;
mod timing;

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::ideal::Shading;
use crate::metrics::Metrics;
use crate::output::write_atomically;

pub use chip_section::{ChipSection, Table};
pub use embedded::{parse_firmware_results, read_firmware_results, EmbeddedResult, Target};
pub use error::Error;
pub use knob_section::KnobSection;
pub use plot::pareto_front;
pub use summary::{
    aggregate, Aggregate, CostSource, Pick, Point, Summary, MODE_TOLERANCE, QUALITY_TOLERANCE,
};
pub use sweep::{sweep_scenes, SweepScene, QUICK_SCENES};
pub use timing::{time_frames, Repeats, Timing};

/// A shading mode every object of a scene is given.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// One colour per triangle.
    Flat,
    /// Colours at the vertices, interpolated.
    Gouraud,
    /// Normals interpolated, lit per pixel.
    Phong,
}

impl Mode {
    /// Every mode, cheapest first.
    pub const ALL: [Self; 3] = [Self::Flat, Self::Gouraud, Self::Phong];

    /// Its name (`flat`, `gouraud`, `phong`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Flat => "flat",
            Self::Gouraud => "gouraud",
            Self::Phong => "phong",
        }
    }

    /// Its name for people.
    pub fn title(self) -> &'static str {
        match self {
            Self::Flat => "flat",
            Self::Gouraud => "Gouraud",
            Self::Phong => "Phong",
        }
    }

    /// The mode called `name` (any case).
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(name))
    }

    /// The scene file's shading.
    pub fn shading(self) -> Shading {
        match self {
            Self::Flat => Shading::Flat,
            Self::Gouraud => Shading::Gouraud,
            Self::Phong => Shading::Phong,
        }
    }
}

/// What to run and where to write.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReportOptions {
    /// The output folder (created if missing).
    pub out: PathBuf,
    /// The short sweep (see the [module docs](self#the-sweep)).
    pub quick: bool,
    /// The firmware's results (see [`read_firmware_results`]).
    pub firmware_results: Option<PathBuf>,
    /// Draw a progress bar on stderr (never drawn when stderr is not a
    /// terminal).
    pub progress: bool,
    /// The chip measurements (default: [`chips::DEFAULT_PATH`] of the
    /// checkout).
    pub measurements: Option<PathBuf>,
    /// Use measurements from other sources (the page says they are
    /// stale).
    pub allow_stale: bool,
    /// Re-measure the firmware under QEMU instead of reading the file;
    /// with scene files, measure the firmware generated for them (the
    /// built-in scenes' figures are then read from the file).
    pub measure_firmware: bool,
    /// The profiles `measure_firmware` measures (all when empty).
    pub firmware_profiles: Vec<crate::core_render::CoreProfile>,
    /// The user's scene files to sweep instead of the built-in scenes.
    pub scene_files: Vec<PathBuf>,
}

/// Host cost of one record.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HostCost {
    /// Timed runs.
    pub runs: u32,
    /// Median time per frame, milliseconds.
    pub median_ms: f64,
    /// Fastest run, milliseconds.
    pub min_ms: f64,
    /// Slowest run, milliseconds.
    pub max_ms: f64,
    /// Pixels shaded per frame (depth-test passes).
    pub pixels_shaded: u32,
    /// Pixels shaded per second at the median time.
    pub pixels_per_s: f64,
}

/// Memory of one record, bytes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Memory {
    /// RAM of the prepared frame (`CoreFrame::prepared_bytes`).
    pub prepared_bytes: usize,
    /// RAM of the colour band: width × 16 rows × bytes per pixel.
    pub band_bytes: usize,
    /// RAM of the 16-bit depth band: width × 16 rows × 2.
    pub depth_band_bytes: usize,
    /// The three together.
    pub ram_bytes: usize,
    /// Flash for the meshes' positions (6 bytes each).
    pub positions_bytes: usize,
    /// Flash for the meshes' triangles (6 bytes each).
    pub triangles_bytes: usize,
    /// Flash for the meshes' normals and per-corner normal indices (6
    /// bytes each).
    pub normals_bytes: usize,
    /// The three together.
    pub mesh_flash_bytes: usize,
}

/// Where a profile's frame departs from its twin's.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ErrorPlaces {
    /// Pixels covered differently or more than one level off.
    pub pixels: u64,
    /// ...of which on a silhouette: covered differently, or next to
    /// (4-neighbour) a pixel that one of the two frames does not cover, or
    /// at the frame's border.
    pub at_silhouette: u64,
    /// ...of which, not on a silhouette, at an edge of the twin's image:
    /// its colour steps by more than 8 levels to a 4-neighbour (occluding
    /// contours inside the object, flat-shaded triangle edges).
    pub at_edge: u64,
}

/// One scene × mode × profile.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// The base scene.
    pub scene: String,
    /// The shading mode every object was given.
    pub mode: Mode,
    /// The profile's name.
    pub profile: String,
    /// Whether the profile is fixed point.
    pub fixed_point: bool,
    /// Whether it interpolates perspective-correctly.
    pub perspective_correct: bool,
    /// Its float twin.
    pub twin: String,
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// Mesh triangles in the scene.
    pub triangles: usize,
    /// Largest specular exponent of the scene's materials.
    pub shininess: f64,
    /// The first base scene that differs from this one at most in its
    /// materials' shininess (the scene itself if none).
    pub shininess_family: String,
    /// Against the ideal reference of the same mode (everything).
    pub vs_ideal: Metrics,
    /// Against the f64 twin (quantization alone).
    pub vs_twin: Metrics,
    /// Against the ideal Phong frame of the scene: how far the mode and
    /// the profile together are from the best shading.
    pub vs_ideal_phong: Metrics,
    /// Where the frame departs from the twin's.
    pub places_vs_twin: ErrorPlaces,
    /// Host cost.
    pub host: HostCost,
    /// Memory.
    pub memory: Memory,
}

/// About a run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Meta {
    /// `--quick`.
    pub quick: bool,
    /// Whether the `fixshade` binary was a debug build.
    pub debug_build: bool,
    /// Frame size divisor (2 in a quick run).
    pub frame_divisor: u32,
    /// Timed runs per record: at least this many...
    pub min_runs: u32,
    /// ...and at least this many milliseconds.
    pub min_time_ms: u64,
    /// The base scenes with the built-in scenes they stand for.
    pub scenes: Vec<SceneInfo>,
    /// The modes.
    pub modes: Vec<Mode>,
    /// The profiles.
    pub profiles: Vec<String>,
    /// The firmware results file, if given.
    pub firmware_results: Option<String>,
    /// Seconds the sweep took.
    pub elapsed_s: f64,
}

/// A base scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneInfo {
    /// Its name.
    pub name: String,
    /// The built-in scenes it stands for.
    pub sources: Vec<String>,
    /// The first one's description.
    pub description: String,
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
}

/// `results.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReportData {
    /// About the run.
    pub meta: Meta,
    /// One per scene × mode × profile.
    pub records: Vec<Record>,
    /// The firmware's figures as read (empty without a file).
    pub embedded: Vec<EmbeddedResult>,
    /// Whether there are embedded figures (`false`: not available, none
    /// are estimated).
    pub embedded_available: bool,
    /// The summary, as on the page.
    pub summary: Vec<String>,
    /// The chip section (picks, costs per profile on the chips).
    pub chips: Option<ChipSection>,
    /// The knob sweeps (when the measurements have them).
    pub knobs: Option<KnobSection>,
    /// The Phong kernel's table-size sweep ([`table_sweep`]).
    #[serde(default)]
    pub tables: Option<table_sweep::TableSweep>,
}

/// What a run wrote.
#[derive(Clone, Debug, PartialEq)]
pub struct ReportOutput {
    /// Everything in `results.json`.
    pub data: ReportData,
    /// The pages written.
    pub files: Vec<PathBuf>,
}

/// Creates `out` (and `out/img`) and checks that files can be written
/// there, by writing and removing a probe file.
///
/// # Errors
/// [`Error::Write`] naming the folder.
pub fn prepare_out_dir(out: &Path) -> Result<(), Error> {
    let img = out.join("img");
    std::fs::create_dir_all(&img).map_err(|e| Error::write(out, e))?;
    for dir in [out, img.as_path()] {
        let probe = dir.join(format!(".fixshade-report-probe-{}", std::process::id()));
        std::fs::write(&probe, b"probe").map_err(|e| Error::write(dir, e))?;
        std::fs::remove_file(&probe).map_err(|e| Error::write(dir, e))?;
    }
    Ok(())
}

/// The chip measurements of a run: re-measured (`--measure-firmware`),
/// or read from the file and checked to be fresh (unless allowed stale).
/// Returns them, the file's name and whether they are stale.
fn chip_measurements(opts: &ReportOptions) -> Result<(chips::Measurements, String, bool), Error> {
    let root = chips::repo_root();
    if opts.measure_firmware && opts.scene_files.is_empty() {
        let ms = measure::measure_firmware(&measure::MeasureOptions {
            root,
            profiles: firmware_profiles(opts),
            progress: opts.progress,
        })?;
        return Ok((ms, "a fresh measurement (--measure-firmware)".into(), false));
    }
    let path = opts
        .measurements
        .clone()
        .unwrap_or_else(|| root.join(chips::DEFAULT_PATH));
    let file = path.display().to_string();
    let ms = chips::load(&path)?;
    let stale = match chips::check_fresh(&ms, &root, &file) {
        Ok(()) => false,
        Err(_) if opts.allow_stale => true,
        Err(e) => return Err(e),
    };
    Ok((ms, file, stale))
}

fn firmware_profiles(opts: &ReportOptions) -> Vec<crate::core_render::CoreProfile> {
    if opts.firmware_profiles.is_empty() {
        crate::core_render::CoreProfile::ALL.to_vec()
    } else {
        opts.firmware_profiles.clone()
    }
}

/// Runs the sweep and writes the report (see the [module docs](self)).
///
/// # Errors
/// [`Error::Write`] for an unwritable output folder or a failed write;
/// [`Error::Input`] or [`Error::Scene`] for a bad firmware results or
/// measurements file or a scene the renderers refuse; with
/// `--measure-firmware`, as [`measure::measure_firmware`]. Checked before
/// the sweep starts, except failures while writing.
pub fn run_report(opts: &ReportOptions) -> Result<ReportOutput, Error> {
    let started = Instant::now();
    let (ms, ms_file, stale) = chip_measurements(opts)?;
    let embedded = match &opts.firmware_results {
        Some(path) => read_firmware_results(path)?,
        None => {
            let text = serde_json::to_string(&ms).unwrap_or_default();
            parse_firmware_results(&text, &ms_file)?
        }
    };
    // Bad scene files are bad input before any output.
    if !opts.scene_files.is_empty() {
        sweep::scene_files(&opts.scene_files)?;
    }
    prepare_out_dir(&opts.out)?;
    // The user's scenes on the chips: measured before the sweep, so a
    // scene the firmware cannot hold or a failed build writes nothing.
    let user_measured = if opts.measure_firmware && !opts.scene_files.is_empty() {
        Some(measure::measure_user_scenes(
            &measure::UserMeasureOptions {
                root: chips::repo_root(),
                files: opts.scene_files.clone(),
                profiles: firmware_profiles(opts),
                targets: measure::TARGETS.iter().map(|t| t.0.to_string()).collect(),
                progress: opts.progress,
            },
        )?)
    } else {
        None
    };
    let fw_scenes: Vec<String> = {
        let mut v: Vec<String> = Vec::new();
        for r in &ms.results {
            if !v.contains(&r.scene) {
                v.push(r.scene.clone());
            }
        }
        v
    };
    let errors = picks::host_errors(&fw_scenes, &crate::core_render::CoreProfile::ALL)?;
    let mut chips = ChipSection::new(&ms, &ms_file, stale, &errors);
    let knobs = KnobSection::new(&ms)?;
    let scenes = if opts.scene_files.is_empty() {
        sweep_scenes(opts.quick)?
    } else {
        sweep::scene_files(&opts.scene_files)?
    };
    let repeats = if opts.quick {
        Repeats::QUICK
    } else {
        Repeats::FULL
    };
    let records = sweep::measure(&scenes, repeats, opts.progress)?;
    if !opts.scene_files.is_empty() {
        chips.add_user_scenes(&ms, &records);
    }
    if let Some(um) = &user_measured {
        chips.add_user_measured(um);
    }
    let elapsed_s = started.elapsed().as_secs_f64();
    let summary = Summary::new(&records, &embedded);
    let meta = Meta {
        quick: opts.quick,
        debug_build: cfg!(debug_assertions),
        frame_divisor: if opts.quick && opts.scene_files.is_empty() {
            2
        } else {
            1
        },
        min_runs: repeats.min_runs,
        min_time_ms: u64::try_from(repeats.min_time.as_millis()).unwrap_or(u64::MAX),
        scenes: scenes.iter().map(SweepScene::info).collect(),
        modes: Mode::ALL.to_vec(),
        profiles: crate::core_render::CoreProfile::ALL
            .iter()
            .map(|p| p.name().to_string())
            .collect(),
        firmware_results: opts
            .firmware_results
            .as_ref()
            .map(|p| p.display().to_string()),
        elapsed_s,
    };
    let data = ReportData {
        meta,
        records,
        embedded_available: !embedded.is_empty(),
        embedded,
        summary: summary.lines(),
        chips: Some(chips),
        knobs,
        tables: Some(table_sweep::TableSweep::run()),
    };

    // Frames of the representative profiles, then the three pages,
    // `index.html` last.
    let frames = page::write_frames(&opts.out, &scenes, &summary)?;
    let json = serde_json::to_string_pretty(&data)
        .map_err(|e| Error::write(&opts.out.join("results.json"), std::io::Error::other(e)))?;
    let mut files = Vec::new();
    let mut write = |name: &str, text: &str| -> Result<(), Error> {
        let path = opts.out.join(name);
        write_atomically(&path, |out| out.write_all(text.as_bytes()))
            .map_err(|e| Error::write(&path, e))?;
        files.push(path);
        Ok(())
    };
    write("results.json", &json)?;
    write("report.md", &page::markdown(&data, &summary))?;
    write("index.html", &page::html(&data, &summary, &frames))?;
    Ok(ReportOutput { data, files })
}

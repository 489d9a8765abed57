//! The sweep: base scenes × modes × profiles, measured.

use std::collections::BTreeSet;
use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressStyle};

use super::Error;
use crate::builtin::{builtin_scenes, load_builtin};
use crate::compare::{core_view, ideal_view, metrics_of};
use crate::core_render::{render_core, CoreFrame, CoreProfile, BAND_ROWS};
use crate::ideal::{self, IdealFrame};
use crate::metrics::compare;
use crate::scene_file::{PixelFormat, SceneDesc};

use super::timing::{time_frames, Repeats};
use super::{ErrorPlaces, HostCost, Memory, Mode, Record, SceneInfo};

/// The base scenes of `--quick`: high shininess, perspective on a bent
/// grid, and the bunny's many small triangles and silhouettes.
pub const QUICK_SCENES: [&str; 3] = ["dodeca-n800", "grid-hotspot", "bunny"];

/// Words of a built-in scene's name that only name its shading.
const SHADING_WORDS: [&str; 4] = ["flat", "gouraud", "phong", "smooth"];

/// A base scene of the sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepScene {
    /// Its name: the built-in name without its shading word.
    pub name: String,
    /// The built-in scenes it stands for (equal once the shading is
    /// overridden).
    pub sources: Vec<String>,
    /// The first one's description.
    pub description: String,
    /// The scene (its objects' shading is overridden per mode).
    pub desc: SceneDesc,
    /// The first base scene that differs from this one at most in its
    /// materials' shininess (itself if none).
    pub family: String,
}

impl SweepScene {
    /// The scene with every object shaded in `mode`.
    pub fn with_mode(&self, mode: Mode) -> SceneDesc {
        let mut d = self.desc.clone();
        for o in &mut d.objects {
            o.shading = mode.shading();
        }
        d
    }

    /// For `results.json`.
    pub fn info(&self) -> SceneInfo {
        SceneInfo {
            name: self.name.clone(),
            sources: self.sources.clone(),
            description: self.description.clone(),
            width: self.desc.width,
            height: self.desc.height,
        }
    }
}

/// `name` without the words that only name a shading.
pub(crate) fn base_name(name: &str) -> String {
    let kept: Vec<&str> = name
        .split('-')
        .filter(|w| !SHADING_WORDS.contains(w))
        .collect();
    if kept.is_empty() {
        name.to_string()
    } else {
        kept.join("-")
    }
}

/// The user's scene files (TOML, or OBJ meshes through their scene
/// files) as base scenes, named by their file stems (`-2`, `-3`, ... for
/// repeated stems), every object's shading overridden per mode as for
/// the built-ins, at their own size (also with `--quick`: the RAM they
/// need is the point).
///
/// # Errors
/// A file that does not load (bad input naming the file and field).
pub fn scene_files(paths: &[std::path::PathBuf]) -> Result<Vec<SweepScene>, Error> {
    let mut out: Vec<SweepScene> = Vec::new();
    for path in paths {
        let mut desc = SceneDesc::load(path)?;
        let stem = path
            .file_stem()
            .map_or_else(|| "scene".to_string(), |s| s.to_string_lossy().into_owned());
        let mut name = stem.clone();
        let mut k = 2;
        while out.iter().any(|s| s.name == name) {
            name = format!("{stem}-{k}");
            k += 1;
        }
        desc.source = path.display().to_string();
        out.push(SweepScene {
            family: name.clone(),
            name,
            sources: vec![path.display().to_string()],
            description: format!("your scene {}", path.display()),
            desc,
        });
    }
    Ok(out)
}

/// The base scenes: the built-in scenes with their shading overridden,
/// equal ones merged (in built-in order), named by the first one's name
/// without its shading words `flat`, `gouraud`, `phong`, `smooth` (the
/// built-in name itself when two different scenes would share a name).
/// `quick` keeps [`QUICK_SCENES`] and halves the frame size.
///
/// # Errors
/// A built-in scene that does not load (a bug: bad input).
pub fn sweep_scenes(quick: bool) -> Result<Vec<SweepScene>, Error> {
    let mut groups: Vec<(SceneDesc, Vec<String>, String)> = Vec::new();
    for &(name, description, _) in builtin_scenes() {
        let mut d = load_builtin(name)?;
        // Only the geometry, lights and materials decide.
        d.source = String::new();
        d.profile = Default::default();
        for o in &mut d.objects {
            o.shading = Mode::Flat.shading();
        }
        match groups.iter_mut().find(|(g, _, _)| *g == d) {
            Some((_, names, _)) => names.push(name.to_string()),
            None => groups.push((d, vec![name.to_string()], description.to_string())),
        }
    }
    let bases: Vec<String> = groups.iter().map(|(_, n, _)| base_name(&n[0])).collect();
    let mut scenes = Vec::new();
    for (i, (mut desc, sources, description)) in groups.into_iter().enumerate() {
        let unique = bases.iter().filter(|b| **b == bases[i]).count() == 1;
        let name = if unique {
            bases[i].clone()
        } else {
            sources[0].clone()
        };
        if quick && !QUICK_SCENES.contains(&name.as_str()) {
            continue;
        }
        desc.source = format!("sweep:{name}");
        if quick {
            desc.width = (desc.width / 2).max(16);
            desc.height = (desc.height / 2).max(16);
        }
        scenes.push(SweepScene {
            family: name.clone(),
            name,
            sources,
            description,
            desc,
        });
    }
    let without_shininess = |d: &SceneDesc| {
        let mut d = SceneDesc {
            source: String::new(),
            ..d.clone()
        };
        for o in &mut d.objects {
            o.material.shininess = 0.0;
        }
        d
    };
    for i in 0..scenes.len() {
        let key = without_shininess(&scenes[i].desc);
        if let Some(first) = scenes[..i]
            .iter()
            .find(|s| without_shininess(&s.desc) == key)
        {
            scenes[i].family = first.family.clone();
        }
    }
    Ok(scenes)
}

/// Bytes per pixel of a pixel format.
fn pixel_bytes(f: PixelFormat) -> usize {
    match f {
        PixelFormat::Gray8 => 1,
        PixelFormat::Rgb565 => 2,
        PixelFormat::Rgb888 => 3,
    }
}

/// Flash of the scene's distinct meshes: (positions, triangles, normals
/// with their indices), 6 bytes per entry.
fn mesh_flash(desc: &SceneDesc) -> (usize, usize, usize) {
    let mut seen = BTreeSet::new();
    let (mut p, mut t, mut n) = (0, 0, 0);
    for o in &desc.objects {
        if !seen.insert(o.mesh.name().to_string()) {
            continue;
        }
        let m = o.mesh.mesh();
        p += m.vertex_count() * 6;
        t += m.triangle_count() * 6;
        if let Some(c) = m.normals() {
            n += c.normals.len() * 6 + c.indices.len() * 6;
        }
    }
    (p, t, n)
}

/// A colour step in the twin larger than this (levels, any channel) to a
/// 4-neighbour makes a pixel an edge pixel.
pub const EDGE_STEP: u8 = 8;

/// Pixels where `a` departs from `b` (covered differently, or more than
/// one level off), and where they lie: on a silhouette, at an edge in
/// `b`, or in a smooth area.
pub(super) fn error_places(a: &CoreFrame, b: &CoreFrame) -> ErrorPlaces {
    let (w, h) = (a.width as usize, a.height as usize);
    let at = |x: isize, y: isize| {
        (x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h)
            .then(|| y as usize * w + x as usize)
    };
    let mut places = ErrorPlaces {
        pixels: 0,
        at_silhouette: 0,
        at_edge: 0,
    };
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let bad = a.covered[i] != b.covered[i]
                || (a.covered[i] && (0..3).any(|c| a.rgb[i][c].abs_diff(b.rgb[i][c]) > 1));
            if !bad {
                continue;
            }
            places.pixels += 1;
            let (x, y) = (x as isize, y as isize);
            let near = [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)].map(|(u, v)| at(u, v));
            let silhouette = a.covered[i] != b.covered[i]
                || near
                    .iter()
                    .any(|n| n.is_none_or(|j| !a.covered[j] || !b.covered[j]));
            if silhouette {
                places.at_silhouette += 1;
            } else if near
                .iter()
                .flatten()
                .any(|&j| (0..3).any(|c| b.rgb[i][c].abs_diff(b.rgb[j][c]) > EDGE_STEP))
            {
                places.at_edge += 1;
            }
        }
    }
    places
}

/// The frame of `desc` (in RGB888 for the metrics) with `profile`.
pub(super) fn rgb_frame(desc: &SceneDesc, profile: CoreProfile) -> Result<CoreFrame, Error> {
    let d = SceneDesc {
        pixel_format: PixelFormat::Rgb888,
        ..desc.clone()
    };
    render_core(&d, Some(profile)).map_err(|e| Error::input(format!("{}: {e}", d.source)))
}

/// The ideal frame of `desc`.
pub(super) fn ideal_frame(desc: &SceneDesc) -> Result<IdealFrame, Error> {
    ideal::render(&desc.to_ideal())
        .map_err(|e| Error::input(format!("{}: ideal reference: {e}", desc.source)))
}

fn progress_bar(total: u64, show: bool) -> ProgressBar {
    if !show || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:32}] {pos}/{len} {msg} (eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar
}

/// Measures every scene × mode × profile, in that order.
///
/// # Errors
/// A scene a renderer refuses (bad input), or a timed frame that differs
/// from `render_core`'s (a bug, reported as bad input with the scene).
pub fn measure(
    scenes: &[SweepScene],
    repeats: Repeats,
    progress: bool,
) -> Result<Vec<Record>, Error> {
    use rayon::prelude::*;
    let total = (scenes.len() * Mode::ALL.len() * CoreProfile::ALL.len()) as u64;
    let bar = progress_bar(total, progress);
    // One task per scene on every core; the records come back in scene
    // order, so the output is the same whatever the scheduling (host
    // times aside: frames timed side by side share the machine).
    let per_scene: Vec<Vec<Record>> = scenes
        .par_iter()
        .map(|s| measure_scene(s, repeats, &bar))
        .collect::<Result<_, Error>>()?;
    bar.finish_and_clear();
    Ok(per_scene.into_iter().flatten().collect())
}

/// The records of one scene, mode then profile order.
fn measure_scene(
    s: &SweepScene,
    repeats: Repeats,
    bar: &ProgressBar,
) -> Result<Vec<Record>, Error> {
    let mut records = Vec::new();
    {
        let phong_ideal = ideal_frame(&s.with_mode(Mode::Phong))?;
        let phong_rgb = phong_ideal.to_rgb8();
        let (p, t, n) = mesh_flash(&s.desc);
        let shininess = s
            .desc
            .objects
            .iter()
            .map(|o| o.material.shininess)
            .fold(0.0, f64::max);
        for mode in Mode::ALL {
            let desc = s.with_mode(mode);
            let ideal = if mode == Mode::Phong {
                phong_ideal.clone()
            } else {
                ideal_frame(&desc)?
            };
            let twins = [
                rgb_frame(&desc, CoreProfile::F64)?,
                rgb_frame(&desc, CoreProfile::F64Pc)?,
            ];
            for profile in CoreProfile::ALL {
                bar.set_message(format!("{} {} {}", s.name, mode.name(), profile.name()));
                let twin = &twins[usize::from(profile.perspective())];
                let fixed = if profile.twin() == profile {
                    twin.clone()
                } else {
                    rgb_frame(&desc, profile)?
                };
                let metrics = metrics_of(&fixed, twin, &ideal)
                    .map_err(|e| Error::input(format!("{}: {e}", desc.source)))?;
                let vs_ideal_phong =
                    compare(&core_view(&fixed), &ideal_view(&phong_ideal, &phong_rgb))
                        .map_err(|e| Error::input(format!("{}: {e}", desc.source)))?;
                let timing = time_frames(&desc, profile, repeats)
                    .map_err(|e| Error::input(format!("{}: {e}", desc.source)))?;
                let reference = render_core(&desc, Some(profile))
                    .map_err(|e| Error::input(format!("{}: {e}", desc.source)))?;
                if reference.bytes != timing.bytes {
                    return Err(Error::input(format!(
                        "{} {} {}: the timed frame differs from render_core's (report bug)",
                        s.name,
                        mode.name(),
                        profile.name()
                    )));
                }
                let ms = |ns: u64| ns as f64 / 1e6;
                let median = timing.median_ns();
                let w = desc.width as usize;
                let band_bytes = w * BAND_ROWS as usize * pixel_bytes(desc.pixel_format);
                let depth_band_bytes = w * BAND_ROWS as usize * 2;
                records.push(Record {
                    scene: s.name.clone(),
                    mode,
                    profile: profile.name().to_string(),
                    fixed_point: profile.is_fixed(),
                    perspective_correct: profile.perspective(),
                    twin: profile.twin().name().to_string(),
                    width: desc.width,
                    height: desc.height,
                    triangles: t / 6,
                    shininess,
                    shininess_family: s.family.clone(),
                    vs_ideal: metrics.vs_ideal,
                    vs_twin: metrics.vs_float,
                    vs_ideal_phong,
                    places_vs_twin: error_places(&fixed, twin),
                    host: HostCost {
                        runs: u32::try_from(timing.runs_ns.len()).unwrap_or(u32::MAX),
                        median_ms: ms(median),
                        min_ms: ms(timing.runs_ns.first().copied().unwrap_or(0)),
                        max_ms: ms(timing.runs_ns.last().copied().unwrap_or(0)),
                        pixels_shaded: timing.pixels_drawn,
                        pixels_per_s: if median == 0 {
                            0.0
                        } else {
                            f64::from(timing.pixels_drawn) / (median as f64 / 1e9)
                        },
                    },
                    memory: Memory {
                        prepared_bytes: fixed.prepared_bytes,
                        band_bytes,
                        depth_band_bytes,
                        ram_bytes: fixed.prepared_bytes + band_bytes + depth_band_bytes,
                        positions_bytes: p,
                        triangles_bytes: t,
                        normals_bytes: n,
                        mesh_flash_bytes: p + t + n,
                    },
                });
                bar.inc(1);
            }
        }
    }
    Ok(records)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base_names_drop_the_shading_word() {
        assert_eq!(base_name("dodeca-phong-n100"), "dodeca-n100");
        assert_eq!(base_name("dodeca-gouraud-n100"), "dodeca-n100");
        assert_eq!(base_name("can-smooth"), "can");
        assert_eq!(base_name("cubes-and-sphere"), "cubes-and-sphere");
        assert_eq!(base_name("phong"), "phong");
    }

    #[test]
    fn scenes_differing_only_by_shading_are_merged() {
        let scenes = sweep_scenes(false).unwrap();
        let find = |n: &str| scenes.iter().find(|s| s.name == n).unwrap();
        assert_eq!(
            find("dodeca-n100").sources,
            [
                "dodeca-phong-n100",
                "dodeca-gouraud-n100",
                "dodeca-flat-n100"
            ]
        );
        assert_eq!(find("bunny").sources, ["bunny-gouraud", "bunny-flat"]);
        assert_eq!(
            find("grid-hotspot").sources,
            ["grid-hotspot-gouraud", "grid-hotspot-phong"]
        );
        // Every built-in scene is in exactly one base scene; names unique.
        let sources: usize = scenes.iter().map(|s| s.sources.len()).sum();
        assert_eq!(sources, builtin_scenes().len());
        let names: BTreeSet<&str> = scenes.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names.len(), scenes.len());
        let quick = sweep_scenes(true).unwrap();
        let quick_names: Vec<&str> = quick.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(quick_names, QUICK_SCENES);
        assert_eq!(quick[2].desc.width * 2, find("bunny").desc.width);
        // The dodecahedra under the same light differ only in shininess.
        for n in [
            "dodeca-n1",
            "dodeca-n10",
            "dodeca-n25",
            "dodeca-n100",
            "dodeca-n800",
        ] {
            assert_eq!(find(n).family, "dodeca-n1", "{n}");
        }
        assert_eq!(find("dodeca-light-2-2-2").family, "dodeca-light-2-2-2");
        assert_eq!(find("bunny").family, "bunny");
    }

    #[test]
    fn the_parallel_sweep_is_deterministic_but_for_host_times() {
        let scenes = sweep_scenes(true).unwrap();
        let once = Repeats {
            min_runs: 1,
            min_time: std::time::Duration::ZERO,
            max_runs: 1,
        };
        let strip = |mut rs: Vec<Record>| {
            for r in &mut rs {
                r.host.median_ms = 0.0;
                r.host.min_ms = 0.0;
                r.host.max_ms = 0.0;
                r.host.pixels_per_s = 0.0;
            }
            rs
        };
        let a = strip(measure(&scenes[..2], once, false).unwrap());
        let b = strip(measure(&scenes[..2], once, false).unwrap());
        assert_eq!(a.len(), 2 * 3 * 8);
        // Scene, then mode, then profile order, whatever the threads did.
        let order: Vec<(String, Mode, String)> = a
            .iter()
            .map(|r| (r.scene.clone(), r.mode, r.profile.clone()))
            .collect();
        let mut sorted = order.clone();
        sorted.sort_by_key(|(s, m, p)| {
            (
                scenes.iter().position(|x| &x.name == s),
                *m,
                CoreProfile::parse(p),
            )
        });
        assert_eq!(order, sorted);
        assert_eq!(a, b);
    }

    #[test]
    fn silhouette_places_are_found() {
        // 3x3 frames: the centre is 3 levels off with every neighbour
        // covered (interior), a corner is covered differently (silhouette),
        // another corner is one level off (not counted).
        let f = |covered: Vec<bool>, rgb: Vec<[u8; 3]>| CoreFrame {
            width: 3,
            height: 3,
            rgb,
            covered,
            bytes: vec![],
            vertices: 0,
            triangles: 0,
            prepared_bytes: 0,
            pixels_drawn: 0,
        };
        let a = f(vec![true; 9], vec![[10; 3]; 9]);
        let mut rgb = vec![[10; 3]; 9];
        rgb[4] = [13, 10, 10]; // centre: 3 levels off, all neighbours covered
        rgb[0] = [11, 10, 10]; // corner: 1 level, not counted
        let mut cov = vec![true; 9];
        cov[8] = false; // corner: covered differently
        let b = f(cov, rgb);
        let p = error_places(&a, &b);
        assert_eq!((p.pixels, p.at_silhouette, p.at_edge), (2, 1, 0));
        // A colour step in the twin next to the centre makes it an edge.
        let (mut ra, mut rb) = (a.rgb.clone(), b.rgb.clone());
        ra[1] = [40, 10, 10];
        rb[1] = [40, 10, 10];
        let (a, b) = (CoreFrame { rgb: ra, ..a }, CoreFrame { rgb: rb, ..b });
        let p = error_places(&a, &b);
        assert_eq!((p.pixels, p.at_silhouette, p.at_edge), (2, 1, 1));
    }
}

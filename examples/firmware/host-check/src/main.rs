//! Renders the firmware's scenes on the host with the same code (the
//! `fixshade-scenes` crate) and prints one line per scene in the
//! firmware's format (without the target-only fields), so `.ci/firmware`
//! can compare the CRCs of the host and both Cortex-M targets. (The CI
//! compares them with the host's `fixshade render --profile fast --crc`
//! too, which renders from the scene files.)
//!
//! `cargo run --profile host -p fixshade-host-check [-- --ppm DIR]`: with
//! `--ppm`, also writes each frame as `DIR/<scene>.ppm` (binary PPM) to look
//! at. `-- --profile NAME` (`precise`, `f32`, `f64`, `fast-pc`, ...)
//! renders with that profile instead, as the firmware built with the
//! feature `profile-NAME` does (`fixshade_scenes::profiled`). `-- --knobs`
//! renders the knob variants of the firmware's `knobs` build (one `knob`
//! line each, as the firmware prints them, without the stack) and counts
//! the pixels where the 32-bit depth frame differs from the 16-bit one.

use fixshade::num::Profile;
use fixshade::render::{Capacity, Tri, Workspace};
use fixshade::target::{PixelFormat, Rgb565Be};
use fixshade_scenes::profiled::{render_frame_with, ProfilePool};
use fixshade_scenes::{
    render_frame, BandPool, Crc32, NoProbe, Pixel, SceneSpec, BAND_PIXELS, CAPACITY, DEPTH_PIXELS,
    SCENES,
};
use std::{error::Error, fs, io::Write, path::PathBuf};

/// Storage on the heap, of the firmware's capacities for the profile
/// (values of type `L`).
struct Owned<L> {
    xy: Vec<fixshade::render::ScreenXy>,
    vals: Vec<L>,
    tris: Vec<Tri>,
    colors: Vec<fixshade::target::Rgb8>,
    faces: Vec<u8>,
    order: Vec<u16>,
}

impl<L: fixshade::raster::Lerp> Owned<L> {
    fn new(n: Capacity) -> Self {
        Self {
            xy: vec![fixshade::render::ScreenXy::ZERO; n.vertices],
            vals: vec![L::ZERO; n.values],
            tris: vec![Tri::default(); n.made],
            colors: vec![fixshade::target::Rgb8::BLACK; n.colors],
            faces: vec![0; n.triangles],
            order: vec![0; n.triangles],
        }
    }

    fn ws(&mut self) -> Workspace<'_, L> {
        self.split().0
    }

    fn split(&mut self) -> (Workspace<'_, L>, &mut [u16]) {
        (
            Workspace {
                xy: &mut self.xy,
                vals: &mut self.vals,
                tris: &mut self.tris,
                colors: &mut self.colors,
                faces: &mut self.faces,
            },
            &mut self.order,
        )
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let mut ppm: Option<PathBuf> = None;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--ppm" => ppm = Some(args.next().ok_or("--ppm needs a directory")?.into()),
            "--knobs" => return knobs(),
            "--profile" => {
                let name = args.next().ok_or("--profile needs a name")?;
                return other_profile(&name);
            }
            _ => {
                return Err(format!(
                    "unknown argument {a}; usage: [--ppm DIR] | [--profile NAME] | [--knobs]"
                )
                .into())
            }
        }
    }
    run::<fixshade::num::Fast>(|spec, ws| {
        if let Some(dir) = &ppm {
            fs::create_dir_all(dir)?;
            let rgb = whole_frame(spec, ws)?;
            let mut out = fs::File::create(dir.join(format!("{}.ppm", spec.name)))?;
            write!(out, "P6\n{} {}\n255\n", spec.width, spec.height)?;
            out.write_all(&rgb)?;
        }
        Ok(())
    })
}

/// Every scene with profile `P`, one `scene` line each, and `then` after
/// each (given the scene and the workspace).
fn run<P: Profile>(
    mut then: impl FnMut(&SceneSpec, &mut Owned<P::Lerp>) -> Result<(), Box<dyn Error>>,
) -> Result<(), Box<dyn Error>> {
    let mut ws = Owned::<P::Lerp>::new(fixshade_scenes::capacity_for::<P>());
    let mut pool = Box::new(ProfilePool::<P>::new());
    // The band memory as the firmware holds it: arrays (no depth band in
    // the `dodeca` build, `DEPTH_PIXELS` = 0).
    let mut px = [0u16; BAND_PIXELS];
    let mut z = [0u16; DEPTH_PIXELS];
    println!("fixshade-host-check target=host profile={}", P::NAME);
    for spec in SCENES.iter() {
        let (w, order) = ws.split();
        let s = render_frame_with::<P, _>(
            spec,
            w,
            &mut px,
            spec.depth.then_some(&mut z[..]),
            order,
            &mut pool,
            &mut NoProbe,
        )
        .map_err(|e| format!("scene {}: {e}", spec.name))?;
        let line = fixshade_scenes::SceneLine {
            spec,
            stats: &s,
            chip: None,
        };
        println!("{line}");
        then(spec, &mut ws)?;
    }
    Ok(())
}

/// The frame of `spec` as 8-bit RGB, rendered in one piece (a band as
/// tall as the frame); fails unless its CRC equals the banded frame's.
fn whole_frame(spec: &SceneSpec, ws: &mut Owned<i32>) -> Result<Vec<u8>, Box<dyn Error>> {
    use fixshade::num::Fast;
    use fixshade::render::prepare;
    use fixshade::target::{Depth16, DepthBuffer, FrameBuf, Target};
    let objects: Vec<_> = spec.objects.iter().map(|o| o.object()).collect();
    let scene = spec.scene(spec.camera()?, &objects);
    let frame = prepare::<Fast>(&scene, spec.width, spec.height, ws.ws())?;
    let n = (spec.width * spec.height) as usize;
    let mut px: Vec<Pixel> = vec![0; n];
    let mut z = vec![0u16; n];
    let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, spec.width, spec.height)?;
    fb.clear(scene.background);
    let mut db = DepthBuffer::<Depth16>::new(&mut z, spec.width, 0, spec.height)?;
    frame.render(&scene, &mut fb, Some(&mut db))?;
    let mut crc = Crc32::new();
    crc.update(fb.bytes());
    let mut banded_px = [0u16; BAND_PIXELS];
    let mut banded_z = [0u16; DEPTH_PIXELS];
    let mut pool = Box::new(BandPool::new());
    let (w, order) = ws.split();
    let banded = render_frame(
        spec,
        w,
        &mut banded_px,
        spec.depth.then_some(&mut banded_z[..]),
        order,
        &mut pool,
        &mut NoProbe,
    )?;
    if crc.finish() != banded.crc {
        return Err(format!("{}: whole frame differs from the bands", spec.name).into());
    }
    Ok(fb
        .pixels()
        .iter()
        .flat_map(|&p| {
            let c = Rgb565Be::decode(p);
            [c.r, c.g, c.b]
        })
        .collect())
}

/// `--profile NAME`: every scene with that profile, one `scene` line each.
fn other_profile(name: &str) -> Result<(), Box<dyn Error>> {
    use fixshade::num::{F32Pc, F64Pc, FastPc, Precise, PrecisePc, F32, F64};
    match name {
        "precise" => run::<Precise>(|_, _| Ok(())),
        "f32" => run::<F32>(|_, _| Ok(())),
        "f64" => run::<F64>(|_, _| Ok(())),
        "fast-pc" => run::<FastPc>(|_, _| Ok(())),
        "precise-pc" => run::<PrecisePc>(|_, _| Ok(())),
        "f32-pc" => run::<F32Pc>(|_, _| Ok(())),
        "f64-pc" => run::<F64Pc>(|_, _| Ok(())),
        _ => Err(format!("unknown profile {name} (precise, f32, f64, fast-pc, precise-pc, f32-pc, f64-pc; the default is fast)").into()),
    }
}

/// `--knobs`: the knob variants (band rows, 32-bit depth, subpixel bits).
fn knobs() -> Result<(), Box<dyn Error>> {
    use fixshade::num::{Fast, Profile};
    use fixshade::target::{Depth16, Depth32, DepthFormat};
    use fixshade_scenes::knobs::{
        render_frame_knobs, FastSub, BAND_ROWS_SWEEP, KNOB_SCENE, MAX_BAND_PIXELS,
    };
    let spec = SCENES
        .iter()
        .find(|s| s.name == KNOB_SCENE)
        .ok_or("no knob scene")?;
    let mut ws = Owned::<i32>::new(CAPACITY);
    let mut px = vec![0u16; MAX_BAND_PIXELS];
    let mut z16 = vec![0u16; MAX_BAND_PIXELS];
    let mut z32 = vec![0u32; MAX_BAND_PIXELS];
    println!("fixshade-host-check target=host knobs scene={KNOB_SCENE}");
    fn line(
        spec: &fixshade_scenes::SceneSpec,
        rows: u32,
        depth: u32,
        bits: u32,
        s: &fixshade_scenes::FrameStats,
    ) {
        let band = spec.width * rows.min(spec.height);
        println!(
            "knob rows={rows} depth={depth} subpixel={bits} scene={} crc=0x{:08x} covered={} drawn={} setups={} prepared_bytes={} band_bytes={} depth_bytes={}",
            spec.name, s.crc, s.covered, s.drawn, s.setups, s.prepared_bytes, band * 2, band * depth / 8
        );
    }
    fn go<P: Profile<Lerp = i32>, D: DepthFormat>(
        spec: &fixshade_scenes::SceneSpec,
        ws: &mut Owned<i32>,
        px: &mut [Pixel],
        z: &mut [D::Raw],
        rows: u32,
    ) -> Result<fixshade_scenes::FrameStats, Box<dyn Error>> {
        let mut pool = Box::new(BandPool::new());
        let (w, order) = ws.split();
        render_frame_knobs::<P, D, _>(spec, w, px, Some(z), rows, order, &mut pool, &mut NoProbe)
            .map_err(|e| format!("knobs: {e}").into())
    }
    for rows in BAND_ROWS_SWEEP {
        let s = go::<Fast, Depth16>(spec, &mut ws, &mut px, &mut z16, rows)?;
        line(spec, rows, 16, 4, &s);
    }
    // The whole frame with each depth format: the pixels that differ.
    let h = spec.height;
    let n = (spec.width * h) as usize;
    let s = go::<Fast, Depth16>(spec, &mut ws, &mut px, &mut z16, h)?;
    let _ = s;
    let frame16: Vec<Pixel> = px[..n].to_vec();
    let s = go::<Fast, Depth32>(spec, &mut ws, &mut px, &mut z32, 16)?;
    line(spec, 16, 32, 4, &s);
    let _ = go::<Fast, Depth32>(spec, &mut ws, &mut px, &mut z32, h)?;
    let differ = frame16.iter().zip(&px[..n]).filter(|(a, b)| a != b).count();
    println!("knob-depth depth32_vs_depth16_pixels={differ}");
    let s = go::<FastSub<2>, Depth16>(spec, &mut ws, &mut px, &mut z16, 16)?;
    line(spec, 16, 16, 2, &s);
    let s = go::<FastSub<3>, Depth16>(spec, &mut ws, &mut px, &mut z16, 16)?;
    line(spec, 16, 16, 3, &s);
    let s = go::<FastSub<6>, Depth16>(spec, &mut ws, &mut px, &mut z16, 16)?;
    line(spec, 16, 16, 6, &s);
    let s = go::<FastSub<8>, Depth16>(spec, &mut ws, &mut px, &mut z16, 16)?;
    line(spec, 16, 16, 8, &s);
    Ok(())
}

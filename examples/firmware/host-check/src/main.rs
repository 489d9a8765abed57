//! Renders the firmware's scenes on the host with the same code (the
//! `fixshade-scenes` crate) and prints one line per scene in the
//! firmware's format (without the target-only fields), so `.ci/firmware`
//! can compare the CRCs of the host and both Cortex-M targets. (The CI
//! compares them with the host's `fixshade render --profile fast --crc`
//! too, which renders from the scene files.)
//!
//! `cargo run --release -p fixshade-host-check [-- --ppm DIR]`: with
//! `--ppm`, also writes each frame as `DIR/<scene>.ppm` (binary PPM) to look
//! at.

use fixshade::render::{Tri, Workspace};
use fixshade::target::{PixelFormat, Rgb565Be};
use fixshade_scenes::{
    render_frame, BandPool, Crc32, Needs, NoProbe, Pixel, BAND_PIXELS, MAX_NEEDS, SCENES,
};
use std::{error::Error, fs, io::Write, path::PathBuf};

/// Workspace memory on the heap.
struct Owned {
    xy: Vec<[i32; 2]>,
    vals: Vec<i32>,
    tris: Vec<Tri>,
}

impl Owned {
    fn new(n: Needs) -> Self {
        Self {
            xy: vec![[0; 2]; n.vertices],
            vals: vec![0; n.values],
            tris: vec![Tri::default(); n.triangles],
        }
    }

    fn ws(&mut self) -> Workspace<'_, i32> {
        Workspace {
            xy: &mut self.xy,
            vals: &mut self.vals,
            tris: &mut self.tris,
        }
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let mut ppm: Option<PathBuf> = None;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--ppm" => ppm = Some(args.next().ok_or("--ppm needs a directory")?.into()),
            _ => return Err(format!("unknown argument {a}; usage: [--ppm DIR]").into()),
        }
    }
    let mut ws = Owned::new(MAX_NEEDS);
    let mut px = vec![[0u8; 2]; BAND_PIXELS];
    let mut z = vec![0u16; BAND_PIXELS];
    let mut order = vec![0u16; 2 * MAX_NEEDS.triangles];
    let mut pool = Box::new(BandPool::new());
    println!("fixshade-host-check target=host profile=fast");
    for spec in SCENES.iter() {
        let s = render_frame(
            spec,
            ws.ws(),
            &mut px,
            &mut z,
            &mut order,
            &mut pool,
            &mut NoProbe,
        )
        .map_err(|e| format!("scene {}: {e}", spec.name))?;
        println!(
            "scene {} size={}x{} crc=0x{:08x} covered={} drawn={} setups={} triangles={} prepared_vertices={} prepared_triangles={} prepared_bytes={}",
            spec.name,
            spec.width,
            spec.height,
            s.crc,
            s.covered,
            s.drawn,
            s.setups,
            spec.triangles(),
            s.vertices,
            s.triangles,
            s.prepared_bytes,
        );
        if let Some(dir) = &ppm {
            fs::create_dir_all(dir)?;
            let rgb = whole_frame(spec, &mut ws)?;
            let mut out = fs::File::create(dir.join(format!("{}.ppm", spec.name)))?;
            write!(out, "P6\n{} {}\n255\n", spec.width, spec.height)?;
            out.write_all(&rgb)?;
        }
    }
    Ok(())
}

/// The frame of `spec` as 8-bit RGB, rendered in one piece (a band as
/// tall as the frame); fails unless its CRC equals the banded frame's.
fn whole_frame(
    spec: &fixshade_scenes::SceneSpec,
    ws: &mut Owned,
) -> Result<Vec<u8>, Box<dyn Error>> {
    use fixshade::num::Fast;
    use fixshade::render::prepare;
    use fixshade::target::{Depth16, DepthBuffer, FrameBuf, Target};
    let objects: Vec<_> = spec.objects.iter().map(|o| o.object()).collect();
    let scene = spec.scene(spec.camera()?, &objects);
    let frame = prepare::<Fast>(&scene, spec.width, spec.height, ws.ws())?;
    let n = (spec.width * spec.height) as usize;
    let mut px: Vec<Pixel> = vec![[0; 2]; n];
    let mut z = vec![0u16; n];
    let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, spec.width, spec.height)?;
    fb.clear(scene.background);
    let mut db = DepthBuffer::<Depth16>::new(&mut z, spec.width, 0, spec.height)?;
    frame.render(&scene, &mut fb, Some(&mut db))?;
    let mut crc = Crc32::new();
    crc.update(fb.bytes());
    let mut banded_px = vec![[0u8; 2]; BAND_PIXELS];
    let mut banded_z = vec![0u16; BAND_PIXELS];
    let mut order = vec![0u16; 2 * MAX_NEEDS.triangles];
    let mut pool = Box::new(BandPool::new());
    let banded = render_frame(
        spec,
        ws.ws(),
        &mut banded_px,
        &mut banded_z,
        &mut order,
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

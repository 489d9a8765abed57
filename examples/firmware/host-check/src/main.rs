//! Renders the firmware's scenes on the host with the same code (the
//! `fixshade-scenes` crate) and prints one line per scene in the
//! firmware's format, so `.ci/firmware` can compare the CRCs of the host
//! and both Cortex-M targets.
//!
//! `cargo run --release -p fixshade-host-check [-- --ppm DIR]`: with
//! `--ppm`, also writes each frame as `DIR/<scene>.ppm` (binary PPM) to look
//! at.

use fixshade::target::{PixelFormat, Rgb565Be};
use fixshade_scenes::{render_frame, NoProbe, Pixel, BAND_PIXELS, HEIGHT, SCENES, WIDTH};
use std::{error::Error, fs, io::Write, path::PathBuf};

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let mut ppm: Option<PathBuf> = None;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--ppm" => ppm = Some(args.next().ok_or("--ppm needs a directory")?.into()),
            _ => return Err(format!("unknown argument {a}; usage: [--ppm DIR]").into()),
        }
    }
    let mut px = vec![[0u8; 2]; BAND_PIXELS];
    let mut z = vec![0u16; BAND_PIXELS];
    println!("fixshade-host-check target=host frame={WIDTH}x{HEIGHT}");
    for scene in SCENES.iter() {
        let s = render_frame(scene, &mut px, &mut z, &mut NoProbe)?;
        println!(
            "scene {} crc=0x{:08x} covered={} triangles={}",
            scene.name, s.crc, s.covered, scene.triangles
        );
        if let Some(dir) = &ppm {
            fs::create_dir_all(dir)?;
            write_ppm(&dir.join(format!("{}.ppm", scene.name)), scene)?;
        }
    }
    Ok(())
}

/// Renders the scene into a whole frame and writes it as binary PPM.
fn write_ppm(path: &std::path::Path, scene: &fixshade_scenes::Scene) -> Result<(), Box<dyn Error>> {
    use fixshade::target::{Depth16, DepthBuffer, FrameBuf, Target};
    let n = (WIDTH * HEIGHT) as usize;
    let mut px: Vec<Pixel> = vec![[0; 2]; n];
    let mut z = vec![0u16; n];
    let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, WIDTH, HEIGHT)?;
    fb.clear(fixshade_scenes::BACKGROUND);
    let mut db = DepthBuffer::<Depth16>::new(&mut z, WIDTH, 0, HEIGHT)?;
    (scene.draw)(&mut fb, &mut db)?;
    let mut out = fs::File::create(path)?;
    write!(out, "P6\n{WIDTH} {HEIGHT}\n255\n")?;
    for &p in fb.pixels() {
        let c = Rgb565Be::decode(p);
        out.write_all(&[c.r, c.g, c.b])?;
    }
    Ok(())
}

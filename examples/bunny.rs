//! Renders the bunny benchmark scene (Gouraud, one directional light) with
//! a chosen profile, in 16-row bands, and writes a PNG.
//!
//! `cargo run --release --example bunny -- [fast|precise|f32|f64] [OUT.png]`

mod common;

use common::{Bunny, Store};
use fixshade::num::{Fast, Precise, Profile, F32, F64};
use fixshade::render::{prepare, BandState, Pool, RenderError};
use fixshade::scene::Shading;
use fixshade::target::{BandBuf, PixelFormat, Rgb565Be};
use std::{error::Error, fs::File, io::BufWriter};

const W: u32 = 240;

fn run<P: Profile>(out: &str, shading: Shading) -> Result<(), Box<dyn Error>> {
    let bunny = Bunny::<P::Real>::new(shading)?;
    let scene = bunny.scene();
    let mut store = Box::new(Store::<P::Lerp>::EMPTY);
    let (ws, order) = store.split();
    let frame = prepare::<P>(&scene, W, W, ws)?;
    let mut band = vec![0u16; (W * 16) as usize];
    let mut z = vec![0u16; (W * 16) as usize];
    let mut rgb = Vec::new();
    let mut buf = BandBuf::<Rgb565Be>::new(&mut band, Some(&mut z), W, 16)?;
    let mut pool = Box::new(Pool::<P::Lerp, 64, 8>::new());
    let mut state = BandState::new(order, &mut pool);
    let stats = frame.render_bands(&scene, &mut state, &mut buf, |b| {
        rgb.extend(b.pixels().iter().flat_map(|&p| {
            let c = Rgb565Be::decode(p);
            [c.r, c.g, c.b]
        }));
        Ok::<(), RenderError>(())
    })?;
    let mut enc = png::Encoder::new(BufWriter::new(File::create(out)?), W, W);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header()?.write_image_data(&rgb)?;
    println!(
        "{}: {} prepared vertices, {} triangles, {} bytes; drew {} pixels",
        P::NAME,
        frame.vertex_count(),
        frame.triangle_count(),
        frame.bytes_used(),
        stats.pixels
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let profile = std::env::args().nth(1).unwrap_or_else(|| "precise".into());
    let out = std::env::args()
        .nth(2)
        .unwrap_or_else(|| "bunny.png".into());
    let shading = Shading::Gouraud;
    match profile.as_str() {
        "fast" => run::<Fast>(&out, shading),
        "precise" => run::<Precise>(&out, shading),
        "f32" => run::<F32>(&out, shading),
        "f64" => run::<F64>(&out, shading),
        p => Err(format!("unknown profile {p}").into()),
    }
}

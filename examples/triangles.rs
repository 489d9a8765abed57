//! Renders Gouraud-shaded, depth-tested triangles into a 240×240 RGB565
//! frame with the fixed-point core and writes it as a PNG.
//!
//! `cargo run --release --example triangles -- [OUT.png]` (default
//! `triangles.png`).

use fixshade::raster::{Fill, Gouraud, SubpixelBits, Vertex, DEPTH_ONE};
use fixshade::target::{Depth16, DepthBuffer, FrameBuf, PixelFormat, Rgb565Be, Rgb8, Target};
use std::{error::Error, fs::File, io::BufWriter};

const W: u32 = 240;

fn main() -> Result<(), Box<dyn Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "triangles.png".into());
    let mut px = vec![0u16; (W * W) as usize];
    let mut z = vec![0u16; (W * W) as usize];
    let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, W, W)?;
    fb.clear(Rgb8::new(16, 16, 32));
    let mut db = DepthBuffer::<Depth16>::new(&mut z, W, 0, W)?;
    let sub = SubpixelBits::DEFAULT;
    let mut fill = Fill::new(&mut fb, Some(&mut db), Gouraud)?;
    // A fan of twelve triangles around the centre, its hub far away and its
    // rim near, crossed by a band of two triangles at middle depth.
    let level = |c: f32| (c.clamp(0.0, 1.0) * 255.0 * 65536.0) as i32;
    let v = |x: f32, y: f32, d: f32, rgb: [f32; 3]| Vertex {
        x: sub.from_f32(x),
        y: sub.from_f32(y),
        z: (d * DEPTH_ONE as f32) as i32,
        attrs: rgb.map(level),
    };
    for k in 0..12 {
        let a0 = k as f32 / 12.0 * std::f32::consts::TAU;
        let a1 = (k + 1) as f32 / 12.0 * std::f32::consts::TAU;
        let hue = |a: f32| {
            [
                0.5 + 0.5 * a.cos(),
                0.5 + 0.5 * (a + 2.1).cos(),
                0.5 + 0.5 * (a + 4.2).cos(),
            ]
        };
        let tri = [
            v(120.0, 120.0, 0.9, [1.0, 1.0, 1.0]),
            v(
                120.0 + 110.0 * a0.cos(),
                120.0 + 110.0 * a0.sin(),
                0.1,
                hue(a0),
            ),
            v(
                120.0 + 110.0 * a1.cos(),
                120.0 + 110.0 * a1.sin(),
                0.1,
                hue(a1),
            ),
        ];
        fill.draw(&tri, sub)?;
    }
    let band = [
        v(-20.0, 100.0, 0.5, [0.1, 0.1, 0.1]),
        v(260.0, 80.0, 0.5, [0.9, 0.9, 0.2]),
        v(260.0, 140.0, 0.5, [0.9, 0.9, 0.2]),
    ];
    fill.draw(&band, sub)?;
    fill.draw(
        &[band[0], band[2], v(-20.0, 160.0, 0.5, [0.1, 0.1, 0.1])],
        sub,
    )?;

    let rgb: Vec<u8> = fb
        .pixels()
        .iter()
        .flat_map(|&p| {
            let c = Rgb565Be::decode(p);
            [c.r, c.g, c.b]
        })
        .collect();
    let mut enc = png::Encoder::new(BufWriter::new(File::create(&out)?), W, W);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header()?.write_image_data(&rgb)?;
    println!("wrote {out} ({W}x{W} RGB565, {} bytes of frame)", W * W * 2);
    Ok(())
}

//! Span filling on the host, in time per pixel: flat and Gouraud spans with
//! a 16-bit depth test into a 240×240 RGB565 frame.
//!
//! `cargo bench --bench spans`; criterion reports the throughput in pixels
//! per second (its reciprocal is the time per pixel).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use fixshade::raster::{Fill, Flat, Gouraud, SubpixelBits, Vertex, DEPTH_ONE};
use fixshade::target::{Depth16, DepthBuffer, FrameBuf, Rgb565Be, Rgb8};
use std::hint::black_box;

const W: u32 = 240;

fn quad() -> [[Vertex<i32, 3>; 3]; 2] {
    let s = SubpixelBits::DEFAULT;
    let p = |x: i32, y: i32, l: i32| Vertex {
        x: s.from_px(x),
        y: s.from_px(y),
        z: DEPTH_ONE / 2 + x * 1000,
        attrs: [l << 16, (255 - l) << 16, (l / 2) << 16],
    };
    let (a, b, c, d) = (p(0, 0, 0), p(240, 0, 255), p(240, 240, 128), p(0, 240, 60));
    [[a, b, c], [a, c, d]]
}

fn spans(cr: &mut Criterion) {
    let mut px = vec![0u16; (W * W) as usize];
    let mut z = vec![0u16; (W * W) as usize];
    let tris = quad();
    let mut g = cr.benchmark_group("span_fill_240x240");
    g.throughput(Throughput::Elements((W * W) as u64));
    g.bench_function("flat_depth16", |b| {
        b.iter(|| {
            let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, W, W).unwrap();
            let mut db = DepthBuffer::<Depth16>::new(&mut z, W, 0, W).unwrap();
            let mut f = Fill::new(&mut fb, Some(&mut db), Flat(Rgb8::WHITE)).unwrap();
            for t in &tris {
                f.draw(black_box(t), SubpixelBits::DEFAULT).unwrap();
            }
        })
    });
    g.bench_function("gouraud_rgb_depth16", |b| {
        b.iter(|| {
            let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, W, W).unwrap();
            let mut db = DepthBuffer::<Depth16>::new(&mut z, W, 0, W).unwrap();
            let mut f = Fill::new(&mut fb, Some(&mut db), Gouraud).unwrap();
            for t in &tris {
                f.draw(black_box(t), SubpixelBits::DEFAULT).unwrap();
            }
        })
    });
    g.bench_function("gouraud_rgb_f32_depth16", |b| {
        let ft = tris.map(|t| {
            t.map(|v| Vertex {
                x: v.x,
                y: v.y,
                z: v.z as f32 / DEPTH_ONE as f32,
                attrs: v.attrs.map(|a| a as f32 / 65536.0),
            })
        });
        b.iter(|| {
            let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, W, W).unwrap();
            let mut db = DepthBuffer::<Depth16>::new(&mut z, W, 0, W).unwrap();
            let mut f = Fill::new(&mut fb, Some(&mut db), Gouraud).unwrap();
            for t in &ft {
                f.draw(black_box(t), SubpixelBits::DEFAULT).unwrap();
            }
        })
    });
    g.finish();
}

criterion_group!(benches, spans);
criterion_main!(benches);

//! Fuzz target: arbitrary bytes decoded into screen-space triangles and
//! into small 3D scenes, run through the rasterizer and the whole pipeline.
//!
//! Asserts: no panic (the library has no `unsafe`, so a write outside a
//! buffer would panic on the bounds check), no write outside a target's
//! window (a checking target panics on one), `RasterError::OutOfRange`
//! exactly when a vertex is outside the stated range, and never a
//! `RenderError::Raster` out of `Frame::render` (clipping must keep every
//! triangle inside the rasterizer's range).
#![no_main]

use fixshade::geom::{Affine, Mat3, Vec3};
use fixshade::illum::{Light, LightKind, Material, Specular, Viewer};
use fixshade::mesh::{shapes, Mesh};
use fixshade::num::{F32Pc, F64Pc, Fast, FastPc, Precise, PrecisePc, Profile, Real, F32, F64};
use fixshade::raster::{
    draw_triangle, Fill, Flat, Gouraud, GouraudMono, Lerp, Persp, RasterError, Shader, Span, Spans,
    SubpixelBits, Vertex,
};
use fixshade::render::{prepare, BandState, Pool, RenderError, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::{
    BandBuf, Depth16, Depth32, DepthBuffer, DepthFormat, FrameBuf, Gray8, PixelFormat, Rgb565Be,
    Rgb8, Target, Window,
};
use libfuzzer_sys::fuzz_target;

/// Reads values from the input; zeros once it runs out.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }
    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
    fn i32(&mut self) -> i32 {
        self.u32() as i32
    }
    fn bool(&mut self) -> bool {
        self.u8() & 1 == 1
    }
    /// Any f32 (NaN and infinities included) half the time, otherwise a
    /// "reasonable" value in [-8, 8) so that scenes show something.
    fn f32(&mut self) -> f32 {
        match self.u8() % 4 {
            0 => f32::from_bits(self.u32()),
            1 => [
                0.0,
                -0.0,
                1.0,
                f32::NAN,
                f32::INFINITY,
                f32::NEG_INFINITY,
                1e30,
                1e-30,
            ][self.u8() as usize % 8],
            _ => (self.i32() >> 16) as f32 / 4096.0,
        }
    }
    /// An i32 coordinate: anything, near the limit, or near the window.
    fn coord(&mut self, lim: i32) -> i32 {
        match self.u8() % 4 {
            0 => self.i32(),
            1 => lim.saturating_add((self.u8() as i32) - 128),
            2 => -lim.saturating_add((self.u8() as i32) - 128),
            _ => (self.i32() >> 18) % 4096, // within about ±64 px at 6 bits
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    match b.u8() % 3 {
        0 => screen(&mut b),
        _ => scene(&mut b),
    }
});

// ---------------------------------------------------------------------
// Screen space.

/// A target without a fast path that panics on a write outside its
/// window.
struct Checked {
    w: Window,
    writes: u64,
}

impl Target for Checked {
    type Format = Gray8;
    fn window(&self) -> Window {
        self.w
    }
    fn write_pixel(&mut self, x: u32, y: u32, _p: [u8; 1]) {
        assert!(
            x < self.w.width && y >= self.w.y0 && y < self.w.y1,
            "write outside the window at ({x}, {y})"
        );
        self.writes += 1;
    }
}

/// A span sink checking that spans are inside the window and not empty.
struct SpanCheck(Window);

impl<L: Lerp, const N: usize> Spans<L, N> for SpanCheck {
    fn span(&mut self, s: &Span<L, N>) {
        assert!(s.x0 < s.x1 && s.x1 <= self.0.width, "{:?}", (s.x0, s.x1));
        assert!(s.y >= self.0.y0 && s.y < self.0.y1, "row {}", s.y);
    }
}

fn screen(b: &mut Bytes<'_>) {
    let bits = b.u8() % 10;
    let sub = match SubpixelBits::new(u32::from(bits)) {
        Ok(s) => s,
        Err(e) => {
            assert!(!(1..=8).contains(&bits));
            assert_eq!(RasterError::from(e), RasterError::BadSubpixelBits);
            return;
        }
    };
    let width = u32::from(b.u8() % 65);
    let height = u32::from(b.u8() % 65);
    let y0 = u32::from(b.u8()) % (height + 1);
    let y1 = y0 + u32::from(b.u8()) % (height - y0 + 1);
    let window = Window { width, y0, y1 };
    let n = window.len();
    let lim = sub.coord_limit();
    let ntris = 1 + b.u8() % 6;
    let mode = b.u8();
    let depth_kind = b.u8() % 3;
    let mut px = vec![0u16; n];
    let mut z16 = vec![0u16; n];
    let mut z32 = vec![0u32; n];
    let mut fb = FrameBuf::<Rgb565Be>::band(&mut px, width, y0, y1).expect("valid band");
    let mut d16 = DepthBuffer::<Depth16>::new(&mut z16, width, y0, y1).expect("valid");
    let mut d32 = DepthBuffer::<Depth32>::new(&mut z32, width, y0, y1).expect("valid");
    let mut checked = Checked {
        w: window,
        writes: 0,
    };
    for _ in 0..ntris {
        let xy: [(i32, i32); 3] = core::array::from_fn(|_| (b.coord(lim), b.coord(lim)));
        let out = xy
            .iter()
            .position(|&(x, y)| x < -lim || x > lim || y < -lim || y > lim);
        let want = match out {
            Some(i) => Err(RasterError::OutOfRange(i as u8)),
            None => Ok(()),
        };
        let zs: [i32; 3] = core::array::from_fn(|_| b.i32());
        let attrs: [[i32; 4]; 3] = core::array::from_fn(|_| core::array::from_fn(|_| b.i32()));
        match mode % 4 {
            0 => {
                let t = fixed::<0>(&xy, &zs, &attrs);
                assert_eq!(draw_triangle(&t, sub, window, &mut SpanCheck(window)), want);
                let mut f =
                    Fill::<_, Depth16, _>::new(&mut checked, None, Flat(Rgb8::WHITE)).unwrap();
                assert_eq!(f.draw(&t, sub), want);
                draw::<Rgb565Be, _, 0, _>(
                    &mut fb,
                    &mut d16,
                    &mut d32,
                    depth_kind,
                    Flat(Rgb8::WHITE),
                    &t,
                    sub,
                    want,
                );
            }
            1 => {
                let t = fixed::<1>(&xy, &zs, &attrs);
                assert_eq!(draw_triangle(&t, sub, window, &mut SpanCheck(window)), want);
                let mut f = Fill::<_, Depth16, _>::new(&mut checked, None, GouraudMono).unwrap();
                assert_eq!(f.draw(&t, sub), want);
                draw::<Rgb565Be, _, 1, _>(
                    &mut fb,
                    &mut d16,
                    &mut d32,
                    depth_kind,
                    GouraudMono,
                    &t,
                    sub,
                    want,
                );
            }
            2 => {
                let t = fixed::<4>(&xy, &zs, &attrs);
                assert_eq!(draw_triangle(&t, sub, window, &mut SpanCheck(window)), want);
                draw::<Rgb565Be, _, 4, _>(
                    &mut fb,
                    &mut d16,
                    &mut d32,
                    depth_kind,
                    Persp(Gouraud),
                    &t,
                    sub,
                    want,
                );
            }
            _ => {
                // The float twins with arbitrary bit patterns (NaN, inf).
                let t: [Vertex<f32, 3>; 3] = core::array::from_fn(|i| Vertex {
                    x: xy[i].0,
                    y: xy[i].1,
                    z: f32::from_bits(zs[i] as u32),
                    attrs: attrs[i].map(|a| f32::from_bits(a as u32))[..3]
                        .try_into()
                        .unwrap(),
                });
                assert_eq!(draw_triangle(&t, sub, window, &mut SpanCheck(window)), want);
                draw::<Rgb565Be, _, 3, _>(
                    &mut fb, &mut d16, &mut d32, depth_kind, Gouraud, &t, sub, want,
                );
                let t64 = t.map(|v| Vertex {
                    x: v.x,
                    y: v.y,
                    z: f64::from(v.z),
                    attrs: v.attrs.map(f64::from),
                });
                let mut f = Fill::<_, Depth16, _>::new(&mut checked, None, Gouraud).unwrap();
                assert_eq!(f.draw(&t64, sub), want);
            }
        }
    }
    assert!(checked.writes <= u64::from(ntris) * n as u64);
}

fn fixed<const N: usize>(
    xy: &[(i32, i32); 3],
    z: &[i32; 3],
    a: &[[i32; 4]; 3],
) -> [Vertex<i32, N>; 3] {
    core::array::from_fn(|i| Vertex {
        x: xy[i].0,
        y: xy[i].1,
        z: z[i],
        attrs: core::array::from_fn(|k| a[i][k]),
    })
}

#[allow(clippy::too_many_arguments)]
fn draw<F: PixelFormat, L: Lerp, const N: usize, S: Shader<L, N>>(
    fb: &mut FrameBuf<'_, F>,
    d16: &mut DepthBuffer<'_, Depth16>,
    d32: &mut DepthBuffer<'_, Depth32>,
    kind: u8,
    shader: S,
    t: &[Vertex<L, N>; 3],
    sub: SubpixelBits,
    want: Result<(), RasterError>,
) {
    let got = match kind {
        0 => Fill::<_, Depth16, _>::new(fb, None, shader)
            .unwrap()
            .draw(t, sub),
        1 => Fill::new(fb, Some(d16), shader).unwrap().draw(t, sub),
        _ => Fill::new(fb, Some(d32), shader).unwrap().draw(t, sub),
    };
    assert_eq!(got, want);
}

// ---------------------------------------------------------------------
// 3D scenes.

const MESHES: [Mesh<'static>; 6] = shapes::ALL;

fn scene(b: &mut Bytes<'_>) {
    match b.u8() % 8 {
        0 => scene_for::<Fast>(b),
        1 => scene_for::<Precise>(b),
        2 => scene_for::<F32>(b),
        3 => scene_for::<F64>(b),
        4 => scene_for::<FastPc>(b),
        5 => scene_for::<PrecisePc>(b),
        6 => scene_for::<F32Pc>(b),
        _ => scene_for::<F64Pc>(b),
    }
}

fn v3<R: Real>(b: &mut Bytes<'_>) -> Vec3<R> {
    Vec3::new(
        R::from_f32(b.f32()),
        R::from_f32(b.f32()),
        R::from_f32(b.f32()),
    )
}

fn scene_for<P: Profile>(b: &mut Bytes<'_>) {
    let r = |b: &mut Bytes<'_>| P::Real::from_f32(b.f32());
    let (w, h) = (u32::from(b.u8() % 65), u32::from(b.u8() % 65));
    // Camera: through the checked constructor, or any fields at all.
    let camera = if !b.u8().is_multiple_of(4) {
        let eye = [b.f32(), b.f32(), b.f32()];
        let target = [b.f32(), b.f32(), b.f32()];
        let up = [b.f32(), b.f32(), b.f32()];
        let far = b.bool().then(|| b.f32());
        match Camera::<P::Real>::look_at_f32(eye, target, up, b.f32() * 20.0, b.f32(), far) {
            Ok(c) => c,
            Err(_) => return,
        }
    } else {
        Camera {
            view: Affine {
                m: Mat3 {
                    rows: [v3(b), v3(b), v3(b)],
                },
                t: v3(b),
            },
            focal: r(b),
            near: r(b),
            far: b.bool().then(|| r(b)),
        }
    };
    let nobj = 1 + b.u8() as usize % 3;
    let objects: Vec<Object<'static, P::Real>> = (0..nobj)
        .map(|_| {
            let mesh = MESHES[b.u8() as usize % MESHES.len()];
            let transform = if b.bool() {
                Affine::from_parts(r(b), v3(b), v3(b))
            } else {
                Affine {
                    m: Mat3 {
                        rows: [v3(b), v3(b), v3(b)],
                    },
                    t: v3(b),
                }
            };
            Object {
                mesh,
                transform,
                material: Material {
                    color: v3(b),
                    ka: r(b),
                    kd: r(b),
                    ks: r(b),
                    shininess: P::Real::from_f32(b.f32() * 1000.0),
                },
                shading: [Shading::Flat, Shading::Gouraud, Shading::Phong][b.u8() as usize % 3],
                cull_backfaces: b.bool(),
            }
        })
        .collect();
    let nlights = b.u8() as usize % 10; // 9 is one too many: an error
    let lights: Vec<Light<P::Real>> = (0..nlights)
        .map(|_| Light {
            kind: if b.bool() {
                LightKind::Point(v3(b))
            } else {
                LightKind::Directional(v3(b))
            },
            intensity: r(b),
            color: v3(b),
        })
        .collect();
    let scene = Scene {
        camera,
        objects: &objects,
        lights: &lights,
        ambient: r(b),
        specular: if b.bool() {
            Specular::Phong
        } else {
            Specular::Blinn
        },
        viewer: if b.bool() {
            Viewer::Local
        } else {
            Viewer::Infinite
        },
        background: Rgb8::new(b.u8(), b.u8(), b.u8()),
    };
    // Workspace: usually big enough, sometimes not.
    let small = b.u8().is_multiple_of(8);
    let cap = |b: &mut Bytes<'_>, big: usize| if small { b.u16() as usize % 64 } else { big };
    let verts = cap(b, 6000);
    let mut xy = vec![fixshade::render::ScreenXy::ZERO; verts];
    let mut vals = vec![P::Lerp::default(); cap(b, 6000 * 8)];
    let mut tris = vec![Tri::default(); cap(b, 8000)];
    let mut colors = vec![fixshade::target::Rgb8::BLACK; cap(b, 8000)];
    let mut faces = vec![0u8; cap(b, 8000)];
    let ws = Workspace {
        xy: &mut xy,
        vals: &mut vals,
        tris: &mut tris,
        colors: &mut colors,
        faces: &mut faces,
    };
    let frame = match prepare::<P>(&scene, w, h, ws) {
        Ok(f) => f,
        Err(e) => {
            assert!(
                !matches!(e, RenderError::Raster(_) | RenderError::Buffer(_)),
                "{e:?}"
            );
            return;
        }
    };
    // A band of the screen, and sometimes a depth buffer of other rows.
    let y0 = u32::from(b.u8()) % (h + 1);
    let y1 = y0 + u32::from(b.u8()) % (h - y0 + 1);
    let n = (w * (y1 - y0)) as usize;
    let mut px = vec![0u16; n];
    let mut fb = FrameBuf::<Rgb565Be>::band(&mut px, w, y0, y1).expect("valid band");
    fb.clear(scene.background);
    let r = match b.u8() % 4 {
        0 => frame.render::<_, Depth16>(&scene, &mut fb, None),
        1 => {
            let mut z = vec![0u16; n];
            let mut d = DepthBuffer::<Depth16>::new(&mut z, w, y0, y1).unwrap();
            frame.render(&scene, &mut fb, Some(&mut d))
        }
        2 => {
            let mut z = vec![0u32; n];
            let mut d = DepthBuffer::<Depth32>::new(&mut z, w, y0, y1).unwrap();
            frame.render(&scene, &mut fb, Some(&mut d))
        }
        _ => {
            // A depth window one row off: an error, not a panic.
            let mut z = vec![0u32; w as usize];
            let mut d = DepthBuffer::<Depth32>::new(&mut z, w, y1, (y1 + 1).min(4096)).unwrap();
            let r = frame.render(&scene, &mut fb, Some(&mut d));
            if w > 0 {
                assert!(r.is_err());
            }
            r
        }
    };
    if let Err(e) = r {
        assert!(
            !matches!(e, RenderError::Raster(RasterError::OutOfRange(_))),
            "{e:?}"
        );
    }
    // Bands of any height (any u32): the buffer must match, or an error.
    let rows = match b.u8() % 3 {
        0 => b.u32(),
        _ => 1 + u32::from(b.u8()) % (h + 1),
    };
    let len = if u64::from(rows) * u64::from(w) <= 65 * 65 {
        (rows * w) as usize
    } else {
        b.u8() as usize
    };
    let mut band = vec![0u16; len];
    let mut zb = vec![0u16; len];
    let depth = if b.bool() { Some(&mut zb[..]) } else { None };
    let Ok(mut buf) = BandBuf::<Rgb565Be>::new(&mut band, depth, w, rows) else {
        return;
    };
    // Any order scratch (too short: an error) and a tiny pool (full: the
    // triangles are set up again in each band, the same bytes).
    let mut order = vec![0u16; cap(b, 2 * frame.triangle_count() + 2)];
    let mut pool = Pool::<P::Lerp, 3, 4>::new();
    let mut state = BandState::new(&mut order, &mut pool);
    let r = frame.render_bands(&scene, &mut state, &mut buf, |fb| {
        assert!(fb.pixels().len() <= len);
        Ok::<(), RenderError>(())
    });
    if let Err(e) = r {
        assert!(!matches!(e, RenderError::Raster(_)), "{e:?}");
    }
    let _ = (Depth32::CLEAR, Gray8::BYTES);
}

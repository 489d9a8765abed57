//! The "fan" scenes: 34 large, overlapping triangles from integer constants
//! (a star-shaped fan of 24 triangles, its hub far and its rim near, a band
//! of two triangles crossing it and partly off screen, and eight small
//! near triangles), Gouraud-shaded in colour or flat.

use crate::{level, meets_rows, Band, BandDepth, SUB};
use fixshade::raster::{Fill, Flat, Gouraud, RasterError, Vertex, DEPTH_ONE};
use fixshade::target::{Rgb8, Target};

/// Triangles in the scene.
pub const TRIANGLES: usize = 24 + 2 + 8;

/// `round(2^14 · cos(2πk/24))` for `k` in `0..24`.
const COS24: [i32; 24] = [
    16384, 15826, 14189, 11585, 8192, 4240, 0, -4240, -8192, -11585, -14189, -15826, -16384,
    -15826, -14189, -11585, -8192, -4240, 0, 4240, 8192, 11585, 14189, 15826,
];

const fn cos24(k: usize) -> i32 {
    COS24[k % 24]
}

const fn sin24(k: usize) -> i32 {
    COS24[(k + 18) % 24]
}

/// Subpixels per pixel.
const S: i32 = 16;
/// The frame's centre, in subpixels.
const C: i32 = 120 * S;

/// `r` pixels times a Q14 factor, in subpixels, rounded.
const fn polar(r: i32, q14: i32) -> i32 {
    (r * S * q14 + (1 << 13)) >> 14
}

/// A level oscillating with the angle `k` (of 24) and a phase.
const fn hue(k: usize, phase: usize) -> i32 {
    level(128 + ((127 * cos24(k + phase)) >> 14))
}

const fn rgb_at(k: usize) -> [i32; 3] {
    [hue(k, 0), hue(k, 8), hue(k, 16)]
}

const fn v(x: i32, y: i32, z: i32, attrs: [i32; 3]) -> Vertex<i32, 3> {
    Vertex { x, y, z, attrs }
}

const fn build() -> [[Vertex<i32, 3>; 3]; TRIANGLES] {
    let z = Vertex {
        x: 0,
        y: 0,
        z: 0,
        attrs: [0; 3],
    };
    let mut t = [[z; 3]; TRIANGLES];
    let white = [level(255); 3];
    let hub = v(C, C, DEPTH_ONE / 10 * 9, white);
    // The fan: rim radius alternating 110 and 86 pixels.
    let mut k = 0;
    while k < 24 {
        let r0 = if k & 1 == 0 { 110 } else { 86 };
        let r1 = if k & 1 == 0 { 86 } else { 110 };
        let k1 = k + 1;
        t[k] = [
            hub,
            v(
                C + polar(r0, cos24(k)),
                C + polar(r0, sin24(k)),
                DEPTH_ONE / 10,
                rgb_at(k),
            ),
            v(
                C + polar(r1, cos24(k1)),
                C + polar(r1, sin24(k1)),
                DEPTH_ONE / 10,
                rgb_at(k1),
            ),
        ];
        k += 1;
    }
    // A band at middle depth crossing the fan and both sides of the screen.
    let dark = [level(25); 3];
    let yellow = [level(230), level(230), level(51)];
    let a = v(-20 * S, 100 * S + 5, DEPTH_ONE / 2, dark);
    let b = v(260 * S, 80 * S - 3, DEPTH_ONE / 2, yellow);
    let c = v(260 * S, 140 * S + 7, DEPTH_ONE / 2, yellow);
    let d = v(-20 * S, 160 * S, DEPTH_ONE / 2, dark);
    t[24] = [a, b, c];
    t[25] = [a, c, d];
    // Eight small triangles nearest of all, on a ring of 70 pixels.
    let mut i = 0;
    while i < 8 {
        let k = 3 * i;
        let (x, y) = (C + polar(70, cos24(k)), C + polar(70, sin24(k)));
        let near = DEPTH_ONE / 20;
        t[26 + i] = [
            v(x - 12 * S, y - 10 * S + 3, near, rgb_at(k + 12)),
            v(x + 13 * S + 5, y - 2 * S, near + DEPTH_ONE / 50, white),
            v(x - 3 * S, y + 11 * S + 9, near, rgb_at(k + 6)),
        ];
        i += 1;
    }
    t
}

/// The triangles, Gouraud colour attributes.
pub const FAN: [[Vertex<i32, 3>; 3]; TRIANGLES] = build();

/// The mean of the vertices' colours, for flat shading.
const fn flat_colour(t: &[Vertex<i32, 3>; 3]) -> Rgb8 {
    let mut c = [0u8; 3];
    let mut i = 0;
    while i < 3 {
        let sum = (t[0].attrs[i] >> 16) + (t[1].attrs[i] >> 16) + (t[2].attrs[i] >> 16);
        c[i] = (sum / 3) as u8;
        i += 1;
    }
    Rgb8::new(c[0], c[1], c[2])
}

const fn build_flat() -> [(Rgb8, [Vertex<i32, 0>; 3]); TRIANGLES] {
    let z = Vertex {
        x: 0,
        y: 0,
        z: 0,
        attrs: [],
    };
    let mut out = [(Rgb8::BLACK, [z; 3]); TRIANGLES];
    let mut i = 0;
    while i < TRIANGLES {
        let t = &FAN[i];
        let mut tri = [z; 3];
        let mut j = 0;
        while j < 3 {
            tri[j] = Vertex {
                x: t[j].x,
                y: t[j].y,
                z: t[j].z,
                attrs: [],
            };
            j += 1;
        }
        out[i] = (flat_colour(t), tri);
        i += 1;
    }
    out
}

/// The triangles with one colour each, no attributes.
pub const FAN_FLAT: [(Rgb8, [Vertex<i32, 0>; 3]); TRIANGLES] = build_flat();

/// Draws the Gouraud fan into a band.
pub fn draw_gouraud(fb: &mut Band<'_>, db: &mut BandDepth<'_>) -> Result<(), RasterError> {
    let w = fb.window();
    let mut fill = Fill::new(fb, Some(db), Gouraud)?;
    for tri in FAN.iter() {
        if meets_rows(tri, w) {
            fill.draw(tri, SUB)?;
        }
    }
    Ok(())
}

/// Draws the flat fan into a band.
pub fn draw_flat(fb: &mut Band<'_>, db: &mut BandDepth<'_>) -> Result<(), RasterError> {
    let w = fb.window();
    let mut fill = Fill::new(fb, Some(db), Flat(Rgb8::BLACK))?;
    for (colour, tri) in FAN_FLAT.iter() {
        if meets_rows(tri, w) {
            fill.shader = Flat(*colour);
            fill.draw(tri, SUB)?;
        }
    }
    Ok(())
}

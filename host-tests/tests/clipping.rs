//! Near-plane clipping: the core's clipped triangles cover the pixels the
//! independent ideal reference covers, up to the subpixel snapping of the
//! clipped corners.

use crate::support::{ObjSpec, Spec};
use fixshade::mesh::Mesh;
use fixshade::num::{Precise, Profile, F64};
use fixshade::scene::Shading;

const W: u32 = 96;
const H: u32 = 72;
const EYE: [f64; 3] = [0.0, 0.0, 1.5];
const NEAR: f64 = 0.5;

/// Triangles crossing the near plane (z = 1.0 in the world): one corner,
/// two corners, and a sliver, in Q1.14.
const CASES: [[[i16; 3]; 3]; 4] = [
    [
        [-16000, -9000, -16000],
        [16000, -7000, -14000],
        [2000, 6000, 30000],
    ],
    [
        [-9000, 14000, 30000],
        [12000, 9000, 29000],
        [1000, -12000, -20000],
    ],
    [
        [-12000, -2000, 25000],
        [15000, 1000, -30000],
        [-11000, 1500, 24000],
    ],
    [[-20000, -15000, 0], [20000, -15000, 0], [0, 12000, 32000]],
];

/// The clipped triangle `pos` as one white, unlit (`ka` = 1) object seen
/// from [`EYE`] with the near plane at [`NEAR`]: one description for the
/// core and the ideal reference.
fn spec(pos: &'static [[i16; 3]; 3]) -> Spec<'static> {
    let mesh = Mesh::new(pos, &[[0, 1, 2]], None).unwrap();
    let mut s = Spec::new(W, H, EYE);
    s.near = NEAR;
    s.objects = vec![ObjSpec {
        ka: 1.0,
        kd: 0.0,
        ..ObjSpec::new(mesh, Shading::Flat)
    }];
    s
}

fn core_mask<P: Profile>(pos: &'static [[i16; 3]; 3]) -> Vec<bool> {
    let frame = spec(pos).render::<P>().unwrap();
    // The near plane cuts the triangle into a polygon of three or four
    // corners, drawn as a fan of one or two triangles.
    assert_eq!(
        frame.stats.triangles as usize,
        screen_polygon(pos).len() - 2,
        "the triangle was clipped: {:?}",
        frame.stats
    );
    frame.covered
}

/// Exact screen polygon of the clipped triangle (f64), for distances.
fn screen_polygon(pos: &[[i16; 3]; 3]) -> Vec<[f64; 2]> {
    let k = H as f64 / 2.0 / (30.0f64.to_radians()).tan();
    let eye: Vec<[f64; 3]> = pos
        .iter()
        .map(|p| {
            [
                p[0] as f64 / 16384.0 - EYE[0],
                p[1] as f64 / 16384.0 - EYE[1],
                p[2] as f64 / 16384.0 - EYE[2],
            ]
        })
        .collect();
    let mut poly = vec![];
    for i in 0..3 {
        let (a, b) = (eye[i], eye[(i + 1) % 3]);
        let (da, db) = (-a[2] - NEAR, -b[2] - NEAR);
        if da >= 0.0 {
            poly.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            poly.push([
                a[0] + (b[0] - a[0]) * t,
                a[1] + (b[1] - a[1]) * t,
                a[2] + (b[2] - a[2]) * t,
            ]);
        }
    }
    poly.iter()
        .map(|p| {
            [
                W as f64 / 2.0 + k * p[0] / -p[2],
                H as f64 / 2.0 - k * p[1] / -p[2],
            ]
        })
        .collect()
}

fn distance_to_edges(poly: &[[f64; 2]], q: [f64; 2]) -> f64 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let t =
                (((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
            ((a[0] + t * dx - q[0]).powi(2) + (a[1] + t * dy - q[1]).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

fn ideal_mask(pos: &'static [[i16; 3]; 3]) -> Vec<bool> {
    spec(pos).render_ideal().1
}

#[test]
fn clipped_triangles_cover_the_reference_pixels() {
    for (n, pos) in CASES.iter().enumerate() {
        let want = ideal_mask(pos);
        let poly = screen_polygon(pos);
        assert!(
            want.iter().filter(|&&c| c).count() > 200,
            "case {n} covers the screen"
        );
        for (name, got) in [
            ("f64", core_mask::<F64>(pos)),
            ("precise", core_mask::<Precise>(pos)),
        ] {
            let mut mismatches = 0;
            for (i, (&g, &w)) in got.iter().zip(want.iter()).enumerate() {
                if g != w {
                    mismatches += 1;
                    let q = [(i as u32 % W) as f64 + 0.5, (i as u32 / W) as f64 + 0.5];
                    // Snapping moves each corner by at most 1/32 pixel per
                    // axis, an edge by at most sqrt(2)/32 < 0.045 pixel.
                    let d = distance_to_edges(&poly, q);
                    assert!(
                        d < 0.045,
                        "case {n} {name}: pixel {q:?} differs, {d} px from an edge"
                    );
                }
            }
            println!("case {n} {name}: {mismatches} pixels differ, all within snapping of an edge");
        }
    }
}

use super::{error_ulps, Rng};
use crate::mesh::{face_normal, normalize_q14, Crease};

#[test]
fn normalize_q14_bounds_and_symmetry() {
    assert_eq!(normalize_q14([0, 0, 0]), None);
    assert_eq!(normalize_q14([5, 0, 0]), Some([16384, 0, 0]));
    assert_eq!(normalize_q14([0, -1 << 40, 0]), Some([0, -16384, 0]));
    assert_eq!(normalize_q14([i64::MIN, 0, 0]), Some([-16384, 0, 0]));
    assert_eq!(normalize_q14([1, 1, 1]), Some([9459, 9459, 9459]));
    assert_eq!(normalize_q14([3, 4, 0]), Some([9830, 13107, 0]));
    let mut rng = Rng(12345);
    let mut worst = 0.0f64;
    for i in 0..20000 {
        let shift = i % 40;
        let v = [0, 1, 2].map(|_| (rng.next() as i64) >> (20 + shift));
        let Some(n) = normalize_q14(v) else { continue };
        assert_eq!(normalize_q14(v.map(|c| -c)), Some(n.map(|c| -c)));
        worst = worst.max(error_ulps(n, v.map(|c| c as f64)));
    }
    assert!(worst <= 0.50007, "worst {worst}");
}

#[test]
fn face_normal_matches_f64() {
    assert_eq!(face_normal([0; 3], [100, 0, 0], [0, 100, 0]), [0, 0, 16384]);
    assert_eq!(
        face_normal([0; 3], [0, 100, 0], [100, 0, 0]),
        [0, 0, -16384]
    );
    // Zero area: repeated and collinear corners.
    assert_eq!(face_normal([1, 2, 3], [1, 2, 3], [4, 5, 6]), [0; 3]);
    assert_eq!(face_normal([0; 3], [10, 20, 30], [-20, -40, -60]), [0; 3]);
    // Extreme coordinates: the cross product needs 34 bits.
    let (lo, hi) = (i16::MIN, i16::MAX);
    let n = face_normal([lo, lo, lo], [hi, lo, lo], [lo, hi, lo]);
    assert_eq!(n, [0, 0, 16384]);
    let mut rng = Rng(777);
    let mut worst = 0.0f64;
    for _ in 0..20000 {
        let p = [0, 1, 2].map(|_| [rng.i16(), rng.i16(), rng.i16()]);
        let d = |i: usize, k: usize| f64::from(p[i][k]) - f64::from(p[0][k]);
        // Exact in f64: |products| < 2^32, |differences| < 2^33.
        let c = [
            d(1, 1) * d(2, 2) - d(1, 2) * d(2, 1),
            d(1, 2) * d(2, 0) - d(1, 0) * d(2, 2),
            d(1, 0) * d(2, 1) - d(1, 1) * d(2, 0),
        ];
        let n = face_normal(p[0], p[1], p[2]);
        if c == [0.0; 3] {
            assert_eq!(n, [0; 3]);
        } else {
            worst = worst.max(error_ulps(n, c));
        }
    }
    assert!(worst <= 0.50007, "worst {worst}");
}

#[test]
fn crease_from_degrees_is_correctly_rounded() {
    assert_eq!(Crease::from_degrees(0), Crease::FLAT);
    assert_eq!(Crease::from_degrees(60).cos_q14(), 8192);
    assert_eq!(Crease::from_degrees(90).cos_q14(), 0);
    assert_eq!(Crease::from_degrees(120).cos_q14(), -8192);
    assert_eq!(Crease::from_degrees(180), Crease::SMOOTH);
    assert_eq!(Crease::from_degrees(1000), Crease::SMOOTH);
    assert_eq!(Crease::from_cos_q14(i16::MAX), Crease::FLAT);
    assert_eq!(Crease::from_cos_q14(i16::MIN), Crease::SMOOTH);
    for d in 0..=180u32 {
        let exact = 16384.0 * libm::cos(f64::from(d) * core::f64::consts::PI / 180.0);
        let got = f64::from(Crease::from_degrees(d).cos_q14());
        assert!(
            libm::fabs(got - exact) <= 0.5,
            "{d} degrees: {got} vs {exact}"
        );
    }
}

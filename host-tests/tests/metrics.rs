//! Tests of the frame metrics (hand-computed values on tiny frames), PNG
//! input/output, the difference heat map and the reference-image check.

use crate::support::TempDir;

use fixshade_host::image::{
    check_reference_in, diff_heatmap, heat_color, read_png, write_png, ReferenceError,
    COVERAGE_MISMATCH_COLOR,
};
use fixshade_host::metrics::{compare, FrameView, Metrics, MetricsError};

const A: [[u8; 3]; 4] = [[10, 20, 30], [0, 0, 0], [255, 255, 255], [100, 100, 100]];
// Channel differences to A: (2, 0, 3), (0, 0, 0), (5, 0, 0), (0, 1, 0).
const B: [[u8; 3]; 4] = [[12, 20, 27], [0, 0, 0], [250, 255, 255], [100, 101, 100]];
const ALL: [bool; 4] = [true; 4];

/// A 2 x 2 frame view.
fn view<'a>(rgb: &'a [[u8; 3]], covered: &'a [bool]) -> FrameView<'a> {
    FrameView {
        width: 2,
        height: 2,
        rgb,
        covered,
        object: None,
    }
}

#[test]
fn fully_covered_frames_give_the_hand_computed_metrics() {
    let m = compare(&view(&A, &ALL), &view(&B, &ALL)).expect("same size");
    assert_eq!(m.coverage_mismatch, 0);
    assert_eq!(m.max_abs_error, 5);
    // 11 levels over 12 channel values.
    assert_eq!(m.mean_abs_error, 11.0 / 12.0);
    // Two of four pixels have a channel off by more than 1.
    assert_eq!(m.share_over_1, 0.5);
    // MSE = (4 + 9 + 25 + 1) / 12 = 3.25; PSNR = 10 log10(65025 / 3.25).
    assert!((m.psnr_db - 43.012_0).abs() < 1e-4, "{}", m.psnr_db);
    assert!((m.psnr_db - 10.0 * (65025.0f64 / 3.25).log10()).abs() < 1e-12);
    assert_eq!(m.depth_order_disagreements, None);
}

#[test]
fn coverage_limits_the_error_statistics_but_not_psnr() {
    let a_cov = [true, true, false, true];
    let b_cov = [true, false, false, true];
    let m = compare(&view(&A, &a_cov), &view(&B, &b_cov)).expect("same size");
    assert_eq!(m.coverage_mismatch, 1);
    // Covered in both: pixels 0 and 3, differences (2, 0, 3) and (0, 1, 0).
    assert_eq!(m.max_abs_error, 3);
    assert_eq!(m.mean_abs_error, 1.0);
    assert_eq!(m.share_over_1, 0.5);
    assert!((m.psnr_db - 43.012_0).abs() < 1e-4);
    // Nothing covered in both: statistics are 0, mismatches counted.
    let none = [false; 4];
    let m = compare(&view(&A, &ALL), &view(&B, &none)).expect("same size");
    assert_eq!((m.coverage_mismatch, m.max_abs_error), (4, 0));
    assert_eq!((m.mean_abs_error, m.share_over_1), (0.0, 0.0));
}

#[test]
fn psnr_extremes() {
    let black = [[0u8; 3]; 4];
    let white = [[255u8; 3]; 4];
    let m = compare(&view(&black, &ALL), &view(&white, &ALL)).expect("same size");
    assert_eq!(m.psnr_db, 0.0);
    assert_eq!(
        (m.max_abs_error, m.mean_abs_error, m.share_over_1),
        (255, 255.0, 1.0)
    );
    let m = compare(&view(&A, &ALL), &view(&A, &ALL)).expect("same size");
    assert_eq!(m.psnr_db, f64::INFINITY);
    assert_eq!((m.max_abs_error, m.mean_abs_error), (0, 0.0));
}

#[test]
fn metrics_serialise_with_infinite_psnr_as_null() {
    let m = compare(&view(&A, &ALL), &view(&A, &ALL)).expect("same size");
    let json = serde_json::to_string(&m).expect("serialisable");
    assert_eq!(
        json,
        r#"{"coverage_mismatch":0,"max_abs_error":0,"mean_abs_error":0.0,"psnr_db":null,"share_over_1":0.0,"depth_order_disagreements":null}"#
    );
    let back: Metrics = serde_json::from_str(&json).expect("deserialisable");
    assert_eq!(back, m);
    let finite = compare(&view(&A, &ALL), &view(&B, &ALL)).expect("same size");
    let json = serde_json::to_string(&finite).expect("serialisable");
    assert!(json.contains(r#""psnr_db":43.01"#), "{json}");
    assert_eq!(
        serde_json::from_str::<Metrics>(&json).expect("round trip"),
        finite
    );
}

#[test]
fn object_ids_count_depth_order_disagreements() {
    let ids_a = [Some(0), Some(1), None, Some(2)];
    let ids_b = [Some(0), Some(2), Some(1), Some(1)];
    let cov = [true, true, false, true];
    let a = FrameView {
        object: Some(&ids_a),
        ..view(&A, &cov)
    };
    let b = FrameView {
        object: Some(&ids_b),
        ..view(&A, &cov)
    };
    // Pixels 1 and 3 disagree; pixel 2 is not covered.
    assert_eq!(
        compare(&a, &b).expect("ok").depth_order_disagreements,
        Some(2)
    );
    let no_ids = view(&A, &cov);
    assert_eq!(
        compare(&a, &no_ids).expect("ok").depth_order_disagreements,
        None
    );
}

#[test]
fn mismatched_sizes_and_buffers_are_errors() {
    let wide = FrameView {
        width: 4,
        height: 1,
        ..view(&A, &ALL)
    };
    assert_eq!(
        compare(&view(&A, &ALL), &wide).unwrap_err(),
        MetricsError::SizeMismatch {
            a: (2, 2),
            b: (4, 1)
        }
    );
    let short = view(&A[..3], &ALL);
    assert_eq!(
        compare(&view(&A, &ALL), &short).unwrap_err(),
        MetricsError::BufferLength {
            buffer: "b.rgb",
            expected: 4,
            actual: 3
        }
    );
    let bad_ids = FrameView {
        object: Some(&[None]),
        ..view(&A, &ALL)
    };
    assert!(compare(&bad_ids, &view(&A, &ALL)).is_err());
    assert!(diff_heatmap(&view(&A, &ALL), &short).is_err());
}

#[test]
fn heatmap_colours() {
    let a_cov = [true, true, false, true];
    let b_cov = [true, false, false, true];
    let map = diff_heatmap(&view(&A, &a_cov), &view(&B, &b_cov)).expect("same size");
    assert_eq!(
        map,
        vec![
            heat_color(3),
            COVERAGE_MISMATCH_COLOR,
            heat_color(5),
            heat_color(1)
        ]
    );
    assert_eq!(heat_color(0), [0, 0, 0]);
    assert_eq!(heat_color(1), [68, 1, 84]);
    assert_eq!(heat_color(255), [253, 231, 37]);
    // Brighter with larger errors (luminance within rounding), never black
    // or the coverage colour.
    let lum =
        |c: [u8; 3]| 0.2126 * f64::from(c[0]) + 0.7152 * f64::from(c[1]) + 0.0722 * f64::from(c[2]);
    for e in 1..=255u8 {
        let c = heat_color(e);
        assert!(c != [0, 0, 0] && c != COVERAGE_MISMATCH_COLOR);
        if e > 1 {
            assert!(lum(c) >= lum(heat_color(e - 1)) - 1.0, "{e}");
        }
    }
    assert!(lum(heat_color(2)) > lum(heat_color(1)) + 5.0);
}

#[test]
fn png_round_trip_leaves_no_temporary_file() {
    let dir = TempDir::new("host-png");
    let path = dir.join("a.png");
    let rgb: Vec<[u8; 3]> = (0..12u8).map(|i| [i * 20, 255 - i, i % 3 * 100]).collect();
    write_png(&path, 4, 3, &rgb).expect("written");
    let back = read_png(&path).expect("read");
    assert_eq!((back.width, back.height, back.pixels), (4, 3, rgb.clone()));
    let names: Vec<_> = std::fs::read_dir(&dir)
        .expect("dir")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("a.png")]);
    // Bad input: no file, an error.
    let err = write_png(dir.join("b.png"), 5, 3, &rgb).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    assert!(write_png(dir.join("c.png"), 0, 0, &[]).is_err());
    assert!(write_png(dir.join("missing/d.png"), 4, 3, &rgb).is_err());
    assert_eq!(std::fs::read_dir(&dir).expect("dir").count(), 1);
    std::fs::write(dir.join("junk.png"), b"not a png").expect("write");
    assert!(read_png(dir.join("junk.png")).is_err());
    assert!(read_png(dir.join("none.png")).is_err());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn read_png_converts_grey_and_rgba_to_rgb() {
    let dir = TempDir::new("host-colour-types");
    let cases: [(png::ColorType, &[u8]); 2] = [
        (png::ColorType::Grayscale, &[7, 200]),
        (png::ColorType::Rgba, &[1, 2, 3, 0, 4, 5, 6, 255]),
    ];
    let want = [[[7; 3], [200; 3]], [[1, 2, 3], [4, 5, 6]]];
    for ((color, data), want) in cases.into_iter().zip(want) {
        let path = dir.join("t.png");
        let file = std::fs::File::create(&path).expect("create");
        let mut enc = png::Encoder::new(std::io::BufWriter::new(file), 2, 1);
        enc.set_color(color);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().expect("header");
        w.write_image_data(data).expect("data");
        w.finish().expect("finish");
        assert_eq!(read_png(&path).expect("read").pixels, want.to_vec());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn reference_check_writes_a_three_panel_diff_on_mismatch() {
    let dir = TempDir::new("host-reference");
    let (images, diffs) = (dir.join("images"), dir.join("diff"));
    let check =
        |rgb: &[[u8; 3]], make| check_reference_in(&images, &diffs, "tiny", 2, 2, rgb, make);
    assert!(matches!(check(&A, false), Err(ReferenceError::Missing(_))));
    check(&A, true).expect("reference written");
    check(&A, false).expect("identical");
    let mut changed = A;
    changed[1] = [0, 0, 1];
    changed[2] = [0, 0, 0];
    let err = check(&changed, false).unwrap_err();
    let diff_path = diffs.join("tiny.png");
    match &err {
        ReferenceError::Mismatch { diff, differing } => {
            assert_eq!((diff, *differing), (&diff_path, 2))
        }
        other => panic!("unexpected {other:?}"),
    }
    let message = err.to_string();
    assert!(
        message.contains("2 pixels differ") && message.contains("tiny.png"),
        "{message}"
    );
    // expected | mask | actual, row by row.
    let panels = read_png(&diff_path).expect("diff written");
    assert_eq!((panels.width, panels.height), (6, 2));
    let (k, w) = ([0u8; 3], [255u8; 3]);
    let want = vec![
        A[0], A[1], k, w, changed[0], changed[1], A[2], A[3], w, k, changed[2], changed[3],
    ];
    assert_eq!(panels.pixels, want);
    // A later match removes the stale diff.
    check(&A, false).expect("identical again");
    assert!(!diff_path.exists());
    let too_wide = check_reference_in(&images, &diffs, "tiny", 4, 1, &A, false);
    assert!(matches!(
        too_wide,
        Err(ReferenceError::SizeMismatch {
            expected: (2, 2),
            actual: (4, 1),
            ..
        })
    ));
    for bad in ["", "../x", "a/b", "a b"] {
        let r = check_reference_in(&images, &diffs, bad, 2, 2, &A, true);
        assert!(matches!(r, Err(ReferenceError::InvalidName(_))), "{bad:?}");
    }
    assert!(matches!(
        check(&A[..3], false),
        Err(ReferenceError::BadImage(_))
    ));
    let _ = std::fs::remove_dir_all(&dir);
}

//! Bad input gives an error value, never a panic.

use fixshade_host::ideal::{render, IdealError, IdealScene, LightKind, Shading};

use super::{camera, light, matte, object, scene, square, tri};

/// A small valid scene with one light and one square.
fn valid() -> IdealScene {
    let mut s = scene(8, 6, camera([0.0, 0.0, 3.0], [0.0; 3], 60.0, 0.1));
    s.lights.push(light(LightKind::Directional {
        direction: [0.0, 0.0, 1.0],
    }));
    s.objects.push(object(
        square(-1.0, -1.0, 1.0, 1.0, 0.0),
        Shading::Phong,
        matte(),
        true,
    ));
    s
}

/// Renders `valid()` after `edit` and returns the error.
fn error_after(edit: impl FnOnce(&mut IdealScene)) -> IdealError {
    let mut s = valid();
    edit(&mut s);
    render(&s).expect_err("scene should be rejected")
}

#[test]
fn the_valid_scene_renders() {
    assert!(render(&valid()).expect("valid").covered_count() > 0);
}

#[test]
fn camera_errors() {
    for fov in [0.0, 180.0, -10.0, 200.0] {
        assert_eq!(
            error_after(|s| s.camera.fov_y_deg = fov),
            IdealError::FieldOfView(fov)
        );
    }
    assert_eq!(error_after(|s| s.camera.near = 0.0), IdealError::Near(0.0));
    assert_eq!(
        error_after(|s| s.camera.near = -1.0),
        IdealError::Near(-1.0)
    );
    assert_eq!(
        error_after(|s| s.camera.far = Some(0.05)),
        IdealError::Far {
            near: 0.1,
            far: 0.05
        }
    );
    assert_eq!(
        error_after(|s| s.camera.target = s.camera.eye),
        IdealError::EyeAtTarget
    );
    assert_eq!(
        error_after(|s| s.camera.up = [0.0, 0.0, -2.0]),
        IdealError::UpParallel
    );
    assert_eq!(
        error_after(|s| s.camera.up = [0.0; 3]),
        IdealError::UpParallel
    );
}

#[test]
fn non_finite_values_are_named() {
    let e = error_after(|s| s.objects[0].triangles[1][2].position[0] = f64::NAN);
    assert_eq!(
        e,
        IdealError::NonFinite("objects[0].triangles[1][2].position".into())
    );
    let e = error_after(|s| s.objects[0].triangles[0][0].normal[1] = f64::INFINITY);
    assert_eq!(
        e,
        IdealError::NonFinite("objects[0].triangles[0][0].normal".into())
    );
    let e = error_after(|s| s.camera.eye[2] = f64::NEG_INFINITY);
    assert_eq!(e, IdealError::NonFinite("camera.eye".into()));
    let e = error_after(|s| s.camera.fov_y_deg = f64::NAN);
    assert_eq!(e, IdealError::NonFinite("camera.fov_y_deg".into()));
    let e = error_after(|s| s.lights[0].intensity = f64::NAN);
    assert_eq!(e, IdealError::NonFinite("lights[0].intensity".into()));
    let e = error_after(|s| s.objects[0].material.ks = f64::NAN);
    assert_eq!(e, IdealError::NonFinite("objects[0].material.ks".into()));
    let e = error_after(|s| s.ambient = f64::NAN);
    assert_eq!(e, IdealError::NonFinite("ambient".into()));
    assert!(e.to_string().contains("ambient"));
}

#[test]
fn light_and_material_errors() {
    let e = error_after(|s| {
        s.lights[0].kind = LightKind::Directional {
            direction: [0.0; 3],
        }
    });
    assert_eq!(e, IdealError::ZeroLightDirection(0));
    let e = error_after(|s| s.objects[0].material.shininess = -1.0);
    assert_eq!(
        e,
        IdealError::Shininess {
            object: 0,
            value: -1.0
        }
    );
}

#[test]
fn frame_size_limits() {
    let e = error_after(|s| (s.width, s.height) = (u32::MAX, u32::MAX));
    assert_eq!(
        e,
        IdealError::FrameTooLarge {
            width: u32::MAX,
            height: u32::MAX
        }
    );
    for (w, h) in [(0, 0), (0, 5), (5, 0)] {
        let mut s = valid();
        (s.width, s.height) = (w, h);
        let frame = render(&s).expect("empty frames are allowed");
        assert_eq!((frame.width, frame.height), (w, h));
        assert!(frame.color.is_empty() && frame.covered.is_empty());
        assert!(frame.depth.is_empty() && frame.object.is_empty());
    }
}

#[test]
fn huge_but_finite_coordinates_do_not_panic() {
    let mut s = valid();
    let big = 1e300;
    s.objects.push(object(
        vec![tri(
            [[-big, -big, -1.0], [big, -big, -1.0], [0.0, big, -1.0]],
            [0.0, 0.0, 1.0],
        )],
        Shading::Phong,
        matte(),
        true,
    ));
    match render(&s) {
        Ok(frame) => assert_eq!(frame.color.len(), 48),
        Err(e) => assert_eq!(e, IdealError::Overflow),
    }
}

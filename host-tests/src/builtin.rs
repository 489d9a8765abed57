//! The built-in scenes: the TOML files of `host-tests/scenes/`, embedded.
//!
//! They reproduce the demonstrations of the project's seeds: the
//! dodecahedron under several shininess values and light positions in
//! Phong, Gouraud and flat shading, the can of pop flat and smooth, the hot spot
//! on a bent grid, a light close to a big face, cubes and a sphere, and the
//! bunny benchmark scene. All are small (at most 240x240) and quick to
//! render with the ideal reference.

use crate::scene_file::{SceneDesc, SceneError};

/// `(name, description, TOML text)` of every built-in scene.
const SCENES: &[(&str, &str, &str)] = &[
    (
        "dodeca-phong-n1",
        "Dodecahedron, smooth normals, Phong, shininess 1, point light at (0, 0, 2)",
        include_str!("../scenes/dodeca-phong-n1.toml"),
    ),
    (
        "dodeca-phong-n10",
        "Dodecahedron, smooth normals, Phong, shininess 10, point light at (0, 0, 2)",
        include_str!("../scenes/dodeca-phong-n10.toml"),
    ),
    (
        "dodeca-phong-n25",
        "Dodecahedron, smooth normals, Phong, shininess 25, point light at (0, 0, 2)",
        include_str!("../scenes/dodeca-phong-n25.toml"),
    ),
    (
        "dodeca-phong-n100",
        "Dodecahedron, smooth normals, Phong, shininess 100, point light at (0, 0, 2)",
        include_str!("../scenes/dodeca-phong-n100.toml"),
    ),
    (
        "dodeca-phong-n800",
        "Dodecahedron, smooth normals, Phong, shininess 800, point light at (0, 0, 2)",
        include_str!("../scenes/dodeca-phong-n800.toml"),
    ),
    (
        "dodeca-gouraud-n100",
        "Dodecahedron, smooth normals, Gouraud, shininess 100, point light at (0, 0, 2)",
        include_str!("../scenes/dodeca-gouraud-n100.toml"),
    ),
    (
        "dodeca-gouraud-n800",
        "Dodecahedron, smooth normals, Gouraud, shininess 800, point light at (0, 0, 2)",
        include_str!("../scenes/dodeca-gouraud-n800.toml"),
    ),
    (
        "dodeca-flat-n100",
        "Dodecahedron, flat faces, flat shading, shininess 100, point light at (0, 0, 2)",
        include_str!("../scenes/dodeca-flat-n100.toml"),
    ),
    (
        "dodeca-phong-light-2-2-2",
        "Dodecahedron, smooth normals, Phong, shininess 100, point light at (2, 2, 2)",
        include_str!("../scenes/dodeca-phong-light-2-2-2.toml"),
    ),
    (
        "dodeca-phong-light-20-0-20",
        "Dodecahedron, smooth normals, Phong, shininess 100, point light at (20, 0, 20)",
        include_str!("../scenes/dodeca-phong-light-20-0-20.toml"),
    ),
    (
        "dodeca-phong-light-2-0-2",
        "Dodecahedron, smooth normals, Phong, shininess 100, point light at (2, 0, 2)",
        include_str!("../scenes/dodeca-phong-light-2-0-2.toml"),
    ),
    (
        "can-flat",
        "Can of pop, flat shading: one colour per triangle",
        include_str!("../scenes/can-flat.toml"),
    ),
    (
        "can-smooth",
        "Can of pop, Gouraud shading with smooth sides and flat caps",
        include_str!("../scenes/can-smooth.toml"),
    ),
    (
        "grid-hotspot-gouraud",
        "Bent 9x9 grid, point light close above a cell, Gouraud: misses the hot spot",
        include_str!("../scenes/grid-hotspot-gouraud.toml"),
    ),
    (
        "grid-hotspot-phong",
        "Bent 9x9 grid, point light close above a cell, Phong: shows the hot spot",
        include_str!("../scenes/grid-hotspot-phong.toml"),
    ),
    (
        "big-face-gouraud",
        "Cube face lit by a point light just in front of its centre, Gouraud: dim",
        include_str!("../scenes/big-face-gouraud.toml"),
    ),
    (
        "big-face-phong",
        "Cube face lit by a point light just in front of its centre, Phong: bright centre",
        include_str!("../scenes/big-face-phong.toml"),
    ),
    (
        "cubes-and-sphere",
        "Three cubes and a sphere, different materials and shadings, two lights",
        include_str!("../scenes/cubes-and-sphere.toml"),
    ),
    (
        "bunny-gouraud",
        "Bunny benchmark: 240x240 RGB565, I = 0.2 + 0.8 max(0, N.L), Gouraud",
        include_str!("../scenes/bunny-gouraud.toml"),
    ),
    (
        "bunny-flat",
        "Bunny benchmark: 240x240 RGB565, I = 0.2 + 0.8 max(0, N.L), flat shading",
        include_str!("../scenes/bunny-flat.toml"),
    ),
];

/// Every built-in scene as `(name, description, TOML text)`, in a fixed
/// order.
pub fn builtin_scenes() -> &'static [(&'static str, &'static str, &'static str)] {
    SCENES
}

/// Loads the built-in scene `name`. Errors name the file as
/// `builtin:NAME`; an unknown name gives an error listing the known ones.
pub fn load_builtin(name: &str) -> Result<SceneDesc, SceneError> {
    let Some((_, _, text)) = SCENES.iter().find(|(n, _, _)| *n == name) else {
        let known: Vec<&str> = SCENES.iter().map(|(n, _, _)| *n).collect();
        return Err(SceneError::file(
            &format!("builtin:{name}"),
            format!("no such built-in scene; known scenes: {}", known.join(", ")),
        ));
    };
    SceneDesc::from_toml(text, &format!("builtin:{name}"), None)
}

//! Firmwares that hold some of the scenes only, sized for them alone: the
//! scenes picked from [`crate::generated`] by name at compile time, their
//! storage ([`Capacity::max`] of theirs), width and depth band computed
//! from them by `const fn`s.
//!
//! [`dodeca`]: the dodecahedron scenes (feature `dodeca` of this crate
//! and of the firmware, `cargo build --release --features dodeca` in
//! `examples/firmware`). One convex object with back faces culled needs
//! no depth band; its 36 triangles need 1 368 bytes of storage at most
//! (Phong with the eye position, the widest of the three), so the static
//! RAM is the colour band, that storage and the pool:
//!
//! | part | bytes |
//! |------|------:|
//! | colour band: 160 px × 8 rows × 2 (RGB565) | 2 560 |
//! | storage ([`dodeca::CAPACITY`], `Capacity::bytes(4)`) | 1 368 |
//! | pool: 12 slots of 7 values ([`dodeca::DodecaPool`]) | `size_of` (about 2 100) |
//! | total, within the 8 KB = 8 192 bytes budget | about 6 100 |
//!
//! (The tests check the sum against 8 192 bytes less 512 for the rest of
//! the firmware's `.data` and `.bss`; `.ci/firmware` checks the ELF's.)

use crate::generated;
use crate::SceneSpec;
use fixshade::render::Capacity;

/// Whether `name` starts with `prefix`.
const fn starts_with(name: &str, prefix: &str) -> bool {
    let (n, p) = (name.as_bytes(), prefix.as_bytes());
    if n.len() < p.len() {
        return false;
    }
    let mut i = 0;
    while i < p.len() {
        if n[i] != p[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// Scenes of [`generated::SCENES`] whose name starts with `prefix`.
const fn count(prefix: &str) -> usize {
    let mut n = 0;
    let mut i = 0;
    while i < generated::SCENES.len() {
        if starts_with(generated::SCENES[i].name, prefix) {
            n += 1;
        }
        i += 1;
    }
    n
}

/// The `N` scenes whose name starts with `prefix`, in order.
const fn pick<const N: usize>(prefix: &str) -> [SceneSpec; N] {
    let mut out = [generated::SCENES[0]; N];
    let mut n = 0;
    let mut i = 0;
    while i < generated::SCENES.len() {
        if starts_with(generated::SCENES[i].name, prefix) {
            assert!(n < N, "more scenes than counted");
            out[n] = generated::SCENES[i];
            n += 1;
        }
        i += 1;
    }
    assert!(n == N, "fewer scenes than counted");
    out
}

/// The storage of `scenes` (each part's largest).
const fn capacity(scenes: &[SceneSpec]) -> Capacity {
    let mut c = Capacity::EMPTY;
    let mut i = 0;
    while i < scenes.len() {
        c = c.max(scenes[i].capacity);
        i += 1;
    }
    c
}

/// Whether some scene of `scenes` needs a depth band.
const fn depth(scenes: &[SceneSpec]) -> bool {
    let mut i = 0;
    while i < scenes.len() {
        if scenes[i].depth {
            return true;
        }
        i += 1;
    }
    false
}

/// The widest of `scenes`, pixels.
const fn width(scenes: &[SceneSpec]) -> u32 {
    let mut w = 0;
    let mut i = 0;
    while i < scenes.len() {
        if scenes[i].width > w {
            w = scenes[i].width;
        }
        i += 1;
    }
    w
}

/// The dodecahedron scenes alone (feature `dodeca`).
pub mod dodeca {
    use super::SceneSpec;
    use fixshade::render::{Capacity, Pool};

    const PREFIX: &str = "dodeca-";
    const N: usize = super::count(PREFIX);
    const PICKED: [SceneSpec; N] = super::pick::<N>(PREFIX);

    /// The dodecahedron scenes, in the firmware's order.
    pub static SCENES: [SceneSpec; N] = PICKED;
    /// Their storage.
    pub const CAPACITY: Capacity = super::capacity(&PICKED);
    /// Whether one needs a depth band (not one convex object culled).
    pub const DEPTH: bool = super::depth(&PICKED);
    /// The widest, pixels: the colour band's width.
    pub const WIDTH: u32 = super::width(&PICKED);
    /// Rows per band: 8 (a 2 560-byte colour band at 160 pixels; the
    /// frame is the same for every band height).
    pub const BAND_ROWS: u32 = 8;
    /// Active triangles kept from band to band: at most 10 cross a band
    /// border in these scenes (checked by the tests, with 8- and 16-row
    /// bands); fewer slots would only set some triangles up again (the
    /// same bytes).
    pub const POOL_SLOTS: usize = 12;
    /// Values a slot holds: 7 (depth, normal and eye position of
    /// `dodeca-phong-n100`).
    pub const POOL_VALUES: usize = 7;
    /// The pool of such a firmware.
    pub type DodecaPool = Pool<i32, POOL_SLOTS, POOL_VALUES>;
    /// Bytes of the colour band.
    pub const BAND_BYTES: usize = (WIDTH * BAND_ROWS) as usize * 2;
    /// Bytes the firmware's statics hold for the scenes: the colour band,
    /// the depth band (none), the storage and the pool.
    pub const STATIC_BYTES: usize = BAND_BYTES
        + if DEPTH { BAND_BYTES } else { 0 }
        + CAPACITY.bytes(4)
        + core::mem::size_of::<DodecaPool>();
}

#[cfg(test)]
mod tests {
    use super::dodeca;
    use crate::profiled::raster_bands;
    use crate::{generated, Pixel};
    use fixshade::num::Fast;
    use fixshade::render::{prepare, Storage};
    use fixshade::target::Depth16;
    use std::{boxed::Box, vec};

    #[test]
    fn the_dodecahedron_alone_fits_8_kb() {
        let names: std::vec::Vec<_> = dodeca::SCENES.iter().map(|s| s.name).collect();
        assert_eq!(
            names,
            [
                "dodeca-flat-n100",
                "dodeca-gouraud-n100",
                "dodeca-phong-n100"
            ]
        );
        const { assert!(!dodeca::DEPTH) };
        assert_eq!(dodeca::WIDTH, 160);
        assert_eq!(dodeca::BAND_BYTES, 2560);
        assert_eq!(dodeca::CAPACITY.bytes(4), 1368);
        // The statics other than storage, pool and band (a few hundred
        // bytes) must fit in what is left of 8 KB.
        const { assert!(dodeca::STATIC_BYTES <= 8192 - 512) };
    }

    /// At most [`dodeca::POOL_SLOTS`] triangles active at once in each
    /// scene, in the dodeca build's band height and in 16-row bands (the
    /// peak measured with the default build's larger pool: with a pool of
    /// at least the peak, each triangle is set up once), and the same
    /// frame in both.
    #[test]
    fn the_dodeca_pool_holds_every_active_triangle() {
        const C: fixshade::render::Capacity = dodeca::CAPACITY;
        let mut st = Box::new(Storage::<i32, { C.vertices }, { C.values }, { C.triangles }>::new());
        let mut pool = Box::new(crate::BandPool::new());
        for spec in dodeca::SCENES.iter() {
            let full = generated::SCENES
                .iter()
                .find(|s| s.name == spec.name)
                .unwrap();
            assert_eq!(spec.capacity, full.capacity);
            let mut crcs = vec![];
            for rows in [dodeca::BAND_ROWS, 16] {
                let parts = crate::profiled::Parts::<fixshade::num::Q16>::new(spec);
                let scene = parts.scene(spec, parts.camera.unwrap());
                let (ws, order) = st.split();
                let frame = prepare::<Fast>(&scene, spec.width, spec.height, ws).unwrap();
                let mut px = vec![[0u8; 2] as Pixel; (spec.width * rows) as usize];
                let s = raster_bands::<Fast, Depth16, _>(
                    &frame,
                    &scene,
                    &mut px,
                    None,
                    rows,
                    order,
                    &mut pool,
                    &mut crate::NoProbe,
                )
                .unwrap();
                assert!(s.active_peak as usize <= dodeca::POOL_SLOTS, "{s:?}");
                assert_eq!(s.setups, s.triangles, "{}", spec.name);
                crcs.push(s.crc);
            }
            assert_eq!(crcs[0], crcs[1], "{}", spec.name);
        }
    }
}

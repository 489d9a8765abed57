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

/// The bunny Gouraud benchmark scene alone (feature `bunny`): the
/// firmware the RAM budget of a prepared bunny frame is measured in.
/// Storage for one Gouraud object with a grey level (two values per
/// vertex: [`bunny::CAPACITY`] is the scene's own), a depth band (the
/// bunny is not convex), 8-row bands and a pool sized by the measured
/// peak of active triangles:
///
/// | part | bytes |
/// |------|------:|
/// | colour band: 240 px × 8 rows × 2 (RGB565) | 3 840 |
/// | depth band: 240 px × 8 rows × 2 (16-bit) | 3 840 |
/// | storage: 1 839 vertices × (8 + 2 × 4) + 3 674 triangles × (14 + 4) | 95 556 |
/// | pool: 62 slots of 2 values, 88 + 4 bytes each ([`bunny::BunnyPool`]) | 5 704 |
/// | total | 108 940 |
///
/// The budget is 40 KB = 40 960 bytes; the storage alone exceeds it (the
/// tests check these figures).
pub mod bunny {
    use super::SceneSpec;
    use fixshade::render::{Capacity, Pool};

    const PREFIX: &str = "bunny-gouraud";
    const N: usize = super::count(PREFIX);
    const PICKED: [SceneSpec; N] = super::pick::<N>(PREFIX);

    /// The bunny Gouraud scene.
    pub static SCENES: [SceneSpec; N] = PICKED;
    /// Its storage.
    pub const CAPACITY: Capacity = super::capacity(&PICKED);
    /// Whether it needs a depth band (yes: the bunny is not convex).
    pub const DEPTH: bool = super::depth(&PICKED);
    /// Its width, pixels: the colour band's width.
    pub const WIDTH: u32 = super::width(&PICKED);
    /// Rows per band: 8 (3 840 bytes of colour band and as many of depth
    /// band at 240 pixels; the frame is the same for every band height).
    pub const BAND_ROWS: u32 = 8;
    /// Active triangles kept from band to band: 62, the peak in 8-row
    /// bands (checked by the tests; 55 in 16-row bands); fewer slots would
    /// only set some triangles up again (the same bytes).
    pub const POOL_SLOTS: usize = 62;
    /// Values a slot holds: 2 (depth and grey level).
    pub const POOL_VALUES: usize = 2;
    /// The pool of such a firmware.
    pub type BunnyPool = Pool<i32, POOL_SLOTS, POOL_VALUES>;
    /// Bytes of the colour band.
    pub const BAND_BYTES: usize = (WIDTH * BAND_ROWS) as usize * 2;
    /// Bytes the firmware's statics hold for the scene: the colour band,
    /// the depth band, the storage and the pool.
    pub const STATIC_BYTES: usize = BAND_BYTES
        + if DEPTH { BAND_BYTES } else { 0 }
        + CAPACITY.bytes(4)
        + core::mem::size_of::<BunnyPool>();
}

#[cfg(test)]
mod tests {
    use super::dodeca;
    use crate::profiled::{depth_in, raster_bands_in};
    use crate::Pixel;
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
    /// frame in both. (Not in the `bunny` build: its pool holds 2 values.)
    #[test]
    #[cfg(not(feature = "bunny"))]
    fn the_dodeca_pool_holds_every_active_triangle() {
        const C: fixshade::render::Capacity = dodeca::CAPACITY;
        let mut st = Box::new(Storage::<i32, { C.vertices }, { C.values }, { C.triangles }>::new());
        let mut pool = Box::new(crate::BandPool::new());
        for spec in dodeca::SCENES.iter() {
            let full = crate::generated::SCENES
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
                let mut px = vec![0u16 as Pixel; (spec.width * rows) as usize];
                let (z, with_depth) = depth_in(None);
                let s = raster_bands_in::<Fast, Depth16, _>(
                    &frame,
                    &scene,
                    &mut px,
                    z,
                    with_depth,
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

    /// The bunny alone: its prepared frame (exact bytes), the pool's peak
    /// in 8-row bands (each triangle set up once), the same frame as in
    /// 16-row bands, and its static RAM. (Not in the `dodeca` build: its
    /// pool has 12 slots.)
    #[test]
    #[cfg(not(feature = "dodeca"))]
    fn the_bunny_alone_and_its_prepared_frame() {
        use super::bunny;
        let names: std::vec::Vec<_> = bunny::SCENES.iter().map(|s| s.name).collect();
        assert_eq!(names, ["bunny-gouraud"]);
        const { assert!(bunny::DEPTH) };
        assert_eq!(bunny::WIDTH, 240);
        assert_eq!(bunny::BAND_BYTES, 3840);
        // 1 839 vertices × (8 + 2 × 4) + 3 674 triangles × (14 + 4).
        assert_eq!(bunny::CAPACITY.bytes(4), 1839 * 16 + 3674 * 18);
        assert_eq!(bunny::CAPACITY.bytes(4), 95_556);
        assert_eq!(
            core::mem::size_of::<bunny::BunnyPool>(),
            bunny::POOL_SLOTS * 92
        );
        assert_eq!(bunny::STATIC_BYTES, 2 * 3840 + 95_556 + 62 * 92);
        assert_eq!(bunny::STATIC_BYTES, 108_940);
        const C: fixshade::render::Capacity = bunny::CAPACITY;
        let mut st = Box::new(Storage::<i32, { C.vertices }, { C.values }, { C.triangles }>::new());
        // The build's pool: 56 slots by default (the peak it reports is
        // the bunny build's need), 62 with the feature `bunny`.
        let mut pool = Box::new(crate::BandPool::new());
        let spec = &bunny::SCENES[0];
        let mut crcs = vec![];
        for rows in [bunny::BAND_ROWS, 16] {
            let parts = crate::profiled::Parts::<fixshade::num::Q16>::new(spec);
            let scene = parts.scene(spec, parts.camera.unwrap());
            let (ws, order) = st.split();
            let frame = prepare::<Fast>(&scene, spec.width, spec.height, ws).unwrap();
            // 1 839 vertices × (8 bytes xy + 2 values × 4) + 1 498 kept
            // triangles × 14.
            assert_eq!(frame.vertex_count(), 1839);
            assert_eq!(frame.triangle_count(), 1498);
            assert_eq!(frame.bytes_used(), 1839 * 16 + 1498 * 14);
            assert_eq!(frame.bytes_used(), 50_396);
            let mut px = vec![0u16 as Pixel; (spec.width * rows) as usize];
            let mut z = vec![0u16; (spec.width * rows) as usize];
            let s = raster_bands_in::<Fast, Depth16, _>(
                &frame,
                &scene,
                &mut px,
                &mut z,
                true,
                rows,
                order,
                &mut pool,
                &mut crate::NoProbe,
            )
            .unwrap();
            if rows == bunny::BAND_ROWS {
                // 62 triangles active at once in 8-row bands: the 56 slots
                // of the default build set 8 up twice, the bunny build's
                // 62 each once.
                assert_eq!(s.active_peak as usize, bunny::POOL_SLOTS, "{s:?}");
                let again = if cfg!(feature = "bunny") { 0 } else { 8 };
                assert_eq!(s.setups, s.triangles + again, "{s:?}");
            }
            crcs.push(s.crc);
        }
        assert_eq!(crcs[0], crcs[1]);
        assert_eq!(crcs[0], 0x1a5e_2025);
    }
}

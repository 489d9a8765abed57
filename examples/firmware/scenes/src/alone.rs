//! Firmwares that hold some of the scenes only, sized for them alone: the
//! scenes picked from [`crate::generated`] by name at compile time, their
//! storage ([`Capacity::max`] of theirs), width and depth band computed
//! from them by `const fn`s.
//!
//! [`dodeca`]: the dodecahedron scenes (feature `dodeca` of this crate
//! and of the firmware, `cargo build --release --features dodeca` in
//! `examples/firmware`). One convex object with back faces culled needs
//! no depth band; its 20 vertices and 36 triangles need 856 bytes of
//! storage at most (Phong with the eye position, the widest of the three:
//! 20 × (4 + 7 × 4) for the vertices, 36 × (1 + 2) for the triangle
//! numbers' bytes and order entries, 36 × 3 for the flat scene's
//! colours), so the static RAM is the colour band, that storage and the
//! pool:
//!
//! | part | bytes |
//! |------|------:|
//! | colour band: 160 px × 8 rows × 2 (RGB565) | 2 560 |
//! | storage ([`dodeca::CAPACITY`], `Capacity::bytes(4)`) | 856 |
//! | pool: 12 slots of 7 values ([`dodeca::DodecaPool`]) | `size_of` (about 2 100) |
//! | total, within the 8 KB = 8 192 bytes budget | about 5 300 |
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

/// What a firmware built for some of the scenes alone holds, derived from
/// the scenes and the band and pool chosen for them ([`Alone::of`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Alone {
    /// The scenes' storage (each part's largest).
    pub capacity: Capacity,
    /// Whether one needs a depth band (not one convex object culled).
    pub depth: bool,
    /// The widest, pixels: the colour band's width.
    pub width: u32,
    /// Bytes of the colour band: `width × band rows × 2` (RGB565).
    pub band_bytes: usize,
    /// Bytes the firmware's statics hold for the scenes: the colour band,
    /// the depth band (as many bytes, 16-bit depth, when `depth`), the
    /// storage in `fast` ([`Capacity::in_profile`], [`Capacity::bytes`]
    /// with 4-byte values) and the pool.
    pub static_bytes: usize,
}

impl Alone {
    /// The firmware of `scenes` in bands of `band_rows` rows with a pool
    /// of `pool_bytes` bytes.
    pub const fn of(scenes: &[SceneSpec], band_rows: u32, pool_bytes: usize) -> Self {
        let (capacity, depth, width) = (capacity(scenes), depth(scenes), width(scenes));
        let band_bytes = (width * band_rows) as usize * 2;
        Self {
            capacity,
            depth,
            width,
            band_bytes,
            static_bytes: band_bytes
                + if depth { band_bytes } else { 0 }
                + capacity.in_profile::<fixshade::num::Fast>().bytes(4)
                + pool_bytes,
        }
    }
}

/// A module of the scenes whose name starts with a prefix, with the band
/// height and pool chosen for them and what follows ([`Alone::of`]):
/// `SCENES`, `BAND_ROWS`, `POOL_SLOTS`, `POOL_VALUES`, the pool type,
/// `FIRMWARE` and its parts `CAPACITY`, `DEPTH`, `WIDTH`, `BAND_BYTES`,
/// `STATIC_BYTES`.
macro_rules! alone {
    (
        $(#[$doc:meta])*
        pub mod $name:ident {
            prefix: $prefix:literal,
            $(#[$rows_doc:meta])* band_rows: $rows:expr,
            $(#[$slots_doc:meta])* pool_slots: $slots:expr,
            $(#[$values_doc:meta])* pool_values: $values:expr,
            $(#[$pool_doc:meta])* pool: $pool:ident,
        }
    ) => {
        $(#[$doc])*
        pub mod $name {
            use super::{Alone, SceneSpec};
            use fixshade::render::{Capacity, Pool};

            const N: usize = super::count($prefix);
            const PICKED: [SceneSpec; N] = super::pick::<N>($prefix);

            /// The scenes, in the firmware's order.
            pub static SCENES: [SceneSpec; N] = PICKED;
            $(#[$rows_doc])*
            pub const BAND_ROWS: u32 = $rows;
            $(#[$slots_doc])*
            pub const POOL_SLOTS: usize = $slots;
            $(#[$values_doc])*
            pub const POOL_VALUES: usize = $values;
            $(#[$pool_doc])*
            pub type $pool = Pool<i32, POOL_SLOTS, POOL_VALUES>;
            /// The firmware's statics for the scenes.
            pub const FIRMWARE: Alone =
                Alone::of(&PICKED, BAND_ROWS, core::mem::size_of::<$pool>());
            /// Their storage ([`Alone::capacity`]).
            pub const CAPACITY: Capacity = FIRMWARE.capacity;
            /// Whether one needs a depth band ([`Alone::depth`]).
            pub const DEPTH: bool = FIRMWARE.depth;
            /// The widest, pixels ([`Alone::width`]).
            pub const WIDTH: u32 = FIRMWARE.width;
            /// Bytes of the colour band ([`Alone::band_bytes`]).
            pub const BAND_BYTES: usize = FIRMWARE.band_bytes;
            /// Bytes of the statics for the scenes ([`Alone::static_bytes`]).
            pub const STATIC_BYTES: usize = FIRMWARE.static_bytes;
        }
    };
}

alone! {
    /// The dodecahedron scenes alone (feature `dodeca`).
    pub mod dodeca {
        prefix: "dodeca-",
        /// Rows per band: 8 (a 2 560-byte colour band at 160 pixels; the
        /// frame is the same for every band height).
        band_rows: 8,
        /// Active triangles kept from band to band: at most 10 cross a band
        /// border in these scenes (checked by the tests, with 8- and 16-row
        /// bands); fewer slots would only set some triangles up again (the
        /// same bytes).
        pool_slots: 12,
        /// Values a slot holds: 7 (depth, normal and eye position of
        /// `dodeca-phong-n100`).
        pool_values: 7,
        /// The pool of such a firmware.
        pool: DodecaPool,
    }
}

alone! {
    /// The bunny Gouraud benchmark scene alone (feature `bunny`): the
    /// firmware the RAM budget of a prepared bunny frame is measured in.
    /// Storage for one Gouraud object with a grey level (in `fast` one
    /// value per vertex, depth and level packed: [`bunny::CAPACITY`] in
    /// `fast`, the scene's own), a depth band (the bunny is not convex),
    /// 8-row bands and a pool sized by the measured peak of active
    /// triangles:
    ///
    /// | part | bytes |
    /// |------|------:|
    /// | colour band: 240 px × 8 rows × 2 (RGB565) | 3 840 |
    /// | depth band: 240 px × 8 rows × 2 (16-bit) | 3 840 |
    /// | storage: 1 839 vertices × (4 + 4) + 3 674 triangle numbers × (1 + 2), rounded to 4 | 25 736 |
    /// | pool: 62 slots of 2 values, 112 + 4 bytes each ([`bunny::BunnyPool`]: the walk, 88, kept unpacked) | 7 192 |
    /// | total, within the 40 KB = 40 960 bytes budget | 40 608 |
    ///
    /// The storage's parts: screen positions 1 839 × 4 = 7 356 (`i16`
    /// subpixels, [`fixshade::render::ScreenXy`]), values 1 839 × 4 =
    /// 7 356 (depth and grey level, 16 bits each), a byte per mesh
    /// triangle 3 674 (whether the view keeps it, its first row, whether
    /// it is a back face: no copy of the mesh's triangles, whose vertices
    /// the frame reads from the mesh in flash) and the band order 3 674 ×
    /// 2 = 7 348 (the kept triangles by band, 1 498 here, and in the rest
    /// the queue of those put off while the pool is full); no made
    /// triangle (the bunny lies inside the clipping planes, culled) and no
    /// colour (Gouraud). The tests check these figures. The prepared frame
    /// itself is 18 386 bytes (7 356 + 7 356 + 3 674).
    pub mod bunny {
        prefix: "bunny-gouraud",
        /// Rows per band: 8 (3 840 bytes of colour band and as many of depth
        /// band at 240 pixels; the frame is the same for every band height).
        band_rows: 8,
        /// Active triangles kept from band to band: 62, the peak in 8-row
        /// bands (checked by the tests; 55 in 16-row bands); fewer slots would
        /// only set some triangles up again (the same bytes).
        pool_slots: 62,
        /// Values a slot holds: 2 (depth and grey level).
        pool_values: 2,
        /// The pool of such a firmware.
        pool: BunnyPool,
    }
}

#[cfg(test)]
mod tests {
    use super::dodeca;
    use crate::profiled::raster_bands_in;
    use crate::Pixel;
    use fixshade::num::Fast;
    use fixshade::render::prepare;
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
        assert_eq!(dodeca::CAPACITY.bytes(4), 856);
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
        let mut st = Box::new(<fixshade::storage!(i32, C)>::new());
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
                let (z, with_depth) = crate::profiled::depth_in(None);
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
        // 1 839 vertices × (4 + 4: depth and grey level packed in one
        // value) + 3 674 triangle numbers × (1 byte + a 2-byte order
        // entry), no triangle made (inside the clipping planes, culled),
        // rounded up to 4 bytes; 2 values a vertex in the profiles that do
        // not pack.
        const C: fixshade::render::Capacity = bunny::CAPACITY.in_profile::<Fast>();
        assert_eq!((C.triangles, C.made, C.colors), (3674, 0, 0));
        assert_eq!(C.bytes(4), (1839 * 8 + 3674 * 3 + 3) & !3);
        assert_eq!(C.bytes(4), 25_736);
        assert_eq!(
            core::mem::size_of::<fixshade::storage!(i32, C)>(),
            C.bytes(4)
        );
        assert_eq!(bunny::CAPACITY.bytes(4), (1839 * 12 + 3674 * 3 + 3) & !3);
        assert_eq!(
            core::mem::size_of::<bunny::BunnyPool>(),
            bunny::POOL_SLOTS * 116
        );
        assert_eq!(bunny::STATIC_BYTES, 2 * 3840 + 25_736 + 62 * 116);
        assert_eq!(bunny::STATIC_BYTES, 40_608);
        const { assert!(bunny::STATIC_BYTES <= 40 * 1024) };
        let mut st = Box::new(<fixshade::storage!(i32, C)>::new());
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
            // 1 839 vertices × (4 bytes xy + 4: depth and grey level packed
            // in one value) + a byte per mesh triangle (1 498 of the
            // 3 674 kept).
            assert_eq!(frame.vertex_count(), 1839);
            assert_eq!(frame.triangle_count(), 1498);
            assert_eq!(frame.bytes_used(), 1839 * 8 + 3674);
            assert_eq!(frame.bytes_used(), 18_386);
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
        assert_eq!(crcs[0], 0xca58_1561);
    }
}

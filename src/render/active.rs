//! The band renderer: an active triangle list walked band to band.
//!
//! [`Frame::bands`] orders the prepared triangles by the band of their
//! first row (a stable counting sort of their numbers into the caller's
//! [`BandState`], the first rows read from the [`Workspace::faces`]
//! bytes; when the band height is a multiple of the bytes' row step, the
//! counts by row are those prepare kept ([`Frame::face_rows`]) and the
//! sort is one placing pass: about 2 instructions per triangle number
//! and 13 per kept triangle on the Cortex-M4, 5 and 31 on the Cortex-M0;
//! bunny-gouraud raster 1 833 849 -> 1 816 817 and 2 814 970 ->
//! 2 778 399, geometry 380 268 -> 387 922 and 656 917 -> 666 100, the
//! counting there 5 to 6 a kept triangle). Each band
//! then draws, in triangle order (so that ties of equal depth resolve as
//! in a full frame), the merge of three ordered streams:
//!
//! - the *active* triangles, set up in an earlier band and kept in the
//!   [`Pool`] with their edge walkers and row values: resumed where they
//!   stopped, no setup;
//! - the triangles starting in this band (the next run of the order):
//!   set up once, walked down to the band's last row, and kept in the pool
//!   when they continue below it;
//! - the triangles that continue from the band above but found the pool
//!   full (or have more values than a slot holds): set up afresh at this
//!   band's first row, exactly (the edge walkers' exact start at any row),
//!   so the bytes are the same, only slower.
//!
//! The band's list is the run of the order starting in the band, ended
//! by a sentinel entry while the band is drawn; the triangles continuing
//! from the band above (the first and third streams: the pool's ring and
//! the queue, each in triangle order) are few, and the least of their
//! heads is a limit below which each triangle of the list is taken with
//! one load and a test (`Cur::next`); the ring and the queue are looked
//! at only when the list reaches that limit. When a frame has more bands
//! than one ordering covers, each later run of bands is moved to the end
//! of the run's entries.
//!
//! Measured and not kept: the continuing triangles merged into the band's
//! list once when the band starts (a resumed one's entry `numbers +
//! slot`), so that every pick is the same load and test. Exact QEMU
//! counts, raster, without -> with: bunny-gouraud thumbv7em 1 609 213 ->
//! 1 638 302, thumbv6m 2 359 309 -> 2 400 855; bunny-flat 1 453 231 ->
//! 1 478 523, 2 052 248 -> 2 093 794. The merge moves the list's entries
//! below each continuing triangle: 1 371 moves for the bunny's 352
//! continuing triangles, ~40 K instructions on the Cortex-M4.
//!
//! No band scans the triangles of other bands, and with a pool large
//! enough every triangle is set up exactly once per frame. A triangle
//! walked in pieces gives the very columns and values of one walked at
//! once (integer DDA, exact wrapping steps), so a banded frame equals the
//! full frame byte for byte.
//!
//! # The fixed affine fast path
//! Flat and grey Gouraud objects of the fixed affine profiles (`i32`
//! values, no perspective: [`Lerp::fixed_raw`]) take `Bands::run_fast`:
//! the same streams, with the setup of `raster::fast` (32-bit where the
//! triangle's extents allow it, on every target; tested equal to the
//! general setup), written into a scratch walk and values (copied into a
//! free pool slot only when the triangle continues below the band: the
//! setup writing straight into a slot measured no faster), and its fused
//! row kernel (two
//! edge steps, one multiply-add per value for a span start, the span
//! stage's own pixel loops), so the bytes are those of the general path.
//! bunny-gouraud raster (exact QEMU counts, 16-row bands): thumbv7em
//! 2.534 -> 2.272 -> 2.281 M instructions, thumbv6m 4.036 -> 3.938 ->
//! 3.809 M (the last step: the 32-bit setup on ARMv6-M too, out of line
//! there, into the pool slot). The other layouts and profiles take
//! `Bands::run`.
//!
//! # Memory
//! | part | bytes |
//! |------|-------|
//! | order scratch ([`BandState`]) | 2 per triangle number (one `u16` per entry of [`Workspace::faces`], at least [`Frame::triangle_count`]: the kept triangles by band, and in the rest the queue of triangles that found the pool full) |
//! | pool slot ([`Pool::SLOT_BYTES`]) | 88 (the walk: three edge walkers of 20 bytes, five `i32` rows, three flags; the triangle index) + `12 × V` (value, x step, y step of each of the `V` values a slot holds), plus 4 for the pool's two lists |
//! | quadratics slot ([`QuadSlot::BYTES`], `Q` per [`Pool`], none by default) | 328 (the point light's six quadratics of a triangle, 288; its key, light position, last row, anchor) |
//!
//! With `i32` values: 112 bytes per active triangle for `V = 2` (depth
//! and a grey level), 136 for `V = 4`, 184 for `V = 8` (any layout). A
//! slot keeps the walk as the row kernels walk it: a triangle starting in
//! a band is set up and walked in a scratch walk and copied into a free
//! slot (with its values) only when it continues below the band; a
//! resumed one is walked in its slot, in place, and its slot index goes
//! back to the ring (or to the free stack when it is done).
//!
//! The bunny at 240×240 in 16-row bands crosses band borders 352 times
//! and keeps at most 55 triangles at once ([`Bands::active_peak`]). The
//! walk kept packed in 16-bit columns and rows (64-byte slots) instead
//! saved 24 bytes per slot (1 344 bytes for the firmware's 56 slots of 8
//! values, 9 184 -> 10 528 bytes) for an unpack and a range-checked pack
//! per resumed triangle: kept unpacked, exact QEMU counts, bunny-flat
//! raster thumbv7em 1.901 -> 1.847 M, thumbv6m 2.725 -> 2.693 M;
//! bunny-gouraud 2.175 -> 2.172 M and 3.180 -> 3.152 M. The order scratch
//! for its 3 674 triangle numbers is 7 348 bytes (1 498 kept, the rest
//! room for the queue).
//!
//! A Phong triangle of one point light (position layout) crossing bands
//! makes its quadratics (`phong_span::tri`) in every band it reaches
//! unless a [`QuadSlot`] keeps them: dodeca-phong-n100 (160×160, 16-row
//! bands) makes 46 set-ups without slots, 18 (one per triangle) with 10;
//! raster thumbv7em 1 822 957 -> 1 700 554, thumbv6m 5 917 574 ->
//! 5 484 886 instructions, for 3 280 bytes of pool and 56 (M4) or 88
//! (M0) of stack.
//!
//! [`Workspace::faces`]: super::Workspace::faces

use super::band::PhongShader;
use super::phong_span::{
    KernelError, PhongKernel, PhongKernelShader, PosPlane, QuadSlot, SpecCache,
};
use super::position::PosFrame;
use super::prepare::eye_lights;
use super::{
    face_shift, FaceRows, Frame, Layout, Part, PreparedObject, PreparedTri, RenderError,
    RenderStats, FACE_ROW,
};
use crate::illum::{Light, Shade, MAX_LIGHTS};
use crate::num::wide::NO_LONG_MUL;
use crate::num::{Kernels, Profile, Raw16, Real};
use crate::raster::{
    draw_small, grey_l, grey_z, in_limits, pack_vals, setup, setup_fast, sort3, span_pixels,
    BandMem, Flat, Gouraud, GouraudMono, Lerp, Persp, RasterError, RowSpans, Shader, SubpixelBits,
    Vals, Vertex, Walk,
};
use crate::scene::{Object, Scene, SceneError};
use crate::target::{BandBuf, DepthFormat, PixelFormat, Rgb8, Window};

/// One active triangle: its index, walk and values.
#[derive(Clone, Copy, Debug)]
pub struct Slot<L, const V: usize> {
    tri: u16,
    walk: Walk,
    /// Per value (depth first): the value at pixel (0, 0) (floats: at
    /// the anchor), its step per pixel along x, along y (none of them
    /// changes while the triangle is walked).
    vals: [[L; 3]; V],
}

/// The active triangles' storage: `CAP` slots of `V` values each (depth
/// and attributes: 2 for grey Gouraud, 4 for colour Gouraud or Phong with
/// a normal, 8 for every layout), sized by the compiler.
///
/// A triangle with more values than `V`, or arriving when every slot is
/// taken, is set up afresh in each band it reaches instead (the same
/// bytes, more setups: see [`RenderStats::triangles`]).
///
/// `Q` slots ([`QuadSlot`], [`QuadSlot::BYTES`] each) keep the point
/// light's per-triangle quadratics of the Phong position layout from one
/// band to the next (none by default: set up again in every band).
#[derive(Clone, Debug)]
pub struct Pool<L, const CAP: usize, const V: usize = 8, const Q: usize = 0> {
    act: Active<L, CAP, V>,
    quads: [QuadSlot; Q],
}

/// The active triangles' slots and lists ([`Pool`]).
#[derive(Clone, Debug)]
struct Active<L, const CAP: usize, const V: usize> {
    slots: [Slot<L, V>; CAP],
    /// Ring of the slots in use, in triangle order.
    ring: [u16; CAP],
    /// Free slots (a stack).
    free: [u16; CAP],
}

impl<L: Lerp, const CAP: usize, const V: usize, const Q: usize> Pool<L, CAP, V, Q> {
    /// Bytes of one slot (the RAM per active triangle, without the 4 bytes
    /// of the two lists).
    pub const SLOT_BYTES: usize = core::mem::size_of::<Slot<L, V>>();

    /// An empty pool (`const`: it may live in a `static`).
    pub const fn new() -> Self {
        Self {
            act: Active {
                slots: [Slot {
                    tri: 0,
                    walk: Walk::EMPTY,
                    vals: [[L::ZERO; 3]; V],
                }; CAP],
                ring: [0; CAP],
                free: [0; CAP],
            },
            quads: [QuadSlot::EMPTY; Q],
        }
    }
}

impl<L: Lerp, const CAP: usize, const V: usize, const Q: usize> Default for Pool<L, CAP, V, Q> {
    fn default() -> Self {
        Self::new()
    }
}

/// The band renderer's memory besides the band buffer: the triangle order
/// (at least [`Frame::triangle_count`] `u16`, one per triangle number as
/// [`Storage`](super::Storage) sizes it: the kept triangles by band, and
/// in the rest the queue of those put off while the pool is full) and
/// the active pool.
#[derive(Debug)]
pub struct BandState<'a, L, const CAP: usize, const V: usize = 8, const Q: usize = 0> {
    /// Scratch for the order of the triangles.
    pub order: &'a mut [u16],
    /// The active triangles.
    pub pool: &'a mut Pool<L, CAP, V, Q>,
}

impl<'a, L: Lerp, const CAP: usize, const V: usize, const Q: usize> BandState<'a, L, CAP, V, Q> {
    /// The state in `order` (at least one entry per prepared triangle)
    /// and `pool`.
    pub fn new(order: &'a mut [u16], pool: &'a mut Pool<L, CAP, V, Q>) -> Self {
        Self { order, pool }
    }
}

/// No triangle (an exhausted stream).
const NONE: u32 = u32::MAX;

/// Buckets of one counting-sort pass.
const RADIX_BITS: u32 = 6;

/// A frame being rendered band by band: [`Bands::next_band`] renders the
/// next band into a band buffer.
///
/// The triangles are ordered once by the band of their first row (a
/// stable counting sort into the [`BandState`]'s order scratch, from the
/// first rows prepare stored, see [`Workspace::faces`](super::Workspace::faces);
/// frames of more than 64 bands ordered again every 64). Each band then
/// draws, in triangle order
/// (so that ties of equal depth resolve as in a full frame), the merge of
/// the triangles kept from the bands above (resumed with their edge
/// walkers and row values: no setup), those starting in the band (set up
/// once, kept in the [`Pool`] when they continue below it) and those that
/// continue but found the pool full (set up afresh at the band's first
/// row: the same bytes, more setups). No band looks at the triangles of
/// other bands, and with a pool of [`Bands::active_peak`] slots every
/// triangle is set up exactly once per frame. A banded frame equals the
/// full frame byte for byte: the edge walkers and the integer attribute
/// steps are exact, so a triangle walked in pieces gives the very columns
/// and values of one walked at once.
///
/// ```
/// use fixshade::geom::{Affine, Vec3};
/// use fixshade::illum::{Light, Material, Specular, Viewer};
/// use fixshade::mesh::shapes::DODECAHEDRON;
/// use fixshade::num::{Fast, Real, Q16};
/// use fixshade::render::{prepare, BandState, Pool, ScreenXy, Workspace};
/// use fixshade::scene::{Camera, Object, Scene, Shading};
/// use fixshade::target::{BandBuf, Rgb565Be, Rgb8};
///
/// let q = |n: i32, d: i32| Q16::from_ratio(n, d);
/// let camera = Camera::look_at(
///     Vec3::new(q(0, 1), q(0, 1), q(6, 1)), Vec3::ZERO, Vec3::new(q(0, 1), q(1, 1), q(0, 1)),
///     fixshade::geom::radians(q(40, 1)), q(1, 2), None,
/// )?;
/// let material = Material { color: Vec3::new(q(1, 1), q(3, 10), q(2, 10)), ka: q(2, 10), kd: q(5, 10), ks: q(0, 1), shininess: q(1, 1) };
/// let objects = [Object { mesh: DODECAHEDRON, transform: Affine::IDENTITY, material, shading: Shading::Gouraud, cull_backfaces: true }];
/// let lights = [Light::point(Vec3::new(q(0, 1), q(0, 1), q(2, 1)), q(1, 1))];
/// let scene = Scene { camera, objects: &objects, lights: &lights, ambient: q(1, 1),
///                     specular: Specular::Phong, viewer: Viewer::Local, background: Rgb8::BLACK };
/// // Room for the dodecahedron's 20 vertices and a byte per triangle (36);
/// // inside the clipping planes it makes no triangle.
/// let (mut xy, mut vals, mut faces) = ([ScreenXy::ZERO; 64], [0i32; 64 * 7], [0u8; 64]);
/// let ws = Workspace { xy: &mut xy, vals: &mut vals, tris: &mut [], colors: &mut [], faces: &mut faces };
/// let frame = prepare::<Fast>(&scene, 96, 96, ws)?;
///
/// // Two band buffers of 8 rows: one is rendered while the other is sent.
/// let (mut p0, mut z0) = ([0u16; 96 * 8], [0u16; 96 * 8]);
/// let (mut p1, mut z1) = ([0u16; 96 * 8], [0u16; 96 * 8]);
/// let mut bufs = [
///     BandBuf::<Rgb565Be>::new(&mut p0, Some(&mut z0), 96, 8)?,
///     BandBuf::<Rgb565Be>::new(&mut p1, Some(&mut z1), 96, 8)?,
/// ];
/// let (mut order, mut pool) = ([0u16; 64], Pool::<i32, 16, 4>::new());
/// let mut state = BandState::new(&mut order, &mut pool);
/// let mut bands = frame.bands(&scene, &mut state, 8)?;
/// let mut i = 0;
/// while let Some(win) = bands.next_band(&mut bufs[i])? {
///     // Start sending bufs[i] (rows win.y0..win.y1) by DMA here; the
///     // next band is rendered into the other buffer meanwhile.
///     assert_eq!(bufs[i].pixels().len(), (96 * win.rows()) as usize);
///     i ^= 1;
/// }
/// // Each prepared triangle set up once.
/// assert_eq!(bands.stats().triangles as usize, frame.triangle_count());
/// # Ok::<(), Box<dyn core::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct Bands<'a, 'w, P: Profile, const CAP: usize, const V: usize> {
    frame: &'a Frame<'w, P>,
    scene: &'a Scene<'a, 'a, P::Real>,
    lights: heapless::Vec<Light<P::Real>, MAX_LIGHTS>,
    /// The band's list, the queue and the pool.
    ls: Cur<'a, P::Lerp, CAP, V>,
    /// The pool's [`QuadSlot`]s.
    quads: &'a mut [QuadSlot],
    rows: u32,
    /// First row of the next band.
    y: u32,
    /// End of each band's entries of the order (band `epoch + b`'s in
    /// `ends[b]`), so that a band's run needs no triangle's rows again.
    ends: [u16; 1 << RADIX_BITS],
    /// The first band of those ordered (every [`EPOCH`] bands the
    /// triangles starting in the next ones are ordered).
    epoch: u32,
    stats: RenderStats,
    /// The Phong kernel's specular table, built once a frame per
    /// shininess rather than once a band.
    spec_cache: Option<SpecCache>,
}

/// [`PhongKernel::new_cached`], not inlined: its temporaries (the
/// lights' terms, the specular table) then take a stack frame only while
/// the kernel is made, not room in the Phong arm's frame under the span
/// loops.
#[inline(never)]
fn kernel_of<'s, R: Real>(
    q: Raw16<R>,
    shade: &'s Shade<R>,
    cache: &mut Option<SpecCache>,
) -> Result<PhongKernel<'s, R>, KernelError> {
    PhongKernel::new_cached(q, shade, cache)
}

impl<'w, P: Profile> Frame<'w, P> {
    /// Starts rendering the frame in bands of `rows` rows (see [`Bands`]):
    /// orders the triangles into `state`.
    ///
    /// # Errors
    /// [`RenderError::Capacity`] ([`Part::Order`]) when the order scratch
    /// holds fewer entries than the prepared triangles (and from
    /// [`Bands::next_band`] when a triangle put off while the pool was
    /// full finds no room in the rest of it: with an order of one entry
    /// per triangle number, as [`Storage`](super::Storage) gives, the rest
    /// holds every triangle a view does not keep);
    /// [`RenderError::Window`] for `rows == 0`; a scene with too many
    /// lights gives [`RenderError::Scene`].
    // Not inlined: the set-up's temporaries (the eye-space lights, the
    // band ends) then stay out of the caller's stack frame, which stands
    // under every band.
    #[inline(never)]
    pub fn bands<'a, const CAP: usize, const V: usize, const Q: usize>(
        &'a self,
        scene: &'a Scene<'_, '_, P::Real>,
        state: &'a mut BandState<'_, P::Lerp, CAP, V, Q>,
        rows: u32,
    ) -> Result<Bands<'a, 'w, P, CAP, V>, RenderError> {
        let order = &mut *state.order;
        if rows == 0 {
            return Err(RenderError::Window);
        }
        let short = RenderError::Capacity {
            part: Part::Order,
            object: 0,
        };
        if self.triangle_numbers() > u16::MAX as usize {
            return Err(short);
        }
        let lights = eye_lights(scene)?;
        let Pool { act: pool, quads } = &mut *state.pool;
        QuadSlot::clear(quads);
        for (i, f) in pool.free.iter_mut().take(CAP).enumerate() {
            *f = (CAP - 1 - i) as u16;
        }
        // (The kept triangles counted while ordering.)
        let (ends, run_at, n) = sort_by_band(self, order, rows, self.height, 0, None);
        if order.len() < n {
            return Err(short);
        }
        // The queue: the entries outside the run. (Split checked: a
        // split's panic branch survived the optimisation there.)
        let (run, queue) = if run_at == 0 {
            order.split_at_mut_checked(n).ok_or(short)?
        } else {
            let (q, r) = order.split_at_mut_checked(run_at).ok_or(short)?;
            (r, q)
        };
        Ok(Bands {
            frame: self,
            scene,
            lights,
            quads,
            rows,
            y: 0,
            ends,
            epoch: 0,
            ls: Cur {
                run,
                queue,
                pool,
                s: Streams {
                    cursor: 0,
                    band_end: 0,
                    lost: false,
                    free_len: CAP,
                    ring_head: 0,
                    ring_cur: 0,
                    ring_len: 0,
                    def_head: 0,
                    def_cur: 0,
                    def_len: 0,
                    heads: [NONE; 2],
                    spec: NONE,
                    lim: NONE,
                    peak: 0,
                },
            },
            stats: RenderStats::default(),
            spec_cache: None,
        })
    }

    /// Renders the whole frame band by band into `band` (cleared to the
    /// scene's background before each band), handing each finished band to
    /// `sink` (to send it to a display, or checksum it).
    ///
    /// # Errors
    /// As [`Frame::bands`] and [`Bands::next_band`], or the sink's error.
    pub fn render_bands<F, D, E, const CAP: usize, const V: usize, const Q: usize>(
        &self,
        scene: &Scene<'_, '_, P::Real>,
        state: &mut BandState<'_, P::Lerp, CAP, V, Q>,
        band: &mut BandBuf<'_, F, D>,
        mut sink: impl FnMut(&BandBuf<'_, F, D>) -> Result<(), E>,
    ) -> Result<RenderStats, E>
    where
        F: PixelFormat,
        D: DepthFormat,
        E: From<RenderError>,
    {
        let mut bands = self.bands(scene, state, band.rows())?;
        while bands.next_band(band)?.is_some() {
            sink(band)?;
        }
        Ok(bands.stats())
    }
}

/// Band of a row: `r / rows`, without a division for the usual heights
/// (a power of two: a shift; below 256: a multiply by `ceil(2^20 /
/// rows)`, exact for `r < 2^12`: the product stays below `2^12 · 2^19`
/// and its excess over `r / rows` below `r / 2^20 < 2^-8 <= 1 / rows`).
#[inline(always)]
pub(super) fn band_of(r: u32, rows: u32, shift: Option<u32>, m: u32) -> u32 {
    match shift {
        Some(s) => r >> s,
        None if m != 0 => (r * m) >> 20,
        None => r / rows.max(1),
    }
}

/// The divisor constants of [`band_of`] for `rows`.
pub(super) fn band_consts(rows: u32) -> (Option<u32>, u32) {
    if rows.is_power_of_two() {
        (Some(rows.trailing_zeros()), 0)
    } else if rows < 256 {
        (None, (1u32 << 20).div_ceil(rows.max(1)))
    } else {
        (None, 0)
    }
}

/// Bands ordered at once (a run): a frame of more bands is ordered again
/// every `EPOCH` bands (`first..first + EPOCH`, counted in 64 buckets).
const EPOCH: u32 = 1 << RADIX_BITS;

/// The band of kept triangles from their [`Workspace::faces`] bytes.
///
/// [`Workspace::faces`]: super::Workspace::faces
#[derive(Clone, Copy, Debug)]
struct BandOf {
    /// `Some`: the band height a multiple of `2^q` (`q` the frame's row
    /// shift, [`face_shift`]): the band is the stored row `(r >> q)`
    /// divided by `rows >> q` ([`band_of`] with these constants), exact
    /// (`floor(r / rows) = floor(floor(r / 2^q) / (rows / 2^q))`); `None`:
    /// from the triangle's vertices.
    coarse: Option<(u32, Option<u32>, u32)>,
    rows: u32,
    shift: Option<u32>,
    m: u32,
    /// The last band.
    last: u32,
}

impl BandOf {
    fn new(rows: u32, height: u32) -> Self {
        let q = face_shift(height);
        let (shift, m) = band_consts(rows);
        let coarse = (rows.trailing_zeros() >= q).then(|| {
            let r = rows >> q;
            let (s, m) = band_consts(r);
            (r, s, m)
        });
        Self {
            coarse,
            rows,
            shift,
            m,
            last: height.div_ceil(rows.max(1)).saturating_sub(1),
        }
    }

    /// The band of kept triangle number `i` with byte `b`.
    #[inline(always)]
    fn band<P: Profile>(&self, frame: &Frame<'_, P>, i: usize, b: u8) -> u32 {
        match self.coarse {
            Some((rows, shift, m)) => {
                band_of(u32::from(b & FACE_ROW).wrapping_sub(1), rows, shift, m).min(self.last)
            }
            None => self.band_slow(frame, i),
        }
    }

    /// [`Self::band`] from the vertices (the band height not a multiple
    /// of `2^q`): the object of the triangle found among the objects.
    #[inline(never)]
    #[cold]
    fn band_slow<P: Profile>(&self, frame: &Frame<'_, P>, i: usize) -> u32 {
        let r = frame
            .tri_vertices(i)
            .map_or(0, |v| u32::from(frame.tri_first_row(v)));
        band_of(r.min(4095), self.rows, self.shift, self.m).min(self.last)
    }
}

/// [`sort_by_band`] when the bands follow from the bytes' rows
/// ([`BandOf::coarse`], `(rows, shift, m)` for [`band_of`] of a stored row,
/// the last band, the run's first): the kept triangles by stored row as
/// prepare counted them (`per_row`, [`Frame::face_rows`]), each row's
/// band (within the run, or none) found once, then every kept triangle
/// placed by a table lookup in one pass over the bytes (a word of four
/// bytes none of which is kept skipped at once). The same order; the run
/// at `at` (or 0).
///
/// Measured and not kept: every byte of a word with a kept one placed
/// without a test (row code 0 and bands outside the run to a bucket past
/// every valid entry, `u32` counts): bunny-gouraud raster thumbv7em
/// 1 634 450 -> 1 642 031, thumbv6m 2 491 561 -> 2 495 229.
#[inline(never)]
#[allow(clippy::cast_possible_truncation)]
fn sort_coarse(
    faces: &[u8],
    per_row: &FaceRows,
    order: &mut [u16],
    ((rows, shift, m), last, first): ((u32, Option<u32>, u32), u32, u32),
    at: Option<(usize, usize)>,
) -> ([u16; 1 << RADIX_BITS], usize, usize) {
    // The kept triangles.
    let n = at.map_or_else(|| per_row.iter().map(|&p| usize::from(p)).sum(), |a| a.1);
    // Each stored row's band within the run (`EPOCH`: outside).
    let mut band = [EPOCH as u8; FACE_ROW as usize + 1];
    // The bands' counts (`count[b + 1]`: band `b` of the run), then their
    // first entries. Indexed by a band below 128, masked: no bound check.
    let mut count = [0u16; FACE_ROW as usize + 1];
    for (c, &p) in per_row.iter().enumerate().skip(1) {
        if p == 0 {
            continue;
        }
        // A band before `first` wraps past `EPOCH`.
        let b = band_of(c as u32 - 1, rows, shift, m)
            .min(last)
            .wrapping_sub(first);
        if b < EPOCH {
            band[c & 127] = b as u8;
            count[(b as usize + 1) & 127] += p;
        }
    }
    let mut sum = 0;
    for c in count.iter_mut().take(EPOCH as usize + 1) {
        sum += *c;
        *c = sum;
    }
    let run_at = at.map_or(0, |a| a.0);
    let dst = order.get_mut(run_at..).unwrap_or_default();
    // ARMv6-M loads a word byte by byte: there the bytes one by one, from
    // the last ([`place_backwards`]): bunny-gouraud, this function, 60 300
    // -> 54 070 on the Cortex-M0 (the bytes' union per word of four, each
    // byte of a word with a kept one then placed, before; forwards one by
    // one 55 560, two bytes at a time 57 942, `u32` counts 55 040). On the
    // Cortex-M4 a word load, a word of four bytes none of which is kept
    // skipped at once (below): 31 824, the bytes' union of four loaded one
    // by one 38 710.
    #[cfg(armv6m)]
    return (place_backwards(faces, &band, &mut count, dst), run_at, n);
    #[cfg(not(armv6m))]
    {
        let mut place = |i: usize, b: u8| {
            // (`EPOCH`: outside the run, placed nowhere.)
            let k = usize::from(band[usize::from(b & FACE_ROW)]);
            if k < EPOCH as usize {
                let c = &mut count[k & 127];
                if let Some(d) = dst.get_mut(usize::from(*c)) {
                    // Numbers below `MAX_TRIANGLES`.
                    *d = i as u16;
                }
                *c += 1;
            }
        };
        let mut quads = faces.chunks_exact(4);
        let mut i = 0;
        for q in quads.by_ref() {
            let w = u32::from_le_bytes([q[0], q[1], q[2], q[3]]);
            if w & u32::from_le_bytes([FACE_ROW; 4]) != 0 {
                for (j, &b) in q.iter().enumerate() {
                    if b & FACE_ROW != 0 {
                        place(i + j, b);
                    }
                }
            }
            i += 4;
        }
        for (j, &b) in quads.remainder().iter().enumerate() {
            if b & FACE_ROW != 0 {
                place(i + j, b);
            }
        }
        let mut ends = [0u16; 1 << RADIX_BITS];
        for (e, c) in ends.iter_mut().zip(count.iter()) {
            *e = *c;
        }
        (ends, run_at, n)
    }
}

/// The placing pass of [`sort_coarse`] on ARMv6-M: each kept triangle
/// number `i` (byte `b` of `faces` with a row) placed in its band's
/// entries of `dst` (`band[b & FACE_ROW]`: its band within the run,
/// [`EPOCH`] outside it, placed nowhere; `count[k]` the first entry of
/// band `k`, the prefix sums), from the last byte to the first, one at a
/// time: each band filled from its end down (the bands' ends are the
/// prefix sums past each band, `count[k + 1]`), so the order is that of
/// the forward pass (stable: ascending numbers within a band), and the
/// loop holds no end index (on the Cortex-M0: 8 instructions a byte, 14
/// more a kept triangle). Returns the end of each band's entries.
#[cfg(any(armv6m, test))]
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn place_backwards(
    faces: &[u8],
    band: &[u8; FACE_ROW as usize + 1],
    count: &mut [u16; FACE_ROW as usize + 1],
    dst: &mut [u16],
) -> [u16; 1 << RADIX_BITS] {
    let mut ends = [0u16; 1 << RADIX_BITS];
    for (e, c) in ends.iter_mut().zip(count.iter().skip(1)) {
        *e = *c;
    }
    let mut i = faces.len();
    while i > 0 {
        i -= 1;
        let b = faces.get(i).copied().unwrap_or(0);
        if b & FACE_ROW != 0 {
            let k = usize::from(band[usize::from(b & FACE_ROW)]);
            if k < EPOCH as usize {
                let c = &mut count[(k + 1) & 127];
                *c = c.wrapping_sub(1);
                if let Some(d) = dst.get_mut(usize::from(*c)) {
                    // Numbers below `MAX_TRIANGLES`.
                    *d = i as u16;
                }
            }
        }
    }
    ends
}

/// The placing pass of [`sort_coarse`] and [`sort_by_band`]: each kept
/// triangle number (byte of `faces` with a row) placed at its bucket's
/// next entry, `count` holding each bucket's first entry (the prefix sums
/// of the counts; bucket `b` of the run at `count[b]`, `slot(i, byte)`
/// giving the bucket of triangle `i`, `None` for one placed nowhere).
/// From the kept numbers listed at the start of `order` (the first
/// ordering, when `order` holds them twice: `n` of them, placed into
/// `order[len - n..]`), else from `faces` into the run at `at` (or 0).
/// Returns the end of each band's entries (relative to the run's start),
/// where the run starts in `order`, and `n`.
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn place_run<const C: usize>(
    faces: &[u8],
    order: &mut [u16],
    n: usize,
    at: Option<(usize, usize)>,
    count: &mut [u16; C],
    slot: impl Fn(usize, u8) -> Option<usize>,
) -> ([u16; 1 << RADIX_BITS], usize, usize) {
    let mut place = |dst: &mut [u16], i: usize, b: u8| {
        if let Some(c) = slot(i, b).and_then(|k| count.get_mut(k)) {
            if let Some(d) = dst.get_mut(usize::from(*c)) {
                // Numbers below `MAX_TRIANGLES`.
                *d = i as u16;
            }
            *c += 1;
        }
    };
    let run_at = if at.is_none() && n <= order.len() / 2 {
        let (src, dst) = order.split_at_mut(order.len() - n);
        for &i in src.get(..n).unwrap_or_default() {
            let i = usize::from(i);
            place(dst, i, faces.get(i).copied().unwrap_or(0));
        }
        order.len() - n
    } else {
        let at = at.map_or(0, |a| a.0);
        let dst = order.get_mut(at..).unwrap_or_default();
        for (i, &b) in faces.iter().enumerate() {
            if b & FACE_ROW != 0 {
                place(dst, i, b);
            }
        }
        at
    };
    let mut ends = [0u16; 1 << RADIX_BITS];
    for (e, c) in ends.iter_mut().zip(count.iter()) {
        *e = *c;
    }
    (ends, run_at, n)
}

/// Orders the numbers of `frame`'s kept triangles starting in bands
/// `first..first + EPOCH` by band, stably (ascending numbers within a
/// band), into `order` (at least [`Frame::triangle_count`] entries): each
/// kept triangle's band read from its [`Workspace::faces`] byte (its first
/// row), a counting sort. Returns the end of each band's entries (band
/// `first + b`'s in `ends[b]`, relative to the start of the run) and where
/// the run starts in `order`.
///
/// The first ordering (`at` = `None`) lists the kept numbers in `order`
/// while counting; when `order` holds them twice, it places them from
/// there into the run `order[len - n..]` (the placing pass over the kept
/// triangles only); else, and for a later run of bands (`at`: where the
/// run starts), the placing pass reads the numbers' bytes again and writes
/// the run at `at` (or 0). The rest of `order` is the queue of the
/// triangles put off while the pool is full.
///
/// [`Workspace::faces`]: super::Workspace::faces
fn sort_by_band<P: Profile>(
    frame: &Frame<'_, P>,
    order: &mut [u16],
    rows: u32,
    height: u32,
    first: u32,
    at: Option<(usize, usize)>,
) -> ([u16; 1 << RADIX_BITS], usize, usize) {
    let key = BandOf::new(rows, height);
    let faces = frame
        .faces
        .get(..frame.triangle_numbers())
        .unwrap_or_default();
    if let Some(coarse) = key.coarse {
        return sort_coarse(
            faces,
            &frame.face_rows,
            order,
            (coarse, key.last, first),
            at,
        );
    }
    let mut count = [0u16; (1 << RADIX_BITS) + 1];
    let list: &mut [u16] = if at.is_none() { order } else { &mut [] };
    let mut listed = 0;
    for (i, &b) in faces.iter().enumerate() {
        if b & FACE_ROW == 0 {
            continue;
        }
        // A band before `first` wraps past `EPOCH`.
        let k = key.band(frame, i, b).wrapping_sub(first);
        if k < EPOCH {
            count[k as usize + 1] += 1;
        }
        if let Some(d) = list.get_mut(listed) {
            // Numbers below `MAX_TRIANGLES`.
            *d = i as u16;
        }
        listed += 1;
    }
    let mut sum = 0;
    for c in count.iter_mut() {
        sum += *c;
        *c = sum;
    }
    let n = at.map_or(listed, |a| a.1);
    place_run(faces, order, n, at, &mut count, |i, b| {
        let k = key.band(frame, i, b).wrapping_sub(first);
        (k < EPOCH).then_some(k as usize)
    })
}

/// The row kernel's sink: a band's colour and depth slices and a shader.
struct Kernel<'k, 'b, F: PixelFormat, D: DepthFormat, S> {
    px: &'k mut &'b mut [F::Raw],
    z: &'k mut Option<&'b mut [D::Raw]>,
    y0: i32,
    width: usize,
    shader: &'k mut S,
    drawn: u32,
}

impl<L: Lerp, const N: usize, F: PixelFormat, D: DepthFormat, S: Shader<L, N>> RowSpans<L, N>
    for Kernel<'_, '_, F, D, S>
{
    #[inline(always)]
    fn span(&mut self, j: i32, x0: i32, x1: i32, v: &Vals<L, N>, sx: &Vals<L, N>, z16: bool) {
        // The walker gives rows of the band and columns within the width.
        let base = (j - self.y0) as usize * self.width;
        let r = base + x0 as usize..base + x1 as usize;
        let Some(row) = self.px.get_mut(r.clone()) else {
            return;
        };
        let drow = match self.z.as_deref_mut() {
            Some(z) => match z.get_mut(r) {
                Some(d) => Some(d),
                None => return,
            },
            None => None,
        };
        let plane = D::plane_in_range(z16);
        self.drawn += span_pixels::<L, N, F, D, S>(row, drow, v, sx, plane, self.shader, (x0, j));
    }
}

/// A band's buffers as the kernels see them.
struct Target<'b, F: PixelFormat, D: DepthFormat> {
    px: &'b mut [F::Raw],
    z: Option<&'b mut [D::Raw]>,
    y0: u32,
    y1: u32,
    width: u32,
}

impl<'w, P: Profile, const CAP: usize, const V: usize> Bands<'_, 'w, P, CAP, V> {
    /// What has been drawn so far: triangle setups (every prepared triangle
    /// once, when the pool holds every active triangle) and pixels.
    pub fn stats(&self) -> RenderStats {
        self.stats
    }

    /// The most triangles kept for a later band at once so far (in the
    /// pool, or queued when it was full; a band resumes and admits them in
    /// triangle order, so this can exceed the count at a band border): a
    /// pool of this many slots sets every triangle up once.
    pub fn active_peak(&self) -> usize {
        self.ls.s.peak
    }

    /// Renders the next band into `band` (moved to the band's rows and
    /// cleared to the scene's background first): `Some(window)` with the
    /// rows drawn, `None` after the last band.
    ///
    /// # Errors
    /// [`RenderError::Window`] when the band buffer's width differs from
    /// the frame's or its rows from those the bands were ordered for;
    /// [`RenderError::Raster`] for a vertex outside the rasterizer's
    /// limits (not after [`super::prepare`]); [`RenderError::Capacity`]
    /// ([`Part::Order`]) when a triangle continuing below the band found
    /// the pool full and no room in the order scratch's queue (the band
    /// is drawn; the frame would miss the triangle's rest).
    pub fn next_band<F: PixelFormat, D: DepthFormat>(
        &mut self,
        band: &mut BandBuf<'_, F, D>,
    ) -> Result<Option<Window>, RenderError> {
        let (w, h) = self.frame.size();
        if self.y >= h {
            return Ok(None);
        }
        if band.window().width != w || band.rows() != self.rows {
            return Err(RenderError::Window);
        }
        let y0 = self.y;
        let y1 = y0.saturating_add(self.rows).min(h);
        let (px, z) = band
            .start(y0, y1, self.scene.background)
            .ok_or(RenderError::Window)?;
        let mut t = Target::<F, D> {
            px,
            z,
            y0,
            y1,
            width: w,
        };
        let band_index = y0 / self.rows.max(1);
        // The triangles starting in this band: the next run of the order
        // (each triangle's band found once per frame, here).
        if band_index >= self.epoch + EPOCH {
            // The next run of bands: its triangles ordered (into the
            // run's entries).
            let n = self.ls.run.len();
            let (ends, ..) = sort_by_band(
                self.frame,
                self.ls.run,
                self.rows,
                self.frame.height,
                band_index,
                Some((0, n)),
            );
            self.ends = ends;
            self.epoch = band_index;
            self.ls.s.cursor = 0;
        }
        // Bands past the last hold no start (keys are clamped to it).
        self.ls.s.band_end = self
            .ends
            .get((band_index - self.epoch) as usize)
            .map_or(self.ls.run.len(), |&e| usize::from(e))
            .min(self.ls.run.len())
            .max(self.ls.s.cursor);
        // The band's list, and the heads of the continuing triangles.
        let under = self.ls.start_band();
        // No triangle to resume or start: the band draws nothing.
        let untouched = self.ls.first() == NONE;
        let frame = self.frame;
        let mut drawn = Ok(());
        // The fixed affine profiles take the fused kernels (`raster::fast`).
        let fixed = !P::PERSPECTIVE && P::Lerp::ZERO.fixed_raw().is_some();
        for (po, obj) in frame.objects.iter().zip(self.scene.objects.iter()) {
            if po.tris.is_empty() || self.ls.first() >= po.tris.end as u32 {
                continue;
            }
            let r = match po.layout() {
                Layout::Flat if fixed => {
                    self.run_fast::<0, _, _, _>(po, &mut t, Flat(Rgb8::BLACK), |s, t| s.0 = t.color)
                }
                Layout::Flat => {
                    self.run::<0, _, _, _>(po, &mut t, Flat(Rgb8::BLACK), |s, t| s.0 = t.color)
                }
                Layout::GouraudMono if P::PERSPECTIVE => {
                    self.run::<2, _, _, _>(po, &mut t, Persp(GouraudMono), |_, _| {})
                }
                Layout::GouraudMono if fixed => {
                    self.run_fast::<1, _, _, _>(po, &mut t, GouraudMono, |_, _| {})
                }
                Layout::GouraudMono => self.run::<1, _, _, _>(po, &mut t, GouraudMono, |_, _| {}),
                Layout::GouraudRgb if P::PERSPECTIVE => {
                    self.run::<4, _, _, _>(po, &mut t, Persp(Gouraud), |_, _| {})
                }
                Layout::GouraudRgb => self.run::<3, _, _, _>(po, &mut t, Gouraud, |_, _| {}),
                // Out of line: its shade and kernel take a stack frame
                // only while a Phong object is drawn.
                Layout::PhongNormal | Layout::PhongPosition => self.phong(po, obj, &mut t),
            };
            if r.is_err() {
                drawn = r;
                break;
            }
        }
        self.ls.end_band(under);
        drawn?;
        if untouched {
            // Nothing drawn: the buffer still holds the clear, which the
            // next band then skips ([`BandBuf::start`]).
            band.untouched();
        }
        self.y = y1;
        if self.ls.s.lost {
            return Err(RenderError::Capacity {
                part: Part::Order,
                object: 0,
            });
        }
        Ok(Some(Window { width: w, y0, y1 }))
    }

    /// Draws this band's part of Phong object `po` (scene object `obj`):
    /// its shade, and the span kernel where the profile has one.
    #[inline(never)]
    fn phong<F: PixelFormat, D: DepthFormat>(
        &mut self,
        po: &PreparedObject,
        obj: &Object<'_, P::Real>,
        t: &mut Target<'_, F, D>,
    ) -> Result<(), RenderError> {
        let frame = self.frame;
        let sc = self.scene;
        // The shade and the kernel are borrowed where they are made (no
        // move of either out of its `Result`: a stack slot each).
        let shade = Shade::new(
            &obj.material,
            sc.ambient,
            &self.lights,
            sc.specular,
            sc.viewer,
        );
        let Ok(shade) = &shade else {
            return Err(SceneError::TooManyLights.into());
        };
        let normal = po.layout() == Layout::PhongNormal;
        // The span kernel (`phong_span`) where the profile has
        // one (the affine Q16 profiles), else the per-pixel
        // shader.
        let cache = &mut self.spec_cache;
        let kernel = if P::PERSPECTIVE {
            None
        } else {
            <P::Real as Real>::Kernels::pick(|q| Some(kernel_of(q, shade, cache)), || None)
        };
        if let Some(Ok(k)) = &kernel {
            let quads = core::mem::take(&mut self.quads);
            let mut sh = PhongKernelShader::new(k);
            sh.keep_in(&mut *quads, (t.y0, t.y1));
            let r = if normal {
                let set =
                    |s: &mut PhongKernelShader<'_, '_, P::Real>, t: &PreparedTri| s.back = t.back;
                self.run::<3, _, _, _>(po, t, sh, set)
            } else {
                // The exact position plane per triangle
                // (`PosPlane`).
                let plane = k.wants_plane();
                // The triangle's quadratics (`TriQuad`) for one point light.
                let quad = k.wants_tri();
                let set = |s: &mut PhongKernelShader<'_, '_, P::Real>, t: &PreparedTri| {
                    s.back = t.back;
                    if plane {
                        s.plane = PosPlane::of_tri(frame, po, t);
                    }
                    if quad {
                        s.set_tri(frame, po, t);
                    }
                };
                self.run::<6, _, _, _>(po, t, sh, set)
            };
            self.quads = quads;
            return r;
        }
        let frame = PosFrame::of_object::<P>(sc, obj);
        let sh = PhongShader::<P>::for_object(shade, frame.as_ref());
        if P::PERSPECTIVE {
            let set = |s: &mut Persp<PhongShader<'_, P>>, t: &PreparedTri| s.0.set_back(t.back);
            if normal {
                self.run::<4, _, _, _>(po, t, Persp(sh), set)?;
            } else {
                self.run::<7, _, _, _>(po, t, Persp(sh), set)?;
            }
        } else {
            let set = |s: &mut PhongShader<'_, P>, t: &PreparedTri| s.set_back(t.back);
            if normal {
                self.run::<3, _, _, _>(po, t, sh, set)?;
            } else {
                self.run::<6, _, _, _>(po, t, sh, set)?;
            }
        }
        Ok(())
    }

    /// Draws this band's part of object `po`: the merge, in triangle order,
    /// of its active triangles, those that found the pool full and those
    /// starting in the band.
    #[inline(never)]
    fn run<const N: usize, S, F, D>(
        &mut self,
        po: &PreparedObject,
        t: &mut Target<'_, F, D>,
        mut shader: S,
        per_tri: impl Fn(&mut S, &PreparedTri),
    ) -> Result<(), RenderError>
    where
        S: Shader<P::Lerp, N>,
        F: PixelFormat,
        D: DepthFormat,
    {
        let end = po.tris.end as u32;
        let (y1, width) = (t.y1 as i32, t.width as i32);
        let frame = self.frame;
        let mesh = frame.mesh_tris(po);
        let cur = &mut self.ls;
        let stats = &mut self.stats;
        cur.s.lim = cur.s.spec.min(end);
        let r = loop {
            let (ti, src) = match cur.next() {
                Some(ti) => (ti, Src::Fresh),
                None => {
                    let Some(t) = cur.special(end) else {
                        break Ok(());
                    };
                    t
                }
            };
            let Some(tri) = frame.tri_of(po, mesh, ti as usize) else {
                break Ok(());
            };
            per_tri(&mut shader, &tri);
            let mut k = Kernel::<F, D, S> {
                px: &mut t.px,
                z: &mut t.z,
                y0: t.y0 as i32,
                width: t.width as usize,
                shader: &mut shader,
                drawn: 0,
            };
            match src {
                Src::Slot(si) => {
                    // Resume an active triangle.
                    let Some(slot) = cur.pool.slots.get_mut(si) else {
                        break Ok(());
                    };
                    let (row, sx, sy) = unpack::<_, N, V>(&slot.vals);
                    slot.walk.rows(&row, &sx, &sy, y1, width, &mut k);
                    let done = slot.walk.done();
                    cur.put_back(si, done);
                }
                Src::Fresh => {
                    let y0 = t.y0 as i32;
                    let fresh =
                        match Self::fresh::<N>(frame, &mut stats.triangles, po, &tri, y0, width) {
                            Ok(f) => f,
                            Err(e) => break Err(e),
                        };
                    let Some((mut walk, row, sx, sy)) = fresh else {
                        stats.pixels += k.drawn;
                        continue;
                    };
                    walk.rows(&row, &sx, &sy, y1, width, &mut k);
                    if !walk.done() {
                        cur.keep::<N>(ti as u16, walk, &row, &sx, &sy);
                    }
                }
            }
            stats.pixels += k.drawn;
        };
        r
    }

    /// [`Bands::run`] for the fixed affine profiles (`i32` values, no
    /// perspective) and shaders of at most one attribute: the fused row
    /// kernel of `raster::fast` (the same bytes, see there). A triangle
    /// starting in the band is set up in a scratch walk and values (by
    /// [`fresh_fast`]), walked from there and kept in a free slot when it
    /// continues below the band ([`Cur::keep_fixed`]); a resumed one is
    /// walked in its slot.
    #[inline(never)]
    fn run_fast<const N: usize, S, F, D>(
        &mut self,
        po: &PreparedObject,
        t: &mut Target<'_, F, D>,
        mut shader: S,
        per_tri: impl Fn(&mut S, &PreparedTri),
    ) -> Result<(), RenderError>
    where
        S: Shader<i32, N>,
        F: PixelFormat,
        D: DepthFormat,
    {
        let end = po.tris.end as u32;
        let frame = self.frame;
        let mesh = frame.mesh_tris(po);
        // Flat shaders read the object from a copy of it on ARMv6-M
        // ([`COPY_FLAT`]; the Gouraud bunny measured 26 K more with the
        // copy).
        let copy;
        let po = if N == 0 && COPY_FLAT {
            copy = po.clone();
            &copy
        } else {
            po
        };
        let (y0, y1, width) = (t.y0 as i32, t.y1 as i32, t.width as i32);
        // A triangle that finds no free slot is set up here.
        let mut scratch = (Walk::EMPTY, [[0i32; 3]; V]);
        let fetch = |ti: u32| {
            if N == 1 && cfg!(armv6m) {
                frame.tri_in(po, mesh, ti as usize, false)
            } else {
                frame.tri_of(po, mesh, ti as usize)
            }
        };
        // Setups and pixels counted here, added to the stats at the end.
        let (mut setups, mut pixels) = (0u32, 0u32);
        let cur = &mut self.ls;
        // The band's list taken below `lim` (the next continuing
        // triangle, the object's end): one load and a test a triangle
        // ([`Cur::next`]), the ring and the queue looked at only when the
        // list reaches a continuing triangle ([`Cur::special`]). It
        // replaces a three-way merge of the ring's, the queue's and the
        // order's heads before every triangle (34 instructions a triangle
        // on the Cortex-M4), and its first shortcut (the order's head below
        // the other two, flat and grey Gouraud off ARMv6-M: 21). Exact
        // QEMU counts, raster, with [`COPY_FLAT`]: thumbv7em bunny-gouraud
        // 1 615 109 -> 1 609 209, bunny-flat 1 456 821 -> 1 453 227,
        // dodeca-gouraud 239 432 -> 236 132; thumbv6m bunny-gouraud
        // 2 369 374 -> 2 373 133, bunny-flat 2 055 671 -> 2 052 246,
        // dodeca-flat 122 033 -> 124 046 (the band code's own lines on
        // the Cortex-M4: about 11 K instructions less on the Gouraud bunny;
        // the rest is the inlined kernel's registers). Measured and not
        // kept: the limit in a local (thumbv7em bunny-gouraud 1 618 568,
        // bunny-flat 1 470 301); the band's end tested before each load
        // for flat objects (bunny-flat 1 478 187); the continuing
        // triangles' take out of line off ARMv6-M (bunny-gouraud
        // 1 640 139); the order's list state copied into locals for the
        // run (1 689 897); the setups counted from the list's entries
        // taken (1 650 195).
        cur.s.lim = cur.s.spec.min(end);
        let done = loop {
            let (ti, src) = match cur.next() {
                Some(ti) => (ti, Src::Fresh),
                None => {
                    let Some(t) = cur.special(end) else {
                        break Ok(());
                    };
                    t
                }
            };
            // The mesh looked up once per object (measured on the bunny,
            // Cortex-M4: per triangle cost the flat frame 20 K instructions;
            // the Gouraud frame first 27 K less that way, with the kernel's
            // set-up as it is now 4.2 K more: raster 1 646 369 against
            // 1 642 120 once, thumbv6m 2 694 098 against 2 690 337).
            // ARMv6-M's grey Gouraud objects read without their layout
            // (not flat: no colour): bunny-gouraud raster thumbv6m
            // 2 416 972 -> 2 409 306, every other count the same. Without
            // it everywhere (flat from `N`) cost bunny-flat thumbv6m
            // 2 079 435 -> 2 112 692 and bunny-gouraud thumbv7em
            // 1 631 488 -> 1 661 002.
            // A resumed triangle of values (`N > 0`, no colour of its own:
            // `per_tri` does nothing) is walked without its triangle read
            // (off ARMv6-M: [`SKIP_FETCH`]).
            let tri = if SKIP_FETCH && N > 0 && matches!(src, Src::Slot(_)) {
                PreparedTri::default()
            } else {
                let Some(tri) = fetch(ti) else {
                    break Ok(());
                };
                per_tri(&mut shader, &tri);
                tri
            };
            let mut mem = BandMem::<F::Raw, D::Raw> {
                px: &mut t.px,
                z: &mut t.z,
                y0,
                width,
            };
            let drawn = match src {
                Src::Slot(si) => {
                    let Some(slot) = cur.pool.slots.get_mut(si) else {
                        break Ok(());
                    };
                    let walk = &mut slot.walk;
                    let Some(vals) = P::Lerp::fixed_slots(&mut slot.vals) else {
                        break Ok(());
                    };
                    let drawn = draw_resumed::<N, V, S, F, D>(walk, vals, y1, &mut mem, &shader);
                    let done = walk.done();
                    cur.put_back(si, done);
                    drawn
                }
                Src::Fresh => {
                    // The continuation written straight into the free slot
                    // a kept triangle would take ([`Cur::take_slot`]),
                    // else into the scratch and queued.
                    let free = cur.free_slot::<N>();
                    let target = free.and_then(|si| cur.pool.slots.get_mut(si as usize));
                    let (walk, vals) = match target {
                        Some(slot) if IN_PLACE => match P::Lerp::fixed_slots(&mut slot.vals) {
                            Some(v) => (&mut slot.walk, v),
                            None => (&mut scratch.0, &mut scratch.1),
                        },
                        _ => (&mut scratch.0, &mut scratch.1),
                    };
                    match fresh_fast::<P, N, V, S, F, D>(
                        frame, po, &tri, y1, &mut mem, walk, vals, &shader,
                    ) {
                        Err(e) => break Err(e),
                        Ok(Some((drawn, more))) => {
                            setups += 1;
                            // Kept in a slot when it continues below the band.
                            if more {
                                match free {
                                    Some(si) if IN_PLACE => cur.take_slot::<N>(ti as u16, si),
                                    _ => cur.keep_fixed::<N>(ti as u16, &scratch.0, &scratch.1),
                                }
                            }
                            drawn
                        }
                        Ok(None) => 0,
                    }
                }
            };
            pixels += drawn;
        };
        self.stats.triangles += setups;
        self.stats.pixels += pixels;
        done
    }

    /// Sets up triangle `tri` of object `po` from row `max(first row,
    /// j0)`; `None` when it draws nothing from there (or a vertex is
    /// missing).
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn fresh<const N: usize>(
        frame: &Frame<'_, P>,
        triangles: &mut u32,
        po: &PreparedObject,
        tri: &PreparedTri,
        j0: i32,
        width: i32,
    ) -> Result<Option<(Walk, Vals<P::Lerp, N>, Vals<P::Lerp, N>, Vals<P::Lerp, N>)>, RenderError>
    {
        let sub = P::SUBPIXEL_BITS;
        let xy = |i: u16| frame.xy(usize::from(i));
        let (Some(p0), Some(p1), Some(p2)) = (xy(tri.v[0]), xy(tri.v[1]), xy(tri.v[2])) else {
            return Ok(None);
        };
        // All six coordinates within ±lim at once, without branches: `v`
        // lies in `[-lim, lim]` exactly when `v + lim` (wrapping) is in
        // `[0, 2·lim]` as a `u32` (`lim <= 2^21`); the same test as
        // `in_limits`, whose vertex index is looked for only on failure.
        let lim = sub.coord_limit();
        let off = |v: i32| (v.wrapping_add(lim) as u32 > (2 * lim) as u32) as u32;
        let outside = off(p0[0]) | off(p0[1]) | off(p1[0]) | off(p1[1]) | off(p2[0]) | off(p2[1]);
        let [(i0, q0), (i1, q1), (i2, q2)] =
            sort3([(tri.v[0], p0), (tri.v[1], p1), (tri.v[2], p2)], |v| v.1[1]);
        let (Some(a), Some(b), Some(c)) = (
            frame.vertex::<N>(po, i0, q0),
            frame.vertex::<N>(po, i1, q1),
            frame.vertex::<N>(po, i2, q2),
        ) else {
            return Ok(None);
        };
        *triangles += 1;
        if outside != 0 {
            let i = [p0, p1, p2]
                .iter()
                .position(|&[x, y]| !in_limits(x, y, sub))
                .unwrap_or(0);
            return Err(RasterError::OutOfRange(i as u8).into());
        }
        Ok(setup::<P::Lerp, N>(&a, &b, &c, sub, j0, width))
    }
}

/// The band's list and the pool's lists: where each stands (kept in
/// [`Bands`], reached through a [`Cur`] while an object's part of a band
/// is drawn).
#[derive(Clone, Copy, Debug)]
struct Streams {
    /// Next entry of the band's list in the run.
    cursor: usize,
    /// End of the band's list (the entries of the order starting in the
    /// band; the entry there, when the run holds one, is replaced by
    /// [`SENTINEL`] while the band is drawn).
    band_end: usize,
    /// A triangle put off while the pool was full found the queue full
    /// too (the rest of the order): the band is reported as an error.
    lost: bool,
    /// Entries of the free stack.
    free_len: usize,
    /// Pool ring (the slots continuing below the band, in triangle
    /// order): first entry, entries of the band above still to resume,
    /// entries in all.
    ring_head: usize,
    ring_cur: usize,
    ring_len: usize,
    /// Queue of triangles that found the pool full (a ring in the order's
    /// entries past the run): first entry, entries of the band above,
    /// entries in all.
    def_head: usize,
    def_cur: usize,
    def_len: usize,
    /// The first triangle of the ring and of the queue this band
    /// ([`NONE`] when exhausted), and the least of them: the next
    /// continuing triangle, before which the band's list is taken
    /// without looking at the ring or the queue ([`Cur::next`]).
    heads: [u32; 2],
    spec: u32,
    /// The least of `spec` and the end of the object being drawn.
    lim: u32,
    /// Most triangles kept at once so far (in the pool, or queued when it
    /// was full).
    peak: usize,
}

/// The list entry that ends a band's list (above every triangle number
/// and object end).
const SENTINEL: u16 = u16::MAX;

/// The band's triangles and the pool: the run of the order (the band's
/// list in it), the queue, the pool's slots and lists, and where each
/// stands.
#[derive(Debug)]
struct Cur<'s, L, const CAP: usize, const V: usize> {
    run: &'s mut [u16],
    queue: &'s mut [u16],
    pool: &'s mut Active<L, CAP, V>,
    s: Streams,
}

impl<L: Lerp, const CAP: usize, const V: usize> Cur<'_, L, CAP, V> {
    /// Starts the band: the ring's and the queue's entries (the triangles
    /// continuing from the band above) made this band's, the sentinel placed at `band_end` (its entry
    /// returned, to be put back by [`Cur::end_band`]).
    #[inline(never)]
    fn start_band(&mut self) -> Option<u16> {
        self.s.ring_cur = self.s.ring_len;
        self.s.def_cur = self.s.def_len;
        self.s.heads = [self.ring_head_tri(), self.queue_head()];
        self.s.spec = self.s.heads[0].min(self.s.heads[1]);
        let end = self.s.band_end;
        self.run
            .get_mut(end)
            .map(|e| core::mem::replace(e, SENTINEL))
    }

    /// Ends the band: the entry under the sentinel put back.
    #[inline(always)]
    fn end_band(&mut self, under: Option<u16>) {
        let end = self.s.band_end;
        if let (Some(e), Some(u)) = (self.run.get_mut(end), under) {
            *e = u;
        }
    }

    /// The triangle at the head of the pool's ring when it is to be
    /// resumed this band.
    #[inline(always)]
    fn ring_head_tri(&self) -> u32 {
        if self.s.ring_cur > 0 {
            self.pool
                .ring
                .get(self.s.ring_head)
                .and_then(|&s| self.pool.slots.get(s as usize))
                .map_or(NONE, |s| s.tri as u32)
        } else {
            NONE
        }
    }

    /// The triangle at the head of the queue when it is to be set up
    /// this band.
    #[inline(always)]
    fn queue_head(&self) -> u32 {
        if self.s.def_cur > 0 {
            self.queue.get(self.s.def_head).map_or(NONE, |&t| t as u32)
        } else {
            NONE
        }
    }

    /// The first triangle of the band ([`NONE`] when it has none).
    #[inline(always)]
    fn first(&self) -> u32 {
        let k = self.s.cursor;
        let e = if k < self.s.band_end {
            self.run.get(k).map_or(NONE, |&e| u32::from(e))
        } else {
            NONE
        };
        e.min(self.s.spec)
    }

    /// The band list's next entry when it lies below `lim` (the next
    /// continuing triangle, [`Streams::spec`], and the object's end): taken
    /// (`Ok`), one load and a test; else the entry (`Err`, [`NONE`] past
    /// the run's last; the sentinel at the band's end).
    #[inline(always)]
    fn next(&mut self) -> Option<u32> {
        let k = self.s.cursor;
        let e = u32::from(*self.run.get(k)?);
        if e < self.s.lim {
            self.s.cursor = k + 1;
            Some(e)
        } else {
            None
        }
    }

    /// After [`Cur::next`] gave entry `e`: the next continuing triangle
    /// when it lies below both `e` and `end` (the object's end), taken:
    /// resumed from its slot (the ring's) or set up afresh (the queue's);
    /// else `None`.
    ///
    /// Out of line on ARMv6-M: exact QEMU counts, raster thumbv6m
    /// bunny-flat 2 076 244 -> 2 052 246, bunny-gouraud 2 353 642 ->
    /// 2 373 133 (out of line on ARMv7-M too: bunny-gouraud thumbv7em
    /// 1 609 209 -> 1 640 139).
    #[cfg_attr(armv6m, inline(never))]
    #[cfg_attr(not(armv6m), inline(always))]
    fn special(&mut self, end: u32) -> Option<(u32, Src)> {
        let k = self.s.cursor;
        let e = self.run.get(k).map_or(NONE, |&e| u32::from(e));
        let sp = self.s.spec;
        if sp >= end || sp >= e {
            return None;
        }
        let src = if sp == self.s.heads[0] {
            Src::Slot(self.next_in_ring())
        } else {
            self.next_in_queue();
            Src::Fresh
        };
        self.s.spec = self.s.heads[0].min(self.s.heads[1]);
        self.s.lim = self.s.spec.min(end);
        Some((sp, src))
    }

    /// Takes the ring's head: its slot, the ring's next head made.
    #[inline(always)]
    fn next_in_ring(&mut self) -> usize {
        let si = self.pool.ring.get(self.s.ring_head).copied().unwrap_or(0) as usize;
        self.s.ring_head = wrap(self.s.ring_head + 1, CAP);
        self.s.ring_cur -= 1;
        self.s.ring_len -= 1;
        self.s.heads[0] = self.ring_head_tri();
        si
    }

    /// Takes the queue's head, its next head made.
    #[inline(always)]
    fn next_in_queue(&mut self) {
        self.s.def_head = wrap(self.s.def_head + 1, self.queue.len());
        self.s.def_cur -= 1;
        self.s.def_len -= 1;
        self.s.heads[1] = self.queue_head();
    }

    /// Returns slot `si` to the free stack.
    #[inline(always)]
    fn free(&mut self, si: usize) {
        if let Some(f) = self.pool.free.get_mut(self.s.free_len) {
            *f = si as u16;
            self.s.free_len += 1;
        }
    }

    /// Appends slot `si` to the ring's tail (continuing below the band).
    #[inline(always)]
    fn ring_push(&mut self, si: u16) {
        let tail = wrap(self.s.ring_head + self.s.ring_len, CAP);
        if let Some(r) = self.pool.ring.get_mut(tail) {
            *r = si;
            self.s.ring_len += 1;
        }
    }

    /// Returns slot `si`, its walk walked in place in this band: to the
    /// free stack when the triangle is `done`, else to the ring for the
    /// next band.
    #[inline(always)]
    fn put_back(&mut self, si: usize, done: bool) {
        if done {
            self.free(si);
        } else {
            self.ring_push(si as u16);
        }
    }

    /// Takes a free slot for a triangle continuing below the band with
    /// `N` values (`None`: none free, or `N >= V`).
    #[inline(always)]
    fn take_free<const N: usize>(&mut self) -> Option<u16> {
        if N < V && self.s.free_len > 0 {
            self.s.free_len -= 1;
            self.pool.free.get(self.s.free_len).copied()
        } else {
            None
        }
    }

    /// The most triangles kept at once, updated.
    #[inline(always)]
    fn note_peak(&mut self) {
        self.s.peak = self.s.peak.max(CAP - self.s.free_len + self.s.def_len);
    }

    /// Keeps a triangle that continues below the band: in a free slot, or
    /// in the queue of those set up afresh in the next band.
    #[inline(always)]
    fn keep<const N: usize>(
        &mut self,
        ti: u16,
        walk: Walk,
        row: &Vals<L, N>,
        sx: &Vals<L, N>,
        sy: &Vals<L, N>,
    ) {
        let slot = self
            .take_free::<N>()
            .and_then(|si| Some((si, self.pool.slots.get_mut(usize::from(si))?)));
        match slot {
            Some((si, slot)) => {
                slot.tri = ti;
                slot.walk = walk;
                pack_vals::<_, N, V>(&mut slot.vals, row, sx, sy);
                self.ring_push(si);
            }
            None => self.defer(ti),
        }
        self.note_peak();
    }

    /// [`Cur::keep`] for the fast path: the walk and the values copied
    /// into a free slot, or the triangle queued.
    #[inline(always)]
    fn keep_fixed<const N: usize>(&mut self, ti: u16, walk: &Walk, vals: &[[i32; 3]; V]) {
        let slot = self
            .take_free::<N>()
            .and_then(|si| Some((si, self.pool.slots.get_mut(usize::from(si))?)));
        match slot {
            Some((si, slot)) => {
                slot.tri = ti;
                walk.copy_to(&mut slot.walk);
                if let Some(v) = L::fixed_slots(&mut slot.vals) {
                    // The depth and the N values in use, not the whole slot.
                    for (d, s) in v.iter_mut().zip(vals).take(N + 1) {
                        *d = *s;
                    }
                }
                self.ring_push(si);
            }
            None => self.defer(ti),
        }
        self.note_peak();
    }

    /// The slot a fast triangle continuing below the band takes: the free
    /// stack's top (`None` when the pool is full or the values do not fit,
    /// `N >= V`). Not taken yet ([`Cur::take_slot`]).
    #[inline(always)]
    fn free_slot<const N: usize>(&self) -> Option<u16> {
        if N < V && self.s.free_len > 0 {
            self.pool.free.get(self.s.free_len - 1).copied()
        } else {
            None
        }
    }

    /// Takes slot `si` ([`Cur::free_slot`], its walk and values written
    /// in place) for triangle `ti`: off the free stack, onto the ring.
    #[inline(always)]
    fn take_slot<const N: usize>(&mut self, ti: u16, si: u16) {
        self.s.free_len -= 1;
        if let Some(slot) = self.pool.slots.get_mut(si as usize) {
            slot.tri = ti;
        }
        self.ring_push(si);
        self.note_peak();
    }

    /// Queues a triangle that continues below the band but has no slot:
    /// set up afresh in the next band.
    #[inline(always)]
    fn defer(&mut self, ti: u16) {
        // The queue: a ring in the order's entries outside the run.
        let len = self.queue.len();
        let tail = wrap(self.s.def_head + self.s.def_len, len);
        match self.queue.get_mut(tail) {
            Some(q) if self.s.def_len < len => {
                *q = ti;
                self.s.def_len += 1;
            }
            _ => self.s.lost = true,
        }
    }
}

/// `x mod m` for `x < 2·m`, the positions in the pool's ring (`m` =
/// its slots) and in the queue (`m` = its entries): a head
/// below `m` plus an entry count at most `m`. No division (a library call
/// on ARMv6-M: bunny-gouraud raster thumbv6m 3 151 780 -> 3 112 736,
/// thumbv7em 2 172 222 -> 2 148 352). A
/// position that breaks that bound stays out of range and is ignored by
/// the checked accesses.
#[inline(always)]
fn wrap(x: usize, m: usize) -> usize {
    if x >= m {
        x - m
    } else {
        x
    }
}

/// Resumed triangles of values walked without their triangle read
/// ([`Bands::run_fast`]; `per_tri` does nothing for them): exact QEMU
/// counts, bunny-gouraud raster thumbv7em 1 657 797 -> 1 622 563 (with
/// the resume kernel), bunny-flat unchanged. On ARMv6-M too since the
/// band list ([`Cur::next`]): bunny-gouraud raster thumbv6m 2 373 133 ->
/// 2 359 307, every other count the same (before it, the first form of
/// it, the fetch moved into both arms, cost there 2 369 374 -> 2 383 904,
/// and bunny-flat thumbv7em 1 456 821 -> 1 469 333).
const SKIP_FETCH: bool = true;

/// A fast triangle that continues below its band writes its walk and
/// values straight into the slot it takes ([`Cur::free_slot`], taken
/// before the set-up), not into a scratch copied into the slot afterwards
/// ([`Cur::keep_fixed`]). Off: exact QEMU counts, bunny-gouraud raster
/// thumbv7em 1 624 644 -> 1 674 453, thumbv6m 2 379 156 -> 2 424 753
/// (the slot's address, a run-time value, live across the whole inlined
/// kernel instead of the scratch's fixed stack place). Taken after the
/// set-up instead (measured, not kept: [`draw_small`] handed a `Carry`
/// that takes the slot only when the triangle continues, the walk and
/// values then written in place): the slot's bookkeeping in a closure
/// inlined into the kernel, 1 697 479; out of line (42 instructions a
/// kept triangle) with the slot returned to the kernel's tail,
/// 1 652 332 against 1 615 109 (bunny-flat 1 456 821 -> 1 490 265;
/// thumbv6m bunny-gouraud 2 369 374 -> 2 363 070, bunny-flat 2 055 671 ->
/// 2 082 781). [`Cur::keep_fixed`] out of line: 1 615 109 -> 1 637 080.
const IN_PLACE: bool = false;

/// Flat objects read from a copy of the object ([`Bands::run_fast`]), on
/// ARMv6-M only. Exact QEMU counts with the band list ([`Cur::next`]),
/// bunny-flat raster: thumbv7em 1 477 404 with the copy, 1 453 227 in
/// place (bunny-gouraud unchanged); thumbv6m 2 052 246 with it,
/// 2 086 012 in place. Grey Gouraud objects from a copy too: bunny-gouraud
/// thumbv7em 1 609 209 -> 1 642 612, thumbv6m 2 359 307 -> 2 371 511.
/// (Before the band list, the copy measured the
/// dodecahedron's flat frame 1.7 K and the bunny's 7 K instructions less
/// on the Cortex-M4.)
const COPY_FLAT: bool = cfg!(armv6m);

/// Where a band's next triangle comes from.
#[derive(Clone, Copy, Debug)]
enum Src {
    /// Resumed from this pool slot.
    Slot(usize),
    /// Set up afresh (starting in the band, or queued when the pool was
    /// full).
    Fresh,
}

/// Calls `$walk` with `$c` bound to the colour of shader `$shader` in
/// pixel format `$F`: its constant colour encoded once, or its colour per
/// pixel. One body for [`draw_fused`] and [`draw_resumed`], which stay
/// two functions: one generic function for both kernels (a `const`
/// switch) measured bunny-gouraud raster thumbv7em 1 615 109 ->
/// 1 617 190 and bunny-flat 1 456 821 -> 1 461 504 (the inlining order
/// follows the functions' names).
macro_rules! by_color {
    ($shader:expr, $F:ty, $N:ident, |$c:ident| $walk:expr) => {
        if let Some(c) = $shader.constant() {
            let raw = <$F>::encode(c);
            let $c = move |_: &[i32; $N]| raw;
            $walk
        } else {
            let $c = |a: &[i32; $N]| $shader.shade_raw::<$F>(a);
            $walk
        }
    };
}

/// Walks a fixed triangle with the fused row kernel: the shader's
/// constant colour encoded once, or its colour per pixel.
#[inline(always)]
fn draw_fused<const N: usize, const V: usize, S: Shader<i32, N>, F: PixelFormat, D: DepthFormat>(
    walk: &mut Walk,
    vals: &[[i32; 3]; V],
    until: i32,
    mem: &mut BandMem<'_, '_, F::Raw, D::Raw>,
    shader: &S,
) -> u32 {
    by_color!(shader, F, N, |color| walk
        .rows_fused::<N, V, F::Raw, D>(vals, until, mem, color))
}

/// Walks a resumed fixed triangle (a pool slot's walk and values, in
/// place) with the resume kernel ([`Walk::rows_resumed`]): the shader's
/// constant colour encoded once, or its colour per pixel.
#[inline(always)]
fn draw_resumed<
    const N: usize,
    const V: usize,
    S: Shader<i32, N>,
    F: PixelFormat,
    D: DepthFormat,
>(
    walk: &mut Walk,
    vals: &[[i32; 3]; V],
    until: i32,
    mem: &mut BandMem<'_, '_, F::Raw, D::Raw>,
    shader: &S,
) -> u32 {
    by_color!(shader, F, N, |color| walk
        .rows_resumed::<N, V, F::Raw, D>(vals, until, mem, color))
}

/// A triangle of the fast path starting in the band (or set up afresh):
/// fetched, set up and walked down to the band's end `until` by the
/// small-triangle kernel ([`draw_small`]) or, when that does not apply,
/// by the 32-bit setup and the fused row kernel; a function of its own so
/// that its registers are not shared with the stream merge of
/// [`Bands::run_fast`]. `Ok(None)` when a vertex is missing, else the
/// pixels drawn and whether the triangle continues below the band (its
/// walk and values then in `walk` and `vals`).
///
/// Inlined: measured on the Cortex-M4 (exact QEMU counts, bunny-gouraud
/// raster 1 833 849 inlined), out of line it took 2 060 328; its general
/// part (the 32-bit setup and the fused row kernel, 63 of the bunny's
/// 1 498 triangles) out of line and `#[cold]` 1 972 131; [`setup_fixed`]
/// out of line 1 861 990; the object's values sliced once per object
/// rather than per triangle 1 852 644 (one more value live across the
/// stream merge); `packed` from the layout constant rather than the
/// object 1 849 386.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn fresh_fast<P: Profile, const N: usize, const V: usize, S, F, D>(
    frame: &Frame<'_, P>,
    po: &PreparedObject,
    tri: &PreparedTri,
    until: i32,
    mem: &mut BandMem<'_, '_, F::Raw, D::Raw>,
    walk: &mut Walk,
    vals: &mut [[i32; 3]; V],
    shader: &S,
) -> Result<Option<(u32, bool)>, RenderError>
where
    S: Shader<i32, N>,
    F: PixelFormat,
    D: DepthFormat,
{
    let Some(v) = fetch_fixed::<P, N>(frame, po, tri) else {
        return Ok(None);
    };
    let sub = P::SUBPIXEL_BITS;
    // Packed grey vertices hold their words ([`fetch_fixed`]): depths and
    // levels from their 16-bit fields.
    let packed = N == 1 && Layout::GouraudMono.packed_in::<P>();
    // The object's triangles fit the kernel's fast head (prepare's
    // [`PreparedObject::kernel_fit`]).
    let fit = po.kernel_fit();
    if let Some(r) =
        draw_small_shaded::<N, V, S, F, D>(&v, sub, until, mem, walk, vals, packed, fit, shader)
    {
        return Ok(Some(r));
    }
    // The general path takes the values.
    let v = if packed {
        v.map(|p| Vertex {
            z: grey_z(p.z),
            attrs: p.attrs.map(grey_l),
            ..p
        })
    } else {
        v
    };
    in_limits_fixed::<P, N>(frame, tri, &v)?;
    // Set up and walked in the scratch.
    let drawn = if setup_fixed::<N, V>(v, sub, mem.y0, mem.width, walk, vals) {
        draw_fused::<N, V, S, F, D>(walk, vals, until, mem, shader)
    } else {
        0
    };
    Ok(Some((drawn, !walk.done())))
}

/// The vertices of triangle `tri` of object `po`, sorted by `y`, with
/// their depths and first `N` values as fixed-point `i32`s (each corner
/// and its values read once), a packed grey vertex with its word as both
/// (for [`draw_small`]'s `packed`; [`fresh_fast`] unpacks it for the
/// general path: bunny-gouraud raster thumbv7em 1 749 614 -> 1 719 996,
/// thumbv6m 2 734 554 -> 2 728 342); `None` when a vertex is missing. Positions
/// are not checked against the rasterizer's limits ([`in_limits_fixed`]).
/// The fast path's objects only ([`Bands::run_fast`]): flat ones for `N =
/// 0`, grey Gouraud ones for `N = 1`, so that the layout follows from `N`
/// (and the profile: packed or not) without reading it. Packed grey and
/// flat vertices (one value each) are read straight from the object's
/// values, the same ones [`Frame::vertex`] reads: exact QEMU counts,
/// bunny-gouraud raster thumbv7em 1 891 494 -> 1 840 648 -> 1 837 546,
/// thumbv6m 2 936 823 -> 2 919 764 -> 2 899 188; bunny-flat thumbv7em
/// 1 589 795 -> 1 584 846 -> 1 571 349, thumbv6m 2 454 888 -> 2 443 138
/// -> 2 430 264 (the second step: the layout from `N`). Measured and not
/// kept: the corners sorted as their stored words (one load a corner,
/// two registers through the sort, `y` the high half, unpacked after the
/// sort), bunny-gouraud raster thumbv7em 1 578 408 -> 1 628 560,
/// bunny-flat 1 422 709 -> 1 449 818 (thumbv6m 2 032 058 -> 2 104 930);
/// later (from 1 567 929, bunny-flat 1 398 776, 2 005 847) the `y`s alone
/// through the sort and the `x`s read after it, 1 616 537 (bunny-flat
/// 1 428 976, 2 045 544).
#[inline(always)]
pub(super) fn fetch_fixed<P: Profile, const N: usize>(
    frame: &Frame<'_, P>,
    po: &PreparedObject,
    tri: &PreparedTri,
) -> Option<[Vertex<i32, N>; 3]> {
    if N == 1 && cfg!(armv6m) && Layout::GouraudMono.packed_in::<P>() {
        return fetch_grey_then_sort(frame, po, tri);
    }
    let xy = |i: u16| frame.xy(usize::from(i));
    let (p0, p1, p2) = (xy(tri.v[0])?, xy(tri.v[1])?, xy(tri.v[2])?);
    let [(i0, q0), (i1, q1), (i2, q2)] =
        sort3([(tri.v[0], p0), (tri.v[1], p1), (tri.v[2], p2)], |v| v.1[1]);
    if N == 1 && Layout::GouraudMono.packed_in::<P>() {
        // Packed grey (`N = 1`: a grey Gouraud object): one value per
        // vertex (the layout's stride, 1), read from the object's values
        // as `Frame::vertex` reads it (`None` for a vertex not of the
        // object), left packed: the word as the depth and as the value
        // (the small kernel takes the fields where it needs them, the
        // general path unpacks: [`fresh_fast`]).
        let (vals, off) = val_index(frame, po);
        let grey = |i, p| grey_vertex::<P, N>(vals, off, i, p);
        return Some([grey(i0, q0)?, grey(i1, q1)?, grey(i2, q2)?]);
    }
    if N == 0 {
        // Flat (`N = 0`): the depth alone, one value per vertex (the layout's
        // stride, 1), read as `Frame::vertex` reads it.
        let (vals, off) = val_index(frame, po);
        let flat = |i: u16, [x, y]: [i32; 2]| -> Option<Vertex<i32, N>> {
            Some(Vertex {
                x,
                y,
                z: vals.get(usize::from(i).wrapping_add(off))?.fixed_raw()?,
                attrs: [0; N],
            })
        };
        return Some([flat(i0, q0)?, flat(i1, q1)?, flat(i2, q2)?]);
    }
    let raw = |v: Option<Vertex<P::Lerp, N>>| -> Option<Vertex<i32, N>> {
        let v = v?;
        let mut attrs = [0; N];
        for (o, a) in attrs.iter_mut().zip(v.attrs.iter()) {
            *o = a.fixed_raw()?;
        }
        Some(Vertex {
            x: v.x,
            y: v.y,
            z: v.z.fixed_raw()?,
            attrs,
        })
    };
    Some([
        raw(frame.vertex::<N>(po, i0, q0))?,
        raw(frame.vertex::<N>(po, i1, q1))?,
        raw(frame.vertex::<N>(po, i2, q2))?,
    ])
}

/// [`fetch_fixed`] of a packed grey triangle (`N = 1`) with each corner's
/// value read before the sort, the sort moving whole vertices rather than
/// vertex indices (the same order: the same compares on the same `y`s;
/// `None` for the same triangles; tested equal). Taken on ARMv6-M, where
/// the index no longer lives through the sort: bunny-gouraud raster
/// thumbv6m 2 409 306 -> 2 404 762 (written in `fetch_fixed` itself
/// 2 403 792, kept apart to be tested on the host; the value read with
/// each position rather than after all three 2 406 320). On the Cortex-M4
/// it cost 1 631 488 -> 1 666 991; for flat triangles (`N = 0`) on
/// ARMv6-M bunny-flat 2 079 435 -> 2 099 777. Sorting a raw position with the index packed in one word
/// (two registers a corner) measured 2 432 985 and bunny-flat 2 127 385 on
/// thumbv6m (from 2 426 630 and 2 079 435); the raw positions sorted
/// before adding the origin 2 551 249.
#[inline(always)]
pub(super) fn fetch_grey_then_sort<P: Profile, const N: usize>(
    frame: &Frame<'_, P>,
    po: &PreparedObject,
    tri: &PreparedTri,
) -> Option<[Vertex<i32, N>; 3]> {
    let xy = |i: u16| frame.xy(usize::from(i));
    let (p0, p1, p2) = (xy(tri.v[0])?, xy(tri.v[1])?, xy(tri.v[2])?);
    let (vals, off) = val_index(frame, po);
    let grey = |i, p| grey_vertex::<P, N>(vals, off, i, p);
    let v = [
        grey(tri.v[0], p0)?,
        grey(tri.v[1], p1)?,
        grey(tri.v[2], p2)?,
    ];
    Some(sort3(v, |v| v.y))
}

/// Vertex `i` of a packed grey object at position `[x, y]`: its value
/// (at `off` from `i` in `vals`, as [`val_index`] gives them) read as
/// `Frame::vertex` reads it and left packed, the word as the depth and as
/// the value; `None` for a vertex not of the object.
#[inline(always)]
fn grey_vertex<P: Profile, const N: usize>(
    vals: &[P::Lerp],
    off: usize,
    i: u16,
    [x, y]: [i32; 2],
) -> Option<Vertex<i32, N>> {
    let w = vals.get(usize::from(i).wrapping_add(off))?.fixed_raw()?;
    Some(Vertex {
        x,
        y,
        z: w,
        attrs: [w; N],
    })
}

/// The frame's values and the offset (wrapping) that takes a vertex of
/// object `po` with one value per vertex to its value: `val_base + i -
/// verts.start` for vertex `i`, one addition and one bounds test per
/// vertex (rather than the object's values sliced per triangle: exact
/// QEMU counts, bunny-gouraud raster thumbv7em 1 675 080 -> 1 658 600,
/// thumbv6m 2 733 115 -> 2 717 413). A vertex index that is not the object's reads another value
/// or none, never out of bounds (prepared triangles name their object's
/// vertices).
#[inline(always)]
fn val_index<'f, P: Profile>(
    frame: &'f Frame<'_, P>,
    po: &PreparedObject,
) -> (&'f [P::Lerp], usize) {
    let off = po.val_base().wrapping_sub(usize::from(po.verts.start));
    (&frame.ws.vals[..], off)
}

/// The error of a fetched triangle ([`fetch_fixed`]) with a vertex
/// outside the rasterizer's limits (the index of the first such vertex
/// in `tri`'s order), else `Ok`.
#[inline(always)]
fn in_limits_fixed<P: Profile, const N: usize>(
    frame: &Frame<'_, P>,
    tri: &PreparedTri,
    v: &[Vertex<i32, N>; 3],
) -> Result<(), RenderError> {
    let sub = P::SUBPIXEL_BITS;
    let lim = sub.coord_limit();
    let off = |v: i32| (v.wrapping_add(lim) as u32 > (2 * lim) as u32) as u32;
    let outside = v.iter().fold(0, |o, v| o | off(v.x) | off(v.y));
    if outside != 0 {
        return Err(out_of_limits(frame, tri));
    }
    Ok(())
}

/// [`in_limits_fixed`]'s error, out of line.
#[cold]
#[inline(never)]
fn out_of_limits<P: Profile>(frame: &Frame<'_, P>, tri: &PreparedTri) -> RenderError {
    let sub = P::SUBPIXEL_BITS;
    let i = tri
        .v
        .iter()
        .position(|&i| {
            frame
                .xy(usize::from(i))
                .is_some_and(|[x, y]| !in_limits(x, y, sub))
        })
        .unwrap_or(0);
    RasterError::OutOfRange(i as u8).into()
}

/// [`draw_small_shaded`] takes [`draw_small`] with `LEVELS` for the grey level
/// (`N = 1`): on ARMv6-M, where the clamp costs five instructions a pixel
/// (bunny-gouraud raster thumbv6m 2 888 025 -> 2 866 494), and off ARM
/// (x86-64 clamps in five instructions where ARMv7-M has one `USAT`:
/// the host's bunny frame, callgrind, 2 351 001 -> 2 324 508). The
/// ARMv7-M path is checked by the firmware's frames under QEMU.
const LEVELS_IN_RANGE: bool = NO_LONG_MUL || !cfg!(target_arch = "arm");

/// Draws a fetched triangle ([`fetch_fixed`]) with the small-triangle
/// kernel ([`draw_small`]) when it applies: the shader's constant colour
/// encoded once, or its colour per pixel; `None` (nothing drawn) when the
/// triangle needs the general path, else the pixels drawn and whether it
/// continues below the band (in `walk` and `vals`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn draw_small_shaded<
    const N: usize,
    const V: usize,
    S: Shader<i32, N>,
    F: PixelFormat,
    D: DepthFormat,
>(
    v: &[Vertex<i32, N>; 3],
    sub: SubpixelBits,
    until: i32,
    mem: &mut BandMem<'_, '_, F::Raw, D::Raw>,
    walk: &mut Walk,
    vals: &mut [[i32; 3]; V],
    packed: bool,
    fit: bool,
    shader: &S,
) -> Option<(u32, bool)> {
    if let Some(c) = shader.constant() {
        let raw = F::encode(c);
        draw_small::<N, V, F::Raw, D, false>(
            v,
            sub,
            until,
            mem,
            walk,
            vals,
            packed,
            fit,
            move |_| raw,
        )
    } else if N == 1 && LEVELS_IN_RANGE {
        // One grey level (the fast path's `N = 1` shader is
        // [`GouraudMono`]): without the clamp where the triangle allows it.
        draw_small::<N, V, F::Raw, D, true>(v, sub, until, mem, walk, vals, packed, fit, |a| {
            shader.shade_raw_in_range::<F>(a)
        })
    } else {
        draw_small::<N, V, F::Raw, D, false>(v, sub, until, mem, walk, vals, packed, fit, |a| {
            shader.shade_raw::<F>(a)
        })
    }
}

/// Sets a fetched triangle ([`fetch_fixed`]) up for the fused row kernel
/// from row `max(first row, j0)` into `walk` and `vals` (a pool slot's, or
/// the scratch): `true` when it draws rows from there, `false` (and `walk`
/// done) when it draws none. A function of its own on ARMv6-M (its live
/// state then does not share the eight low registers with the row
/// loop's); inlined elsewhere (out of line, thumbv7em bunny-gouraud raster
/// took 2.317 -> 2.351 M). The vertices by value: a copy on this path
/// only, not a vertex array in memory on every path.
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline(always))]
fn setup_fixed<const N: usize, const V: usize>(
    v: [Vertex<i32, N>; 3],
    sub: SubpixelBits,
    j0: i32,
    width: i32,
    walk: &mut Walk,
    vals: &mut [[i32; 3]; V],
) -> bool {
    let [a, b, c] = &v;
    let set = setup_fast::<N, V>(a, b, c, sub, j0, width, walk, vals);
    if !set {
        *walk = Walk::EMPTY;
    }
    set
}

/// A slot's values as the walker's row values and steps.
#[inline(always)]
fn unpack<L: Lerp, const N: usize, const V: usize>(
    v: &[[L; 3]; V],
) -> (Vals<L, N>, Vals<L, N>, Vals<L, N>) {
    let get = |k: usize, c: usize| v.get(k).map_or(L::ZERO, |x| x[c]);
    let f = |c: usize| Vals {
        z: get(0, c),
        a: core::array::from_fn(|k| get(k + 1, c)),
    };
    (f(0), f(1), f(2))
}

#[cfg(test)]
mod place_tests {
    use super::{place_backwards, EPOCH, FACE_ROW, RADIX_BITS};
    use crate::geom::testkit::xorshift;

    /// The backwards placing pass (ARMv6-M's) gives the stable order by
    /// band (ascending numbers within a band) and the bands' ends, on
    /// random bytes (kept or not, back faces,
    /// bands within and outside the run) and on the extremes (no kept
    /// byte, every byte kept in one band, lengths 0 to 9).
    #[test]
    fn backwards_equals_words() {
        let mut rnd = xorshift(0x5eed_0014);
        const ROWS: usize = FACE_ROW as usize + 1;
        for case in 0..400 {
            let len = match case {
                0..=9 => case,
                _ => (rnd() % 600) as usize,
            };
            // A band per row code: within the run (below `EPOCH`) or not.
            let mut band = [EPOCH as u8; ROWS];
            for (c, b) in band.iter_mut().enumerate().skip(1) {
                *b = match case % 3 {
                    0 => ((c - 1) / 8) as u8,
                    1 => (rnd() % 80).min(u64::from(EPOCH)) as u8,
                    _ => 5,
                };
            }
            let faces: [u8; 600] = core::array::from_fn(|_| match case % 4 {
                0 => 0,
                1 => (rnd() % 256) as u8,
                // Mostly not kept, some back faces.
                _ => {
                    (if rnd().is_multiple_of(3) {
                        rnd() % 256
                    } else {
                        rnd() % 2 * 128
                    }) as u8
                }
            });
            let faces = &faces[..len];
            // The prefix sums of the bands' counts.
            let mut count = [0u16; ROWS];
            for &b in faces {
                let k = usize::from(band[usize::from(b & FACE_ROW)]);
                if b & FACE_ROW != 0 && k < EPOCH as usize {
                    count[k + 1] += 1;
                }
            }
            let mut sum = 0;
            for c in count.iter_mut().take(EPOCH as usize + 1) {
                sum += *c;
                *c = sum;
            }
            let n = usize::from(sum);
            // The reference: band by band, the kept numbers in order.
            let (mut want, mut want_ends, mut m) = ([u16::MAX; 600], [0u16; 1 << RADIX_BITS], 0);
            for (k, e) in want_ends.iter_mut().enumerate() {
                for (i, &b) in faces.iter().enumerate() {
                    if b & FACE_ROW != 0 && usize::from(band[usize::from(b & FACE_ROW)]) == k {
                        want[m] = i as u16;
                        m += 1;
                    }
                }
                *e = m as u16;
            }
            assert_eq!(m, n, "case {case}");
            let mut got = [u16::MAX; 600];
            let mut c = count;
            let ends = place_backwards(faces, &band, &mut c, &mut got[..n]);
            assert_eq!(ends, want_ends, "case {case}");
            assert_eq!(got, want, "case {case}");
        }
    }
}

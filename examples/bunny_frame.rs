//! One bunny benchmark frame (clear + prepare + render in 16-row bands,
//! Gouraud, RGB565, 16-bit depth), in a function of its own so that
//! `valgrind --tool=callgrind --toggle-collect=*one_frame*` counts exactly
//! one frame's instructions.
//!
//! `cargo build --release --example bunny_frame &&
//! GLIBC_TUNABLES=glibc.cpu.x86_rep_stosb_threshold=16777216 valgrind
//! --tool=callgrind --toggle-collect='*one_frame*'
//! target/release/examples/bunny_frame [PROFILE]`
//!
//! The tunable keeps glibc's `memset` of the band clears on vector
//! stores: its `rep stosb` (used above 2 KB) is counted by callgrind
//! once per byte, about 230 K instructions for the frame's 30 clears.

mod common;

use common::{Bunny, Store};
use fixshade::num::{Fast, Precise, Profile, F32, F64};
use fixshade::render::{prepare, BandState, Pool, RenderError};
use fixshade::scene::{Scene, Shading};
use fixshade::target::{BandBuf, Rgb565Be};
use std::hint::black_box;

struct Mem<L> {
    store: Box<Store<L>>,
    band: Vec<u16>,
    z: Vec<u16>,
    pool: Box<Pool<L, 64, 8>>,
}

#[inline(never)]
fn one_frame<P: Profile>(scene: &Scene<'_, '_, P::Real>, m: &mut Mem<P::Lerp>) -> u32 {
    let (ws, order) = m.store.split();
    let frame = prepare::<P>(scene, 240, 240, ws).expect("prepare");
    let mut crc = 0u32;
    let mut band = BandBuf::<Rgb565Be>::new(&mut m.band, Some(&mut m.z), 240, 16).expect("band");
    let mut state = BandState::new(order, &mut m.pool);
    let stats = frame
        .render_bands(scene, &mut state, &mut band, |b| {
            crc = crc.wrapping_add(b.pixels().len() as u32);
            Ok::<(), RenderError>(())
        })
        .expect("render");
    stats.pixels ^ crc
}

fn run<P: Profile>() {
    let bunny = Bunny::<P::Real>::new(Shading::Gouraud).expect("camera");
    let scene = bunny.scene();
    let mut m = Mem {
        store: Box::new(Store::EMPTY),
        band: vec![0; 240 * 16],
        z: vec![0; 240 * 16],
        pool: Box::new(Pool::new()),
    };
    println!(
        "{}: {} pixels",
        P::NAME,
        black_box(one_frame::<P>(black_box(&scene), &mut m))
    );
}

fn main() {
    match std::env::args().nth(1).as_deref().unwrap_or("fast") {
        "fast" => run::<Fast>(),
        "precise" => run::<Precise>(),
        "f32" => run::<F32>(),
        "f64" => run::<F64>(),
        p => eprintln!("unknown profile {p}"),
    }
}

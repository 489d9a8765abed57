//! Chooses the board's memory map by target and hands it to cortex-m-rt's
//! `link.x` (which includes `memory.x`) through OUT_DIR. There is
//! deliberately no `memory.x` in the crate root: the linker would find that
//! one first, whatever the target.

use std::{env, fs, path::PathBuf};

fn main() {
    let target = env::var("TARGET").expect("cargo sets TARGET");
    let board = if target.starts_with("thumbv6m") {
        "mps2-an385"
    } else if target.starts_with("thumbv7em") {
        "mps2-an386"
    } else {
        panic!("fixshade-panic-never builds for thumbv6m-none-eabi or thumbv7em-none-eabihf, not {target}");
    };
    let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy(format!("memory/{board}.x"), out.join("memory.x")).expect("copy memory map");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rerun-if-changed=memory");
    println!("cargo:rerun-if-changed=build.rs");
}

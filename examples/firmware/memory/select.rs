// The build script of examples/firmware and of examples/panic-never (each
// `build.rs` includes this file): the memory map by target, handed to
// cortex-m-rt's `link.x` (which includes `memory.x`) through OUT_DIR.

use std::{env, fs, path::PathBuf};

fn main() {
    let target = env::var("TARGET").expect("cargo sets TARGET");
    let board = if target.starts_with("thumbv6m") {
        "mps2-an385"
    } else if target.starts_with("thumbv7em") {
        "mps2-an386"
    } else {
        panic!(
            "{} builds for thumbv6m-none-eabi or thumbv7em-none-eabihf, not {target}",
            env!("CARGO_PKG_NAME")
        );
    };
    let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy(format!("memory/{board}.x"), out.join("memory.x")).expect("copy memory map");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rustc-env=FW_TARGET={target}");
    println!("cargo:rustc-env=FW_BOARD={board}");
    println!("cargo:rerun-if-changed=memory");
    println!("cargo:rerun-if-changed=../firmware/memory/select.rs");
    println!("cargo:rerun-if-changed=build.rs");
}

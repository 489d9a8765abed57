// The build script of both boards (each `build.rs` includes this file):
// the board's `memory.x` handed to cortex-m-rt's `link.x` through OUT_DIR,
// rebuilt when it changes.

use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("copy memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=../memory_x.rs");
    println!("cargo:rerun-if-changed=build.rs");
}

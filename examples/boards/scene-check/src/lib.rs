//! Host check of the board examples' scenes.
//!
//! Includes each board's `src/scene.rs` (its scene, capacities and band
//! pool, with no board dependency) and renders every frame of its turn
//! exactly as the board does (the core is the same code): the frame must
//! fit the board's workspace, the band renderer's active-triangle peak
//! must fit the board's pool (so every prepared triangle is set up once),
//! and the Pico's frames must be the QEMU animation firmware's frames.
//!
//! `cargo test -- --nocapture` (from this folder; `.ci/boards` runs the
//! tests) prints, frame by frame, the figures the board READMEs and the
//! scene files quote; the tests assert them.

#[path = "../../blackpill-ssd1306/src/scene.rs"]
pub mod blackpill;
#[path = "../../pico-st7789/src/scene.rs"]
pub mod pico;

#[cfg(test)]
mod tests;

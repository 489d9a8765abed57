//! Chooses the board's memory map by target and hands it to cortex-m-rt's
//! `link.x` (which includes `memory.x`) through OUT_DIR. There is
//! deliberately no `memory.x` in the crate root: the linker would find that
//! one first, whatever the target. The script is `memory/select.rs`, shared
//! with examples/panic-never.

include!("memory/select.rs");

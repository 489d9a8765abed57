//! Chooses the board's memory map by target and hands it to cortex-m-rt's
//! `link.x` (which includes `memory.x`) through OUT_DIR, as the firmware
//! does (the script is the firmware's, examples/firmware/memory/select.rs).
//! There is deliberately no `memory.x` in the crate root: the linker would
//! find that one first, whatever the target.

include!("../firmware/memory/select.rs");

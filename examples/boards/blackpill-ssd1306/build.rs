//! Hands `memory.x` to cortex-m-rt's `link.x` through OUT_DIR and rebuilds
//! when it changes (the script is examples/boards/memory_x.rs, shared by
//! the boards).

include!("../memory_x.rs");

//! Build script: one name for the Arm targets the core's integer kernels
//! treat apart.
//!
//! `armv6m`: ARMv6-M (Cortex-M0, M0+, M1), which has no 32×32→64 multiply
//! (`UMULL`/`SMULL`), no divide instruction and no 32-bit atomics. rustc
//! has no `cfg` for the architecture version; among Arm targets the
//! missing 32-bit atomics (`target_has_atomic = "32"`) tell ARMv6-M from
//! ARMv7-M and later, so the alias stands for
//! `all(target_arch = "arm", not(target_has_atomic = "32"))`.

fn main() {
    cfg_aliases::cfg_aliases! {
        armv6m: { all(target_arch = "arm", not(target_has_atomic = "32")) },
    }
}

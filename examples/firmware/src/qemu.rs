//! Leaving QEMU: the exit status through semihosting (0 on success, 1 on
//! any error), and the panic handler that prints the panic and exits
//! with 1. Shared by the firmware's binaries.

use core::panic::PanicInfo;
use cortex_m_semihosting::{debug, hprintln};

/// Ends the run with `status` (QEMU exits; on a board without a debugger
/// the core waits for interrupts forever).
pub fn exit(status: debug::ExitStatus) -> ! {
    debug::exit(status);
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    hprintln!("panic: {}", info);
    exit(debug::EXIT_FAILURE)
}

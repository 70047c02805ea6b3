//! Placeholder; replaced below.
#![no_std]
#![no_main]
use fixshade_firmware_qemu as _;
#[cortex_m_rt::entry]
fn main() -> ! {
    fixshade_firmware_qemu::host::exit_ok()
}

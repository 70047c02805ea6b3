//! fixshade on an emulated Cortex-M: what the firmware binaries share.
//!
//! - [`scenes`]: the standard scenes in kernel formats, generated at build
//!   time by `build.rs` from the host's `fixshade_host::standard_scenes`.
//! - [`count`]: the two marker functions between which the QEMU plugin
//!   (`firmware/plugin/insn_count.c`) counts executed instructions.
//! - [`stack`]: paint the stack, render, find the high-water mark.
//! - [`host`]: semihosting output and exit; the panic handler exits with a
//!   non-zero code.

#![no_std]

use core::convert::Infallible;

use fixshade::framebuffer::Framebuffer;
use fixshade::render::{CachedVertex, DrawStats, RenderError};

/// The generated scenes.
#[allow(clippy::all, clippy::pedantic, missing_docs)]
pub mod scenes {
    use core::convert::Infallible;

    use embedded_graphics::pixelcolor::raw::RawU16;
    use embedded_graphics::pixelcolor::Rgb565;
    use fixshade::depth::DepthBuffer;
    use fixshade::framebuffer::Framebuffer;
    use fixshade::render::{CachedVertex, DrawStats, RenderError};

    use crate::Variant;

    include!(concat!(env!("OUT_DIR"), "/scenes_data.rs"));
}

/// A frame the firmware renders.
pub struct Variant {
    /// Scene and shading mode, e.g. `s1_gouraud`.
    pub name: &'static str,
    /// Host file name, NUL-terminated.
    pub file: &'static str,
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// Mesh vertices.
    pub vertices: usize,
    /// Clears and renders into a framebuffer.
    pub render: RenderFn,
}

/// A scene's render function: framebuffer, depth storage, vertex cache.
pub type RenderFn = fn(
    &mut Framebuffer,
    &mut [u16],
    &mut [CachedVertex],
) -> Result<DrawStats, RenderError<Infallible>>;

/// Markers for the instruction-counting plugin: it starts counting when
/// `fw_count_begin` executes and stops at `fw_count_end` (their addresses
/// come from the ELF's symbol table).
pub mod count {
    use core::ptr::{addr_of_mut, write_volatile};

    /// Written by the markers (volatile, so that the calls stay).
    static mut MARK: u32 = 0;

    /// Start of a counted region.
    #[inline(never)]
    #[no_mangle]
    pub extern "C" fn fw_count_begin() {
        // SAFETY: a volatile store to a static nothing else uses.
        unsafe { write_volatile(addr_of_mut!(MARK), 1) };
    }

    /// End of a counted region.
    #[inline(never)]
    #[no_mangle]
    pub extern "C" fn fw_count_end() {
        // SAFETY: as above.
        unsafe { write_volatile(addr_of_mut!(MARK), 2) };
    }

    /// Start counting.
    #[inline(always)]
    pub fn begin() {
        fw_count_begin();
    }

    /// Stop counting.
    #[inline(always)]
    pub fn end() {
        fw_count_end();
    }
}

/// Stack high-water mark: paint a window below the current stack pointer,
/// run, and find the lowest word that changed.
pub mod stack {
    const PAINT: u32 = 0xA5C3_5A3C;
    /// Bytes painted below the caller's stack pointer.
    pub const WINDOW: usize = 64 * 1024;
    /// Bytes left unpainted just below the stack pointer (the painting
    /// loop runs in registers, but keep clear of the caller's red zone).
    const GAP: usize = 16;

    /// Runs `f` and returns its result and the bytes of stack it used
    /// below the caller's frame.
    #[inline(always)]
    pub fn measure<R>(f: impl FnOnce() -> R) -> (R, usize) {
        let sp = cortex_m::register::msp::read() as usize;
        let top = sp - GAP;
        let bottom = top - WINDOW;
        let mut p = bottom;
        while p < top {
            // SAFETY: the window lies in RAM below the live stack (the
            // firmware's RAM is 4 MB; statics sit at its bottom, far below).
            unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
            p += 4;
        }
        let r = f();
        let mut p = bottom;
        // SAFETY: as above.
        while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
            p += 4;
        }
        (r, sp - p)
    }
}

/// Semihosting: files on the host, console, exit.
pub mod host {
    use cortex_m_semihosting::{debug, nr, syscall};

    /// A host file could not be opened or written.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub struct HostIoError;

    /// Writes `data` to the host file `name` (NUL-terminated), relative to
    /// QEMU's working directory (semihosting `SYS_OPEN`, `SYS_WRITE`,
    /// `SYS_CLOSE`).
    pub fn write_file(name: &str, data: &[u8]) -> Result<(), HostIoError> {
        let n = name.as_bytes();
        if n.last() != Some(&0) {
            return Err(HostIoError);
        }
        // SAFETY: `name` is NUL-terminated; the length excludes the NUL.
        let fd = unsafe { syscall!(OPEN, n.as_ptr(), nr::open::W_TRUNC_BINARY, n.len() - 1) };
        if fd as isize == -1 {
            return Err(HostIoError);
        }
        let mut rest = data;
        while !rest.is_empty() {
            // SAFETY: `rest` is a live slice; the call returns the bytes
            // *not* written.
            let left = unsafe { syscall!(WRITE, fd, rest.as_ptr(), rest.len()) };
            if left > rest.len() {
                return Err(HostIoError);
            }
            rest = &rest[rest.len() - left..];
            if left == 0 {
                break;
            }
        }
        // SAFETY: `fd` was opened above.
        unsafe { syscall!(CLOSE, fd) };
        Ok(())
    }

    /// Exits QEMU with status 0.
    pub fn exit_ok() -> ! {
        debug::exit(debug::EXIT_SUCCESS);
        #[allow(clippy::empty_loop)]
        loop {}
    }

    /// Exits QEMU with a non-zero status.
    pub fn exit_fail() -> ! {
        debug::exit(debug::EXIT_FAILURE);
        #[allow(clippy::empty_loop)]
        loop {}
    }
}

/// The frame as little-endian bytes (the host's `--raw` format).
pub fn frame_bytes(px: &[u16]) -> &[u8] {
    // SAFETY: u16 has no padding; Cortex-M is little-endian, so the bytes
    // in memory are the little-endian encoding.
    unsafe { core::slice::from_raw_parts(px.as_ptr().cast::<u8>(), core::mem::size_of_val(px)) }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    cortex_m_semihosting::hprintln!("panic: {}", info);
    host::exit_fail()
}

#[cortex_m_rt::exception]
unsafe fn HardFault(_: &cortex_m_rt::ExceptionFrame) -> ! {
    cortex_m_semihosting::hprintln!("hard fault");
    host::exit_fail()
}

/// A value that the optimiser cannot see through.
pub fn keep<T>(v: T) -> T {
    core::hint::black_box(v)
}

/// Result type of a render.
pub type RenderResult = Result<DrawStats, RenderError<Infallible>>;

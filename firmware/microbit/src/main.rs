//! fixshade on an emulated Cortex-M0 with 16 KB of RAM (QEMU `microbit`):
//! 320 × 240 frames, which cannot be held (150 KB each), rendered with the
//! kernel's band renderer (a draw into `Bands`, four rows per band,
//! vertices recomputed per band: no per-vertex storage), each band streamed
//! to the host through semihosting as the renderer hands it to its
//! `DrawTarget`; then exit through semihosting.
//!
//! The frames are S1, S2 and S4 of the standard scenes in their own
//! shading modes (firmware/common/scenes.rs, `m0_variants`); the host
//! renders the same scenes as whole frames and scripts/firmware.sh compares
//! them byte for byte. Instructions are counted per frame around the
//! render call (the renderer's set-up and the draw), streaming included.

#![no_std]
#![no_main]

use core::ptr::{addr_of, addr_of_mut, write_volatile};

use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hprintln, nr, syscall};
use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{OriginDimensions, Size};
use embedded_graphics::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;
use fixshade::render::{DrawStats, RenderError};

#[allow(clippy::all, missing_docs)]
mod scene {
    use super::Variant;
    use embedded_graphics::pixelcolor::raw::RawU16;
    use embedded_graphics::pixelcolor::Rgb565;
    include!(concat!(env!("OUT_DIR"), "/scene.rs"));
}

/// Rows per band.
const ROWS: usize = 4;
/// The widest frame.
const W: usize = 320;

static mut COLOUR: [u16; W * ROWS] = [0; W * ROWS];
static mut DEPTH: [u16; W * ROWS] = [0; W * ROWS];

/// Renders one frame band by band into the stream, given the colour and
/// depth bands.
type RenderFn =
    fn(&mut Stream, &mut [u16], &mut [u16]) -> Result<DrawStats, RenderError<StreamError>>;

/// One frame the firmware renders.
pub struct Variant {
    name: &'static str,
    /// File name, NUL-terminated.
    file: &'static str,
    width: u32,
    height: u32,
    render: RenderFn,
}

/// Why the stream refused pixels.
#[derive(Debug)]
pub enum StreamError {
    /// Pixels not in raster order from the frame's top left, whole rows at
    /// a time (the only order a stream can take).
    Order,
    /// The host did not take the bytes.
    Write,
}

/// A display that is a semihosting file: it takes whole rows, top to
/// bottom, as `Bands` sends them, and writes them to the host.
pub struct Stream {
    fd: usize,
    size: Size,
    /// The next row expected.
    row: u32,
}

impl OriginDimensions for Stream {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Stream {
    type Color = Rgb565;
    type Error = StreamError;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), StreamError> {
        Err(StreamError::Order)
    }

    // Out of line: the copy's registers then do not depend on the band
    // renderer's, into which it was inlined (a change in the kernel moved
    // S2 by four instructions a pixel here, with the kernel's code unchanged).
    #[inline(never)]
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), StreamError> {
        let (p, s) = (area.top_left, area.size);
        if p.x != 0 || p.y != self.row as i32 || s.width != self.size.width {
            return Err(StreamError::Order);
        }
        let mut buf = [0u8; 256];
        let mut n = 0;
        for c in colors.into_iter().take((s.width * s.height) as usize) {
            buf[n..n + 2].copy_from_slice(&RawU16::from(c).into_inner().to_le_bytes());
            n += 2;
            if n == buf.len() {
                write_all(self.fd, &buf)?;
                n = 0;
            }
        }
        write_all(self.fd, &buf[..n])?;
        self.row += s.height;
        Ok(())
    }
}

#[no_mangle]
#[inline(never)]
extern "C" fn fw_count_begin() {
    static mut MARK: u32 = 0;
    // SAFETY: a volatile store to a static nothing else uses.
    unsafe { write_volatile(addr_of_mut!(MARK), 1) };
}

#[no_mangle]
#[inline(never)]
extern "C" fn fw_count_end() {
    static mut MARK: u32 = 0;
    // SAFETY: as above.
    unsafe { write_volatile(addr_of_mut!(MARK), 2) };
}

fn exit(ok: bool) -> ! {
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    #[allow(clippy::empty_loop)]
    loop {}
}

/// Semihosting `SYS_WRITE` of all of `data` to `fd`.
fn write_all(fd: usize, data: &[u8]) -> Result<(), StreamError> {
    let mut rest = data;
    while !rest.is_empty() {
        // SAFETY: `rest` is a live slice; the call returns the bytes not
        // written.
        let left = unsafe { syscall!(WRITE, fd, rest.as_ptr(), rest.len()) };
        if left == 0 {
            return Ok(());
        }
        if left > rest.len() {
            return Err(StreamError::Write);
        }
        rest = &rest[rest.len() - left..];
    }
    Ok(())
}

const PAINT: u32 = 0xA5C3_5A3C;

extern "C" {
    static __ebss: u32;
}

/// Paints the free RAM between the statics and the stack; returns its
/// bounds.
fn paint() -> (usize, usize, usize) {
    let sp = cortex_m::register::msp::read() as usize;
    // The linker's end of .bss (taking its address needs no `unsafe`).
    let bottom = (addr_of!(__ebss) as usize + 3) & !3;
    let top = sp - 16;
    let mut p = bottom;
    while p < top {
        // SAFETY: free RAM below the live stack.
        unsafe { write_volatile(p as *mut u32, PAINT) };
        p += 4;
    }
    (sp, bottom, top)
}

/// The lowest painted word that changed.
fn high_water(bottom: usize, top: usize) -> usize {
    let mut p = bottom;
    // SAFETY: free RAM below the live stack, painted by `paint`.
    while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
        p += 4;
    }
    p
}

#[entry]
fn main() -> ! {
    // SAFETY: `main` runs once; these are the only references.
    let (colour, depth) = unsafe { (&mut *addr_of_mut!(COLOUR), &mut *addr_of_mut!(DEPTH)) };
    let mut ok = true;
    for v in &scene::VARIANTS {
        let name = v.file.as_bytes();
        // SAFETY: NUL-terminated name; the length excludes the NUL.
        let fd = unsafe {
            syscall!(
                OPEN,
                name.as_ptr(),
                nr::open::W_TRUNC_BINARY,
                name.len() - 1
            )
        };
        if fd as isize == -1 || v.width as usize > W {
            exit(false)
        }
        let mut stream = Stream {
            fd,
            size: Size::new(v.width, v.height),
            row: 0,
        };
        let (sp, bottom, top) = paint();
        fw_count_begin();
        let res = (v.render)(&mut stream, &mut colour[..], &mut depth[..]);
        fw_count_end();
        let low = high_water(bottom, top);
        // SAFETY: `fd` was opened above.
        unsafe { syscall!(CLOSE, fd) };
        match res {
            Ok(s) if stream.row == v.height => hprintln!(
                "m0 frame={} bands={} rows={} pixels={} stack={} free={}",
                v.name,
                v.height.div_ceil(ROWS as u32),
                ROWS,
                s.pixels,
                sp - low,
                low - bottom
            ),
            other => {
                hprintln!("m0 {} failed: {:?}", v.name, other.err());
                ok = false;
            }
        }
    }
    exit(ok)
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    hprintln!("panic: {}", info);
    exit(false)
}

#[exception]
unsafe fn HardFault(_: &ExceptionFrame) -> ! {
    hprintln!("hard fault");
    exit(false)
}

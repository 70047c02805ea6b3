//! fixshade on an emulated Cortex-M0 with 16 KB of RAM (QEMU `microbit`):
//! a 320 × 240 frame, which cannot be held (150 KB), rendered band by band
//! (four rows at a time) and each band written to the host through
//! semihosting as it is done; then exit through semihosting.
//!
//! Until the kernel's band renderer (issue 7) exists, a band is drawn by
//! rendering the whole scene into a [`Band`] target with a [`BandDepth`]
//! test: the depth test of rows outside the band reads a row of zeros, so
//! nothing is drawn there; rows inside see exactly the spans a whole-frame
//! render gives them. Every band repeats the vertex stage and the
//! triangle set-up, so the instruction count is not the kernel's cost per
//! frame (scripts/firmware.sh counts that on the whole-frame firmware).

#![no_std]
#![no_main]

use core::convert::Infallible;
use core::mem::MaybeUninit;
use core::ptr::{addr_of, addr_of_mut, write_volatile};

use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hprintln, nr, syscall};
use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{OriginDimensions, Size};
use embedded_graphics::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::primitives::{PointsIter, Rectangle};
use embedded_graphics::Pixel;
use fixshade::depth::DepthTest;
use fixshade::render::CachedVertex;

#[allow(clippy::all, missing_docs)]
mod scene {
    include!(concat!(env!("OUT_DIR"), "/scene.rs"));
}

const W: usize = scene::WIDTH as usize;
const ROWS: usize = 4;
const VERTICES: usize = scene::MESH_P.len();

static mut PIXELS: [u16; W * ROWS] = [0; W * ROWS];
static mut DEPTH: [u16; W * ROWS] = [0; W * ROWS];
static mut ZEROS: [u16; W] = [0; W];
static mut CACHE: [MaybeUninit<CachedVertex>; VERTICES] =
    [const { MaybeUninit::uninit() }; VERTICES];

/// The frame's rows `y0 .. y0 + ROWS`; pixels elsewhere are dropped.
struct Band<'a> {
    px: &'a mut [u16],
    y0: i32,
}

impl Band<'_> {
    #[inline]
    fn put(&mut self, x: i32, y: i32, c: Rgb565) {
        let r = y - self.y0;
        if (0..ROWS as i32).contains(&r) && (0..W as i32).contains(&x) {
            self.px[r as usize * W + x as usize] = RawU16::from(c).into_inner();
        }
    }
}

impl OriginDimensions for Band<'_> {
    fn size(&self) -> Size {
        Size::new(scene::WIDTH, scene::HEIGHT)
    }
}

impl DrawTarget for Band<'_> {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        it: I,
    ) -> Result<(), Infallible> {
        for Pixel(p, c) in it {
            self.put(p.x, p.y, c);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        for (p, c) in area.points().zip(colors) {
            self.put(p.x, p.y, c);
        }
        Ok(())
    }
}

/// The depth rows of the band; any other row reads as zeros (nearer than
/// anything), so no pixel outside the band passes.
struct BandDepth<'a> {
    rows: &'a mut [u16],
    zeros: &'a mut [u16],
    y0: u32,
}

impl DepthTest for BandDepth<'_> {
    const ENABLED: bool = true;
    fn row(&mut self, y: u32, x0: u32, len: u32) -> &mut [u16] {
        let x0 = x0 as usize;
        if x0 >= W {
            return &mut [];
        }
        let n = (len as usize).min(W - x0);
        if y >= self.y0 && y < self.y0 + ROWS as u32 {
            let start = (y - self.y0) as usize * W + x0;
            &mut self.rows[start..start + n]
        } else {
            // Never written: no depth passes against 0.
            &mut self.zeros[..n]
        }
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
fn write_all(fd: usize, data: &[u8]) -> bool {
    let mut rest = data;
    while !rest.is_empty() {
        // SAFETY: `rest` is a live slice; the call returns the bytes not
        // written.
        let left = unsafe { syscall!(WRITE, fd, rest.as_ptr(), rest.len()) };
        if left == 0 {
            return true;
        }
        if left > rest.len() {
            return false;
        }
        rest = &rest[rest.len() - left..];
    }
    true
}

const PAINT: u32 = 0xA5C3_5A3C;

extern "C" {
    static __ebss: u32;
}

#[entry]
fn main() -> ! {
    // SAFETY: `main` runs once; these are its only references.
    let (px, depth, zeros, cache) = unsafe {
        let cache = &mut *addr_of_mut!(CACHE);
        for c in cache.iter_mut() {
            c.write(CachedVertex::default());
        }
        (
            &mut *addr_of_mut!(PIXELS),
            &mut *addr_of_mut!(DEPTH),
            &mut *addr_of_mut!(ZEROS),
            core::slice::from_raw_parts_mut(cache.as_mut_ptr().cast::<CachedVertex>(), VERTICES),
        )
    };
    let name = scene::FILE.as_bytes();
    // SAFETY: NUL-terminated name; the length excludes the NUL.
    let fd = unsafe {
        syscall!(
            OPEN,
            name.as_ptr(),
            nr::open::W_TRUNC_BINARY,
            name.len() - 1
        )
    };
    if fd as isize == -1 {
        exit(false)
    }

    // Paint the free RAM between the statics and the stack.
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

    let mut ok = true;
    let mut pixels = 0;
    let mut y0 = 0;
    while y0 < scene::HEIGHT {
        px.fill(scene::BACKGROUND);
        depth.fill(u16::MAX);
        let mut band = Band {
            px: &mut px[..],
            y0: y0 as i32,
        };
        let mut bd = BandDepth {
            rows: &mut depth[..],
            zeros: &mut zeros[..],
            y0,
        };
        fw_count_begin();
        let res = scene::render(&mut band, &mut bd, cache);
        fw_count_end();
        match res {
            Ok(s) => pixels += s.pixels,
            Err(_) => ok = false,
        }
        // SAFETY: u16 has no padding; little-endian bytes.
        let bytes = unsafe { core::slice::from_raw_parts(px.as_ptr().cast::<u8>(), px.len() * 2) };
        ok &= write_all(fd, bytes);
        y0 += ROWS as u32;
    }
    // SAFETY: `fd` was opened above.
    unsafe { syscall!(CLOSE, fd) };

    let mut p = bottom;
    // SAFETY: as above.
    while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
        p += 4;
    }
    hprintln!(
        "m0 bands={} rows={} pixels={} stack={} free={}",
        (scene::HEIGHT as usize).div_ceil(ROWS),
        ROWS,
        pixels,
        sp - p,
        p - bottom
    );
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

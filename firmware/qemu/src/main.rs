//! Renders every scene of [`scenes::VARIANTS`] into a whole-frame buffer,
//! writes each frame to the host (`NAME.bin`, raw little-endian RGB565)
//! and one line of counts per frame to the console, then exits through
//! semihosting (0 if every frame rendered and was written).

#![no_std]
#![no_main]

use core::mem::MaybeUninit;
use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use fixshade::framebuffer::Framebuffer;
use fixshade::render::CachedVertex;
use fixshade_firmware_qemu::scenes::{MAX_VERTICES, VARIANTS};
use fixshade_firmware_qemu::{frame_bytes, host, stack};

const PIXELS: usize = 320 * 240;

static mut FRAME: [u16; PIXELS] = [0; PIXELS];
static mut DEPTH: [u16; PIXELS] = [0; PIXELS];
static mut CACHE: [MaybeUninit<CachedVertex>; MAX_VERTICES] =
    [const { MaybeUninit::uninit() }; MAX_VERTICES];

#[entry]
fn main() -> ! {
    // SAFETY: `main` runs once; these are its only references.
    let (frame, depth, cache) = unsafe {
        let cache = &mut *addr_of_mut!(CACHE);
        for c in cache.iter_mut() {
            c.write(CachedVertex::default());
        }
        (
            &mut *addr_of_mut!(FRAME),
            &mut *addr_of_mut!(DEPTH),
            core::slice::from_raw_parts_mut(
                cache.as_mut_ptr().cast::<CachedVertex>(),
                MAX_VERTICES,
            ),
        )
    };
    let mut ok = true;
    for v in &VARIANTS {
        let n = (v.width * v.height) as usize;
        let mut fb = match Framebuffer::new(&mut frame[..n], v.width, v.height) {
            Ok(fb) => fb,
            Err(_) => host::exit_fail(),
        };
        let (res, used) = stack::measure(|| (v.render)(&mut fb, &mut depth[..], &mut cache[..]));
        match res {
            Ok(s) => hprintln!(
                "frame {} triangles={} drawn={} clipped={} pixels={} lit={} vertices={} stack={}",
                v.name,
                s.triangles,
                s.drawn,
                s.clipped,
                s.pixels,
                s.lit,
                v.vertices,
                used
            ),
            Err(e) => {
                hprintln!("frame {} error: {}", v.name, e);
                ok = false;
                continue;
            }
        }
        if host::write_file(v.file, frame_bytes(&frame[..n])).is_err() {
            hprintln!("frame {}: cannot write {}", v.name, v.file);
            ok = false;
        }
    }
    if ok {
        host::exit_ok()
    } else {
        host::exit_fail()
    }
}

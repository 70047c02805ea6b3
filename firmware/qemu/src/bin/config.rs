//! One scene configuration of the flash/RAM table: S1's sphere rendered
//! with the terms the enabled feature adds, each level on top of the one
//! before: `ambient` (no lights), `lambert` (S1's directional light,
//! diffuse only), `specular` (Blinn–Phong), `point` (+ a point light with
//! attenuation), `spot` (+ a spot light), `depth` (+ a depth buffer),
//! `phong` (+ per-pixel shading). `s1` is not cumulative: `specular` with
//! the depth buffer, which is standard scene S1 exactly (scripts/firmware.sh
//! checks its frame's checksum against the host's `s1_gouraud` frame).
//! Each is built with the kernel's `clip` feature (this crate's default)
//! and, for `s1` and `ambient`, once more without it
//! (`--no-default-features`): the same frame, the rare path not linked.
//! Built with `--cfg fixshade_explicit_draw`, each draws through the
//! kernel's explicit call instead of the draw call (src/explicit.rs).
//! Without a feature it renders nothing: the runtime's own size
//! (semihosting, the panic handler's formatting). Prints a checksum of the
//! frame and the stack used by the render call, then exits through
//! semihosting.

#![no_std]
#![no_main]

use core::mem::MaybeUninit;
use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use fixshade::framebuffer::Framebuffer;
use fixshade::render::CachedVertex;
use fixshade_firmware_qemu::{host, stack, RenderResult};

const W: u32 = 320;
const H: u32 = 240;
const PIXELS: usize = (W * H) as usize;
#[cfg(feature = "ambient")]
const VERTICES: usize = fixshade_firmware_qemu::scenes::SPHERE48_POSITIONS.len();
#[cfg(not(feature = "ambient"))]
const VERTICES: usize = 0;
#[cfg(feature = "depth-buffer")]
const DEPTH_PIXELS: usize = PIXELS;
#[cfg(not(feature = "depth-buffer"))]
const DEPTH_PIXELS: usize = 0;

static mut FRAME: [u16; PIXELS] = [0; PIXELS];
static mut DEPTH: [u16; DEPTH_PIXELS] = [0; DEPTH_PIXELS];
static mut CACHE: [MaybeUninit<CachedVertex>; VERTICES] =
    [const { MaybeUninit::uninit() }; VERTICES];

#[cfg(feature = "ambient")]
#[inline(never)]
fn render(fb: &mut Framebuffer, depth: &mut [u16], cache: &mut [CachedVertex]) -> RenderResult {
    use fixshade::render::RenderOptions;
    use fixshade::Mat4;
    use fixshade_firmware_qemu::count;
    use fixshade_firmware_qemu::scenes::*;

    let mesh = SPHERE48;
    #[cfg(not(feature = "specular"))]
    let material = S1_MATERIAL;
    #[cfg(feature = "specular")]
    let material = S1_MATERIAL.with_specular(S1_SPECULAR);
    #[cfg(not(feature = "lambert"))]
    let lights = ();
    #[cfg(all(feature = "lambert", not(feature = "point")))]
    let lights = S1_SUN;
    #[cfg(all(feature = "point", not(feature = "spot")))]
    let lights = (S1_SUN, LAMP);
    #[cfg(feature = "spot")]
    let lights = (S1_SUN, LAMP, SPOT);
    #[cfg(not(feature = "phong"))]
    type Mode = fixshade::render::Gouraud;
    #[cfg(feature = "phong")]
    type Mode = fixshade::render::PhongShading;

    // A new depth buffer is cleared.
    #[cfg(feature = "depth-buffer")]
    let mut db = fixshade::depth::DepthBuffer::new(depth, W, H)
        .map_err(|_| fixshade::render::RenderError::DepthTooSmall)?;
    #[cfg(not(feature = "depth-buffer"))]
    let _ = depth;
    count::begin();
    // The draw call, as a program writes it.
    #[cfg(not(fixshade_explicit_draw))]
    let res = {
        let r = fixshade::Renderer::new(&S1_CAMERA, &material, &lights)
            .with_ambient(S1_AMBIENT)
            .with_shading(Mode::default())
            .with_options(RenderOptions::default());
        let shaded = mesh.shaded(&r).with_model(Mat4::IDENTITY);
        #[cfg(feature = "depth-buffer")]
        let shaded = shaded.with_depth(&mut db);
        shaded.with_cache(cache).draw(fb)
    };
    // The same draw as one explicit call, the baseline the draw call is
    // held to (scripts/firmware.sh builds it with `--cfg
    // fixshade_explicit_draw`).
    #[cfg(fixshade_explicit_draw)]
    let res = {
        #[cfg(feature = "depth-buffer")]
        let depth = &mut db;
        #[cfg(not(feature = "depth-buffer"))]
        let depth = fixshade::depth::NoDepth;
        fixshade::explicit::draw::<Mode, fixshade::illumination::InfiniteViewer, _, _, _, _, _>(
            &S1_CAMERA,
            &material,
            &lights,
            S1_AMBIENT,
            RenderOptions::default(),
            &mesh,
            Mat4::IDENTITY,
            depth,
            &mut fixshade::band::Cached(cache),
            fb,
        )
    };
    count::end();
    res
}

#[cfg(not(feature = "ambient"))]
fn frame_probe() -> &'static [u16] {
    &[0; 4]
}

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
            core::slice::from_raw_parts_mut(cache.as_mut_ptr().cast::<CachedVertex>(), VERTICES),
        )
    };
    let Ok(mut fb) = Framebuffer::new(&mut frame[..], W, H) else {
        host::exit_fail()
    };
    #[cfg(feature = "ambient")]
    let (res, used) = stack::measure(|| render(&mut fb, &mut depth[..], cache));
    #[cfg(not(feature = "ambient"))]
    let (res, used): (RenderResult, usize) = stack::measure(|| {
        // Nothing rendered, but a bounds check that can panic, as the
        // kernel's can: the panic handler's formatting is in the baseline.
        let _ = (&mut fb, &mut depth[..], cache);
        let i = fixshade_firmware_qemu::keep(0usize);
        let _ = fixshade_firmware_qemu::keep(frame_probe()[i]);
        Ok(Default::default())
    });
    let Ok(stats) = res else { host::exit_fail() };
    // FNV-1a over the frame: a cheap fingerprint of what was drawn.
    let sum = frame.iter().fold(0x811c_9dc5u32, |h, &p| {
        (h ^ u32::from(p)).wrapping_mul(0x0100_0193)
    });
    hprintln!(
        "config pixels={} lit={} checksum={:08x} stack={}",
        stats.pixels,
        stats.lit,
        sum,
        used
    );
    host::exit_ok()
}

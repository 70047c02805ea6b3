//! fixshade on a Raspberry Pi Pico (RP2040 at 133 MHz) with a 240 × 240
//! ST7789 on SPI1: the Stanford bunny (3674 triangles, Gouraud shading,
//! Blinn–Phong, a key and a blue fill light, a depth test) spinning.
//!
//! The three steps:
//! 1. convert: `src/bunny.fxm` is the host converter's output,
//!    `fixshade-convert bunny.obj src/bunny.fxm --derive-normals`;
//! 2. include: `fixshade::include_mesh!("bunny.fxm")` (its bytes stay in
//!    flash, 40 KB);
//! 3. draw: `mesh.shaded(&renderer).with_model(..).draw(&mut bands)`.
//!
//! No framebuffer: the frame is drawn in bands of [`ROWS`] rows
//! ([`Bands`]), each cleared to the background, depth-tested in a depth
//! band, and sent to the panel as one block; every frame sends every band,
//! so nothing of the previous frame remains. Core 0 draws the even bands
//! and core 1 the odd ones (`Bands::interleaved`), each with its own vertex
//! cache, colour band, depth band and transmit buffer; a band goes out by
//! DMA while its core draws the next ([`lcd`]).
//!
//! Wiring (see README.md): SCK GP10, MOSI GP11, DC GP8, CS GP9, RST GP12,
//! backlight GP13. The Pico's LED (GP25) lights if a frame fails to draw.

#![no_std]
#![no_main]

mod lcd;

use core::cell::RefCell;
use core::ptr::addr_of_mut;

use critical_section::Mutex;
use embedded_graphics::prelude::*;
use embedded_hal::digital::OutputPin;
use fixshade::prelude::*;
use fixshade::render::DrawStats;
use rp_pico::entry;
use rp_pico::hal::clocks::ClocksManager;
use rp_pico::hal::dma::{Channel, DMAExt, CH0};
use rp_pico::hal::fugit::{HertzU32, RateExtU32};
use rp_pico::hal::gpio::{self, FunctionSpi};
use rp_pico::hal::multicore::{Multicore, Stack};
use rp_pico::hal::pll::{common_configs::PLL_USB_48MHZ, setup_pll_blocking, PLLConfig};
use rp_pico::hal::{self, pac, spi, Clock};

use lcd::{LcdError, Sender, HEIGHT, WIDTH};

/// The system clock: 12 MHz crystal × 133 = 1596 MHz VCO, ÷ 6 ÷ 2.
const PLL_SYS_133MHZ: PLLConfig = PLLConfig {
    vco_freq: HertzU32::MHz(1596),
    refdiv: 1,
    post_div1: 6,
    post_div2: 2,
};

/// The SPI clock. The PL022 divides the peripheral clock (133 MHz) by an
/// even number: 66.5 MHz (÷ 2) is above the ST7789's 62.5 MHz rating (it
/// works on many modules: try it), 33.25 MHz (÷ 4) is within it.
const SPI_HZ: u32 = 33_250_000;

/// Rows per band: 15 bands of 240 × 16, 8 for core 0 and 7 for core 1.
const ROWS: u32 = 16;
/// Pixels per band.
const BAND: usize = (WIDTH * ROWS) as usize;
/// Workers: the two cores.
const CORES: u32 = 2;
// Every band fills a transmit buffer, so every band goes out by DMA (a
// shorter last band would be written by the CPU).
const _: () = assert!(HEIGHT.is_multiple_of(ROWS));

/// The mesh's vertex count, read from its header (bytes 8..12, a
/// little-endian `u32`) when compiling: one cache entry per vertex.
const VERTICES: usize = {
    let b = include_bytes!("bunny.fxm");
    u32::from_le_bytes([b[8], b[9], b[10], b[11]]) as usize
};

/// Pixels no triangle covers.
const BACKGROUND: Rgb565 = Rgb565::new(2, 5, 9);
/// The global ambient light.
const AMBIENT: Rgb = Rgb::grey(0.2);
/// Seconds per turn, as microseconds.
const TURN_US: u64 = 8_000_000;

/// What each core needs to draw its bands: 52 KB.
struct Memory {
    /// One entry per vertex: transformed, projected and lit once a frame.
    cache: [CachedVertex; VERTICES],
    /// The band being drawn.
    colour: [u16; BAND],
    /// Its depths.
    depth: [u16; BAND],
    /// The band being sent.
    tx: [u16; BAND],
}

impl Memory {
    const fn new() -> Self {
        Memory {
            cache: [CachedVertex::new(); VERTICES],
            colour: [0; BAND],
            depth: [0; BAND],
            tx: [0; BAND],
        }
    }
}

/// Both cores' memory (zeroed RAM, not flash).
static mut MEMORY: [Memory; 2] = [const { Memory::new() }; 2];

/// Core 1's stack: 16 KB (a draw uses about 7 KB).
static mut CORE1_STACK: Stack<4096> = Stack::new();

type Sck = gpio::Pin<gpio::bank0::Gpio10, FunctionSpi, gpio::PullDown>;
type Mosi = gpio::Pin<gpio::bank0::Gpio11, FunctionSpi, gpio::PullDown>;
/// SPI1 in 16-bit frames (8-bit for the panel's set-up).
type LcdSpi = spi::Spi<spi::Enabled, pac::SPI1, (Mosi, Sck), 16>;
type Out = gpio::Pin<gpio::DynPinId, gpio::FunctionSioOutput, gpio::PullDown>;
type Dma = Channel<CH0>;

/// The panel's bus, shared by the cores.
static LINK: lcd::Shared<Dma, LcdSpi, Out, BAND> = Mutex::new(RefCell::new(None));

/// The camera, material, lights and mesh, written by hand.
#[derive(Clone, Copy)]
struct Scene {
    camera: Camera,
    material: Material<BlinnPhong>,
    lights: (DirectionalLight, DirectionalLight),
    mesh: Mesh<'static>,
}

impl Scene {
    fn new() -> Option<Scene> {
        // The bunny: x ±5, y 0 … 9.7, z ±3.8 (the converter prints its box).
        let mesh = fixshade::include_mesh!("bunny.fxm").ok()?;
        // Slightly above, 17 units away (the model matrix centres the
        // bunny on the origin), 45° high: it fills the panel as it turns.
        let camera = Camera::look_at([0.0, 3.0, 17.0], [0.0; 3], [0.0, 1.0, 0.0])
            .ok()?
            .with_projection(Projection::Perspective { fovy_deg: 45.0 }, 8.0, 25.0)
            .ok()?;
        let porcelain = Rgb::clamped(0.85, 0.8, 0.72);
        let material = Material::new()
            .with_ambient(porcelain)
            .with_diffuse(porcelain)
            .with_specular(BlinnPhong {
                color: Rgb::grey(0.5),
                shininess: Exponent::from_int(24),
            });
        // A warm key light from the upper right, a blue fill from the left.
        let key = DirectionalLight::new([1.0, 1.0, 1.0])
            .ok()?
            .with_diffuse(Rgb::clamped(0.9, 0.85, 0.8));
        let fill = DirectionalLight::new([-1.0, -0.2, 0.5])
            .ok()?
            .with_diffuse(Rgb::clamped(0.15, 0.25, 0.55))
            .with_specular(Rgb::BLACK);
        Some(Scene {
            camera,
            material,
            lights: (key, fill),
            mesh,
        })
    }

    /// The model matrix: the mesh's box centred on the origin, turned by
    /// `angle` radians about the vertical.
    fn model(&self, angle: f32) -> Mat4 {
        let o = self.mesh.bounds.offset;
        Mat4::rotation_y(angle) * Mat4::translation(Vec3::from_bits(-o[0], -o[1], -o[2]))
    }
}

/// One core's share of the frame: its bands, its memory, its end of the
/// link.
struct Worker {
    index: u32,
    scene: Scene,
    cache: &'static mut [CachedVertex; VERTICES],
    colour: &'static mut [u16; BAND],
    depth: &'static mut [u16; BAND],
    sender: Sender<Dma, LcdSpi, Out, BAND>,
}

impl Worker {
    fn new(index: u32, scene: Scene, memory: &'static mut Memory) -> Self {
        let Memory {
            cache,
            colour,
            depth,
            tx,
        } = memory;
        Worker {
            index,
            scene,
            cache,
            colour,
            depth,
            sender: Sender::new(&LINK, index as usize, tx),
        }
    }

    /// Draws and sends this core's bands of the frame at `angle`.
    fn draw(&mut self, angle: f32) -> Result<DrawStats, RenderError<LcdError>> {
        let s = &self.scene;
        let renderer = Renderer::new(&s.camera, &s.material, &s.lights).with_ambient(AMBIENT);
        let mut depth = DepthBand::new(&mut self.depth[..]);
        let mut bands = Bands::new(&mut self.sender, &mut self.colour[..], ROWS)
            .with_background(BACKGROUND)
            .interleaved(self.index, CORES);
        s.mesh
            .shaded(&renderer)
            .with_model(s.model(angle))
            .with_depth(&mut depth)
            .with_cache(&mut self.cache[..])
            .draw(&mut bands)
    }
}

/// The crystal, the PLLs and the clocks as `init_clocks_and_plls` sets
/// them, but the system PLL at 133 MHz: clk_sys = clk_peri = 133 MHz.
fn clocks_133mhz(
    xosc: pac::XOSC,
    clocks: pac::CLOCKS,
    pll_sys: pac::PLL_SYS,
    pll_usb: pac::PLL_USB,
    resets: &mut pac::RESETS,
    watchdog: &mut hal::Watchdog,
) -> Option<ClocksManager> {
    let xosc = hal::xosc::setup_xosc_blocking(xosc, rp_pico::XOSC_CRYSTAL_FREQ.Hz()).ok()?;
    watchdog.enable_tick_generation((rp_pico::XOSC_CRYSTAL_FREQ / 1_000_000) as u8);
    let mut clocks = ClocksManager::new(clocks);
    let f = xosc.operating_frequency();
    let pll_sys = setup_pll_blocking(pll_sys, f, PLL_SYS_133MHZ, &mut clocks, resets).ok()?;
    let pll_usb = setup_pll_blocking(pll_usb, f, PLL_USB_48MHZ, &mut clocks, resets).ok()?;
    clocks.init_default(&xosc, &pll_sys, &pll_usb).ok()?;
    Some(clocks)
}

#[entry]
fn main() -> ! {
    let Some(mut pac) = pac::Peripherals::take() else {
        halt()
    };
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let Some(clocks) = clocks_133mhz(
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    ) else {
        halt()
    };
    let mut sio = hal::Sio::new(pac.SIO);
    let pins = rp_pico::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let led = pins.led.into_push_pull_output();

    // The panel: SPI1 (mode 0; a module without a CS pin wants
    // embedded_hal::spi::MODE_3), reset, set-up, backlight on.
    let sck: Sck = pins.gpio10.into_function();
    let mosi: Mosi = pins.gpio11.into_function();
    let mut spi8 = spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        SPI_HZ.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let mut dc: Out = pins.gpio8.into_push_pull_output().into_dyn_pin();
    let mut cs: Out = pins.gpio9.into_push_pull_output().into_dyn_pin();
    let mut rst: Out = pins.gpio12.into_push_pull_output().into_dyn_pin();
    lcd::init(&mut spi8, &mut dc, &mut cs, &mut rst, &mut timer);
    let _ = pins.gpio13.into_push_pull_output().set_high();
    let (spi1, spi_pins) = spi8.free();
    let spi: LcdSpi = spi::Spi::new(spi1, spi_pins).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        SPI_HZ.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let dma = pac.DMA.split(&mut pac.RESETS);
    critical_section::with(|c| {
        LINK.replace(c, Some(lcd::Link::new(dma.ch0, spi, dc, cs)));
    });

    let Some(scene) = Scene::new() else { fail(led) };
    // SAFETY: `main` runs once, before core 1 starts; these are the only
    // references to MEMORY, one per core, never shared.
    let [memory0, memory1] = unsafe { &mut *addr_of_mut!(MEMORY) };
    let mut worker = Worker::new(0, scene, memory0);
    let mut other = Worker::new(1, scene, memory1);
    // The panel's RAM holds noise at power-up: clear it once (the frames
    // then rewrite every pixel).
    let _ = worker.sender.clear(BACKGROUND);

    // Core 1 draws the odd bands of the frame whose angle core 0 sends it,
    // and answers 0 (drawn) or 1 (failed).
    {
        let mut mc = Multicore::new(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo);
        let cores = mc.cores();
        // SAFETY: the stack is taken once, here.
        let stack = unsafe { &mut (*addr_of_mut!(CORE1_STACK)).mem };
        let spawned = cores[1].spawn(stack, move || {
            // SAFETY: core 1 uses only its own SIO FIFO end.
            let pac = unsafe { pac::Peripherals::steal() };
            let mut sio = hal::Sio::new(pac.SIO);
            loop {
                let angle = f32::from_bits(sio.fifo.read_blocking());
                let failed = other.draw(angle).is_err();
                sio.fifo.write_blocking(u32::from(failed));
            }
        });
        if spawned.is_err() {
            fail(led)
        }
    }

    let tau = core::f32::consts::TAU;
    loop {
        // The angle from the time, so the speed does not depend on the
        // frame rate.
        let t = timer.get_counter().ticks() % TURN_US;
        let angle = t as f32 * (tau / TURN_US as f32);
        sio.fifo.write_blocking(angle.to_bits());
        let mine = worker.draw(angle);
        let theirs = sio.fifo.read_blocking();
        if mine.is_err() || theirs != 0 {
            fail(led)
        }
    }
}

/// Lights the LED and stops.
fn fail(mut led: impl OutputPin) -> ! {
    let _ = led.set_high();
    halt()
}

fn halt() -> ! {
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    halt()
}

//! Helpers shared by the `render` and `gallery` examples: the kernel drawing
//! into an `embedded-graphics-simulator` display (headless), PNG output, and
//! timing.
#![allow(dead_code)]

use std::path::Path;
use std::time::{Duration, Instant};

use embedded_graphics::geometry::Size;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::{Point, RawData};
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use fixshade::render::CachedVertex;
use fixshade_host::scene_desc::SceneDesc;
use fixshade_host::scene_kernel::KernelScene;

/// Renders `kernel` (converted from `desc`) into a fresh simulator display,
/// exactly as firmware would render into its display driver.
pub fn render_to_display(
    desc: &SceneDesc,
    kernel: &KernelScene,
) -> Result<SimulatorDisplay<Rgb565>, String> {
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(desc.width, desc.height));
    let mut depth = vec![0u16; desc.width as usize * desc.height as usize];
    let mut cache = vec![CachedVertex::default(); desc.mesh.positions.len()];
    kernel
        .render(&mut display, &mut depth, &mut cache)
        .map_err(|e| format!("kernel render: {e}"))?;
    Ok(display)
}

/// The display's pixels as raw RGB565, row-major.
pub fn display_pixels(display: &SimulatorDisplay<Rgb565>, width: u32, height: u32) -> Vec<u16> {
    let mut out = Vec::with_capacity(width as usize * height as usize);
    for y in 0..height as i32 {
        for x in 0..width as i32 {
            let c = display.get_pixel(Point::new(x, y));
            out.push(RawU16::from(c).into_inner());
        }
    }
    out
}

/// Writes the display as a PNG, one image pixel per display pixel.
pub fn save_png(display: &SimulatorDisplay<Rgb565>, path: &Path) -> Result<(), String> {
    let settings = OutputSettingsBuilder::new().scale(1).build();
    display
        .to_rgb_output_image(&settings)
        .save_png(path)
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// Runs `f` `runs` times (at least once) and returns its last result and
/// the median wall-clock time.
pub fn median_time<T>(runs: usize, mut f: impl FnMut() -> T) -> (T, Duration) {
    let mut times = Vec::with_capacity(runs.max(1));
    let mut last = None;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        let out = f();
        times.push(start.elapsed());
        last = Some(out);
    }
    times.sort();
    let result = last.expect("ran at least once");
    (result, times[times.len() / 2])
}

/// Milliseconds, for tables.
pub fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

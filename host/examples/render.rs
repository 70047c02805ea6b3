//! Renders a scene file with the fixed-point kernel into an RGB565
//! `embedded-graphics-simulator` display (headless) and writes it as a PNG.
//!
//! ```text
//! cargo run --release --example render -- SCENE.json OUT.png [--compare] [--raw FRAME.bin] [--coverage MASK.bin]
//! ```
//!
//! * `--compare` also renders the f64 reference and prints the error figures
//!   of SPEC.md section 7 and the median time of each render.
//! * `--raw FRAME.bin` writes the kernel's frame as little-endian `u16`
//!   RGB565, row-major, no header.
//! * `--coverage MASK.bin` writes one byte per pixel: 1 where the kernel drew
//!   the pixel, 0 elsewhere.
//!
//! A bad scene file or bad arguments print one line on stderr and exit with
//! code 2; failing to write an output exits with code 1.

#[path = "common/mod.rs"]
mod common;

use std::path::PathBuf;
use std::process::ExitCode;

use fixshade_host::error_measure::compare;
use fixshade_host::reference;
use fixshade_host::scene_file::{load_scene, one_line};
use fixshade_host::scene_kernel::KernelScene;

const USAGE: &str =
    "usage: render SCENE.json OUT.png [--compare] [--raw FRAME.bin] [--coverage MASK.bin]";

/// Kernel renders timed for `--compare` (the median is printed).
const KERNEL_RUNS: usize = 7;
/// Reference renders timed for `--compare`.
const REFERENCE_RUNS: usize = 3;

struct Args {
    scene: PathBuf,
    out: PathBuf,
    compare: bool,
    raw: Option<PathBuf>,
    coverage: Option<PathBuf>,
}

/// An error and the exit code it gets.
struct Failure {
    code: u8,
    message: String,
}

fn input(message: impl Into<String>) -> Failure {
    Failure {
        code: 2,
        message: message.into(),
    }
}

fn output(message: impl Into<String>) -> Failure {
    Failure {
        code: 1,
        message: message.into(),
    }
}

fn parse_args() -> Result<Args, Failure> {
    let mut positional = Vec::new();
    let mut compare = false;
    let mut raw = None;
    let mut coverage = None;
    let mut args = std::env::args_os().skip(1);
    while let Some(arg) = args.next() {
        match arg.to_str() {
            Some("--compare") => compare = true,
            Some("--raw") => {
                raw = Some(PathBuf::from(
                    args.next()
                        .ok_or_else(|| input("--raw needs a file name"))?,
                ))
            }
            Some("--coverage") => {
                coverage = Some(PathBuf::from(
                    args.next()
                        .ok_or_else(|| input("--coverage needs a file name"))?,
                ))
            }
            Some("-h" | "--help") => return Err(input(USAGE)),
            Some(s) if s.starts_with("--") => {
                return Err(input(format!("unknown option {s}; {USAGE}")))
            }
            _ => positional.push(PathBuf::from(arg)),
        }
    }
    let [scene, out]: [PathBuf; 2] = positional.try_into().map_err(|_| input(USAGE))?;
    Ok(Args {
        scene,
        out,
        compare,
        raw,
        coverage,
    })
}

fn run() -> Result<(), Failure> {
    let args = parse_args()?;
    // Escaped: a file name may hold a line break, and an error is one line.
    let name = one_line(&args.scene.display().to_string());
    let desc = load_scene(&args.scene).map_err(|e| input(format!("{name}: {e}")))?;
    if desc.width == 0 || desc.height == 0 {
        return Err(input(format!(
            "{name}: width and height must be > 0 to write a PNG"
        )));
    }
    let kernel = KernelScene::new(&desc).map_err(|e| input(format!("{name}: {e}")))?;

    // The PNG comes from the kernel drawing into the simulator's display.
    let display = common::render_to_display(&desc, &kernel).map_err(input)?;
    common::save_png(&display, &args.out).map_err(output)?;

    // The same render into a plain framebuffer gives the raw frame, which
    // pixels were drawn, and the time.
    let runs = if args.compare { KERNEL_RUNS } else { 1 };
    let (frame, kernel_time) = common::median_time(runs, || kernel.render_frame());
    let frame = frame.map_err(|e| input(format!("{name}: kernel render: {e}")))?;
    if common::display_pixels(&display, desc.width, desc.height) != frame.pixels {
        eprintln!("warning: the display and the framebuffer renders differ");
    }
    println!(
        "{}: {}x{}, {} triangles, {} drawn, {} pixels -> {}",
        name,
        desc.width,
        desc.height,
        frame.stats.triangles,
        frame.stats.drawn,
        frame.stats.pixels,
        args.out.display()
    );

    if let Some(path) = &args.raw {
        let bytes: Vec<u8> = frame.pixels.iter().flat_map(|p| p.to_le_bytes()).collect();
        std::fs::write(path, bytes)
            .map_err(|e| output(format!("cannot write {}: {e}", path.display())))?;
    }
    if let Some(path) = &args.coverage {
        let bytes: Vec<u8> = frame.covered.iter().map(|&c| u8::from(c)).collect();
        std::fs::write(path, bytes)
            .map_err(|e| output(format!("cannot write {}: {e}", path.display())))?;
    }

    if args.compare {
        // The reference renders the mesh the kernel draws (quantised).
        let (reference, reference_time) = common::median_time(REFERENCE_RUNS, || {
            reference::render(kernel.reference_scene())
        });
        let reference = reference.map_err(|e| input(format!("{name}: reference: {e}")))?;
        let stats = compare(&frame.pixels, &frame.covered, &reference);
        println!(
            "kernel    {:9.3} ms (median of {KERNEL_RUNS})",
            common::ms(kernel_time)
        );
        println!(
            "reference {:9.3} ms (median of {REFERENCE_RUNS})",
            common::ms(reference_time)
        );
        println!("error: {stats}");
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("error: {}", f.message);
            ExitCode::from(f.code)
        }
    }
}

//! Renders the standard scenes and every shipped scene file with the
//! fixed-point kernel through an `embedded-graphics-simulator` display
//! (headless), writes them as PNGs, and prints the error against the f64
//! reference (SPEC.md section 7) and the time of each render.
//!
//! ```text
//! cargo run --release --example gallery [-- OUT_DIR]
//! ```
//!
//! `OUT_DIR` defaults to `report/images` in the crate. The images:
//! `s1_sphere.png` (S1), `s4_bunny.png` (S4), `phong_sphere.png` (S1's sphere
//! with per-pixel Phong shading), and `scene_NAME.png` for each
//! `examples/scenes/NAME.json` that is not one of those (`sphere.json` is
//! S1 and `bunny.json` is S4).

#[path = "common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use fixshade_host::error_measure::compare;
use fixshade_host::reference;
use fixshade_host::scene_desc::{SceneDesc, Shading};
use fixshade_host::scene_file::load_scene;
use fixshade_host::scene_kernel::KernelScene;
use fixshade_host::standard_scenes::{self, HEIGHT, WIDTH};

/// Timed runs per render (the median is printed).
const RUNS: usize = 3;

/// The scenes built in code, with their image names.
fn code_scenes() -> Vec<(String, SceneDesc)> {
    let mut phong = standard_scenes::s1(WIDTH, HEIGHT);
    phong.shading = Shading::Phong;
    vec![
        ("s1_sphere".into(), standard_scenes::s1(WIDTH, HEIGHT)),
        ("s4_bunny".into(), standard_scenes::s4(WIDTH, HEIGHT)),
        ("phong_sphere".into(), phong),
    ]
}

/// The shipped scene files, sorted by name.
fn file_scenes(dir: &Path) -> Result<Vec<(String, SceneDesc)>, String> {
    let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| {
            let stem = p.file_stem().unwrap_or_default().to_string_lossy();
            let desc = load_scene(p).map_err(|e| format!("{}: {e}", p.display()))?;
            Ok((format!("scene_{stem}"), desc))
        })
        .collect()
}

fn run() -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out_dir = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("../report/images"));
    std::fs::create_dir_all(&out_dir)
        .map_err(|e| format!("cannot create {}: {e}", out_dir.display()))?;

    let mut scenes = code_scenes();
    scenes.extend(file_scenes(&root.join("examples/scenes"))?);

    println!(
        "{:<16} {:>6} {:>10} {:>10} {:>9} {:>8} {:>8} {:>6} {:>6} {:>9}",
        "scene",
        "tris",
        "kernel ms",
        "ref ms",
        "max r/g/b",
        "mean",
        "exact %",
        "ties",
        "steps",
        "cov. mism"
    );
    for (i, (name, desc)) in scenes.iter().enumerate() {
        if let Some((same, _)) = scenes[..i].iter().find(|(_, d)| d == desc) {
            println!("{name:<16} is the same scene as {same}");
            continue;
        }
        let kernel = KernelScene::new(desc).map_err(|e| format!("{name}: {e}"))?;
        let display = common::render_to_display(desc, &kernel)?;
        let path = out_dir.join(format!("{name}.png"));
        common::save_png(&display, &path)?;

        let (frame, kernel_time) = common::median_time(RUNS, || kernel.render_frame());
        let frame = frame.map_err(|e| format!("{name}: {e}"))?;
        // The reference renders the mesh the kernel draws (quantised).
        let (reference, reference_time) =
            common::median_time(RUNS, || reference::render(kernel.reference_scene()));
        let reference = reference.map_err(|e| format!("{name}: reference: {e}"))?;
        let e = compare(&frame.pixels, &frame.covered, &reference);
        println!(
            "{:<16} {:>6} {:>10.3} {:>10.3} {:>9} {:>8.4} {:>8.2} {:>6} {:>6} {:>9}",
            name,
            frame.stats.triangles,
            common::ms(kernel_time),
            common::ms(reference_time),
            format!("{}/{}/{}", e.max_error[0], e.max_error[1], e.max_error[2]),
            e.mean_error,
            e.exact_share * 100.0,
            e.depth_ties,
            e.model_steps,
            e.only_kernel + e.only_reference,
        );
    }
    println!(
        "max and mean error in RGB565 LSBs over pixels both drew, depth ties and model steps \
         (SPEC.md 7) counted apart; times are medians of {RUNS} renders (kernel into a \
         framebuffer, reference in f64); images in {}",
        out_dir.display()
    );
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

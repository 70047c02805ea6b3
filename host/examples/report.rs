//! Error against run time : renders every standard scene in every
//! configuration that trades accuracy for time, measures each one's error
//! against the f64 reference and its run time, and writes
//! `report/error_vs_time.md` (a table) and `report/error_vs_time.svg` (error
//! against time, one point per configuration, the Pareto front marked).
//!
//! ```text
//! cargo run --release --example report -- [--reps N] [--out DIR] [--no-callgrind]
//! ```
//!
//! * `--reps N`: timed renders per configuration (default 15); the median and
//!   the spread (interquartile range and min–max) are reported.
//! * `--out DIR`: where the two files go (default `report`).
//! * `--no-callgrind`: skip the instruction count even if valgrind is there.
//!
//! The configurations are the kernel's real knobs: the shading mode (flat,
//! Gouraud, Phong, where the scene allows it), ordered dithering on and off,
//! and the fixed-point kernel against the f64 reference. The specular table
//! (832 bytes) and the interpolation's fractional bits (16 below the RGB565
//! step) are fixed, so they are not swept.
//!
//! Two errors are kept apart: the *fixed-point error* (the kernel against the
//! reference in the same shading mode, undithered, the reference drawing the
//! quantised mesh the kernel draws) and the *model error* (the
//! reference in that mode, quantised, against the reference in Phong mode,
//! the "truth"). The plot shows the *total* error, the kernel against the
//! truth, which is what a user of a configuration gets.
//!
//! Instructions per frame come from `valgrind --tool=callgrind` where it is
//! installed: the report runs itself again under callgrind
//! (`--callgrind-frames`, an internal mode), which renders one frame of each
//! configuration inside [`counted_frame`]; callgrind collects only inside
//! that function (`--toggle-collect`) and writes one profile each time it
//! returns (`--dump-after`), so each profile's total is exactly one frame.
//!
//! The program exits non-zero if a scene fails to render or if the written
//! table lacks a row for some scene and configuration.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::Instant;

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use fixshade::framebuffer::Framebuffer;
use fixshade::render::CachedVertex;
use fixshade_host::error_measure::{compare, ErrorStats};
use fixshade_host::reference::{self, quantize_rgb565, RefFrame};
use fixshade_host::scene_desc::{SceneDesc, Shading};
use fixshade_host::scene_kernel::KernelScene;
use fixshade_host::standard_scenes;

type Error = Box<dyn std::error::Error>;

const USAGE: &str = "usage: report [--reps N] [--out DIR] [--no-callgrind]";

/// Which renderer draws a configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Engine {
    /// The fixed-point kernel into a `Framebuffer`, dithering on or off.
    Kernel { dither: bool },
    /// The f64 reference (never dithered).
    Reference,
}

/// One point of the report: a scene, a shading mode and a renderer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Config {
    scene: &'static str,
    shading: Shading,
    engine: Engine,
}

impl Config {
    /// The configuration column of the table.
    fn label(&self) -> String {
        let mode = mode_name(self.shading);
        match self.engine {
            Engine::Kernel { dither: false } => format!("kernel {mode}"),
            Engine::Kernel { dither: true } => format!("kernel {mode} + dither"),
            Engine::Reference => format!("f64 {mode}"),
        }
    }
}

fn mode_name(s: Shading) -> &'static str {
    match s {
        Shading::Flat => "flat",
        Shading::Gouraud => "Gouraud",
        Shading::Phong => "Phong",
    }
}

/// The shading modes a standard scene allows. S2 is defined as per-vertex
/// colours interpolated (Gouraud, no lighting), so flat and Phong have no
/// meaning there.
fn modes(scene: &str) -> &'static [Shading] {
    match scene {
        "S2" => &[Shading::Gouraud],
        _ => &[Shading::Flat, Shading::Gouraud, Shading::Phong],
    }
}

/// The mode of the "truth" a scene's model error is measured against:
/// per-pixel Phong where the scene allows it, otherwise its only mode.
fn truth_mode(scene: &str) -> Shading {
    let m = modes(scene);
    if m.contains(&Shading::Phong) {
        Shading::Phong
    } else {
        m[0]
    }
}

/// Every configuration, in a fixed order (the callgrind child relies on it).
fn configs() -> Vec<Config> {
    let mut v = Vec::new();
    for (scene, _) in standard_scenes::all() {
        for &shading in modes(scene) {
            for engine in [
                Engine::Kernel { dither: false },
                Engine::Kernel { dither: true },
                Engine::Reference,
            ] {
                v.push(Config {
                    scene,
                    shading,
                    engine,
                });
            }
        }
    }
    v
}

/// The scene description of a configuration.
fn desc_for(base: &SceneDesc, c: &Config) -> SceneDesc {
    SceneDesc {
        shading: c.shading,
        dither: matches!(c.engine, Engine::Kernel { dither: true }),
        ..base.clone()
    }
}

/// Buffers for kernel renders into a plain framebuffer.
struct KernelBuffers {
    pixels: Vec<u16>,
    depth: Vec<u16>,
    cache: Vec<CachedVertex>,
}

impl KernelBuffers {
    fn new(d: &SceneDesc) -> Self {
        let n = d.width as usize * d.height as usize;
        KernelBuffers {
            pixels: vec![0; n],
            depth: vec![0; n],
            cache: vec![CachedVertex::default(); d.mesh.positions.len()],
        }
    }

    /// One frame: clear colour and depth, then draw.
    fn frame(&mut self, scene: &KernelScene) {
        let mut fb =
            Framebuffer::new(&mut self.pixels, scene.width, scene.height).expect("framebuffer");
        let stats = scene
            .render_framebuffer(&mut fb, &mut self.depth, &mut self.cache)
            .expect("standard scene renders");
        black_box(stats);
    }
}

/// The function whose instructions callgrind counts: one call is one frame.
#[inline(never)]
fn counted_frame(frame: &mut dyn FnMut()) {
    frame();
}

/// Run times of one configuration, in seconds.
#[derive(Clone, Copy, Debug, Default)]
struct Timing {
    median: f64,
    p25: f64,
    p75: f64,
    min: f64,
    max: f64,
}

/// Times every frame function `reps` times, in rounds (one call of each
/// function per round, after a warm-up round), so that a burst of load on a
/// shared machine spreads over all configurations instead of spoiling one.
fn time_rounds(reps: usize, frames: &mut [Box<dyn FnMut()>]) -> Vec<Timing> {
    for f in frames.iter_mut() {
        f();
    }
    let mut samples = vec![Vec::with_capacity(reps); frames.len()];
    for _ in 0..reps.max(1) {
        for (f, t) in frames.iter_mut().zip(samples.iter_mut()) {
            let start = Instant::now();
            f();
            t.push(start.elapsed().as_secs_f64());
        }
    }
    samples.into_iter().map(timing).collect()
}

/// Median, quartiles and extremes of some samples (at least one).
fn timing(mut t: Vec<f64>) -> Timing {
    t.sort_by(f64::total_cmp);
    // Quantile with linear interpolation between the sorted samples.
    let q = |p: f64| {
        let x = p * (t.len() - 1) as f64;
        let (i, frac) = (x.floor() as usize, x.fract());
        t[i] + (t[(i + 1).min(t.len() - 1)] - t[i]) * frac
    };
    Timing {
        median: q(0.5),
        p25: q(0.25),
        p75: q(0.75),
        min: t[0],
        max: t[t.len() - 1],
    }
}

/// A reference frame quantised to RGB565, with its coverage, so that
/// [`compare`] can measure it against another reference frame.
fn quantised(r: &RefFrame) -> (Vec<u16>, Vec<bool>) {
    r.color
        .iter()
        .map(|c| (c.map(quantize_rgb565).unwrap_or(0), c.is_some()))
        .unzip()
}

/// One row of the table.
struct Row {
    config: Config,
    /// Kernel against the reference of the same mode (none for the reference).
    fixed: Option<ErrorStats>,
    /// The reference of this mode against the truth.
    model: ErrorStats,
    /// This configuration's output against the truth.
    total: ErrorStats,
    /// Filled in once every configuration has been timed.
    time: Timing,
    instructions: Option<u64>,
}

struct Args {
    reps: usize,
    out: PathBuf,
    callgrind: bool,
}

fn parse_args() -> Result<Option<Args>, String> {
    let mut args = Args {
        reps: 15,
        out: Path::new(env!("CARGO_MANIFEST_DIR")).join("../report"),
        callgrind: true,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--reps" => {
                args.reps = it
                    .next()
                    .and_then(|s| s.parse().ok())
                    .filter(|&n| n > 0)
                    .ok_or("--reps needs a positive integer")?
            }
            "--out" => args.out = PathBuf::from(it.next().ok_or("--out needs a directory")?),
            "--no-callgrind" => args.callgrind = false,
            "--callgrind-frames" => return Ok(None),
            "-h" | "--help" => return Err(USAGE.into()),
            other => return Err(format!("unknown argument {other:?}\n{USAGE}")),
        }
    }
    Ok(Some(args))
}

fn main() -> ExitCode {
    let result = match parse_args() {
        Ok(None) => callgrind_frames(),
        Ok(Some(args)) => run(&args),
        Err(msg) => {
            eprintln!("{msg}");
            return ExitCode::from(2);
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("report: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The child under callgrind: one counted frame per configuration, in the
/// order of [`configs`], each after an uncounted warm-up frame.
fn callgrind_frames() -> Result<(), Error> {
    let scenes = standard_scenes::all();
    for c in configs() {
        let base = &scenes.iter().find(|(n, _)| *n == c.scene).expect("scene").1;
        let d = desc_for(base, &c);
        match c.engine {
            Engine::Kernel { .. } => {
                let scene = KernelScene::new(&d)?;
                let mut bufs = KernelBuffers::new(&d);
                bufs.frame(&scene);
                counted_frame(&mut || bufs.frame(&scene));
            }
            Engine::Reference => {
                counted_frame(&mut || {
                    black_box(reference::render(black_box(&d)).expect("renders"));
                });
            }
        }
    }
    Ok(())
}

/// Instructions per frame of every configuration (in [`configs`] order),
/// or `None` if valgrind is not installed or the run failed.
fn count_instructions(n: usize) -> Option<Vec<u64>> {
    let valgrind_ok = Command::new("valgrind")
        .arg("--version")
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if !valgrind_ok {
        eprintln!("valgrind not found: instructions n/a");
        return None;
    }
    let exe = std::env::current_exe().ok()?;
    let dir = std::env::temp_dir().join(format!("fixshade-callgrind-{}", std::process::id()));
    std::fs::create_dir_all(&dir).ok()?;
    let out_file = dir.join("cg.out");
    // `--toggle-collect` takes a wildcard, `--dump-after` only the exact
    // (demangled) name.
    let pattern = "*counted_frame*";
    let exact = "report::counted_frame";
    let started = Instant::now();
    let status = Command::new("valgrind")
        .arg("--tool=callgrind")
        .arg(format!("--toggle-collect={pattern}"))
        .arg(format!("--dump-after={exact}"))
        .arg(format!("--callgrind-out-file={}", out_file.display()))
        .arg(&exe)
        .arg("--callgrind-frames")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status();
    let counts = match status {
        Ok(s) if s.success() && !dir.join(format!("cg.out.{}", n + 1)).exists() => (1..=n)
            .map(|k| read_total(&dir.join(format!("cg.out.{k}"))))
            .collect::<Option<Vec<u64>>>(),
        _ => None,
    };
    let _ = std::fs::remove_dir_all(&dir);
    match &counts {
        Some(_) => eprintln!(
            "callgrind: {n} frames counted in {:.1} s",
            started.elapsed().as_secs_f64()
        ),
        None => eprintln!("callgrind run failed: instructions n/a"),
    }
    counts
}

/// The `summary:` (or `totals:`) line of a callgrind profile.
fn read_total(path: &Path) -> Option<u64> {
    let text = std::fs::read_to_string(path).ok()?;
    let line = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|rest| rest.split_whitespace().next())
            .and_then(|v| v.parse().ok())
    };
    line("summary:").or_else(|| line("totals:"))
}

fn run(args: &Args) -> Result<(), Error> {
    let started = Instant::now();
    let scenes = standard_scenes::all();
    let all = configs();
    let mut rows: Vec<Row> = Vec::new();
    // One frame function per configuration, timed later in rounds.
    let mut frames: Vec<Box<dyn FnMut()>> = Vec::new();
    for (name, base) in &scenes {
        // The reference frames of every mode, once (reused by the kernel rows).
        let refs: Vec<(Shading, RefFrame)> = modes(name)
            .iter()
            .map(|&m| {
                Ok((
                    m,
                    reference::render(&SceneDesc {
                        shading: m,
                        ..base.clone()
                    })?,
                ))
            })
            .collect::<Result<_, Error>>()?;
        let ref_of = |m: Shading| &refs.iter().find(|(s, _)| *s == m).expect("mode").1;
        let truth = ref_of(truth_mode(name));
        // The fixed-point error is against the reference of the mesh the
        // kernel draws (quantised, the same in every mode); the model and
        // total errors against the scene's own mesh.
        let drawn = KernelScene::new(base)?.reference_scene().clone();
        let drawn_refs: Vec<(Shading, RefFrame)> = modes(name)
            .iter()
            .map(|&m| {
                Ok((
                    m,
                    reference::render(&SceneDesc {
                        shading: m,
                        ..drawn.clone()
                    })?,
                ))
            })
            .collect::<Result<_, Error>>()?;
        let drawn_ref_of = |m: Shading| &drawn_refs.iter().find(|(s, _)| *s == m).expect("mode").1;
        for c in all.iter().filter(|c| c.scene == *name) {
            let d = desc_for(base, c);
            let own_ref = ref_of(c.shading);
            let (qp, qc) = quantised(own_ref);
            let model = compare(&qp, &qc, truth);
            let row = match c.engine {
                Engine::Kernel { .. } => {
                    let scene = KernelScene::new(&d)?;
                    let frame = scene.render_frame().map_err(|e| format!("{name}: {e:?}"))?;
                    let fixed = compare(&frame.pixels, &frame.covered, drawn_ref_of(c.shading));
                    let total = compare(&frame.pixels, &frame.covered, truth);
                    let mut bufs = KernelBuffers::new(&d);
                    frames.push(Box::new(move || bufs.frame(&scene)));
                    Row {
                        config: *c,
                        fixed: Some(fixed),
                        total,
                        model,
                        time: Timing::default(),
                        instructions: None,
                    }
                }
                Engine::Reference => {
                    frames.push(Box::new(move || {
                        black_box(reference::render(black_box(&d)).expect("renders"));
                    }));
                    Row {
                        config: *c,
                        fixed: None,
                        total: model.clone(),
                        model,
                        time: Timing::default(),
                        instructions: None,
                    }
                }
            };
            rows.push(row);
        }
    }
    for (row, time) in rows.iter_mut().zip(time_rounds(args.reps, &mut frames)) {
        eprintln!(
            "{} {:<26} median {:>9.3} ms  total error mean {:.4} LSB",
            row.config.scene,
            row.config.label(),
            time.median * 1e3,
            row.total.mean_error
        );
        row.time = time;
    }
    if args.callgrind {
        if let Some(counts) = count_instructions(all.len()) {
            for (row, n) in rows.iter_mut().zip(counts) {
                row.instructions = Some(n);
            }
        }
    }

    std::fs::create_dir_all(&args.out)?;
    let md_path = args.out.join("error_vs_time.md");
    let svg_path = args.out.join("error_vs_time.svg");
    std::fs::write(&md_path, markdown(&rows, args))?;
    plot(&rows, &svg_path)?;
    check_table(&md_path, &all)?;
    eprintln!(
        "wrote {} and {} in {:.1} s",
        md_path.display(),
        svg_path.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Checks that the written table has exactly one row for every scene and
/// configuration.
fn check_table(md: &Path, all: &[Config]) -> Result<(), Error> {
    let text = std::fs::read_to_string(md)?;
    let mut seen = BTreeSet::new();
    for line in text.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() > 3
            && cells[1].starts_with('S')
            && cells[2].contains(' ')
            && !seen.insert((cells[1].to_string(), cells[2].to_string()))
        {
            return Err(format!("table has two rows for {} {}", cells[1], cells[2]).into());
        }
    }
    let missing: Vec<String> = all
        .iter()
        .filter(|c| !seen.contains(&(c.scene.to_string(), c.label())))
        .map(|c| format!("{} {}", c.scene, c.label()))
        .collect();
    if !missing.is_empty() {
        return Err(format!("table lacks rows for: {}", missing.join(", ")).into());
    }
    if seen.len() != all.len() {
        return Err(format!("table has {} rows, expected {}", seen.len(), all.len()).into());
    }
    eprintln!(
        "table: {} rows, one per scene and configuration",
        seen.len()
    );
    Ok(())
}

/// A command's first output line, or "unknown".
fn command_line(cmd: &str, args: &[&str]) -> String {
    Command::new(cmd)
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| {
            String::from_utf8(o.stdout)
                .ok()?
                .lines()
                .next()
                .map(str::to_string)
        })
        .unwrap_or_else(|| "unknown".into())
}

fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into())
}

fn ms(s: f64) -> String {
    let v = s * 1e3;
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else if v >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

fn mega(n: u64) -> String {
    format!("{:.3} M", n as f64 / 1e6)
}

fn max3(e: &ErrorStats) -> String {
    format!("{}/{}/{}", e.max_error[0], e.max_error[1], e.max_error[2])
}

fn markdown(rows: &[Row], args: &Args) -> String {
    let mut s = String::new();
    let w = &mut s;
    let _ = writeln!(w, "# Error against run time\n");
    let _ = writeln!(
        w,
        "Generated by `cargo run --release --example report -- --reps {}` \
         (examples/report.rs); do not edit by hand.\n",
        args.reps
    );
    let _ = writeln!(w, "Measured on:\n");
    let _ = writeln!(w, "- CPU: {} (`nproc`: {})", cpu_model(), {
        std::thread::available_parallelism().map_or(0, |n| n.get())
    });
    let _ = writeln!(w, "- `{}`", command_line("rustc", &["--version"]));
    let _ = writeln!(w, "- `{}`", command_line("valgrind", &["--version"]));
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|l| l.split_whitespace().next().map(str::to_string))
        .unwrap_or_else(|| "unknown".into());
    let _ = writeln!(
        w,
        "- times: {} timed renders per configuration, in interleaved rounds (one render of \
         every configuration per round) after a warm-up round, one thread; \
         1-minute load average when the table was written: {load} (a shared machine: \
         times are noisy, instruction counts are not)",
        args.reps
    );
    let _ = writeln!(w);
    let _ = writeln!(
        w,
        "All scenes are 320 × 240 RGB565 (see `src/standard_scenes.rs`). A kernel frame \
         is `KernelScene::render_framebuffer` (the framebuffer fast path): clear colour and depth, then draw. \
         A reference frame is `reference::render` (f64, SPEC.md to the letter, allocating \
         its frame).\n"
    );
    let _ = writeln!(w, "## What is swept\n");
    let _ = writeln!(
        w,
        "- **Shading mode**: flat, Gouraud, Phong, in every scene that allows it \
         (S2 is per-vertex colours interpolated, so Gouraud only).\n\
         - **Dithering**: 4 × 4 ordered (Bayer) dithering on or off.\n\
         - **Fixed point against floats**: the kernel against the f64 reference.\n\
         - Not knobs, so not swept: the specular table is one fixed table of 832 bytes \
         (no size to choose), and the interpolation keeps a fixed 16 fractional bits \
         below the RGB565 step (spans of 16 pixels or more: 11, 10 for green, re-anchored \
         every 64 pixels; see src/span.rs).\n"
    );
    let _ = writeln!(w, "## Errors\n");
    let _ = writeln!(
        w,
        "In LSBs of each RGB565 channel (SPEC.md 7), over pixels covered by both sides.\n\n\
         - **Fixed-point error**: the kernel against the f64 reference in the same shading \
         mode, undithered. For a dithered row it is the dithered kernel output against the \
         undithered reference, so it shows what dithering costs in per-pixel error. \
         Max per channel r/g/b, mean, share of pixels exact, coverage mismatches \
         (pixels drawn by one side only), depth ties and model steps (pixels the reference \
         flags as a tie between surfaces' quantised depths or as within 2⁻¹² of a spot's \
         cone edge or a specular cut-off: counted apart, not in the max, mean and exact \
         share).\n\
         - **Model error**: the reference in this shading mode, quantised, against the \
         reference in Phong mode (the truth; for S2, Gouraud is the definition). It is what \
         the shading mode costs, whatever the arithmetic.\n\
         - **Total**: this configuration's output against the truth: the mean error plotted \
         in `error_vs_time.svg`. Model and total errors set apart the truth's depth ties \
         and model steps.\n"
    );
    let _ = writeln!(w, "## Table\n");
    let _ = writeln!(
        w,
        "Instructions per frame: `valgrind --tool=callgrind`, x86-64, `--release`, one \
         frame counted inside one `#[inline(never)]` function (a kernel frame after an \
         uncounted warm-up frame): deterministic, so it compares across noisy machines \
         (n/a where valgrind is missing). The kernel's speed on the devices is counted on \
         the Cortex-M cores by `scripts/firmware.sh` ([firmware.md](firmware.md)).\n"
    );
    let _ = writeln!(
        w,
        "| scene | configuration | fixed-point max r/g/b | fixed-point mean | fixed-point exact | \
         coverage mismatches | depth ties | model steps | model max r/g/b | model mean | \
         model exact | total mean | median time (ms) | IQR p25–p75 (ms) | min–max (ms) | \
         instructions/frame |"
    );
    let _ = writeln!(
        w,
        "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | --- | --- | ---: |"
    );
    for r in rows {
        let (fmax, fmean, fexact, fcov, fties, fsteps) = match &r.fixed {
            Some(e) => (
                max3(e),
                format!("{:.4}", e.mean_error),
                format!("{:.2} %", e.exact_share * 100.0),
                format!("{}", e.only_kernel + e.only_reference),
                format!("{}", e.depth_ties),
                format!("{}", e.model_steps),
            ),
            None => (
                "—".into(),
                "—".into(),
                "—".into(),
                "—".into(),
                "—".into(),
                "—".into(),
            ),
        };
        let _ = writeln!(
            w,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.4} | {:.2} % | {:.4} | {} | {}–{} | {}–{} | {} |",
            r.config.scene,
            r.config.label(),
            fmax,
            fmean,
            fexact,
            fcov,
            fties,
            fsteps,
            max3(&r.model),
            r.model.mean_error,
            r.model.exact_share * 100.0,
            r.total.mean_error,
            ms(r.time.median),
            ms(r.time.p25),
            ms(r.time.p75),
            ms(r.time.min),
            ms(r.time.max),
            r.instructions.map_or("n/a".into(), mega),
        );
    }
    let _ = writeln!(w);
    let _ = writeln!(w, "## Plot\n");
    let _ = writeln!(
        w,
        "![error against time](error_vs_time.svg)\n\n\
         One panel per scene; x: median time per frame (log), y: total mean error against \
         the truth in LSB (log; an exact configuration is drawn on the bottom edge). \
         Filled markers and the red staircase: the Pareto front (no other configuration \
         is both faster and more accurate)."
    );
    s
}

/// Tick values `m · 10^k` in `[lo, hi]` for each mantissa `m` in `mantissas`.
fn ticks(lo: f64, hi: f64, mantissas: &[f64]) -> Vec<f64> {
    let mut v = Vec::new();
    for k in (lo.log10().floor() as i32 - 1)..=(hi.log10().ceil() as i32) {
        for m in mantissas {
            let t = m * 10f64.powi(k);
            if (lo..=hi).contains(&t) {
                v.push(t);
            }
        }
    }
    v
}

/// A tick value with just the decimals it needs (0.05, 2, 20).
fn tick_label(v: f64) -> String {
    let decimals = (-v.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// Indices of the Pareto-optimal points (smaller time and error are better).
fn pareto(points: &[(f64, f64)]) -> Vec<usize> {
    (0..points.len())
        .filter(|&i| {
            let (ti, ei) = points[i];
            !points
                .iter()
                .enumerate()
                .any(|(j, &(tj, ej))| j != i && tj <= ti && ej <= ei && (tj < ti || ej < ei))
        })
        .collect()
}

fn plot(rows: &[Row], path: &Path) -> Result<(), Error> {
    let root = SVGBackend::new(path, (1280, 960)).into_drawing_area();
    root.fill(&WHITE)?;
    let (title, body) = root.split_vertically(40);
    title.draw(&Text::new(
        "fixshade: error against run time, 320 × 240 RGB565. \
         Filled: on the Pareto front (red); hollow: another configuration is faster and more accurate.",
        (20, 12),
        ("sans-serif", 20).into_font(),
    ))?;
    let scenes: Vec<&str> = standard_scenes::all().iter().map(|(n, _)| *n).collect();
    for (area, scene) in body.split_evenly((2, 2)).iter().zip(scenes) {
        let rs: Vec<&Row> = rows.iter().filter(|r| r.config.scene == scene).collect();
        let nonzero = rs
            .iter()
            .map(|r| r.total.mean_error)
            .filter(|&e| e > 0.0)
            .fold(f64::INFINITY, f64::min);
        let floor = if nonzero.is_finite() {
            nonzero / 4.0
        } else {
            1e-3
        };
        let pts: Vec<(f64, f64)> = rs
            .iter()
            .map(|r| (r.time.median * 1e3, r.total.mean_error.max(floor)))
            .collect();
        let tmin = pts.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
        let tmax = pts.iter().map(|p| p.0).fold(0.0, f64::max);
        let emax = pts.iter().map(|p| p.1).fold(0.0, f64::max);
        let front = pareto(&pts);
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("{scene}: {}", scene_caption(scene)),
                ("sans-serif", 16),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(
                (tmin / 1.6..tmax * 4.0).log_scale().with_key_points(ticks(
                    tmin / 1.6,
                    tmax * 4.0,
                    &[1.0, 2.0, 5.0],
                )),
                (floor / 1.5..emax * 2.5).log_scale().with_key_points(ticks(
                    floor / 1.5,
                    emax * 2.5,
                    &[1.0],
                )),
            )?;
        chart
            .configure_mesh()
            .x_desc("median time per frame (ms)")
            .y_desc("mean error vs truth (LSB)")
            .x_label_formatter(&|v| tick_label(*v))
            .y_label_formatter(&|v| tick_label(*v))
            .light_line_style(WHITE.mix(0.0))
            .draw()?;
        // The Pareto front as a staircase through its points, by time.
        let mut f: Vec<(f64, f64)> = front.iter().map(|&i| pts[i]).collect();
        f.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut stairs = Vec::new();
        for (k, p) in f.iter().enumerate() {
            if k > 0 {
                stairs.push((p.0, f[k - 1].1));
            }
            stairs.push(*p);
        }
        chart
            .draw_series(LineSeries::new(stairs, RED.stroke_width(2)))?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
        let kinds = [
            ("kernel", BLUE, Engine::Kernel { dither: false }),
            (
                "kernel + dither",
                RGBColor(230, 120, 0),
                Engine::Kernel { dither: true },
            ),
            ("f64 reference", BLACK, Engine::Reference),
        ];
        for (kind, color, engine) in kinds {
            let items: Vec<(usize, &Row)> = rs
                .iter()
                .enumerate()
                .filter(|(_, r)| r.config.engine == engine)
                .map(|(i, r)| (i, *r))
                .collect();
            let front = &front;
            let pts = &pts;
            chart
                .draw_series(items.into_iter().map(move |(i, r)| {
                    let on_front = front.contains(&i);
                    let style = if on_front {
                        color.filled()
                    } else {
                        color.stroke_width(2)
                    };
                    let exact = r.total.mean_error == 0.0;
                    let mut label = mode_name(r.config.shading).to_string();
                    if exact {
                        label.push_str(" (exact)");
                    }
                    // Dithered labels left of their point, the others right,
                    // so that a dithered and an undithered point close
                    // together keep readable labels.
                    let font = ("sans-serif", 13).into_font().color(&color);
                    let text = if matches!(r.config.engine, Engine::Kernel { dither: true }) {
                        Text::new(label, (-8, 8), font.pos(Pos::new(HPos::Right, VPos::Top)))
                    } else {
                        Text::new(label, (8, -8), font.pos(Pos::new(HPos::Left, VPos::Bottom)))
                    };
                    EmptyElement::at(pts[i]) + Circle::new((0, 0), 5, style) + text
                }))?
                .label(kind)
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, color.filled()));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK.mix(0.3))
            .label_font(("sans-serif", 13))
            .draw()?;
    }
    root.present()?;
    Ok(())
}

fn scene_caption(scene: &str) -> &'static str {
    match scene {
        "S1" => "sphere 48 × 24, one directional light",
        "S2" => "full-screen quad, per-vertex colours",
        "S3" => "sphere 192 × 96",
        _ => "bunny, point and spot light",
    }
}

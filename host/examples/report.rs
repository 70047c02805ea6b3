//! Error against run time : renders every standard scene in every
//! configuration that trades accuracy for time, measures each one's error
//! against the f64 reference and its run time, and writes
//! `report/error_vs_time.md` (a table) and `report/error_vs_time.svg` (error
//! against time, one point per configuration, the Pareto front marked).
//!
//! ```text
//! cargo run --release -p fixshade-host --example report -- [--reps N] [--out DIR] [--no-callgrind]
//! ```
//!
//! * `--reps N`: timed renders per configuration (default 15, or the
//!   environment variable `REPORT_REPS`, a positive integer, when `--reps` is
//!   not given: CI runs the README's command as written with fewer
//!   repetitions); the median and the spread (interquartile range and
//!   min–max) are reported.
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
//! The time axis is what a board takes, three ways, one panel each: (a) an
//! RP2040 at 133 MHz and (b) an STM32F4 at 168 MHz, both estimated from the
//! instructions counted on QEMU by `scripts/firmware.sh`
//! (`report/firmware_counts.json`, undithered kernel frames only; the
//! cycles per instruction are assumed, and the ms per instruction are taken
//! from that file), and (c) this host, measured. If that file is missing or
//! unreadable the report says so and plots the host panel only. The device
//! panels also show tgx (a float renderer counted on the same QEMU machines:
//! `firmware/peers/tgx.tsv`) at an upper bound on its error against the
//! truth, from its pixel difference to fixshade's frame
//! (`firmware/peers/tgx_pixels.tsv`) and the triangle inequality.
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

const USAGE: &str = "usage: report [--reps N] [--out DIR] [--no-callgrind]\n\
     --reps N: timed renders per configuration (default 15, or $REPORT_REPS if set)";

/// Timed renders per configuration when neither `--reps` nor `REPORT_REPS`
/// says otherwise.
const DEFAULT_REPS: usize = 15;

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
    let mut reps = None;
    let mut args = Args {
        reps: DEFAULT_REPS,
        out: Path::new(env!("CARGO_MANIFEST_DIR")).join("../report"),
        callgrind: true,
    };
    let positive = |s: &str| s.trim().parse::<usize>().ok().filter(|&n| n > 0);
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--reps" => {
                reps = Some(
                    it.next()
                        .as_deref()
                        .and_then(positive)
                        .ok_or("--reps needs a positive integer")?,
                )
            }
            "--out" => args.out = PathBuf::from(it.next().ok_or("--out needs a directory")?),
            "--no-callgrind" => args.callgrind = false,
            "--callgrind-frames" => return Ok(None),
            "-h" | "--help" => return Err(USAGE.into()),
            other => return Err(format!("unknown argument {other:?}\n{USAGE}")),
        }
    }
    args.reps = match reps {
        Some(n) => n,
        None => match std::env::var("REPORT_REPS") {
            Ok(v) => positive(&v)
                .ok_or_else(|| format!("REPORT_REPS needs a positive integer, not {v:?}"))?,
            Err(std::env::VarError::NotPresent) => DEFAULT_REPS,
            Err(e) => return Err(format!("REPORT_REPS: {e}")),
        },
    };
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

/// A Cortex-M core counted on QEMU, and the board its time is estimated for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Core {
    /// thumbv6m, estimated for an RP2040 at 133 MHz.
    M0plus,
    /// thumbv7em, estimated for an STM32F4 at 168 MHz.
    M4,
}

impl Core {
    const ALL: [Core; 2] = [Core::M0plus, Core::M4];

    fn board(self) -> &'static str {
        match self {
            Core::M0plus => "RP2040 133 MHz",
            Core::M4 => "STM32F4 168 MHz",
        }
    }

    fn mhz(self) -> f64 {
        match self {
            Core::M0plus => 133.0,
            Core::M4 => 168.0,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Core::M0plus => "M0+",
            Core::M4 => "M4",
        }
    }
}

/// One frame of `report/firmware_counts.json`: an undithered kernel frame
/// counted on QEMU.
#[derive(Clone, Debug)]
struct DeviceFrame {
    scene: String,
    shading: Shading,
    m4_instructions: u64,
    m0plus_instructions: u64,
    stm32f4_ms: f64,
    rp2040_ms: f64,
}

impl DeviceFrame {
    fn instructions(&self, core: Core) -> u64 {
        match core {
            Core::M0plus => self.m0plus_instructions,
            Core::M4 => self.m4_instructions,
        }
    }

    fn ms(&self, core: Core) -> f64 {
        match core {
            Core::M0plus => self.rp2040_ms,
            Core::M4 => self.stm32f4_ms,
        }
    }
}

/// The device counts written by `scripts/firmware.sh`.
struct DeviceCounts {
    frames: Vec<DeviceFrame>,
}

impl DeviceCounts {
    /// Estimated milliseconds per instruction on a core, as the JSON's
    /// estimates imply (their sum over their instructions' sum, so that the
    /// estimates' rounding to 1 µs hardly matters).
    fn ms_per_instruction(&self, core: Core) -> f64 {
        let ms: f64 = self.frames.iter().map(|f| f.ms(core)).sum();
        let n: u64 = self.frames.iter().map(|f| f.instructions(core)).sum();
        ms / n as f64
    }

    /// The cycles per instruction the estimates assume.
    fn cpi(&self, core: Core) -> f64 {
        self.ms_per_instruction(core) * core.mhz() * 1e3
    }

    /// The estimate for a configuration: undithered kernel frames only.
    fn ms(&self, c: &Config, core: Core) -> Option<f64> {
        if c.engine != (Engine::Kernel { dither: false }) {
            return None;
        }
        self.frames
            .iter()
            .find(|f| f.scene == c.scene && f.shading == c.shading)
            .map(|f| f.ms(core))
    }
}

/// Where `scripts/firmware.sh` writes its counts.
fn firmware_counts_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../report/firmware_counts.json")
}

/// Reads the device counts; the error says what is wrong, for the report.
fn read_device_counts(path: &Path) -> Result<DeviceCounts, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read it: {e}"))?;
    let json: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("not valid JSON: {e}"))?;
    let list = json
        .get("frames")
        .and_then(|f| f.as_array())
        .ok_or("no \"frames\" array")?;
    let mut frames = Vec::new();
    for (i, f) in list.iter().enumerate() {
        let text_of = |key: &str| {
            f.get(key)
                .and_then(|v| v.as_str())
                .ok_or(format!("frames[{i}]: no string {key:?}"))
        };
        let count = |key: &str| {
            f.get(key)
                .and_then(|v| v.as_u64())
                .filter(|&n| n > 0)
                .ok_or(format!("frames[{i}]: no positive integer {key:?}"))
        };
        let ms = |key: &str| {
            f.get(key)
                .and_then(|v| v.as_f64())
                .filter(|v| v.is_finite() && *v > 0.0)
                .ok_or(format!("frames[{i}]: no positive number {key:?}"))
        };
        let shading = match text_of("shading")? {
            "flat" => Shading::Flat,
            "gouraud" => Shading::Gouraud,
            "phong" => Shading::Phong,
            other => return Err(format!("frames[{i}]: unknown shading {other:?}")),
        };
        frames.push(DeviceFrame {
            scene: text_of("scene")?.to_string(),
            shading,
            m4_instructions: count("m4_instructions")?,
            m0plus_instructions: count("m0plus_instructions")?,
            stm32f4_ms: ms("stm32f4_168mhz_ms_estimate")?,
            rp2040_ms: ms("rp2040_133mhz_ms_estimate")?,
        });
    }
    if frames.is_empty() {
        return Err("\"frames\" is empty".into());
    }
    Ok(DeviceCounts { frames })
}

/// A peer renderer's frame counted on a core, and, where its pixels were
/// compared with fixshade's frame, how far apart they are.
#[derive(Clone, Debug)]
struct PeerFrame {
    peer: String,
    core: Core,
    scene: String,
    /// Instructions of the draw (the `draw2` column of `tgx.tsv`).
    instructions: u64,
    pixels: Option<PeerPixels>,
}

/// A row of `tgx_pixels.tsv`: the peer's frame against fixshade's
/// undithered kernel frame of the same scene, over the pixels both draw.
#[derive(Clone, Copy, Debug)]
struct PeerPixels {
    /// Mean |difference| over those pixels and the three channels, in each
    /// channel's LSBs (rounded to 3 decimals in the source).
    mean: f64,
    exact_percent: f64,
    peer_drawn: u64,
    fixshade_drawn: u64,
    both_drawn: u64,
}

fn peers_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../firmware/peers")
}

/// The rows of a tab-separated file (lines starting with `#` skipped, the
/// first other line naming the columns), as (column, value) lookups.
fn read_tsv(path: &Path) -> Result<Vec<Vec<(String, String)>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let header: Vec<String> = lines
        .next()
        .ok_or(format!("{}: no header line", path.display()))?
        .split('\t')
        .map(|h| h.trim().to_string())
        .collect();
    Ok(lines
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split('\t').map(|v| v.trim().to_string()))
                .collect()
        })
        .collect())
}

fn tsv_field<T: std::str::FromStr>(row: &[(String, String)], key: &str) -> Result<T, String> {
    row.iter()
        .find(|(k, _)| k == key)
        .and_then(|(_, v)| v.parse().ok())
        .ok_or(format!("no valid {key:?} in row {row:?}"))
}

fn tsv_core(row: &[(String, String)]) -> Result<Core, String> {
    match tsv_field::<String>(row, "core")?.as_str() {
        "m0" | "m0plus" => Ok(Core::M0plus),
        "m4" => Ok(Core::M4),
        other => Err(format!("unknown core {other:?}")),
    }
}

/// tgx's counted frames (`firmware/peers/tgx.tsv`) with their pixel
/// comparisons (`firmware/peers/tgx_pixels.tsv`) where there are some.
fn read_peers(dir: &Path) -> Result<Vec<PeerFrame>, String> {
    let counts = read_tsv(&dir.join("tgx.tsv"))?;
    let pixels = read_tsv(&dir.join("tgx_pixels.tsv"))?;
    let mut px = Vec::new();
    for row in &pixels {
        px.push((
            tsv_field::<String>(row, "peer")?,
            tsv_core(row)?,
            tsv_field::<String>(row, "scene")?,
            PeerPixels {
                mean: tsv_field(row, "mean_lsb_vs_fixshade")?,
                exact_percent: tsv_field(row, "exact_percent")?,
                peer_drawn: tsv_field(row, "peer_drawn")?,
                fixshade_drawn: tsv_field(row, "fixshade_drawn")?,
                both_drawn: tsv_field(row, "both_drawn")?,
            },
        ));
    }
    let mut frames = Vec::new();
    for row in &counts {
        let (peer, core, scene) = (
            tsv_field::<String>(row, "peer")?,
            tsv_core(row)?,
            tsv_field::<String>(row, "scene")?,
        );
        let pixels = px
            .iter()
            .find(|(p, c, s, _)| *p == peer && *c == core && *s == scene)
            .map(|x| x.3);
        frames.push(PeerFrame {
            instructions: tsv_field(row, "draw2")?,
            peer,
            core,
            scene,
            pixels,
        });
    }
    Ok(frames)
}

/// The largest per-pixel sum of the three channels' |difference| in LSBs.
const MAX_PIXEL_LSB_SUM: f64 = 31.0 + 63.0 + 31.0;

/// An upper bound on a peer frame's total mean error (the report's
/// definition: the mean over the pixels it and the truth both draw, the
/// truth's depth ties and model steps set apart, and the three channels of
/// |difference| in LSBs), from its mean difference to fixshade's frame `F`
/// (over the pixels both draw) and `F`'s own total error `total`.
///
/// Per pixel and channel, |P − T| ≤ |P − F| + |F − T|. Summed over the
/// pixels all three draw (`A`), the first sum is at most the peer's sum over
/// the pixels it and `F` draw, the second at most `F`'s sum over its compared
/// pixels. The pixels the peer and the truth draw but `F` does not (at most
/// `peer_drawn − both_drawn`) add at most 31 + 63 + 31 LSB each. The count
/// divided by is at least `|A| ≥ compared − (F's covered − both_drawn)`.
/// The source's mean is rounded to 3 decimals, so 0.0005 is added to it.
fn peer_bound(px: &PeerPixels, total: &ErrorStats) -> Option<f64> {
    let kernel_covered = total.covered_both + total.only_kernel;
    let lost = kernel_covered.checked_sub(px.both_drawn)?;
    let common = total.compared.checked_sub(lost).filter(|&n| n > 0)? as f64;
    let peer_only = px.peer_drawn.checked_sub(px.both_drawn)? as f64;
    let sum = 3.0 * px.both_drawn as f64 * (px.mean + 0.0005)
        + 3.0 * total.compared as f64 * total.mean_error
        + MAX_PIXEL_LSB_SUM * peer_only;
    Some(sum / (3.0 * common))
}

/// A peer's point in a device panel.
#[derive(Clone, Debug)]
struct PeerPoint {
    frame: PeerFrame,
    pixels: PeerPixels,
    /// The estimated time, with the ms per instruction of fixshade's frames
    /// on that core.
    ms: f64,
    /// fixshade's undithered Gouraud kernel frame's total error.
    fixshade_total: f64,
    /// The upper bound on the peer's total error ([`peer_bound`]).
    bound: f64,
    /// Pixels drawn by fixshade's frame in this run, to check the
    /// transcribed count against.
    fixshade_covered: u64,
}

/// A peer frame the device panels leave out, and why.
#[derive(Clone, Debug)]
struct LeftOut {
    peer: String,
    core: Core,
    scene: String,
    /// A few words for the plot.
    short: &'static str,
    /// A sentence for the markdown.
    long: String,
}

impl LeftOut {
    fn what(&self) -> String {
        format!("{} {} {}", self.peer, self.core.name(), self.scene)
    }
}

/// The peer points the device panels can show, and each counted or
/// standard frame that cannot be shown.
fn peer_points(
    peers: &[PeerFrame],
    rows: &[Row],
    device: &DeviceCounts,
) -> (Vec<PeerPoint>, Vec<LeftOut>) {
    let mut points = Vec::new();
    let mut left_out = Vec::new();
    let gouraud_row = |scene: &str| {
        rows.iter().find(|r| {
            r.config.scene == scene
                && r.config.shading == Shading::Gouraud
                && r.config.engine == (Engine::Kernel { dither: false })
        })
    };
    for f in peers {
        let mut leave = |short: &'static str, long: String| {
            left_out.push(LeftOut {
                peer: f.peer.clone(),
                core: f.core,
                scene: f.scene.clone(),
                short,
                long,
            })
        };
        let Some(px) = f.pixels else {
            leave(
                "pixels not compared",
                format!(
                    "counted ({} instructions), but its pixels were not compared with \
                     fixshade's, so it has no error bound",
                    mega(f.instructions)
                ),
            );
            continue;
        };
        let Some(row) = gouraud_row(&f.scene) else {
            leave(
                "no fixshade Gouraud row",
                "no fixshade Gouraud kernel row for that scene".into(),
            );
            continue;
        };
        let Some(bound) = peer_bound(&px, &row.total) else {
            leave(
                "no bound",
                "its pixel counts do not fit fixshade's frame, so no bound".into(),
            );
            continue;
        };
        points.push(PeerPoint {
            ms: f.instructions as f64 * device.ms_per_instruction(f.core),
            fixshade_total: row.total.mean_error,
            bound,
            fixshade_covered: row.total.covered_both + row.total.only_kernel,
            frame: f.clone(),
            pixels: px,
        });
    }
    let peer_names: BTreeSet<&str> = peers.iter().map(|f| f.peer.as_str()).collect();
    for name in peer_names {
        for (scene, _) in standard_scenes::all() {
            for core in Core::ALL {
                if !peers
                    .iter()
                    .any(|f| f.peer == name && f.scene == scene && f.core == core)
                {
                    left_out.push(LeftOut {
                        peer: name.to_string(),
                        core,
                        scene: scene.to_string(),
                        short: "not counted",
                        long: "not counted (nor compared)".into(),
                    });
                }
            }
        }
    }
    (points, left_out)
}

/// What the device panels show, or why there are none.
struct DeviceView {
    counts: Result<DeviceCounts, String>,
    peers: Result<(Vec<PeerPoint>, Vec<LeftOut>), String>,
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

    let counts_path = firmware_counts_path();
    let counts = read_device_counts(&counts_path).map_err(|e| {
        format!(
            "`report/firmware_counts.json` ({}): {e}",
            counts_path.display()
        )
    });
    let peers = match &counts {
        Ok(c) => read_peers(&peers_dir()).map(|p| peer_points(&p, &rows, c)),
        Err(_) => Err("no device counts to place them against".into()),
    };
    match (&counts, &peers) {
        (Err(e), _) => eprintln!("device estimates n/a, host panel only: {e}"),
        (Ok(_), Err(e)) => eprintln!("peer points n/a: {e}"),
        (Ok(_), Ok((points, _))) => {
            for p in points {
                eprintln!(
                    "{} {} {}: {:.2} ms (est.), error vs truth <= {:.3} LSB",
                    p.frame.peer,
                    p.frame.core.name(),
                    p.frame.scene,
                    p.ms,
                    p.bound
                );
            }
        }
    }
    let view = DeviceView { counts, peers };

    std::fs::create_dir_all(&args.out)?;
    let md_path = args.out.join("error_vs_time.md");
    let svg_path = args.out.join("error_vs_time.svg");
    std::fs::write(&md_path, markdown(&rows, args, &view))?;
    plot(&rows, &svg_path, &view)?;
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

fn markdown(rows: &[Row], args: &Args, view: &DeviceView) -> String {
    let mut s = String::new();
    let w = &mut s;
    let _ = writeln!(w, "# Error against run time\n");
    let _ = writeln!(
        w,
        "Generated by `cargo run --release -p fixshade-host --example report -- --reps {}` \
         (host/examples/report.rs); do not edit by hand.\n",
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
        "All scenes are 320 × 240 RGB565 (see `host/src/standard_scenes.rs`). A kernel frame \
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
         below the RGB565 step (undithered Gouraud spans without a depth test: 11, 10 for \
         green, re-anchored every 64 pixels; see src/span.rs).\n"
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
    match &view.counts {
        Ok(c) => {
            let _ = writeln!(
                w,
                "RP2040 and STM32F4 (est.): the undithered kernel frame's instructions counted \
                 on QEMU by `scripts/firmware.sh` (`report/firmware_counts.json`, \
                 [firmware.md](firmware.md): the draw with the renderer's set-up, the clear not \
                 counted; the host times include the clear) times the time per instruction \
                 those estimates imply: {:.2} ns on the M0+, {:.2} ns on the M4. They are \
                 estimates, not measurements on boards: they assume an average of {:.2} \
                 cycles per instruction on the STM32F4's Cortex-M4 at 168 MHz (most \
                 data-processing instructions and multiplies 1 cycle, loads 2 unless \
                 pipelined, taken branches 2–4; code assumed to hit the STM32F4's ART flash \
                 cache) and {:.2} on the RP2040's Cortex-M0+ at 133 MHz (loads, stores and \
                 taken branches 2 cycles, the single-cycle multiplier; code from SRAM or \
                 hitting the XIP cache). The M0+ counts are of thumbv6m code whose divisions \
                 are software `__aeabi_uidiv` calls; on an RP2040 the HAL's hardware-divider \
                 intrinsics make those cheaper. Blank where not counted: the dithered kernel \
                 and the f64 reference have no device count.\n",
                c.ms_per_instruction(Core::M0plus) * 1e6,
                c.ms_per_instruction(Core::M4) * 1e6,
                c.cpi(Core::M4),
                c.cpi(Core::M0plus),
            );
        }
        Err(e) => {
            let _ = writeln!(
                w,
                "RP2040 and STM32F4 (est.): **not available**, the device counts could not \
                 be read ({e}); run `scripts/firmware.sh` to write them. The columns are \
                 blank and the plot shows the host panel only.\n"
            );
        }
    }
    let _ = writeln!(
        w,
        "| scene | configuration | fixed-point max r/g/b | fixed-point mean | fixed-point exact | \
         coverage mismatches | depth ties | model steps | model max r/g/b | model mean | \
         model exact | total mean | RP2040 133 MHz est. (ms) | STM32F4 168 MHz est. (ms) | \
         host median (ms) | host IQR p25–p75 (ms) | host min–max (ms) | \
         instructions/frame (x86-64) |"
    );
    let _ = writeln!(
        w,
        "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- | ---: |"
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
        let device = |core| {
            view.counts
                .as_ref()
                .ok()
                .and_then(|c| c.ms(&r.config, core))
                .map_or(String::new(), |v| ms(v / 1e3))
        };
        let _ = writeln!(
            w,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.4} | {:.2} % | {:.4} | {} | {} | {} | {}–{} | {}–{} | {} |",
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
            device(Core::M0plus),
            device(Core::M4),
            ms(r.time.median),
            ms(r.time.p25),
            ms(r.time.p75),
            ms(r.time.min),
            ms(r.time.max),
            r.instructions.map_or("n/a".into(), mega),
        );
    }
    let _ = writeln!(w);
    peers_markdown(w, view);
    let _ = writeln!(w, "## Plot\n");
    let panels = if view.counts.is_ok() {
        "One row per scene, three panels per row sharing the y axis: x is the time per \
         frame (log) (a) on an RP2040 at 133 MHz and (b) on an STM32F4 at 168 MHz, both \
         estimated from the QEMU counts (undithered kernel frames only: the dithered \
         kernel and the f64 reference have no device count; tgx as above), and (c) on \
         this host, measured (median)."
    } else {
        "One panel per scene; x: median time per frame on this host (log). The device \
         panels are left out: the device counts could not be read (see above)."
    };
    let _ = writeln!(
        w,
        "![error against time](error_vs_time.svg)\n\n\
         {panels} y: total mean error against the truth in LSB (log; an exact \
         configuration is drawn on the bottom edge). Filled markers and the red \
         staircase: the Pareto front of fixshade's configurations in that panel (no \
         other is both faster and more accurate)."
    );
    s
}

/// The markdown section on the peer's points in the device panels.
fn peers_markdown(w: &mut String, view: &DeviceView) {
    let _ = writeln!(w, "## tgx beside fixshade on the devices\n");
    let (points, left_out) = match &view.peers {
        Ok(p) => p,
        Err(e) => {
            let _ = writeln!(w, "No peer points: {e}.\n");
            return;
        }
    };
    let _ = writeln!(
        w,
        "tgx (github.com/vindar/tgx's `Renderer3D`, float, Gouraud) was counted on the same \
         QEMU machines as fixshade (`firmware/peers/tgx.tsv`, the draw only), and its frames \
         compared with fixshade's undithered Gouraud kernel frames by the peer harness \
         (`firmware/peers/tgx_pixels.tsv`: the mean |difference| over the pixels both draw \
         and the three channels, in LSBs). Its time is estimated with the same time per \
         instruction as fixshade's frames on that core. Its error against the truth was \
         not measured: the plot shows an upper bound. Per pixel and channel, \
         |tgx − truth| ≤ |tgx − fixshade| + |fixshade − truth| (the triangle inequality), and \
         the report's total mean is such a per-channel mean of |difference| in LSBs, so the \
         bound is about the sum of tgx's mean difference to fixshade and fixshade's Gouraud \
         total; it is made to hold for the report's definition over tgx's own pixels by \
         counting each pixel tgx draws and fixshade does not at the largest error \
         (31 + 63 + 31 LSB), dividing by the fewest pixels all three can share, and adding \
         0.0005 for the source's rounding.\n"
    );
    if !points.is_empty() {
        let _ = writeln!(
            w,
            "| peer | core | scene | instructions | est. ms | mean vs fixshade (LSB) | exact vs fixshade | \
             drawn: peer / fixshade / both | fixshade Gouraud total | the two added | error bound (LSB) |"
        );
        let _ = writeln!(
            w,
            "| --- | --- | --- | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: |"
        );
        for p in points {
            let _ = writeln!(
                w,
                "| {} | {} ({}) | {} | {} | {} | {:.3} | {:.2} % | {} / {} / {} | {:.4} | {:.3} | ≤ {:.3} |",
                p.frame.peer,
                p.frame.core.name(),
                p.frame.core.board(),
                p.frame.scene,
                mega(p.frame.instructions),
                ms(p.ms / 1e3),
                p.pixels.mean,
                p.pixels.exact_percent,
                p.pixels.peer_drawn,
                p.pixels.fixshade_drawn,
                p.pixels.both_drawn,
                p.fixshade_total,
                p.pixels.mean + p.fixshade_total,
                p.bound,
            );
        }
        let _ = writeln!(w);
        for p in points
            .iter()
            .filter(|p| p.pixels.fixshade_drawn != p.fixshade_covered)
        {
            let _ = writeln!(
                w,
                "Note: for {} {} {} the comparison counts {} pixels drawn by fixshade, \
                 this run's frame covers {} (pixels drawn black are not counted there): \
                 the bound still holds if the frames are the same, but check that the \
                 comparison is of this frame.\n",
                p.frame.peer,
                p.frame.core.name(),
                p.frame.scene,
                p.pixels.fixshade_drawn,
                p.fixshade_covered
            );
        }
    }
    if !left_out.is_empty() {
        let _ = writeln!(w, "Not plotted:\n");
        for l in left_out {
            let _ = writeln!(w, "- {}: {}.", l.what(), l.long);
        }
        let _ = writeln!(w);
    }
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

/// The time one panel's x axis shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Panel {
    /// Estimated from the QEMU counts for the board of a core.
    Device(Core),
    /// Measured on this host.
    Host,
}

impl Panel {
    /// The x axis's label.
    fn axis(self) -> &'static str {
        match self {
            Panel::Device(Core::M0plus) => "(a) RP2040 133 MHz, estimated from QEMU counts (ms)",
            Panel::Device(Core::M4) => "(b) STM32F4 168 MHz, estimated from QEMU counts (ms)",
            Panel::Host => "(c) host, measured (ms): median per frame",
        }
    }

    /// Its name in a chart's caption.
    fn short(self) -> &'static str {
        match self {
            Panel::Device(Core::M0plus) => "(a) RP2040, estimated",
            Panel::Device(Core::M4) => "(b) STM32F4, estimated",
            Panel::Host => "(c) host, measured",
        }
    }
}

/// What a point of the plot is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// A fixshade configuration.
    Config(Engine),
    /// A peer's frame, at an upper bound on its error.
    Peer,
}

/// One point of a panel: (time in ms, error in LSB), its label and kind.
struct Point {
    at: (f64, f64),
    label: String,
    kind: Kind,
}

const ORANGE: RGBColor = RGBColor(230, 120, 0);
const PEER_GREEN: RGBColor = RGBColor(0, 140, 70);

fn plot(rows: &[Row], path: &Path, view: &DeviceView) -> Result<(), Error> {
    let counts = view.counts.as_ref().ok();
    let (peers, left_out): (&[PeerPoint], &[LeftOut]) = match &view.peers {
        Ok((p, l)) => (p, l),
        Err(_) => (&[], &[]),
    };
    let panels: Vec<Panel> = if counts.is_some() {
        vec![
            Panel::Device(Core::M0plus),
            Panel::Device(Core::M4),
            Panel::Host,
        ]
    } else {
        vec![Panel::Host]
    };
    let scenes: Vec<&str> = standard_scenes::all().iter().map(|(n, _)| *n).collect();
    let mut lines = vec![format!(
        "fixshade: error against time per frame, 320 × 240 RGB565. y: total mean error \
         against the truth (LSB, log){}.",
        if panels.len() > 1 {
            ", the same along each row"
        } else {
            ""
        }
    )];
    match counts {
        Some(c) => {
            lines.push(format!(
                "(a), (b): estimates, not measured on boards: QEMU instruction counts × the time \
                 per instruction in report/firmware_counts.json ({:.2} cycles/instruction \
                 assumed on the M0+ at 133 MHz, {:.2} on the M4 at 168 MHz).",
                c.cpi(Core::M0plus),
                c.cpi(Core::M4)
            ));
            lines.push(
                "(a), (b): undithered kernel frames only (the dithered kernel and the f64 \
                 reference have no device count). (c): every configuration, median of the \
                 host's timed runs."
                    .into(),
            );
            let mut peer_line = "tgx (float, Gouraud): its error against the truth is not \
                measured; plotted at an upper bound: its mean difference to fixshade's Gouraud \
                frame + that frame's error (triangle inequality)."
                .to_string();
            if view.peers.is_err() {
                peer_line.push_str(" Not plotted: the peer files could not be read.");
            } else if !left_out.is_empty() {
                let missing: Vec<String> = left_out
                    .iter()
                    .map(|l| format!("{} ({})", l.what(), l.short))
                    .collect();
                let _ = write!(peer_line, " Not plotted: {}.", missing.join(", "));
            }
            lines.push(peer_line);
        }
        None => lines.push(
            "Host panels only: report/firmware_counts.json could not be read, so there are \
             no device estimates (see error_vs_time.md)."
                .to_string(),
        ),
    }
    let line_h = 24;
    let header = 14 + line_h * (lines.len() as i32 + 1);
    let (size, grid) = if panels.len() == 1 {
        ((1280, 920 + header as u32), (2, 2))
    } else {
        ((1950, 1920 + header as u32), (scenes.len(), panels.len()))
    };
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE)?;
    let (title, body) = root.split_vertically(header);
    for (k, line) in lines.iter().enumerate() {
        title.draw(&Text::new(
            line.as_str(),
            (20, 10 + line_h * k as i32),
            ("sans-serif", if k == 0 { 18 } else { 15 }).into_font(),
        ))?;
    }
    // One legend for every panel, on the header's last line.
    let y = 10 + line_h * lines.len() as i32 + 8;
    let font = ("sans-serif", 15).into_font();
    let mut x = 20;
    title.draw(&PathElement::new(
        vec![(x, y), (x + 24, y)],
        RED.stroke_width(2),
    ))?;
    title.draw(&Text::new(
        "Pareto front (filled: on it; hollow: another is faster and more accurate)",
        (x + 32, y - 8),
        font.clone(),
    ))?;
    x += 560;
    let mut kinds = vec![
        ("fixshade kernel".to_string(), BLUE),
        ("kernel + dither (host only)".to_string(), ORANGE),
        ("f64 reference (host only)".to_string(), BLACK),
    ];
    if counts.is_none() {
        kinds[1].0 = "kernel + dither".into();
        kinds[2].0 = "f64 reference".into();
    }
    for (name, color) in kinds {
        title.draw(&Circle::new((x + 6, y), 5, color.filled()))?;
        title.draw(&Text::new(name.clone(), (x + 18, y - 8), font.clone()))?;
        x += 40 + 8 * name.chars().count() as i32;
    }
    if !peers.is_empty() {
        title.draw(&TriangleMarker::new((x + 6, y), 7, PEER_GREEN.filled()))?;
        title.draw(&Text::new(
            "tgx (float), error ≤ bound",
            (x + 18, y - 8),
            font.clone(),
        ))?;
    }
    let areas = body.split_evenly(grid);
    for (si, scene) in scenes.iter().enumerate() {
        let rs: Vec<&Row> = rows.iter().filter(|r| r.config.scene == *scene).collect();
        let ps: Vec<&PeerPoint> = peers.iter().filter(|p| p.frame.scene == *scene).collect();
        // One error range for the whole row of panels.
        let errors: Vec<f64> = rs
            .iter()
            .map(|r| r.total.mean_error)
            .chain(ps.iter().map(|p| p.bound))
            .collect();
        let nonzero = errors
            .iter()
            .copied()
            .filter(|&e| e > 0.0)
            .fold(f64::INFINITY, f64::min);
        let floor = if nonzero.is_finite() {
            nonzero / 4.0
        } else {
            1e-3
        };
        let emax = errors.iter().fold(floor, |a, &e| a.max(e));
        for (pi, &panel) in panels.iter().enumerate() {
            let mut pts: Vec<Point> = Vec::new();
            for r in &rs {
                let x = match panel {
                    Panel::Host => Some(r.time.median * 1e3),
                    Panel::Device(core) => counts.and_then(|c| c.ms(&r.config, core)),
                };
                if let Some(x) = x {
                    let mut label = mode_name(r.config.shading).to_string();
                    if r.total.mean_error == 0.0 {
                        label.push_str(" (exact)");
                    }
                    pts.push(Point {
                        at: (x, r.total.mean_error.max(floor)),
                        label,
                        kind: Kind::Config(r.config.engine),
                    });
                }
            }
            if let Panel::Device(core) = panel {
                for p in ps.iter().filter(|p| p.frame.core == core) {
                    pts.push(Point {
                        at: (p.ms, p.bound),
                        label: format!("{} ≤ {:.2}", p.frame.peer, p.bound),
                        kind: Kind::Peer,
                    });
                }
            }
            let index = if panels.len() == 1 {
                si
            } else {
                si * panels.len() + pi
            };
            let note = match panel {
                Panel::Device(core) => left_out
                    .iter()
                    .filter(|l| l.core == core && l.scene == *scene)
                    .map(|l| format!("; {}: {}", l.peer, l.short))
                    .collect::<String>(),
                Panel::Host => String::new(),
            };
            panel_chart(
                &areas[index],
                scene,
                panel,
                &note,
                panels.len() == 1,
                &pts,
                (floor, emax),
            )?;
        }
    }
    root.present()?;
    Ok(())
}

/// One panel: a scene's points against one kind of time.
fn panel_chart(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    scene: &str,
    panel: Panel,
    note: &str,
    solo: bool,
    pts: &[Point],
    (floor, emax): (f64, f64),
) -> Result<(), Error> {
    let tmin = pts.iter().map(|p| p.at.0).fold(f64::INFINITY, f64::min);
    let tmax = pts.iter().map(|p| p.at.0).fold(0.0, f64::max);
    let (tmin, tmax) = if tmin.is_finite() && tmax > 0.0 {
        (tmin, tmax)
    } else {
        (1.0, 10.0)
    };
    // The Pareto front among fixshade's configurations (not the peers'
    // bounds).
    let own: Vec<usize> = (0..pts.len())
        .filter(|&i| pts[i].kind != Kind::Peer)
        .collect();
    let front: Vec<usize> = pareto(&own.iter().map(|&i| pts[i].at).collect::<Vec<_>>())
        .into_iter()
        .map(|k| own[k])
        .collect();
    // Alone, the host panel needs no "(c)".
    let solo_label = |s: &'static str| {
        if solo {
            s.trim_start_matches("(c) ")
        } else {
            s
        }
    };
    let (x0, x1) = (tmin / 1.6, tmax * 4.0);
    let (y0, y1) = (floor / 1.5, emax * 2.5);
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "{scene}: {} — {}{note}",
                scene_caption(scene),
                solo_label(panel.short())
            ),
            ("sans-serif", 16),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(64)
        .build_cartesian_2d(
            (x0..x1)
                .log_scale()
                .with_key_points(ticks(x0, x1, &[1.0, 2.0, 5.0])),
            (y0..y1).log_scale().with_key_points(ticks(y0, y1, &[1.0])),
        )?;
    chart
        .configure_mesh()
        .x_desc(solo_label(panel.axis()))
        .y_desc("total mean error vs truth (LSB)")
        .x_label_formatter(&|v| tick_label(*v))
        .y_label_formatter(&|v| tick_label(*v))
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    // The Pareto front as a staircase through its points, by time.
    let mut f: Vec<(f64, f64)> = front.iter().map(|&i| pts[i].at).collect();
    f.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut stairs = Vec::new();
    for (k, p) in f.iter().enumerate() {
        if k > 0 {
            stairs.push((p.0, f[k - 1].1));
        }
        stairs.push(*p);
    }
    chart.draw_series(LineSeries::new(stairs, RED.stroke_width(2)))?;
    let kinds = [
        (BLUE, Engine::Kernel { dither: false }),
        (ORANGE, Engine::Kernel { dither: true }),
        (BLACK, Engine::Reference),
    ];
    for (color, engine) in kinds {
        let items: Vec<usize> = (0..pts.len())
            .filter(|&i| pts[i].kind == Kind::Config(engine))
            .collect();
        if items.is_empty() {
            continue;
        }
        let front = &front;
        chart.draw_series(items.into_iter().map(move |i| {
            let p = &pts[i];
            let style = if front.contains(&i) {
                color.filled()
            } else {
                color.stroke_width(2)
            };
            // Dithered labels left of their point, the others right,
            // so that a dithered and an undithered point close
            // together keep readable labels.
            let font = ("sans-serif", 13).into_font().color(&color);
            let text = if engine == (Engine::Kernel { dither: true }) {
                Text::new(
                    p.label.clone(),
                    (-8, 8),
                    font.pos(Pos::new(HPos::Right, VPos::Top)),
                )
            } else {
                Text::new(
                    p.label.clone(),
                    (8, -8),
                    font.pos(Pos::new(HPos::Left, VPos::Bottom)),
                )
            };
            EmptyElement::at(p.at) + Circle::new((0, 0), 5, style) + text
        }))?;
    }
    let peers: Vec<&Point> = pts.iter().filter(|p| p.kind == Kind::Peer).collect();
    if !peers.is_empty() {
        chart.draw_series(peers.into_iter().map(|p| {
            let font = ("sans-serif", 13).into_font().color(&PEER_GREEN);
            EmptyElement::at(p.at)
                + TriangleMarker::new((0, 0), 7, PEER_GREEN.filled())
                + Text::new(
                    p.label.clone(),
                    (-9, 6),
                    font.pos(Pos::new(HPos::Right, VPos::Top)),
                )
        }))?;
    }
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

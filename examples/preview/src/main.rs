//! Live preview of a scene file: the fixed-point kernel renders into an
//! `embedded-graphics-simulator` window (SDL2) while the model spins.
//!
//! ```text
//! cargo run --release --manifest-path examples/preview/Cargo.toml -- examples/scenes/bunny.json
//! ```
//!
//! Keys: `S` shading (flat, Gouraud, Phong), `M` specular model (Blinn,
//! Phong), `V` viewer (infinite, local), `L` light (all of the scene's lights,
//! each one alone, a headlight from the camera), `Space` pause or resume the
//! spin, `Left`/`Right` turn by 5°, `Esc` or closing the window quits.
//!
//! The overlay shows the kernel's render time (median of the last frames)
//! and its error against the f64 reference (SPEC.md section 7), recomputed
//! whenever a setting changes and twice a second while spinning.

use std::collections::VecDeque;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use embedded_graphics::mono_font::ascii::FONT_6X10;
use embedded_graphics::mono_font::MonoTextStyleBuilder;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use embedded_graphics_simulator::sdl2::Keycode;
use embedded_graphics_simulator::{
    OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
};
use fixshade_host::error_measure::{compare, ErrorStats};
use fixshade_host::reference;
use fixshade::render::CachedVertex;
use fixshade_host::scene_desc::{LightDesc, SceneDesc, Shading, SpecularModel, Viewer};
use fixshade_host::scene_file::load_scene;
use fixshade_host::scene_kernel::KernelScene;

/// Spin speed, degrees per second.
const SPIN_DEG_PER_S: f64 = 30.0;
/// How often the error is recomputed while nothing but the angle changes.
const ERROR_PERIOD: Duration = Duration::from_millis(500);
/// Frames whose render times make up the shown median.
const TIME_WINDOW: usize = 31;

/// Which lights are on.
#[derive(Clone, Copy, PartialEq, Eq)]
enum LightChoice {
    /// Every light of the scene file.
    All,
    /// Only the scene's light with this index.
    One(usize),
    /// A white directional light from the camera.
    Headlight,
}

/// What the keys change.
struct Settings {
    shading: Shading,
    specular: SpecularModel,
    viewer: Viewer,
    light: LightChoice,
    spinning: bool,
    angle_deg: f64,
}

impl Settings {
    fn from_scene(s: &SceneDesc) -> Self {
        Settings {
            shading: s.shading,
            specular: s.specular_model,
            viewer: s.viewer,
            light: LightChoice::All,
            spinning: true,
            angle_deg: 0.0,
        }
    }

    /// Applies a key; true if the picture's settings changed.
    fn key(&mut self, key: Keycode, light_count: usize) -> bool {
        match key {
            Keycode::S => {
                self.shading = match self.shading {
                    Shading::Flat => Shading::Gouraud,
                    Shading::Gouraud => Shading::Phong,
                    Shading::Phong => Shading::Flat,
                }
            }
            Keycode::M => {
                self.specular = match self.specular {
                    SpecularModel::Blinn => SpecularModel::Phong,
                    SpecularModel::Phong => SpecularModel::Blinn,
                }
            }
            Keycode::V => {
                self.viewer = match self.viewer {
                    Viewer::Infinite => Viewer::Local,
                    Viewer::Local => Viewer::Infinite,
                }
            }
            Keycode::L => {
                self.light = match self.light {
                    LightChoice::All if light_count > 1 => LightChoice::One(0),
                    LightChoice::One(i) if i + 1 < light_count => LightChoice::One(i + 1),
                    LightChoice::Headlight => LightChoice::All,
                    _ => LightChoice::Headlight,
                }
            }
            Keycode::Space => self.spinning = !self.spinning,
            Keycode::Left => self.angle_deg -= 5.0,
            Keycode::Right => self.angle_deg += 5.0,
            _ => return false,
        }
        true
    }

    /// The scene as the settings make it.
    fn apply(&self, base: &SceneDesc) -> SceneDesc {
        let mut s = base.clone();
        s.shading = self.shading;
        s.specular_model = self.specular;
        s.viewer = self.viewer;
        s.lights = match self.light {
            LightChoice::All => base.lights.clone(),
            LightChoice::One(i) => base.lights.get(i).cloned().into_iter().collect(),
            LightChoice::Headlight => {
                let c = &base.camera;
                vec![LightDesc::directional(sub(c.eye, c.target))]
            }
        };
        s.model = mul(&spin(base, self.angle_deg), &base.model);
        s
    }

    fn light_name(&self, base: &SceneDesc) -> String {
        match self.light {
            LightChoice::All => format!("all {}", base.lights.len()),
            LightChoice::One(i) => format!("{i}: {}", kind(&base.lights[i])),
            LightChoice::Headlight => "headlight".into(),
        }
    }
}

fn kind(l: &LightDesc) -> &'static str {
    match l {
        LightDesc::Directional { .. } => "directional",
        LightDesc::Point { .. } => "point",
        LightDesc::Spot { .. } => "spot",
        LightDesc::Area { .. } => "area",
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// A rotation by `deg` about the vertical line through the camera's target.
fn spin(s: &SceneDesc, deg: f64) -> [[f64; 4]; 4] {
    let (sin, cos) = deg.to_radians().sin_cos();
    let [cx, _, cz] = s.camera.target;
    // T(c) · Ry · T(−c)
    [
        [cos, 0.0, sin, cx - cos * cx - sin * cz],
        [0.0, 1.0, 0.0, 0.0],
        [-sin, 0.0, cos, cz + sin * cx - cos * cz],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

fn mul(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let mut out = [[0.0; 4]; 4];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

fn name(s: Shading) -> &'static str {
    match s {
        Shading::Flat => "flat",
        Shading::Gouraud => "gouraud",
        Shading::Phong => "phong",
    }
}

fn median(times: &VecDeque<Duration>) -> Duration {
    let mut v: Vec<Duration> = times.iter().copied().collect();
    v.sort();
    v.get(v.len() / 2).copied().unwrap_or_default()
}

/// The kernel's error against the reference for this scene (the reference
/// renders the mesh the kernel draws, quantised).
fn error(kernel: &KernelScene) -> Result<ErrorStats, String> {
    let frame = kernel.render_frame().map_err(|e| e.to_string())?;
    let reference = reference::render(kernel.reference_scene()).map_err(|e| e.to_string())?;
    Ok(compare(&frame.pixels, &frame.covered, &reference))
}

fn has_display() -> bool {
    if cfg!(target_os = "linux") {
        ["DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER"]
            .iter()
            .any(|v| std::env::var_os(v).is_some())
    } else {
        true
    }
}

fn run() -> Result<(), (u8, String)> {
    let path: PathBuf = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .ok_or((2, "usage: fixshade-preview SCENE.json".to_string()))?;
    let base = load_scene(&path).map_err(|e| (2, format!("{}: {e}", path.display())))?;
    KernelScene::new(&base).map_err(|e| (2, format!("{}: {e}", path.display())))?;
    if base.width == 0 || base.height == 0 {
        return Err((2, format!("{}: empty viewport", path.display())));
    }
    if !has_display() {
        return Err((
            1,
            "no display (DISPLAY or WAYLAND_DISPLAY is not set)".into(),
        ));
    }

    let size = Size::new(base.width, base.height);
    let mut display = SimulatorDisplay::<Rgb565>::new(size);
    let mut depth = vec![0u16; base.width as usize * base.height as usize];
    let mut cache = vec![CachedVertex::default(); base.mesh.positions.len()];
    let settings_out = OutputSettingsBuilder::new().scale(2).build();
    let title = format!("fixshade preview: {}", path.display());
    let mut window = Window::new(&title, &settings_out);
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(Rgb565::WHITE)
        .background_color(Rgb565::BLACK)
        .build();

    let mut settings = Settings::from_scene(&base);
    let mut times: VecDeque<Duration> = VecDeque::with_capacity(TIME_WINDOW);
    let mut last_error: Option<Result<ErrorStats, String>> = None;
    let mut error_due = Instant::now();
    let mut last_frame = Instant::now();
    loop {
        let now = Instant::now();
        if settings.spinning {
            settings.angle_deg += SPIN_DEG_PER_S * (now - last_frame).as_secs_f64();
            settings.angle_deg %= 360.0;
        }
        last_frame = now;

        let desc = settings.apply(&base);
        let kernel = KernelScene::new(&desc).map_err(|e| (1, e.to_string()))?;
        let start = Instant::now();
        kernel
            .render(&mut display, &mut depth, &mut cache)
            .map_err(|e| (1, format!("kernel render: {e}")))?;
        if times.len() == TIME_WINDOW {
            times.pop_front();
        }
        times.push_back(start.elapsed());
        if now >= error_due {
            last_error = Some(error(&kernel));
            error_due = now + ERROR_PERIOD;
        }

        let spec = match settings.specular {
            SpecularModel::Blinn => "blinn",
            SpecularModel::Phong => "phong",
        };
        let viewer = match settings.viewer {
            Viewer::Infinite => "infinite",
            Viewer::Local => "local",
        };
        let lines = [
            format!(
                "[S]{} [M]{} [V]{} [L]{}",
                name(settings.shading),
                spec,
                viewer,
                settings.light_name(&base)
            ),
            format!("kernel {:.2} ms/frame", median(&times).as_secs_f64() * 1e3),
            match &last_error {
                Some(Ok(e)) => format!(
                    "err max {}/{}/{} mean {:.4} exact {:.1}% ties {} steps {} cov {}",
                    e.max_error[0],
                    e.max_error[1],
                    e.max_error[2],
                    e.mean_error,
                    e.exact_share * 100.0,
                    e.depth_ties,
                    e.model_steps,
                    e.only_kernel + e.only_reference
                ),
                Some(Err(e)) => format!("reference: {e}"),
                None => String::new(),
            },
        ];
        for (i, line) in lines.iter().enumerate() {
            Text::with_baseline(line, Point::new(2, 2 + 11 * i as i32), style, Baseline::Top)
                .draw(&mut display)
                .map_err(|e| (1, format!("overlay: {e:?}")))?;
        }

        window.update(&display);
        for event in window.events() {
            match event {
                SimulatorEvent::Quit => return Ok(()),
                SimulatorEvent::KeyDown { keycode, .. } => {
                    if settings.key(keycode, base.lights.len()) {
                        error_due = Instant::now();
                    }
                }
                _ => {}
            }
        }
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err((code, message)) => {
            eprintln!("error: {message}");
            ExitCode::from(code)
        }
    }
}

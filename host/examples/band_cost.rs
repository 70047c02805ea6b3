//! Band rendering: instructions per frame against band height, RAM, stack.
//!
//! ```sh
//! cargo run --release --example band_cost            # needs valgrind; writes report/band_cost.{md,svg}
//! cargo run --release --example band_cost -- probe s1 cached 16   # one frame (run under callgrind)
//! cargo run --release --example band_cost -- stack s1 cached 16   # stack of one frame, painted
//! ```
//!
//! Instructions are counted with `valgrind --tool=callgrind
//! --toggle-collect=*band_cost*frame*` around one frame at 320 × 240 (the
//! probe renders one frame through `#[inline(never)]` [`whole_frame`] or
//! [`band_frame`]). A whole frame is: clear the framebuffer and the depth
//! buffer, draw (the framebuffer fast path). A banded frame is: per band,
//! clear the colour and depth bands, draw the band's triangles, and copy
//! the band to the target (a `Framebuffer` standing for the display) with
//! one `fill_contiguous`.
//!
//! Stack: the probe builds S1 and S4 as firmware would (concrete light
//! types, not `KernelScene`'s run-time set of up to 64 lights), paints
//! 256 KB of stack below its frame with a pattern, renders one frame, and
//! finds the deepest byte that changed (host x86-64 `--release`; a
//! Cortex-M build differs). It checks that the frame equals `KernelScene`'s.

use std::fmt::Write as _;
use std::process::Command;

use embedded_graphics::pixelcolor::Rgb565;
use fixshade::band::Bands;
use fixshade::camera::{Camera, Projection};
use fixshade::depth::{DepthBand, DepthBuffer};
use fixshade::framebuffer::Framebuffer;
use fixshade::illumination::{InfiniteViewer, LocalViewer};
use fixshade::light::{
    unit_from_f64, Attenuation, DirectionalLight, PointLight, SpotCone, SpotLight,
};
use fixshade::material::BlinnPhong;
use fixshade::mesh::Mesh;
use fixshade::num::WidePoint;
use fixshade::render::CachedVertex;
use fixshade::render::{Gouraud, PhongShading, RenderOptions};
use fixshade::{Exponent, Mat4, Material, Renderer, Rgb};
use fixshade_host::scene_desc::{LightDesc, SceneDesc};
use fixshade_host::scene_kernel::KernelScene;
use fixshade_host::standard_scenes;
use plotters::prelude::*;

const W: u32 = 320;
const H: u32 = 240;
const HEIGHTS: [u32; 9] = [1, 2, 4, 8, 16, 32, 60, 120, 240];

fn scene(name: &str) -> KernelScene {
    let d = match name {
        "s1" => standard_scenes::s1(W, H),
        "s2" => standard_scenes::s2(W, H),
        "s3" => standard_scenes::s3(W, H),
        _ => standard_scenes::s4(W, H),
    };
    KernelScene::new(&d).expect("standard scene")
}

/// One whole frame through the framebuffer fast path.
#[inline(never)]
fn whole_frame(k: &KernelScene, px: &mut [u16], depth: &mut [u16], cache: &mut [CachedVertex]) {
    let mut fb = Framebuffer::new(px, W, H).unwrap();
    k.render_framebuffer(&mut fb, depth, cache).unwrap();
}

/// One frame in bands of `h` rows.
#[inline(never)]
fn band_frame(
    k: &KernelScene,
    px: &mut [u16],
    h: u32,
    colour: &mut [u16],
    depth: &mut [u16],
    cache: Option<&mut [CachedVertex]>,
) {
    let mut fb = Framebuffer::new(px, W, H).unwrap();
    k.render_bands(&mut fb.canvas(), h, colour, depth, cache)
        .unwrap();
}

/// Buffers of one run.
struct Run {
    k: KernelScene,
    px: Vec<u16>,
    colour: Vec<u16>,
    depth: Vec<u16>,
    cache: Vec<CachedVertex>,
    band_cache: Vec<CachedVertex>,
}

impl Run {
    fn new(name: &str, h: u32) -> Run {
        let k = scene(name);
        let n = k.mesh().positions.len();
        let band = (W * h.clamp(1, H)) as usize;
        Run {
            k,
            px: vec![0; (W * H) as usize],
            colour: vec![0; band],
            depth: vec![0; (W * H) as usize],
            cache: vec![CachedVertex::default(); n],
            band_cache: vec![CachedVertex::default(); n],
        }
    }

    fn frame(&mut self, mode: &str, h: u32) {
        match mode {
            "whole" => whole_frame(&self.k, &mut self.px, &mut self.depth, &mut self.cache),
            "cached" => band_frame(
                &self.k,
                &mut self.px,
                h,
                &mut self.colour,
                &mut self.depth,
                Some(&mut self.band_cache),
            ),
            _ => band_frame(
                &self.k,
                &mut self.px,
                h,
                &mut self.colour,
                &mut self.depth,
                None,
            ),
        }
    }
}

/// S1 and S4 as firmware would build them: concrete light types (no
/// 64-light run-time set as in `KernelScene`), so that the stack measured
/// is the kernel's.
#[allow(clippy::too_many_arguments)]
fn firmware_frame(
    d: &SceneDesc,
    mesh: &Mesh,
    mode: &str,
    h: u32,
    px: &mut [u16],
    colour: &mut [u16],
    depth: &mut [u16],
    cache: &mut [CachedVertex],
    whole_cache: &mut [CachedVertex],
) {
    let c = &d.camera;
    let fovy = match c.projection {
        fixshade_host::scene_desc::Projection::Perspective { fovy_deg } => fovy_deg as f32,
        _ => unreachable!(),
    };
    let camera = Camera::look_at_f64(c.eye, c.target, c.up)
        .and_then(|cam| {
            cam.with_projection(
                Projection::Perspective { fovy_deg: fovy },
                c.near as f32,
                c.far as f32,
            )
        })
        .unwrap();
    let m = &d.material;
    let rgb = |v: [f64; 3]| Rgb::from_f64(v).unwrap();
    let material = Material::new()
        .with_emission(rgb(m.emission))
        .with_ambient(rgb(m.ambient))
        .with_diffuse(rgb(m.diffuse))
        .with_specular(BlinnPhong {
            color: rgb(m.specular),
            shininess: Exponent::from_f64(m.shininess).unwrap(),
        });
    let model = Mat4::from_f64(d.model).unwrap();
    let opts = RenderOptions {
        cull: d.cull,
        two_sided: d.two_sided,
        dither: d.dither,
    };
    let bg = Rgb565::new(0, 0, 0);
    let mut fb = Framebuffer::new(px, W, H).unwrap();
    macro_rules! go {
        ($r:expr) => {{
            let r = $r;
            let shaded = mesh.shaded(&r).with_model(model);
            match mode {
                "whole" => {
                    // Cleared to the far value as made.
                    let mut db = DepthBuffer::new(depth, W, H).unwrap();
                    shaded
                        .with_depth(&mut db)
                        .with_cache(whole_cache)
                        .draw(&mut fb)
                        .unwrap();
                }
                "cached" => {
                    let mut display = fb.canvas();
                    let mut bands = Bands::new(&mut display, colour, h).with_background(bg);
                    shaded
                        .with_depth(&mut DepthBand::new(depth))
                        .with_cache(cache)
                        .draw(&mut bands)
                        .unwrap();
                }
                _ => {
                    let mut display = fb.canvas();
                    let mut bands = Bands::new(&mut display, colour, h).with_background(bg);
                    shaded
                        .with_depth(&mut DepthBand::new(depth))
                        .draw(&mut bands)
                        .unwrap();
                }
            }
        }};
    }
    let ga = rgb(d.global_ambient);
    match &d.lights[..] {
        [LightDesc::Directional {
            direction,
            diffuse,
            specular,
        }] => {
            let l = DirectionalLight::from_unit(unit_from_f64(*direction).unwrap())
                .with_diffuse(rgb(*diffuse))
                .with_specular(rgb(*specular));
            go!(Renderer::new(&camera, &material, &l)
                .with_ambient(ga)
                .with_viewer(InfiniteViewer)
                .with_shading(Gouraud)
                .with_options(opts))
        }
        [LightDesc::Point {
            position,
            diffuse,
            specular,
            attenuation,
        }, LightDesc::Spot {
            position: sp,
            axis,
            cutoff_deg,
            exponent,
            diffuse: sd,
            specular: ss,
            attenuation: sa,
        }] => {
            let point = |p: [f64; 3], d: [f64; 3], s: [f64; 3], a: [f64; 3]| PointLight {
                position: WidePoint::from_f64(p).unwrap(),
                diffuse: rgb(d),
                specular: rgb(s),
                attenuation: Attenuation::from_f64(a).unwrap(),
            };
            let lights = (
                point(*position, *diffuse, *specular, *attenuation),
                SpotLight {
                    light: point(*sp, *sd, *ss, *sa),
                    cone: SpotCone::from_f64(*axis, *cutoff_deg, *exponent).unwrap(),
                },
            );
            go!(Renderer::new(&camera, &material, &lights)
                .with_ambient(ga)
                .with_viewer(LocalViewer)
                .with_shading(PhongShading)
                .with_options(opts))
        }
        _ => unreachable!("S1 or S4"),
    }
}

const PAINT: usize = 256 * 1024;
const PATTERN: u8 = 0xA5;

/// Fills `PAINT` bytes below `base` (minus a margin for this frame) with
/// the pattern.
#[inline(never)]
fn paint(base: usize) {
    for a in (base - PAINT)..(base - 512) {
        // SAFETY: below the live frames, inside this thread's mapped stack
        // (8 MB for the main thread); nothing live is there.
        unsafe { std::ptr::write_volatile(a as *mut u8, PATTERN) };
    }
}

/// The deepest painted byte that changed, as a distance below `base`.
#[inline(never)]
fn scan(base: usize) -> usize {
    for a in (base - PAINT)..(base - 512) {
        // SAFETY: as in `paint`.
        if unsafe { std::ptr::read_volatile(a as *const u8) } != PATTERN {
            return base - a;
        }
    }
    0
}

/// Stack of one firmware-style frame (bytes below the caller's frame),
/// painted; checks that its pixels are `KernelScene`'s (with a black
/// background).
#[inline(never)]
fn stack_of(name: &str, mode: &str, h: u32) -> usize {
    let mut d = match name {
        "s1" => standard_scenes::s1(W, H),
        _ => standard_scenes::s4(W, H),
    };
    d.background = [0.0; 3];
    let k = KernelScene::new(&d).unwrap();
    let mesh = k.mesh();
    let n = mesh.positions.len();
    let (mut px, mut depth) = (vec![0u16; (W * H) as usize], vec![0u16; (W * H) as usize]);
    let mut colour = vec![0u16; (W * h) as usize];
    let (mut cache, mut wc) = (
        vec![CachedVertex::default(); n],
        vec![CachedVertex::default(); n],
    );
    // Warm up (page faults, lazy statics).
    firmware_frame(
        &d,
        &mesh,
        mode,
        h,
        &mut px,
        &mut colour,
        &mut depth,
        &mut cache,
        &mut wc,
    );
    let marker = 0u8;
    let base = std::hint::black_box(&marker) as *const u8 as usize;
    paint(base);
    firmware_frame(
        &d,
        &mesh,
        mode,
        h,
        &mut px,
        &mut colour,
        &mut depth,
        &mut cache,
        &mut wc,
    );
    let used = scan(base);
    let mut expect = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::new(&mut expect, W, H).unwrap();
    k.render_framebuffer(&mut fb, &mut depth, &mut wc).unwrap();
    assert!(expect == px, "firmware-style frame equals KernelScene's");
    used
}

fn callgrind(scene: &str, mode: &str, h: u32) -> u64 {
    let exe = std::env::current_exe().unwrap();
    let out = format!("/tmp/band_cost.{scene}.{mode}.{h}.cg");
    let status = Command::new("valgrind")
        .args([
            "--tool=callgrind",
            "--toggle-collect=*band_cost*frame*",
            &format!("--callgrind-out-file={out}"),
        ])
        .arg(&exe)
        .args(["probe", scene, mode, &h.to_string()])
        .output()
        .expect("valgrind runs");
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let _ = std::fs::remove_file(&out);
    text.lines()
        .find_map(|l| {
            l.strip_prefix("totals:")
                .or_else(|| l.strip_prefix("summary:"))
        })
        .and_then(|v| v.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .expect("callgrind totals")
}

fn stack_run(scene: &str, mode: &str, h: u32) -> usize {
    let exe = std::env::current_exe().unwrap();
    let out = Command::new(exe)
        .args(["stack", scene, mode, &h.to_string()])
        .output()
        .unwrap();
    String::from_utf8_lossy(&out.stdout).trim().parse().unwrap()
}

fn m(x: u64) -> String {
    format!("{:.2} M", x as f64 / 1e6)
}

fn kb(x: usize) -> String {
    format!("{:.1} KB", x as f64 / 1024.0)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    match args.get(1).map(String::as_str) {
        Some("probe") => {
            let h = args[4].parse().unwrap();
            let mut run = Run::new(&args[2], h);
            run.frame(&args[3], h);
            if args.get(5).is_some_and(|a| a == "stats") {
                let mut fb = Framebuffer::new(&mut run.px, W, H).unwrap();
                let whole = run
                    .k
                    .render_framebuffer(&mut fb, &mut run.depth, &mut run.cache)
                    .unwrap();
                let cache = (args[3] == "cached").then_some(&mut run.band_cache[..]);
                let b = run
                    .k
                    .render_bands(&mut fb.canvas(), h, &mut run.colour, &mut run.depth, cache)
                    .unwrap();
                println!("whole {whole:?}\nbands {b:?}");
            }
            return;
        }
        Some("stack") => {
            println!("{}", stack_of(&args[2], &args[3], args[4].parse().unwrap()));
            return;
        }
        _ => {}
    }
    let mut md = String::new();
    writeln!(
        md,
        "Whole frame (callgrind, x86-64 `--release`, instructions/frame):\n"
    )
    .unwrap();
    writeln!(md, "| scene | whole frame |\n| --- | --- |").unwrap();
    let mut whole = std::collections::HashMap::new();
    for s in ["s1", "s2", "s3", "s4"] {
        let n = callgrind(s, "whole", H);
        whole.insert(s, n);
        writeln!(md, "| {} | {} |", s.to_uppercase(), m(n)).unwrap();
        eprintln!("{s} whole {n}");
    }
    let mut curves: Vec<(String, Vec<(u32, f64)>)> = Vec::new();
    writeln!(
        md,
        "\nInstructions per frame against band height (320 × 240, depth test):\n"
    )
    .unwrap();
    let head: Vec<String> = HEIGHTS.iter().map(|h| h.to_string()).collect();
    writeln!(md, "| scene, vertices | whole | {} |", head.join(" | ")).unwrap();
    writeln!(md, "| --- | --- |{}", " --- |".repeat(HEIGHTS.len())).unwrap();
    let mut ram = String::new();
    writeln!(ram, "| scene | vertices | band rows | band buffers | vertex cache | stack (painted) | total RAM | instructions/frame | vs whole frame |").unwrap();
    writeln!(
        ram,
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
    )
    .unwrap();
    for s in ["s1", "s4"] {
        let nv = scene(s).mesh().positions.len();
        for mode in ["cached", "recomputed"] {
            let mut row = Vec::new();
            let mut pts = Vec::new();
            for &h in &HEIGHTS {
                let n = callgrind(s, mode, h);
                eprintln!("{s} {mode} {h} {n}");
                row.push(m(n));
                pts.push((h, n as f64 / whole[s] as f64));
                if [8, 16, 32].contains(&h) {
                    let buffers = (W * h * 2 * 2) as usize;
                    let cache = if mode == "cached" {
                        nv * core::mem::size_of::<CachedVertex>()
                    } else {
                        0
                    };
                    let stack = stack_run(s, mode, h);
                    writeln!(
                        ram,
                        "| {} | {mode} | {h} | {} | {} | {} | {} | {} | {:+.1} % |",
                        s.to_uppercase(),
                        kb(buffers),
                        kb(cache),
                        kb(stack),
                        kb(buffers + cache + stack),
                        m(n),
                        (n as f64 / whole[s] as f64 - 1.0) * 100.0
                    )
                    .unwrap();
                }
            }
            writeln!(
                md,
                "| {}, {mode} | {} | {} |",
                s.to_uppercase(),
                m(whole[s]),
                row.join(" | ")
            )
            .unwrap();
            curves.push((format!("{} {mode}", s.to_uppercase()), pts));
        }
    }
    let ws = stack_run("s1", "whole", H);
    let ws4 = stack_run("s4", "whole", H);
    let text = format!("{md}\nRAM beyond the mesh (band buffers: colour and depth, `u16`, 320 × rows; CachedVertex {} bytes; whole-frame stack S1 {}, S4 {}):\n\n{ram}", core::mem::size_of::<CachedVertex>(), kb(ws), kb(ws4));
    println!("{text}");
    std::fs::create_dir_all("report").unwrap();
    std::fs::write("report/band_cost.md", &text).unwrap();
    plot(&curves);
}

fn plot(curves: &[(String, Vec<(u32, f64)>)]) {
    let root = SVGBackend::new("report/band_cost.svg", (720, 480)).into_drawing_area();
    root.fill(&WHITE).unwrap();
    let ymax = curves
        .iter()
        .flat_map(|c| c.1.iter().map(|p| p.1))
        .fold(1.2f64, f64::max)
        .min(20.0);
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Band rendering at 320 × 240: instructions per frame / whole frame",
            ("sans-serif", 18),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d((1f64..240f64).log_scale(), (0.8f64..ymax).log_scale())
        .unwrap();
    chart
        .configure_mesh()
        .x_desc("band height (rows)")
        .y_desc("instructions / whole frame")
        .draw()
        .unwrap();
    let colours = [RED, BLUE, GREEN, MAGENTA];
    for (i, (name, pts)) in curves.iter().enumerate() {
        let c = colours[i % colours.len()];
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|&(h, r)| (h as f64, r)),
                c.stroke_width(2),
            ))
            .unwrap()
            .label(name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
        chart
            .draw_series(
                pts.iter()
                    .map(|&(h, r)| Circle::new((h as f64, r), 3, c.filled())),
            )
            .unwrap();
    }
    chart
        .draw_series(LineSeries::new(
            [(1.0, 1.15), (240.0, 1.15)],
            BLACK.mix(0.4),
        ))
        .unwrap()
        .label("whole frame + 15 %")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(0.4)));
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .unwrap();
    root.present().unwrap();
}

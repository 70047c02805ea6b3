//! Stiff and extreme cases in rendered scenes, each held to the
//! bound of SPEC.md 7 against the f64 reference (≤ 1 LSB per channel,
//! coverage mismatches ≤ 0.1 %), with no pixel sent outside the target and
//! no overflow (the tests run with overflow checks in debug).
//!
//! Per-vertex lighting alone is covered by `tests/lighting_vs_reference.rs`
//! (hand-picked and random); these are the same extremes drawn: shininess
//! up to the largest the API accepts on a sphere in Phong shading, N·L and
//! N·H within 10⁻⁴ of 0 and 1, near and far lights with extreme
//! attenuation, narrow and wide spots, bright and many lights; then the
//! geometry: degenerate triangles and slivers, triangles a million pixels
//! wide, vertices behind the camera and on the near plane, 0 × 0, 1 × 1 and
//! 4096 × 4096 targets, a viewport wider than `i16`.
//!
//! `cargo test --test stiff_cases -- --nocapture` prints each case's
//! measured error (the README's table).

use crate::common;
use crate::fuzz_scene;

use common::assert_within_bound;
use fixshade::camera::{Camera, Projection as CamProjection};
use fixshade::framebuffer::Framebuffer;
use fixshade::mesh::{Mesh, PackedNormal};
use fixshade::render::{CachedVertex, Flat, RenderError, RenderOptions};
use fixshade::{Material, Renderer, Vec3};
use fixshade_host::error_measure::{compare, ErrorStats};
use fixshade_host::generate;
use fixshade_host::reference::{self, quantize_rgb565};
use fixshade_host::scene_desc::{
    CameraDesc, LightDesc, MaterialDesc, MeshDesc, Projection, SceneDesc, Shading, SpecularModel,
    Viewer,
};
use fixshade_host::scene_kernel::KernelScene;
use fuzz_scene::CountingTarget;

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

/// Renders with the kernel twice (through the counting target, which must
/// see nothing outside, and through the framebuffer path used by
/// `render_frame`) and with the reference; returns the comparison.
fn measure(name: &str, scene: &SceneDesc) -> ErrorStats {
    scene.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
    let k = KernelScene::new(scene).unwrap_or_else(|e| panic!("{name}: {e}"));
    let frame = k.render_frame().expect("kernel render");
    let mut t = CountingTarget::new(scene.width, scene.height);
    let mut depth = vec![0u16; (scene.width * scene.height) as usize];
    let mut cache = vec![CachedVertex::default(); scene.mesh.positions.len()];
    let stats = k.render(&mut t, &mut depth, &mut cache).expect("render");
    assert_eq!(t.outside, 0, "{name}: pixels sent outside the target");
    assert_eq!(stats, frame.stats, "{name}: the two renders differ");
    let r = reference::render(k.reference_scene()).expect("reference");
    compare(&frame.pixels, &frame.covered, &r)
}

fn check(name: &str, scene: &SceneDesc) -> ErrorStats {
    let e = measure(name, scene);
    assert_within_bound(name, &e);
    e
}

fn normalized(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| x / l)
}

fn perspective(eye: [f64; 3], fovy_deg: f64, near: f64, far: f64) -> CameraDesc {
    CameraDesc {
        eye,
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near,
        far,
        projection: Projection::Perspective { fovy_deg },
    }
}

/// Looking down −Z at the plane z = 0 from z = 1, `height` units tall.
fn ortho(height: f64) -> CameraDesc {
    CameraDesc {
        eye: [0.0, 0.0, 1.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 0.5,
        far: 2.0,
        projection: Projection::Orthographic { height },
    }
}

/// The sphere of S1 (48 × 24, radius 1, seen from z = 3) in Phong shading
/// with one white light from the viewer's side and the given material.
fn sphere(material: MaterialDesc, lights: Vec<LightDesc>, w: u32, h: u32) -> SceneDesc {
    let mut s = SceneDesc::new(
        w,
        h,
        perspective([0.0, 0.0, 3.0], 60.0, 0.1, 10.0),
        generate::sphere(48, 24, 1.0),
    );
    s.material = material;
    s.lights = lights;
    s.global_ambient = [0.1; 3];
    s.shading = Shading::Phong;
    s
}

/// A 2 × 2 quad in the plane z = 0 filling a `size × size` orthographic
/// view, every vertex with normal `n`, Phong shading.
fn quad(n: [f64; 3], lights: Vec<LightDesc>, material: MaterialDesc, size: u32) -> SceneDesc {
    let mesh = MeshDesc {
        positions: vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        normals: Some(vec![n; 4]),
        indices: vec![[0, 1, 2], [0, 2, 3]],
    };
    let mut s = SceneDesc::new(size, size, ortho(2.0), mesh);
    s.material = material;
    s.lights = lights;
    s.global_ambient = [0.05; 3];
    s.shading = Shading::Phong;
    s
}

fn material(diffuse: f64, specular: f64, shininess: f64) -> MaterialDesc {
    MaterialDesc {
        emission: [0.0; 3],
        ambient: [0.2, 0.3, 0.4],
        diffuse: [diffuse, diffuse * 0.8, diffuse * 0.6],
        specular: [specular; 3],
        shininess,
    }
}

fn directional(d: [f64; 3], i: f64) -> LightDesc {
    LightDesc::Directional {
        direction: d,
        diffuse: [i; 3],
        specular: [i; 3],
    }
}

// ---------------------------------------------------------------------------
// Lighting extremes, drawn
// ---------------------------------------------------------------------------

/// Shininess 0, 1, 128, 1000, 2048 and 4096 (the largest `Exponent`
/// accepts) on a rendered sphere in Phong shading, both specular models,
/// both viewers. With the light beside the eye every visible point has
/// N·L > 1/3 (no specular switch-off in view), so shininess 0 — specular 1
/// wherever N·L > 0 — is defined everywhere drawn.
#[test]
fn shininess_up_to_the_largest_on_a_phong_sphere() {
    let light = LightDesc::Directional {
        direction: [0.1, 0.15, 1.0],
        diffuse: [0.7; 3],
        specular: [0.6; 3],
    };
    let mut worst = [0u32; 3];
    for n in [0.0, 1.0, 128.0, 1000.0, 2048.0, 4096.0] {
        for model in [SpecularModel::Blinn, SpecularModel::Phong] {
            for viewer in [Viewer::Infinite, Viewer::Local] {
                let mut s = sphere(material(0.6, 0.4, n), vec![light.clone()], 96, 96);
                s.specular_model = model;
                s.viewer = viewer;
                let e = check(&format!("shininess {n} {model:?} {viewer:?}"), &s);
                for (w, m) in worst.iter_mut().zip(e.max_error) {
                    *w = (*w).max(m);
                }
            }
        }
    }
    println!("shininess sweep: worst {worst:?} LSB");
}

/// The largest shininess renders a highlight at all: the pixel nearest the
/// mirror direction is brighter than the diffuse-only render.
#[test]
fn shininess_4096_still_has_a_highlight() {
    let light = directional([0.0, 0.0, 1.0], 1.0);
    let lit = sphere(material(0.3, 1.0, 4096.0), vec![light.clone()], 64, 64);
    let dull = sphere(material(0.3, 0.0, 4096.0), vec![light], 64, 64);
    let a = KernelScene::new(&lit).unwrap().render_frame().unwrap();
    let b = KernelScene::new(&dull).unwrap().render_frame().unwrap();
    let c = 32 * 64 + 32;
    assert!(
        a.pixels[c] > b.pixels[c],
        "no highlight: {:#06x} vs {:#06x}",
        a.pixels[c],
        b.pixels[c]
    );
}

/// N·L and N·H within 10⁻⁴ of 0 and of 1 on a drawn quad (every pixel the
/// same input). N·L just above 0 is drawn without specular (the switch at
/// N·L = 0 is a discontinuity of the equation); N·L just below 0 is dark.
/// With specular, N·L within 2⁻¹² of 0 is a step of the model that the
/// measure counts apart (every pixel of the quad); at ±10⁻³, four times
/// that margin, no pixel is, and every pixel holds the bound.
#[test]
fn dot_products_within_1e4_of_0_and_1() {
    let n = [0.0, 0.0, 1.0];
    let mut cases: Vec<(String, SceneDesc)> = Vec::new();
    for nl in [1e-4f64, -1e-4, 1.0 - 1e-4, 1.0, 0.5e-4] {
        let l = [(1.0 - nl * nl).sqrt(), 0.0, nl];
        cases.push((
            format!("N·L = {nl}"),
            quad(n, vec![directional(l, 1.0)], material(0.9, 0.0, 0.0), 24),
        ));
        // Specular only where N·L is not at the switch.
        if nl > 0.1 {
            for model in [SpecularModel::Blinn, SpecularModel::Phong] {
                let mut s = quad(n, vec![directional(l, 1.0)], material(0.5, 0.5, 64.0), 24);
                s.specular_model = model;
                cases.push((format!("N·L = {nl}, specular {model:?}"), s));
            }
        }
    }
    // N·H = cos(θ/2) for L at angle θ from N = V = +Z (infinite viewer).
    for nh in [1.0 - 1e-4, 1.0] {
        let theta = 2.0 * f64::acos(nh);
        let l = [theta.sin(), 0.0, theta.cos()];
        for n_shiny in [1.0, 128.0, 4096.0] {
            cases.push((
                format!("N·H = {nh}, n = {n_shiny}"),
                quad(
                    n,
                    vec![directional(l, 1.0)],
                    material(0.3, 0.7, n_shiny),
                    24,
                ),
            ));
        }
    }
    // N·H near 0 with N·L > 0: N ⟂ H = normalise(L + V) for L = +X,
    // V = +Z, tilted by 10⁻⁴. Normals are given, so N need not face V.
    for eps in [1e-4, -1e-4] {
        let a = std::f64::consts::FRAC_PI_4 + eps;
        let nrm = [a.cos(), 0.0, -a.sin()];
        for n_shiny in [1.0, 2.0, 128.0] {
            let mut s = quad(
                normalized(nrm),
                vec![directional([1.0, 0.0, 0.0], 1.0)],
                material(0.3, 0.9, n_shiny),
                24,
            );
            s.cull = false;
            cases.push((format!("N·H = {eps:+e}, n = {n_shiny}"), s));
        }
    }
    for (name, s) in &cases {
        let e = check(name, s);
        assert_eq!(e.model_steps, 0, "{name}: {e}");
    }
    // The specular cut-off itself, with Blinn–Phong: H = normalise(L + V)
    // is 45° from N, so the term it cuts off is large on both sides.
    for nl in [1e-4f64, -1e-4, 1e-3, -1e-3] {
        let l = [(1.0 - nl * nl).sqrt(), 0.0, nl];
        let mut s = quad(n, vec![directional(l, 1.0)], material(0.5, 0.5, 1.0), 24);
        s.specular_model = SpecularModel::Blinn;
        let name = format!("N·L = {nl}, specular Blinn, n = 1");
        let e = measure(&name, &s);
        println!("{name}: {e}");
        assert_eq!(e.covered_both, 24 * 24, "{name}: {e}");
        if nl.abs() <= reference::STEP_MARGIN {
            // Every pixel on the step: none held to the bound.
            assert_eq!((e.model_steps, e.compared), (24 * 24, 0), "{name}: {e}");
            assert_eq!(e.coverage_mismatch_share, 0.0, "{name}: {e}");
        } else {
            assert_within_bound(&name, &e);
            assert_eq!(e.model_steps, 0, "{name}: {e}");
        }
    }
}

/// Point lights 10⁻³, 1 and 10⁴ units from the surface with attenuation
/// constants from 10⁻⁶ to 10⁶, drawn in Phong shading (the light moves
/// across the quad's pixels, so near lights see L and d vary per pixel).
#[test]
fn near_and_far_point_lights_with_extreme_attenuation() {
    let atts = [
        [1.0, 0.0, 0.0],
        [1e-6, 0.0, 0.0],
        [1e6, 0.0, 0.0],
        [0.0, 1e-6, 0.0],
        [0.0, 1e6, 0.0],
        [0.0, 0.0, 1e-6],
        [0.0, 0.0, 1e6],
        [1e-6, 1e-6, 1e-6],
        [1e6, 1e6, 1e6],
        [0.0, 0.0, 0.0],
        [1.0, 1e3, 1e6],
    ];
    for d in [1e-3, 1.0, 1e4] {
        for a in atts {
            // Off-centre so that no pixel centre is at d = 0.
            let l = LightDesc::Point {
                position: [0.013, -0.021, d],
                diffuse: [0.9, 0.8, 0.7],
                specular: [0.5; 3],
                attenuation: a,
            };
            let s = quad([0.0, 0.0, 1.0], vec![l], material(0.8, 0.5, 16.0), 32);
            check(&format!("point at {d}, attenuation {a:?}"), &s);
        }
    }
}

/// Spots with cutoffs of 0.5° and 90° and exponents up to 128, shining
/// down on the quad. The cone's edge is a discontinuity of the equation
/// (s jumps from 0 to cos(cutoff)^p): the spot is placed so that no pixel
/// centre lies within 0.05° of it (checked), and the comparison holds
/// everywhere else.
#[test]
fn narrow_and_wide_spots() {
    let size = 48u32;
    for cutoff in [0.5f64, 90.0] {
        for p in [0.0, 1.0, 16.0, 128.0] {
            // Height chosen so that the 0.5° cone has a radius of a few
            // pixels; the 90° cone covers the plane.
            let h = 0.311;
            let centre = [0.0123, 0.0071];
            let margin = cone_margin_deg(size, centre, h, cutoff);
            assert!(
                margin > 0.05,
                "cutoff {cutoff}: a pixel centre {margin}° from the cone edge"
            );
            let l = LightDesc::Spot {
                position: [centre[0], centre[1], h],
                axis: [0.0, 0.0, -1.0],
                cutoff_deg: cutoff,
                exponent: p,
                diffuse: [1.0, 0.9, 0.8],
                specular: [0.6; 3],
                attenuation: [1.0, 0.0, 0.0],
            };
            let mut s = quad([0.0, 0.0, 1.0], vec![l], material(0.8, 0.4, 32.0), size);
            s.global_ambient = [0.2; 3];
            let e = check(&format!("spot cutoff {cutoff}° exponent {p}"), &s);
            assert!(e.covered_both == (size * size) as u64);
        }
    }
}

/// A spot cone whose edge passes exactly through pixel centres: the spot
/// stands over a pixel centre of the 48 × 48 quad and its 30° cone meets
/// the plane in a circle of radius 10 pixels, through the twelve centres
/// at offsets (±10, 0), (0, ±10), (±6, ±8) and (±8, ±6). There the model
/// jumps (the spot factor falls from `cos(30°)^p` to 0), so the reference
/// flags them as model steps; the flags lie on the circle and nowhere else,
/// and every other pixel holds the bound.
#[test]
fn spot_cone_edge_through_pixel_centres() {
    let size = 48u32;
    let px = 2.0 / f64::from(size); // a pixel's side in plane units
    let centre = [0.5 * px, -0.5 * px]; // the centre of pixel (24, 24)
    let (cutoff, radius): (f64, f64) = (30.0, 10.0);
    let h = radius * px / cutoff.to_radians().tan();
    for p in [0.0, 1.0, 16.0] {
        let l = LightDesc::Spot {
            position: [centre[0], centre[1], h],
            axis: [0.0, 0.0, -1.0],
            cutoff_deg: cutoff,
            exponent: p,
            diffuse: [1.0, 0.9, 0.8],
            specular: [0.6; 3],
            attenuation: [1.0, 0.0, 0.0],
        };
        let mut s = quad([0.0, 0.0, 1.0], vec![l], material(0.8, 0.4, 32.0), size);
        s.global_ambient = [0.2; 3];
        let name = format!("spot cone edge through pixel centres, exponent {p}");
        let e = check(&name, &s);
        assert!(e.exact_share >= 0.99, "{name}: {e}");
        let kernel = KernelScene::new(&s).expect("kernel scene");
        let r = reference::render(kernel.reference_scene()).expect("reference");
        let mut on_circle = 0;
        for (i, &step) in r.step.iter().enumerate() {
            let (x, y) = ((i as u32 % size) as f64, (i as u32 / size) as f64);
            let dist = ((x - 24.0).powi(2) + (y - 24.0).powi(2)).sqrt();
            // 2⁻¹² in cosγ is about 0.011 pixel of radius here.
            if step {
                assert!((dist - radius).abs() < 0.05, "{name}: step at ({x}, {y})");
            }
            on_circle += usize::from(dist == radius);
            if dist == radius {
                assert!(step, "{name}: ({x}, {y}) on the edge, not flagged");
            }
        }
        assert_eq!(on_circle, 12);
        assert_eq!(e.model_steps, r.step.iter().filter(|&&f| f).count() as u64);
        assert!(e.model_steps >= 12, "{name}: {e}");
    }
}

/// How far (in degrees) the nearest pixel centre of a `size × size` view of
/// the 2 × 2 quad is from the cone of a spot at height `h` above `centre`
/// pointing straight down.
fn cone_margin_deg(size: u32, centre: [f64; 2], h: f64, cutoff: f64) -> f64 {
    let mut m = f64::MAX;
    for y in 0..size {
        for x in 0..size {
            let px = (x as f64 + 0.5) / size as f64 * 2.0 - 1.0;
            let py = 1.0 - (y as f64 + 0.5) / size as f64 * 2.0;
            let r = ((px - centre[0]).powi(2) + (py - centre[1]).powi(2)).sqrt();
            let gamma = r.atan2(h).to_degrees();
            m = m.min((gamma - cutoff).abs());
        }
    }
    m
}

/// Light intensities above 1 (up to the 256 the format clamps to) on the
/// Phong sphere: the result clamps to 1 per channel exactly where the
/// reference's does. (Material colours above 1 are rejected by
/// `SceneDesc::validate`; the kernel's clamp of them is covered per vertex
/// in `tests/lighting_vs_reference.rs`.)
#[test]
fn intensities_above_one_clamp() {
    for i in [1.5, 4.0, 100.0, 256.0, 1e4] {
        let l = LightDesc::Directional {
            direction: [0.3, 0.5, 1.0],
            diffuse: [i, i / 8.0, i / 300.0],
            specular: [i / 50.0; 3],
        };
        let s = sphere(material(0.7, 0.3, 40.0), vec![l], 64, 64);
        check(&format!("intensity {i}"), &s);
    }
}

/// Sixteen lights of every kind summing past 1 on the Phong sphere.
#[test]
fn sixteen_lights_summing_past_one() {
    let lights: Vec<LightDesc> = (0..16)
        .map(|j| {
            let a = j as f64 * 0.41;
            let (c, s) = (a.cos(), a.sin());
            let i = [0.15 + 0.01 * j as f64, 0.12, 0.1];
            match j % 4 {
                0 => LightDesc::Directional {
                    direction: [c, s, 1.2],
                    diffuse: i,
                    specular: i,
                },
                1 => LightDesc::Point {
                    position: [2.0 * c, 2.0 * s, 2.0],
                    diffuse: i,
                    specular: i,
                    attenuation: [1.0, 0.1, 0.02],
                },
                2 => LightDesc::Spot {
                    position: [3.0 * c, 3.0 * s, 3.0],
                    axis: [-c, -s, -1.0],
                    cutoff_deg: 90.0,
                    exponent: 4.0,
                    diffuse: i,
                    specular: i,
                    attenuation: [1.0, 0.0, 0.0],
                },
                _ => LightDesc::Area {
                    center: [c, s, 3.0],
                    edge_u: [0.5, 0.0, 0.0],
                    edge_v: [0.0, 0.5, 0.0],
                    samples_k: 2,
                    diffuse: i,
                    specular: i,
                    attenuation: [1.0, 0.0, 0.0],
                },
            }
        })
        .collect();
    let s = sphere(material(0.7, 0.3, 24.0), lights, 80, 80);
    let e = check("16 lights", &s);
    // The sum does pass 1: some pixel is saturated in red.
    let k = KernelScene::new(&s).unwrap().render_frame().unwrap();
    assert!(k.pixels.iter().any(|&p| p >> 11 == 31), "{e}");
}

// ---------------------------------------------------------------------------
// Geometry at the edges
// ---------------------------------------------------------------------------

/// Degenerate triangles (all vertices equal, collinear, repeated indices)
/// draw nothing; slivers thinner than a pixel draw exactly the pixels whose
/// centres they contain (the reference's coverage), in every shading mode.
#[test]
fn degenerate_triangles_and_slivers() {
    let positions = vec![
        // 0–2: a normal triangle, so that something is drawn.
        [-0.9, -0.9, 0.0],
        [0.9, -0.9, 0.0],
        [0.0, 0.9, 0.0],
        // 3–5: one point three times (zero area).
        [0.1, 0.1, 0.0],
        [0.1, 0.1, 0.0],
        [0.1, 0.1, 0.0],
        // 6–8: collinear.
        [-0.5, -0.5, 0.0],
        [0.0, 0.0, 0.0],
        [0.5, 0.5, 0.0],
        // 9–11: a sliver 1/100 pixel thick, long (a 64 px view of 2 units:
        // a pixel is 1/32 unit).
        [-0.95, 0.95, 0.001],
        [0.95, 0.9501, 0.001],
        [0.95, 0.9499, 0.001],
        // 12–14: a sliver 0.3 pixel thick along a diagonal.
        [-0.8, -0.3, 0.002],
        [0.8, 0.5, 0.002],
        [0.8, 0.51, 0.002],
        // 15, in no triangle: x spans what y does, so that x and y are
        // quantised alike and 6–8 stay on the line x = y.
        [0.9501, -0.95, 0.0],
    ];
    let indices = vec![
        [0, 1, 2],
        [3, 4, 5],
        [6, 7, 8],
        [8, 7, 6],
        [0, 0, 1],
        [1, 2, 2],
        [5, 5, 5],
        [9, 11, 10],
        [12, 13, 14],
    ];
    for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
        for normals in [false, true] {
            let mesh = MeshDesc {
                positions: positions.clone(),
                normals: normals.then(|| vec![normalized([0.1, 0.2, 1.0]); positions.len()]),
                indices: indices.clone(),
            };
            let mut s = SceneDesc::new(64, 64, ortho(2.0), mesh);
            s.shading = shading;
            s.cull = false;
            s.depth = false;
            s.lights = vec![directional([0.2, 0.3, 1.0], 0.9)];
            let name = format!("degenerate {shading:?}, normals {normals}");
            let e = check(&name, &s);
            assert_eq!(
                e.only_kernel + e.only_reference,
                0,
                "{name}: coverage differs"
            );
            // Only the real triangle and the slivers' pixels: the
            // degenerate ones add nothing.
            let alone = {
                let k = KernelScene::new(&s).unwrap();
                let mut t = k.reference_scene().clone();
                t.mesh.indices = vec![[0, 1, 2], [9, 11, 10], [12, 13, 14]];
                reference::render(&t).unwrap().covered_count()
            };
            assert_eq!(e.covered_both as usize, alone, "{name}");
        }
    }
}

/// A draw of slivers and degenerate triangles directly, with a
/// counting target: sub-pixel triangles between pixel centres draw
/// nothing, a zero-area triangle nothing, and nothing goes outside.
#[test]
fn sub_pixel_slivers_between_centres_draw_nothing() {
    // Orthographic 16 × 16 over 2 units: a pixel is 1/8 unit, centres at
    // (k + ½)/8 − 1.
    let camera = Camera::look_at([0.0, 0.0, 1.0], [0.0; 3], [0.0, 1.0, 0.0])
        .and_then(|c| c.with_projection(CamProjection::Orthographic { height: 2.0 }, 0.5, 2.0))
        .unwrap();
    let q = 1 << 21; // 1/8 unit = one pixel, in I8F24
    let p = |x: i32, y: i32| Vec3::from_bits(x, y, 0);
    // Two meshes (each has its box: the far one's steps are 1/256 unit).
    let near = common::quantised(&[
        // A sliver along a pixel-boundary row (y = 0), 1/64 pixel tall.
        p(-6 * q, 0),
        p(6 * q, 0),
        p(6 * q, q / 64),
        // A tiny triangle inside one pixel, away from its centre.
        p(q / 8, q / 8),
        p(q / 4, q / 8),
        p(q / 8, q / 4),
    ]);
    // Zero area, far outside.
    let far = common::quantised(&[p(i32::MAX, i32::MAX), p(i32::MIN, i32::MIN), p(0, 0)]);
    let normals = [PackedNormal::Z; 6];
    let near_idx = [[0u16, 1, 2], [3, 4, 5]];
    let far_idx = [[0u16, 1, 2], [0, 0, 0]];
    let meshes = [
        Mesh::new(&near.positions, near.bounds, &near_idx).with_normals(&normals),
        Mesh::new(&far.positions, far.bounds, &far_idx).with_normals(&normals[..3]),
    ];
    let m = Material::new();
    let sun = fixshade::light::DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    let opts = RenderOptions {
        cull: false,
        ..RenderOptions::default()
    };
    let r = Renderer::new(&camera, &m, &sun).with_options(opts);
    let mut t = CountingTarget::new(16, 16);
    let mut cache = [CachedVertex::default(); 6];
    for mesh in &meshes {
        let stats = mesh.shaded(&r).with_cache(&mut cache).draw(&mut t).unwrap();
        assert_eq!(t.outside, 0);
        assert_eq!(t.writes, 0, "{stats:?}");
    }
}

/// Triangles far larger than the screen: a quad 10⁻⁴ in front of the near
/// plane (vertices near ±5·10⁴ pixels, clamped by no format), and a floor
/// under a 179.9° field of view (±10⁶ pixels). Each covers what the
/// reference covers. The quad ten times closer (±5·10⁵ pixels, near 10⁻⁴)
/// is refused: the vertex rows, scaled to the quad's reach of 1, are too
/// coarse 10⁻⁴ from the eye (`Camera::resolves`).
#[test]
fn triangles_a_million_pixels_wide() {
    // The quad: corners at x_e = ±1, z_e = −(near + near/10), 60° at 64 px:
    // x_w ≈ 32 + 32·1.73/1.1·10⁻³ ≈ 5·10⁴ px.
    let z = 0.0;
    let mesh = MeshDesc {
        positions: vec![
            [-1.0, -1.0, z],
            [1.0, -1.0, z],
            [1.0, 1.0, z],
            [-1.0, 1.0, z],
        ],
        normals: Some(vec![normalized([0.3, 0.2, 1.0]); 4]),
        indices: vec![[0, 1, 2], [0, 2, 3]],
    };
    for near in [1e-3, 1e-4] {
        let eye = [0.0, 0.0, near * 1.1];
        for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
            let mut s = SceneDesc::new(64, 48, perspective(eye, 60.0, near, 10.0), mesh.clone());
            s.shading = shading;
            s.lights = vec![LightDesc::Point {
                position: [0.1, 0.2, 0.5],
                diffuse: [0.9; 3],
                specular: [0.5; 3],
                attenuation: [1.0, 0.5, 0.0],
            }];
            s.material = material(0.8, 0.4, 8.0);
            s.viewer = Viewer::Local;
            let name = format!("quad {near} before the near plane, {shading:?}");
            if near < 1e-3 {
                let k = KernelScene::new(&s).expect("scene");
                let e = k.render_frame().err();
                assert_eq!(
                    e,
                    Some(fixshade::render::RenderError::SceneTooSmall),
                    "{name}"
                );
                continue;
            }
            let e = check(&name, &s);
            assert_eq!(e.covered_both, 64 * 48, "the quad covers the screen");
        }
    }
    // A floor under a very wide field of view: far corners at ±10⁶ px.
    for fov in [170.0, 179.0, 179.9] {
        let floor = MeshDesc {
            positions: vec![
                [-100.0, -1.0, 100.0],
                [100.0, -1.0, 100.0],
                [100.0, -1.0, -100.0],
                [-100.0, -1.0, -100.0],
            ],
            normals: Some(vec![[0.0, 1.0, 0.0]; 4]),
            indices: vec![[0, 1, 2], [0, 2, 3]],
        };
        let cam = CameraDesc {
            eye: [0.0, 0.0, 0.0],
            target: [0.0, -0.2, -1.0],
            up: [0.0, 1.0, 0.0],
            near: 0.05,
            far: 120.0,
            projection: Projection::Perspective { fovy_deg: fov },
        };
        let mut s = SceneDesc::new(64, 64, cam, floor);
        s.lights = vec![directional([0.3, 1.0, 0.2], 0.8)];
        s.shading = Shading::Gouraud;
        check(&format!("floor under {fov}°"), &s);
    }
}

/// Vertices behind the camera and exactly on the near plane (0.5 and the
/// positions are exact in binary), in every shading mode: the clipped
/// pieces are drawn as the reference draws them.
#[test]
fn vertices_behind_the_camera_and_on_the_near_plane() {
    let positions = vec![
        // Eye at z = 3, near 0.5: the near plane is z = 2.5.
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [0.0, 0.5, 2.5],  // on the near plane
        [0.0, -0.5, 5.0], // behind the eye
        [0.5, 0.5, 3.0],  // level with the eye
        [-0.5, 0.4, 2.5], // on the near plane
    ];
    let indices = vec![[0, 1, 2], [0, 1, 3], [1, 4, 0], [0, 5, 1], [2, 5, 3]];
    for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
        let mesh = MeshDesc {
            positions: positions.clone(),
            normals: Some(vec![normalized([0.0, 0.4, 1.0]); positions.len()]),
            indices: indices.clone(),
        };
        let mut s = SceneDesc::new(64, 64, perspective([0.0, 0.0, 3.0], 70.0, 0.5, 10.0), mesh);
        s.shading = shading;
        s.cull = false;
        s.depth = false;
        s.lights = vec![directional([0.1, 0.5, 1.0], 0.9)];
        let e = check(&format!("behind and on the near plane, {shading:?}"), &s);
        let k = KernelScene::new(&s).unwrap().render_frame().unwrap();
        assert!(k.stats.clipped > 0, "nothing was clipped");
        assert!(e.covered_both > 500);
    }
}

/// 0 × 0 and 1 × 1 targets through the comparison (nothing, and the one
/// pixel the sphere covers, as the reference does).
#[test]
fn zero_and_one_pixel_targets() {
    let l = vec![directional([0.2, 0.3, 1.0], 1.0)];
    let s = sphere(material(0.8, 0.3, 64.0), l.clone(), 1, 1);
    let e = check("1 × 1", &s);
    assert_eq!(e.covered_both, 1);
    let s0 = sphere(material(0.8, 0.3, 64.0), l, 0, 0);
    let e0 = measure("0 × 0", &s0);
    assert_eq!((e0.covered_both, e0.only_kernel), (0, 0));
}

/// A 4096 × 4096 target: S2's Gouraud quad covers every pixel exactly once
/// (counted), and a sample of 4096 pixels has the reference's colour
/// (vertex colours from the f64 reference, interpolated with affine
/// barycentrics at the pixel centre as SPEC.md 4 says) within 1 LSB.
#[test]
fn target_4096_square() {
    const N: u32 = 4096;
    let scene = fixshade_host::standard_scenes::s2(N, N);
    let k = KernelScene::new(&scene).unwrap();
    let mut t = CountingTarget::new(N, N);
    let mut cache = vec![CachedVertex::default(); 4];
    let stats = k.render(&mut t, &mut [], &mut cache).unwrap();
    assert_eq!(t.outside, 0);
    assert_eq!(t.writes, (N * N) as u64, "{stats:?}");
    assert_eq!(stats.pixels, N * N);
    assert!(
        t.pixels.iter().all(|&p| p != 0),
        "a pixel left at the black background"
    );
    // Reference vertex colours and window positions (orthographic: the
    // quad's corners are the screen's corners).
    let lights = reference::eye_lights(
        &scene.lights,
        &reference::look_at([0.0, 0.0, 1.0], [0.0; 3], [0.0, 1.0, 0.0]),
    );
    let model = reference::LightingModel {
        material: &scene.material,
        global_ambient: scene.global_ambient,
        lights: &lights,
        specular_model: scene.specular_model,
        viewer: scene.viewer,
    };
    // The normals the kernel draws (packed and decoded).
    let normals = k.reference_scene().mesh.normals.as_ref().unwrap();
    let colour: Vec<[f64; 3]> = normals
        .iter()
        .map(|n| reference::illuminate(&model, [0.0, 0.0, -1.0], normalized(*n)))
        .collect();
    // Window positions of vertices 0 (top left), 1 (top right), 2 (bottom
    // right), 3 (bottom left); triangles [0, 3, 2] and [0, 2, 1].
    let f = N as f64;
    let win = [[0.0, 0.0], [f, 0.0], [f, f], [0.0, f]];
    let bary = |p: [f64; 2], t: [usize; 3]| -> Option<[f64; 3]> {
        let [a, b, c] = t.map(|i| win[i]);
        let e = |u: [f64; 2], v: [f64; 2], q: [f64; 2]| {
            (v[0] - u[0]) * (q[1] - u[1]) - (v[1] - u[1]) * (q[0] - u[0])
        };
        let area = e(a, b, c);
        let l = [e(b, c, p) / area, e(c, a, p) / area, e(a, b, p) / area];
        l.iter().all(|&x| x >= 0.0).then_some(l)
    };
    let mut worst = [0i32; 3];
    for i in 0..4096u32 {
        let (x, y) = (i.wrapping_mul(2654435761) % N, (i * 40503 + 7) % N);
        let p = [x as f64 + 0.5, y as f64 + 0.5];
        let (tri, l) = match bary(p, [0, 3, 2]) {
            Some(l) => ([0, 3, 2], l),
            None => ([0, 2, 1], bary(p, [0, 2, 1]).expect("inside the quad")),
        };
        let c: [f64; 3] = [0, 1, 2].map(|ch| {
            (0..3)
                .map(|k| l[k] * colour[tri[k]][ch])
                .sum::<f64>()
                .clamp(0.0, 1.0)
        });
        let want = quantize_rgb565(c);
        let got = t.at(x, y);
        let ch = |v: u16| [(v >> 11) as i32, ((v >> 5) & 63) as i32, (v & 31) as i32];
        let (a, b) = (ch(want), ch(got));
        for ((w, x), y) in worst.iter_mut().zip(a).zip(b) {
            *w = (*w).max((x - y).abs());
        }
    }
    println!("4096 × 4096: sampled max error {worst:?} LSB");
    assert!(worst.iter().all(|&w| w <= 1), "{worst:?}");
}

/// A viewport wider than `i16` (40000 × 2), in perspective (an
/// orthographic view that wide cannot fit the ±128 eye-space range): a
/// quad past the whole view covers each of the 80 000 pixels once; a strip
/// at window x ≈ 32760…32780 (past 2¹⁵) covers a contiguous run of
/// columns within a pixel of where the kernel's own projection
/// coefficients put its edges, the same in both draw paths.
#[test]
fn viewport_wider_than_i16() {
    const W: u32 = 40000;
    let camera = Camera::look_at([0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0])
        .and_then(|c| c.with_projection(CamProjection::Perspective { fovy_deg: 90.0 }, 1e-3, 10.0))
        .unwrap();
    let p = camera.projection_for(W, 2).unwrap();
    let sx = p.sx as f64 / (1u64 << 24) as f64;
    let z = -1.0 / 128.0;
    // x_w = (sx·x_e/(−z_e) + 1)·W/2 with the kernel's sx.
    let xe = |xw: f64| (xw / (W as f64 / 2.0) - 1.0) * -z / sx;
    let quad = |x0: f64, x1: f64, z: f64| {
        common::quantised(&[
            Vec3::from_f64([x0, -0.1, z]).unwrap(),
            Vec3::from_f64([x1, -0.1, z]).unwrap(),
            Vec3::from_f64([x1, 0.1, z]).unwrap(),
            Vec3::from_f64([x0, 0.1, z]).unwrap(),
        ])
    };
    let idx = [[0u16, 1, 2], [0, 2, 3]];
    let normals = [PackedNormal::Z; 4];
    let m = Material::new();
    let sun = fixshade::light::DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    let r = Renderer::new(&camera, &m, &sun).with_shading(Flat);
    let mut cache = [CachedVertex::default(); 4];
    let (a, b) = (32760.25, 32779.75);
    for (pos, cols) in [
        // x_e/z_e = ±32512: past x_ndc = ±1.
        (quad(-127.0, 127.0, -1.0 / 256.0), 0..W),
        (quad(xe(a), xe(b), z), 32760..32780),
    ] {
        let mesh = Mesh::new(&pos.positions, pos.bounds, &idx).with_normals(&normals);
        let mut t = CountingTarget::new(W, 2);
        mesh.shaded(&r).with_cache(&mut cache).draw(&mut t).unwrap();
        assert_eq!(t.outside, 0);
        let drawn: Vec<u32> = (0..W)
            .filter(|&x| t.at(x, 0) != fuzz_scene::BACKGROUND)
            .collect();
        let (lo, hi) = (drawn[0], *drawn.last().unwrap());
        assert_eq!(drawn.len() as u32, hi - lo + 1, "not contiguous");
        assert!(
            lo.abs_diff(cols.start) <= 1 && hi.abs_diff(cols.end - 1) <= 1,
            "{lo}..={hi} for {cols:?}"
        );
        assert_eq!(
            t.writes,
            2 * drawn.len() as u64,
            "each pixel of both rows once"
        );
        let mut px = vec![fuzz_scene::BACKGROUND; (W * 2) as usize];
        let mut fb = Framebuffer::new(&mut px, W, 2).unwrap();
        mesh.shaded(&r)
            .with_cache(&mut cache)
            .draw(&mut fb)
            .unwrap();
        assert!(px == t.pixels, "{cols:?}: the two paths differ");
    }
}

/// Models that scale one axis far below the others (a sphere flattened to
/// a disc, face on and turned): drawn within the bound up to 1 000 times
/// flatter in every shading mode (the normals' matrix keeps the small
/// axis: taken from the entries rounded to the largest's precision, it
/// lost it, and the disc drew with zero normals, ambient alone), and
/// refused past about `MAX_ANISOTROPY` (at 10⁴, the normals' own steps,
/// turned that much, put Phong shading 2 LSB away from the reference when
/// it was drawn, before the limit: measured once, not repeated here).
#[test]
fn strongly_anisotropic_models() {
    let light = LightDesc::Directional {
        direction: [0.3, 0.4, 1.0],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
    };
    for k in [1e-2, 3e-3, 1e-3, 1e-4, 2f64.powi(-20), 1e-7] {
        for turn in [0.0, 0.7] {
            let (c, s) = (f64::cos(turn), f64::sin(turn));
            for shading in [Shading::Gouraud, Shading::Phong, Shading::Flat] {
                let mut sc = sphere(material(0.8, 0.5, 16.0), vec![light.clone()], 96, 72);
                sc.shading = shading;
                // Flattened along z, then turned about x.
                sc.model = [
                    [1.0, 0.0, 0.0, 0.0],
                    [0.0, c, -s * k, 0.0],
                    [0.0, s, c * k, 0.0],
                    [0.0, 0.0, 0.0, 1.0],
                ];
                let name = format!("z scaled by {k:e}, turned {turn}, {shading:?}");
                if k >= 1e-3 {
                    let e = check(&name, &sc);
                    println!("{name}: {e}");
                } else {
                    let kernel = KernelScene::new(&sc).unwrap_or_else(|e| panic!("{name}: {e}"));
                    let err = kernel.render_frame().expect_err(&name);
                    assert_eq!(err, RenderError::DegenerateModel, "{name}");
                    assert!(!err.to_string().contains('\n'));
                }
            }
        }
    }
}

//! The world's absolute formats (`I8F24`: steps of 2⁻²⁴ world units) at
//! any scale: a scene is drawn within the bound of SPEC.md 7 or refused
//! with [`RenderError::SceneTooSmall`], never drawn wrong.
//!
//! The sphere (with an off-centre model translation and eye, so that no
//! quantisation cancels by symmetry) is drawn at scales from 10⁻⁶ to 1,
//! once scaled by the model matrix and once by its own coordinates, on
//! three target sizes, in perspective and orthographic projection; the
//! scenes past the formats' range (far 200, a camera at (100, 100, 100),
//! a mesh of extent 10⁶, a model scaled by 10⁶) are refused as errors.
//!
//! `cargo test --release -p fixshade-host --test suite world_scale --
//! --nocapture` prints each case.

use fixshade::render::RenderError;
use fixshade_host::error_measure::compare;
use fixshade_host::generate;
use fixshade_host::reference;
use fixshade_host::scene_desc::{CameraDesc, Projection, SceneDesc};
use fixshade_host::scene_kernel::KernelScene;
use fixshade_host::standard_scenes::sphere_scene;

/// Draws `s` and holds it to the bound (`true`), or checks that it was
/// refused (`false`): at draw time as too small, or earlier by a format's
/// range (an orthographic view volume under 2/127 units high).
fn drawn(name: &str, s: &SceneDesc) -> bool {
    let k = match KernelScene::new(s) {
        Ok(k) => k,
        Err(e) => {
            println!("{name}: refused ({e})");
            assert!(!e.to_string().contains('\n'), "{name}");
            return false;
        }
    };
    match k.render_frame() {
        Ok(frame) => {
            let r = reference::render(k.reference_scene()).expect("reference");
            let e = compare(&frame.pixels, &frame.covered, &r);
            println!("{name}: {e}");
            assert!(frame.stats.pixels > 0, "{name}: nothing drawn");
            assert!(e.max_error.iter().all(|&m| m <= 1), "{name}: {e}");
            // What the check bounds is drift, about 1/512 px: an edge pixel
            // in a few hundred may change its coverage, one of a small
            // frame's, and 1 % of its pixels a small frame's handful. The
            // 0.1 % and the 99 % hold on frames of thousands of pixels.
            let mismatched = e.coverage_mismatch_share * e.covered_both as f64;
            assert!(
                e.coverage_mismatch_share <= 0.001 || mismatched <= 1.5,
                "{name}: {e}"
            );
            assert!(e.compared < 2000 || e.exact_share >= 0.99, "{name}: {e}");
            true
        }
        Err(e) => {
            assert_eq!(e, RenderError::SceneTooSmall, "{name}");
            println!("{name}: refused ({e})");
            false
        }
    }
}

fn scaled(w: u32, h: u32, s: f64, by_model: bool, ortho: bool) -> SceneDesc {
    shifted(w, h, s, by_model, ortho, 0.0)
}

/// [`scaled`] with the scene, camera and all, moved `t` along z: the
/// matrices' roundings grow with the distance from the world's origin.
fn shifted(w: u32, h: u32, s: f64, by_model: bool, ortho: bool, t: f64) -> SceneDesc {
    let mut sc = sphere_scene(w, h, 48, 24);
    let (radius, m) = if by_model { (1.0, s) } else { (s, 1.0) };
    sc.mesh = generate::sphere(48, 24, radius);
    sc.model = [
        [m, 0.0, 0.0, 0.17 * s],
        [0.0, m, 0.0, -0.11 * s],
        [0.0, 0.0, m, 0.05 * s + t],
        [0.0, 0.0, 0.0, 1.0],
    ];
    sc.camera.eye = [0.013 * s, 0.021 * s, 3.0 * s + t];
    sc.camera.target = [0.0, 0.0, t];
    sc.camera.near = 0.1 * s;
    sc.camera.far = 10.0 * s;
    if ortho {
        sc.camera.projection = Projection::Orthographic { height: 3.0 * s };
    }
    sc
}

#[test]
fn every_scale_is_drawn_within_the_bound_or_refused() {
    for (w, h) in [(64, 48), (320, 240), (1024, 768)] {
        for ortho in [false, true] {
            for t in [0.0, 30.0, 110.0] {
                let mut smallest_drawn = f64::INFINITY;
                for k in 0..=24 {
                    let s = 10f64.powf(-k as f64 / 4.0);
                    for by_model in [true, false] {
                        let name = format!(
                            "{w}x{h}, {}, scale {s:.1e} by the {}, {t} from the origin",
                            if ortho { "orthographic" } else { "perspective" },
                            if by_model { "model" } else { "mesh" }
                        );
                        if drawn(&name, &shifted(w, h, s, by_model, ortho, t)) {
                            smallest_drawn = smallest_drawn.min(s);
                        } else if t == 0.0 {
                            // At the origin, refused scenes are the small
                            // ones: every larger scale of the kind was drawn.
                            assert!(s < 0.1, "{name}: refused");
                        }
                    }
                }
                println!("{w}x{h} ortho {ortho} at {t}: drawn down to {smallest_drawn:.1e}");
                // At the origin, down to where the formats hold the bound:
                // a sphere of radius 1/10 fills a quarter of the height.
                let reach = if t == 0.0 { 0.1 } else { 1.0 };
                assert!(smallest_drawn <= reach, "{w}x{h} at {t}: {smallest_drawn}");
            }
        }
    }
}

/// Scenes past the formats' range are errors, not frames.
#[test]
fn scenes_past_the_range_are_refused() {
    let mut far = sphere_scene(64, 48, 24, 12);
    far.camera = CameraDesc {
        eye: [100.0, 100.0, 100.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 1.0,
        far: 200.0,
        projection: Projection::Perspective { fovy_deg: 60.0 },
    };
    let mut huge_mesh = sphere_scene(64, 48, 24, 12);
    huge_mesh.mesh = generate::sphere(24, 12, 1e6);
    huge_mesh.model = [
        [1e-6, 0.0, 0.0, 0.0],
        [0.0, 1e-6, 0.0, 0.0],
        [0.0, 0.0, 1e-6, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let mut huge_model = sphere_scene(64, 48, 24, 12);
    huge_model.mesh = generate::sphere(24, 12, 1e-6);
    huge_model.model = [
        [1e6, 0.0, 0.0, 0.0],
        [0.0, 1e6, 0.0, 0.0],
        [0.0, 0.0, 1e6, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    for (name, s) in [
        ("far 200, camera at (100, 100, 100)", far),
        ("mesh of extent 10⁶", huge_mesh),
        ("model scaled by 10⁶", huge_model),
    ] {
        let e = KernelScene::new(&s).err();
        println!("{name}: {e:?}");
        assert!(e.is_some(), "{name}: accepted");
        assert!(!e.unwrap().to_string().contains('\n'), "{name}");
    }
    // The tiny scene of the same kind is a draw-time error.
    let tiny = scaled(64, 48, 1e-6, true, false);
    let k = KernelScene::new(&tiny).expect("representable");
    assert_eq!(k.render_frame().err(), Some(RenderError::SceneTooSmall));
}

/// A rod 100 units long reaching from far to close before the eye: the
/// vertex rows, scaled to its reach, are coarse at its near end (before
/// the check's second term, such a rod was accepted and drawn with 1 % of
/// its coverage wrong). Refused, or within the bound.
#[test]
fn long_objects_reaching_the_eye_are_refused_or_within_the_bound() {
    let rod = |w: u32, h: u32, a: f64, len: f64, z0: f64, eye: [f64; 3], near: f64| {
        let mut sc = sphere_scene(w, h, 8, 4);
        sc.mesh = generate::cube(1.0);
        for p in &mut sc.mesh.positions {
            *p = [p[0] * a, p[1] * a, p[2] * len];
        }
        sc.mesh.normals = None;
        sc.model[2][3] = -(z0 + len / 2.0);
        sc.camera.eye = eye;
        sc.camera.target = [0.0, 0.0, -1.0];
        sc.camera.near = near;
        sc.camera.far = 127.0;
        sc
    };
    let mut drawn_any = false;
    for (w, h, a, len, z0, eye, near) in [
        (320, 240, 0.001, 100.0, 0.002, [3e-4, 2e-4, 0.0], 0.001),
        (1024, 768, 0.01, 100.0, 0.02, [0.003, 0.002, 0.0], 0.01),
        (1024, 768, 0.001, 1.0, 0.002, [1e-4, 7e-5, 0.0], 0.001),
        (320, 240, 0.1, 100.0, 0.2, [0.03, 0.02, 0.0], 0.1),
        (320, 240, 0.5, 20.0, 1.0, [0.13, 0.07, 0.0], 0.1),
    ] {
        let name = format!("{w}x{h}, rod {a} × {len} from {z0}");
        drawn_any |= drawn(&name, &rod(w, h, a, len, z0, eye, near));
    }
    assert!(drawn_any, "a rod of ordinary size is drawn");
}

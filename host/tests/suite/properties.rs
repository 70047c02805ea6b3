//! Property tests over random meshes, cameras and lights:
//!
//! 1. no panic (the tests run with overflow checks in debug) and no write
//!    outside the target (a counting `DrawTarget`, any origin), with the
//!    documented errors, over scenes decoded from random bytes by the fuzz
//!    target's decoder (`tests/common/fuzz_scene.rs`), which reaches raw
//!    and extreme values of every public field;
//! 2. the same over random well-formed scenes (descriptions → kernel);
//! 3. the error bound against the reference (≤ 1 LSB, coverage mismatches
//!    ≤ 0.1 %) over random scenes that avoid the equation's
//!    discontinuities: inputs where, at some vertex (or centroid), N·L, a
//!    spot's cone edge, R·V or N·H sits within 0.02 of its switch are
//!    skipped, and Phong shading (where those vary per pixel) is drawn
//!    without specular and with 90° spots, where the equation is
//!    continuous. No depth test (depth ties between nearly coplanar
//!    triangles are not what is measured here) and no near-plane crossing
//!    (tested in `tests/stiff_cases.rs`).
//!
//! `PROPTEST_CASES` overrides the modest default case counts.

use crate::common;
use crate::fuzz_scene;

use common::kernel_vs_reference;
use fixshade::render::CachedVertex;
use fixshade_host::reference::{eye_lights, look_at, orthographic, perspective, EyeLight};
use fixshade_host::scene_desc::{
    CameraDesc, LightDesc, MaterialDesc, MeshDesc, Projection, SceneDesc, Shading, SpecularModel,
    Viewer,
};
use fixshade_host::scene_kernel::KernelScene;
use fuzz_scene::CountingTarget;
use proptest::prelude::*;

fn config(default_cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default_cases);
    ProptestConfig {
        cases,
        max_global_rejects: cases * 20 + 1024,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

// ---------------------------------------------------------------------------
// Strategies
// ---------------------------------------------------------------------------

fn coord(lim: f64) -> impl Strategy<Value = [f64; 3]> {
    [-lim..lim, -lim..lim, -lim..lim]
}

fn direction() -> impl Strategy<Value = [f64; 3]> {
    coord(1.0).prop_filter("non-zero", |v| dot(*v, *v) > 1e-3)
}

fn colour(max: f64) -> impl Strategy<Value = [f64; 3]> {
    [0.0..max, 0.0..max, 0.0..max]
}

/// A few triangles (1 to 6) in a 2-unit box around the origin, with or
/// without normals.
fn mesh() -> impl Strategy<Value = MeshDesc> {
    (3usize..=8, any::<bool>()).prop_flat_map(|(n, with_normals)| {
        (
            prop::collection::vec(coord(1.0), n),
            prop::collection::vec(direction(), n),
            prop::collection::vec([0..n as u16, 0..n as u16, 0..n as u16], 1..=6),
        )
            .prop_map(move |(positions, normals, indices)| MeshDesc {
                positions,
                normals: with_normals.then(|| normals.iter().map(|v| normalized(*v)).collect()),
                indices,
            })
    })
}

/// A camera 2.5 to 5 units from the origin looking at it.
fn camera() -> impl Strategy<Value = CameraDesc> {
    (direction(), 2.5..5.0f64, any::<bool>(), 30.0..100.0f64).prop_map(|(d, r, persp, fov)| {
        let d = normalized(d);
        let up = if d[1].abs() > 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        CameraDesc {
            eye: d.map(|x| x * r),
            target: [0.0; 3],
            up,
            near: 0.5,
            far: 20.0,
            projection: if persp {
                Projection::Perspective { fovy_deg: fov }
            } else {
                Projection::Orthographic { height: fov / 20.0 }
            },
        }
    })
}

fn attenuation() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        Just([1.0, 0.0, 0.0]),
        [0.0..2.0, 0.0..1.0, 0.0..1.0f64],
        [1e-6..1e-3, 1e-6..1e-3, 1e-6..1e-3f64],
    ]
}

fn light(wide_spots: bool) -> impl Strategy<Value = LightDesc> {
    let cutoff = if wide_spots { 90.0..=90.0 } else { 5.0..=90.0 };
    prop_oneof![
        (direction(), colour(1.5), colour(1.5)).prop_map(|(d, i, s)| LightDesc::Directional {
            direction: d,
            diffuse: i,
            specular: s,
        }),
        (coord(6.0), colour(2.0), colour(2.0), attenuation()).prop_map(|(p, i, s, a)| {
            LightDesc::Point {
                position: p,
                diffuse: i,
                specular: s,
                attenuation: a,
            }
        }),
        (
            coord(6.0),
            direction(),
            cutoff,
            0.0..64.0f64,
            colour(2.0),
            attenuation()
        )
            .prop_map(|(p, axis, c, e, i, a)| LightDesc::Spot {
                position: p,
                axis,
                cutoff_deg: c,
                exponent: e,
                diffuse: i,
                specular: i,
                attenuation: a,
            }),
    ]
}

fn material(specular: bool) -> impl Strategy<Value = MaterialDesc> {
    let shininess = prop_oneof![Just(0.0), Just(1.0), 1.0..200.0f64, Just(2048.0)];
    (
        colour(0.3),
        colour(1.0),
        colour(1.0),
        colour(1.0),
        shininess,
    )
        .prop_map(move |(e, a, d, s, n)| MaterialDesc {
            emission: e,
            ambient: a,
            diffuse: d,
            specular: if specular { s } else { [0.0; 3] },
            shininess: n,
        })
}

/// A random scene for the bound. Phong shading gets no specular and only
/// 90° spots (continuous everywhere); flat and Gouraud get everything.
fn scene() -> impl Strategy<Value = SceneDesc> {
    (0u8..3).prop_flat_map(|shading| {
        let phong = shading == 2;
        (
            mesh(),
            camera(),
            material(!phong),
            prop::collection::vec(light(phong), 1..=4),
            colour(0.5),
            any::<bool>(),
            any::<bool>(),
            any::<bool>(),
            any::<bool>(),
        )
            .prop_map(
                move |(mesh, camera, material, lights, ambient, blinn, local, cull, two_sided)| {
                    let mut s = SceneDesc::new(48, 40, camera, mesh);
                    s.material = material;
                    s.lights = lights;
                    s.global_ambient = ambient;
                    s.shading = [Shading::Flat, Shading::Gouraud, Shading::Phong][shading as usize];
                    s.specular_model = if blinn {
                        SpecularModel::Blinn
                    } else {
                        SpecularModel::Phong
                    };
                    s.viewer = if local {
                        Viewer::Local
                    } else {
                        Viewer::Infinite
                    };
                    s.cull = cull;
                    s.two_sided = two_sided;
                    s.depth = false;
                    s
                },
            )
    })
}

// ---------------------------------------------------------------------------
// Discontinuities (SPEC.md 3)
// ---------------------------------------------------------------------------

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn normalized(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    if l > 0.0 {
        v.map(|x| x / l)
    } else {
        [0.0; 3]
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn mul(m: &[[f64; 4]; 4], p: [f64; 3], w: f64) -> [f64; 3] {
    [0, 1, 2].map(|r| m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3] * w)
}

/// Whether eye-space point `p` with unit normal `n` (either side) sits
/// within `EPS` of a switch of the equation for some light.
fn near_switch(s: &SceneDesc, lights: &[EyeLight], p: [f64; 3], n: [f64; 3]) -> bool {
    const EPS: f64 = 0.02;
    if dot(n, n) < 0.5 {
        return true; // a zero normal: only where the kernel's rounding differs
    }
    let specular = s.material.specular.iter().any(|&c| c > 0.0);
    let vs = match s.viewer {
        Viewer::Infinite => [0.0, 0.0, 1.0],
        Viewer::Local => normalized(p.map(|x| -x)),
    };
    for l in lights {
        let (to, spot) = match l {
            EyeLight::Directional { to_light, .. } => (*to_light, None),
            EyeLight::Point { position, .. } => (sub(*position, p), None),
            EyeLight::Spot {
                position,
                axis,
                cos_cutoff,
                ..
            } => (sub(*position, p), Some((*axis, *cos_cutoff))),
        };
        if dot(to, to).sqrt() < 0.05 {
            return true;
        }
        let l = normalized(to);
        if let Some((axis, cc)) = spot {
            if (-dot(l, axis) - cc).abs() < EPS {
                return true;
            }
        }
        for n in [n, n.map(|x| -x)] {
            let nl = dot(n, l);
            if specular && nl.abs() < EPS {
                return true;
            }
            if specular && nl > 0.0 {
                let r = [0, 1, 2].map(|i| 2.0 * nl * n[i] - l[i]);
                let h = [0, 1, 2].map(|i| l[i] + vs[i]);
                if dot(h, h) < EPS || dot(r, vs).abs() < EPS || dot(n, normalized(h)).abs() < EPS {
                    return true;
                }
            }
        }
    }
    false
}

/// Whether any vertex (Gouraud) or centroid (flat) of a drawn triangle is
/// near a switch, or a triangle is close to the near plane.
fn near_discontinuity(s: &SceneDesc) -> bool {
    let c = &s.camera;
    let view = look_at(c.eye, c.target, c.up);
    let lights = eye_lights(&s.lights, &view);
    let eye: Vec<[f64; 3]> = s
        .mesh
        .positions
        .iter()
        .map(|p| mul(&view, *p, 1.0))
        .collect();
    let normals: Vec<[f64; 3]> = match &s.mesh.normals {
        Some(ns) => ns.clone(),
        None => fixshade_host::reference::vertex_normals(&s.mesh),
    };
    // Derived vertex normals whose face normals (nearly) cancel are
    // undefined (SPEC.md 4 normalises their sum): the kernel gives the zero
    // vector where the sum is 0, the reference the direction of its
    // rounding noise.
    if s.mesh.normals.is_none() {
        let mut sums = vec![[0.0; 3]; s.mesh.positions.len()];
        for t in &s.mesh.indices {
            let [a, b, d] = t.map(|i| s.mesh.positions[i as usize]);
            let f = normalized(cross(sub(b, a), sub(d, a)));
            for &i in t {
                sums[i as usize] = [0, 1, 2].map(|k| sums[i as usize][k] + f[k]);
            }
        }
        let used = s.mesh.indices.iter().flatten();
        if used
            .into_iter()
            .any(|&i| dot(sums[i as usize], sums[i as usize]) < 0.01)
        {
            return true;
        }
    }
    let eye_n: Vec<[f64; 3]> = normals
        .iter()
        .map(|n| normalized(mul(&view, *n, 0.0)))
        .collect();
    // Snapping to 1/16 pixel is a discontinuity too: a vertex whose window
    // position is within 1 % of a step from a rounding boundary may snap
    // one way in f64 and the other in fixed point, moving a pixel.
    let aspect = s.width as f64 / s.height as f64;
    let proj = match c.projection {
        Projection::Perspective { fovy_deg } => perspective(fovy_deg, aspect, c.near, c.far),
        Projection::Orthographic { height } => orthographic(height, aspect, c.near, c.far),
    };
    let near_step = |v: f64| {
        let f = (v * 16.0 + 0.5).rem_euclid(1.0);
        !(0.01..=0.99).contains(&f)
    };
    for t in &s.mesh.indices {
        let [a, b, d] = t.map(|i| i as usize);
        if [a, b, d].iter().any(|&i| -eye[i][2] < c.near + 0.05) {
            return true;
        }
        for &i in &[a, b, d] {
            let clip = mul(&proj, eye[i], 1.0);
            let w = [0, 1, 2, 3]
                .iter()
                .map(|&k| proj[3][k] * [eye[i][0], eye[i][1], eye[i][2], 1.0][k])
                .sum::<f64>();
            let xw = (clip[0] / w + 1.0) * s.width as f64 / 2.0;
            let yw = (1.0 - clip[1] / w) * s.height as f64 / 2.0;
            if near_step(xw) || near_step(yw) {
                return true;
            }
        }
        match s.shading {
            Shading::Flat => {
                let n = normalized(cross(sub(eye[b], eye[a]), sub(eye[d], eye[a])));
                let cen = [0, 1, 2].map(|k| (eye[a][k] + eye[b][k] + eye[d][k]) / 3.0);
                // A sliver's face normal is ill-conditioned: skip those.
                let area = dot(cross(sub(eye[b], eye[a]), sub(eye[d], eye[a])), [1.0; 3]).abs();
                if area < 1e-3 || near_switch(s, &lights, cen, n) {
                    return true;
                }
            }
            _ => {
                if [a, b, d]
                    .iter()
                    .any(|&i| near_switch(s, &lights, eye[i], eye_n[i]))
                {
                    return true;
                }
            }
        }
    }
    false
}

// ---------------------------------------------------------------------------
// Properties
// ---------------------------------------------------------------------------

proptest! {
    #![proptest_config(config(512))]

    /// Scenes from arbitrary bytes: no panic, nothing outside, the
    /// documented errors, both draw paths agree (`fuzz_scene::check`).
    #[test]
    fn arbitrary_bytes_no_panic_nothing_outside(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        fuzz_scene::run(&bytes);
    }
}

proptest! {
    #![proptest_config(config(128))]

    /// Random well-formed scenes, with depth test and near-plane crossings
    /// allowed, through a counting target at a random origin.
    #[test]
    fn random_scenes_nothing_outside(
        s in scene(),
        depth in any::<bool>(),
        ox in -70000i32..70000,
        oy in -70000i32..70000,
        size in (0u32..70, 0u32..70),
    ) {
        let mut s = s;
        s.depth = depth;
        s.width = size.0;
        s.height = size.1;
        let k = match KernelScene::new(&s) {
            Ok(k) => k,
            Err(_) => return Ok(()), // e.g. a position the format cannot hold
        };
        let mut t = CountingTarget::with_origin(
            embedded_graphics::geometry::Point::new(ox, oy), s.width, s.height);
        let mut d = vec![0u16; (s.width * s.height) as usize];
        let mut cache = vec![CachedVertex::default(); s.mesh.positions.len()];
        let res = k.render(&mut t, &mut d, &mut cache);
        prop_assert_eq!(t.outside, 0);
        if let Ok(stats) = res {
            prop_assert_eq!(stats.pixels as u64, t.writes);
        }
    }

    /// Random scenes away from the equation's discontinuities: within the
    /// bound of SPEC.md 7.
    #[test]
    fn random_scenes_within_the_bound(s in scene()) {
        // The discontinuities of the mesh the kernel draws (quantised).
        let converted = KernelScene::new(&s);
        prop_assume!(converted.is_ok());
        prop_assume!(!near_discontinuity(converted.unwrap().reference_scene()));
        let (e, _) = kernel_vs_reference(&s);
        prop_assume!(e.covered_both > 0);
        prop_assert!(e.max_error.iter().all(|&m| m <= 1), "{}", e);
        prop_assert!(e.coverage_mismatch_share <= 0.001, "{}", e);
    }
}

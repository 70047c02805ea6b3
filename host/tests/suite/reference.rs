//! Tests of the f64 reference: illumination, rasterization, generators, OBJ
//! loading and the error measure.

use fixshade_host::error_measure::{compare, compare_checked};
use fixshade_host::generate::{cube, load_obj, plane, sphere, torus, ObjErrorKind};
use fixshade_host::reference::{
    eye_lights, illuminate, look_at, quantize_depth, quantize_rgb565, render, vertex_normals,
    EyeLight, LightingModel, RefFrame,
};
use fixshade_host::scene_desc::{
    CameraDesc, LightDesc, MaterialDesc, MeshDesc, Projection, SceneDesc, SceneError, Shading,
    SpecularModel, Viewer,
};
use proptest::prelude::*;

const EPS: f64 = 1e-12;

fn close(a: [f64; 3], b: [f64; 3], eps: f64) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= eps)
}

fn material() -> MaterialDesc {
    MaterialDesc {
        emission: [0.05, 0.0, 0.1],
        ambient: [0.3, 0.2, 0.1],
        diffuse: [0.4, 0.5, 0.2],
        specular: [0.2, 0.1, 0.3],
        shininess: 8.0,
    }
}

fn model<'a>(mat: &'a MaterialDesc, lights: &'a [EyeLight]) -> LightingModel<'a> {
    LightingModel {
        material: mat,
        global_ambient: [0.2, 0.4, 0.6],
        lights,
        specular_model: SpecularModel::Blinn,
        viewer: Viewer::Infinite,
    }
}

/// `E + A·Ka` of [`material`] under [`model`]'s ambient.
fn base(mat: &MaterialDesc) -> [f64; 3] {
    let a = [0.2, 0.4, 0.6];
    std::array::from_fn(|c| mat.emission[c] + a[c] * mat.ambient[c])
}

fn point(position: [f64; 3], attenuation: [f64; 3]) -> EyeLight {
    EyeLight::Point {
        position,
        diffuse: [1.0; 3],
        specular: [0.0; 3],
        attenuation,
    }
}

// ---------------------------------------------------------------- lighting

#[test]
fn directional_along_normal_gives_full_sum() {
    let mat = material();
    let id = [0.5, 0.6, 0.7];
    let is = [0.3, 0.2, 0.1];
    let lights = [EyeLight::Directional {
        to_light: [0.0, 0.0, 1.0],
        diffuse: id,
        specular: is,
    }];
    let b = base(&mat);
    let expected: [f64; 3] =
        std::array::from_fn(|c| b[c] + id[c] * mat.diffuse[c] + is[c] * mat.specular[c]);
    for spec in [SpecularModel::Blinn, SpecularModel::Phong] {
        for viewer in [Viewer::Infinite, Viewer::Local] {
            let m = LightingModel {
                specular_model: spec,
                viewer,
                ..model(&mat, &lights)
            };
            // p on the −Z axis so the local viewer also gives V = (0, 0, 1).
            let c = illuminate(&m, [0.0, 0.0, -3.0], [0.0, 0.0, 2.0]);
            assert!(close(c, expected, EPS), "{spec:?} {viewer:?}: {c:?}");
        }
    }
}

#[test]
fn result_is_clamped() {
    let mat = material();
    let lights = [EyeLight::Directional {
        to_light: [0.0, 0.0, 1.0],
        diffuse: [10.0; 3],
        specular: [10.0; 3],
    }];
    let c = illuminate(&model(&mat, &lights), [0.0; 3], [0.0, 0.0, 1.0]);
    assert_eq!(c, [1.0; 3]);
}

#[test]
fn light_behind_surface_gives_emission_and_ambient_only() {
    let mat = material();
    let lights = [
        EyeLight::Directional {
            to_light: [0.0, 0.0, -1.0],
            diffuse: [1.0; 3],
            specular: [1.0; 3],
        },
        EyeLight::Directional {
            to_light: [1.0, 0.0, 0.0], // grazing: N·L = 0
            diffuse: [1.0; 3],
            specular: [1.0; 3],
        },
    ];
    let c = illuminate(&model(&mat, &lights), [0.0, 0.0, -1.0], [0.0, 0.0, 1.0]);
    assert!(close(c, base(&mat), EPS), "{c:?}");
}

#[test]
fn zero_normal_gives_emission_and_ambient_only() {
    let mat = material();
    let lights = [EyeLight::Directional {
        to_light: [0.0, 0.0, 1.0],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
    }];
    let c = illuminate(&model(&mat, &lights), [0.0, 0.0, -1.0], [0.0; 3]);
    assert!(close(c, base(&mat), EPS));
}

#[test]
fn attenuation_values() {
    let mat = material();
    let b = base(&mat);
    let p = [0.0, 0.0, -2.0];
    let n = [0.0, 0.0, 1.0];
    // Light 2 units along the normal.
    let light_at = [0.0, 0.0, 0.0];
    let diffuse_with = |f: f64| -> [f64; 3] { std::array::from_fn(|c| b[c] + f * mat.diffuse[c]) };
    let cases = [
        ([1.0, 1.0, 0.5], 1.0 / 5.0), // den = 1 + 2 + 2
        ([0.0, 0.0, 1.0], 1.0 / 4.0), // den = d²
        ([0.5, 0.0, 0.0], 1.0),       // den < 1 → f = 1
        ([0.0, 0.0, 0.0], 1.0),       // den = 0 → f = 1
        ([1.0, 0.0, 0.0], 1.0),
    ];
    for (att, f) in cases {
        let lights = [point(light_at, att)];
        let c = illuminate(&model(&mat, &lights), p, n);
        assert!(close(c, diffuse_with(f), EPS), "{att:?}: {c:?}");
    }
    // The light sits on the point: no contribution.
    let lights = [point(p, [1.0, 0.0, 0.0])];
    assert!(close(illuminate(&model(&mat, &lights), p, n), b, EPS));
}

#[test]
fn spot_cutoff_inside_and_outside() {
    let mat = MaterialDesc {
        specular: [0.0; 3],
        ..material()
    };
    let b = base(&mat);
    // Spot 1 unit above the origin shining straight down (−Z in eye space);
    // the point sits 30° off its axis.
    let p = [30f64.to_radians().tan(), 0.0, -1.0];
    let n = [0.0, 0.0, 1.0];
    let l = {
        let d = [-p[0], 0.0, 1.0];
        let len = (d[0] * d[0] + 1.0f64).sqrt();
        [d[0] / len, 0.0, 1.0 / len]
    };
    let spot = |cutoff: f64, exponent: f64| EyeLight::Spot {
        position: [0.0, 0.0, 0.0],
        axis: [0.0, 0.0, -1.0],
        cos_cutoff: cutoff.to_radians().cos(),
        exponent,
        diffuse: [1.0; 3],
        specular: [1.0; 3],
        attenuation: [1.0, 0.0, 0.0],
    };
    // Outside a 20° cone.
    let lights = [spot(20.0, 1.0)];
    assert!(close(illuminate(&model(&mat, &lights), p, n), b, EPS));
    // Inside a 40° cone: s = cos(30°)^p, N·L = l.z.
    for exponent in [0.0, 1.0, 4.0] {
        let lights = [spot(40.0, exponent)];
        let s = 30f64.to_radians().cos().powf(exponent);
        let expected: [f64; 3] = std::array::from_fn(|c| b[c] + s * mat.diffuse[c] * l[2]);
        let c = illuminate(&model(&mat, &lights), p, n);
        assert!(close(c, expected, 1e-12), "p = {exponent}: {c:?}");
    }
}

#[test]
fn area_light_with_one_sample_equals_point_light() {
    let mat = material();
    let view = look_at([1.0, 2.0, 5.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let center = [0.3, 2.0, 1.0];
    let att = [1.0, 0.1, 0.02];
    let area = LightDesc::Area {
        center,
        edge_u: [1.0, 0.0, 0.0],
        edge_v: [0.0, 0.0, 1.0],
        samples_k: 1,
        diffuse: [0.9, 0.8, 0.7],
        specular: [0.5, 0.6, 0.4],
        attenuation: att,
    };
    let pt = LightDesc::Point {
        position: center,
        diffuse: [0.9, 0.8, 0.7],
        specular: [0.5, 0.6, 0.4],
        attenuation: att,
    };
    let a = eye_lights(&[area], &view);
    let b = eye_lights(&[pt], &view);
    assert_eq!(a, b);
    let c1 = illuminate(&model(&mat, &a), [0.1, 0.2, -4.0], [0.2, 0.6, 0.7]);
    let c2 = illuminate(&model(&mat, &b), [0.1, 0.2, -4.0], [0.2, 0.6, 0.7]);
    assert_eq!(c1, c2);
    assert!(c1 != base(&mat));
}

#[test]
fn area_light_samples_are_cell_centres() {
    let identity = fixshade_host::scene_desc::IDENTITY;
    let area = LightDesc::Area {
        center: [0.0, 5.0, 0.0],
        edge_u: [2.0, 0.0, 0.0],
        edge_v: [0.0, 0.0, 4.0],
        samples_k: 2,
        diffuse: [1.0; 3],
        specular: [0.8; 3],
        attenuation: [1.0, 0.0, 0.0],
    };
    let lights = eye_lights(&[area], &identity);
    assert_eq!(lights.len(), 4);
    let mut positions: Vec<[f64; 3]> = lights
        .iter()
        .map(|l| match l {
            EyeLight::Point {
                position,
                diffuse,
                specular,
                ..
            } => {
                assert_eq!(*diffuse, [0.25; 3]);
                assert_eq!(*specular, [0.2; 3]);
                *position
            }
            other => panic!("expected a point light, got {other:?}"),
        })
        .collect();
    positions.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(
        positions,
        vec![
            [-0.5, 5.0, -1.0],
            [-0.5, 5.0, 1.0],
            [0.5, 5.0, -1.0],
            [0.5, 5.0, 1.0]
        ]
    );
}

#[test]
fn power_zero_is_one_even_for_zero_base() {
    // N = +X, L = +X → R = +X, V = +Z: R·V = 0, and 0^0 = 1.
    let mat = MaterialDesc {
        emission: [0.0; 3],
        ambient: [0.0; 3],
        diffuse: [0.0; 3],
        specular: [0.5; 3],
        shininess: 0.0,
    };
    let lights = [EyeLight::Directional {
        to_light: [1.0, 0.0, 0.0],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
    }];
    let m = LightingModel {
        material: &mat,
        global_ambient: [0.0; 3],
        lights: &lights,
        specular_model: SpecularModel::Phong,
        viewer: Viewer::Infinite,
    };
    assert_eq!(illuminate(&m, [0.0; 3], [1.0, 0.0, 0.0]), [0.5; 3]);
    // With shininess 1 the same geometry gives no specular.
    let mat1 = MaterialDesc {
        shininess: 1.0,
        ..mat.clone()
    };
    let m1 = LightingModel {
        material: &mat1,
        ..m.clone()
    };
    assert_eq!(illuminate(&m1, [0.0; 3], [1.0, 0.0, 0.0]), [0.0; 3]);
}

#[test]
fn phong_and_blinn_by_hand() {
    // N = +Z, L at 60° from N in the XZ plane, V = +Z, n = 2.
    // Phong: R·V = cos 60° → 0.25. Blinn: N·H = cos 30° → 0.75.
    let mat = MaterialDesc {
        emission: [0.0; 3],
        ambient: [0.0; 3],
        diffuse: [0.0; 3],
        specular: [1.0; 3],
        shininess: 2.0,
    };
    let t = 60f64.to_radians();
    let lights = [EyeLight::Directional {
        to_light: [t.sin(), 0.0, t.cos()],
        diffuse: [0.0; 3],
        specular: [1.0; 3],
    }];
    let mut m = LightingModel {
        material: &mat,
        global_ambient: [0.0; 3],
        lights: &lights,
        specular_model: SpecularModel::Phong,
        viewer: Viewer::Infinite,
    };
    let n = [0.0, 0.0, 1.0];
    assert!(close(illuminate(&m, [0.0; 3], n), [0.25; 3], 1e-12));
    m.specular_model = SpecularModel::Blinn;
    assert!(close(illuminate(&m, [0.0; 3], n), [0.75; 3], 1e-12));
    // Local viewer at P = 0: V undefined → no specular.
    m.viewer = Viewer::Local;
    assert_eq!(illuminate(&m, [0.0; 3], n), [0.0; 3]);
}

#[test]
fn eye_lights_rotate_directions_and_move_positions() {
    // Camera on +X looking at the origin: world +X is eye +Z.
    let view = look_at([5.0, 0.0, 0.0], [0.0; 3], [0.0, 1.0, 0.0]);
    let lights = eye_lights(
        &[
            LightDesc::directional([3.0, 0.0, 0.0]),
            LightDesc::point([5.0, 1.0, 0.0]),
        ],
        &view,
    );
    match &lights[0] {
        EyeLight::Directional { to_light, .. } => {
            assert!(close(*to_light, [0.0, 0.0, 1.0], EPS))
        }
        other => panic!("{other:?}"),
    }
    match &lights[1] {
        EyeLight::Point { position, .. } => assert!(close(*position, [0.0, 1.0, 0.0], EPS)),
        other => panic!("{other:?}"),
    }
}

// ------------------------------------------------------------- rasterizer

/// A `size × size` frame with an orthographic camera mapping object
/// `(x, y, 0)` to window `(x + size/2, size/2 − y)`: one unit per pixel.
fn ortho_scene(size: u32, mesh: MeshDesc) -> SceneDesc {
    let camera = CameraDesc {
        eye: [0.0, 0.0, 1.0],
        target: [0.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
        near: 0.5,
        far: 4.0,
        projection: Projection::Orthographic {
            height: f64::from(size),
        },
    };
    let mut scene = SceneDesc::new(size, size, camera, mesh);
    scene.lights.push(LightDesc::directional([0.0, 0.0, 1.0]));
    scene
}

/// A mesh from window-space positions of an [`ortho_scene`] of `size`.
fn window_mesh(size: u32, tris: &[[(f64, f64); 3]]) -> MeshDesc {
    let h = f64::from(size) / 2.0;
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for tri in tris {
        let base = positions.len() as u16;
        for &(x, y) in tri {
            positions.push([x - h, h - y, 0.0]);
        }
        indices.push([base, base + 1, base + 2]);
    }
    MeshDesc {
        positions,
        normals: None,
        indices,
    }
}

fn coverage(frame: &RefFrame) -> Vec<bool> {
    frame.color.iter().map(Option::is_some).collect()
}

#[test]
fn single_triangle_covers_hand_computed_pixels() {
    // Object (−6.3, −5.2), (4.1, −5.2), (−6.3, 3.7) on a 16 × 16 frame snap to
    // (27, 211), (194, 211), (27, 69) in 1/16 px: a right triangle, CCW in NDC.
    // Covered samples (16x+8, 16y+8): X > 27, Y < 211 and
    // 142(X − 27) + 167(211 − Y) < 23714 (no sample lies on an edge): 41.
    let mesh = MeshDesc {
        positions: vec![[-6.3, -5.2, 0.0], [4.1, -5.2, 0.0], [-6.3, 3.7, 0.0]],
        normals: None,
        indices: vec![[0, 1, 2]],
    };
    let frame = render(&ortho_scene(16, mesh)).unwrap();
    let mut expected = 0;
    for y in 0..16i64 {
        for x in 0..16i64 {
            let (sx, sy) = (16 * x + 8, 16 * y + 8);
            let inside = sx > 27 && sy < 211 && 142 * (sx - 27) + 167 * (211 - sy) < 23714;
            expected += i32::from(inside);
            assert_eq!(
                frame.pixel(x as u32, y as u32).is_some(),
                inside,
                "pixel ({x}, {y})"
            );
        }
    }
    assert_eq!(expected, 41);
    assert_eq!(frame.covered_count(), 41);
    // Default material, white light along the normal: 0.2·0.2 + 0.8.
    for c in frame.color.iter().flatten() {
        assert!(close(*c, [0.84; 3], 1e-9), "{c:?}");
    }
}

/// Renders each triangle alone and checks that no pixel is covered twice and
/// that the union covers exactly `expected` (if given).
fn check_shared_edge(size: u32, a: [(f64, f64); 3], b: [(f64, f64); 3], expected: Option<&[bool]>) {
    let mut sa = ortho_scene(size, window_mesh(size, &[a]));
    let mut sb = ortho_scene(size, window_mesh(size, &[b]));
    sa.cull = false;
    sb.cull = false;
    let fa = coverage(&render(&sa).unwrap());
    let fb = coverage(&render(&sb).unwrap());
    for (i, (x, y)) in fa.iter().zip(&fb).enumerate() {
        assert!(!(*x && *y), "pixel {i} covered twice");
        if let Some(e) = expected {
            assert_eq!(*x || *y, e[i], "pixel {i}");
        }
    }
}

/// Pixels whose sample lies in the half-open window rectangle
/// `[x0, x1) × [y0, y1)` (the top-left rule for an axis-aligned rectangle).
fn rect_coverage(size: u32, x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<bool> {
    let mut out = Vec::new();
    for y in 0..size {
        for x in 0..size {
            let (sx, sy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            out.push(sx >= x0 && sx < x1 && sy >= y0 && sy < y1);
        }
    }
    out
}

#[test]
fn quad_split_along_diagonal_covers_each_pixel_once() {
    let size = 24;
    // Edges through sample centres (the hardest case for the tie rule), and
    // at awkward sub-pixel offsets (multiples of 1/16 so snapping is exact).
    for (x0, y0, x1, y1) in [
        (2.5, 3.5, 11.5, 12.5),
        (1.5, 1.5, 22.5, 9.5),
        (2.3125, 3.6875, 19.8125, 21.0625),
        (0.0625, 5.4375, 23.9375, 6.5625),
    ] {
        let expected = rect_coverage(size, x0, y0, x1, y1);
        let (tl, tr, br, bl) = ((x0, y0), (x1, y0), (x1, y1), (x0, y1));
        // Both diagonals, both orientations.
        check_shared_edge(size, [bl, br, tl], [tl, br, tr], Some(&expected));
        check_shared_edge(size, [tl, bl, tr], [tr, bl, br], Some(&expected));
        check_shared_edge(size, [bl, tl, br], [tl, tr, br], Some(&expected));
        // Rendered as one mesh, the union is the same.
        let mut scene = ortho_scene(size, window_mesh(size, &[[bl, br, tl], [tl, br, tr]]));
        scene.cull = false;
        assert_eq!(coverage(&render(&scene).unwrap()), expected);
    }
}

#[test]
fn fan_around_a_sample_point_covers_it_once() {
    // Six triangles meeting at a pixel centre: that pixel is drawn exactly once.
    let size = 16;
    let c = (8.5, 8.5);
    let ring = [
        (8.5, 2.5),
        (13.5, 5.5),
        (13.5, 11.5),
        (8.5, 14.5),
        (3.5, 11.5),
        (3.5, 5.5),
    ];
    let mut counts = vec![0u32; (size * size) as usize];
    for k in 0..6 {
        let tri = [c, ring[(k + 1) % 6], ring[k]];
        let mut scene = ortho_scene(size, window_mesh(size, &[tri]));
        scene.cull = false;
        for (n, cov) in counts.iter_mut().zip(coverage(&render(&scene).unwrap())) {
            *n += u32::from(cov);
        }
    }
    assert_eq!(counts[8 * 16 + 8], 1);
    assert!(counts.iter().all(|&n| n <= 1));
}

#[test]
fn backface_culling_drops_clockwise_triangle() {
    let size = 16;
    let ccw_ndc = [(2.0, 14.0), (14.0, 14.0), (2.0, 2.0)]; // CCW in NDC (y up)
    let cw_ndc = [(2.0, 14.0), (2.0, 2.0), (14.0, 14.0)];
    let front = render(&ortho_scene(size, window_mesh(size, &[ccw_ndc]))).unwrap();
    let back = render(&ortho_scene(size, window_mesh(size, &[cw_ndc]))).unwrap();
    assert!(front.covered_count() > 50);
    assert_eq!(back.covered_count(), 0);
    let mut no_cull = ortho_scene(size, window_mesh(size, &[cw_ndc]));
    no_cull.cull = false;
    assert_eq!(
        render(&no_cull).unwrap().covered_count(),
        front.covered_count()
    );
}

#[test]
fn two_sided_lighting_lights_back_faces() {
    let size = 16;
    // A clockwise (back-facing) triangle; its computed normal points away
    // from the camera and the light.
    let mesh = window_mesh(size, &[[(2.0, 14.0), (2.0, 2.0), (14.0, 14.0)]]);
    let mut scene = ortho_scene(size, mesh);
    scene.cull = false;
    for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
        scene.shading = shading;
        scene.two_sided = false;
        let one = render(&scene).unwrap();
        scene.two_sided = true;
        let two = render(&scene).unwrap();
        assert_eq!(one.covered_count(), two.covered_count());
        for (a, b) in one.color.iter().flatten().zip(two.color.iter().flatten()) {
            assert!(close(*a, [0.04; 3], 1e-9), "{shading:?} one-sided: {a:?}");
            assert!(close(*b, [0.84; 3], 1e-9), "{shading:?} two-sided: {b:?}");
        }
    }
}

#[test]
fn shading_modes_agree_on_a_lit_plane() {
    let camera = CameraDesc {
        eye: [0.0, 0.0, 3.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 0.5,
        far: 10.0,
        projection: Projection::Perspective { fovy_deg: 50.0 },
    };
    let mut scene = SceneDesc::new(32, 24, camera, plane(2.0, 4));
    scene.lights.push(LightDesc::directional([0.0, 0.0, 1.0]));
    let mut counts = Vec::new();
    for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
        scene.shading = shading;
        let frame = render(&scene).unwrap();
        counts.push(frame.covered_count());
        for c in frame.color.iter().flatten() {
            assert!(close(*c, [0.84; 3], 1e-9), "{shading:?}: {c:?}");
        }
    }
    assert!(counts[0] > 100);
    assert!(counts.iter().all(|&n| n == counts[0]));
}

#[test]
fn depth_test_keeps_nearest() {
    let size = 16;
    let h = 8.0;
    // Two overlapping squares, far (z = −1) and near (z = +0.3).
    let quad = |z: f64| {
        vec![
            [-h, -h, z],
            [h, -h, z],
            [h, h, z],
            [-h, -h, z],
            [h, h, z],
            [-h, h, z],
        ]
    };
    for near_first in [false, true] {
        let mut positions = quad(-1.0);
        positions.extend(quad(0.3));
        if near_first {
            positions.rotate_left(6);
        }
        let mesh = MeshDesc {
            positions,
            normals: None,
            indices: (0..4).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
        };
        let mut scene = ortho_scene(size, mesh);
        scene.shading = Shading::Phong;
        // Colour by depth through a point light between the planes, right
        // above the sample point of pixel (8, 8) at object (0.5, −0.5).
        scene.lights = vec![LightDesc::Point {
            position: [0.5, -0.5, 0.4],
            diffuse: [1.0; 3],
            specular: [0.0; 3],
            attenuation: [0.0, 0.0, 1.0],
        }];
        scene.global_ambient = [0.0; 3];
        let frame = render(&scene).unwrap();
        // The centre pixel sees the near plane: d ≈ 0.1 → f = 1, diffuse 0.8;
        // the far plane would give d = 1.4, f ≈ 0.51, diffuse ≈ 0.41.
        let c = frame.pixel(8, 8).unwrap();
        assert!(c[0] > 0.7, "near_first = {near_first}: {c:?}");
        scene.depth = false;
        let frame = render(&scene).unwrap();
        let c = frame.pixel(8, 8).unwrap();
        // Without depth test the last drawn wins.
        assert_eq!(
            c[0] > 0.7,
            !near_first,
            "no depth, near_first = {near_first}"
        );
    }
}

/// Depth ties (SPEC.md 7): where a surface's quantised depth comes within
/// 1 of the depth stored by another, whichever wins, the pixel is flagged;
/// a surface that wins by 2 or more clears the flag; without the depth
/// test nothing is flagged.
#[test]
fn depth_ties_are_flagged() {
    let size = 8u32;
    // In `ortho_scene`, z_w = (0.5 − z)/3.5: d = ⌊z_w·65535 + ½⌋ is 9362 at
    // z = 0 (9362.14) and moves by one per 3.5/65535 of z.
    let step = 3.5 / 65535.0;
    assert_eq!(quantize_depth(0.5 / 3.5), 9362);
    let h = f64::from(size);
    // Squares covering the view, `k` depth steps behind z = 0.
    let scene = |ks: &[f64], depth: bool| {
        let mut positions = Vec::new();
        for &k in ks {
            let z = -k * step;
            positions.extend([
                [-h, -h, z],
                [h, -h, z],
                [h, h, z],
                [-h, -h, z],
                [h, h, z],
                [-h, h, z],
            ]);
        }
        let n = positions.len() as u16 / 3;
        let mesh = MeshDesc {
            positions,
            normals: None,
            indices: (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
        };
        let mut s = ortho_scene(size, mesh);
        s.depth = depth;
        s
    };
    let cases: [(&[f64], bool); 7] = [
        (&[0.0, 0.0], true),        // equal: the second loses by 0
        (&[0.0, 1.0], true),        // the second loses by 1
        (&[1.0, 0.0], true),        // the second wins by 1
        (&[0.0, 2.0], false),       // loses by 2
        (&[2.0, 0.0], false),       // wins by 2
        (&[0.0, 1.0, -2.0], false), // a tie, then a win by 2 over both
        (&[0.0, 1.0, 3.0], true),   // a tie, then a clear loss
    ];
    for (ks, tie) in cases {
        let frame = render(&scene(ks, true)).unwrap();
        assert_eq!(frame.covered_count(), (size * size) as usize, "{ks:?}");
        assert!(
            frame.tie.iter().all(|&t| t == tie),
            "{ks:?}: tie {tie} expected"
        );
        assert!(frame.step.iter().all(|&t| !t), "{ks:?}");
        let frame = render(&scene(ks, false)).unwrap();
        assert!(frame.tie.iter().all(|&t| !t), "{ks:?} without depth test");
    }
}

#[test]
fn triangle_crossing_near_plane_renders_without_nan() {
    let camera = CameraDesc {
        eye: [0.0, 0.0, 5.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 1.0,
        far: 20.0,
        projection: Projection::Perspective { fovy_deg: 60.0 },
    };
    // A floor triangle from in front of the camera to behind it, plus one
    // with a vertex exactly at the eye.
    let mesh = MeshDesc {
        positions: vec![
            [-3.0, -1.0, 0.0],
            [3.0, -1.0, 0.0],
            [0.0, -1.0, 12.0],
            [-1.0, 0.5, -2.0],
            [1.0, 0.5, -2.0],
            [0.0, 0.0, 5.0],
        ],
        normals: None,
        indices: vec![[0, 2, 1], [0, 1, 2], [3, 4, 5], [3, 5, 4]],
    };
    let mut scene = SceneDesc::new(40, 30, camera, mesh);
    scene.lights.push(LightDesc::point([0.0, 2.0, 2.0]));
    scene.cull = false;
    for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
        for viewer in [Viewer::Local, Viewer::Infinite] {
            scene.shading = shading;
            scene.viewer = viewer;
            let frame = render(&scene).unwrap();
            assert!(frame.covered_count() > 100, "{shading:?}");
            for c in frame.color.iter().flatten() {
                assert!(c.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x)));
            }
        }
    }
}

#[test]
fn fully_behind_near_plane_draws_nothing() {
    let camera = CameraDesc {
        eye: [0.0, 0.0, 5.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 1.0,
        far: 20.0,
        projection: Projection::Perspective { fovy_deg: 60.0 },
    };
    let mesh = MeshDesc {
        positions: vec![[-1.0, -1.0, 4.5], [1.0, -1.0, 4.5], [0.0, 1.0, 4.5]],
        normals: None,
        indices: vec![[0, 1, 2]],
    };
    let mut scene = SceneDesc::new(16, 16, camera, mesh);
    scene.cull = false;
    assert_eq!(render(&scene).unwrap().covered_count(), 0);
}

#[test]
fn sphere_covers_expected_disc() {
    let (d, fovy, size) = (4.0f64, 40.0f64, 64u32);
    let camera = CameraDesc {
        eye: [0.0, 0.0, d],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 0.5,
        far: 10.0,
        projection: Projection::Perspective { fovy_deg: fovy },
    };
    let mut scene = SceneDesc::new(size, size, camera, sphere(48, 24, 1.0));
    scene.lights.push(LightDesc::directional([1.0, 1.0, 1.0]));
    let frame = render(&scene).unwrap();
    // Silhouette: angular radius asin(r/d), projected radius in pixels.
    let radius_px =
        (1.0 / d).asin().tan() / (fovy.to_radians() / 2.0).tan() * f64::from(size) / 2.0;
    let expected = std::f64::consts::PI * radius_px * radius_px;
    let got = frame.covered_count() as f64;
    assert!(
        (got - expected).abs() / expected < 0.03,
        "covered {got}, expected about {expected}"
    );
    // Culling changes nothing when the depth test is on.
    scene.cull = false;
    assert_eq!(render(&scene).unwrap().covered_count() as f64, got);
    // The lit side is brighter than the unlit side.
    let lit = frame.pixel(42, 22).unwrap();
    let unlit = frame.pixel(22, 42).unwrap();
    assert!(lit[0] > unlit[0] + 0.3, "{lit:?} vs {unlit:?}");
}

#[test]
fn empty_and_invalid_scenes() {
    let camera = CameraDesc {
        eye: [0.0, 0.0, 3.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 0.5,
        far: 10.0,
        projection: Projection::Perspective { fovy_deg: 50.0 },
    };
    let scene = SceneDesc::new(0, 0, camera.clone(), cube(1.0));
    let frame = render(&scene).unwrap();
    assert_eq!((frame.width, frame.height, frame.color.len()), (0, 0, 0));
    assert_eq!(
        render(&SceneDesc::new(0, 7, camera.clone(), cube(1.0)))
            .unwrap()
            .color
            .len(),
        0
    );

    let ok = SceneDesc::new(8, 8, camera.clone(), cube(1.0));
    let expect_err = |s: SceneDesc, field: &str| {
        let e = render(&s).unwrap_err();
        assert!(e.to_string().contains(field), "{e} should name {field}");
        e
    };
    expect_err(SceneDesc::new(9000, 8, camera.clone(), cube(1.0)), "width");

    let mut s = ok.clone();
    s.mesh.indices.push([0, 1, 24]);
    let e = expect_err(s, "mesh.indices[12]");
    assert!(matches!(e, SceneError::IndexOutOfRange { index: 24, .. }));

    let mut s = ok.clone();
    s.mesh.positions[3][1] = f64::NAN;
    expect_err(s, "mesh.positions[3]");

    let mut s = ok.clone();
    s.camera.far = 0.4;
    expect_err(s, "camera.far");

    let mut s = ok.clone();
    s.camera.target = s.camera.eye;
    expect_err(s, "camera.target");

    let mut s = ok.clone();
    s.material.shininess = -1.0;
    expect_err(s, "material.shininess");

    let mut s = ok.clone();
    s.model[0][0] = 0.0;
    s.model[0][1] = 0.0;
    s.model[0][2] = 0.0;
    expect_err(s, "model");

    let mut s = ok.clone();
    s.lights.push(LightDesc::point([0.0; 3]));
    s.lights.push(LightDesc::Spot {
        position: [0.0; 3],
        axis: [0.0, -1.0, 0.0],
        cutoff_deg: 95.0,
        exponent: 1.0,
        diffuse: [1.0; 3],
        specular: [1.0; 3],
        attenuation: [1.0, 0.0, 0.0],
    });
    expect_err(s, "lights[1].cutoff_deg");

    let mut s = ok.clone();
    s.lights.push(LightDesc::Area {
        center: [0.0; 3],
        edge_u: [1.0, 0.0, 0.0],
        edge_v: [0.0, 1.0, 0.0],
        samples_k: 0,
        diffuse: [1.0; 3],
        specular: [1.0; 3],
        attenuation: [1.0, 0.0, 0.0],
    });
    expect_err(s, "lights[0].samples_k");

    let mut s = ok.clone();
    s.mesh.normals = Some(vec![[0.0, 0.0, 1.0]]);
    expect_err(s, "mesh.normals");

    assert!(ok.validate().is_ok());
}

#[test]
fn quantize_rounds_halves_up() {
    assert_eq!(quantize_rgb565([0.0; 3]), 0);
    assert_eq!(quantize_rgb565([1.0; 3]), 0xFFFF);
    // 0.5·31 = 15.5 → 16; 0.5·63 = 31.5 → 32.
    assert_eq!(quantize_rgb565([0.5; 3]), (16 << 11) | (32 << 5) | 16);
    assert_eq!(quantize_rgb565([2.0, -1.0, f64::NAN]), 0xF800);
}

#[test]
fn vertex_normals_of_a_flat_quad_and_a_cube() {
    let mut quad = plane(1.0, 3);
    quad.normals = None;
    assert!(vertex_normals(&quad)
        .iter()
        .all(|n| close(*n, [0.0, 0.0, 1.0], EPS)));
    // Cube corners shared by three faces: normal along the diagonal.
    let mut c = cube(2.0);
    c.normals = None;
    let s = 1.0 / 3f64.sqrt();
    for (p, n) in c.positions.iter().zip(vertex_normals(&c)) {
        // Each of the 24 vertices belongs to one face only (two triangles or one).
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-12);
        assert!(n.iter().zip(p).all(|(a, b)| a * b >= 0.0), "{p:?} {n:?}");
    }
    let shared = MeshDesc {
        positions: vec![
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 0.0],
        ],
        normals: None,
        indices: vec![[0, 1, 2], [0, 3, 1], [0, 2, 3]],
    };
    assert!(close(vertex_normals(&shared)[0], [s; 3], 1e-12));
}

// -------------------------------------------------------------- generators

/// Every triangle's geometric normal agrees with its vertex normals (so the
/// winding is counter-clockwise seen from outside), and normals are unit.
fn check_outward(mesh: &MeshDesc) {
    let normals = mesh.normals.as_ref().expect("generators give normals");
    assert_eq!(normals.len(), mesh.positions.len());
    for n in normals {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-12);
    }
    for tri in &mesh.indices {
        let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
        let e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let f = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let area = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        assert!(area > 1e-12, "degenerate triangle {tri:?}");
        for &i in tri {
            let n = normals[i as usize];
            assert!(
                f[0] * n[0] + f[1] * n[1] + f[2] * n[2] > 0.0,
                "triangle {tri:?} winds against its normals"
            );
        }
    }
}

#[test]
fn generators_wind_outwards() {
    let s = sphere(48, 24, 1.5);
    assert_eq!(s.indices.len(), 48 * (2 * 24 - 2));
    check_outward(&s);
    for p in &s.positions {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((r - 1.5).abs() < 1e-12);
    }
    let c = cube(2.0);
    assert_eq!((c.positions.len(), c.indices.len()), (24, 12));
    check_outward(&c);
    assert!(c.positions.iter().flatten().all(|x| x.abs() == 1.0));
    let t = torus(1.0, 0.3, 24, 12);
    assert_eq!(t.indices.len(), 2 * 24 * 12);
    check_outward(&t);
    let p = plane(3.0, 5);
    assert_eq!((p.positions.len(), p.indices.len()), (36, 50));
    check_outward(&p);
    // Degenerate parameters are clamped, not panicking.
    check_outward(&sphere(0, 0, 1.0));
    check_outward(&torus(1.0, 0.5, 0, 1));
    assert_eq!(plane(1.0, 0).indices.len(), 2);
}

#[test]
fn generated_meshes_render_as_solids() {
    // Culling on vs off with the depth test: same coverage for closed meshes.
    let camera = CameraDesc {
        eye: [1.0, 2.0, 4.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        near: 0.5,
        far: 10.0,
        projection: Projection::Perspective { fovy_deg: 45.0 },
    };
    for mesh in [cube(1.5), torus(1.0, 0.35, 32, 16), sphere(24, 12, 1.0)] {
        let mut scene = SceneDesc::new(48, 48, camera.clone(), mesh);
        scene.lights.push(LightDesc::point([2.0, 3.0, 3.0]));
        let culled = render(&scene).unwrap();
        scene.cull = false;
        let unculled = render(&scene).unwrap();
        assert!(culled.covered_count() > 200);
        assert_eq!(coverage(&culled), coverage(&unculled));
    }
}

// -------------------------------------------------------------------- OBJ

#[test]
fn bunny_parses() {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/bunny.obj"))
            .unwrap();
    let mesh = load_obj(&text).unwrap();
    assert_eq!(mesh.positions.len(), 1839);
    assert_eq!(mesh.indices.len(), 3674);
    assert!(mesh.normals.is_none());
    assert_eq!(mesh.positions[0], [1.301895, 0.122622, 2.550061]);
    // The bunny renders.
    let camera = CameraDesc {
        eye: [0.0, 3.0, 12.0],
        target: [0.0, 3.0, 0.0],
        up: [0.0, 1.0, 0.0],
        near: 1.0,
        far: 30.0,
        projection: Projection::Perspective { fovy_deg: 50.0 },
    };
    let mut scene = SceneDesc::new(64, 64, camera, mesh);
    scene.lights.push(LightDesc::directional([0.0, 1.0, 1.0]));
    assert!(render(&scene).unwrap().covered_count() > 300);
}

#[test]
fn obj_face_formats_and_normals() {
    let text = "\
# a quad with normals, two formats
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vn 0 0 1
vn 0 0 -1
f 1//1 2//1 3//1 4//1
f -4/1/2 -2/1/2 -3/1/2
";
    let m = load_obj(text).unwrap();
    assert_eq!(m.indices.len(), 3);
    // Vertices 1..4 with normal 1, and 1, 3, 2 with normal 2: 7 unique pairs.
    assert_eq!(m.positions.len(), 7);
    let normals = m.normals.unwrap();
    assert_eq!(m.indices[0], [0, 1, 2]);
    assert_eq!(m.indices[1], [0, 2, 3]);
    let last = m.indices[2];
    assert_eq!(m.positions[last[0] as usize], [0.0, 0.0, 0.0]);
    assert_eq!(m.positions[last[1] as usize], [1.0, 1.0, 0.0]);
    assert_eq!(m.positions[last[2] as usize], [1.0, 0.0, 0.0]);
    assert!(last
        .iter()
        .all(|&i| normals[i as usize] == [0.0, 0.0, -1.0]));

    // Mixed: one face without normals → no normals at all.
    let m = load_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n").unwrap();
    assert!(m.normals.is_none());
    assert_eq!(m.positions.len(), 3);
    assert_eq!(m.indices, vec![[0, 1, 2], [0, 1, 2]]);
}

#[test]
fn obj_errors_name_the_line() {
    let cases: [(&str, usize); 8] = [
        ("v 0 0\n", 1),
        ("v 0 0 0\nv 1 zero 0\n", 2),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", 5),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", 4),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", 4),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n# ok\nf 1/x 2 3\n", 5),
    ];
    for (text, line) in cases {
        let e = load_obj(text).unwrap_err();
        assert_eq!(e.line, line, "{text:?}: {e}");
        assert!(e.to_string().starts_with(&format!("line {line}:")));
    }
    let e = load_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n").unwrap_err();
    assert_eq!(
        e.kind,
        ObjErrorKind::IndexOutOfRange {
            what: "position",
            index: 7,
            count: 3
        }
    );
    assert!(matches!(
        load_obj("v 1 inf 0").unwrap_err().kind,
        ObjErrorKind::BadNumber(_)
    ));
}

// ---------------------------------------------------------- error measure

fn sample_frame() -> RefFrame {
    RefFrame::new(
        3,
        2,
        vec![
            Some([0.1, 0.2, 0.3]),
            Some([1.0, 0.5, 0.0]),
            None,
            Some([0.7, 0.7, 0.7]),
            None,
            Some([0.0, 0.0, 1.0]),
        ],
    )
}

#[test]
fn identical_frames_are_exact() {
    let r = sample_frame();
    let pixels = r.to_rgb565([0.0; 3]);
    let covered = coverage(&r);
    let s = compare(&pixels, &covered, &r);
    assert_eq!(s.covered_both, 4);
    assert_eq!((s.only_kernel, s.only_reference), (0, 0));
    assert_eq!(s.max_error, [0; 3]);
    assert_eq!(s.mean_error, 0.0);
    assert_eq!(s.exact_share, 1.0);
    assert_eq!(s.coverage_mismatch_share, 0.0);
    assert!(s.is_exact());
}

#[test]
fn one_lsb_change_is_counted() {
    let r = sample_frame();
    let mut pixels = r.to_rgb565([0.0; 3]);
    let covered = coverage(&r);
    // Green of pixel 3 up by one LSB (0.7·63 = 44.1 → 44, so 45 is in range).
    pixels[3] += 1 << 5;
    let s = compare(&pixels, &covered, &r);
    assert_eq!(s.max_error, [0, 1, 0]);
    assert!((s.mean_error - 1.0 / 12.0).abs() < 1e-15);
    assert_eq!(s.exact_share, 0.75);
    assert!(!s.is_exact());
    let line = s.to_string();
    assert!(line.contains("0/1/0") && line.contains("75.00 %"), "{line}");
}

#[test]
fn coverage_mismatches_and_lengths() {
    let r = sample_frame();
    let pixels = r.to_rgb565([0.0; 3]);
    let mut covered = coverage(&r);
    covered[0] = false; // reference only
    covered[2] = true; // kernel only
    let s = compare(&pixels, &covered, &r);
    assert_eq!((s.covered_both, s.only_kernel, s.only_reference), (3, 1, 1));
    assert!((s.coverage_mismatch_share - 2.0 / 5.0).abs() < 1e-15);
    // Length mismatch: common prefix, no panic; the checked form refuses.
    let s = compare(&pixels[..2], &covered, &r);
    assert_eq!(s.covered_both, 1);
    assert!(compare_checked(&pixels[..2], &covered, &r).is_err());
    assert!(compare_checked(&pixels, &covered, &r).is_ok());
    let empty = compare(&[], &[], &r);
    assert_eq!((empty.covered_both, empty.exact_share), (0, 1.0));
}

// -------------------------------------------------------------- proptests

fn colour() -> impl Strategy<Value = [f64; 3]> {
    [0.0..=1.0f64, 0.0..=1.0f64, 0.0..=1.0f64]
}

fn vec3(r: f64) -> impl Strategy<Value = [f64; 3]> {
    [-r..=r, -r..=r, -r..=r]
}

proptest! {
    // About half of the shared-edge cases are rejected (both side vertices
    // on one side of the diagonal), so allow many rejects.
    #![proptest_config(ProptestConfig { max_global_rejects: 1 << 20, ..ProptestConfig::with_cases(200) })]

    #[test]
    fn illuminate_stays_in_unit_range(
        e in colour(), ka in colour(), kd in colour(), ks in colour(),
        shininess in 0.0..200.0f64,
        p in vec3(5.0), n in vec3(1.0), lp in vec3(5.0), dir in vec3(1.0),
        exponent in 0.0..50.0f64, cutoff in 0.0..=90.0f64,
        phong in any::<bool>(), local in any::<bool>(),
    ) {
        let mat = MaterialDesc { emission: e, ambient: ka, diffuse: kd, specular: ks, shininess };
        let lights = eye_lights(&[
            LightDesc::point(lp),
            LightDesc::directional(dir),
            LightDesc::Spot {
                position: lp, axis: dir, cutoff_deg: cutoff, exponent,
                diffuse: [2.0; 3], specular: [1.0; 3], attenuation: [0.5, 0.1, 0.01],
            },
        ], &fixshade_host::scene_desc::IDENTITY);
        let m = LightingModel {
            material: &mat,
            global_ambient: [0.2; 3],
            lights: &lights,
            specular_model: if phong { SpecularModel::Phong } else { SpecularModel::Blinn },
            viewer: if local { Viewer::Local } else { Viewer::Infinite },
        };
        let c = illuminate(&m, p, n);
        prop_assert!(c.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x)), "{:?}", c);
    }

    /// Two triangles sharing an edge (the other vertices on opposite sides)
    /// never draw the same pixel.
    #[test]
    fn shared_edge_never_double_covers(
        a in (0.0..24.0f64, 0.0..24.0f64),
        c in (0.0..24.0f64, 0.0..24.0f64),
        b in (-4.0..28.0f64, -4.0..28.0f64),
        d in (-4.0..28.0f64, -4.0..28.0f64),
    ) {
        // Opposite sides of the diagonal after snapping to 1/16 pixel (the
        // coverage rule's grid); before snapping is not enough: a vertex
        // near the diagonal can snap across it, and then the two triangles
        // really overlap.
        let snap = |p: (f64, f64)| ((p.0 * 16.0 + 0.5).floor(), (p.1 * 16.0 + 0.5).floor());
        let (sa, sc) = (snap(a), snap(c));
        let side = |p: (f64, f64)| {
            let p = snap(p);
            (sc.0 - sa.0) * (p.1 - sa.1) - (sc.1 - sa.1) * (p.0 - sa.0)
        };
        prop_assume!(side(b) * side(d) < 0.0);
        check_shared_edge(24, [a, b, c], [a, c, d], None);
    }

    #[test]
    fn random_scenes_render_in_range(
        positions in prop::collection::vec(vec3(3.0), 3..12),
        raw in prop::collection::vec([0u16..12, 0u16..12, 0u16..12], 1..12),
        eye in vec3(6.0),
        shading in 0usize..3,
        two_sided in any::<bool>(),
        ortho in any::<bool>(),
    ) {
        let n = positions.len() as u16;
        let indices = raw.into_iter().map(|t| t.map(|i| i % n)).collect();
        let camera = CameraDesc {
            eye,
            target: [0.0; 3],
            up: [0.0, 1.0, 0.0],
            near: 0.3,
            far: 20.0,
            projection: if ortho {
                Projection::Orthographic { height: 6.0 }
            } else {
                Projection::Perspective { fovy_deg: 70.0 }
            },
        };
        let mut scene = SceneDesc::new(24, 16, camera, MeshDesc { positions, normals: None, indices });
        scene.shading = [Shading::Flat, Shading::Gouraud, Shading::Phong][shading];
        scene.two_sided = two_sided;
        scene.cull = false;
        scene.lights.push(LightDesc::point([1.0, 4.0, 2.0]));
        match render(&scene) {
            Ok(frame) => {
                prop_assert_eq!(frame.color.len(), 24 * 16);
                for c in frame.color.iter().flatten() {
                    prop_assert!(c.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x)));
                }
            }
            // A degenerate camera (eye at the target, up parallel) is rejected.
            Err(e) => prop_assert!(matches!(e, SceneError::Degenerate { .. }), "{}", e),
        }
    }
}

/// An OBJ file whose (position, normal) pairs make more than 65 536
/// vertices is refused at the face that makes one too many, with its line.
#[test]
fn obj_too_many_vertices_names_the_face() {
    let mut text = String::new();
    for i in 0..65536 {
        text.push_str(&format!("v {i} 0 0\n"));
    }
    text.push_str("vn 0 0 1\nvn 0 1 0\n");
    // Faces of three new positions with the first normal (65 535 pairs),
    // then again with the second: the first such face makes pairs 65 536
    // and 65 537, one too many.
    let mut line = 65538;
    let mut failing = None;
    for normal in 1..=2 {
        for first in (1..=65534).step_by(3) {
            line += 1;
            let f = |k: usize| format!("{}//{normal}", first + k);
            text.push_str(&format!("f {} {} {}\n", f(0), f(1), f(2)));
            if normal == 2 && failing.is_none() {
                failing = Some(line);
            }
        }
    }
    let e = load_obj(&text).unwrap_err();
    assert_eq!(e.kind, ObjErrorKind::TooManyVertices);
    assert_eq!(e.line, failing.unwrap(), "{e}");
}

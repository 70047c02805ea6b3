//! Scenes and comparison helpers shared by the integration tests.
#![allow(dead_code)]

use fixshade::Vec3;
use fixshade_host::error_measure::{compare, ErrorStats};
use fixshade_host::mesh_convert::MeshData;
use fixshade_host::reference::{self, quantize_rgb565, RefFrame};
use fixshade_host::scene_desc::{MeshDesc, Projection, SceneDesc};
use fixshade_host::scene_kernel::{KernelFrame, KernelScene};

/// Positions through the host converter, as a kernel mesh's quantised
/// positions and box (no triangles: the caller brings its own).
pub fn quantised(points: &[Vec3]) -> MeshData {
    let desc = MeshDesc {
        positions: points
            .iter()
            .map(|p| p.to_bits().map(|b| b as f64 / (1u64 << 24) as f64))
            .collect(),
        normals: None,
        indices: Vec::new(),
    };
    MeshData::from_desc(&desc).expect("I8F24 positions convert")
}

/// Renders `scene` with the kernel and the reference and compares them;
/// the reference renders the mesh the kernel draws (the converted one,
/// dequantised: `KernelScene::reference_scene`).
pub fn kernel_vs_reference(scene: &SceneDesc) -> (ErrorStats, KernelFrame) {
    scene.validate().expect("valid scene");
    let kernel = KernelScene::new(scene).expect("kernel scene");
    let k = kernel.render_frame().expect("kernel render");
    let r = reference::render(kernel.reference_scene()).expect("reference render");
    (compare(&k.pixels, &k.covered, &r), k)
}

/// Pixels whose centre lies within 1/16 pixel of a fold on screen: an edge
/// shared by two triangles that face opposite ways there (the surface
/// turns over at a silhouette, and the two overlap). Snapping moves each
/// corner up to 1/32 pixel on each axis (an edge up to √2/32 ≈ 0.044
/// pixel), so at such a pixel the kernel may find the pixel inside one of
/// the two where the reference finds it inside the other: a coverage
/// difference between two triangles that both cover the pixel's
/// neighbourhood, which the colour comparison would count as a colour
/// error. (The reference projection, in `f64`; corners behind the near
/// plane are skipped.)
pub fn fold_pixels(scene: &SceneDesc) -> Vec<bool> {
    use std::collections::HashMap;
    let (w, h) = (scene.width as usize, scene.height as usize);
    let c = &scene.camera;
    let view = reference::look_at(c.eye, c.target, c.up);
    let aspect = w as f64 / h as f64;
    let proj = match c.projection {
        Projection::Perspective { fovy_deg } => {
            reference::perspective(fovy_deg, aspect, c.near, c.far)
        }
        Projection::Orthographic { height } => {
            reference::orthographic(height, aspect, c.near, c.far)
        }
    };
    let mul = |m: &[[f64; 4]; 4], p: [f64; 4]| {
        [0, 1, 2, 3].map(|r| (0..4).map(|k| m[r][k] * p[k]).sum::<f64>())
    };
    let win: Vec<Option<[f64; 2]>> = scene
        .mesh
        .positions
        .iter()
        .map(|p| {
            let world = mul(&scene.model, [p[0], p[1], p[2], 1.0]);
            let clip = mul(&proj, mul(&view, world));
            (clip[3] > 0.0).then(|| {
                [
                    (clip[0] / clip[3] + 1.0) * w as f64 / 2.0,
                    (1.0 - clip[1] / clip[3]) * h as f64 / 2.0,
                ]
            })
        })
        .collect();
    let mut facing: HashMap<(u16, u16), Vec<f64>> = HashMap::new();
    for t in &scene.mesh.indices {
        let Some(v) = t
            .iter()
            .map(|&i| win[i as usize])
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let area =
            (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0]);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            facing.entry((a.min(b), a.max(b))).or_default().push(area);
        }
    }
    let mut mask = vec![false; w * h];
    for ((a, b), areas) in facing {
        let turns = areas.iter().any(|&x| x > 0.0) && areas.iter().any(|&x| x < 0.0);
        let (Some(p), Some(q)) = (win[a as usize], win[b as usize]) else {
            continue;
        };
        if !turns {
            continue;
        }
        let d = [q[0] - p[0], q[1] - p[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let r = 1.0 / 16.0;
        let x0 = (p[0].min(q[0]) - 1.0).floor().max(0.0) as usize;
        let x1 = ((p[0].max(q[0]) + 1.0).ceil().max(0.0) as usize).min(w);
        let y0 = (p[1].min(q[1]) - 1.0).floor().max(0.0) as usize;
        let y1 = ((p[1].max(q[1]) + 1.0).ceil().max(0.0) as usize).min(h);
        for y in y0..y1 {
            for x in x0..x1 {
                let c = [x as f64 + 0.5 - p[0], y as f64 + 0.5 - p[1]];
                let t = if len2 > 0.0 {
                    ((c[0] * d[0] + c[1] * d[1]) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let e = [c[0] - t * d[0], c[1] - t * d[1]];
                if e[0] * e[0] + e[1] * e[1] <= r * r {
                    mask[y * w + x] = true;
                }
            }
        }
    }
    mask
}

/// [`kernel_vs_reference`] leaving out the [`fold_pixels`] (both sides'
/// coverage there too); returns how many pixels were left out.
pub fn kernel_vs_reference_away_from_folds(scene: &SceneDesc) -> (ErrorStats, usize) {
    scene.validate().expect("valid scene");
    let kernel = KernelScene::new(scene).expect("kernel scene");
    let mut k = kernel.render_frame().expect("kernel render");
    let mut r = reference::render(kernel.reference_scene()).expect("reference render");
    let mask = fold_pixels(kernel.reference_scene());
    for (i, _) in mask.iter().enumerate().filter(|(_, &m)| m) {
        k.covered[i] = false;
        r.color[i] = None;
    }
    let left_out = mask.iter().filter(|&&m| m).count();
    (compare(&k.pixels, &k.covered, &r), left_out)
}

/// The bound of SPEC.md 7: at most 1 LSB per channel on the pixels both
/// cover, depth ties and model steps counted apart (and printed, with the
/// rest of the measure, here and in every failure message), coverage
/// mismatches at most 0.1 % of covered pixels. Some pixel must be held to
/// the bound: a scene whose pixels were all set apart would pass vacuously.
pub fn assert_within_bound(name: &str, e: &ErrorStats) {
    println!("{name}: {e}");
    assert!(e.covered_both > 0, "{name}: nothing covered");
    assert!(e.compared > 0, "{name}: every pixel a tie or a step: {e}");
    assert!(
        e.max_error.iter().all(|&m| m <= 1),
        "{name}: max error {:?} LSB: {e}",
        e.max_error
    );
    assert!(
        e.coverage_mismatch_share <= 0.001,
        "{name}: coverage mismatches {:.4} %: {e}",
        100.0 * e.coverage_mismatch_share
    );
}

/// What setting flagged pixels apart hides: over the pixels both sides
/// cover where `flag` is set (the reference's `tie` or `step`), how many
/// are more than 1 LSB off in some channel, and the largest error.
pub fn flagged_error(k: &KernelFrame, r: &RefFrame, flag: &[bool]) -> (usize, u32) {
    let channels = |c: u16| {
        [
            u32::from(c >> 11),
            u32::from((c >> 5) & 0x3F),
            u32::from(c & 0x1F),
        ]
    };
    let (mut over, mut worst) = (0, 0);
    for (i, &f) in flag.iter().enumerate() {
        let (Some(c), true, true) = (r.color[i], k.covered[i], f) else {
            continue;
        };
        let (a, b) = (channels(k.pixels[i]), channels(quantize_rgb565(c)));
        let e = (0..3).map(|ch| a[ch].abs_diff(b[ch])).max().unwrap_or(0);
        over += usize::from(e > 1);
        worst = worst.max(e);
    }
    (over, worst)
}

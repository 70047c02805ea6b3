//! Transforms, clipping and rasterization of the reference (SPEC.md sections
//! 1, 4, 5 and 6), in `f64` with exact integer coverage tests.
//!
//! The pipeline of [`render`], which the kernel mirrors step by step:
//!
//! 1. `MV = view · model`; eye position `P_e = MV·p`; eye normal = inverse
//!    transpose of MV's 3 × 3 part applied to the object normal (the mesh's,
//!    else [`vertex_normals`]), normalised; `clip = Proj·P_e`;
//!    `aspect = width / height`.
//! 2. Gouraud: per-vertex colour [`illuminate`]d with the eye normal (front)
//!    and, if two-sided lighting is on, with its negation (back).
//! 3. Near-plane clipping in clip space with `d = z_c + w_c` (inside iff
//!    `d ≥ 0`): Sutherland–Hodgman over `v0→v1, v1→v2, v2→v0`, intersection
//!    `a + t(b − a)`, `t = d_a/(d_a − d_b)`, every attribute (clip and eye
//!    positions, eye normal, both Gouraud colours) interpolated linearly in
//!    `t`; the 3- or 4-gon is fanned `(p0,p1,p2), (p0,p2,p3)`.
//! 4. Window: `x_w = (x_c/w_c + 1)·W/2`, `y_w = (1 − y_c/w_c)·H/2`,
//!    `z_w = (z_c/w_c + 1)/2`; snapped to `X = floor(16·x_w + ½)`,
//!    `Y = floor(16·y_w + ½)` (clamped to ±2⁶⁰ so that the integer arithmetic
//!    cannot overflow).
//! 5. Edge function `E_ab(p) = (b.x−a.x)(p.y−a.y) − (b.y−a.y)(p.x−a.x)`;
//!    `Area2 = E_{v0v1}(v2)`; zero draws nothing. Front faces are
//!    counter-clockwise in NDC (SPEC.md section 5); window `y` points down,
//!    so with this `E` a front face has **`Area2 < 0`** and a back face
//!    `Area2 > 0`. Back faces are dropped when culling is on. A triangle
//!    with `Area2 < 0` is then made positive by swapping `v1` and `v2` (and
//!    their attributes); coverage and barycentrics below always use the
//!    positively oriented order.
//! 6. Pixel `(x, y)` (sample `(16x+8, 16y+8)`) is inside iff each edge has
//!    `E > 0`, or `E = 0` on a top-left edge (`dy = 0 ∧ dx > 0` or `dy < 0`).
//! 7. Affine barycentrics `λ0 = E_{v1v2}/Area2`, `λ1 = E_{v2v0}/Area2`,
//!    `λ2 = E_{v0v1}/Area2`; depth `z = Σλ_i z_i`, quantised to
//!    `d = ⌊z·65535 + ½⌋` ([`quantize_depth`]) and drawn iff `d <` the
//!    stored `u16` (cleared to 65535) when the depth test is on.
//! 8. Colour: flat (once per original triangle at the centroid of its eye
//!    positions with its unit eye-space face normal), Gouraud (`Σλ_i c_i`) or
//!    Phong (`illuminate(Σλ_i P_i, Σλ_i n_i)`); on a back face with two-sided
//!    lighting the back colours / negated normals are used.
//! 9. Flags for the error measure (SPEC.md 7), per pixel: a depth tie
//!    where the drawn surface's `d` came within 1 of another surface's
//!    ([`RefFrame::tie`]), and a model step where the drawn colour was
//!    evaluated within [`STEP_MARGIN`] of a step of the model
//!    ([`RefFrame::step`], [`illuminate_with_margin`]).
//!
//! [`illuminate`]: super::illuminate
//! [`illuminate_with_margin`]: super::illuminate_with_margin

use super::lighting::{eye_lights, illuminate_with_margin, LightingModel};
use super::math::{
    add, cross, length, mat_mul, mul3, normal_matrix, normalize, scale, sub, transform4,
    transform_point, V3,
};
use crate::scene_desc::{MeshDesc, Projection, SceneDesc, SceneError, Shading};
use std::borrow::Cow;

/// Snapped window coordinates are clamped to this magnitude (1/16 px units).
const SNAP_LIMIT: f64 = (1u64 << 60) as f64;

/// How close to a step of the model (a spot's cone edge, a specular
/// cut-off) a pixel's colour may be evaluated before the pixel is flagged
/// as a model step (SPEC.md 7): 2⁻¹², in `cosγ` or `N·L`.
///
/// ```
/// use fixshade_host::reference::STEP_MARGIN;
/// assert_eq!(STEP_MARGIN, 1.0 / 4096.0);
/// ```
pub const STEP_MARGIN: f64 = 1.0 / 4096.0;

/// The depth a pixel is tested and stored with (SPEC.md 5): `z_w`
/// quantised to 16 bits, `d = ⌊z_w · 65535 + ½⌋`, clamped to 0 ..= 65535
/// (NaN gives 65535, which never passes a test against the cleared value).
///
/// ```
/// use fixshade_host::reference::quantize_depth;
/// assert_eq!(quantize_depth(0.0), 0);
/// assert_eq!(quantize_depth(0.5), 32768); // 32767.5, the half rounded up
/// assert_eq!(quantize_depth(1.0), 65535);
/// assert_eq!((quantize_depth(-0.1), quantize_depth(2.0)), (0, 65535));
/// assert_eq!(quantize_depth(f64::NAN), 65535);
/// ```
pub fn quantize_depth(z_w: f64) -> u16 {
    let d = (z_w * 65535.0 + 0.5).floor();
    if d.is_nan() {
        u16::MAX
    } else {
        d.clamp(0.0, 65535.0) as u16
    }
}

/// A rendered reference frame: one entry per pixel, row-major (top row
/// first); `None` where nothing was drawn. Colours are clamped to [0, 1] and
/// not quantised (see [`quantize_rgb565`]). Beside each colour, the flags
/// that SPEC.md 7 counts apart: a depth tie and a model step.
///
/// ```
/// use fixshade_host::reference::RefFrame;
/// let f = RefFrame::new(2, 1, vec![None, Some([1.0, 0.0, 0.0])]);
/// assert_eq!(f.pixel(1, 0), Some([1.0, 0.0, 0.0]));
/// assert_eq!(f.covered_count(), 1);
/// assert_eq!((f.tie, f.step), (vec![false; 2], vec![false; 2]));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RefFrame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width · height` entries, row-major.
    pub color: Vec<Option<[f64; 3]>>,
    /// Per pixel, whether it is a depth tie: the surface drawn there has a
    /// quantised depth within 1 of that of another surface covering the
    /// pixel (one it beat by at most 1, or one that later lost to it by at
    /// most 1), so which of them the kernel draws is ill-conditioned. A
    /// surface that wins by 2 or more clears the flag. Always `false`
    /// without the depth test.
    pub tie: Vec<bool>,
    /// Per pixel, whether the colour drawn there was evaluated within
    /// [`STEP_MARGIN`] of a step of the model (flat: at the triangle's
    /// centroid; Gouraud: at any of the triangle's vertices; Phong: at the
    /// pixel), see [`illuminate_with_margin`].
    pub step: Vec<bool>,
}

impl RefFrame {
    /// A frame of the given colours with no pixel flagged.
    ///
    /// ```
    /// use fixshade_host::reference::RefFrame;
    /// let f = RefFrame::new(1, 2, vec![Some([0.5; 3]), None]);
    /// assert_eq!((f.width, f.height, f.tie.len(), f.step.len()), (1, 2, 2, 2));
    /// ```
    pub fn new(width: u32, height: u32, color: Vec<Option<[f64; 3]>>) -> RefFrame {
        let n = color.len();
        RefFrame {
            width,
            height,
            color,
            tie: vec![false; n],
            step: vec![false; n],
        }
    }

    /// The colour at `(x, y)`, `None` if not drawn or outside the frame.
    ///
    /// ```
    /// use fixshade_host::reference::RefFrame;
    /// let green = Some([0.0, 1.0, 0.0]);
    /// let f = RefFrame::new(2, 2, vec![None, None, green, None]);
    /// assert_eq!(f.pixel(0, 1), Some([0.0, 1.0, 0.0])); // row-major: index 1 · 2 + 0
    /// assert_eq!(f.pixel(1, 0), None); // not drawn
    /// assert_eq!(f.pixel(2, 1), None); // outside
    /// ```
    pub fn pixel(&self, x: u32, y: u32) -> Option<[f64; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = y as usize * self.width as usize + x as usize;
        self.color.get(i).copied().flatten()
    }

    /// Number of drawn pixels.
    ///
    /// ```
    /// use fixshade_host::{reference::render, standard_scenes::sphere_scene};
    /// let frame = render(&sphere_scene(16, 16, 12, 6)).unwrap();
    /// let n = frame.covered_count();
    /// assert!(n > 0 && n < 16 * 16); // the sphere, not the corners
    /// assert_eq!(n, frame.color.iter().filter(|c| c.is_some()).count());
    /// ```
    pub fn covered_count(&self) -> usize {
        self.color.iter().filter(|c| c.is_some()).count()
    }

    /// The frame quantised to RGB565, `background` where nothing was drawn.
    ///
    /// ```
    /// use fixshade_host::reference::RefFrame;
    /// let f = RefFrame::new(2, 1, vec![None, Some([1.0, 1.0, 1.0])]);
    /// assert_eq!(f.to_rgb565([0.0; 3]), vec![0x0000, 0xFFFF]);
    /// ```
    pub fn to_rgb565(&self, background: [f64; 3]) -> Vec<u16> {
        self.color
            .iter()
            .map(|c| quantize_rgb565(c.unwrap_or(background)))
            .collect()
    }
}

/// Quantises a colour to RGB565 as SPEC.md section 6: `r5 = floor(31·r + ½)`,
/// `g6 = floor(63·g + ½)`, `b5 = floor(31·b + ½)`, packed `r5 << 11 | g6 << 5 | b5`.
/// Channels are clamped to [0, 1] first (NaN counts as 0).
///
/// ```
/// use fixshade_host::reference::quantize_rgb565;
/// assert_eq!(quantize_rgb565([1.0, 0.0, 0.0]), 0xF800);
/// assert_eq!(quantize_rgb565([0.0, 1.0, 0.0]), 0x07E0);
/// assert_eq!(quantize_rgb565([0.5 / 31.0, 0.0, 0.0]), 1 << 11); // halves round up
/// ```
pub fn quantize_rgb565(c: [f64; 3]) -> u16 {
    let q = |x: f64, max: f64| {
        let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
        (x * max + 0.5).floor() as u16
    };
    (q(c[0], 31.0) << 11) | (q(c[1], 63.0) << 5) | q(c[2], 31.0)
}

/// The OpenGL look-at view matrix (row-major, column vectors): the eye goes
/// to the origin, `target − eye` to −Z, `up` towards +Y.
///
/// Degenerate input (`eye == target`, `up` parallel to the view direction)
/// gives a matrix with zero rows; [`SceneDesc::validate`] rejects it.
///
/// ```
/// use fixshade_host::reference::look_at;
/// let v = look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0]);
/// assert_eq!(v[2][3], -5.0);
/// ```
pub fn look_at(eye: [f64; 3], target: [f64; 3], up: [f64; 3]) -> [[f64; 4]; 4] {
    let f = normalize(sub(target, eye));
    let s = normalize(cross(f, up));
    let u = cross(s, f);
    let d = |a: V3| -(a[0] * eye[0] + a[1] * eye[1] + a[2] * eye[2]);
    [
        [s[0], s[1], s[2], d(s)],
        [u[0], u[1], u[2], d(u)],
        [-f[0], -f[1], -f[2], -d(f)],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// The OpenGL perspective matrix (as `gluPerspective`).
///
/// ```
/// use fixshade_host::reference::perspective;
/// let p = perspective(90.0, 2.0, 1.0, 3.0);
/// assert!((p[1][1] - 1.0).abs() < 1e-12 && (p[0][0] - 0.5).abs() < 1e-12);
/// assert_eq!(p[3], [0.0, 0.0, -1.0, 0.0]);
/// ```
pub fn perspective(fovy_deg: f64, aspect: f64, near: f64, far: f64) -> [[f64; 4]; 4] {
    let f = 1.0 / (fovy_deg.to_radians() / 2.0).tan();
    [
        [f / aspect, 0.0, 0.0, 0.0],
        [0.0, f, 0.0, 0.0],
        [
            0.0,
            0.0,
            (far + near) / (near - far),
            2.0 * far * near / (near - far),
        ],
        [0.0, 0.0, -1.0, 0.0],
    ]
}

/// The OpenGL orthographic matrix (as `glOrtho`) with `top = height/2`,
/// `right = height·aspect/2` and symmetric bottom and left.
///
/// ```
/// use fixshade_host::reference::orthographic;
/// let o = orthographic(4.0, 1.5, 1.0, 11.0);
/// assert_eq!(o[1][1], 0.5);
/// assert_eq!(o[2][3], -1.2);
/// ```
pub fn orthographic(height: f64, aspect: f64, near: f64, far: f64) -> [[f64; 4]; 4] {
    let top = height / 2.0;
    let right = height * aspect / 2.0;
    [
        [1.0 / right, 0.0, 0.0, 0.0],
        [0.0, 1.0 / top, 0.0, 0.0],
        [0.0, 0.0, -2.0 / (far - near), -(far + near) / (far - near)],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// Vertex normals as SPEC.md section 4: for each vertex, the normalised sum
/// of the unit normals `normalise((p1−p0)×(p2−p0))` of the faces sharing it.
/// Degenerate faces (zero or non-finite normal) and faces with an index out
/// of range add nothing; a zero sum gives `[0, 0, 0]`.
///
/// ```
/// use fixshade_host::reference::vertex_normals;
/// use fixshade_host::scene_desc::MeshDesc;
/// let mesh = MeshDesc {
///     positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [5.0, 5.0, 5.0]],
///     normals: None,
///     indices: vec![[0, 1, 2]],
/// };
/// let n = vertex_normals(&mesh);
/// assert_eq!(n[0], [0.0, 0.0, 1.0]);
/// assert_eq!(n[3], [0.0, 0.0, 0.0]);
/// ```
pub fn vertex_normals(mesh: &MeshDesc) -> Vec<[f64; 3]> {
    let count = mesh.positions.len();
    let mut sums = vec![[0.0; 3]; count];
    for tri in &mesh.indices {
        if tri.iter().any(|&i| i as usize >= count) {
            continue;
        }
        let [p0, p1, p2] = tri.map(|i| mesh.positions[i as usize]);
        let n = cross(sub(p1, p0), sub(p2, p0));
        let len = length(n);
        if !(len > 0.0 && len.is_finite()) {
            continue;
        }
        let unit = scale(n, 1.0 / len);
        for &i in tri {
            sums[i as usize] = add(sums[i as usize], unit);
        }
    }
    sums.into_iter().map(normalize).collect()
}

/// One vertex with every attribute the clipper interpolates.
#[derive(Clone, Copy, Debug)]
struct Vert {
    clip: [f64; 4],
    eye: V3,
    normal: V3,
    front: V3,
    back: V3,
    /// Gouraud: how far the front and back colours were evaluated from a
    /// step of the model (`illuminate_with_margin`).
    front_margin: f64,
    back_margin: f64,
}

impl Vert {
    fn lerp(a: &Vert, b: &Vert, t: f64) -> Vert {
        let l = |x: f64, y: f64| x + t * (y - x);
        let l3 = |x: V3, y: V3| [l(x[0], y[0]), l(x[1], y[1]), l(x[2], y[2])];
        Vert {
            clip: [
                l(a.clip[0], b.clip[0]),
                l(a.clip[1], b.clip[1]),
                l(a.clip[2], b.clip[2]),
                l(a.clip[3], b.clip[3]),
            ],
            eye: l3(a.eye, b.eye),
            normal: l3(a.normal, b.normal),
            front: l3(a.front, b.front),
            back: l3(a.back, b.back),
            // A cut vertex's colour is a mix of both ends': near a step if
            // either is.
            front_margin: a.front_margin.min(b.front_margin),
            back_margin: a.back_margin.min(b.back_margin),
        }
    }

    /// Signed distance to the near plane in clip space (inside iff `≥ 0`).
    fn near_d(&self) -> f64 {
        self.clip[2] + self.clip[3]
    }
}

/// Clips a triangle against the near plane; returns up to 4 vertices.
fn clip_near(tri: &[Vert; 3]) -> ([Vert; 4], usize) {
    let mut out = [tri[0]; 4];
    let d = tri.map(|v| v.near_d());
    let inside = d.map(|x| x >= 0.0);
    if inside.iter().all(|&b| b) {
        out[..3].copy_from_slice(tri);
        return (out, 3);
    }
    if !inside.iter().any(|&b| b) {
        return (out, 0);
    }
    let mut n = 0;
    for a in 0..3 {
        let b = (a + 1) % 3;
        if inside[a] {
            out[n] = tri[a];
            n += 1;
        }
        if inside[a] != inside[b] {
            let t = d[a] / (d[a] - d[b]);
            out[n] = Vert::lerp(&tri[a], &tri[b], t);
            n += 1;
        }
    }
    (out, n)
}

/// A vertex in snapped window space.
#[derive(Clone, Copy, Debug)]
struct Snapped {
    x: i64,
    y: i64,
    z: f64,
}

fn snap(v: &Vert, w: f64, h: f64) -> Snapped {
    let [xc, yc, zc, wc] = v.clip;
    let xw = (xc / wc + 1.0) * w / 2.0;
    let yw = (1.0 - yc / wc) * h / 2.0;
    let zw = (zc / wc + 1.0) / 2.0;
    // `as` saturates and maps NaN to 0; the clamp keeps products in i128.
    let s = |v: f64| (v * 16.0 + 0.5).floor().clamp(-SNAP_LIMIT, SNAP_LIMIT) as i64;
    Snapped {
        x: s(xw),
        y: s(yw),
        z: zw,
    }
}

/// `E_ab(p)` in exact integer arithmetic.
fn edge(a: (i64, i64), b: (i64, i64), p: (i64, i64)) -> i128 {
    let (dx, dy) = (
        i128::from(b.0) - i128::from(a.0),
        i128::from(b.1) - i128::from(a.1),
    );
    dx * (i128::from(p.1) - i128::from(a.1)) - dy * (i128::from(p.0) - i128::from(a.0))
}

fn is_top_left(a: (i64, i64), b: (i64, i64)) -> bool {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    (dy == 0 && dx > 0) || dy < 0
}

fn inside_edge(e: i128, a: (i64, i64), b: (i64, i64)) -> bool {
    e > 0 || (e == 0 && is_top_left(a, b))
}

/// What one drawn triangle piece needs besides its vertices.
struct Target<'a> {
    color: &'a mut [Option<V3>],
    tie: &'a mut [bool],
    step: &'a mut [bool],
    /// Quantised depths, cleared to 65535.
    depth: &'a mut [u16],
    width: u32,
    height: u32,
}

/// Per-piece shading inputs.
struct Shade<'a, 'b> {
    lighting: &'a LightingModel<'b>,
    shading: Shading,
    cull: bool,
    depth_test: bool,
    two_sided: bool,
    /// Flat colours (front, back) of the original triangle, and how far
    /// each was evaluated from a step of the model.
    flat: (V3, V3),
    flat_margin: (f64, f64),
}

fn draw_triangle(verts: [Vert; 3], target: &mut Target, shade: &Shade) {
    let (w, h) = (f64::from(target.width), f64::from(target.height));
    let mut v = verts;
    let mut s = v.map(|x| snap(&x, w, h));
    let xy = |s: &Snapped| (s.x, s.y);
    let mut area2 = edge(xy(&s[0]), xy(&s[1]), xy(&s[2]));
    if area2 == 0 {
        return;
    }
    // Front faces are counter-clockwise in NDC (SPEC.md section 5). With y
    // pointing down in window space, that is a *negative* `E_{v0v1}(v2)`.
    let back = area2 > 0;
    if back && shade.cull {
        return;
    }
    if area2 < 0 {
        // Make the triangle positively oriented for the coverage test.
        v.swap(1, 2);
        s.swap(1, 2);
        area2 = -area2;
    }
    let use_back = back && shade.two_sided;
    let (p0, p1, p2) = (xy(&s[0]), xy(&s[1]), xy(&s[2]));

    let min_x = p0.0.min(p1.0).min(p2.0);
    let max_x = p0.0.max(p1.0).max(p2.0);
    let min_y = p0.1.min(p1.1).min(p2.1);
    let max_y = p0.1.max(p1.1).max(p2.1);
    let last_x = i64::from(target.width) - 1;
    let last_y = i64::from(target.height) - 1;
    let x_lo = (min_x - 8).div_euclid(16).max(0);
    let x_hi = (max_x - 8).div_euclid(16).min(last_x);
    let y_lo = (min_y - 8).div_euclid(16).max(0);
    let y_hi = (max_y - 8).div_euclid(16).min(last_y);
    let area = area2 as f64;

    for py in y_lo..=y_hi {
        for px in x_lo..=x_hi {
            let p = (16 * px + 8, 16 * py + 8);
            let e01 = edge(p0, p1, p);
            let e12 = edge(p1, p2, p);
            let e20 = edge(p2, p0, p);
            if !(inside_edge(e01, p0, p1) && inside_edge(e12, p1, p2) && inside_edge(e20, p2, p0)) {
                continue;
            }
            let l = [e12 as f64 / area, e20 as f64 / area, e01 as f64 / area];
            let i = (py * i64::from(target.width) + px) as usize;
            let mut tie = false;
            if shade.depth_test {
                let z = l[0] * s[0].z + l[1] * s[1].z + l[2] * s[2].z;
                let d = quantize_depth(z);
                let stored = target.depth[i];
                // A stored value below the cleared 65535 is another
                // surface's (a surface is stored only where its d is below
                // what was there). Within 1 of it, the kernel's d, which
                // can be 1 off this one, may keep either surface.
                let near = stored < u16::MAX && d.abs_diff(stored) <= 1;
                if d >= stored {
                    target.tie[i] |= near;
                    continue;
                }
                target.depth[i] = d;
                tie = near;
            }
            target.tie[i] = tie;
            let mix = |f: fn(&Vert) -> V3| {
                let mut out = [0.0; 3];
                for (k, vert) in v.iter().enumerate() {
                    out = add(out, scale(f(vert), l[k]));
                }
                out
            };
            let (color, margin) = match shade.shading {
                Shading::Flat => {
                    if use_back {
                        (shade.flat.1, shade.flat_margin.1)
                    } else {
                        (shade.flat.0, shade.flat_margin.0)
                    }
                }
                Shading::Gouraud => {
                    // Every vertex colour is in the mix: near a step if
                    // any of them is.
                    let least = |m: [f64; 3]| m[0].min(m[1]).min(m[2]);
                    if use_back {
                        (mix(|v| v.back), least(v.map(|v| v.back_margin)))
                    } else {
                        (mix(|v| v.front), least(v.map(|v| v.front_margin)))
                    }
                }
                Shading::Phong => {
                    let n = mix(|v| v.normal);
                    let n = if use_back { scale(n, -1.0) } else { n };
                    illuminate_with_margin(shade.lighting, mix(|v| v.eye), n)
                }
            };
            target.color[i] = Some(color.map(|c| if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) }));
            target.step[i] = margin <= STEP_MARGIN;
        }
    }
}

/// Renders `scene` with the f64 reference pipeline (module documentation,
/// steps 1 to 9). The scene is [validated](SceneDesc::validate) first.
///
/// Returns a frame with `Some(colour)` at every drawn pixel and `None`
/// elsewhere (the background is not stored), with each pixel's depth-tie
/// and model-step flags (step 9). A 0 × N frame is empty.
/// Triangles are drawn in index order, clipped pieces in fan order; without
/// the depth test later pieces overwrite earlier ones.
///
/// ```
/// use fixshade_host::reference::render;
/// use fixshade_host::scene_desc::*;
/// // A triangle covering the lower-left half of an 8 × 8 orthographic view.
/// let cam = CameraDesc {
///     eye: [0.0, 0.0, 1.0], target: [0.0; 3], up: [0.0, 1.0, 0.0],
///     near: 0.5, far: 2.0, projection: Projection::Orthographic { height: 2.0 },
/// };
/// let mesh = MeshDesc {
///     positions: vec![[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [-1.0, 1.0, 0.0]],
///     normals: None,
///     indices: vec![[0, 1, 2]],
/// };
/// let frame = render(&SceneDesc::new(8, 8, cam, mesh)).unwrap();
/// // 0 + 1 + … + 7 = 28 pixels strictly below the diagonal; the 8 samples on
/// // it are not drawn (the interior lies left of it: a right edge).
/// assert_eq!(frame.covered_count(), 28);
/// ```
pub fn render(scene: &SceneDesc) -> Result<RefFrame, SceneError> {
    scene.validate()?;
    let (width, height) = (scene.width, scene.height);
    let pixels = width as usize * height as usize;
    let mut frame = RefFrame::new(width, height, vec![None; pixels]);
    if pixels == 0 {
        return Ok(frame);
    }

    let cam = &scene.camera;
    let view = look_at(cam.eye, cam.target, cam.up);
    let aspect = f64::from(width) / f64::from(height);
    let proj = match cam.projection {
        Projection::Perspective { fovy_deg } => perspective(fovy_deg, aspect, cam.near, cam.far),
        Projection::Orthographic { height } => orthographic(height, aspect, cam.near, cam.far),
    };
    let mv = mat_mul(&view, &scene.model);
    let nm = normal_matrix(&mv).ok_or(SceneError::Degenerate {
        field: "model".into(),
        reason: "3x3 part is singular",
    })?;
    let lights = eye_lights(&scene.lights, &view);
    let lighting = LightingModel {
        material: &scene.material,
        global_ambient: scene.global_ambient,
        lights: &lights,
        specular_model: scene.specular_model,
        viewer: scene.viewer,
    };

    let mesh = &scene.mesh;
    let object_normals: Cow<[V3]> = match &mesh.normals {
        Some(n) => Cow::Borrowed(n),
        None => Cow::Owned(vertex_normals(mesh)),
    };
    let gouraud = scene.shading == Shading::Gouraud;
    let verts: Vec<Vert> = mesh
        .positions
        .iter()
        .zip(object_normals.iter())
        .map(|(p, n)| {
            let eye = transform_point(&mv, *p);
            let normal = normalize(mul3(&nm, *n));
            let clip = transform4(&proj, eye);
            let ((front, front_margin), (back, back_margin)) = if gouraud {
                let front = illuminate_with_margin(&lighting, eye, normal);
                let back = if scene.two_sided {
                    illuminate_with_margin(&lighting, eye, scale(normal, -1.0))
                } else {
                    front
                };
                (front, back)
            } else {
                (([0.0; 3], f64::INFINITY), ([0.0; 3], f64::INFINITY))
            };
            Vert {
                clip,
                eye,
                normal,
                front,
                back,
                front_margin,
                back_margin,
            }
        })
        .collect();

    let mut depth = vec![u16::MAX; pixels];
    let mut target = Target {
        color: &mut frame.color,
        tie: &mut frame.tie,
        step: &mut frame.step,
        depth: &mut depth,
        width,
        height,
    };
    for tri in &mesh.indices {
        let v = tri.map(|i| verts[i as usize]);
        let ((front, front_margin), (back, back_margin)) = if scene.shading == Shading::Flat {
            let [e0, e1, e2] = v.map(|x| x.eye);
            let centroid = add(add(e0, e1), e2).map(|c| c / 3.0);
            let n = normalize(cross(sub(e1, e0), sub(e2, e0)));
            let front = illuminate_with_margin(&lighting, centroid, n);
            let back = if scene.two_sided {
                illuminate_with_margin(&lighting, centroid, scale(n, -1.0))
            } else {
                front
            };
            (front, back)
        } else {
            (([0.0; 3], f64::INFINITY), ([0.0; 3], f64::INFINITY))
        };
        let shade = Shade {
            lighting: &lighting,
            shading: scene.shading,
            cull: scene.cull,
            depth_test: scene.depth,
            two_sided: scene.two_sided,
            flat: (front, back),
            flat_margin: (front_margin, back_margin),
        };
        let (poly, n) = clip_near(&v);
        for k in 1..n.saturating_sub(1) {
            draw_triangle([poly[0], poly[k], poly[k + 1]], &mut target, &shade);
        }
    }
    Ok(frame)
}

//! The vertex stage: each mesh vertex's window position, depth and lit
//! colour, in a 16-byte [`CachedVertex`] per vertex.
//!
//! Once a frame ([`Frame::project_all`]) a vertex's window position comes
//! from its `i16` mesh position through the projection's rows folded with
//! the viewport, the model-view matrix and the mesh's box ([`Fold`]),
//! divided by its `w_c` with one reciprocal, and snapped to 1/16 pixel;
//! its eye-space depth decides the near test as the clipping does. It is
//! lit the first time a visible triangle needs its colour. Everything else a triangle may need of a vertex (its
//! eye position and normal for flat and Phong shading and for lighting,
//! its clip coordinates where a triangle crosses the near plane or the
//! guard band, its window position when a coordinate lies outside
//! [−2 048, 2 048) pixels of the target's top-left corner) is
//! computed again from the mesh: the same functions of the same inputs,
//! so the same values, and no bytes kept for the rare paths.
//!
//! The whole frame, the band renderer's cached mode and its recomputed
//! mode (three cache entries per triangle, on the stack) share this store
//! and its [`Corners`], so cull, box and facing are decided on the same
//! values everywhere.

use crate::camera::ProjectionCoeffs;
use crate::color::Shade;
use crate::illumination::Viewer;
use crate::light::LightSet;
use crate::material::Specular;
use crate::normalize::normalize;
use crate::num::widening::{mul_by_narrow, mul_i32_i16};
use crate::rasterizer::{Recip, COORD_LIMIT, QUOT_SAT};
use crate::render::{DrawStats, Frame};
use crate::vector::Mat4;
use crate::vector::{Unit3, Vec3};

/// A window position and depth attribute ([`Frame::window`]): `x`, `y` in
/// 1/16 pixel within ±2²⁸, the depth within ±2³⁰, so every coordinate and
/// its difference from a tile's centre (below 2²⁵) fits `i32`.
pub(crate) type Win = [i32; 3];

/// The colour and flags word: red in bits 0–16, green 17–33, blue 34–50
/// (three `Q.16` channels, 0 ..= 65536), then the flags.
const COLOUR_MASK: u64 = (1 << 51) - 1;
/// In front of the near plane (`z_c + w_c ≥ 0`): the window position and
/// depth are set.
const B_INSIDE: u64 = 1 << 51;
/// The colour is the front face's.
const B_FRONT: u64 = 1 << 52;
/// The colour is the back face's (negated normal).
const B_BACK: u64 = 1 << 53;
/// A window coordinate lies outside `i16` (outside [−2 048, 2 048) pixels
/// of the target's top-left corner): `x`, `y` are not kept, and
/// [`Corners::win`] computes them again. A target of one tile (at most
/// [`CLIP_LIMIT`](crate::rasterizer::CLIP_LIMIT) = 2 032 pixels a side)
/// has its guard band, `±(2¹⁴ − 16)` sixteenths around its centre, within
/// `[−2¹⁴, 2¹⁵)`: every vertex the set-up takes as it is has its position
/// kept.
const B_FAR: u64 = 1 << 54;

/// One vertex's per-frame data, in a cache the caller provides (one per
/// mesh vertex): 16 bytes.
///
/// The window position is kept as `i16` sixteenths of a pixel, the depth
/// attribute as `i32`, and one lit colour
/// (three 17-bit channels) with the flags in 64 bits. A vertex lit for
/// both faces (a silhouette vertex with two-sided lighting) keeps the
/// first face's colour; the other one is lit again when asked for.
///
/// ```
/// use fixshade::render::CachedVertex;
/// assert_eq!(core::mem::size_of::<CachedVertex>(), 16);
/// // `const`: a cache can be a `static`.
/// static EMPTY: [CachedVertex; 642] = [CachedVertex::new(); 642];
/// ```
///
/// ```
/// # use fixshade::prelude::*;
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
/// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// # let material = Material::new();
/// # let renderer = Renderer::new(&camera, &material, &sun);
/// let mut px = [0u16; 32 * 32];
/// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
/// let mut short = [CachedVertex::new(); 2]; // the mesh has 3 vertices
/// let e = MESH.shaded(&renderer).with_cache(&mut short).draw(&mut fb);
/// assert_eq!(e, Err(RenderError::CacheTooSmall));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CachedVertex {
    x: i16,
    y: i16,
    z: i32,
    c: [u32; 2],
}

const _: () = assert!(core::mem::size_of::<CachedVertex>() == 16);

impl CachedVertex {
    /// An empty entry (every draw call overwrites what it uses).
    ///
    /// ```
    /// use fixshade::render::CachedVertex;
    /// const EMPTY: CachedVertex = CachedVertex::new();
    /// assert_eq!(EMPTY, CachedVertex::default());
    /// ```
    pub const fn new() -> CachedVertex {
        CachedVertex {
            x: 0,
            y: 0,
            z: 0,
            c: [0; 2],
        }
    }

    #[inline(always)]
    fn bits(&self) -> u64 {
        self.c[0] as u64 | (self.c[1] as u64) << 32
    }

    #[inline(always)]
    fn set_bits(&mut self, v: u64) {
        self.c = [v as u32, (v >> 32) as u32];
    }

    /// Whether flag `b` (one of bits 32–63) is set, from the high word.
    #[inline(always)]
    fn has(&self, b: u64) -> bool {
        self.c[1] & ((b >> 32) as u32) != 0
    }

    /// The window position kept (of a vertex in front of the near plane,
    /// not [`B_FAR`]).
    #[inline(always)]
    fn kept(&self) -> Win {
        [self.x as i32, self.y as i32, self.z]
    }

    /// The window `y` of a vertex in front of the near plane whose position
    /// is kept (not [`B_FAR`]), else `None`.
    #[inline(always)]
    pub(crate) fn near_y(&self) -> Option<i32> {
        let near = self.c[1] & (((B_INSIDE | B_FAR) >> 32) as u32) == (B_INSIDE >> 32) as u32;
        near.then_some(self.y as i32)
    }
}

fn pack(s: Shade) -> u64 {
    let b = s.to_bits();
    b[0] as u64 | (b[1] as u64) << 17 | (b[2] as u64) << 34
}

#[inline(always)]
fn unpack(v: u64) -> Shade {
    let m = (1u64 << 17) - 1;
    Shade::from_bits(
        (v & m) as u32,
        ((v >> 17) & m) as u32,
        ((v >> 34) & m) as u32,
    )
}

/// A triangle's three corners: corner `k` is `cache[slot[k]]`, mesh vertex
/// `vertex[k]`, projected ([`Frame::project_into`]). The whole frame and
/// the band renderer's cached mode index the frame's cache (`slot =
/// vertex`), its recomputed mode a cache of three.
pub(crate) struct Corners<'c> {
    cache: &'c mut [CachedVertex],
    slot: [usize; 3],
    vertex: [usize; 3],
}

impl<'c> Corners<'c> {
    /// Triangle `idx` (mesh vertex indices) of a cache of one entry per
    /// mesh vertex.
    #[inline(always)]
    pub(crate) fn of(cache: &'c mut [CachedVertex], idx: [usize; 3]) -> Self {
        Corners {
            cache,
            slot: idx,
            vertex: idx,
        }
    }

    /// Triangle `idx` from a cache of its three corners, in order.
    #[inline(always)]
    pub(crate) fn of_three(cache: &'c mut [CachedVertex; 3], idx: [usize; 3]) -> Self {
        Corners {
            cache,
            slot: [0, 1, 2],
            vertex: idx,
        }
    }

    /// The mesh vertex of corner `k`.
    #[inline(always)]
    pub(crate) fn vertex(&self, k: usize) -> usize {
        self.vertex[k]
    }

    /// Whether corner `k` is in front of the near plane (`z_c + w_c ≥ 0`).
    #[inline(always)]
    pub(crate) fn inside(&self, k: usize) -> bool {
        self.cache[self.slot[k]].has(B_INSIDE)
    }

    /// Window position and depth of corner `k` (in front of the near plane).
    #[inline(always)]
    pub(crate) fn win<S: Specular, V: Viewer, L: LightSet>(
        &self,
        f: &Frame<'_, '_, S, V, L>,
        k: usize,
    ) -> Win {
        let v = &self.cache[self.slot[k]];
        if v.has(B_FAR) {
            f.far_window(self.vertex[k])
        } else {
            v.kept()
        }
    }

    /// [`Corners::win`] of all three corners (in front of the near plane),
    /// with one test for far ones.
    #[inline(always)]
    pub(crate) fn wins<S: Specular, V: Viewer, L: LightSet>(
        &self,
        f: &Frame<'_, '_, S, V, L>,
    ) -> [Win; 3] {
        let v = self.slot.map(|s| &self.cache[s]);
        if (v[0].c[1] | v[1].c[1] | v[2].c[1]) & ((B_FAR >> 32) as u32) == 0 {
            [v[0].kept(), v[1].kept(), v[2].kept()]
        } else {
            self.wins_far(f)
        }
    }

    /// [`Corners::wins`] with a far corner, out of line (rare).
    #[inline(never)]
    fn wins_far<S: Specular, V: Viewer, L: LightSet>(
        &self,
        f: &Frame<'_, '_, S, V, L>,
    ) -> [Win; 3] {
        [self.win(f, 0), self.win(f, 1), self.win(f, 2)]
    }

    /// Clip-space position of corner `k` (asked only when the triangle
    /// crosses the near plane or the guard band, or may have turned over).
    pub(crate) fn clip<S: Specular, V: Viewer, L: LightSet>(
        &self,
        f: &Frame<'_, '_, S, V, L>,
        k: usize,
    ) -> [i64; 4] {
        f.proj.clip(f.eye(self.vertex[k]))
    }

    /// The lit colour of corner `k`, for its back (negated normal) if `back`.
    #[inline(always)]
    pub(crate) fn shade<S: Specular, V: Viewer, L: LightSet>(
        &mut self,
        f: &Frame<'_, '_, S, V, L>,
        k: usize,
        back: bool,
        stats: &mut DrawStats,
    ) -> Shade {
        let v = &mut self.cache[self.slot[k]];
        let want = if back { B_BACK } else { B_FRONT };
        if v.has(want) {
            unpack(v.bits())
        } else {
            f.light(v, self.vertex[k], want, stats)
        }
    }

    /// Eye-space position and (if `normal`) normal of corner `k`.
    #[inline(always)]
    pub(crate) fn eye_normal<S: Specular, V: Viewer, L: LightSet>(
        &self,
        f: &Frame<'_, '_, S, V, L>,
        k: usize,
        normal: bool,
    ) -> (Vec3, Unit3) {
        let i = self.vertex[k];
        let n = if normal { f.eye_normal(i) } else { Unit3::ZERO };
        (f.eye(i), n)
    }
}

/// `⌊num/2^k + ½⌋` for any `k`, or ±[`QUOT_SAT`] where that is larger in
/// magnitude. For `1 ≤ k ≤ 63` it is `⌊(⌊num/2^(k−1)⌋ + 1)/2⌋` (nested
/// floors), the inner quotient first saturated (so the `+ 1` cannot
/// overflow); for `k ≥ 64`, `|num/2^k| ≤ ½` rounds to 0.
fn shift_round(num: i64, k: i32) -> i64 {
    let q = match k {
        64.. => return 0,
        1..=63 => num >> (k - 1),
        _ => num.saturating_mul(1 << (-k).min(62)),
    };
    let q = q.clamp(-2 * QUOT_SAT, 2 * QUOT_SAT);
    if k >= 1 {
        (q + 1) >> 1
    } else {
        q.clamp(-QUOT_SAT, QUOT_SAT)
    }
}

/// The projection's `x` and `y` rows folded with the viewport and the
/// model-view matrix (the mesh's box in it), once a draw: from a mesh's
/// `i16` position `q`, `X = Σ g[c]·q[c] + t` is `8W·x_c·2^down` before
/// the eye position's and `x_c`'s roundings (likewise `Y` for
/// `−8H·y_c`), so the window position is `X/(w_c·2^down) + 8W`.
///
/// Exactly, with `M` the model-view rows in raw `I8F24` and `q` read as
/// `Q.15`: `x_e·2¹⁵ = Σ M[c]·q[c] + M[3]·2¹⁵`, `x_c·2³⁹ = s_x·x_e·2¹⁵ +
/// t_x·2³⁹`, so `G[c] = 8W·s_x·M[c]` (below `2²³·2³¹·2³¹ = 2⁸⁵`) and `T =
/// 8W·(s_x·M[3]·2¹⁵ + t_x·2³⁹)` (below 2¹⁰¹), in `i128`. A row keeps them
/// divided by `2^e`, rounded, with `e` the least that brings every
/// `|g[c]|` to at most 2²⁸ and `|t|` to at most 2⁴⁴ (`down = 39 − e`):
/// then `|X| ≤ 3·2²⁸·2¹⁵ + 2⁴⁴ < 2⁴⁶`, each product `i32 × i16`. The
/// entries' roundings move `X` by at most `3·2¹⁴ + ½` against a
/// magnitude of 2⁴⁴ or more where `t` set `e` (2⁻²⁹ of it), or 2²⁸·|q|
/// where a `g` did: precision relative to the mesh's extent and
/// position, whatever the world's size.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fold {
    g: [[i32; 3]; 2],
    t: [i64; 2],
    /// Each row's `down`.
    pub(crate) down: [i32; 2],
}

impl Fold {
    /// The rows for a target of `w × h` pixels.
    pub(crate) fn new(m: &Mat4, p: &ProjectionCoeffs, w: i64, h: i64) -> Fold {
        let mut fold = Fold {
            g: [[0; 3]; 2],
            t: [0; 2],
            down: [0; 2],
        };
        let rows = [(8 * w, p.sx, p.tx, 0), (-8 * h, p.sy, p.ty, 1)];
        for (k, (scale, s, t, r)) in rows.into_iter().enumerate() {
            let row = &m.m[r];
            let g = [0, 1, 2].map(|c| scale as i128 * s as i128 * row[c] as i128);
            let t = scale as i128 * (((s as i128 * row[3] as i128) << 15) + ((t as i128) << 39));
            let bits = |v: u128| 128 - v.leading_zeros() as i32;
            let gmax = g.iter().map(|v| v.unsigned_abs()).max().unwrap_or(0);
            let e = (bits(gmax) - 28).max(bits(t.unsigned_abs()) - 44);
            let scaled = |v: i128| {
                if e > 0 {
                    (v + (1 << (e - 1))) >> e
                } else {
                    v << -e
                }
            };
            fold.g[k] = g.map(|v| scaled(v) as i32);
            fold.t[k] = scaled(t) as i64;
            fold.down[k] = 39 - e;
        }
        fold
    }

    /// `X` (`k = 0`) or `Y` (`k = 1`) of position `q`.
    #[inline(always)]
    pub(crate) fn row(&self, k: usize, q: [i16; 3]) -> i64 {
        let g = &self.g[k];
        mul_i32_i16(g[0], q[0]) + mul_i32_i16(g[1], q[1]) + mul_i32_i16(g[2], q[2]) + self.t[k]
    }
}

impl<S: Specular, V: Viewer, L: LightSet> Frame<'_, '_, S, V, L> {
    /// Projects every vertex of the mesh into `cache` (one per vertex), the
    /// vertex's work inlined in one loop instead of a call per vertex.
    #[inline(never)]
    pub(crate) fn project_all(&self, cache: &mut [CachedVertex]) {
        for (i, c) in cache.iter_mut().enumerate() {
            self.project_into(c, i);
        }
    }

    /// The corners `idx` projected and snapped, without a cache (no colour
    /// yet).
    #[inline(always)]
    pub(crate) fn project3(&self, idx: [usize; 3]) -> [CachedVertex; 3] {
        let mut l = [CachedVertex::new(); 3];
        for (c, &i) in l.iter_mut().zip(&idx) {
            self.project_into(c, i);
        }
        l
    }

    /// Projects and snaps mesh vertex `i` into `c` (no colour yet).
    #[inline(always)]
    pub(crate) fn project_into(&self, c: &mut CachedVertex, i: usize) {
        *c = CachedVertex::new();
        let Some(w) = self.vertex_window(i) else {
            return;
        };
        c.z = w[2];
        match (i16::try_from(w[0]), i16::try_from(w[1])) {
            (Ok(x), Ok(y)) => {
                (c.x, c.y) = (x, y);
                c.set_bits(B_INSIDE);
            }
            _ => c.set_bits(B_INSIDE | B_FAR),
        }
    }

    /// The window position of a vertex in front of the near plane that
    /// [`Frame::project_into`] found far ([`B_FAR`]): the same computation
    /// (rare, out of line).
    #[inline(never)]
    pub(crate) fn far_window(&self, i: usize) -> Win {
        self.vertex_window(i).unwrap_or([0; 3])
    }

    /// Window position and depth attribute of mesh vertex `i`, or `None`
    /// behind the near plane (`z_c + w_c < 0`).
    ///
    /// Its eye-space depth and `z_c`, `w_c` are computed as
    /// [`ProjectionCoeffs::clip`] computes them, so the near test agrees
    /// with the clipping's; `x` and `y` come from the mesh position through
    /// the folded rows ([`Fold`]), divided by `w_c` with one reciprocal.
    #[inline(always)]
    fn vertex_window(&self, i: usize) -> Option<Win> {
        let q = self.mesh.positions[i];
        let [z, w] = self.depth_clip(q);
        if z + w < 0 {
            return None;
        }
        let f = &self.fold;
        Some(self.window_of((f.row(0, q), f.down[0]), (f.row(1, q), f.down[1]), z, w))
    }

    /// The folded rows and `w_c` of mesh vertex `i` (in front of the near
    /// plane): its window position is `(X/(w·2^dx) + 8W, Y/(w·2^dy) + 8H)`
    /// before rounding. [`Fold`] bounds `|X|, |Y|` by 2⁴⁶; `0 < w ≤ 2³¹`
    /// for a vertex with a window position.
    pub(crate) fn homogeneous(&self, i: usize) -> [i64; 3] {
        let q = self.mesh.positions[i];
        let [_, w] = self.depth_clip(q);
        [self.fold.row(0, q), self.fold.row(1, q), w]
    }

    /// `[z_c, w_c]` of mesh position `q`: its eye-space depth row, then
    /// [`ProjectionCoeffs::depth_clip`] (the clip coordinates' own).
    #[inline(always)]
    fn depth_clip(&self, q: [i16; 3]) -> [i64; 2] {
        self.proj.depth_clip(self.modelview.quantised_row(2, q))
    }

    /// Eye-space position of mesh vertex `i`.
    #[inline]
    pub(crate) fn eye(&self, i: usize) -> Vec3 {
        self.modelview.transform_quantised(self.mesh.positions[i])
    }

    /// Eye-space normal of mesh vertex `i`: its octahedral point
    /// transformed, then normalised once.
    #[inline]
    pub(crate) fn eye_normal(&self, i: usize) -> Unit3 {
        match self.mesh.normals {
            Some(ns) => self.normal_to_eye(ns[i].octahedron()),
            None => Unit3::ZERO,
        }
    }

    /// `N_eye = normalise(M_n · N)` for `N` a point of the octahedron
    /// ([`PackedNormal::octahedron`]): `|M_n| ≤ 2¹⁴` and `Σ|N| ≤ 3·2¹⁵`
    /// (32767 for the encoder's bits), so each row's sum of 16 × 16-bit
    /// products is at most `3·2²⁹ < 2³¹`.
    ///
    /// [`PackedNormal::octahedron`]: crate::mesh::PackedNormal::octahedron
    #[inline]
    fn normal_to_eye(&self, b: [i32; 3]) -> Unit3 {
        let m = &self.r.normal_m;
        let row = |r: usize| m[r][0] as i32 * b[0] + m[r][1] as i32 * b[1] + m[r][2] as i32 * b[2];
        normalize([row(0), row(1), row(2)]).unwrap_or(Unit3::ZERO)
    }

    /// Window position (1/16 pixel, clamped to ±2²⁸) and depth attribute of
    /// a clip-space point in front of the near plane (SPEC.md 1, 5): a
    /// corner that clipping made.
    ///
    /// `|x_c|, |y_c|, |z_c| < 2³⁸ + 2³¹` (a projection coefficient below
    /// 2³¹ raw times an `I8F24` coordinate, shifted by 24, plus an offset
    /// below 2³¹) and `8W, 8H ≤ 2²³`: `8W·x_c` is below 2⁶², within `i64`.
    #[inline(never)]
    pub(crate) fn window(&self, c: &[i64; 4]) -> Win {
        let x = mul_by_narrow(c[0], 8 * self.w);
        let y = mul_by_narrow(-c[1], 8 * self.h);
        self.window_of((x, 0), (y, 0), c[2], c[3])
    }

    /// The window position `(X/(w·2^dx) + 8W, Y/(w·2^dy) + 8H)` rounded to
    /// 1/16 pixel (`dx`, `dy`: the [`Fold`]'s shifts, 0 for a corner that
    /// clipping made) and the depth attribute `Z = ⌊z_c·K/w⌋ + 2²³`, `K =
    /// 65535·2⁷ = 2²³ − 2⁷`, each quotient from one reciprocal of `w`
    /// ([`Recip::div_scaled`]: within `½ + |q|·2⁻²⁹` of the exact `q`, so a
    /// snapped coordinate within ±2²⁴ is within 1/16 of the rounding's
    /// half-unit; beyond, it is clamped or far off screen).
    ///
    /// The depth attribute is scaled so that `Z >> 8` is SPEC.md 5's
    /// quantised depth `d = ⌊z_w·65535 + ½⌋`: with `z_w = (z_c/w + 1)/2`,
    /// `z_w·65535·2⁸ + 2⁷ = z_c·K/w + 2²³` (the offset `65535·2⁷ + 2⁷` is
    /// `2²³`), and `⌊⌊x⌋/2⁸⌋ = ⌊x/2⁸⌋`. The floor is the rounding of
    /// `(2K·z_c − w)/(2w)`: `|2K·z_c| < 2²⁴·(2³⁸ + 2³¹)` and `w ≤ 2³¹`, so
    /// the numerator is within `i64`.
    ///
    /// Clamps: `x`, `y` to ±2²⁸ and `Z` to ±2³⁰ ([`Win`]); a quotient that
    /// [`Recip::div_scaled`] saturates lands on them.
    #[inline(always)]
    fn window_of(&self, x: (i64, i32), y: (i64, i32), z: i64, w: i64) -> Win {
        if w <= 0 {
            return [0, 0, 0];
        }
        let (hw, hh) = (8 * self.w, 8 * self.h);
        let z = mul_by_narrow(z, (1 << 24) - (1 << 8)) - w;
        let [x, y, z] = if w & (w - 1) == 0 {
            // A power of two (every `w` of an orthographic projection):
            // exact quotients.
            let k = w.trailing_zeros() as i32;
            [
                shift_round(x.0, k + x.1),
                shift_round(y.0, k + y.1),
                shift_round(z, k + 1),
            ]
        } else {
            // Kept positions are within 2¹⁶ of the viewport's centre,
            // depths within 2²⁴ (a point between the near and far planes).
            let r = Recip::new(w);
            [
                r.div_scaled(x.0, x.1, 16),
                r.div_scaled(y.0, y.1, 16),
                r.div_scaled(z, 1, 24),
            ]
        };
        [
            (x + hw).clamp(-COORD_LIMIT, COORD_LIMIT) as i32,
            (y + hh).clamp(-COORD_LIMIT, COORD_LIMIT) as i32,
            (z + (1 << 23)).clamp(-(1 << 30), 1 << 30) as i32,
        ]
    }

    /// Lights `v` (mesh vertex `i`) for the facing `want` ([`B_FRONT`] or
    /// [`B_BACK`]), keeping the colour if the vertex has none yet.
    #[inline(never)]
    fn light(&self, v: &mut CachedVertex, i: usize, want: u64, stats: &mut DrawStats) -> Shade {
        let n = self.eye_normal(i);
        let n = if want == B_BACK { n.neg() } else { n };
        let s = self.r.lighting().shade(self.eye(i), n);
        stats.lit = stats.lit.saturating_add(1);
        let bits = v.bits();
        if bits & (B_FRONT | B_BACK) == 0 {
            v.set_bits((bits & !COLOUR_MASK) | pack(s) | want);
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::shift_round;
    use crate::rasterizer::tests::xorshift;
    use crate::rasterizer::QUOT_SAT;

    /// `shift_round` is `⌊num/2^k + ½⌋` in `i128`, saturated: both signs,
    /// every magnitude, ties, shifts either way and past 64.
    #[test]
    fn shift_round_is_the_rounded_quotient() {
        let mut next = xorshift(0x8f1b_bcdc_ca62_c1d6);
        let mut nums = vec![0i64, 1, -1, i64::MAX, i64::MIN + 1, 3 << 20, -(3 << 20)];
        nums.extend(
            (0..20_000).map(|_| (next() >> (next() % 64)) as i64 * [1, -1][(next() & 1) as usize]),
        );
        for num in nums {
            for k in -70..=70 {
                let want = if k >= 0 {
                    let d = 1i128 << k.min(100);
                    (2 * num as i128 + d).div_euclid(2 * d)
                } else {
                    let v = num as i128;
                    v.checked_mul(1 << -k).unwrap_or(v.signum() * i128::MAX)
                };
                let want = want.clamp(-(QUOT_SAT as i128), QUOT_SAT as i128) as i64;
                assert_eq!(shift_round(num, k), want, "{num} >> {k}");
            }
        }
    }
}

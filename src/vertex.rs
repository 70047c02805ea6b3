//! The vertex stage: each mesh vertex's window position, depth and lit
//! colour, in a 16-byte [`CachedVertex`] per vertex.
//!
//! A vertex is transformed (the mesh's `i16` position through the
//! model-view matrix with the mesh's box folded in, to `I8F24` eye space),
//! projected to clip space and snapped to 1/16 pixel once a frame
//! ([`Frame::project_all`]); it is lit the first time a visible triangle
//! needs its colour. Everything else a triangle may need of a vertex (its
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

use crate::color::Shade;
use crate::illumination::Viewer;
use crate::light::LightSet;
use crate::material::Specular;
use crate::normalize::normalize;
use crate::num::division::{floor_div, floor_div_all};
use crate::num::widening::mul_by_narrow;
use crate::rasterizer::COORD_LIMIT;
use crate::render::{DrawStats, Frame};
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
/// # use fixshade::camera::Camera;
/// # use fixshade::illumination::InfiniteViewer;
/// # use fixshade::light::DirectionalLight;
/// # use fixshade::mesh::{Bounds, Mesh, PackedNormal};
/// # use fixshade::render::{CachedVertex, RenderOptions, Renderer};
/// # use fixshade::{Mat4, Material, Rgb};
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
/// # const BOX: Bounds = Bounds::from_bits([0; 3], [2 << 24; 3]);
/// # let mesh = Mesh::new(&P, BOX, &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// # let renderer = Renderer::<_, InfiniteViewer, _>::new(
/// #     &camera, Mat4::IDENTITY, &Material::new(), Rgb::BLACK, &sun, RenderOptions::default(),
/// # );
/// use fixshade::framebuffer::Framebuffer;
/// use fixshade::render::{Gouraud, NoDepth, RenderError};
/// let mut px = [0u16; 32 * 32];
/// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
/// let mut short = [CachedVertex::default(); 2]; // the mesh has 3 vertices
/// let e = renderer.draw_framebuffer::<Gouraud, _>(&mesh, &mut fb, &mut NoDepth, &mut short);
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

impl<S: Specular, V: Viewer, L: LightSet> Frame<'_, '_, S, V, L> {
    /// Projects every vertex of the mesh into `cache` (one per vertex), the
    /// vertex's work inlined in one loop instead of a call per vertex.
    #[inline(never)]
    pub(crate) fn project_all(&self, cache: &mut [CachedVertex]) {
        for (i, c) in cache.iter_mut().enumerate() {
            self.project_into(c, i);
        }
    }

    /// Transforms, projects and snaps mesh vertex `i` into `c` (no colour
    /// yet).
    #[inline(always)]
    pub(crate) fn project_into(&self, c: &mut CachedVertex, i: usize) {
        let clip = self.proj.clip(self.eye_inline(i));
        *c = CachedVertex::new();
        if clip[2] + clip[3] < 0 {
            return;
        }
        let w = self.window_inline(&clip);
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
        self.window_inline(&self.proj.clip(self.eye(i)))
    }

    /// Eye-space position of mesh vertex `i`.
    #[inline]
    pub(crate) fn eye(&self, i: usize) -> Vec3 {
        self.eye_inline(i)
    }

    /// [`Frame::eye`], always inlined: for the loops over every vertex.
    /// The mesh's `i16` position goes straight into the matrix that has
    /// the box folded in (no sum can overflow:
    /// [`Mat4::transform_quantised`](crate::vector::Mat4::transform_quantised)).
    #[inline(always)]
    pub(crate) fn eye_inline(&self, i: usize) -> Vec3 {
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
    /// a clip-space point in front of the near plane (SPEC.md 1, 5):
    /// `X = ⌊x_w·16 + ½⌋`, `Z = ⌊z_w·65535·2⁸ + 2⁷⌋` (clamped to ±2³⁰).
    ///
    /// The depth attribute is scaled so that `Z >> 8` is SPEC.md 5's
    /// quantised depth `d = ⌊z_w·65535 + ½⌋`: with `z_w = (z_c/w + 1)/2`,
    /// `z_w·65535·2⁸ + 2⁷ = z_c·K/w + 2²³` where `K = 65535·2⁷ = 2²³ − 2⁷`
    /// (the offset `65535·2⁷ + 2⁷` is `2²³`), so `Z = ⌊z_c·K/w⌋ + 2²³`, and
    /// `⌊⌊x⌋/2⁸⌋ = ⌊x/2⁸⌋` makes `Z >> 8 = ⌊z_w·65535 + ½⌋` exactly for the
    /// clip coordinates given. The span loop takes `Z >> 8` per pixel as
    /// before; only this per-vertex scale changed.
    ///
    /// `|x_c|, |z_c| < 2³⁸ + 2³¹` (a projection coefficient below 2³¹ raw
    /// times an `I8F24` coordinate, shifted by 24, plus an offset below
    /// 2³¹), `8W ≤ 2²³` and `2K < 2²⁴`: `|2·x_c·8W|`, `|z_c·2²⁴|` and
    /// `|2·z_c·K|` are below `2⁶² + 2⁵⁵`; with `0 < w < 2³²`, each
    /// numerator is within ±(2⁶² + 2⁵⁶), so it minus the divisor `2w`
    /// (below 2³³) stays within `i64` ([`floor_div_all`]'s conditions).
    #[inline(always)]
    fn window_inline(&self, c: &[i64; 4]) -> Win {
        let w = c[3];
        if w <= 0 {
            return [0, 0, 0];
        }
        let (hw, hh) = (8 * self.w, 8 * self.h);
        // x_w·16 = 8W·(x_c/w + 1); y_w·16 = 8H·(1 − y_c/w), each rounded
        // (the `+ w` over `2w`); the depth z_c·K/w floored, 2K = 2²⁴ − 2⁸.
        // The quotients are exact within ±2³¹, beyond which each clamp
        // below decides alike (the offsets 8W, 8H and 2²³ are at most 2²³,
        // the clamps at 2²⁸ and 2³⁰).
        let n = [
            mul_by_narrow(2 * c[0], hw) + w,
            mul_by_narrow(-2 * c[1], hh) + w,
            mul_by_narrow(c[2], (1 << 24) - (1 << 8)),
        ];
        let [x, y, z] = if crate::platform::SOFT_DIV64 {
            floor_div_all(n, 2 * w)
        } else {
            // (Each division written out: as an array map, x86-64 took
            // 4 to 36 instructions more per vertex, by scheduling.)
            [
                floor_div(n[0], 2 * w),
                floor_div(n[1], 2 * w),
                floor_div(n[2], 2 * w),
            ]
        };
        [
            (x + hw).clamp(-COORD_LIMIT, COORD_LIMIT) as i32,
            (y + hh).clamp(-COORD_LIMIT, COORD_LIMIT) as i32,
            (z + (1 << 23)).clamp(-(1 << 30), 1 << 30) as i32,
        ]
    }

    /// [`Frame::window_inline`], out of line: for the clipping paths.
    #[inline(never)]
    pub(crate) fn window(&self, c: &[i64; 4]) -> Win {
        self.window_inline(c)
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

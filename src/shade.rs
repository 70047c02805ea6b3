//! A triangle's shading: the attributes its mode interpolates (the depth,
//! and the lit colours of Gouraud shading, the normal and eye position of
//! Phong shading) or its one colour (flat shading), at the corners of the
//! pieces it is drawn in, handed to the set-up, the walk and the spans.
//! The lean path (`src/triangle.rs`) draws a triangle as one piece; the
//! rare path (`src/clip.rs`) draws what clipping leaves of it.

use core::mem::MaybeUninit;

use embedded_graphics::pixelcolor::raw::{RawData, RawU16};

use crate::color::Shade;
use crate::depth::DepthTest;
use crate::illumination::Viewer;
use crate::light::LightSet;
use crate::material::Specular;
use crate::mesh::face_normal;
use crate::num::division::{floor_third, recip_nodes};
use crate::options::{DrawStats, RenderOptions, ShadingKind, ShadingMode};
use crate::planes::{Planes, Row};
use crate::platform;
use crate::setup::{self, Rect, Samples, SetUp, Vtx};
use crate::span::{self, Out, Shader};
use crate::vector::{Unit3, Vec3};
use crate::vertex::{CachedVertex, Stage};
use crate::walk::CHUNK;

// The platform's Gouraud set-up writes at most 32 rows.
const _: () = assert!(CHUNK == 32);

/// One draw's constants and what it draws into: the vertex stage, the
/// switches, the pixels drawn.
pub(crate) struct Frame<'a, 'm, S: Specular, V: Viewer, L: LightSet> {
    pub(crate) stage: Stage<'a, 'm, S, V, L>,
    pub(crate) options: RenderOptions,
    /// The target's size.
    pub(crate) size: (u32, u32),
    /// The target pixel at the set-up's origin (its centre, rounded down).
    pub(crate) origin: (i32, i32),
    /// The pixels drawn, from the origin: the target's, or a band's rows.
    pub(crate) rect: Rect,
}

/// Where a triangle's vertices are: `cache[slot[k]]` is mesh vertex
/// `vertex[k]`, projected.
pub(crate) struct Corners<'c> {
    pub(crate) cache: &'c mut [CachedVertex],
    pub(crate) slot: [usize; 3],
    pub(crate) vertex: [usize; 3],
}

/// The target pixel at the set-up's origin (the centre, rounded down) and
/// the target's pixels from there, for a target of `size` (at most 2²⁰ a
/// side).
pub(crate) fn rect_of(size: (u32, u32)) -> ((i32, i32), Rect) {
    let (w, h) = (size.0 as i32, size.1 as i32);
    let origin = (w >> 1, h >> 1);
    let rect = Rect {
        c0: -origin.0,
        c1: w - 1 - origin.0,
        r0: -origin.1,
        r1: h - 1 - origin.1,
    };
    (origin, rect)
}

impl<S: Specular, V: Viewer, L: LightSet> Frame<'_, '_, S, V, L> {
    /// Lights and draws triangle `c` as it is (the lean path): of doubled
    /// area `area` (not 0), its samples on the frame's rectangle `s`, its
    /// corners' window positions and depths `p` where the caller has read
    /// them.
    ///
    /// # Safety
    /// Every `c.slot[k] < c.cache.len()` (`Frame::triangle`'s contract):
    /// the corners' positions are read without bounds checks.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) unsafe fn whole<M: ShadingMode, O: Out, D: DepthTest>(
        &self,
        c: &mut Corners,
        p: Option<[[i32; 3]; 3]>,
        area: i32,
        s: &Samples,
        out: &mut O,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), O::Error> {
        let back = area > 0 && self.options.two_sided;
        let rect = &self.rect;
        // SAFETY: the contract above.
        let corners = |c: &Corners| {
            p.unwrap_or_else(|| {
                c.slot
                    .map(|k| unsafe { c.cache.get_unchecked(k) }.position())
            })
        };
        // Vertex k with attributes `a`, its depth first.
        fn vtx<const N: usize>(p: &[i32; 3], mut a: [i32; N]) -> Vtx<N> {
            a[0] = p[2];
            Vtx {
                x: p[0],
                y: p[1],
                a,
            }
        }
        match M::KIND {
            ShadingKind::Gouraud => {
                if platform::GOURAUD_SET_UP && !back && !s.clamp {
                    // SAFETY: the contract above.
                    if let Some(res) = unsafe { self.gouraud_in_one(c, area, s, out, depth, stats) }
                    {
                        return res;
                    }
                }
                let a = self.gouraud(c, back, stats);
                let p = corners(c);
                let v = [vtx(&p[0], a[0]), vtx(&p[1], a[1]), vtx(&p[2], a[2])];
                self.gouraud_draw(&v, area, s, rect, out, depth, stats)
            }
            ShadingKind::Flat => {
                let sh = self.flat(c, back, stats);
                let p = corners(c);
                let v = [vtx(&p[0], [0]), vtx(&p[1], [0]), vtx(&p[2], [0])];
                self.draw(&v, area, s, rect, out, depth, stats, &sh)
            }
            ShadingKind::Phong => {
                let (e, n) = self.phong_corners(c, back);
                let (a, sh) = self.phong(e, n);
                let p = corners(c);
                let v = [vtx(&p[0], a[0]), vtx(&p[1], a[1]), vtx(&p[2], a[2])];
                self.draw(&v, area, s, rect, out, depth, stats, &sh)
            }
        }
    }

    /// Lights and draws the triangles `tris` (corner indices into
    /// `corners`: window position and depth attribute from the set-up's
    /// origin) cut from the triangle `c`, whose facing is `facing`'s sign;
    /// corner `k`'s other attributes are the triangle's vertices' mixed by
    /// `w[k]` (`Q.30` weights, `src/clip.rs`), drawn on `rect`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn pieces<M: ShadingMode, O: Out, D: DepthTest>(
        &self,
        c: &mut Corners,
        corners: &[(i32, i32, i32)],
        w: &[[i32; 3]],
        tris: &[[usize; 3]],
        facing: i32,
        rect: &Rect,
        out: &mut O,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), O::Error> {
        let back = facing > 0 && self.options.two_sided;
        let corner = |k: usize| corners.get(k).copied().unwrap_or((0, 0, 0));
        let weights = |k: usize| w.get(k).copied().unwrap_or([1 << 30, 0, 0]);
        match M::KIND {
            ShadingKind::Gouraud => {
                let a = self.gouraud(c, back, stats);
                for t in tris {
                    let v = t.map(|k| {
                        let (x, y, z) = corner(k);
                        let mut a = mix(weights(k), &a);
                        a[0] = z;
                        Vtx { x, y, a }
                    });
                    if let Some((a, s)) = area_and_samples(&v, rect) {
                        self.gouraud_draw(&v, a, &s, rect, out, depth, stats)?;
                    }
                }
                Ok(())
            }
            ShadingKind::Flat => {
                let sh = self.flat(c, back, stats);
                for t in tris {
                    let v = t.map(|k| {
                        let (x, y, z) = corner(k);
                        Vtx { x, y, a: [z] }
                    });
                    if let Some((a, s)) = area_and_samples(&v, rect) {
                        self.draw(&v, a, &s, rect, out, depth, stats, &sh)?;
                    }
                }
                Ok(())
            }
            ShadingKind::Phong => {
                let (e, n) = self.phong_corners(c, back);
                // Positions relative to vertex 0 (differences below 2³²).
                let rel = e.map(|p| [0, 1, 2].map(|j| p[j] - e[0][j]));
                for t in tris {
                    let pe = t.map(|k| {
                        let d = mix_wide(weights(k), &rel);
                        [0, 1, 2].map(|j| e[0][j] + d[j])
                    });
                    let (a, sh) = self.phong(pe, t.map(|k| mix(weights(k), &n)));
                    let v = [0, 1, 2].map(|j| {
                        let (x, y, z) = corner(t[j]);
                        let mut a = a[j];
                        a[0] = z;
                        Vtx { x, y, a }
                    });
                    if let Some((a, s)) = area_and_samples(&v, rect) {
                        self.draw(&v, a, &s, rect, out, depth, stats, &sh)?;
                    }
                }
                Ok(())
            }
        }
    }

    /// Gouraud attributes of the three vertices (depth left 0): each lit
    /// colour's 5/6-bit channels times 2¹⁶, plus ½ (SPEC.md 6), at most
    /// 63.5·2¹⁶ < 2²² and at least 2¹⁵ inside their fields.
    #[inline(always)]
    fn gouraud(&self, c: &mut Corners, back: bool, stats: &mut DrawStats) -> [[i32; 4]; 3] {
        let ch = |v: u32, m: u32| (v * m + (1 << 15)) as i32;
        let a = |s: Shade| {
            let b = s.to_bits();
            [0, ch(b[0], 31), ch(b[1], 63), ch(b[2], 31)]
        };
        let [s0, s1, s2] = self.shades(c, back, stats);
        [a(s0), a(s1), a(s2)]
    }

    /// Sets up and draws front-lit Gouraud triangle `c` (doubled area
    /// `area`, samples `s`, no span that needs a clamp) with the platform's
    /// one-routine set-up ([`platform::gouraud_set_up`]), its corners lit
    /// first; `None` where that leaves it to the set-up in Rust (a corner
    /// whose entry keeps the back face's colour, more rows than a table,
    /// a steep plane), which then finds the same spans and planes.
    /// Out of line, as [`Frame::draw`] is: the row loop gets the registers.
    ///
    /// # Safety
    /// Every `c.slot[k] < c.cache.len()` ([`Frame::whole`]'s contract).
    #[inline(never)]
    unsafe fn gouraud_in_one<O: Out, D: DepthTest>(
        &self,
        c: &mut Corners,
        area: i32,
        s: &Samples,
        out: &mut O,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Option<Result<(), O::Error>> {
        let mut entries = [core::ptr::null(); 3];
        for (k, e) in entries.iter_mut().enumerate() {
            // SAFETY: the contract above.
            let v = unsafe { c.cache.get_unchecked_mut(c.slot[k]) };
            if !self.stage.lit_front(v, c.vertex[k], stats) {
                return None;
            }
            *e = (v as *const CachedVertex).cast::<u32>();
        }
        let mut planes = MaybeUninit::<Planes<4>>::uninit();
        let mut table = [MaybeUninit::<Row>::uninit(); CHUNK];
        // Undithered rows in stores that hold the draw's rect: drawn by
        // the routine itself.
        let stores = if self.options.dither {
            None
        } else {
            out.row_stores(depth, s.rows.0)
        };
        let (cbase, zbase, stride) = match &stores {
            Some(t) => (t.colour, t.depth, t.stride),
            None => (core::ptr::null_mut(), core::ptr::null_mut(), 0),
        };
        let args = platform::GouraudSetUp {
            entries,
            area,
            first_row: s.rows.0,
            last_row: s.rows.1,
            nodes: recip_nodes(),
            planes: planes.as_mut_ptr(),
            table: table.as_mut_ptr().cast::<Row>(),
            cbase,
            stride,
            zbase,
        };
        // SAFETY: three cache entries lit for the front face, the
        // reciprocals' table, a slot for the planes and a table of CHUNK
        // (32) rows; the stores hold every row of the draw's rect (in
        // which the samples `s` lie, with the columns of every span: no
        // span of this triangle needs a clamp).
        let n = unsafe { platform::gouraud_set_up(&args) }?;
        stats.drawn = stats.drawn.saturating_add(1);
        if stores.is_some() {
            stats.pixels = stats.pixels.saturating_add(n as u32);
            return Some(Ok(()));
        }
        if n == 0 {
            return Some(Ok(()));
        }
        // SAFETY: the routine wrote the planes and the first `n` rows.
        let (planes, rows) = unsafe {
            (
                planes.assume_init_ref(),
                core::slice::from_raw_parts(table.as_ptr().cast::<Row>(), n),
            )
        };
        let sh = span::Gouraud {
            dither: self.options.dither,
        };
        let rect = &self.rect;
        let res = out.rows(depth, rows, (s.rows.0, 0), (rect.c0, rect.c1), planes, &sh);
        if let Ok(w) = res {
            stats.pixels = stats.pixels.saturating_add(w);
        }
        Some(res.map(|_| ()))
    }

    /// Sets up and draws Gouraud triangle `v`, dithered or not.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn gouraud_draw<O: Out, D: DepthTest>(
        &self,
        v: &[Vtx<4>; 3],
        area: i32,
        s: &Samples,
        rect: &Rect,
        out: &mut O,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), O::Error> {
        let sh = span::Gouraud {
            dither: self.options.dither,
        };
        self.draw(v, area, s, rect, out, depth, stats, &sh)
    }

    /// The flat shader: the equation at the centroid with the face normal.
    fn flat(&self, c: &Corners, back: bool, stats: &mut DrawStats) -> span::Flat {
        let e = c.vertex.map(|i| self.stage.eye(i));
        let n = face_normal(e[0], e[1], e[2]).unwrap_or(Unit3::ZERO);
        let n = if back { n.neg() } else { n };
        let shade = self.stage.lighting.shade(centroid(e), n);
        stats.lit = stats.lit.saturating_add(1);
        span::Flat {
            plain: RawU16::from(shade.to_rgb565()).into_inner(),
            shade,
            dither: self.options.dither,
        }
    }

    /// The three vertices' eye positions (raw) and normals (`Q.22`, below
    /// 2²³: 8 more fractional bits than a unit vector's), for the back if
    /// `back`.
    fn phong_corners(&self, c: &mut Corners, back: bool) -> ([[i64; 3]; 3], [[i32; 3]; 3]) {
        let e = c.vertex.map(|i| self.stage.eye(i).to_bits().map(i64::from));
        let n = [0, 1, 2].map(|k| {
            let n = match c.cache.get_mut(c.slot[k]) {
                Some(v) => self.stage.normal(v, c.vertex[k]),
                None => Unit3::ZERO,
            };
            let n = if back { n.neg() } else { n };
            n.to_bits().map(|v| (v as i32) << 8)
        });
        (e, n)
    }

    /// Phong attributes of three corners (eye positions `e`, normals `n`;
    /// depth left 0) and their shader: eye positions relative to corner
    /// 0's, shifted right until every difference is below 2²⁴ (the
    /// set-up's attributes stay within ±2²⁵): full precision for a small
    /// triangle, 2⁻²⁴ of its extent for a large one. (A piece the rare
    /// path cuts from a triangle gets its own: its extent, not the
    /// triangle's, sets the precision.) Out of line: written once for
    /// both paths.
    #[inline(never)]
    fn phong(
        &self,
        e: [[i64; 3]; 3],
        n: [[i32; 3]; 3],
    ) -> ([[i32; 7]; 3], span::Phong<'_, S, V, L>) {
        let origin = e[0];
        let mut spread = 0u64;
        for p in &e[1..] {
            for k in 0..3 {
                spread = spread.max((p[k] - origin[k]).unsigned_abs());
            }
        }
        let shift = (64 - spread.leading_zeros()).saturating_sub(24);
        let a = [0, 1, 2].map(|k| {
            let rel = |j: usize| ((e[k][j] - origin[j]) >> shift) as i32;
            [0, n[k][0], n[k][1], n[k][2], rel(0), rel(1), rel(2)]
        });
        let sh = span::Phong::new(self.stage.lighting, origin, shift, self.options.dither);
        (a, sh)
    }

    /// The three corners' lit colours (Gouraud), for the back if `back`.
    #[inline(always)]
    fn shades(&self, c: &mut Corners, back: bool, stats: &mut DrawStats) -> [Shade; 3] {
        [
            self.corner_shade(c, 0, back, stats),
            self.corner_shade(c, 1, back, stats),
            self.corner_shade(c, 2, back, stats),
        ]
    }

    /// Corner `k`'s lit colour: the cached one, or lit now (out of line).
    #[inline(always)]
    fn corner_shade(&self, c: &mut Corners, k: usize, back: bool, stats: &mut DrawStats) -> Shade {
        match c.cache.get_mut(c.slot[k]) {
            Some(v) => self.stage.shade(v, c.vertex[k], back, stats),
            None => Shade::BLACK,
        }
    }

    /// Sets up and walks one triangle `v` of doubled area `area` (not 0)
    /// on `rect`, where its samples are `s`, sending its rows' spans
    /// through `sh` (the depth left out without a depth test). Out of
    /// line: its row and pixel loops get the registers, not the triangle
    /// loop's state.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn draw<const N: usize, O: Out, D: DepthTest, Sh: Shader<N>>(
        &self,
        v: &[Vtx<N>; 3],
        area: i32,
        s: &Samples,
        rect: &Rect,
        out: &mut O,
        depth: &mut D,
        stats: &mut DrawStats,
        sh: &Sh,
    ) -> Result<(), O::Error> {
        let mut slot = MaybeUninit::uninit();
        let mut table = [MaybeUninit::uninit(); CHUNK];
        let (planes, walk) = match setup::set_up(v, area, s, rect, &mut slot, &mut table) {
            // Counted as set up, as a walk of empty rows would be.
            SetUp::Uncovered => {
                stats.drawn = stats.drawn.saturating_add(1);
                return Ok(());
            }
            // Most triangles: every row at once, one call of the output.
            SetUp::Rows { planes, rows, y } => {
                stats.drawn = stats.drawn.saturating_add(1);
                let res = out.rows(depth, rows, (y, 0), (rect.c0, rect.c1), planes, sh);
                if let Ok(w) = res {
                    stats.pixels = stats.pixels.saturating_add(w);
                }
                return res.map(|_| ());
            }
            SetUp::Walk(setup::Triangle { planes, walk }) => (planes, walk),
        };
        stats.drawn = stats.drawn.saturating_add(1);
        // A triangle's pixels are at most 2¹¹ × 2¹¹: no overflow.
        let (mut pixels, top) = (0u32, walk.y);
        let res = loop {
            let y = walk.y;
            let rows = walk.fill(&mut table);
            if rows.is_empty() {
                break Ok(());
            }
            match out.rows(depth, rows, (y, y - top), walk.cols, planes, sh) {
                Ok(w) => pixels += w,
                Err(e) => break Err(e),
            }
        };
        stats.pixels = stats.pixels.saturating_add(pixels);
        res
    }
}

/// A piece's doubled area and its samples on `rect`, if it has an area
/// and a row of samples there.
fn area_and_samples<const N: usize>(v: &[Vtx<N>; 3], rect: &Rect) -> Option<(i32, Samples)> {
    let a = setup::area(v);
    if a == 0 {
        return None;
    }
    Some((a, setup::samples(v, rect)?))
}

/// Attributes mixed from the three vertices' `a` by `Q.30` weights `w`
/// (summing to 2³⁰): `|a| < 2²⁶`, so each product is below 2⁵⁶. Out of
/// line: the rare path's, once a corner.
#[inline(never)]
fn mix<const N: usize>(w: [i32; 3], a: &[[i32; N]; 3]) -> [i32; N] {
    core::array::from_fn(|i| {
        let s: i64 = (0..3).map(|j| w[j] as i64 * a[j][i] as i64).sum();
        ((s + (1 << 29)) >> 30) as i32
    })
}

/// Values below 2³² in magnitude mixed by `Q.30` weights `w` (summing to
/// 2³⁰), rounded: each product below 2⁶², their sum too.
fn mix_wide(w: [i32; 3], a: &[[i64; 3]; 3]) -> [i64; 3] {
    core::array::from_fn(|i| {
        let s: i64 = (0..3).map(|j| w[j] as i64 * a[j][i]).sum();
        (s + (1 << 29)) >> 30
    })
}

/// The centroid of three eye-space points, each coordinate `⌊(2s +
/// 3)/6⌋` of its sum `s` (a third, rounded half up), in 32-bit steps: with
/// each `bₖ = 3qₖ + rₖ` (`rₖ ∈ {0, 1, 2}`, [`floor_third`]), `s = 3Σq +
/// Σr`, so the value is `Σq + ⌊(2Σr + 3)/6⌋`: 1 from `Σr = 2` on, 2
/// from 5.
fn centroid(e: [Vec3; 3]) -> Vec3 {
    let b = [e[0].to_bits(), e[1].to_bits(), e[2].to_bits()];
    let mut c = [0; 3];
    for (k, out) in c.iter_mut().enumerate() {
        // Wrapping: the value lies within `i32`, the sums may pass its
        // ends on the way (three coordinates at `i32::MIN`).
        let (mut q, mut r) = (0i32, 0i32);
        for v in &b {
            let t = floor_third(v[k]);
            q = q.wrapping_add(t);
            r += v[k].wrapping_sub(t.wrapping_mul(3));
        }
        *out = q.wrapping_add(i32::from(r >= 2) + i32::from(r >= 5));
    }
    Vec3::from_bits(c[0], c[1], c[2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::xorshift;

    /// The centroid is the sums' third rounded half up, with coordinates
    /// at `i32`'s ends and between.
    #[test]
    fn centroid_is_the_rounded_third() {
        let mut next = xorshift(0x1319_8a2e_0370_7344);
        for i in 0..100_000 {
            let mut r = || {
                let v = next() as i32 >> (next() % 32);
                if i % 7 == 0 {
                    [i32::MAX, i32::MIN, -1][(next() % 3) as usize]
                } else {
                    v
                }
            };
            let p = [[r(), r(), r()], [r(), r(), r()], [r(), r(), r()]];
            let c = centroid(p.map(|v| Vec3::from_bits(v[0], v[1], v[2]))).to_bits();
            for k in 0..3 {
                let s: i64 = p.iter().map(|v| v[k] as i64).sum();
                assert_eq!(c[k] as i64, (2 * s + 3).div_euclid(6), "{p:?}");
            }
        }
    }
}

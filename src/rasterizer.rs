//! The rasterizer's standalone entry (compiled for the tests; the renderer
//! calls the set-up itself): one triangle of window positions, its
//! spans through a callback. It runs the renderer's own set-up and walk
//! (`src/setup.rs`: 32-bit edges and attribute planes), with the same
//! limits: vertices within the guard band around the clip rectangle's
//! centre ([`GUARD`]), attributes within ±[`ATTR_LIMIT`], a clip rectangle
//! of at most [`CLIP_LIMIT`] pixels a side. The renderer keeps its
//! triangles inside them by clipping in clip space.
//!
//! # Coverage (SPEC.md 5)
//! Vertices are in 1/16 pixel. Sample `(16x + 8, 16y + 8)` is inside where
//! every edge function `E_ab(p) = (b.x−a.x)(p.y−a.y) − (b.y−a.y)(p.x−a.x)`
//! of the positively oriented triangle is positive, or zero on a top-left
//! edge: two triangles that share an edge draw each sample on it once.
//!
//! Also here: the tiny-box coverage test (`coverage`) and the area
//! reciprocal (`Recip`) that the set-up shares.

use crate::num::division::recip63;
use crate::num::widening::{mul_narrow, mul_u32};
use crate::setup;

/// Sub-pixel bits of the snapping grid (SPEC.md 5: 1/16 pixel).
#[cfg(test)]
pub(crate) const SUBPIXEL_BITS: u32 = 4;

/// The renderer clamps window positions to ±2²⁸ (1/16 pixel, ±2²⁴ pixels):
/// past it a vertex moves (SPEC.md departures); the guard band's clipping
/// takes every polygon inside [`GUARD`] of a tile's centre from there.
pub(crate) const COORD_LIMIT: i64 = 1 << 28;

/// How far a vertex may lie from the clip rectangle's centre pixel corner,
/// in 1/16 pixel, on each axis (±1 023 pixels): then every edge function,
/// area and step of the set-up fits `i32`.
// rustc before 1.88 does not count the compile-time assertion below as a use.
#[allow(dead_code)]
pub(crate) const GUARD: i64 = setup::GUARD as i64;

/// Attributes lie within `±ATTR_LIMIT` (2²⁵), so that the set-up's
/// differences, with four fractional bits, fit 32 bits.
#[cfg(test)]
pub(crate) const ATTR_LIMIT: i64 = setup::ATTR as i64;

/// A triangle vertex in window space: position in 1/16 pixel and `N`
/// attributes in the caller's units.
///
/// [`rasterize`] draws nothing for a triangle with a vertex outside the
/// limits ([`GUARD`], [`ATTR_LIMIT`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct RasterVertex<const N: usize> {
    /// x in 1/16 pixel, within [`GUARD`] of the clip rectangle's centre.
    pub(crate) x: i64,
    /// y in 1/16 pixel (down), within [`GUARD`] of the clip rectangle's centre.
    pub(crate) y: i64,
    /// Attributes, each within ±[`ATTR_LIMIT`].
    pub(crate) attr: [i64; N],
}

/// The inclusive pixel rectangle that may be drawn (the target's bounds),
/// at most [`CLIP_LIMIT`] pixels a side for the rasterizer to draw in it
/// (see [`ClipRect::within_limits`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ClipRect {
    /// First column.
    pub(crate) x0: i32,
    /// First row.
    pub(crate) y0: i32,
    /// Last column (inclusive).
    pub(crate) x1: i32,
    /// Last row (inclusive).
    pub(crate) y1: i32,
}

/// The most pixels a [`ClipRect`] may span on either axis: a tile of the
/// renderer, whose guard band ([`GUARD`]) holds it with two pixels to
/// spare.
pub(crate) const CLIP_LIMIT: i64 = 2032;
const _: () = assert!(8 * CLIP_LIMIT + 32 <= GUARD - 40);

impl ClipRect {
    /// Whether the rasterizer draws in this rectangle: each side at most
    /// [`CLIP_LIMIT`] pixels (an empty rectangle, `x0 > x1` or `y0 > y1`,
    /// qualifies and draws nothing).
    #[cfg(test)]
    #[inline]
    pub(crate) fn within_limits(&self) -> bool {
        let side = |a: i32, b: i32| (b as i64) - (a as i64) < CLIP_LIMIT;
        side(self.x0, self.x1) && side(self.y0, self.y1)
    }

    /// The rectangle of a `width × height` target at the origin; `None`
    /// when it is empty.
    pub(crate) fn of_size(width: u32, height: u32) -> Option<ClipRect> {
        if width == 0 || height == 0 {
            return None;
        }
        Some(ClipRect {
            x0: 0,
            y0: 0,
            x1: (width.min(i32::MAX as u32) - 1) as i32,
            y1: (height.min(i32::MAX as u32) - 1) as i32,
        })
    }
}

/// Which way a triangle faces on screen.
#[cfg(test)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Facing {
    /// Counter-clockwise in NDC (clockwise on screen, y down).
    Front,
    /// Clockwise in NDC.
    Back,
}

/// The signed doubled area `E_{01}(v2)` in 1/256 pixel²: negative for a
/// front face (counter-clockwise in NDC; window y points down). The
/// vertices must be within the limits (see [`RasterVertex`]).
#[inline]
pub(crate) fn area2<const N: usize>(v: &[RasterVertex<N>; 3]) -> i64 {
    // Coordinates within ±2^28: differences within ±2^29.
    mul_narrow(v[1].x - v[0].x, v[2].y - v[0].y) - mul_narrow(v[1].y - v[0].y, v[2].x - v[0].x)
}

/// The most pixel centres a triangle's box may hold for the renderer to
/// test them one by one ([`coverage`]) before it lights an unclipped
/// triangle: one that covers none is dropped. At most 32 (the mask's bits).
pub(crate) const TINY: i64 = 4;
const _: () = assert!(TINY <= 32);

/// Which pixel centres of columns `xs.0 ..= xs.1` and rows
/// `ys.0 ..= ys.1` (at most 32 in all) the oriented triangle `v`
/// (positions in 1/16 pixel, positive area) covers, by the rule the set-up
/// follows: bit `w·(y − ys.0) + (x − xs.0)` for centre `(x, y)`, `w`
/// the box's width. For each edge `a → b`,
/// `E = dx·(py − a.y) − dy·(px − a.x)`, `E ≥ 0` on a left (`dy < 0`) or
/// top (`dy = 0`, `dx > 0`) edge, `E > 0` on the others. A row's covered
/// centres are contiguous, as are a column's (each `E` admits a
/// half-line of any line, or all of it, or none).
///
/// Positions are taken relative to the box's first centre, where each
/// `E` is computed, then stepped (`−16·dy` a column, `16·dx` a row). The
/// box lies within the vertices' box, so each relative coordinate and
/// each difference is at most 2²⁹, each product at most 2⁵⁸, and `E` at any
/// centre of the box or one step beyond it below 2⁶⁰ in magnitude: `i64`.
/// On 32-bit targets, vertices within 2¹⁴ of that centre (any tiny
/// triangle not far across the viewport's edge) take `i32`: differences
/// below 2¹⁵, products below 2²⁹, `E` at the first centre below 2³⁰, and
/// at most 32 column and 32 row steps of at most 2¹⁹ each from there
/// leave it below 2³¹ (a row's wrap, `16·dx − (w − 1)·(−16·dy)`, is
/// below 2²⁴).
#[inline]
pub(crate) fn coverage(v: [(i64, i64); 3], xs: (i64, i64), ys: (i64, i64)) -> u32 {
    let (w, h) = (xs.1 - xs.0 + 1, ys.1 - ys.0 + 1);
    debug_assert!(w >= 1 && h >= 1 && w * h <= 32);
    let (px, py) = (16 * xs.0 + 8, 16 * ys.0 + 8);
    let rel = v.map(|p| (p.0 - px, p.1 - py));
    let near = rel
        .iter()
        .all(|p| p.0.unsigned_abs() < 1 << 14 && p.1.unsigned_abs() < 1 << 14);
    if !crate::platform::wide_pointer() && near {
        coverage_from(rel.map(|p| (p.0 as i32, p.1 as i32)), w as u32, h as u32)
    } else {
        coverage_from(rel, w as u32, h as u32)
    }
}

/// [`coverage`] of a `w × h` box with the triangle's vertices relative to
/// its first centre, in `i32` or `i64` (see there for the ranges).
#[inline(always)]
fn coverage_from<T>(v: [(T, T); 3], w: u32, h: u32) -> u32
where
    T: Copy
        + PartialOrd
        + From<i8>
        + core::ops::Add<Output = T>
        + core::ops::Sub<Output = T>
        + core::ops::Mul<Output = T>
        + core::ops::BitOr<Output = T>,
{
    let (zero, sixteen) = (T::from(0), T::from(16));
    let mut e = [zero; 3];
    let mut step_x = [zero; 3];
    let mut wrap = [zero; 3];
    for k in 0..3 {
        let (a, b) = (v[k], v[(k + 1) % 3]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        // Inclusive edges admit E = 0. Kept as E − 1 (exclusive) or E
        // (inclusive), a centre is inside when all three are ≥ 0: when
        // their bitwise or is.
        let inclusive = dy < zero || (dy == zero && dx > zero);
        e[k] = dy * a.0 - dx * a.1 - T::from(if inclusive { 0 } else { 1 });
        step_x[k] = zero - sixteen * dy;
        // A row's last centre steps to the next row's first (w ≤ 32).
        wrap[k] = sixteen * dx - T::from((w - 1) as i8) * step_x[k];
    }
    // One loop over the centres, row by row (the compiler would vectorise
    // nested loops, a loss at a few centres).
    let (mut mask, mut col) = (0u32, 1);
    for bit in 0..w * h {
        mask |= (((e[0] | e[1] | e[2]) >= zero) as u32) << bit;
        let step = if col == w { &wrap } else { &step_x };
        col = if col == w { 1 } else { col + 1 };
        for k in 0..3 {
            e[k] = e[k] + step[k];
        }
    }
    mask
}

/// What the caller of the set-up knows of a triangle's tiny box
/// ([`TINY`], [`coverage`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Cover {
    /// Nothing: the set-up tests a tiny box itself.
    Untested,
    /// Its box is known not to be tiny, or need not be tested.
    Skip,
    /// Its box is tiny, all in the rows drawn, and this is its coverage
    /// (not zero: an empty one is dropped before the set-up).
    Mask(u32),
}

/// `1 / area` as a 32-bit mantissa and a shift: `1/a ≈ m / 2^sh`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Recip {
    /// In `(2^31, 2^32]`.
    m: i64,
    sh: u32,
}

impl Recip {
    /// For `a > 0` (at most 2⁶⁰).
    pub(crate) fn new(a: i64) -> Recip {
        let a = a as u64;
        let hi = (a >> 32) as u32;
        let bits = if hi != 0 {
            64 - crate::platform::leading_zeros(hi)
        } else {
            32 - crate::platform::leading_zeros(a as u32)
        };
        // a ≈ a32 · 2^e with a32 ∈ [2^31, 2^32).
        // (A 64-bit shift by a variable amount is a library call on a
        // Cortex-M0: the common case, `a < 2³²`, shifts the low word.)
        let (a32, e) = if bits > 32 {
            (a >> (bits - 32), (bits - 32) as i32)
        } else {
            (((a as u32) << (32 - bits)) as u64, -((32 - bits) as i32))
        };
        // 1/a ≈ (2^63 / a32) · 2^−(63 + e); 2^63/a32 ∈ (2^31, 2^32].
        Recip {
            // (The plain division where it is one instruction, written
            // on the `u64`: through a `u32` argument x86-64 took 1.8 % more
            // on S1 in flat shading, from instruction selection.)
            m: if crate::platform::SOFT_DIV64 {
                recip63(a32 as u32)
            } else {
                (1u64 << 63) / a32
            } as i64,
            sh: (63 + e) as u32,
        }
    }

    /// As [`Recip::div`] for `|num| < 2⁶³`: [`Recip::div_i64_wide`] on
    /// 64-bit targets; on 32-bit ones [`Recip::div_i64_narrow`] where it
    /// applies (a numerator below 2³¹ and a shift below 64), else
    /// [`Recip::div_i64_limbs`]; all three give the same value. (On x86-64
    /// the narrow form measured dearer: callgrind S1 +2.8 %.)
    #[inline(always)]
    pub(crate) fn div_i64(self, num: i64, up: u32) -> i128 {
        let sh = self.sh - up;
        if crate::platform::wide_pointer() {
            self.div_i64_wide(num, up)
        } else if sh < 64 && num.unsigned_abs() < NARROW_NUM {
            self.div_i64_narrow(num, sh) as i128
        } else {
            self.div_i64_limbs(num, up)
        }
    }

    /// `num / (a·2^down)` rounded to nearest (halves away from zero), for
    /// any `num` and `down`, where the quotients that matter are below
    /// `2^bits` (`bits ≤ 29`): within `2^(bits − 30)` of the exact quotient
    /// `q` (plus the rounding's ½) while `|q| < 2^bits`, within `|q|·2⁻²⁹`
    /// beyond, or ±[`QUOT_SAT`] where `|q|` reaches 2³¹ (a result the
    /// callers clamp anyway).
    ///
    /// `q = num·m/2^t`, `t = sh + down`, `m ∈ (2³¹, 2³²]`. A quotient
    /// below `2^bits` has `|num| < 2^(bits + t − 31)`: shifted right by `s =
    /// max(0, bits + t − 62)` it is below 2³¹ (`n`), and `n·m/2^(t − s)`,
    /// `t − s ≥ 33` (for `t ≥ 33`), rounds from the product's high word
    /// alone: `⌊⌊p/2³²⌋/2^(t − s − 33)⌋ = ⌊2p/2^(t − s)⌋`, whose half rounded
    /// up is the nearest. The bits dropped from `num` move `q` by at most
    /// `m/2^(t − s) ≤ 2^(bits − 30)`, `m`'s relative error of 2⁻³¹ by
    /// `|q|·2⁻³¹`. A larger numerator (a far vertex), or `t < 33`, takes
    /// [`Recip::div_normalised`].
    #[inline(always)]
    pub(crate) fn div_scaled(self, num: i64, down: i32, bits: i32) -> i64 {
        debug_assert!(bits <= 29);
        let t = self.sh as i32 + down;
        let s = (bits + t - 62).max(0) as u32;
        let a = num.unsigned_abs();
        match shr_u64_below_2_31(a, s) {
            Some(n) if t >= 33 => {
                let m = self.m as u64;
                // ⌊n·m/2³²⌋ (m = 2³² has a zero low word: then n).
                let hi = if m >> 32 != 0 {
                    n
                } else {
                    (mul_u32(n, m as u32) >> 32) as u32
                };
                let q = ((hi >> (t as u32 - s - 33)) + 1) >> 1;
                if num >= 0 {
                    q as i64
                } else {
                    -(q as i64)
                }
            }
            _ => self.div_normalised(num, t),
        }
    }

    /// [`Recip::div_scaled`] for any numerator and shift `t`: the numerator
    /// cut to its top 31 bits (`n ≥ 2³⁰` when any were dropped, a relative
    /// error below 2⁻³⁰), so the quotient is within `½ + |q|·2⁻²⁹`. With
    /// the shift below 1, `|q| ≥ n·m/2 ≥ 2³⁰` for `n ≥ 1`; above 63,
    /// `|q| < 2⁶³/2⁶⁴` rounds to 0. (Rare: far vertices.)
    #[inline(never)]
    fn div_normalised(self, num: i64, t: i32) -> i64 {
        let a = num.unsigned_abs();
        let s = (64 - a.leading_zeros()).saturating_sub(31);
        let n = (a >> s) as i64;
        let n = if num < 0 { -n } else { n };
        let sh = t - s as i32;
        if sh < 1 {
            n.signum() * QUOT_SAT
        } else if sh > 63 {
            0
        } else {
            self.div_i64_narrow(n, sh as u32)
        }
    }

    /// [`Recip::div_i64`] in 64-bit arithmetic, for `|num| < 2³¹` and a
    /// shift `sh = self.sh − up` in `1 ..= 63` (`self.sh ≥ 32` and `up ≤ 8`
    /// give `sh ≥ 24`): the magnitude's product `P = |num|·m < 2⁶³`
    /// (`m ≤ 2³²`) plus the rounding term `h = 2^(sh−1) ≤ 2⁶²` stays below
    /// 2⁶⁴, and, as in [`Recip::div_i64_limbs`], `−⌊(P + h − 1)/2^sh⌋` is
    /// the negative numerator's quotient with the same rounding. One
    /// 32 × 32 → 64-bit product (`m = 2³²` has a zero low word: then
    /// `|num| · 2³²`) where the limb form takes two and `u128` sums.
    #[inline]
    fn div_i64_narrow(self, num: i64, sh: u32) -> i64 {
        debug_assert!(num.unsigned_abs() < NARROW_NUM && (1..64).contains(&sh));
        let (n, m) = (num.unsigned_abs(), self.m as u64);
        let p = mul_u32(n as u32, m as u32) + if m >> 32 != 0 { n << 32 } else { 0 };
        let h = 1u64 << (sh - 1);
        if num >= 0 {
            ((p + h) >> sh) as i64
        } else {
            -(((p + h - 1) >> sh) as i64)
        }
    }

    /// [`Recip::div_i64`] as one signed 64 × 64 → 128-bit multiply.
    #[inline]
    fn div_i64_wide(self, num: i64, up: u32) -> i128 {
        let sh = self.sh - up;
        ((num as i128) * (self.m as i128) + (1i128 << (sh - 1))) >> sh
    }

    /// [`Recip::div_i64`] without a signed 128-bit multiply, which takes six
    /// 64-bit multiplies (library calls on a Cortex-M0) where two suffice:
    /// `|num| = n1·2³² + n0` and `m ≤ 2³²`, so `n0·m < 2⁶⁴` and
    /// `n1·m < 2⁶³`, and `P = |num|·m < 2⁹⁵` is exact in `u128`. With
    /// `h = 2^(sh−1)`, `⌊(−P + h)/2^sh⌋ = −⌊(P + h − 1)/2^sh⌋`: the same
    /// rounding (half up) for either sign.
    #[inline]
    fn div_i64_limbs(self, num: i64, up: u32) -> i128 {
        let sh = self.sh - up;
        let (n, m) = (num.unsigned_abs(), self.m as u64);
        // x·m for x < 2^32 and m ≤ 2^32 (m = 2^32 has a zero low word).
        let by_m = |x: u64| mul_u32(x as u32, m as u32) + if m >> 32 != 0 { x << 32 } else { 0 };
        let p = ((by_m(n >> 32) as u128) << 32) + by_m(n & 0xFFFF_FFFF) as u128;
        let h = 1u128 << (sh - 1);
        if num >= 0 {
            ((p + h) >> sh) as i128
        } else {
            -(((p + h - 1) >> sh) as i128)
        }
    }
}

/// `⌊a / 2^s⌋` if it is below 2³¹, in 32-bit shifts (a 64-bit shift by
/// a variable amount is a library call on a Cortex-M0).
#[inline(always)]
fn shr_u64_below_2_31(a: u64, s: u32) -> Option<u32> {
    let (hi, lo) = ((a >> 32) as u32, a as u32);
    let n = match s {
        0 => (hi == 0).then_some(lo),
        1..=31 => (hi >> s == 0).then(|| hi << (32 - s) | lo >> s),
        32..=63 => Some(hi >> (s - 32)),
        _ => Some(0),
    }?;
    (n >> 31 == 0).then_some(n)
}

/// What [`Recip::div_scaled`] returns for a quotient of 2³¹ or more (its
/// sign kept).
pub(crate) const QUOT_SAT: i64 = 1 << 40;

/// On 32-bit targets, numerators below this take [`Recip::div_i64_narrow`].
const NARROW_NUM: u64 = 1 << 31;

/// What a span covers: row `y`, columns `x0 ..= x1`, the attributes at `x0`
/// and their step per pixel.
#[cfg(test)]
#[derive(Clone, Copy, Debug)]
pub(crate) struct Span<const N: usize> {
    /// Row.
    pub(crate) y: i32,
    /// First column.
    pub(crate) x0: i32,
    /// Last column (inclusive).
    pub(crate) x1: i32,
    /// Attributes at `x0`.
    pub(crate) start: [i64; N],
    /// Attribute step per pixel.
    pub(crate) step: [i64; N],
}

/// How far a span's attributes may stray from the range of the triangle's
/// vertex values, in attribute units, at the span's first pixel; stepped
/// from `start` by `step` (the gradient rounded to a unit), pixel `k` of
/// the span is within `DRIFT + k/2`. The plane at a covered pixel lies
/// between the vertex values; the set-up's rounding of origin and
/// gradients adds the rest (`src/setup.rs`).
pub(crate) const DRIFT: i64 = setup::DRIFT as i64;

/// Sets up triangle `v` and calls `f` with each of its spans inside `clip`,
/// top to bottom; returns how it faced, or `None` if it drew nothing (no
/// area, culled, no sample row inside, or a vertex or `clip` outside the
/// limits: [`GUARD`], [`ATTR_LIMIT`], [`ClipRect::within_limits`]).
#[cfg(test)]
pub(crate) fn rasterize<const N: usize>(
    v: &[RasterVertex<N>; 3],
    clip: ClipRect,
    cull: bool,
    f: impl FnMut(&Span<N>),
) -> Option<Facing> {
    rasterize_rows(v, clip, (clip.y0, clip.y1), cull, f)
}

/// As [`rasterize`], drawing only rows `rows.0 ..= rows.1` of `clip` (a
/// band), with exactly the spans the whole rectangle gives on those rows:
/// the guard band and the planes are anchored at `clip`'s centre, whatever
/// the rows.
#[cfg(test)]
pub(crate) fn rasterize_rows<const N: usize>(
    v: &[RasterVertex<N>; 3],
    clip: ClipRect,
    rows: (i32, i32),
    cull: bool,
    mut f: impl FnMut(&Span<N>),
) -> Option<Facing> {
    if !clip.within_limits() {
        return None;
    }
    // The centre pixel's corner: columns and rows shift by integers.
    let (cx, cy) = (
        (clip.x0 as i64 + clip.x1 as i64 + 1) >> 1,
        (clip.y0 as i64 + clip.y1 as i64 + 1) >> 1,
    );
    let (ox, oy) = (16 * cx, 16 * cy);
    let inside = |p: &RasterVertex<N>| {
        (p.x - ox).unsigned_abs() <= GUARD as u64
            && (p.y - oy).unsigned_abs() <= GUARD as u64
            && p.attr.iter().all(|a| a.unsigned_abs() <= ATTR_LIMIT as u64)
    };
    if !v.iter().all(inside) {
        return None;
    }
    let s = v.map(|p| setup::Vertex {
        x: (p.x - ox) as i32,
        y: (p.y - oy) as i32,
        a: p.attr.map(|a| a as i32),
    });
    // Within the guard band the doubled area fits `i32`; negative is a
    // front face (y down).
    let area = (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y);
    let facing = if area < 0 {
        Facing::Front
    } else {
        Facing::Back
    };
    if area == 0 || (cull && facing == Facing::Back) {
        return None;
    }
    let (cx, cy) = (cx as i32, cy as i32);
    // Rows and columns relative to the centre; each within ±2²⁰ + 2032.
    let c = (clip.x0.max(cx - CLIP_LIMIT as i32) - cx, clip.x1 - cx);
    let r = (
        rows.0.max(clip.y0).max(cy - CLIP_LIMIT as i32) - cy,
        rows.1.min(clip.y1) - cy,
    );
    let drawn = setup::draw(&s, c, r, (cx, cy), |sp| {
        f(&Span {
            y: sp.y,
            x0: sp.x0,
            x1: sp.x1,
            start: sp.start.map(i64::from),
            step: sp.step.map(i64::from),
        })
    });
    drawn.then_some(facing)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::{coverage_from, Recip, NARROW_NUM};

    /// A xorshift generator: reproducible operands without a dependency.
    pub(crate) fn xorshift(mut x: u64) -> impl FnMut() -> u64 {
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        }
    }

    /// The 32-bit form of the coverage test is the 64-bit one wherever
    /// 32-bit targets take it (vertices within 2¹⁴ of the box's first
    /// centre), at the ends of that range too, in boxes of every shape up
    /// to 32 centres; overflow checks are on in the test build. (Which form
    /// `coverage` takes depends on the target: the firmware frames,
    /// identical to the host's, run the 32-bit one.)
    #[test]
    fn narrow_coverage_is_the_wide_one() {
        let mut bits = xorshift(0x6a09_e667_f3bc_c909);
        let mut next = move |m: i64| (bits() % (2 * m as u64 + 1)) as i64 - m;
        let lim = (1 << 14) - 1;
        let mut covered = 0;
        for n in 0..200_000 {
            let w = 1 + next(31).unsigned_abs() as u32;
            let h = 1 + next(31).unsigned_abs() as u32 % (32 / w);
            let reach = [24, 400, lim][n % 3];
            let mut v = [(0i64, 0i64); 3];
            for p in &mut v {
                *p = if n % 7 == 0 {
                    (lim * next(1).signum(), lim * next(1).signum())
                } else {
                    (next(reach), next(reach))
                };
            }
            // Positive area, as the set-up orients it.
            let a = (v[1].0 - v[0].0) * (v[2].1 - v[0].1) - (v[1].1 - v[0].1) * (v[2].0 - v[0].0);
            if a < 0 {
                v.swap(1, 2);
            }
            let wide = coverage_from(v, w, h);
            assert_eq!(
                coverage_from(v.map(|p| (p.0 as i32, p.1 as i32)), w, h),
                wide,
                "{v:?} {w}x{h}"
            );
            covered += (wide != 0) as u32;
        }
        assert!(covered > 20_000, "{covered}");
    }

    /// The 64-bit quotient equals the 128-bit one wherever `div_i64`
    /// takes it: numerators up to the bound (both signs), areas across
    /// their range, both shifts, and the rounding ties (exact ones for
    /// power-of-two areas at `up = 0`). The last comparison checks the
    /// dispatch only where `div_i64` can take the narrow form, on 32-bit
    /// targets; on the host it compares the `i128` form with itself (the
    /// firmware frames, byte-identical to the host's, exercise it there).
    #[test]
    fn narrow_quotient_is_the_wide_one() {
        let mut next = xorshift(0x6a09_e667_f3bc_c908);
        let lim = NARROW_NUM as i64 - 1;
        let mut nums = vec![0i64, 1, -1, lim, -lim, lim / 3, -(lim / 7)];
        let mut areas = vec![1i64, 2, 3, 1 << 31, (1 << 31) + 1, (1 << 32) - 1, 1 << 32];
        for _ in 0..3000 {
            let n = (next() >> (34 + next() % 30)) as i64;
            nums.push(if next() & 1 == 0 { n } else { -n });
            areas.push((next() >> (4 + next() % 60)).max(1) as i64);
        }
        let mut narrow = 0;
        for &a in &areas {
            let r = Recip::new(a);
            let ties = [1i64, 3, 5].map(|k| (k << r.sh.saturating_sub(33).min(28)).min(lim));
            for &num in nums.iter().chain(&ties).chain(&ties.map(|t| -t)) {
                for up in [0, 4, 8] {
                    let sh = r.sh - up;
                    if sh < 64 {
                        narrow += 1;
                        assert_eq!(
                            r.div_i64_narrow(num, sh) as i128,
                            r.div_i64_wide(num, up),
                            "a {a} num {num} up {up}"
                        );
                    }
                    assert_eq!(r.div_i64(num, up), r.div_i64_wide(num, up));
                }
            }
        }
        assert!(narrow > 1_000_000, "{narrow}");
    }

    /// [`Recip::div_scaled`] is within its stated bound of the exact
    /// quotient `num / (a·2^down)`: divisors of every bit length up to 2³¹
    /// (a vertex's `w`), numerators of both signs and every magnitude,
    /// shifts either way, each `bits` the callers pass; quotients of 2³¹
    /// or more saturate.
    #[test]
    fn scaled_quotient_is_within_its_bound() {
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        let mut fast = 0;
        for _ in 0..300_000 {
            let a = (next() >> (33 + next() % 31)).max(1) as i64;
            let r = Recip::new(a);
            let down = (next() % 80) as i32 - 20;
            let bits = [16, 24, 29][(next() % 3) as usize];
            let n = (next() >> (next() % 64)) as i64;
            let num = if next() & 1 == 0 { n } else { -n };
            // In f64: a relative error near 2^-52, inside the tolerance.
            let exact = if down >= 0 {
                ((num as f64) / (a as f64)) / (down as f64).exp2()
            } else {
                ((num as f64) / (a as f64)) * (-down as f64).exp2()
            };
            let got = r.div_scaled(num, down, bits);
            if exact.abs() >= (1u64 << 31) as f64 * (1.0 + 1e-9) {
                assert!(
                    got.abs() >= 1 << 30,
                    "{num} / {a}·2^{down}: {got}, want ≈ {exact}"
                );
                continue;
            }
            if exact.abs() < (1u64 << 30) as f64 {
                let small = exact.abs() < (bits as f64).exp2();
                fast += small as u32;
                let tol = if small {
                    0.5 + (bits as f64 - 30.0).exp2() + exact.abs() * 2f64.powi(-31)
                } else {
                    0.5 + exact.abs() * 2f64.powi(-29)
                } + 1e-6 * (1.0 + exact.abs() * 1e-9);
                assert!(
                    (got as f64 - exact).abs() <= tol,
                    "{num} / {a}·2^{down} ({bits}): {got}, want {exact}"
                );
            }
        }
        assert!(fast > 10_000, "{fast}");
    }

    /// The two-limb quotient of 32-bit targets equals the 128-bit one, for
    /// areas and numerators across their ranges, both signs, and the
    /// rounding ties (`num · m` a multiple of `2^(sh−1)`).
    #[test]
    fn limb_quotient_is_the_wide_one() {
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        let mut areas = vec![
            1i64,
            2,
            3,
            1 << 31,
            (1 << 31) + 1,
            1 << 40,
            (1 << 60) - 1,
            1 << 60,
        ];
        let mut nums = vec![0i64, 1, -1, i64::MAX, -i64::MAX, 1 << 47, -(1 << 47)];
        for _ in 0..2000 {
            areas.push((next() >> (4 + next() % 60)).max(1) as i64);
            let n = (next() >> (1 + next() % 63)) as i64;
            nums.push(if next() & 1 == 0 { n } else { -n });
        }
        for &a in &areas {
            let r = Recip::new(a);
            // Ties: num·m = ±k·2^(sh−1) when m is a power of two.
            let ties = [1i64, 3, 5].map(|k| k << (r.sh.saturating_sub(33)).min(60));
            for &num in nums.iter().chain(&ties).chain(&ties.map(|t| -t)) {
                for up in [0, 4] {
                    assert_eq!(
                        r.div_i64_limbs(num, up),
                        r.div_i64_wide(num, up),
                        "a {a} num {num} up {up}"
                    );
                }
            }
        }
    }

    /// The example from the docs of `SUBPIXEL_BITS`.
    #[test]
    fn doc_subpixel_bits() {
        use crate::rasterizer::{rasterize, ClipRect, RasterVertex, SUBPIXEL_BITS};
        // Pixel (x, y) has its centre at 16x + 8: a triangle whose vertices
        // sit on pixel corners, one pixel in from the target's, covers its box.
        let px = |c: i64| c << SUBPIXEL_BITS;
        let v = [(px(1), px(1)), (px(1), px(5)), (px(5), px(1))].map(|(x, y)| RasterVertex {
            x,
            y,
            attr: [],
        });
        let mut n = 0;
        rasterize(&v, ClipRect::of_size(8, 8).unwrap(), false, |s| {
            n += s.x1 - s.x0 + 1
        });
        // The centres strictly below the diagonal of the 4 × 4 box: those on
        // it lie on a right edge, which the top-left rule leaves out.
        assert_eq!(n, 3 + 2 + 1);
    }

    /// The example from the docs of `GUARD`.
    #[test]
    fn doc_guard() {
        use crate::rasterizer::{rasterize, ClipRect, RasterVertex, GUARD};
        let clip = ClipRect::of_size(8, 8).unwrap(); // centre pixel corner (4, 4): 64
        let tri = |far: i64| {
            [(64, 64), (64, 64 + far), (64 + far, 64)].map(|(x, y)| RasterVertex { x, y, attr: [] })
        };
        // At the limit the triangle covers the target; past it, it is refused.
        assert!(rasterize(&tri(GUARD), clip, false, |_| ()).is_some());
        assert!(rasterize(&tri(GUARD + 1), clip, false, |_| ()).is_none());
    }

    /// The example from the docs of `ATTR_LIMIT`.
    #[test]
    fn doc_attr_limit() {
        use crate::rasterizer::{rasterize, ClipRect, RasterVertex, ATTR_LIMIT};
        let clip = ClipRect::of_size(8, 8).unwrap();
        let tri = |a: i64| {
            [(0, 0, a), (0, 256, -a), (256, 0, 0)].map(|(x, y, a)| RasterVertex { x, y, attr: [a] })
        };
        assert!(rasterize(&tri(ATTR_LIMIT), clip, false, |_| ()).is_some());
        assert!(rasterize(&tri(ATTR_LIMIT + 1), clip, false, |_| ()).is_none());
    }

    /// The example from the docs of `RasterVertex`.
    #[test]
    fn doc_raster_vertex() {
        use crate::rasterizer::{rasterize, ClipRect, RasterVertex};
        // One attribute, 0 at the left and 1600 at the right (16 pixels on):
        // 100 units per pixel along x.
        let v = [(0, 0, 0), (0, 256, 0), (256, 0, 1600)].map(|(x, y, a)| RasterVertex {
            x,
            y,
            attr: [a],
        });
        let mut first = None;
        rasterize(&v, ClipRect::of_size(16, 16).unwrap(), false, |s| {
            first.get_or_insert((s.start[0], s.step[0]));
        });
        assert_eq!(first, Some((50, 100))); // pixel (0, 0)'s centre is half a pixel in
    }

    /// The example from the docs of `ClipRect`.
    #[test]
    fn doc_clip_rect() {
        use crate::rasterizer::{rasterize, ClipRect, RasterVertex};
        let v = [(0, 0), (0, 4096), (4096, 0)].map(|(x, y)| RasterVertex { x, y, attr: [] });
        let clip = ClipRect {
            x0: 2,
            y0: 3,
            x1: 5,
            y1: 4,
        };
        let mut rows = Vec::new();
        rasterize(&v, clip, false, |s| rows.push((s.y, s.x0, s.x1)));
        assert_eq!(rows, [(3, 2, 5), (4, 2, 5)]); // nothing outside the rectangle
    }

    /// The example from the docs of `CLIP_LIMIT`.
    #[test]
    fn doc_clip_limit() {
        use crate::rasterizer::{rasterize, ClipRect, RasterVertex, CLIP_LIMIT};
        let v = [(0, 0), (0, 64), (64, 0)].map(|(x, y)| RasterVertex { x, y, attr: [] });
        let huge = ClipRect {
            x0: 0,
            y0: 0,
            x1: CLIP_LIMIT as i32,
            y1: 0,
        };
        assert!(rasterize(&v, huge, false, |_| ()).is_none()); // refused, not drawn
        let fits = ClipRect {
            x1: CLIP_LIMIT as i32 - 1,
            ..huge
        };
        assert!(rasterize(&v, fits, false, |_| ()).is_some());
    }

    /// The example from the docs of `ClipRect::within_limits`.
    #[test]
    fn doc_clip_rect_within_limits() {
        use crate::rasterizer::{ClipRect, CLIP_LIMIT};
        assert!(ClipRect::of_size(320, 240).unwrap().within_limits());
        assert!(ClipRect::of_size(CLIP_LIMIT as u32, 1)
            .unwrap()
            .within_limits());
        assert!(!ClipRect::of_size(CLIP_LIMIT as u32 + 1, 1)
            .unwrap()
            .within_limits());
    }

    /// The example from the docs of `ClipRect::of_size`.
    #[test]
    fn doc_clip_rect_of_size() {
        use crate::rasterizer::ClipRect;
        assert_eq!(
            ClipRect::of_size(320, 240),
            Some(ClipRect {
                x0: 0,
                y0: 0,
                x1: 319,
                y1: 239
            })
        );
        assert_eq!(ClipRect::of_size(0, 240), None);
    }

    /// The example from the docs of `Facing`.
    #[test]
    fn doc_facing() {
        use crate::rasterizer::{rasterize, ClipRect, Facing, RasterVertex};
        let v = [(8, 8), (8, 200), (200, 8)].map(|(x, y)| RasterVertex { x, y, attr: [] });
        let clip = ClipRect::of_size(16, 16).unwrap();
        let back = [v[0], v[2], v[1]];
        assert_eq!(rasterize(&v, clip, true, |_| ()), Some(Facing::Front));
        assert_eq!(rasterize(&back, clip, false, |_| ()), Some(Facing::Back)); // kept: no culling
        assert_eq!(rasterize(&back, clip, true, |_| ()), None); // culled
    }

    /// The example from the docs of `Span`.
    #[test]
    fn doc_span() {
        use crate::rasterizer::{rasterize, ClipRect, RasterVertex};
        // attr = 10·x_px + 1000·y_px at pixel centres.
        let v = [(0, 0, 0), (0, 512, 32_000), (512, 0, 320)].map(|(x, y, a)| RasterVertex {
            x,
            y,
            attr: [a],
        });
        rasterize(&v, ClipRect::of_size(32, 32).unwrap(), false, |s| {
            let at = |x: i32| 10 * x as i64 + 1000 * s.y as i64 + 505;
            assert_eq!(s.start[0], at(s.x0));
            assert_eq!(s.start[0] + (s.x1 - s.x0) as i64 * s.step[0], at(s.x1));
        });
    }

    /// The example from the docs of `DRIFT`.
    #[test]
    fn doc_drift() {
        use crate::rasterizer::{rasterize, ClipRect, RasterVertex, DRIFT};
        let v = [(3, 5, 0), (90, 1000, 77_777), (1700, 40, -12_345)]
            .map(|(x, y, a)| RasterVertex { x, y, attr: [a] });
        rasterize(&v, ClipRect::of_size(128, 128).unwrap(), false, |s| {
            for k in 0..=(s.x1 - s.x0) as i64 {
                let a = s.start[0] + k * s.step[0];
                let d = DRIFT + (k + 1) / 2;
                assert!((-12_345 - d..=77_777 + d).contains(&a));
            }
        });
    }

    /// The example from the docs of `rasterize`.
    #[test]
    fn doc_rasterize() {
        use crate::rasterizer::{rasterize, ClipRect, RasterVertex};
        let v = [(8, 8), (8, 200), (200, 8)].map(|(x, y)| RasterVertex { x, y, attr: [] });
        let mut pixels = 0;
        rasterize(&v, ClipRect::of_size(16, 16).unwrap(), true, |s| {
            pixels += s.x1 - s.x0 + 1
        });
        assert!(pixels > 50);
    }

    /// The example from the docs of `rasterize_rows`.
    #[test]
    fn doc_rasterize_rows() {
        use crate::rasterizer::{rasterize_rows, ClipRect, RasterVertex};
        let v = [(8, 8), (8, 200), (200, 8)].map(|(x, y)| RasterVertex { x, y, attr: [] });
        let mut rows = Vec::new();
        rasterize_rows(&v, ClipRect::of_size(16, 16).unwrap(), (4, 5), true, |s| {
            rows.push(s.y)
        });
        assert_eq!(rows, [4, 5]);
    }
}

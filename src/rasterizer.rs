//! Triangle setup and scan conversion: integer edge functions on a 1/16
//! pixel grid, the top-left fill rule, and attribute plane equations.
//!
//! # Coverage (SPEC.md 5)
//! Vertices arrive snapped to 1/16 pixel (`X = floor(x_w · 16 + ½)`), as
//! integers clamped to ±2²⁸ (±16.7 million pixels: the documented limit
//! past which a vertex is moved; the [`crate::render`] stage clips the
//! near plane, so this only matters for vertices very close to the eye
//! plane). With `|X|, |Y| ≤ 2²⁸` every edge-function product is below 2⁵⁸
//! and every sum below 2⁶⁰: `i64` is exact.
//!
//! For edge `a → b` and sample `p`, `E(p) = (b.x−a.x)(p.y−a.y) −
//! (b.y−a.y)(p.x−a.x)` (y down). A triangle is oriented so that
//! `E_{01}(v2) > 0`; sample `(16x+8, 16y+8)` is inside where every
//! `E > 0`, or `E = 0` on a top-left edge (`dy < 0`, or `dy = 0` and
//! `dx > 0`). Two triangles that share an edge see it with opposite
//! directions, so exactly one of them owns each sample on it.
//!
//! # Spans
//! Per row, one edge of the left chain and one of the right chain bound
//! the span (the chain with two edges switches at the middle vertex's
//! row); each bound is an exact integer division (floor or ceiling) kept
//! row to row as a quotient and remainder, so the span is exact. The span
//! is clipped to the caller's rectangle (the target's bounds). A box of at
//! most four pixel centres is tested centre by centre instead, and its
//! covered centres give the walk's bounds directly (`coverage`,
//! `masked_walk`): the same spans, without the edges' divisions.
//!
//! # Attributes
//! Each attribute (depth, colour, normal, position; scaled by the caller)
//! is a plane `A(p) = A0 + ΔA1·λ1 + ΔA2·λ2` with affine barycentrics at
//! pixel centres (SPEC.md 4). Setup computes its per-pixel gradients with
//! one reciprocal of the area per triangle (a 32-bit mantissa: relative
//! error 2⁻³¹) and its value at the clipped bounding box's corner exactly
//! (`i128`); spans step from there. Within a target of at most 2¹³ pixels
//! a side the stepping error stays below 2⁻⁴ of the attribute's unit.

use crate::num::division::{floor_div, recip63};
use crate::num::widening::{mul_by_narrow, mul_by_small, mul_i32_u16, mul_narrow, mul_u32};

/// Sub-pixel bits of the snapping grid (SPEC.md 5: 1/16 pixel).
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex, SUBPIXEL_BITS};
/// // Pixel (x, y) has its centre at 16x + 8: a triangle whose vertices
/// // sit on pixel corners, one pixel in from the target's, covers its box.
/// let px = |c: i64| c << SUBPIXEL_BITS;
/// let v = [(px(1), px(1)), (px(1), px(5)), (px(5), px(1))]
///     .map(|(x, y)| RasterVertex { x, y, attr: [] });
/// let mut n = 0;
/// rasterize(&v, ClipRect::of_size(8, 8).unwrap(), false, |s| n += s.x1 - s.x0 + 1);
/// // The centres strictly below the diagonal of the 4 × 4 box: those on
/// // it lie on a right edge, which the top-left rule leaves out.
/// assert_eq!(n, 3 + 2 + 1);
/// ```
pub const SUBPIXEL_BITS: u32 = 4;
/// The largest snapped coordinate magnitude, in 1/16 pixel.
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex, COORD_LIMIT};
/// let clip = ClipRect::of_size(8, 8).unwrap();
/// let tri = |far: i64| [(0, 0), (0, far), (far, 0)].map(|(x, y)| RasterVertex { x, y, attr: [] });
/// // At the limit the triangle covers the target; past it, it is refused.
/// assert!(rasterize(&tri(COORD_LIMIT), clip, false, |_| ()).is_some());
/// assert!(rasterize(&tri(COORD_LIMIT + 1), clip, false, |_| ()).is_none());
/// ```
pub const COORD_LIMIT: i64 = 1 << 28;

/// Attributes lie in `−ATTR_LIMIT ≤ a < ATTR_LIMIT` (34-bit signed
/// integers), so that the differences between a triangle's vertices stay
/// below 2³⁴ in magnitude, which the set-up's exact
/// products and plane equations assume (the renderer's depths, colours,
/// normals and positions are all below it).
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex, ATTR_LIMIT};
/// let clip = ClipRect::of_size(8, 8).unwrap();
/// let tri = |a: i64| [(0, 0, a), (0, 256, -a), (256, 0, 0)]
///     .map(|(x, y, a)| RasterVertex { x, y, attr: [a] });
/// let mut lo = i64::MAX;
/// assert!(rasterize(&tri(ATTR_LIMIT - 1), clip, false, |s| lo = lo.min(s.start[0])).is_some());
/// assert!(lo >= -ATTR_LIMIT);
/// assert!(rasterize(&tri(ATTR_LIMIT), clip, false, |_| ()).is_none());
/// ```
pub const ATTR_LIMIT: i64 = 1 << 33;

/// A triangle vertex in window space: position in 1/16 pixel and `N`
/// attributes in the caller's units.
///
/// The rasterizer's entry points ([`Triangle::setup_rows`], [`rasterize`]
/// and the like) draw nothing for a triangle with a vertex outside these
/// limits ([`RasterVertex::within_limits`]);
/// [`RasterVertex::clamped`] moves a vertex inside them, as the renderer
/// does with a vertex far off screen.
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex};
/// // One attribute, 0 at the left and 1600 at the right (16 pixels on):
/// // 100 units per pixel along x.
/// let v = [(0, 0, 0), (0, 256, 0), (256, 0, 1600)]
///     .map(|(x, y, a)| RasterVertex { x, y, attr: [a] });
/// let mut first = None;
/// rasterize(&v, ClipRect::of_size(16, 16).unwrap(), false, |s| {
///     first.get_or_insert((s.start[0], s.step[0]));
/// });
/// assert_eq!(first, Some((50, 100))); // pixel (0, 0)'s centre is half a pixel in
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RasterVertex<const N: usize> {
    /// x in 1/16 pixel, within ±[`COORD_LIMIT`].
    pub x: i64,
    /// y in 1/16 pixel (down), within ±[`COORD_LIMIT`].
    pub y: i64,
    /// Attributes, each in `−`[`ATTR_LIMIT`]` ≤ a < `[`ATTR_LIMIT`].
    pub attr: [i64; N],
}

impl<const N: usize> RasterVertex<N> {
    /// Whether the vertex is one the rasterizer takes: `|x|, |y| ≤`
    /// [`COORD_LIMIT`] and every `−`[`ATTR_LIMIT`]` ≤ attr < `[`ATTR_LIMIT`].
    ///
    /// ```
    /// use fixshade::rasterizer::{RasterVertex, ATTR_LIMIT, COORD_LIMIT};
    /// assert!(RasterVertex { x: COORD_LIMIT, y: -COORD_LIMIT, attr: [ATTR_LIMIT - 1] }.within_limits());
    /// assert!(!RasterVertex { x: COORD_LIMIT + 1, y: 0, attr: [0] }.within_limits());
    /// assert!(RasterVertex { x: 0, y: 0, attr: [-ATTR_LIMIT] }.within_limits());
    /// assert!(!RasterVertex { x: 0, y: 0, attr: [ATTR_LIMIT] }.within_limits());
    /// ```
    #[inline]
    pub fn within_limits(&self) -> bool {
        let coord = |c: i64| c.unsigned_abs() <= COORD_LIMIT as u64;
        coord(self.x)
            && coord(self.y)
            && self
                .attr
                .iter()
                .all(|a| (-ATTR_LIMIT..ATTR_LIMIT).contains(a))
    }

    /// The vertex with each coordinate clamped to ±[`COORD_LIMIT`] and each
    /// attribute to `−`[`ATTR_LIMIT`]` ..= `[`ATTR_LIMIT`]` − 1`: within the
    /// limits.
    ///
    /// ```
    /// use fixshade::rasterizer::{RasterVertex, ATTR_LIMIT, COORD_LIMIT};
    /// let v = RasterVertex { x: i64::MIN, y: 5, attr: [i64::MAX] }.clamped();
    /// assert_eq!(v, RasterVertex { x: -COORD_LIMIT, y: 5, attr: [ATTR_LIMIT - 1] });
    /// ```
    #[inline]
    pub fn clamped(self) -> Self {
        let coord = |c: i64| c.clamp(-COORD_LIMIT, COORD_LIMIT);
        RasterVertex {
            x: coord(self.x),
            y: coord(self.y),
            attr: self.attr.map(|a| a.clamp(-ATTR_LIMIT, ATTR_LIMIT - 1)),
        }
    }
}

/// The inclusive pixel rectangle that may be drawn (the target's bounds),
/// at most [`CLIP_LIMIT`] pixels a side for the rasterizer to draw in it
/// (see [`ClipRect::within_limits`]).
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex};
/// let v = [(0, 0), (0, 4096), (4096, 0)].map(|(x, y)| RasterVertex { x, y, attr: [] });
/// let clip = ClipRect { x0: 2, y0: 3, x1: 5, y1: 4 };
/// let mut rows = Vec::new();
/// rasterize(&v, clip, false, |s| rows.push((s.y, s.x0, s.x1)));
/// assert_eq!(rows, [(3, 2, 5), (4, 2, 5)]); // nothing outside the rectangle
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClipRect {
    /// First column.
    pub x0: i32,
    /// First row.
    pub y0: i32,
    /// Last column (inclusive).
    pub x1: i32,
    /// Last row (inclusive).
    pub y1: i32,
}

/// The most pixels a [`ClipRect`] may span on either axis: the renderer's
/// largest target ([`crate::render::MAX_TARGET_SIDE`]). Attributes are
/// stepped across it, row by row and column by column; with gradients of
/// at most 2⁴⁰ per pixel that stays within `i64`.
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex, CLIP_LIMIT};
/// let v = [(0, 0), (0, 64), (64, 0)].map(|(x, y)| RasterVertex { x, y, attr: [] });
/// let huge = ClipRect { x0: 0, y0: 0, x1: CLIP_LIMIT as i32, y1: 0 };
/// assert!(rasterize(&v, huge, false, |_| ()).is_none()); // refused, not drawn
/// let fits = ClipRect { x1: CLIP_LIMIT as i32 - 1, ..huge };
/// assert!(rasterize(&v, fits, false, |_| ()).is_some());
/// ```
pub const CLIP_LIMIT: i64 = 1 << 20;

impl ClipRect {
    /// Whether the rasterizer draws in this rectangle: each side at most
    /// [`CLIP_LIMIT`] pixels (an empty rectangle, `x0 > x1` or `y0 > y1`,
    /// qualifies and draws nothing).
    ///
    /// ```
    /// use fixshade::rasterizer::{ClipRect, CLIP_LIMIT};
    /// assert!(ClipRect::of_size(320, 240).unwrap().within_limits());
    /// assert!(ClipRect::of_size(CLIP_LIMIT as u32, 1).unwrap().within_limits());
    /// assert!(!ClipRect::of_size(CLIP_LIMIT as u32 + 1, 1).unwrap().within_limits());
    /// ```
    #[inline]
    pub fn within_limits(&self) -> bool {
        let side = |a: i32, b: i32| (b as i64) - (a as i64) < CLIP_LIMIT;
        side(self.x0, self.x1) && side(self.y0, self.y1)
    }

    /// The rectangle of a `width × height` target at the origin; `None`
    /// when it is empty.
    ///
    /// ```
    /// use fixshade::rasterizer::ClipRect;
    /// assert_eq!(ClipRect::of_size(320, 240), Some(ClipRect { x0: 0, y0: 0, x1: 319, y1: 239 }));
    /// assert_eq!(ClipRect::of_size(0, 240), None);
    /// ```
    pub fn of_size(width: u32, height: u32) -> Option<ClipRect> {
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
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, Facing, RasterVertex};
/// let v = [(8, 8), (8, 200), (200, 8)].map(|(x, y)| RasterVertex { x, y, attr: [] });
/// let clip = ClipRect::of_size(16, 16).unwrap();
/// let back = [v[0], v[2], v[1]];
/// assert_eq!(rasterize(&v, clip, true, |_| ()), Some(Facing::Front));
/// assert_eq!(rasterize(&back, clip, false, |_| ()), Some(Facing::Back)); // kept: no culling
/// assert_eq!(rasterize(&back, clip, true, |_| ()), None); // culled
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Facing {
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

/// The most pixel centres a triangle's box may hold for
/// [`Triangle::setup_rows`] (and the renderer, before it lights an
/// unclipped triangle) to test them one by one instead of walking its
/// edges: a triangle that covers none is dropped, and one that covers some
/// draws the centres its [`coverage`] mask holds, with no edge set-up.
/// At most 4: the covered centres of such a box are one row, two rows or
/// one column, which is what [`masked_walk`] walks (and its row shifts
/// stay below 32 bits).
pub(crate) const TINY: i64 = 4;
const _: () = assert!(TINY <= 4);

/// Which pixel centres of columns `xs.0 ..= xs.1` and rows
/// `ys.0 ..= ys.1` (at most 32 in all) the oriented triangle `v`
/// (positions in 1/16 pixel, positive area) covers, by the rule the edge
/// walk follows: bit `w·(y − ys.0) + (x − xs.0)` for centre `(x, y)`, `w`
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
    if cfg!(not(target_pointer_width = "64")) && near {
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

/// The walk of a tiny box's coverage `mask` ([`coverage`]; columns
/// `xs.0 ..= xs.1`, first row `y0`): edges whose bounds are each covered
/// row's first and last columns, and the first and last covered rows;
/// `None` for an empty mask, or one whose spans those edges cannot give.
///
/// The covered rows are contiguous, as are a row's covered columns (each
/// edge function admits a half-line of any line). Edges that step by a
/// whole column a row give the bounds of two rows exactly, and of any
/// number of rows of a one-column box (the same column); a box of at
/// most [`TINY`] ≤ 4 centres has no other shape with three covered rows,
/// so for it the walk always exists.
#[inline(always)]
fn masked_walk(mask: u32, xs: (i64, i64), y0: i64) -> Option<(Edge, Edge, i64, i64)> {
    if mask == 0 {
        return None;
    }
    // At most TINY (≤ 4) columns.
    let w = (xs.1 - xs.0 + 1) as u32;
    let full = u32::MAX >> (32 - w);
    let (mut first, mut m) = (y0, mask);
    while m & full == 0 {
        (first, m) = (first + 1, m >> w);
    }
    let top = m & full;
    let (mut last, mut bottom) = (first, top);
    while m >> w != 0 {
        (last, m) = (last + 1, m >> w);
        bottom = m & full;
    }
    if last - first > 1 && w > 1 {
        return None;
    }
    let lo = |b: u32| xs.0 + b.trailing_zeros() as i64;
    let hi = |b: u32| xs.0 + 31 - b.leading_zeros() as i64;
    let edge = |q: i64, q_last: i64| Edge {
        q,
        r: 0,
        dq: q_last - q,
        dr: 0,
        den: 1,
    };
    Some((
        edge(lo(top), lo(bottom)),
        edge(hi(top), hi(bottom)),
        first,
        last,
    ))
}

/// One edge's bound on the span, stepped row by row without division.
///
/// For edge `a → b` and row sample `ys`, `E(px) = K − dy·px` with
/// `K = dx·(ys − a.y) + dy·a.x`. The columns it admits are
/// `x ≥ ⌈(−K − 8m)/(16m)⌉` for `dy = −m < 0` (top-left: `E ≥ 0`) and
/// `x ≤ ⌊(K − 8dy − 1)/(16dy)⌋` for `dy > 0` (`E > 0`, i.e. `E ≥ 1`;
/// such an edge is never top-left). The two nested divisions of
/// `px = 16x + 8` fold into one (`⌈⌈a/m⌉/16⌉ = ⌈a/16m⌉`), and a ceiling is
/// the floor of the numerator plus `den − 1`. From row to row the numerator
/// moves by a constant, so the quotient is kept with its remainder (a DDA):
/// exact, two divisions per edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Edge {
    /// The bound on the current row (first or last column admitted), and
    /// the remainder of its division, `0 ≤ r < den`.
    q: i64,
    r: i64,
    /// Per-row step of quotient and remainder.
    dq: i64,
    dr: i64,
    den: i64,
}

/// An edge that is not horizontal, before it is placed on a row.
#[derive(Clone, Copy, Debug)]
struct EdgeLine {
    a: (i64, i64),
    dx: i64,
    dy: i64,
}

impl EdgeLine {
    /// The DDA of this edge's bound starting at row sample `ys`: on 32-bit
    /// targets in 32-bit arithmetic where it fits ([`EdgeLine::at_narrow`]),
    /// else (and on 64-bit targets, where it is no cheaper) in 64-bit.
    /// (Inline hints per target: as measured, by QEMU on the Cortex-M0 and
    /// callgrind on x86-64, whose cached bands it keeps cheaper.)
    #[cfg_attr(target_pointer_width = "64", inline)]
    fn at(self, ys: i64) -> Edge {
        if cfg!(target_pointer_width = "64") {
            self.at_wide(ys)
        } else {
            self.at_narrow(ys).unwrap_or_else(|| self.at_wide(ys))
        }
    }

    /// [`EdgeLine::at`] in `i64`: two 64-bit divisions.
    #[cfg_attr(target_pointer_width = "64", inline)]
    fn at_wide(self, ys: i64) -> Edge {
        let EdgeLine { a, dx, dy } = self;
        // |K| < 2^59 (coordinates within ±2^28).
        let k = dx * (ys - a.1) + dy * a.0;
        // Numerator N and its per-row step, so that the bound is ⌊N/den⌋.
        let (n, dn, den) = if dy < 0 {
            let den = -16 * dy;
            (-k + 8 * dy + den - 1, -16 * dx, den)
        } else {
            (k - 8 * dy - 1, 16 * dx, 16 * dy)
        };
        let q = floor_div(n, den);
        let dq = floor_div(dn, den);
        Edge {
            q,
            r: n - q * den,
            dq,
            dr: dn - dq * den,
            den,
        }
    }

    /// [`EdgeLine::at`] in `i32`, where it fits.
    ///
    /// With `a.x = 16h + l` (`0 ≤ l < 16`), the term `dy·a.x` of `K` puts
    /// `den·h` into the numerator: `N = den·h + N'`, so the bound is
    /// `h + ⌊N'/den⌋` with the same remainder, and `N'` depends on the
    /// vertex's position only through `l` and `t = ys − a.y`. For an edge
    /// under 2¹⁴ sub-pixels a side sampled within 2¹⁵ of `a` (every edge of
    /// a small triangle) `N'`, its step and `den` fit `i32`: two 32-bit
    /// divisions (one instruction each on a Cortex-M4, a short library call
    /// on a Cortex-M0) instead of two 64-bit ones (library calls on both).
    /// `None` for a longer edge or a farther sample.
    fn at_narrow(self, ys: i64) -> Option<Edge> {
        let EdgeLine { a, dx, dy } = self;
        let t = ys - a.1;
        let near = |v: i64, lim: u32| v.unsigned_abs() < 1 << lim;
        if !(near(dx, 14) && near(dy, 14) && near(t, 15)) {
            return None;
        }
        // |dx·t| < 2^29, |dy|·l < 2^18, 8|dy| < 2^17: below 2^30.
        let (h, l) = (a.0 >> 4, (a.0 & 15) as i32);
        let (dx, dy, t) = (dx as i32, dy as i32, t as i32);
        // dy < 0: N = −K + 8dy + den − 1 = den·h + (−dx·t − dy·l − 8dy − 1);
        // dy > 0: N = K − 8dy − 1 = den·h + (dx·t + dy·l − 8dy − 1).
        let (n, dn, den) = if dy < 0 {
            (-dx * t - dy * l - 8 * dy - 1, -16 * dx, -16 * dy)
        } else {
            (dx * t + dy * l - 8 * dy - 1, 16 * dx, 16 * dy)
        };
        let (q, dq) = (floor_div(n, den), floor_div(dn, den));
        Some(Edge {
            q: h + q as i64,
            r: (n - q * den) as i64,
            dq: dq as i64,
            dr: (dn - dq * den) as i64,
            den: den as i64,
        })
    }
}

impl Edge {
    /// Moves to the next row.
    #[inline(always)]
    fn step(&mut self) {
        self.q += self.dq;
        self.r += self.dr;
        if self.r >= self.den {
            self.r -= self.den;
            self.q += 1;
        }
    }
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
        let bits = 64 - a.leading_zeros();
        // a ≈ a32 · 2^e with a32 ∈ [2^31, 2^32).
        let (a32, e) = if bits > 32 {
            (a >> (bits - 32), (bits - 32) as i32)
        } else {
            (a << (32 - bits), -((32 - bits) as i32))
        };
        // 1/a ≈ (2^63 / a32) · 2^−(63 + e); 2^63/a32 ∈ (2^31, 2^32].
        Recip {
            // (The plain division where it is one instruction, written
            // on the `u64`: through a `u32` argument x86-64 took 1.8 % more
            // on S1 in flat shading, from instruction selection.)
            m: if cfg!(fixshade_soft_div64) {
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
    #[cfg_attr(not(target_pointer_width = "64"), inline(always))]
    #[cfg_attr(target_pointer_width = "64", inline)]
    pub(crate) fn div_i64(self, num: i64, up: u32) -> i128 {
        let sh = self.sh - up;
        if cfg!(target_pointer_width = "64") {
            self.div_i64_wide(num, up)
        } else if sh < 64 && num.unsigned_abs() < NARROW_NUM {
            self.div_i64_narrow(num, sh) as i128
        } else {
            self.div_i64_limbs(num, up)
        }
    }

    /// [`Recip::div_i64`] in 64-bit arithmetic, for `|num| < 2³¹` and a
    /// shift `sh = self.sh − up` in `1 ..= 63` (`self.sh ≥ 32` and `up ≤ 4`
    /// give `sh ≥ 28`): the magnitude's product `P = |num|·m < 2⁶³`
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

    /// `round(num · 2^up / a)`; `|num| < 2⁹⁴` keeps the product below 2¹²⁶.
    #[inline]
    fn div(self, num: i128, up: u32) -> i128 {
        let sh = self.sh - up;
        (num * self.m as i128 + (1i128 << (sh - 1))) >> sh
    }
}

/// On 32-bit targets, numerators below this take [`Recip::div_i64_narrow`].
const NARROW_NUM: u64 = 1 << 31;

/// A triangle's scan conversion paused at a row: its edges there, the
/// attribute values at the row's first column, and the rows it has left in
/// the viewport.
///
/// [`Triangle::walk_rows`] gives it when a band ends above the triangle's
/// last row; [`Walk::resume`] draws the next band's rows from it without a
/// new set-up, with exactly the spans the uninterrupted walk gives there
/// (the state is the walk's own: integers, stepped row by row). A sliver
/// (whose spans start from the plane equations) does not pause.
///
/// ```
/// use fixshade::rasterizer::{ClipRect, RasterVertex, Triangle};
/// let v = [(8, 8), (8, 300), (250, 8)].map(|(x, y)| RasterVertex { x, y, attr: [x * y] });
/// let vp = ClipRect::of_size(16, 16).unwrap();
/// let mut whole = Vec::new();
/// Triangle::setup(&v, vp, true).unwrap().for_each_span(|s| whole.push((s.y, s.x0, s.x1, s.start)));
/// // Rows 0..=4, then the rest resumed band by band without a set-up.
/// let mut banded = Vec::new();
/// let t = Triangle::setup_rows(&v, vp, (0, 4), true).unwrap();
/// let mut walk = t.walk_rows(|s| banded.push((s.y, s.x0, s.x1, s.start)));
/// for y0 in [5, 10, 15] {
///     walk = walk.and_then(|w| w.resume((y0, y0 + 4), |s| banded.push((s.y, s.x0, s.x1, s.start))));
/// }
/// assert!(walk.is_none()); // the triangle's last row was drawn
/// assert_eq!(whole, banded);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Walk<const N: usize> {
    /// The edges bounding the current row from the left and the right.
    left: Edge,
    right: Edge,
    /// The edge that takes over on one side at row `switch` (where the
    /// triangle's middle vertex is passed; `i64::MAX` if never), and
    /// whether it is the left one.
    next: EdgeLine,
    next_left: bool,
    switch: i64,
    x_lo: i64,
    x_hi: i64,
    /// The row the walk is at, and its last row: the triangle's last row in
    /// the viewport (a tiny box's last covered row).
    y: i64,
    y_end: i64,
    /// Attribute values at pixel (x_lo, y).
    row: [i64; N],
    /// Per-pixel gradients along x.
    ddx: [i64; N],
    /// Per-pixel gradients along y.
    ddy: [i64; N],
    /// Spans stay within [`DRIFT`] of the vertex values.
    bounded: bool,
}

/// A set-up triangle: its walk at the first drawn row, the last row drawn
/// (the band's), and what a sliver's span starts need.
///
/// ```
/// use fixshade::rasterizer::{ClipRect, Facing, RasterVertex, Triangle};
/// let v = [(8, 8), (200, 8), (8, 200)].map(|(x, y)| RasterVertex { x, y, attr: [] });
/// let t = Triangle::setup(&v, ClipRect::of_size(16, 16).unwrap(), false).unwrap();
/// assert_eq!(t.facing, Facing::Back); // kept (no culling), and drawn all the same
/// let mut rows = Vec::new();
/// t.for_each_span(|s| rows.push(s.y));
/// assert_eq!(rows, (0..12).collect::<Vec<_>>()); // row centres 8 … 184 lie inside
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Triangle<'v, const N: usize> {
    walk: Walk<N>,
    /// The last row drawn.
    y_hi: i64,
    /// Gradients too steep to step (a sliver): each span's start is
    /// evaluated from the plane equation instead.
    exact: bool,
    recip: Recip,
    /// The caller's vertices (for the exact path), and whether orienting
    /// the triangle swapped the last two.
    verts: &'v [RasterVertex<N>; 3],
    swapped: bool,
    /// Which way the triangle faced before it was oriented.
    pub facing: Facing,
}

/// Gradients above this (per pixel, in attribute units) mark a sliver.
/// Inside a triangle every attribute stays between its vertex values
/// (`|d| < 2^34`), so a span whose step exceeds 2^40 is one pixel long and
/// the step is never used; stepping rows with it could overflow, though.
const STEEP: u128 = 1 << 40;

/// `A(s)` for the sample whose edge functions relative to the oriented
/// triangle are `e20`, `e01`: `A0 + (d1·E20 + d2·E01) / area`. `|E| < 2^60`
/// and `|d| < 2^34`: the products (below 2^94) are split in a high and a
/// low part so that the product with the 32-bit mantissa stays in `i128`.
fn plane_at<const N: usize>(
    v: [&RasterVertex<N>; 3],
    r: Recip,
    i: usize,
    e20: i64,
    e01: i64,
) -> i64 {
    let d1 = (v[1].attr[i] - v[0].attr[i]) as i128;
    let d2 = (v[2].attr[i] - v[0].attr[i]) as i128;
    let hi = r.div(d1 * (e20 >> 4) as i128 + d2 * (e01 >> 4) as i128, 4);
    let lo = r.div(d1 * (e20 & 15) as i128 + d2 * (e01 & 15) as i128, 0);
    let a = v[0].attr[i] as i128 + hi + lo;
    a.clamp(i64::MIN as i128 / 2, i64::MAX as i128 / 2) as i64
}

/// What a span covers: row `y`, columns `x0 ..= x1`, the attributes at `x0`
/// and their step per pixel.
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex};
/// // attr = 10·x_px + 1000·y_px at pixel centres.
/// let v = [(0, 0, 0), (0, 512, 32_000), (512, 0, 320)]
///     .map(|(x, y, a)| RasterVertex { x, y, attr: [a] });
/// rasterize(&v, ClipRect::of_size(32, 32).unwrap(), false, |s| {
///     let at = |x: i32| 10 * x as i64 + 1000 * s.y as i64 + 505;
///     assert_eq!(s.start[0], at(s.x0));
///     assert_eq!(s.start[0] + (s.x1 - s.x0) as i64 * s.step[0], at(s.x1));
///     assert!(s.bounded);
/// });
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Span<const N: usize> {
    /// Row.
    pub y: i32,
    /// First column.
    pub x0: i32,
    /// Last column (inclusive).
    pub x1: i32,
    /// Attributes at `x0`.
    pub start: [i64; N],
    /// Attribute step per pixel.
    pub step: [i64; N],
    /// Every attribute at every pixel of the span lies within [`DRIFT`]
    /// of the range of the triangle's vertex values (a small triangle with
    /// moderate gradients, see [`DRIFT`]); `false` when not known.
    pub bounded: bool,
}

/// How far a bounded span's attributes may stray from the range of the
/// vertex values, in attribute units.
///
/// A triangle is bounded when its bounding box is under 256 pixels a side,
/// it is not a sliver, and every gradient is at most [`BOUNDED_GRADIENT`]
/// per pixel. The exact plane at a covered pixel centre (inside the
/// closed triangle) lies between the vertex values. The stepped value
/// differs from it by the origin's error (the gradients' rounding, ½ unit
/// per pixel plus the reciprocal's relative 2⁻³¹ of at most 2²⁴, over at
/// most 256 pixels on each axis, then ½ for the final rounding: below 258)
/// plus the stepping's (the same per pixel over at most 2 × 256 pixels:
/// below 257). 1024 leaves twice that.
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex, DRIFT};
/// let v = [(3, 5, 0), (90, 1000, 77_777), (1700, 40, -12_345)]
///     .map(|(x, y, a)| RasterVertex { x, y, attr: [a] });
/// rasterize(&v, ClipRect::of_size(128, 128).unwrap(), false, |s| {
///     assert!(s.bounded);
///     for k in 0..=(s.x1 - s.x0) as i64 {
///         let a = s.start[0] + k * s.step[0];
///         assert!((-12_345 - DRIFT..=77_777 + DRIFT).contains(&a));
///     }
/// });
/// ```
pub const DRIFT: i64 = 1024;

/// The largest gradient (per pixel, attribute units) of a bounded triangle.
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex, BOUNDED_GRADIENT};
/// // Gradient along x: attr(256 sub-pixels = 16 px) / 16 px.
/// let tri = |a: i64| {
///     [(0, 0, 0), (0, 256, 0), (256, 0, a)].map(|(x, y, a)| RasterVertex { x, y, attr: [a] })
/// };
/// let bounded = |a| {
///     let mut all = true;
///     rasterize(&tri(a), ClipRect::of_size(16, 16).unwrap(), false, |s| all &= s.bounded);
///     all
/// };
/// assert!(bounded(16 * BOUNDED_GRADIENT));
/// assert!(!bounded(16 * BOUNDED_GRADIENT + 16));
/// ```
pub const BOUNDED_GRADIENT: i64 = 1 << 24;

impl<'v, const N: usize> Triangle<'v, N> {
    /// Sets up a triangle for drawing inside `clip`. `None` when it has no
    /// area, is a back face and `cull` is set, cannot touch `clip`, or has
    /// a vertex outside the limits (see [`RasterVertex::within_limits`]),
    /// or `clip` is larger than they allow ([`ClipRect::within_limits`]).
    /// A back face that is kept is reoriented (its `facing` says so).
    ///
    /// ```
    /// use fixshade::rasterizer::{ClipRect, RasterVertex, Triangle};
    /// let v = [(8, 8), (200, 8), (8, 200)].map(|(x, y)| RasterVertex { x, y, attr: [0i64] });
    /// let clip = ClipRect::of_size(16, 16).unwrap();
    /// // Counter-clockwise on screen (y down) is a back face: culled.
    /// assert!(Triangle::setup(&v, clip, true).is_none());
    /// assert!(Triangle::setup(&[v[0], v[2], v[1]], clip, true).is_some());
    /// ```
    #[inline(always)]
    pub fn setup(v: &'v [RasterVertex<N>; 3], clip: ClipRect, cull: bool) -> Option<Self> {
        Self::setup_rows(v, clip, (clip.y0, clip.y1), cull)
    }

    /// As [`Triangle::setup`] for the rows `rows.0 ..= rows.1` of the
    /// viewport `viewport` only (a band). The attribute planes are anchored
    /// as for the whole viewport and the edges and rows start exactly where
    /// the whole-viewport walk would be at the band's first row, so every
    /// span is bit for bit the span the whole viewport gives on that row.
    ///
    /// ```
    /// use fixshade::rasterizer::{ClipRect, RasterVertex, Triangle};
    /// let v = [(8, 8), (8, 300), (250, 8)].map(|(x, y)| RasterVertex { x, y, attr: [x * y] });
    /// let vp = ClipRect::of_size(16, 16).unwrap();
    /// let mut whole = Vec::new();
    /// Triangle::setup(&v, vp, true).unwrap().for_each_span(|s| whole.push((s.y, s.x0, s.x1, s.start)));
    /// let mut banded = Vec::new();
    /// for y0 in (0..16).step_by(3) {
    ///     if let Some(t) = Triangle::setup_rows(&v, vp, (y0, (y0 + 2).min(15)), true) {
    ///         t.for_each_span(|s| banded.push((s.y, s.x0, s.x1, s.start)));
    ///     }
    /// }
    /// assert_eq!(whole, banded);
    /// ```
    #[inline(always)]
    pub fn setup_rows(
        v: &'v [RasterVertex<N>; 3],
        viewport: ClipRect,
        rows: (i32, i32),
        cull: bool,
    ) -> Option<Self> {
        if !(v.iter().all(RasterVertex::within_limits) && viewport.within_limits()) {
            return None;
        }
        let culled = cull.then_some(Facing::Back);
        Self::setup_rows_within(v, viewport, rows, culled, Cover::Untested)
    }

    /// [`Triangle::setup_rows`] for vertices the caller knows to be within
    /// the limits (the renderer's, which it clamps when it snaps them): no
    /// check. Outside them a debug build may panic on overflow and a
    /// release build may draw the wrong pixels of `viewport`. `culled`: the
    /// facing that draws nothing (`Some(Back)`: culling). `cover`: what
    /// the caller knows of a tiny box (the renderer tests an unclipped
    /// triangle's before it lights it). The pixels are the same whichever
    /// it says: a tiny box's walk from its mask gives the spans the walk
    /// along its edges would.
    #[inline(always)]
    pub(crate) fn setup_rows_within(
        v: &'v [RasterVertex<N>; 3],
        viewport: ClipRect,
        rows: (i32, i32),
        culled: Option<Facing>,
        cover: Cover,
    ) -> Option<Self> {
        debug_assert!(v.iter().all(RasterVertex::within_limits) && viewport.within_limits());
        let clip = viewport;
        let caller = v;
        let a = area2(v);
        if a == 0 {
            return None;
        }
        // With y down, a triangle counter-clockwise in NDC (a front face)
        // has a negative area; coverage wants it positive.
        // References, not copies, of the oriented vertices.
        let (facing, v) = if a < 0 {
            (Facing::Front, [&v[0], &v[2], &v[1]])
        } else {
            (Facing::Back, [&v[0], &v[1], &v[2]])
        };
        if culled == Some(facing) {
            return None;
        }
        let a = a.abs();
        // Pixel bounds of the samples (16x+8 within [min, max]).
        let minx = v[0].x.min(v[1].x).min(v[2].x);
        let maxx = v[0].x.max(v[1].x).max(v[2].x);
        let miny = v[0].y.min(v[1].y).min(v[2].y);
        let maxy = v[0].y.max(v[1].y).max(v[2].y);
        // ⌈(m − 8)/16⌉ = (m + 7) >> 4 and ⌊(m − 8)/16⌋ = (m − 8) >> 4
        // (arithmetic shifts floor).
        let x_lo = ((minx + 7) >> 4).max(clip.x0 as i64);
        let x_hi = ((maxx - 8) >> 4).min(clip.x1 as i64);
        let y_lo = ((miny + 7) >> 4).max(clip.y0 as i64);
        let y_hi = ((maxy - 8) >> 4).min(clip.y1 as i64);
        // The rows drawn: the band's part of the viewport's rows.
        let r_lo = y_lo.max(rows.0 as i64);
        // A box of at most TINY pixel centres, all in the rows drawn, is
        // tested centre by centre, unless the caller has (the renderer
        // does for unclipped triangles, before lighting them; clipped
        // pieces and `setup_rows` callers are tested here): none covered,
        // nothing is drawn; else the rows and edges of the walk come from
        // the mask, not from the triangle's edges. (The box lies within
        // the vertices' box: each side below 2^26 pixels.)
        let mask = match cover {
            Cover::Mask(m) => m,
            Cover::Skip => 0,
            Cover::Untested => {
                if x_lo <= x_hi
                    && r_lo == y_lo
                    && y_lo <= y_hi
                    && y_hi <= rows.1 as i64
                    && mul_narrow(x_hi - x_lo + 1, y_hi - y_lo + 1) <= TINY
                {
                    let m = coverage(v.map(|p| (p.x, p.y)), (x_lo, x_hi), (y_lo, y_hi));
                    if m == 0 {
                        return None;
                    }
                    m
                } else {
                    0
                }
            }
        };
        let idle = EdgeLine {
            a: (0, 0),
            dx: 0,
            dy: 0,
        };
        let (left, right, next, next_left, switch, r_lo, y_end) =
            if let Some((left, right, first, last)) = masked_walk(mask, (x_lo, x_hi), y_lo) {
                (left, right, idle, false, i64::MAX, first, last)
            } else {
                let mut y_end = y_hi;
                // Sort the edges into the left chain (dy < 0: `E ≥ 0` admits the
                // columns right of them) and the right chain (dy > 0). Within the
                // triangle's rows, the row's span lies between the two chains: one
                // chain is a single edge, the other two edges meeting at the middle
                // vertex, and on a side with two edges the other edge's line never
                // binds (the triangle is convex; on the middle vertex's own row both
                // give the same bound, ties included, as both pass through it).
                // A horizontal edge (`dy = 0`, at most one) bounds rows only: a top
                // one (`dx > 0`, top-left) admits its own row, which the bounding
                // box already starts at; a bottom one (`dx < 0`) excludes its row.
                let mut lines = [idle; 3];
                // Left edges fill `lines` from the front, right ones from the back.
                let (mut nl, mut nr) = (0, 3);
                for (a, b) in [(0, 1), (1, 2), (2, 0)] {
                    let line = EdgeLine {
                        a: (v[a].x, v[a].y),
                        dx: v[b].x - v[a].x,
                        dy: v[b].y - v[a].y,
                    };
                    if line.dy < 0 {
                        lines[nl] = line;
                        nl += 1;
                    } else if line.dy > 0 {
                        nr -= 1;
                        lines[nr] = line;
                    } else if line.dx < 0 {
                        // ys < a.y: 16r + 8 ≤ a.y − 1.
                        y_end = y_end.min((line.a.1 - 9) >> 4);
                    }
                }
                let r_hi = y_end.min(rows.1 as i64);
                if x_lo > x_hi || r_lo > r_hi {
                    return None;
                }
                // The edges start at the first drawn row: the DDA's quotient and
                // remainder there are those the walk from `y_lo` reaches (both are
                // the exact floor of the same numerator).
                let ys0 = 16 * r_lo + 8;
                let (mut left, mut right) = (lines[0], lines[2]);
                let (mut next, mut next_left, mut switch) = (lines[1], false, i64::MAX);
                if nl == 2 || nr == 1 {
                    // Two edges on one side, `lines[1]` the second one. The upper
                    // one ends (left chain: starts; right chain: the edges run
                    // down) at the middle vertex.
                    let (e0, e1) = (lines[if nl == 2 { 0 } else { 2 }], lines[1]);
                    let top = |e: &EdgeLine| if e.dy < 0 { e.a.1 + e.dy } else { e.a.1 };
                    let (upper, lower) = if top(&e0) < top(&e1) {
                        (e0, e1)
                    } else {
                        (e1, e0)
                    };
                    let mid_y = if upper.dy < 0 {
                        upper.a.1
                    } else {
                        upper.a.1 + upper.dy
                    };
                    // The first row whose sample is at or below the middle vertex.
                    let r_mid = (mid_y + 7) >> 4;
                    let first = if r_lo < r_mid {
                        (next, switch) = (lower, r_mid);
                        upper
                    } else {
                        lower
                    };
                    next_left = nl == 2;
                    if next_left {
                        left = first;
                    } else {
                        right = first;
                    }
                }
                (
                    left.at(ys0),
                    right.at(ys0),
                    next,
                    next_left,
                    switch,
                    r_lo,
                    y_end,
                )
            };
        let r_hi = y_end.min(rows.1 as i64);
        let r = Recip::new(a);
        // Sample at the origin pixel, relative to each vertex.
        let (sx, sy) = (16 * x_lo + 8, 16 * y_lo + 8);
        // λ1 ∝ E20(s), λ2 ∝ E01(s): for the plane equations, which a small
        // triangle does not use.
        let lambdas = || {
            (
                (v[0].x - v[2].x) * (sy - v[2].y) - (v[0].y - v[2].y) * (sx - v[2].x),
                (v[1].x - v[0].x) * (sy - v[0].y) - (v[1].y - v[0].y) * (sx - v[0].x),
            )
        };
        let mut exact = false;
        // Small: bounding box within 256 pixels (2^12 sub-pixels) a side.
        let small = maxx - minx < 1 << 12 && maxy - miny < 1 << 12;
        let mut origin = [0i64; N];
        let mut ddx = [0i64; N];
        let mut ddy = [0i64; N];
        for i in 0..N {
            let d1 = v[1].attr[i] - v[0].attr[i];
            let d2 = v[2].attr[i] - v[0].attr[i];
            let (gx, gy) = if small {
                // |d| < 2^34, coordinate differences < 2^12: below 2^47;
                // divided by an area of at least 1 and scaled by 16, the
                // gradients stay below 2^51.
                let m = mul_by_small;
                let nx = m(d1, v[2].y - v[0].y) + m(d2, v[0].y - v[1].y);
                let ny = m(d1, v[0].x - v[2].x) + m(d2, v[1].x - v[0].x);
                (
                    r.div_i64(nx, SUBPIXEL_BITS) as i64,
                    r.div_i64(ny, SUBPIXEL_BITS) as i64,
                )
            } else {
                // The reciprocal through `black_box`: else LLVM hoists
                // `m` times the coordinate differences (four i128
                // multiplies: to it loop-invariant and cheap) out of the
                // attribute loop and computes them for every triangle,
                // small ones included (callgrind, S3 on x86-64: 0.34 M
                // instructions a frame; QEMU, S1 on the Cortex-M0, where
                // they are 24 library calls a triangle: 0.7 M).
                let r = core::hint::black_box(r);
                // Below 2^65: i128.
                let (d1, d2) = (d1 as i128, d2 as i128);
                let nx = d1 * (v[2].y - v[0].y) as i128 + d2 * (v[0].y - v[1].y) as i128;
                let ny = d1 * (v[0].x - v[2].x) as i128 + d2 * (v[1].x - v[0].x) as i128;
                let steep = STEEP as i128;
                (
                    r.div(nx, SUBPIXEL_BITS).clamp(-2 * steep, 2 * steep) as i64,
                    r.div(ny, SUBPIXEL_BITS).clamp(-2 * steep, 2 * steep) as i64,
                )
            };
            exact |= gx.unsigned_abs() as u128 > STEEP || gy.unsigned_abs() as u128 > STEEP;
            ddx[i] = gx.clamp(-(STEEP as i64), STEEP as i64);
            ddy[i] = gy.clamp(-(STEEP as i64), STEEP as i64);
            origin[i] = if small && !exact {
                // From vertex 0 along the gradients: the origin is within
                // 256 px (4096 sub-pixels) of it, |gradient| ≤ 2^40, so the
                // products stay below 2^53; the gradients' rounding (½ unit)
                // moves the result by at most 128 units.
                let t = mul_by_narrow(ddx[i], sx - v[0].x) + mul_by_narrow(ddy[i], sy - v[0].y);
                v[0].attr[i] + ((t + 8) >> 4)
            } else {
                // (As above: not hoisted.)
                let (e20, e01) = core::hint::black_box(lambdas)();
                plane_at(v, r, i, e20, e01)
            };
        }
        let bounded = small
            && !exact
            && ddx
                .iter()
                .chain(&ddy)
                .all(|g| (-BOUNDED_GRADIENT..=BOUNDED_GRADIENT).contains(g));
        // The planes are anchored at the viewport's corner (x_lo, y_lo), so
        // that rounding does not depend on the band; the first drawn row's
        // values are the origin plus k row steps, exactly (integers; the
        // wrapping product equals k wrapping additions).
        let k = r_lo - y_lo;
        if k != 0 && !exact {
            for (o, d) in origin.iter_mut().zip(&ddy) {
                *o = o.wrapping_add(d.wrapping_mul(k));
            }
        }
        Some(Triangle {
            walk: Walk {
                left,
                right,
                next,
                next_left,
                switch,
                x_lo,
                x_hi,
                y: r_lo,
                y_end,
                row: origin,
                ddx,
                ddy,
                bounded,
            },
            y_hi: r_hi,
            exact,
            recip: r,
            verts: caller,
            swapped: facing == Facing::Front,
            facing,
        })
    }

    /// Calls `f` with each non-empty span, top to bottom.
    #[inline(always)]
    ///
    /// ```
    /// use fixshade::rasterizer::{ClipRect, RasterVertex, Triangle};
    /// // Two triangles sharing a diagonal: each pixel of the square once.
    /// let q = [(0, 0), (256, 0), (256, 256), (0, 256)]
    ///     .map(|(x, y)| RasterVertex { x, y, attr: [] });
    /// let clip = ClipRect::of_size(16, 16).unwrap();
    /// let mut hits = [0u8; 256];
    /// for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
    ///     Triangle::setup(&t, clip, false).unwrap().for_each_span(|s| {
    ///         for x in s.x0..=s.x1 {
    ///             hits[(s.y * 16 + x) as usize] += 1;
    ///         }
    ///     });
    /// }
    /// assert!(hits.iter().all(|&h| h == 1));
    /// ```
    pub fn for_each_span(self, f: impl FnMut(&Span<N>)) {
        self.walk_rows(f);
    }

    /// As [`Triangle::for_each_span`], and then the walk paused below the
    /// last row drawn if the triangle goes on below it (and is not a
    /// sliver): what [`Walk::resume`] continues in the next band.
    #[inline(always)]
    ///
    /// ```
    /// use fixshade::rasterizer::{ClipRect, RasterVertex, Triangle};
    /// let v = [(8, 8), (8, 200), (200, 8)].map(|(x, y)| RasterVertex { x, y, attr: [] });
    /// let vp = ClipRect::of_size(16, 16).unwrap();
    /// // Rows 0 ..= 3 of its 12: it goes on below.
    /// let t = Triangle::setup_rows(&v, vp, (0, 3), false).unwrap();
    /// assert!(t.walk_rows(|s| assert!(s.y <= 3)).is_some());
    /// // All of them: nothing left.
    /// let t = Triangle::setup_rows(&v, vp, (0, 15), false).unwrap();
    /// assert!(t.walk_rows(|_| ()).is_none());
    /// ```
    pub fn walk_rows(self, f: impl FnMut(&Span<N>)) -> Option<Walk<N>> {
        let Triangle {
            mut walk,
            y_hi,
            exact,
            recip,
            verts,
            swapped,
            ..
        } = self;
        walk.rows(
            y_hi,
            exact,
            |x, y| exact_start(verts, swapped, recip, x, y),
            f,
        );
        (!exact && walk.y <= walk.y_end).then_some(walk)
    }
}

impl<const N: usize> Walk<N> {
    /// Draws the rows `rows.0 ..= rows.1` (a band) that the triangle has
    /// left, stepping over any before `rows.0` without drawing; returns the
    /// walk paused below `rows.1` if the triangle goes on below it.
    #[inline(always)]
    ///
    /// ```
    /// use fixshade::rasterizer::{ClipRect, RasterVertex, Triangle};
    /// let v = [(8, 8), (8, 200), (200, 8)].map(|(x, y)| RasterVertex { x, y, attr: [] });
    /// let vp = ClipRect::of_size(16, 16).unwrap();
    /// let walk = Triangle::setup_rows(&v, vp, (0, 1), false).unwrap().walk_rows(|_| ()).unwrap();
    /// // Rows 2 ..= 4 are stepped over without drawing; 5 ..= 15 drawn.
    /// let mut ys = Vec::new();
    /// assert!(walk.resume((5, 15), |s| ys.push(s.y)).is_none());
    /// assert_eq!(ys, (5..12).collect::<Vec<_>>());
    /// ```
    pub fn resume(mut self, rows: (i32, i32), f: impl FnMut(&Span<N>)) -> Option<Walk<N>> {
        let (first, last) = (rows.0 as i64, rows.1 as i64);
        if self.y < first {
            self.rows(first - 1, false, |_, _| [0; N], |_| ());
        }
        self.rows(last, false, |_, _| [0; N], f);
        (self.y <= self.y_end).then_some(self)
    }

    /// Walks the rows from `self.y` to `last` (and the triangle's last),
    /// calling `f` with each non-empty span; a sliver's span starts come
    /// from `exact_start`.
    #[inline(always)]
    fn rows(
        &mut self,
        last: i64,
        exact: bool,
        exact_start: impl Fn(i64, i64) -> [i64; N],
        mut f: impl FnMut(&Span<N>),
    ) {
        let last = last.min(self.y_end);
        let mut row = self.row;
        let (mut left, mut right) = (self.left, self.right);
        let mut y = self.y;
        while y <= last {
            if y == self.switch {
                let e = self.next.at(16 * y + 8);
                if self.next_left {
                    left = e;
                } else {
                    right = e;
                }
            }
            let lo = left.q.max(self.x_lo);
            let hi = right.q.min(self.x_hi);
            if lo <= hi {
                let mut start = row;
                // Off x86-64, `black_box` (an empty assembly statement)
                // hides the flag from the optimiser: a loop unswitched on
                // `exact` calls `f` from two places, and `f` (the whole span
                // shader) is then not inlined on Cortex-M (QEMU count, S1 on
                // the M4: 6.40 M instructions without it, 6.10 M with). On
                // x86-64 LLVM keeps `f` inline either way, and the plain flag
                // spares the flag's trip through the stack in every span
                // (callgrind: S1 2.538 M → 2.524 M, S3 22.12 M → 22.06 M).
                let exact_here = if cfg!(target_arch = "x86_64") {
                    exact
                } else {
                    core::hint::black_box(exact)
                };
                if exact_here {
                    start = exact_start(lo, y);
                } else if cfg!(fixshade_soft_mul64) && self.bounded {
                    // A bounded triangle is under 256 pixels wide and its
                    // gradients within ±2^24: two 16 × 16-bit products
                    // each where a 64-bit product is a library call.
                    let off = (lo - self.x_lo) as u32;
                    for (s, d) in start.iter_mut().zip(&self.ddx) {
                        *s += mul_i32_u16(*d as i32, off);
                    }
                } else {
                    let off = lo - self.x_lo;
                    for (s, d) in start.iter_mut().zip(&self.ddx) {
                        *s += mul_by_narrow(*d, off);
                    }
                }
                f(&Span {
                    y: y as i32,
                    x0: lo as i32,
                    x1: hi as i32,
                    start,
                    step: self.ddx,
                    bounded: self.bounded,
                });
            }
            if !exact {
                for (r, d) in row.iter_mut().zip(&self.ddy) {
                    *r += d;
                }
            }
            left.step();
            right.step();
            y += 1;
        }
        (self.row, self.left, self.right, self.y) = (row, left, right, y);
    }
}

/// The attributes at pixel `(x, y)` from the plane equations (a sliver's
/// span start; rare, so kept out of the span walk); `swapped`: the
/// triangle was oriented by swapping its last two vertices.
#[cold]
#[inline(never)]
fn exact_start<const N: usize>(
    c: &[RasterVertex<N>; 3],
    swapped: bool,
    recip: Recip,
    x: i64,
    y: i64,
) -> [i64; N] {
    let v = if swapped {
        [&c[0], &c[2], &c[1]]
    } else {
        [&c[0], &c[1], &c[2]]
    };
    let (sx, sy) = (16 * x + 8, 16 * y + 8);
    let e20 = (v[0].x - v[2].x) * (sy - v[2].y) - (v[0].y - v[2].y) * (sx - v[2].x);
    let e01 = (v[1].x - v[0].x) * (sy - v[0].y) - (v[1].y - v[0].y) * (sx - v[0].x);
    core::array::from_fn(|i| plane_at(v, recip, i, e20, e01))
}

/// Sets up triangle `v` and calls `f` with each of its spans inside `clip`,
/// top to bottom; returns how it faced, or `None` if it drew nothing
/// (no area, culled, no pixel centre inside, or a vertex or `clip` outside
/// the limits: see [`RasterVertex::within_limits`] and
/// [`ClipRect::within_limits`]). Set-up and span walk are
/// one inlined step: the set-up triangle never leaves the stack frame.
///
/// ```
/// use fixshade::rasterizer::{rasterize, ClipRect, RasterVertex};
/// let v = [(8, 8), (8, 200), (200, 8)].map(|(x, y)| RasterVertex { x, y, attr: [] });
/// let mut pixels = 0;
/// rasterize(&v, ClipRect::of_size(16, 16).unwrap(), true, |s| pixels += s.x1 - s.x0 + 1);
/// assert!(pixels > 50);
/// ```
#[inline(always)]
pub fn rasterize<const N: usize>(
    v: &[RasterVertex<N>; 3],
    clip: ClipRect,
    cull: bool,
    f: impl FnMut(&Span<N>),
) -> Option<Facing> {
    rasterize_rows(v, clip, (clip.y0, clip.y1), cull, f)
}

/// As [`rasterize`], drawing only rows `rows.0 ..= rows.1` of `viewport`
/// (a band), with exactly the spans the whole viewport gives on those rows
/// (see [`Triangle::setup_rows`]).
///
/// ```
/// use fixshade::rasterizer::{rasterize_rows, ClipRect, RasterVertex};
/// let v = [(8, 8), (8, 200), (200, 8)].map(|(x, y)| RasterVertex { x, y, attr: [] });
/// let mut rows = Vec::new();
/// rasterize_rows(&v, ClipRect::of_size(16, 16).unwrap(), (4, 5), true, |s| rows.push(s.y));
/// assert_eq!(rows, [4, 5]);
/// ```
#[inline(always)]
pub fn rasterize_rows<const N: usize>(
    v: &[RasterVertex<N>; 3],
    viewport: ClipRect,
    rows: (i32, i32),
    cull: bool,
    f: impl FnMut(&Span<N>),
) -> Option<Facing> {
    let t = Triangle::setup_rows(v, viewport, rows, cull)?;
    let facing = t.facing;
    t.for_each_span(f);
    Some(facing)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::{
        coverage, coverage_from, masked_walk, ClipRect, Cover, EdgeLine, RasterVertex, Recip,
        Triangle, NARROW_NUM, TINY,
    };

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

    /// A tiny box's walk from its coverage mask gives exactly the spans
    /// the walk along its edges gives (rows, columns, attribute starts and
    /// steps), whether the set-up tests the box itself or is handed the
    /// mask as the renderer makes it, in the whole viewport and in bands:
    /// random tiny triangles of either winding on the sub-pixel grid, some
    /// across the viewport's edges, some slivers (three vertices within a
    /// sub-pixel or two of a line through a pixel centre) with steep
    /// gradients.
    #[test]
    fn masked_walk_is_the_edge_walk() {
        let mut bits = xorshift(0x9e37_79b9_7f4a_7c15);
        let mut next = move |m: i64| (bits() % (2 * m as u64 + 1)) as i64 - m;
        let vp = ClipRect::of_size(48, 40).unwrap();
        let whole = (vp.y0, vp.y1);
        let (mut masked, mut empty, mut slivers, mut banded) = (0, 0, 0, 0);
        for n in 0..100_000 {
            let c = (24 * 16 + next(26 * 16), 20 * 16 + next(22 * 16));
            let size = 8 + next(8).abs() * 8;
            let mut v: [RasterVertex<2>; 3] = core::array::from_fn(|_| RasterVertex {
                x: c.0 + next(size),
                y: c.1 + next(size),
                attr: [next(1 << 20), next((1 << 33) - 1)],
            });
            if n % 4 == 0 {
                // A sliver along a line through a pixel centre.
                let p = (16 * (c.0 >> 4) + 8, 16 * (c.1 >> 4) + 8);
                let (a, b) = (next(12), next(12));
                let mut at = |dx: i64, dy: i64, e: i64| (p.0 + dx + next(e), p.1 + dy + next(e));
                let w = [at(-a, -b, 1), at(a, b, 1), at(0, 0, 2)];
                for (v, w) in v.iter_mut().zip(w) {
                    (v.x, v.y) = w;
                }
            }
            if super::area2(&v) == 0 {
                continue;
            }
            let spans = |cover, rows| {
                let mut out = Vec::new();
                let t = Triangle::setup_rows_within(&v, vp, rows, None, cover);
                let exact = t.is_some_and(|t| t.exact);
                if let Some(t) = t {
                    t.for_each_span(|s| out.push((s.y, s.x0, s.x1, s.start, s.step, s.bounded)));
                }
                (out, exact)
            };
            let (edges, exact) = spans(Cover::Skip, whole);
            assert_eq!(spans(Cover::Untested, whole).0, edges, "{v:?}");
            // A band of 1 to 4 rows somewhere in the viewport.
            let y0 = next(20).abs() as i32 * 2;
            let band = (y0, (y0 + next(3).abs() as i32).min(vp.y1));
            assert_eq!(
                spans(Cover::Untested, band).0,
                spans(Cover::Skip, band).0,
                "{v:?}"
            );
            // The renderer's test: the box of centres in the viewport.
            let lo = |m: i64, at: i32| ((m + 7) >> 4).max(at as i64);
            let hi = |m: i64, at: i32| ((m - 8) >> 4).min(at as i64);
            let (xs, ys) = (v.map(|p| p.x), v.map(|p| p.y));
            let min = |a: [i64; 3]| a[0].min(a[1]).min(a[2]);
            let max = |a: [i64; 3]| a[0].max(a[1]).max(a[2]);
            let bx = (lo(min(xs), vp.x0), hi(max(xs), vp.x1));
            let by = (lo(min(ys), vp.y0), hi(max(ys), vp.y1));
            if bx.0 > bx.1 || by.0 > by.1 || (bx.1 - bx.0 + 1) * (by.1 - by.0 + 1) > TINY {
                continue;
            }
            let front =
                (v[1].x - v[0].x) * (v[2].y - v[0].y) < (v[1].y - v[0].y) * (v[2].x - v[0].x);
            let o = if front { [0, 2, 1] } else { [0, 1, 2] };
            let m = coverage(o.map(|k| (v[k].x, v[k].y)), bx, by);
            if m == 0 {
                assert!(edges.is_empty(), "{v:?}");
                empty += 1;
                continue;
            }
            // (Every tiny mask has a walk: TINY ≤ 4.)
            assert!(masked_walk(m, bx, by.0).is_some());
            masked += 1;
            slivers += exact as u32;
            assert_eq!(spans(Cover::Mask(m), whole).0, edges, "{v:?}");
            if by.0 >= band.0 as i64 && by.1 <= band.1 as i64 {
                banded += 1;
                assert_eq!(spans(Cover::Mask(m), band).0, edges, "{v:?}");
            }
        }
        assert!(masked > 5_000 && empty > 5_000, "{masked} {empty}");
        assert!(slivers > 10 && banded > 100, "{slivers} {banded}");
    }

    /// The 32-bit edge set-up of 32-bit targets gives the 64-bit one's
    /// DDA wherever it applies: random edges of every slope and sign,
    /// vertices anywhere on the sub-pixel grid (negative too), samples
    /// near and at the limits.
    #[test]
    fn narrow_edge_is_the_wide_one() {
        let mut bits = xorshift(0x2545_f491_4f6c_dd1d);
        let mut next = move |m: i64| (bits() % (2 * m as u64 + 1)) as i64 - m;
        let mut narrow = 0;
        for _ in 0..200_000 {
            let a = (next(1 << 28), next(1 << 28));
            let (dx, dy) = (next(1 << 14), next(1 << 14));
            if dy == 0 {
                continue;
            }
            let ys = a.1 + next(1 << 15);
            let e = EdgeLine { a, dx, dy };
            if let Some(n) = e.at_narrow(ys) {
                assert_eq!(n, e.at_wide(ys), "{e:?} at {ys}");
                narrow += 1;
            }
        }
        assert!(narrow > 100_000, "{narrow}");
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
                for up in [0, 4] {
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
}

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
//! Per row, each edge bounds the span on one side; the bound is found by an
//! exact integer division (floor or ceiling), so the span is exact. The
//! span is clipped to the caller's rectangle (the target's bounds).
//!
//! # Attributes
//! Each attribute (depth, colour, normal, position; scaled by the caller)
//! is a plane `A(p) = A0 + ΔA1·λ1 + ΔA2·λ2` with affine barycentrics at
//! pixel centres (SPEC.md 4). Setup computes its per-pixel gradients with
//! one reciprocal of the area per triangle (a 32-bit mantissa: relative
//! error 2⁻³¹) and its value at the clipped bounding box's corner exactly
//! (`i128`); spans step from there. Within a target of at most 2¹³ pixels
//! a side the stepping error stays below 2⁻⁴ of the attribute's unit.

/// Sub-pixel bits of the snapping grid (SPEC.md 5: 1/16 pixel).
pub const SUBPIXEL_BITS: u32 = 4;
/// The largest snapped coordinate magnitude, in 1/16 pixel.
pub const COORD_LIMIT: i64 = 1 << 28;

/// A triangle vertex in window space: position in 1/16 pixel and `N`
/// attributes in the caller's units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RasterVertex<const N: usize> {
    /// x in 1/16 pixel, within ±[`COORD_LIMIT`].
    pub x: i64,
    /// y in 1/16 pixel (down), within ±[`COORD_LIMIT`].
    pub y: i64,
    /// Attributes.
    pub attr: [i64; N],
}

/// The inclusive pixel rectangle that may be drawn (the target's bounds).
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

impl ClipRect {
    /// The rectangle of a `width × height` target at the origin; `None`
    /// when it is empty.
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
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Facing {
    /// Counter-clockwise in NDC (clockwise on screen, y down).
    Front,
    /// Clockwise in NDC.
    Back,
}

/// The signed doubled area `E_{01}(v2)` in 1/256 pixel²: negative for a
/// front face (counter-clockwise in NDC; window y points down).
#[inline]
pub fn area2<const N: usize>(v: &[RasterVertex<N>; 3]) -> i64 {
    (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x)
}

#[derive(Clone, Copy, Debug)]
struct Edge {
    ax: i64,
    ay: i64,
    dx: i64,
    dy: i64,
    top_left: bool,
}

impl Edge {
    fn new(a: (i64, i64), b: (i64, i64)) -> Edge {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        Edge {
            ax: a.0,
            ay: a.1,
            dx,
            dy,
            top_left: dy < 0 || (dy == 0 && dx > 0),
        }
    }

    /// Narrows `[lo, hi]` (pixel columns) to the samples of row sample
    /// `ys` that this edge admits. Returns `false` if none.
    #[inline]
    fn bound(&self, ys: i64, lo: &mut i64, hi: &mut i64) -> bool {
        // E(px) = K − dy·px, |K| < 2^59.
        let k = self.dx * (ys - self.ay) + self.dy * self.ax;
        if self.dy == 0 {
            return k > 0 || (k == 0 && self.top_left);
        }
        if self.dy < 0 {
            // E = K + m·px, m > 0: px ≥ −K/m (top-left), px > −K/m otherwise.
            let m = -self.dy;
            let px_min = if self.top_left {
                ceil_div(-k, m)
            } else {
                floor_div(-k, m) + 1
            };
            // 16x + 8 ≥ px_min.
            *lo = (*lo).max(ceil_div(px_min - 8, 16));
        } else {
            // E = K − dy·px: px ≤ K/dy (top-left), px < K/dy otherwise.
            let px_max = if self.top_left {
                floor_div(k, self.dy)
            } else {
                ceil_div(k, self.dy) - 1
            };
            *hi = (*hi).min(floor_div(px_max - 8, 16));
        }
        true
    }
}

/// ⌊a / b⌋ for `b > 0`.
#[inline]
fn floor_div(a: i64, b: i64) -> i64 {
    let q = a / b;
    if (a % b) < 0 {
        q - 1
    } else {
        q
    }
}

/// ⌈a / b⌉ for `b > 0`.
#[inline]
fn ceil_div(a: i64, b: i64) -> i64 {
    let q = a / b;
    if (a % b) > 0 {
        q + 1
    } else {
        q
    }
}

/// `1 / area` as a 32-bit mantissa and a shift: `1/a ≈ m / 2^sh`.
#[derive(Clone, Copy, Debug)]
struct Recip {
    m: i128,
    sh: u32,
}

impl Recip {
    /// For `a > 0` (at most 2⁶⁰).
    fn new(a: i64) -> Recip {
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
            m: ((1u64 << 63) / a32) as i128,
            sh: (63 + e) as u32,
        }
    }

    /// `round(num · 2^up / a)`; `|num| < 2⁹⁴` keeps the product below 2¹²⁶.
    #[inline]
    fn div(self, num: i128, up: u32) -> i128 {
        let sh = self.sh - up;
        (num * self.m + (1i128 << (sh - 1))) >> sh
    }
}

/// A set-up triangle: the edges, the rows and columns it may cover, and its
/// attribute planes.
#[derive(Clone, Copy, Debug)]
pub struct Triangle<const N: usize> {
    edges: [Edge; 3],
    x_lo: i64,
    x_hi: i64,
    y_lo: i64,
    y_hi: i64,
    /// Attribute values at pixel (x_lo, y_lo).
    origin: [i64; N],
    /// Per-pixel gradients along x.
    ddx: [i64; N],
    /// Per-pixel gradients along y.
    ddy: [i64; N],
    /// Gradients too steep to step (a sliver): each span's start is
    /// evaluated from the plane equation instead.
    exact: bool,
    recip: Recip,
    verts: [RasterVertex<N>; 3],
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
    v: &[RasterVertex<N>; 3],
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
}

impl<const N: usize> Triangle<N> {
    /// Sets up a triangle for drawing inside `clip`. `None` when it has no
    /// area, is a back face and `cull` is set, or cannot touch `clip`.
    /// A back face that is kept is reoriented (its `facing` says so).
    pub fn setup(v: &[RasterVertex<N>; 3], clip: ClipRect, cull: bool) -> Option<Triangle<N>> {
        let a = area2(v);
        if a == 0 {
            return None;
        }
        // With y down, a triangle counter-clockwise in NDC (a front face)
        // has a negative area; coverage wants it positive.
        let (facing, v) = if a < 0 {
            (Facing::Front, [v[0], v[2], v[1]])
        } else if cull {
            return None;
        } else {
            (Facing::Back, *v)
        };
        let a = a.abs();
        // Pixel bounds of the samples (16x+8 within [min, max]).
        let minx = v[0].x.min(v[1].x).min(v[2].x);
        let maxx = v[0].x.max(v[1].x).max(v[2].x);
        let miny = v[0].y.min(v[1].y).min(v[2].y);
        let maxy = v[0].y.max(v[1].y).max(v[2].y);
        let x_lo = ceil_div(minx - 8, 16).max(clip.x0 as i64);
        let x_hi = floor_div(maxx - 8, 16).min(clip.x1 as i64);
        let y_lo = ceil_div(miny - 8, 16).max(clip.y0 as i64);
        let y_hi = floor_div(maxy - 8, 16).min(clip.y1 as i64);
        if x_lo > x_hi || y_lo > y_hi {
            return None;
        }
        let edges = [
            Edge::new((v[0].x, v[0].y), (v[1].x, v[1].y)),
            Edge::new((v[1].x, v[1].y), (v[2].x, v[2].y)),
            Edge::new((v[2].x, v[2].y), (v[0].x, v[0].y)),
        ];
        let r = Recip::new(a);
        // Sample at the origin pixel, relative to each vertex.
        let (sx, sy) = (16 * x_lo + 8, 16 * y_lo + 8);
        // λ1 ∝ E20(s), λ2 ∝ E01(s).
        let e20 = (v[0].x - v[2].x) * (sy - v[2].y) - (v[0].y - v[2].y) * (sx - v[2].x);
        let e01 = (v[1].x - v[0].x) * (sy - v[0].y) - (v[1].y - v[0].y) * (sx - v[0].x);
        let mut exact = false;
        let mut origin = [0i64; N];
        let mut ddx = [0i64; N];
        let mut ddy = [0i64; N];
        for i in 0..N {
            let d1 = (v[1].attr[i] - v[0].attr[i]) as i128;
            let d2 = (v[2].attr[i] - v[0].attr[i]) as i128;
            // |d| < 2^34 and |Y diffs| < 2^30: numerators below 2^65.
            let nx = d1 * (v[2].y - v[0].y) as i128 + d2 * (v[0].y - v[1].y) as i128;
            let ny = d1 * (v[0].x - v[2].x) as i128 + d2 * (v[1].x - v[0].x) as i128;
            let (gx, gy) = (r.div(nx, SUBPIXEL_BITS), r.div(ny, SUBPIXEL_BITS));
            exact |= gx.unsigned_abs() > STEEP || gy.unsigned_abs() > STEEP;
            ddx[i] = gx.clamp(-(STEEP as i128), STEEP as i128) as i64;
            ddy[i] = gy.clamp(-(STEEP as i128), STEEP as i128) as i64;
            origin[i] = plane_at(&v, r, i, e20, e01);
        }
        Some(Triangle {
            edges,
            x_lo,
            x_hi,
            y_lo,
            y_hi,
            origin,
            ddx,
            ddy,
            exact,
            recip: r,
            verts: v,
            facing,
        })
    }

    /// Calls `f` with each non-empty span, top to bottom.
    #[inline]
    pub fn for_each_span(&self, mut f: impl FnMut(&Span<N>)) {
        let mut row = self.origin;
        for y in self.y_lo..=self.y_hi {
            let ys = 16 * y + 8;
            let (mut lo, mut hi) = (self.x_lo, self.x_hi);
            let inside = self.edges.iter().all(|e| e.bound(ys, &mut lo, &mut hi));
            if inside && lo <= hi {
                let mut start = row;
                if self.exact {
                    let v = &self.verts;
                    let (sx, sy) = (16 * lo + 8, ys);
                    let e20 = (v[0].x - v[2].x) * (sy - v[2].y) - (v[0].y - v[2].y) * (sx - v[2].x);
                    let e01 = (v[1].x - v[0].x) * (sy - v[0].y) - (v[1].y - v[0].y) * (sx - v[0].x);
                    for (i, s) in start.iter_mut().enumerate() {
                        *s = plane_at(v, self.recip, i, e20, e01);
                    }
                } else {
                    let off = lo - self.x_lo;
                    for i in 0..N {
                        start[i] += self.ddx[i] * off;
                    }
                }
                f(&Span {
                    y: y as i32,
                    x0: lo as i32,
                    x1: hi as i32,
                    start,
                    step: self.ddx,
                });
            }
            if !self.exact {
                for i in 0..N {
                    row[i] += self.ddy[i];
                }
            }
        }
    }
}

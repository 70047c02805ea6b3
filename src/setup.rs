//! Triangle set-up and row walk in 32-bit arithmetic, for triangles whose
//! vertices lie inside the guard band.
//!
//! # Ranges
//! Window positions are in 1/16 pixel with `|X|, |Y| ≤` [`GUARD`]
//! (`2¹⁴ − 16`: ±1023 pixels). Then every difference of two coordinates is
//! below 2¹⁵ in magnitude, every product of two differences below 2³⁰ and
//! the doubled area `(X1−X0)(Y2−Y0) − (X2−X0)(Y1−Y0)` below 2³¹: `i32` is
//! exact for the area and for the edges' numerators (see [`Edge`]).
//!
//! # Coverage (SPEC.md 5)
//! Row `r` samples at `sy = 16r + 8`. An edge from `a` down to `b`
//! (`dy = b.y − a.y > 0`) meets that row at `X(sy) = a.x + dx·(sy − a.y)/dy`;
//! a span's left bound is the first column `c` with `16c + 8 ≥ X` (a sample
//! on a left edge is the triangle's), its right bound the last with
//! `16c + 8 < X`. A row whose sample lies on a horizontal top edge is
//! drawn, one on a horizontal bottom edge is not. That is the top-left
//! rule: two triangles sharing an edge draw each sample on it once.
//!
//! # Attributes
//! Each attribute is a plane stepped in integers: `A(c, r) = A_o + gx·(c −
//! c_o) + gy·(r − r_o)` with `gx`, `gy` the per-pixel gradients rounded to
//! integers (in units of 2⁻⁴ of the caller's) and `A_o` the plane at the
//! pixel nearest vertex 0. The sums are taken modulo 2³² (wrapping): they
//! are integers, so at every pixel they equal the same sum taken without
//! a bound, which differs from the exact plane by at most `½(|c − c_o| +
//! |r − r_o|) + 1` units, below 2¹¹ in the guard band. At a covered pixel
//! the exact plane lies between the vertex values, so a span's start,
//! rounded to the caller's units, is within 2⁷ + ½ of that range
//! ([`DRIFT`]). Along the span the caller steps by the gradient rounded to
//! its units, which adds at most ½ a pixel: pixel `k` of a span (`k = 0`
//! at its start) is within `DRIFT + k/2` of the range, below 2¹⁰ across a
//! tile's 2 032 columns.

use crate::num::widening::{mul_by_narrow, mul_i32_i16};
use crate::rasterizer::Recip;

/// The largest magnitude of a window coordinate, in 1/16 pixel.
pub(crate) const GUARD: i32 = (1 << 14) - 16;

/// Attribute values lie within `±ATTR` (caller's units): the differences,
/// times 2⁴, stay below 2³⁰.
pub(crate) const ATTR: i32 = 1 << 25;

/// How far a span's start strays from the range of the vertex values, in
/// the caller's units; each further pixel adds at most ½ (see the module's
/// text).
pub(crate) const DRIFT: i32 = 1 << 8;

/// A vertex: position in 1/16 pixel within ±[`GUARD`], attributes within
/// ±[`ATTR`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Vertex<const N: usize> {
    pub x: i32,
    pub y: i32,
    pub a: [i32; N],
}

/// One edge's column bound, stepped row by row: `q = ⌈n / D⌉` with
/// `n = q·D − rem`, `0 ≤ rem < D`, `D = 16·dy`.
///
/// `n = (a.x − 8)·dy + dx·(sy − a.y)`: `|a.x − 8| < 2¹⁴`, `dy < 2¹⁵`,
/// `|dx| < 2¹⁵` and `|sy − a.y| < 2¹⁵` (the sample row lies inside the
/// guard band), so `|n| < 2²⁹ + 2³⁰`, and `q·D ≤ n + D` fits too.
#[derive(Clone, Copy, Debug, Default)]
struct Edge {
    q: i32,
    rem: i32,
    d: i32,
    /// Per row: `q += step`, `rem += rstep`, then one carry.
    step: i32,
    rstep: i32,
}

impl Edge {
    /// The edge `a → b` (`b.y > a.y`) at sample row `sy`.
    #[inline(always)]
    fn new(ax: i32, ay: i32, bx: i32, by: i32, sy: i32) -> Edge {
        let (dx, dy) = (bx - ax, by - ay);
        let d = 16 * dy;
        let n = (ax - 8) * dy + dx * (sy - ay);
        let q = ceil_div(n, d);
        // ⌈dx/dy⌉·dy − dx ∈ [0, dy): the remainder's step, in 16ths.
        let step = ceil_div(dx, dy);
        Edge {
            q,
            rem: q * d - n,
            d,
            step,
            rstep: 16 * (step * dy - dx),
        }
    }

    #[inline(always)]
    fn advance(&mut self) {
        self.q += self.step;
        self.rem += self.rstep;
        if self.rem >= self.d {
            self.rem -= self.d;
            self.q -= 1;
        }
    }
}

/// `⌈n / d⌉` for `d > 0`.
#[inline(always)]
fn ceil_div(n: i32, d: i32) -> i32 {
    let q = n / d;
    if q * d < n {
        q + 1
    } else {
        q
    }
}

/// A span: row `y`, columns `x0 ..= x1`, the attributes at `x0` and their
/// step per pixel, in the caller's units (the four fractional bits
/// dropped, rounded to nearest).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Span<const N: usize> {
    pub y: i32,
    pub x0: i32,
    pub x1: i32,
    pub start: [i32; N],
    pub step: [i32; N],
}

/// Sets up the triangle `v` and calls `f` for each non-empty span on rows
/// `rows.0 ..= rows.1` and columns `cols.0 ..= cols.1`, its column and row
/// moved by `at` (the guard band's centre in the caller's pixels). Either
/// orientation is drawn; a triangle of no area draws nothing. Returns
/// whether the triangle was set up (it has area and a sample row among
/// `rows`).
#[inline(always)]
pub(crate) fn draw<const N: usize>(
    v: &[Vertex<N>; 3],
    cols: (i32, i32),
    rows: (i32, i32),
    at: (i32, i32),
    mut f: impl FnMut(&Span<N>),
) -> bool {
    // Sorted top to bottom.
    let (mut t, mut m, mut b) = (&v[0], &v[1], &v[2]);
    if m.y < t.y {
        core::mem::swap(&mut t, &mut m);
    }
    if b.y < m.y {
        core::mem::swap(&mut m, &mut b);
        if m.y < t.y {
            core::mem::swap(&mut t, &mut m);
        }
    }
    // Rows whose samples lie in [t.y, b.y): ⌈(t.y − 8)/16⌉ ..= ⌈(b.y − 8)/16⌉ − 1.
    let r_top = ((t.y + 7) >> 4).max(rows.0);
    let r_last = (((b.y + 7) >> 4) - 1).min(rows.1);
    if r_top > r_last {
        return false;
    }
    // Which side the long edge t → b bounds: the middle vertex's side of it.
    let cross = (b.x - t.x) * (m.y - t.y) - (b.y - t.y) * (m.x - t.x);
    if cross == 0 {
        return false;
    }
    let long_left = cross < 0;

    // Planes from v[0]; one reciprocal of the area.
    let (dx1, dy1) = (v[1].x - v[0].x, v[1].y - v[0].y);
    let (dx2, dy2) = (v[2].x - v[0].x, v[2].y - v[0].y);
    let area = dx1 * dy2 - dx2 * dy1;
    let recip = Recip::new(area.unsigned_abs() as i64);
    // The pixel holding vertex 0 and the offset of its centre from it.
    let (co, ro) = (v[0].x >> 4, v[0].y >> 4);
    let (ox, oy) = ((16 * co + 8 - v[0].x) as i64, (16 * ro + 8 - v[0].y) as i64);
    let mut gx = [0i32; N];
    let mut gy = [0i32; N];
    let mut base = [0i32; N];
    for k in 0..N {
        // Per pixel with 4 fractional bits: (d1·dy2 − d2·dy1)·2⁸ / area,
        // |d| < 2²⁶ and |dx|, |dy| < 2¹⁵ − 16 (`i16`): the numerators are
        // below 2⁴².
        let d1 = v[1].a[k] - v[0].a[k];
        let d2 = v[2].a[k] - v[0].a[k];
        let by = |d: i32, e: i32| mul_i32_i16(d, e as i16);
        let nx = by(d1, dy2) - by(d2, dy1);
        let ny = by(d2, dx1) - by(d1, dx2);
        // The quotients are below 2⁵⁰ (an area of at least 1), their
        // products with the offsets (`|o| ≤ 8`) below 2⁵⁴: `i64`.
        let (mut x, mut y) = (recip.div_i64(nx, 8) as i64, recip.div_i64(ny, 8) as i64);
        if area < 0 {
            (x, y) = (-x, -y);
        }
        // Only the values modulo 2³² are stepped (see the module's text).
        gx[k] = x as i32;
        gy[k] = y as i32;
        // The plane at pixel (co, ro)'s centre, 8 sixteenths at most from
        // vertex 0 on each axis.
        let at =
            ((v[0].a[k] as i64) << 4) + ((mul_by_narrow(x, ox) + mul_by_narrow(y, oy) + 8) >> 4);
        base[k] = at as i32;
    }

    // The edges at the first row: the long one, and the short one that
    // holds that row.
    let sy = 16 * r_top + 8;
    let long = Edge::new(t.x, t.y, b.x, b.y, sy);
    let upper = m.y > sy;
    let short = if upper {
        Edge::new(t.x, t.y, m.x, m.y, sy)
    } else {
        Edge::new(m.x, m.y, b.x, b.y, sy)
    };
    // The first row whose sample lies at or below the middle vertex, where
    // the lower short edge takes over.
    let switch = if upper { (m.y + 7) >> 4 } else { i32::MAX };
    let (mut left, mut right) = if long_left {
        (long, short)
    } else {
        (short, long)
    };
    let mut row = [0i32; N];
    for k in 0..N {
        row[k] = base[k].wrapping_add(gy[k].wrapping_mul(r_top - ro));
    }
    let round = |a: i32| a.wrapping_add(8) >> 4;
    let step = gx.map(round);
    let mut y = r_top;
    while y <= r_last {
        if y == switch {
            let e = Edge::new(m.x, m.y, b.x, b.y, 16 * y + 8);
            if long_left {
                right = e;
            } else {
                left = e;
            }
        }
        let lo = left.q.max(cols.0);
        let hi = (right.q - 1).min(cols.1);
        if lo <= hi {
            let mut start = [0i32; N];
            for k in 0..N {
                start[k] = round(row[k].wrapping_add(gx[k].wrapping_mul(lo - co)));
            }
            f(&Span {
                y: y + at.1,
                x0: lo + at.0,
                x1: hi + at.0,
                start,
                step,
            });
        }
        for k in 0..N {
            row[k] = row[k].wrapping_add(gy[k]);
        }
        left.advance();
        right.advance();
        y += 1;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rasterizer::tests::xorshift;

    /// The spans SPEC.md 5 gives triangle `v` in columns `0 ..= w − 1` and
    /// rows `0 ..= h − 1`, sample by sample: every edge function positive,
    /// or zero on a top-left edge of the positively oriented triangle.
    fn oracle(v: &[Vertex<1>; 3], w: i32, h: i32) -> Vec<(i32, i32, i32)> {
        let p = v.map(|v| (v.x as i64, v.y as i64));
        let e = |a: (i64, i64), b: (i64, i64), s: (i64, i64)| {
            (b.0 - a.0) * (s.1 - a.1) - (b.1 - a.1) * (s.0 - a.0)
        };
        let (a, mut b, mut c) = (p[0], p[1], p[2]);
        let area = e(a, b, c);
        if area == 0 {
            return Vec::new();
        }
        if area < 0 {
            core::mem::swap(&mut b, &mut c);
        }
        let edges = [(b, c), (c, a), (a, b)];
        let inside = |s: (i64, i64)| {
            edges.iter().all(|&(p, q)| {
                let top_left = q.1 - p.1 < 0 || (q.1 == p.1 && q.0 - p.0 > 0);
                let f = e(p, q, s);
                f > 0 || (f == 0 && top_left)
            })
        };
        let mut spans = Vec::new();
        for y in 0..h {
            let xs: Vec<i32> = (0..w)
                .filter(|&x| inside((16 * x as i64 + 8, 16 * y as i64 + 8)))
                .collect();
            if let (Some(&x0), Some(&x1)) = (xs.first(), xs.last()) {
                assert_eq!(
                    xs.len() as i32,
                    x1 - x0 + 1,
                    "a row's samples are contiguous"
                );
                spans.push((y, x0, x1));
            }
        }
        spans
    }

    /// The exact plane of attribute 0 at sample `(x, y)` (1/16 pixel).
    fn exact(v: &[Vertex<1>; 3], x: f64, y: f64) -> f64 {
        let f = v.map(|v| (v.x as f64, v.y as f64, v.a[0] as f64));
        let e = |a: (f64, f64, f64), b: (f64, f64, f64)| {
            (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0)
        };
        let whole = e(f[0], f[1]) + e(f[1], f[2]) + e(f[2], f[0]);
        let l1 = e(f[2], f[0]) / whole;
        let l2 = e(f[0], f[1]) / whole;
        f[0].2 + l1 * (f[1].2 - f[0].2) + l2 * (f[2].2 - f[0].2)
    }

    /// The spans the edge functions give, sample by sample, and attributes
    /// within the stated bound of the exact plane, for random triangles
    /// reaching across the band.
    #[test]
    fn spans_are_the_edge_functions() {
        let mut rnd = xorshift(0x1234_5678_9abc_def1);
        let mut spans = 0;
        for i in 0..6_000 {
            let reach = [40 * 16, 200 * 16, GUARD][i % 3];
            let mut r = [0u64; 9];
            r.iter_mut().for_each(|x| *x = rnd());
            let c = |x: u64| (x % (2 * reach as u64 + 1)) as i32 - reach;
            let v = [0, 1, 2].map(|k| Vertex {
                x: c(r[3 * k]) / 4 + 32 * 16 * (i % 2) as i32,
                y: c(r[3 * k + 1]) / 4,
                a: [(r[3 * k + 2] % (1 << 22)) as i32],
            });
            let want = oracle(&v, 64, 48);
            let mut got = Vec::new();
            draw(&v, (0, 63), (0, 47), (0, 0), |s| got.push(*s));
            assert_eq!(want.len(), got.len(), "{v:?}");
            spans += got.len();
            for (w, g) in want.iter().zip(&got) {
                assert_eq!(*w, (g.y, g.x0, g.x1), "{v:?}");
                let off = (g.x0 - (v[0].x >> 4)).abs() + (g.y - (v[0].y >> 4)).abs();
                let e = exact(&v, (16 * g.x0 + 8) as f64, (16 * g.y + 8) as f64);
                let err = (g.start[0] as f64 - e).abs();
                assert!(err <= off as f64 / 32.0 + 2.0, "{v:?}: {g:?} {e}");
            }
        }
        assert!(spans > 30_000, "{spans}");
    }
}

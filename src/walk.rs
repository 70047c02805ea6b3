//! The row walk: a set-up triangle's rows top to bottom, each row's span
//! from its two edges, and the attribute planes at the span's first pixel.
//!
//! # Coverage (SPEC.md 5)
//! Row `r` samples at `sy = 16r + 8` (1/16 pixel, from the set-up's
//! origin). An edge from `a` down to `b` (`dy = b.y − a.y > 0`) meets that
//! row at `X(sy) = a.x + dx·(sy − a.y)/dy`; a span's left bound is the
//! first column `c` with `16c + 8 ≥ X` (a sample on a left edge is the
//! triangle's), its right bound the last with `16c + 8 < X`. A row whose
//! sample lies on a horizontal top edge is drawn, one on a horizontal
//! bottom edge is not. That is the top-left rule: two triangles sharing an
//! edge draw each sample on it once. Every bound is exact: an edge's
//! column is an integer quotient stepped with its remainder row by row;
//! where the core divides in software, a gentle edge finds its quotient
//! and step by steps rather than a division ([`Edge::new`]), the same ones.
//! A triangle of a few samples may instead have each sample tested against
//! its three edge functions ([`EdgeFunctions`]): the same rule, the same
//! spans, without the quotients (where the core divides in software).
//!
//! # Planes
//! Attribute `k` at pixel `(c, r)` is `at[k] + gx[k]·c + gy[k]·(r − r₀)`
//! in wrapping `i32` arithmetic (`src/setup.rs` says why that is exact), so
//! a pixel's value is the same whether it was stepped to or computed, in a
//! band or in the whole frame. A span carries the planes, not its start:
//! the span loop computes it (`src/span.rs`).

use core::mem::MaybeUninit;

use crate::num::division::Divisor;
use crate::planes::{Planes, Row};
use crate::platform;

/// One edge's column bound, stepped row by row: `q = ⌈n / D⌉` with `n =
/// q·D − rem`, `0 ≤ rem < D`, `D = 16·dy`.
///
/// `n = (a.x − 8)·dy + dx·(sy − a.y)`: `|a.x − 8| < 2¹⁴`, `dy < 2¹⁵`,
/// `|dx| < 2¹⁵` and `|sy − a.y| < 2¹⁵` (the sample row lies inside the
/// guard band), so `|n| < 2²⁹ + 2³⁰`, and `q·D ≤ n + D` fits too.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Edge {
    q: i32,
    rem: i32,
    d: i32,
    /// Per row: `q += step`, `rem += rstep`, then one carry.
    step: i32,
    rstep: i32,
}

impl Edge {
    /// The edge `a → b` (`b.y > a.y`) at sample row `sy`: both quotients
    /// by one [`Divisor`] of `dy` (`⌈n/16dy⌉ = ⌈⌈n/16⌉/dy⌉`).
    #[inline(always)]
    pub(crate) fn new(a: (i32, i32), b: (i32, i32), sy: i32) -> Edge {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let n = (a.0 - 8) * dy + dx * (sy - a.1);
        // (The sample row lies at or below `a`: `0 ≤ sy − a.y`, the walk's
        // first row and its switch both.)
        if platform::STEP_QUOTIENTS && dx.unsigned_abs() <= 16 * dy as u32 && sy - a.1 <= 16 {
            return Edge::stepped(a.0, dx, dy, n);
        }
        if platform::hardware_div32() {
            Edge::divided(dx, dy, n)
        } else {
            Edge::divided_by_reciprocal(dx, dy, n)
        }
    }

    /// [`Edge::divided`] out of line, where the core divides in software:
    /// the divisor's reciprocal and the quotients' corrections are 588
    /// bytes of code on a Cortex-M0+, which inlined were made in four
    /// places (the walk's two edges, its switch in either walk), and the
    /// call sites keep fewer values across them.
    #[inline(never)]
    fn divided_by_reciprocal(dx: i32, dy: i32, n: i32) -> Edge {
        Edge::divided(dx, dy, n)
    }

    /// [`Edge::new`]'s quotients by one [`Divisor`] of `dy`.
    #[inline(always)]
    fn divided(dx: i32, dy: i32, n: i32) -> Edge {
        let d = 16 * dy;
        let div = Divisor::new(dy);
        let q = div.ceil((n + 15) >> 4);
        // ⌈dx/dy⌉·dy − dx ∈ [0, dy): the remainder's step, in 16ths.
        let step = div.ceil(dx);
        Edge {
            q,
            rem: q * d - n,
            d,
            step,
            rstep: 16 * (step * dy - dx),
        }
    }

    /// [`Edge::new`] of an edge of at most 16 columns a row whose sample
    /// row `sy` lies at most a row below its top `a` (`n` from `a.x`,
    /// `dx`, `dy` as there), by steps instead of a division: `⌈dx/dy⌉` from
    /// 0, at most 16 steps, and `⌈n/16dy⌉` from `a`'s own column `⌈(a.x −
    /// 8)/16⌉`, within `|dx|·(sy − a.y)/(16·dy) + 1 ≤ 17` steps of it. Each
    /// loop ends where its remainder lies in `[0, divisor)`: the
    /// division's quotients and remainders. Out of line: it is called from
    /// the walk's start and its switch.
    #[inline(never)]
    fn stepped(ax: i32, dx: i32, dy: i32, n: i32) -> Edge {
        /// `⌈n/d⌉` and its remainder `⌈n/d⌉·d − n ∈ [0, d)`, stepped from
        /// the estimate `q` (`d > 0`; `q·d − n` within `i32`).
        #[inline(always)]
        fn ceil_from(mut q: i32, n: i32, d: i32) -> (i32, i32) {
            let mut rem = q * d - n;
            while rem < 0 {
                q += 1;
                rem += d;
            }
            while rem >= d {
                q -= 1;
                rem -= d;
            }
            (q, rem)
        }
        let (step, t) = ceil_from(0, dx, dy);
        let d = 16 * dy;
        // |column| < 2¹⁰ and d < 2¹⁹: the product below 2²⁹.
        let (q, rem) = ceil_from((ax + 7) >> 4, n, d);
        Edge {
            q,
            rem,
            d,
            step,
            rstep: 16 * t,
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

/// A triangle's three edge functions at a sample, stepped sample by
/// sample: SPEC.md 5's rule as the walk applies it (every edge function of
/// the positively oriented triangle positive, or zero on a top or left
/// edge), for a triangle of a few samples, where testing them costs less
/// than the edges' quotients.
///
/// Edge `p → q` at sample `s` is `f = dx·(s.y − p.y) − dy·(s.x − p.x)`,
/// kept less 1 for an edge that is neither top nor left, so that the
/// sample is covered where all three are `≥ 0`: their `|` has no sign bit.
/// Positions within the guard band and samples within the target or a
/// pixel past it (where a scan steps last; the guard band holds the
/// target's pixels with one to spare): differences below 2¹⁵, each
/// product below 2³⁰, `f` below 2³¹.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EdgeFunctions {
    /// The three at the sample.
    f: [i32; 3],
    /// Their changes a column and a row on: `−16·dy` and `16·dx`.
    col: [i32; 3],
    row: [i32; 3],
}

impl EdgeFunctions {
    /// Triangle `p` (doubled area `area`, not 0) at sample `s`.
    #[inline(always)]
    pub(crate) fn new(p: [(i32, i32); 3], area: i32, s: (i32, i32)) -> EdgeFunctions {
        let (a, mut b, mut c) = (p[0], p[1], p[2]);
        if area < 0 {
            core::mem::swap(&mut b, &mut c);
        }
        let mut e = EdgeFunctions {
            f: [0; 3],
            col: [0; 3],
            row: [0; 3],
        };
        for (k, (p, q)) in [(b, c), (c, a), (a, b)].into_iter().enumerate() {
            let (dx, dy) = (q.0 - p.0, q.1 - p.1);
            let top_left = dy < 0 || (dy == 0 && dx > 0);
            e.f[k] = dx * (s.1 - p.1) - dy * (s.0 - p.0) - i32::from(!top_left);
            e.col[k] = -16 * dy;
            e.row[k] = 16 * dx;
        }
        e
    }

    /// Whether the sample is covered.
    #[inline(always)]
    pub(crate) fn covers(&self) -> bool {
        (self.f[0] | self.f[1] | self.f[2]) >= 0
    }

    /// The next column's sample.
    #[inline(always)]
    pub(crate) fn next_col(&mut self) {
        for k in 0..3 {
            self.f[k] += self.col[k];
        }
    }

    /// The sample a row below.
    #[inline(always)]
    pub(crate) fn next_row(&mut self) {
        for k in 0..3 {
            self.f[k] += self.row[k];
        }
    }

    /// The spans of rows `rows.0 ..= rows.1` within columns `cols.0 ..=
    /// cols.1` (at most [`CHUNK`] rows; `self` at sample `(cols.0,
    /// rows.0)`), into `table`: each row's covered samples, contiguous, the
    /// triangle being convex.
    #[inline(always)]
    pub(crate) fn rows(
        mut self,
        rows: (i32, i32),
        cols: (i32, i32),
        table: &mut [MaybeUninit<Row>; CHUNK],
    ) -> &[Row] {
        let n = ((rows.1 - rows.0 + 1) as usize).min(CHUNK);
        for row in &mut table[..n] {
            // The first covered column, then the run from it.
            let (mut e, mut x0) = (self, cols.0);
            while x0 <= cols.1 && !e.covers() {
                e.next_col();
                x0 += 1;
            }
            let mut x1 = x0;
            while x1 <= cols.1 && e.covers() {
                e.next_col();
                x1 += 1;
            }
            row.write(Row { x0, n: x1 - x0 });
            self.next_row();
        }
        // SAFETY: the first `n` rows were written just above.
        unsafe { core::slice::from_raw_parts(table.as_ptr().cast::<Row>(), n) }
    }
}

/// Rows a walk hands over at a time: a table of 256 bytes on the stack.
pub(crate) const CHUNK: usize = 32;

/// A set-up triangle being walked: the next row, the last, the edges.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Walk {
    /// The next row, and the last.
    pub(crate) y: i32,
    pub(crate) last: i32,
    /// The columns drawn, and whether a span may reach past them (else
    /// the spans are not clamped: the triangle lies within the columns).
    pub(crate) cols: (i32, i32),
    pub(crate) clamp: bool,
    /// The left and right edges at row `y`.
    pub(crate) left: Edge,
    pub(crate) right: Edge,
    /// Whether the long edge is the left one.
    pub(crate) long_left: bool,
    /// The row from which the lower short edge (`lower`'s two vertices)
    /// takes over (`i32::MAX`: never).
    pub(crate) switch: i32,
    pub(crate) lower: ((i32, i32), (i32, i32)),
}

/// A span: row `y`, columns `x0 ..= x0 + n − 1` (from the set-up's
/// origin), `dy` rows below the walk's first, on `planes`.
#[derive(Clone, Copy)]
pub(crate) struct Span<'a, const N: usize> {
    pub(crate) y: i32,
    pub(crate) x0: i32,
    pub(crate) n: u32,
    pub(crate) dy: i32,
    pub(crate) planes: &'a Planes<N>,
}

impl<const N: usize> Span<'_, N> {
    /// The planes at the span's first pixel.
    #[inline(always)]
    pub(crate) fn start(&self) -> [i32; N] {
        let p = self.planes;
        core::array::from_fn(|k| {
            p.at[k]
                .wrapping_add(p.gx[k].wrapping_mul(self.x0))
                .wrapping_add(p.gy[k].wrapping_mul(self.dy))
        })
    }

    /// The planes' step from a pixel to the next.
    #[inline(always)]
    pub(crate) fn step(&self) -> &[i32; N] {
        &self.planes.gx
    }
}

/// The spans of `rows.len()` rows between edges `l` and `r`, unclamped,
/// into `rows`; returns the edges stepped past them. Where the platform
/// steps edges itself ([`platform::edge_rows`]), there: most triangles'
/// rows ([`Walk::all`]).
#[inline(always)]
fn segment(rows: &mut [MaybeUninit<Row>], mut l: Edge, mut r: Edge) -> (Edge, Edge) {
    if platform::EDGE_ROWS {
        let e = |e: &Edge| [e.q, e.rem, e.d, e.step, e.rstep];
        // SAFETY: `rows` holds `rows.len()` rows; the edges have the
        // walk's ranges.
        let [lq, lrem, rq, rrem] =
            unsafe { platform::edge_rows(rows.as_mut_ptr().cast(), rows.len(), e(&l), e(&r)) };
        (l.q, l.rem, r.q, r.rem) = (lq, lrem, rq, rrem);
        return (l, r);
    }
    segment_here(rows, l, r)
}

/// [`segment`] in Rust: also a long or clamped walk's, table by table
/// ([`Walk::fill`], rare: the routine inlined there had cost the triangle
/// loop's own code registers).
#[inline(always)]
fn segment_here(rows: &mut [MaybeUninit<Row>], mut l: Edge, mut r: Edge) -> (Edge, Edge) {
    for row in rows {
        row.write(Row {
            x0: l.q,
            n: r.q - l.q,
        });
        l.advance();
        r.advance();
        platform::keep_loop_rolled();
    }
    (l, r)
}

impl Walk {
    /// Fills `rows` with the spans of the next rows, as many as fit or are
    /// left; returns them. (`rows` is not cleared before: clearing a table
    /// of 256 bytes for every triangle set up is 64 word stores each, some
    /// 38 000 on the M4F's S1 with its 594 triangles set up.)
    #[inline(always)]
    pub(crate) fn fill<'r>(&mut self, rows: &'r mut [MaybeUninit<Row>; CHUNK]) -> &'r [Row] {
        let mut k = 0;
        while k < CHUNK && self.y <= self.last {
            if self.y == self.switch {
                let e = Edge::new(self.lower.0, self.lower.1, 16 * self.y + 8);
                if self.long_left {
                    self.right = e;
                } else {
                    self.left = e;
                }
            }
            // The rows up to the switch, the last or the table's end, in
            // a loop of their own, the edges in locals.
            let mut stop = (self.last + 1).min(self.y + (CHUNK - k) as i32);
            if self.switch > self.y {
                stop = stop.min(self.switch);
            }
            let m = (stop - self.y) as usize;
            let (mut l, mut r) = (self.left, self.right);
            let out = rows.get_mut(k..k + m).unwrap_or_default();
            if self.clamp {
                let (c0, c1) = self.cols;
                for row in out {
                    let x0 = l.q.max(c0);
                    row.write(Row {
                        x0,
                        n: (r.q - 1).min(c1) - x0 + 1,
                    });
                    l.advance();
                    r.advance();
                    platform::keep_loop_rolled();
                }
            } else {
                (l, r) = segment_here(out, l, r);
            }
            (self.left, self.right, self.y) = (l, r, stop);
            k += m;
        }
        // SAFETY: the first `k` rows were written just above.
        unsafe { core::slice::from_raw_parts(rows.as_ptr().cast::<Row>(), k) }
    }

    /// All the rows' spans in `rows` at once, for a walk that has at most
    /// [`CHUNK`] rows left and needs no clamp (most triangles): the two
    /// segments in loops of their own, the edges in locals; `None` for
    /// any other walk (then [`Walk::fill`]).
    #[inline(always)]
    pub(crate) fn all<'r>(&self, rows: &'r mut [MaybeUninit<Row>; CHUNK]) -> Option<&'r [Row]> {
        let n = (self.last - self.y + 1) as usize;
        if self.clamp || n > CHUNK {
            return None;
        }
        let (mut l, mut r) = (self.left, self.right);
        let upper = if self.switch > self.last {
            n
        } else {
            (self.switch - self.y) as usize
        };
        let (a, b) = rows.get_mut(..n)?.split_at_mut(upper.min(n));
        (l, r) = segment(a, l, r);
        if !b.is_empty() {
            let e = Edge::new(self.lower.0, self.lower.1, 16 * self.switch + 8);
            if self.long_left {
                r = e;
            } else {
                l = e;
            }
            segment(b, l, r);
        }
        // SAFETY: the first `n` rows were written just above.
        Some(unsafe { core::slice::from_raw_parts(rows.as_ptr().cast::<Row>(), n) })
    }

    /// Calls `span` for each non-empty span on `planes`, top to bottom,
    /// until it fails (for tests): every row at once where [`Walk::all`]
    /// takes the walk, else table by table, as a draw does.
    #[cfg(test)]
    pub(crate) fn run<const N: usize, E>(
        mut self,
        planes: &Planes<N>,
        mut span: impl FnMut(&Span<N>) -> Result<(), E>,
    ) -> Result<(), E> {
        let first = self.y;
        let mut rows = [MaybeUninit::uninit(); CHUNK];
        // As the draw takes them: every row at once where it can, else
        // table by table.
        let mut whole = self.all(&mut rows).map(<[Row]>::to_vec);
        loop {
            let y = self.y;
            let table = match whole.take() {
                Some(t) => {
                    self.y = self.last + 1;
                    t
                }
                None => self.fill(&mut rows).to_vec(),
            };
            if table.is_empty() {
                return Ok(());
            }
            for (j, r) in table.iter().enumerate() {
                if r.n > 0 {
                    let y = y + j as i32;
                    span(&Span {
                        y,
                        x0: r.x0,
                        n: r.n as u32,
                        dy: y - first,
                        planes,
                    })?;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::xorshift;

    /// The stepped quotients are the division's: `q = ⌈n/16dy⌉` and
    /// `step = ⌈dx/dy⌉` with their remainders in `[0, divisor)`, for every
    /// edge the steps take (slopes up to 16 columns a row, the sample row
    /// up to a row below the top, positions across the guard band), the
    /// bounds themselves included.
    #[test]
    fn stepped_edges_are_the_division() {
        let mut rnd = xorshift(0x5eed_0fed_9e50_u64);
        let mut checked = 0;
        for i in 0..200_000 {
            let r = [rnd(), rnd(), rnd(), rnd()];
            let g = crate::vertex::GUARD as u64;
            let ax = (r[0] % (2 * g + 1)) as i32 - g as i32;
            let ay = (r[1] % (2 * g + 1)) as i32 - g as i32;
            let dy = match i % 4 {
                0 => 1 + (r[2] % 16) as i32,
                1 => 1 + (r[2] % 400) as i32,
                _ => 1 + (r[2] % 2000) as i32,
            };
            let reach = 16 * dy as u64;
            let dx = match i % 5 {
                0 => 16 * dy,
                1 => -16 * dy,
                _ => (r[3] % (2 * reach + 1)) as i32 - reach as i32,
            };
            let (bx, by) = (ax + dx, ay + dy);
            if bx.abs() > g as i32 || by > g as i32 {
                continue;
            }
            // The first sample row at or below a, or the next where that
            // is still at most a row below it.
            let sy0 = 16 * ((ay + 7) >> 4) + 8;
            let sy = if i % 2 == 1 && sy0 == ay {
                sy0 + 16
            } else {
                sy0
            };
            let n = (ax - 8) * dy + dx * (sy - ay);
            let e = Edge::stepped(ax, dx, dy, n);
            let d = 16 * dy as i64;
            let q = (n as i64 + d - 1).div_euclid(d);
            let step = (dx as i64 + dy as i64 - 1).div_euclid(dy as i64);
            assert_eq!(
                (e.q as i64, e.rem as i64, e.d as i64),
                (q, q * d - n as i64, d),
                "{ax} {ay} {dx} {dy} {sy}"
            );
            assert_eq!(
                (e.step as i64, e.rstep as i64),
                (step, 16 * (step * dy as i64 - dx as i64)),
                "{dx} {dy}"
            );
            checked += 1;
        }
        assert!(checked > 150_000, "{checked}");
    }
}

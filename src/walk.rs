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
//! column is an integer quotient stepped with its remainder row by row.
//!
//! # Planes
//! Attribute `k` at pixel `(c, r)` is `at[k] + gx[k]·c + gy[k]·(r − r₀)`
//! in wrapping `i32` arithmetic (`src/setup.rs` says why that is exact), so
//! a pixel's value is the same whether it was stepped to or computed, in a
//! band or in the whole frame. A span carries the planes, not its start:
//! the span loop computes it (`src/span.rs`).

use crate::num::division::Divisor;

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
        let div = Divisor::new(dy);
        let d = 16 * dy;
        let n = (a.0 - 8) * dy + dx * (sy - a.1);
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

/// A triangle's attribute planes: attribute `k` at pixel `(c, r)` is
/// `at[k] + gx[k]·c + gy[k]·(r − r₀)` (wrapping), `r₀` the walk's first
/// row. (`repr(C)`: the span loops in assembly read it, `src/platform.rs`.)
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub(crate) struct Planes<const N: usize> {
    pub(crate) at: [i32; N],
    pub(crate) gx: [i32; N],
    pub(crate) gy: [i32; N],
}

impl<const N: usize> Default for Planes<N> {
    fn default() -> Self {
        Planes {
            at: [0; N],
            gx: [0; N],
            gy: [0; N],
        }
    }
}

/// A set-up triangle ready to walk: its rows and edges.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Walk {
    /// The first and last rows drawn.
    pub(crate) rows: (i32, i32),
    /// The columns drawn.
    pub(crate) cols: (i32, i32),
    /// The long edge (top to bottom vertex) and the short edge that holds
    /// the first row.
    pub(crate) long: Edge,
    pub(crate) short: Edge,
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

impl Walk {
    /// Calls `span` for each non-empty span on `planes`, top to bottom,
    /// until it fails.
    #[inline(always)]
    pub(crate) fn run<const N: usize, E>(
        self,
        planes: &Planes<N>,
        mut span: impl FnMut(&Span<N>) -> Result<(), E>,
    ) -> Result<(), E> {
        let (mut left, mut right) = if self.long_left {
            (self.long, self.short)
        } else {
            (self.short, self.long)
        };
        let (c0, c1) = self.cols;
        let (first, last) = self.rows;
        for y in first..=last {
            if y == self.switch {
                let e = Edge::new(self.lower.0, self.lower.1, 16 * y + 8);
                if self.long_left {
                    right = e;
                } else {
                    left = e;
                }
            }
            let lo = left.q.max(c0);
            let hi = (right.q - 1).min(c1);
            if lo <= hi {
                span(&Span {
                    y,
                    x0: lo,
                    n: (hi - lo + 1) as u32,
                    dy: y - first,
                    planes,
                })?;
            }
            left.advance();
            right.advance();
        }
        Ok(())
    }
}

//! Triangle set-up in 32-bit arithmetic: the rows and columns a triangle
//! covers, its edges and its attribute planes, and its rows' spans from
//! the row walk (`src/walk.rs`), or, for a triangle of a few samples where
//! the core divides in software, from each sample's edge functions. On
//! ARMv7-M a kept Gouraud triangle takes the same values from one routine
//! of assembly (`platform::gouraud_set_up`, called by `src/shade.rs`),
//! which leaves what it does not take to these functions.
//!
//! # Ranges
//! Window positions are in 1/16 pixel from the set-up's origin, within
//! `GUARD` (`2¹⁴ − 16`: ±1023 pixels, `src/vertex.rs`) on each axis. Then every
//! difference of two coordinates is below 2¹⁵ in magnitude, every product
//! of two differences below 2³⁰ and the doubled area below 2³¹: `i32` is
//! exact for the area and the edges. Attributes lie within ±[`ATTR`].
//!
//! # Planes
//! An attribute's plane is kept with four more fractional bits than the
//! attribute (units of 2⁻⁴), as integers: `P(c, r) = base + gx·(c − c₀) +
//! gy·(r − r₀)` with `gx`, `gy` its gradients per pixel rounded to
//! integers and `base` the plane at the centre of pixel `(c₀, r₀)`, the one
//! that holds vertex 0. The sums are taken modulo 2³² (wrapping): they are
//! integers, so at every pixel they equal the same sum taken without a
//! bound, which differs from the exact plane by at most `(½ + (|d₁| +
//! |d₂|)·2⁻²⁴)·(|c − c₀| + |r − r₀| + 1) + 1` units, `d` the attribute's
//! differences from vertex 0 ([`lambdas`] bounds each gradient's error;
//! `src/tests/coverage.rs` holds the bound at the limits). At a covered
//! pixel the exact plane lies between the vertex values, so the integer
//! plane is that close to their range there, whatever the gradients'
//! size: below 2¹²·⁶ units for attributes within 2²², the colours', and
//! 2¹⁵·² for any (`|d| < 2²⁶`), across the guard band's 2¹² pixels. A
//! caller whose values keep that margin inside their field needs no
//! clamp.
//!
//! A gradient is `256·N/A` (`A` the doubled area in 1/256 pixel², `N` the
//! attribute differences' cross product with the sides, below 2⁴²): from
//! one reciprocal of `|A|` ([`recip_fast`]) and the barycentric gradients
//! ([`gradient`]), or, where those do not fit `i32` (a sliver, a steep
//! plane), from the exact division, kept modulo 2³². Both are functions of
//! the vertices alone, the same on every core.

use core::mem::MaybeUninit;

use crate::num::division::{floor_div, recip_fast};
use crate::num::widening::{dot2_round16, dot2_round_shr24, mul_i32, mul_u32_i16_shr, shr_to_i32};
use crate::planes::{Planes, Row};
use crate::platform;
use crate::walk::{Edge, EdgeFunctions, Walk, CHUNK};

/// Attribute values lie within `±ATTR`: their differences, below 2²⁶,
/// times a side below 2¹⁵, stay below 2⁴¹.
pub(crate) const ATTR: i32 = 1 << 25;

/// A set-up vertex: position in 1/16 pixel within ±`GUARD` of the
/// set-up's origin, attributes within ±[`ATTR`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Vtx<const N: usize> {
    pub(crate) x: i32,
    pub(crate) y: i32,
    pub(crate) a: [i32; N],
}

/// The pixels that may be drawn, from the set-up's origin: columns `c0
/// ..= c1` and rows `r0 ..= r1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Rect {
    pub(crate) c0: i32,
    pub(crate) c1: i32,
    pub(crate) r0: i32,
    pub(crate) r1: i32,
}

/// The doubled signed area of `v` in 1/256 pixel²: negative for a front
/// face (counter-clockwise in NDC; window y points down).
#[inline(always)]
pub(crate) fn area<const N: usize>(v: &[Vtx<N>; 3]) -> i32 {
    (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y)
}

/// A set-up triangle: its planes and its walk.
pub(crate) struct Triangle<const N: usize> {
    pub(crate) planes: Planes<N>,
    pub(crate) walk: Walk,
}

/// What [`set_up`] made of a triangle.
pub(crate) enum SetUp<'s, 'r, const N: usize> {
    /// Rows with samples, none of them covered (a thin triangle between
    /// them): nothing to draw, no planes made.
    Uncovered,
    /// Its planes and all its rows' spans, the first at row `y`.
    Rows {
        planes: &'s Planes<N>,
        rows: &'r [Row],
        y: i32,
    },
    /// Its planes and its walk, for rows past one table's or spans that
    /// need a clamp.
    Walk(&'s mut Triangle<N>),
}

/// The most rows and columns of samples a triangle spans whose samples
/// [`set_up`] tests one by one ([`platform::TEST_SAMPLES`]).
pub(crate) const SMALL: i32 = 4;

/// Sets up triangle `v` of doubled area `area` (not 0), whose samples on
/// `rect` are `s` ([`Samples::of_box`]: found by the caller, which tests
/// them first), into `slot`: its walk or, for a triangle of at most [`SMALL`]
/// rows and columns of samples where the core divides in software, every
/// row's span into `table`, each sample tested against the edge functions
/// ([`EdgeFunctions`]) instead of walking the edges (three quotients and
/// their steps); both give the same spans. Then its planes, unless the
/// rows at hand cover no sample. Out of line, into the caller's memory:
/// the set-up's values get the registers, and the caller reads the
/// triangle where it lies, not copied into its own.
#[inline(never)]
pub(crate) fn set_up<'s, 'r, const N: usize>(
    v: &[Vtx<N>; 3],
    area: i32,
    s: &Samples,
    rect: &Rect,
    slot: &'s mut MaybeUninit<Triangle<N>>,
    table: &'r mut [MaybeUninit<Row>; CHUNK],
) -> SetUp<'s, 'r, N> {
    let out = slot.as_mut_ptr();
    // The spans first: a triangle that covers no sample (a tenth of a
    // fine mesh's) is spared its planes.
    let rows =
        if platform::TEST_SAMPLES && s.rows.1 - s.rows.0 < SMALL && s.cols.1 - s.cols.0 < SMALL {
            let at = (16 * s.cols.0 + 8, 16 * s.rows.0 + 8);
            let e = EdgeFunctions::new(v.map(|p| (p.x, p.y)), area, at);
            Ok(e.rows(s.rows, s.cols, table))
        } else {
            let w = walk(v, s, rect);
            // Most triangles: every row at once.
            w.all(table).ok_or(w)
        };
    if let Ok(rows) = rows {
        if rows.iter().all(|r| r.n <= 0) {
            return SetUp::Uncovered;
        }
    }
    // SAFETY: `out` points to the slot, valid for writes; `planes` writes
    // every entry of the planes.
    unsafe { planes(v, area, s.rows.0, core::ptr::addr_of_mut!((*out).planes)) };
    match rows {
        Ok(rows) => SetUp::Rows {
            // SAFETY: written just above.
            planes: unsafe { &*core::ptr::addr_of!((*out).planes) },
            rows,
            y: s.rows.0,
        },
        // SAFETY: as above; with the planes and the walk written, the
        // slot is initialised.
        Err(w) => unsafe {
            core::ptr::addr_of_mut!((*out).walk).write(w);
            SetUp::Walk(slot.assume_init_mut())
        },
    }
}

/// The samples of a triangle within a set-up's rectangle ([`samples`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Samples {
    /// The rows whose samples lie in `[top, bottom)` (those the walk
    /// draws), within the rectangle's.
    pub(crate) rows: (i32, i32),
    /// The columns whose samples lie in `[min x, max x]`, within the
    /// rectangle's (possibly none: `cols.0 > cols.1`).
    pub(crate) cols: (i32, i32),
    /// Whether the rectangle cut those columns: then the walk's spans are
    /// clamped to its columns.
    pub(crate) clamp: bool,
}

/// The samples of triangle `v` within `rect` ([`Samples::of_box`]).
#[inline(always)]
pub(crate) fn samples<const N: usize>(v: &[Vtx<N>; 3], rect: &Rect) -> Option<Samples> {
    let (x, y) = (v.map(|p| p.x), v.map(|p| p.y));
    let lo = (x[0].min(x[1]).min(x[2]), y[0].min(y[1]).min(y[2]));
    let hi = (x[0].max(x[1]).max(x[2]), y[0].max(y[1]).max(y[2]));
    Samples::of_box(lo, hi, rect)
}

impl Samples {
    /// The samples within `rect` of a triangle whose window positions'
    /// box is `lo ..= hi`, or `None` where no row of `rect` has a sample
    /// in `[top, bottom)`: row `r` samples at `16r + 8`, within `[a, b)`
    /// for `r ∈ [⌈(a − 8)/16⌉, ⌈(b − 8)/16⌉ − 1]`; column `c` within `[a,
    /// b]` for `c ∈ [⌈(a − 8)/16⌉, ⌊(b − 8)/16⌋]`.
    #[inline(always)]
    pub(crate) fn of_box(lo: (i32, i32), hi: (i32, i32), rect: &Rect) -> Option<Samples> {
        let r0 = ((lo.1 + 7) >> 4).max(rect.r0);
        // ⌈(b − 8)/16⌉ − 1 = ⌊(b − 9)/16⌋.
        let r1 = ((hi.1 - 9) >> 4).min(rect.r1);
        if r0 > r1 {
            return None;
        }
        let c0 = (lo.0 + 7) >> 4;
        let c1 = (hi.0 - 8) >> 4;
        Some(Samples {
            rows: (r0, r1),
            cols: (c0.max(rect.c0), c1.min(rect.c1)),
            clamp: c0 < rect.c0 || c1 > rect.c1,
        })
    }
}

/// The walk of triangle `v`, whose samples are `s`, on `rect`.
#[inline(always)]
fn walk<const N: usize>(v: &[Vtx<N>; 3], s: &Samples, rect: &Rect) -> Walk {
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
    // Which side the long edge t → b bounds: the middle vertex's side of it.
    let cross = (b.x - t.x) * (m.y - t.y) - (b.y - t.y) * (m.x - t.x);
    // The edges at the first row: the long one, and the short one that
    // holds that row.
    let sy = 16 * s.rows.0 + 8;
    let long = Edge::new((t.x, t.y), (b.x, b.y), sy);
    let upper = m.y > sy;
    let short = if upper {
        Edge::new((t.x, t.y), (m.x, m.y), sy)
    } else {
        Edge::new((m.x, m.y), (b.x, b.y), sy)
    };
    let long_left = cross < 0;
    let (left, right) = if long_left {
        (long, short)
    } else {
        (short, long)
    };
    Walk {
        y: s.rows.0,
        last: s.rows.1,
        cols: (rect.c0, rect.c1),
        clamp: s.clamp,
        left,
        right,
        long_left,
        // The first row whose sample lies at or below the middle vertex.
        switch: if upper { (m.y + 7) >> 4 } else { i32::MAX },
        lower: ((m.x, m.y), (b.x, b.y)),
    }
}

/// The walked set-up of any triangle (no sample tested one by one), for
/// tests: `None` where no row has a sample.
#[cfg(test)]
pub(crate) fn set_up_walked<'s, const N: usize>(
    v: &[Vtx<N>; 3],
    area: i32,
    rect: &Rect,
    slot: &'s mut MaybeUninit<Triangle<N>>,
) -> Option<&'s mut Triangle<N>> {
    let s = samples(v, rect)?;
    let out = slot.as_mut_ptr();
    // SAFETY: the slot is valid for writes; `planes` and the walk's write
    // initialise it.
    unsafe {
        planes(v, area, s.rows.0, core::ptr::addr_of_mut!((*out).planes));
        core::ptr::addr_of_mut!((*out).walk).write(walk(v, &s, rect));
        Some(slot.assume_init_mut())
    }
}

/// The planes of triangle `v` (doubled area `area`, not 0), anchored at
/// column 0 of row `r_top`, into `out`: each attribute's value at the
/// centre of the pixel holding vertex 0 (`(c₀, r₀)`), from vertex 0's and
/// the gradients, moved there (wrapping: see the module's text). Each
/// attribute's three values are written as soon as they are made.
///
/// Out of line: one call a triangle set up. (Inlined after the spans, it
/// made S1's configuration 1.4 KB larger on the Cortex-M0+ and the M4F's S1 0.3 %
/// slower than this call does.)
///
/// # Safety
/// `out` is valid for writes of a `Planes<N>`; every entry is written.
#[inline(never)]
unsafe fn planes<const N: usize>(v: &[Vtx<N>; 3], area: i32, r_top: i32, out: *mut Planes<N>) {
    let (c0, r0) = (v[0].x >> 4, v[0].y >> 4);
    let o = (16 * c0 + 8 - v[0].x, 16 * r0 + 8 - v[0].y);
    let put = |k: usize, gx: i32, gy: i32, off: i32| {
        let at = (v[0].a[k] << 4)
            .wrapping_add(off)
            .wrapping_sub(gx.wrapping_mul(c0))
            .wrapping_add(gy.wrapping_mul(r_top - r0));
        // SAFETY: the caller's contract; `k < N`.
        unsafe {
            core::ptr::addr_of_mut!((*out).at[k]).write(at);
            core::ptr::addr_of_mut!((*out).gx[k]).write(gx);
            core::ptr::addr_of_mut!((*out).gy[k]).write(gy);
        }
    };
    if let Some(lam) = lambdas(v, area) {
        let mut k = 0;
        while k < N {
            let Some((gx, gy)) = gradient(v, k, lam) else {
                break;
            };
            put(k, gx, gy, offset(gx, gy, o));
            k += 1;
            platform::keep_loop_rolled();
        }
        if k == N {
            return;
        }
    }
    // A gradient that does not fit: every plane from the exact quotients
    // (those written above overwritten).
    let (gx, gy, off) = steep_gradients(v, area, o);
    for k in 0..N {
        put(k, gx[k], gy[k], off[k]);
    }
}

/// The barycentric coordinates' gradients `Λ` of triangle `v` (doubled
/// area `area`, not 0), for [`gradient`], or `None` where they do not fit
/// this form.
///
/// Vertex `k`'s weight `λₖ` has gradients `∂λ₁/∂x = dy₂/A`, `∂λ₁/∂y =
/// −dx₂/A`, `∂λ₂/∂x = −dy₁/A`, `∂λ₂/∂y = dx₁/A` (per sixteenth; `A` the
/// doubled area), so an attribute's gradient per pixel in plane units is
/// `gx = 256·(d₁·dy₂ − d₂·dy₁)/A = d₁·Λ₁ₓ + d₂·Λ₂ₓ` with `Λ = 256·side/A`.
/// The four `Λ` are kept as `i32` multiples of 2⁻²⁴ (`Λ·2²⁴ =
/// ⌊side·r/2³¹⁻ⁿ⌋`, `r ≈ 2⁶³/(|A|·2ⁿ)`), so each gradient is two `i32 ×
/// i32` products summed and shifted by 24: the `Λ` within a unit of 2⁻²⁴
/// (times `r`'s common relative error, 2⁻²⁷), the gradient within `|d₁| +
/// |d₂|` units of 2⁻²⁴ plus its rounding's ½. A triangle whose `Λ`
/// or gradients do not fit (a sliver, a steep plane) takes the exact
/// quotients ([`steep_gradients`]).
#[inline(always)]
fn lambdas<const N: usize>(v: &[Vtx<N>; 3], area: i32) -> Option<[i32; 4]> {
    let (dx1, dy1) = (v[1].x - v[0].x, v[1].y - v[0].y);
    let (dx2, dy2) = (v[2].x - v[0].x, v[2].y - v[0].y);
    let a = area.unsigned_abs();
    let n = platform::leading_zeros(a);
    // Within a relative 2⁻²⁷ (`recip_fast`): a factor common to the four
    // Λ, so it scales each plane's change across the triangle alone.
    let r = recip_fast(a << n);
    // Λ·2²⁴ = 256·side·2²⁴/|A| = side·2ⁿ⁺³²·r/2⁶³ = side·r/2³¹⁻ⁿ.
    let sign = if area < 0 { -1 } else { 1 };
    // |side| < 2¹⁵ (an `i16`), r < 2³²: the product below 2⁴⁷; n ≤ 31.
    let lam = |s: i32| mul_u32_i16_shr(r, s * sign, 31 - n);
    Some([
        lam(dy2)?,
        lam(dx2.wrapping_neg())?,
        lam(dy1.wrapping_neg())?,
        lam(dx1)?,
    ])
}

/// Attribute `k`'s gradients per pixel (units of 2⁻⁴ of an attribute)
/// from the `Λ` of [`lambdas`] (`Λ₁ₓ, Λ₁ᵧ, Λ₂ₓ, Λ₂ᵧ`), or `None` where one
/// does not fit `i32`.
#[inline(always)]
fn gradient<const N: usize>(v: &[Vtx<N>; 3], k: usize, lam: [i32; 4]) -> Option<(i32, i32)> {
    let d1 = v[1].a[k] - v[0].a[k];
    let d2 = v[2].a[k] - v[0].a[k];
    if platform::SOFT_MUL64 && ((d1 + 0x7FFF) as u32).max((d2 + 0x7FFF) as u32) < 0xFFFF {
        // Both differences within ±(2¹⁵ − 1) (most of a fine mesh's): the
        // same value in 32-bit steps, which always fits.
        let g = |l1: i32, l2: i32| dot2_round_shr24(l1, d1, l2, d2);
        return Some((g(lam[0], lam[2]), g(lam[1], lam[3])));
    }
    // |d| < 2²⁶, |Λ·2²⁴| < 2³¹: the sums below 2⁵⁸.
    let g = |l1: i32, l2: i32| shr_to_i32(mul_i32(d1, l1) + mul_i32(d2, l2) + (1 << 23), 24);
    Some((g(lam[0], lam[2])?, g(lam[1], lam[3])?))
}

/// `round((gx·oₓ + gy·o_y)/16)` (`|o| ≤ 8`): the plane's change from a
/// vertex to its pixel's centre. Where a 64-bit product is made from
/// 16-bit ones and both gradients lie within ±2²⁷ (nearly every plane's),
/// the sum lies within 2³¹: the same floor in 32-bit arithmetic.
#[inline(always)]
fn offset(gx: i32, gy: i32, o: (i32, i32)) -> i32 {
    let small = |g: i32| (g.wrapping_add(1 << 27) as u32) < 1 << 28;
    if platform::SOFT_MUL64 && small(gx) && small(gy) {
        (gx * o.0 + gy * o.1 + 8) >> 4
    } else {
        dot2_round16(gx, o.0, gy, o.1)
    }
}

/// [`gradient`]'s values from the exact quotients `round(256·N/A)`, `N` the
/// attribute differences' cross products with the sides (below 2⁴²), kept
/// modulo 2³²: a sliver's or a steep plane's (rare, out of line); with
/// the offsets to the centre `o` sixteenths from vertex 0, from the
/// quotients before they are wrapped (the `/16` does not commute with
/// the wrap), modulo 2³².
#[inline(never)]
fn steep_gradients<const N: usize>(
    v: &[Vtx<N>; 3],
    area: i32,
    o: (i32, i32),
) -> ([i32; N], [i32; N], [i32; N]) {
    let (dx1, dy1) = (v[1].x - v[0].x, v[1].y - v[0].y);
    let (dx2, dy2) = (v[2].x - v[0].x, v[2].y - v[0].y);
    let a = area.unsigned_abs() as i64;
    // |num| < 2⁴²: the quotients below 2⁵¹, their offsets' products
    // below 2⁵⁴.
    let q = |num: i64| {
        let q = floor_div(512 * num + a, 2 * a);
        if area < 0 {
            -q
        } else {
            q
        }
    };
    let (mut gx, mut gy, mut off) = ([0i32; N], [0i32; N], [0i32; N]);
    for k in 0..N {
        let d1 = (v[1].a[k] - v[0].a[k]) as i64;
        let d2 = (v[2].a[k] - v[0].a[k]) as i64;
        let (x, y) = (
            q(d1 * dy2 as i64 - d2 * dy1 as i64),
            q(d2 * dx1 as i64 - d1 * dx2 as i64),
        );
        (gx[k], gy[k]) = (x as i32, y as i32);
        off[k] = ((x * o.0 as i64 + y * o.1 as i64 + 8) >> 4) as i32;
    }
    (gx, gy, off)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::xorshift;
    use crate::vertex::GUARD;

    /// The spans SPEC.md 5 gives triangle `v` in columns `0 ..= w − 1` and
    /// rows `0 ..= h − 1`, sample by sample: every edge function positive,
    /// or zero on a top-left edge of the positively oriented triangle.
    pub(crate) fn oracle<const N: usize>(v: &[Vtx<N>; 3], w: i32, h: i32) -> Vec<(i32, i32, i32)> {
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
    fn exact(v: &[Vtx<1>; 3], x: f64, y: f64) -> f64 {
        let f = v.map(|v| (v.x as f64, v.y as f64, v.a[0] as f64));
        let e = |a: (f64, f64, f64), b: (f64, f64, f64)| {
            (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0)
        };
        let whole = e(f[0], f[1]) + e(f[1], f[2]) + e(f[2], f[0]);
        let l1 = e(f[2], f[0]) / whole;
        let l2 = e(f[0], f[1]) / whole;
        f[0].2 + l1 * (f[1].2 - f[0].2) + l2 * (f[2].2 - f[0].2)
    }

    /// All spans of `v` in a `w × h` rectangle at the origin.
    fn spans(v: &[Vtx<1>; 3], w: i32, h: i32) -> Vec<(i32, i32, i32, i32)> {
        let mut got = Vec::new();
        let a = area(v);
        if a == 0 {
            return got;
        }
        let rect = Rect {
            c0: 0,
            c1: w - 1,
            r0: 0,
            r1: h - 1,
        };
        if let Some(Triangle { planes, walk }) =
            set_up_walked(v, a, &rect, &mut MaybeUninit::uninit())
        {
            walk.run(planes, |s| {
                got.push((s.y, s.x0, s.x0 + s.n as i32 - 1, s.start()[0]));
                Ok::<(), ()>(())
            })
            .unwrap();
        }
        got
    }

    /// `set_up` itself, as a draw calls it: small triangles (a few
    /// samples, where it may test each, and the thin ones between samples
    /// that cover none) and larger ones. A triangle it calls `Uncovered`
    /// covers no sample by the edge functions; one it hands over as rows
    /// has exactly their spans and the planes [`set_up_walked`] makes; one
    /// it walks has their spans too.
    #[test]
    fn set_up_skips_only_uncovered_triangles() {
        let mut rnd = xorshift(0x5e70_0bad_c0ff_ee11);
        let (mut uncovered, mut rows) = (0, 0);
        for i in 0..40_000 {
            let reach = [24, 48, 90, 16 * 30][i % 4];
            let c = |x: u64| (x % (2 * reach as u64 + 1)) as i32 - reach;
            let (ox, oy) = (16 * 20 + c(rnd()), 16 * 12 + c(rnd()));
            let v = [0, 1, 2].map(|k| Vtx {
                x: ox + c(rnd()),
                y: oy + c(rnd()),
                a: [k * 1000],
            });
            let a = area(&v);
            if a == 0 {
                continue;
            }
            let want = oracle(&v, 40, 24);
            let rect = Rect {
                c0: 0,
                c1: 39,
                r0: 0,
                r1: 23,
            };
            let mut table = [MaybeUninit::uninit(); CHUNK];
            let mut slot = MaybeUninit::uninit();
            let Some(s) = samples(&v, &rect) else {
                assert!(want.is_empty(), "{v:?}");
                continue;
            };
            match set_up(&v, a, &s, &rect, &mut slot, &mut table) {
                SetUp::Uncovered => {
                    assert!(want.is_empty(), "{v:?}");
                    uncovered += 1;
                }
                SetUp::Rows { planes, rows: r, y } => {
                    let got: Vec<_> = r
                        .iter()
                        .zip(y..)
                        .filter(|(r, _)| r.n > 0)
                        .map(|(r, y)| (y, r.x0, r.x0 + r.n - 1))
                        .collect();
                    assert_eq!(got, want, "{v:?}");
                    let mut other = MaybeUninit::uninit();
                    let walked = set_up_walked(&v, a, &rect, &mut other);
                    let p = &walked.expect("rows, so samples").planes;
                    assert_eq!((planes.at, planes.gx, planes.gy), (p.at, p.gx, p.gy));
                    rows += 1;
                }
                SetUp::Walk(t) => {
                    let mut got = Vec::new();
                    let (planes, walk) = (&t.planes, t.walk);
                    walk.run(planes, |s| {
                        got.push((s.y, s.x0, s.x0 + s.n as i32 - 1));
                        Ok::<(), ()>(())
                    })
                    .unwrap();
                    assert_eq!(got, want, "{v:?}");
                }
            }
        }
        assert!(uncovered > 200 && rows > 5_000, "{uncovered} {rows}");
    }

    /// The spans the edge functions give, sample by sample, and attributes
    /// within the stated bound of the exact plane, for random triangles
    /// reaching across the band, attributes to the bound.
    #[test]
    fn spans_are_the_edge_functions() {
        let mut rnd = xorshift(0x1234_5678_9abc_def1);
        let mut count = 0;
        for i in 0..8_000 {
            let reach = [40 * 16, 200 * 16, GUARD][i % 3];
            let mut r = [0u64; 9];
            r.iter_mut().for_each(|x| *x = rnd());
            let c = |x: u64| (x % (2 * reach as u64 + 1)) as i32 - reach;
            let lim = [1 << 22, ATTR][i % 2] as u64;
            let v = [0, 1, 2].map(|k| Vtx {
                x: c(r[3 * k]) / 4 + 32 * 16 * (i % 2) as i32,
                y: c(r[3 * k + 1]) / 4,
                a: [(r[3 * k + 2] % (2 * lim + 1)) as i32 - lim as i32],
            });
            let want = oracle(&v, 64, 48);
            let got = spans(&v, 64, 48);
            assert_eq!(want.len(), got.len(), "{v:?}");
            count += got.len();
            let d = [v[1].a[0] - v[0].a[0], v[2].a[0] - v[0].a[0]].map(|d| d.unsigned_abs() as f64);
            let rate = 0.5 + (d[0] + d[1]) / (1u64 << 24) as f64;
            for (w, g) in want.iter().zip(&got) {
                assert_eq!(*w, (g.0, g.1, g.2), "{v:?}");
                let off = (g.1 - (v[0].x >> 4)).abs() + (g.0 - (v[0].y >> 4)).abs();
                let e = 16.0 * exact(&v, (16 * g.1 + 8) as f64, (16 * g.0 + 8) as f64);
                let err = (g.3 as f64 - e).abs();
                assert!(err <= rate * (off + 1) as f64 + 1.0, "{v:?}: {g:?} {e}");
            }
        }
        assert!(count > 30_000, "{count}");
    }

    /// Each gradient is `⌊(d₁·Λ₁ + d₂·Λ₂ + 2²³)/2²⁴⌋` of the 64-bit
    /// products, or `None` where that does not fit `i32`, whichever
    /// products make it: differences within ±(2¹⁵ − 1), the 32-bit steps'
    /// (at their ends too), and wider ones, `Λ` of every size.
    #[test]
    fn gradients_are_the_wide_products() {
        let mut rnd = xorshift(0x0bad_5eed_1234_4321);
        let (mut fits, mut wide) = (0, 0);
        for i in 0..400_000 {
            let r = [rnd(), rnd(), rnd(), rnd()];
            let span = [1i64 << 15, 1 << 16, ATTR as i64][i % 3];
            let d = |x: u64| match x % 8 {
                0 => -(1 << 15),
                1 => (1 << 15) - 1,
                2 => 1 << 15,
                _ => (x % (2 * span as u64)) as i64 - span,
            } as i32;
            let a0 = (r[3] % 1000) as i32 - 500;
            let v = [a0, a0 + d(r[0]), a0 + d(r[1])].map(|a| Vtx { x: 0, y: 0, a: [a] });
            let lam = [0, 1, 2, 3].map(|k| {
                (rnd() >> (1 + (r[2] >> (8 * k)) % 40)) as i32 * if rnd() & 1 == 0 { 1 } else { -1 }
            });
            let (d1, d2) = ((v[1].a[0] - a0) as i64, (v[2].a[0] - a0) as i64);
            let want = |l1: i32, l2: i32| {
                let g = (d1 * l1 as i64 + d2 * l2 as i64 + (1 << 23)) >> 24;
                i32::try_from(g).ok()
            };
            let want = want(lam[0], lam[2]).zip(want(lam[1], lam[3]));
            assert_eq!(gradient(&v, 0, lam), want, "{d1} {d2} {lam:?}");
            if d1.abs() < 1 << 15 && d2.abs() < 1 << 15 {
                fits += 1;
            } else {
                wide += 1;
            }
        }
        assert!(fits > 50_000 && wide > 50_000, "{fits} {wide}");
    }

    /// Slivers whose planes are steeper than `i32` holds: the exact
    /// quotient modulo 2³² still gives the plane at their covered pixels.
    #[test]
    fn steep_planes_hold_at_covered_pixels() {
        let mut rnd = xorshift(0x0dd_ba11_cafe_f00d);
        let mut seen = 0;
        for _ in 0..20_000 {
            let x0 = (rnd() % 4000) as i32 - 2000;
            let y0 = (rnd() % 4000) as i32 - 2000;
            let (dx, dy) = ((rnd() % 3000) as i32 + 16, (rnd() % 3000) as i32);
            // A third vertex a sixteenth off the line.
            let (tx, ty) = (x0 + dx / 2, y0 + dy / 2 + 1);
            let v = [
                Vtx {
                    x: x0,
                    y: y0,
                    a: [-ATTR],
                },
                Vtx {
                    x: x0 + dx,
                    y: y0 + dy,
                    a: [ATTR],
                },
                Vtx {
                    x: tx,
                    y: ty,
                    a: [ATTR],
                },
            ];
            let rect = Rect {
                c0: -200,
                c1: 200,
                r0: -200,
                r1: 200,
            };
            let a = area(&v);
            if a == 0 {
                continue;
            }
            if let Some(Triangle { planes, walk: w }) =
                set_up_walked(&v, a, &rect, &mut MaybeUninit::uninit())
            {
                w.run(planes, |s| {
                    for k in 0..s.n as i32 {
                        let p = s.start()[0].wrapping_add(s.step()[0].wrapping_mul(k));
                        assert!(p.unsigned_abs() <= (ATTR as u32) * 16 + (1 << 11), "{v:?}");
                        seen += 1;
                    }
                    Ok::<(), ()>(())
                })
                .unwrap();
            }
        }
        assert!(seen > 100, "{seen}");
    }
}

//! The rare path: a triangle with a vertex the lean path cannot take
//! (behind the near plane, outside the guard band, past `z_w = 2`, or a
//! draw whose rows do not allow the 32-bit vertex form), and targets wider
//! or taller than the guard band reaches.
//!
//! The triangle is clipped in the draw's homogeneous window coordinates
//! (`src/vertex.rs`'s exact rows, clip space up to a positive scale of
//! each axis): by the near plane, then by the guard band around a tile's
//! centre and, with a depth test, by `z_w = 1.5` (a pixel past the far
//! plane is never drawn). Its facing is the sign of the rows'
//! determinant, decided once; a piece that snapping turned the other way
//! draws nothing. The pieces go to the same shading, set-up and walk as
//! the lean path's ([`Frame::pieces`]), their corners' attributes mixed
//! from the triangle's vertices: linearly in clip space along a near cut
//! (SPEC.md 5), linearly in window space along a guard cut (so that every
//! pixel inside the band sees the plane the unclipped triangle had).
//!
//! A vertex the lean path keeps keeps its position here too, so that the
//! rare and lean triangles around it share their edges exactly. Each cut
//! is computed from an edge's inside end to its outside one, whichever way
//! the polygon runs: two triangles sharing an edge cut it at the same
//! point.
//!
//! All of it in `i64`: the rows are below 2⁴⁶, their combinations are
//! [`Wide`] values (61-bit mantissas), the cut fractions 30-bit.

use crate::depth::DepthTest;
use crate::illumination::Viewer;
use crate::light::LightSet;
use crate::material::Specular;
use crate::num::division::floor_div;
use crate::num::Wide;
use crate::options::{DrawStats, ShadingMode};
use crate::setup::{Rect, ATTR};
use crate::shade::{Corners, Frame};
use crate::span::Out;
use crate::vertex::GUARD;

/// The largest side of a tile, in pixels: the guard band (±[`GUARD`]
/// sixteenths) holds it with a pixel to spare.
const TILE: i32 = 2032;
const _: () = assert!(8 * TILE + 16 < GUARD);

/// Most corners a clipped polygon has: a triangle and six planes.
const MAX_CORNERS: usize = 9;

/// One corner of a polygon being clipped: its exact rows, its weights of
/// the triangle's vertices (`Q.30`, summing to 2³⁰) and which vertex it is,
/// if it is one.
#[derive(Clone, Copy, Debug)]
struct Corner {
    h: [i64; 4],
    w: [i32; 3],
    vertex: Option<usize>,
}

/// A plane `a·X + b·Y + c·Z + d·W ≥ 0` of the rows (true values), as
/// factors of each row's true value.
type Plane = [Wide; 4];

/// The signed distance of rows `h` (exponents `e`) from `p`.
fn distance(p: &Plane, h: &[i64; 4], e: &[i32; 4]) -> Wide {
    (0..4).fold(Wide::ZERO, |acc, k| {
        acc.add(&p[k].times(&Wide::new(h[k], e[k])))
    })
}

/// `round(2³⁰·num/den)` for `0 ≤ num ≤ den`, `den > 0`.
fn ratio30(num: Wide, den: Wide) -> i64 {
    let (num, den) = (num.norm(), den.norm());
    if num.m <= 0 {
        return 0;
    }
    // den.m ∈ [2⁶⁰, 2⁶¹): both to den's exponent, then 31 bits each.
    let n = num.at(den.e) >> 30;
    let d = den.m >> 30;
    if d <= 0 {
        return 0;
    }
    (floor_div(2 * (n << 30) + d, 2 * d)).clamp(0, 1 << 30)
}

/// `a + round((b − a)·t/2³⁰)` for `0 ≤ t ≤ 2³⁰` and `|b − a| < 2⁶²`: the
/// difference in 31-bit halves. Out of line: four calls a cut corner.
#[inline(never)]
fn lerp30(a: i64, b: i64, t: i64) -> i64 {
    let d = b - a;
    let (dh, dl) = (d >> 31, d & ((1 << 31) - 1));
    a + ((dh * t) << 1) + ((dl * t + (1 << 29)) >> 30)
}

/// `Xₐ·(Y_b·W_c − Y_c·W_b)`: one term of the facing determinant's
/// expansion along the `X` column, for the rows `a`, `b`, `c` of three
/// consecutive vertices. Out of line: its nine `Wide` operations once, not
/// once a term.
#[inline(never)]
fn cofactor_term(a: &[i64; 4], b: &[i64; 4], c: &[i64; 4]) -> Wide {
    let w = |v: i64| Wide::new(v, 0);
    let minor = w(b[1]).times(&w(c[3])).add(&w(c[1]).times(&w(b[3])).neg());
    w(a[0]).times(&minor)
}

/// Draws triangle `c`, which the lean path does not take.
#[inline(never)]
pub(crate) fn triangle<M, O, D, S, V, L>(
    f: &Frame<'_, '_, S, V, L>,
    c: &mut Corners,
    out: &mut O,
    depth: &mut D,
    stats: &mut DrawStats,
) -> Result<(), O::Error>
where
    M: ShadingMode,
    O: Out,
    D: DepthTest,
    S: Specular,
    V: Viewer,
    L: LightSet,
{
    let rows = &f.stage.rows;
    let e = rows.exponents();
    let h = c.vertex.map(|i| rows.exact(f.stage.position(i)));
    // The facing: the sign of det(X, Y, W), each row's positive scale
    // aside. `X` and `Y` are the clip rows `x_c`, `−y_c` scaled, plus
    // multiples of `w_c`: the determinant is the clip space one's, times
    // −64·W·H, whose sign the window-space area of the triangle (and of each
    // piece cut from it in front of the near plane) has: negative for a
    // front face, as the set-up's doubled area.
    // Expanded along the `X` column: Σₖ Xₖ·(Yₖ₊₁·Wₖ₊₂ − Yₖ₊₂·Wₖ₊₁), a
    // term a vertex ([`cofactor_term`]).
    let mut det = Wide::ZERO;
    for k in 0..3 {
        det = det.add(&cofactor_term(&h[k], &h[(k + 1) % 3], &h[(k + 2) % 3]));
    }
    if det.m == 0 || (det.m > 0 && f.options.cull) {
        return Ok(());
    }
    let facing = if det.m < 0 { -1 } else { 1 };
    let mut poly = [Corner {
        h: [0; 4],
        w: [0; 3],
        vertex: None,
    }; MAX_CORNERS];
    for k in 0..3 {
        let mut w = [0; 3];
        w[k] = 1 << 30;
        poly[k] = Corner {
            h: h[k],
            w,
            vertex: Some(k),
        };
    }
    let mut n = 3;
    // Near: depth attribute ≥ 2⁷, i.e. Z − 2⁷·W ≥ 0.
    let near: Plane = [Wide::ZERO, Wide::ZERO, Wide::new(1, 0), Wide::new(-1, 7)];
    if (0..3).any(|k| distance(&near, &h[k], &e).m < 0) {
        stats.clipped = stats.clipped.saturating_add(1);
        n = cut(&mut poly, n, &near, &e, false);
        if n < 3 {
            return Ok(());
        }
    }
    let (w, hgt) = (f.size.0 as i32, f.size.1 as i32);
    let tiles = |len: i32| {
        if len <= TILE {
            1
        } else {
            (len + TILE - 1) / TILE
        }
    };
    for ty in 0..tiles(hgt) {
        for tx in 0..tiles(w) {
            // The tile's pixels, and its centre (a pixel corner), from the
            // set-up's origin.
            let span = |t: i32, len: i32, o: i32| {
                if len <= TILE {
                    (-o, len - 1 - o, 0)
                } else {
                    let lo = t * TILE;
                    (lo - o, (lo + TILE).min(len) - 1 - o, lo + TILE / 2 - o)
                }
            };
            let (c0, c1, cx) = span(tx, w, f.origin.0);
            let (r0, r1, cy) = span(ty, hgt, f.origin.1);
            let rect = Rect {
                c0: c0.max(f.rect.c0) - cx,
                c1: c1.min(f.rect.c1) - cx,
                r0: r0.max(f.rect.r0) - cy,
                r1: r1.min(f.rect.r1) - cy,
            };
            if rect.c0 > rect.c1 || rect.r0 > rect.r1 {
                continue;
            }
            let mut tile = poly;
            let m = band_clip(&mut tile, n, &e, (16 * cx, 16 * cy), D::ENABLED);
            if m >= 3 {
                draw_polygon::<M, O, D, S, V, L>(
                    f,
                    c,
                    &tile[..m],
                    (cx, cy),
                    rect,
                    facing,
                    out,
                    depth,
                    stats,
                )?;
            }
        }
    }
    Ok(())
}

/// Clips `poly[..n]` by the guard band around sixteenth `o` (from the
/// set-up's origin) and, with a depth test, `z_w ≤ 1.5`.
fn band_clip(
    poly: &mut [Corner; MAX_CORNERS],
    n: usize,
    e: &[i32; 4],
    o: (i32, i32),
    depth: bool,
) -> usize {
    // x − o ≤ G: (G + o)·W − X ≥ 0; x − o ≥ −G: X + (G − o)·W ≥ 0; y alike;
    // and 1.5·2²⁴ ≥ depth attribute. Plane k: axis k/2, negated for even k.
    let g = (GUARD - 40) as i64;
    let one = Wide::new(1, 0);
    let o = [o.0 as i64, o.1 as i64];
    let mut n = n;
    for k in 0..if depth { 5 } else { 4 } {
        let (axis, neg) = (k >> 1, k & 1 == 0);
        let mut p: Plane = [Wide::ZERO; 4];
        p[axis] = if neg { one.neg() } else { one };
        p[3] = match o.get(axis) {
            Some(&o) => Wide::new(if neg { g + o } else { g - o }, 0),
            None => Wide::new(3, 23),
        };
        n = cut(poly, n, &p, e, true);
        if n < 3 {
            return 0;
        }
    }
    n
}

/// Sutherland–Hodgman: `poly[..n]` cut by plane `p`, in place; the new
/// corners' weights along the edge in window space (`window`, for corners
/// in front of the eye) or clip space.
fn cut(poly: &mut [Corner; MAX_CORNERS], n: usize, p: &Plane, e: &[i32; 4], window: bool) -> usize {
    let src = *poly;
    let d: [Wide; MAX_CORNERS] = core::array::from_fn(|k| {
        if k < n {
            distance(p, &src[k].h, e)
        } else {
            Wide::ZERO
        }
    });
    let mut m = 0;
    for k in 0..n {
        let j = if k + 1 == n { 0 } else { k + 1 };
        let (a, b) = (&src[k], &src[j]);
        let (da, db) = (d[k], d[j]);
        if da.m >= 0 && m < MAX_CORNERS {
            poly[m] = *a;
            m += 1;
        }
        if (da.m >= 0) != (db.m >= 0) && m < MAX_CORNERS {
            // From the inside end to the outside one.
            let ((i, di), (o, dout)) = if da.m >= 0 {
                ((a, da), (b, db))
            } else {
                ((b, db), (a, da))
            };
            let t = ratio30(di, di.add(&dout.neg()));
            let hc = [0, 1, 2, 3].map(|r| lerp30(i.h[r], o.h[r], t));
            // The window-space fraction s = t·W_o/W_c where both ends are
            // in front of the eye.
            let s = if window && i.h[3] > 0 && o.h[3] > 0 && hc[3] > 0 {
                ratio30(
                    Wide::new(t, -30).times(&Wide::new(o.h[3], 0)),
                    Wide::new(hc[3], 0),
                )
            } else {
                t
            };
            poly[m] = Corner {
                h: hc,
                w: [0, 1, 2].map(|r| lerp30(i.w[r] as i64, o.w[r] as i64, s) as i32),
                vertex: None,
            };
            m += 1;
        }
    }
    m
}

/// Projects and draws the clipped polygon `poly` in the tile whose centre
/// is pixel `centre` from the set-up's origin, on `rect` (pixels from that
/// centre). Out of line: inlined into [`triangle`]'s tile loop it took
/// 152 bytes more on ARMv6-M.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn draw_polygon<M, O, D, S, V, L>(
    f: &Frame<'_, '_, S, V, L>,
    c: &mut Corners,
    poly: &[Corner],
    centre: (i32, i32),
    rect: Rect,
    facing: i32,
    out: &mut O,
    depth: &mut D,
    stats: &mut DrawStats,
) -> Result<(), O::Error>
where
    M: ShadingMode,
    O: Out,
    D: DepthTest,
    S: Specular,
    V: Viewer,
    L: LightSet,
{
    let rows = &f.stage.rows;
    let (dx, dy) = (16 * centre.0, 16 * centre.1);
    let mut at = [(0i32, 0i32, 0i32); MAX_CORNERS];
    let mut weights = [[0i32; 3]; MAX_CORNERS];
    for (k, p) in poly.iter().enumerate() {
        // A vertex the lean path keeps keeps its position.
        let kept = p
            .vertex
            .and_then(|v| c.cache.get(*c.slot.get(v)?))
            .and_then(|v| v.window());
        let w = match kept {
            Some([x, y, z]) => [x - dx, y - dy, z],
            None => match rows.window_exact(p.h, dx as i64, dy as i64, 1 << 20) {
                // Rounding may take a cut corner a little past the band
                // (a corner already that far out): onto its edge.
                Some([x, y, z]) => [
                    x.clamp(-GUARD, GUARD),
                    y.clamp(-GUARD, GUARD),
                    z.clamp(1 - ATTR, ATTR - 1),
                ],
                None => return Ok(()),
            },
        };
        at[k] = (w[0], w[1], w[2]);
        weights[k] = p.w;
    }
    let mut tris = [[0usize; 3]; MAX_CORNERS - 2];
    let mut count = 0;
    for k in 1..poly.len() - 1 {
        let v = [at[0], at[k], at[k + 1]];
        let area = (v[1].0 - v[0].0) * (v[2].1 - v[0].1) - (v[2].0 - v[0].0) * (v[1].1 - v[0].1);
        // Every piece faces as the triangle does, or draws nothing.
        if area != 0 && (area < 0) == (facing < 0) {
            tris[count] = [0, k, k + 1];
            count += 1;
        }
    }
    if count == 0 {
        return Ok(());
    }
    // The pieces in the tile's coordinates, the output moved to match.
    out.moved(centre);
    let res = f.pieces::<M, O, D>(
        c,
        &at[..poly.len()],
        &weights[..poly.len()],
        &tris[..count],
        facing,
        &rect,
        out,
        depth,
        stats,
    );
    out.moved((-centre.0, -centre.1));
    res
}

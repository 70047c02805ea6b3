//! The set-up and walk's coverage against a brute-force oracle: for random
//! triangles on the 1/16-pixel grid, small and large, inside and around a
//! small viewport, whole and band by band, the spans (walked, and tested
//! sample by sample as a triangle of a few samples is) cover exactly the
//! pixels whose centre passes all three edge functions with the top-left
//! rule (SPEC.md 5), evaluated directly at every pixel; and the planes at
//! every covered pixel lie within the documented distance of the vertex
//! values, out to the guard band and the attributes' bound.

use core::mem::MaybeUninit;

use crate::setup::{area, samples, set_up_walked, Rect, Triangle, Vtx, ATTR};
use crate::triangle::covers_none;
use crate::vertex::GUARD;
use crate::walk::{EdgeFunctions, CHUNK};
use proptest::prelude::*;

/// `E_ab(p)`, y down.
fn edge(a: (i64, i64), b: (i64, i64), p: (i64, i64)) -> i64 {
    (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
}

/// The pixels of `rows` (inclusive) of a `size × size` viewport that the
/// oracle covers, in row-major order.
fn oracle(v: [(i64, i64); 3], size: i64, rows: (i64, i64)) -> Vec<(i64, i64)> {
    let a = edge(v[0], v[1], v[2]);
    let w = if a > 0 { v } else { [v[0], v[2], v[1]] };
    let mut out = Vec::new();
    if a == 0 {
        return out;
    }
    for y in rows.0..=rows.1 {
        for x in 0..size {
            let p = (16 * x + 8, 16 * y + 8);
            let inside = (0..3).all(|i| {
                let (a, b) = (w[i], w[(i + 1) % 3]);
                let e = edge(a, b, p);
                let top_left = b.1 < a.1 || (b.1 == a.1 && b.0 > a.0);
                e > 0 || (e == 0 && top_left)
            });
            if inside {
                out.push((x, y));
            }
        }
    }
    out
}

/// The pixels the set-up and walk cover in `rows`, in row-major order.
fn kernel(v: [(i64, i64); 3], size: i64, rows: (i64, i64)) -> Vec<(i64, i64)> {
    let t = v.map(|(x, y)| Vtx {
        x: x as i32,
        y: y as i32,
        a: [0],
    });
    let mut out = Vec::new();
    let a = area(&t);
    if a == 0 {
        return out;
    }
    let rect = Rect {
        c0: 0,
        c1: size as i32 - 1,
        r0: rows.0 as i32,
        r1: rows.1 as i32,
    };
    if let Some(Triangle { planes, walk }) = set_up_walked(&t, a, &rect, &mut MaybeUninit::uninit())
    {
        walk.run(planes, |s| {
            out.extend((s.x0..s.x0 + s.n as i32).map(|x| (x as i64, s.y as i64)));
            Ok::<(), ()>(())
        })
        .unwrap();
    }
    out
}

/// The pixels in `rows` whose samples the edge functions cover, tested
/// one by one as the set-up does for a triangle of a few samples, in
/// row-major order.
fn tested(v: [(i64, i64); 3], size: i64, rows: (i64, i64)) -> Vec<(i64, i64)> {
    let t = v.map(|(x, y)| Vtx {
        x: x as i32,
        y: y as i32,
        a: [0],
    });
    let rect = Rect {
        c0: 0,
        c1: size as i32 - 1,
        r0: rows.0 as i32,
        r1: rows.1 as i32,
    };
    let a = area(&t);
    let Some(s) = samples(&t, &rect).filter(|_| a != 0) else {
        return Vec::new();
    };
    let e = EdgeFunctions::new(
        t.map(|p| (p.x, p.y)),
        a,
        (16 * s.cols.0 + 8, 16 * s.rows.0 + 8),
    );
    let mut table = [MaybeUninit::uninit(); CHUNK];
    let spans = e.rows(s.rows, s.cols, &mut table);
    let mut out = Vec::new();
    for (j, r) in spans.iter().enumerate() {
        let y = s.rows.0 as i64 + j as i64;
        out.extend((r.x0..r.x0 + r.n).map(|x| (x as i64, y)));
    }
    out
}

/// The walk, and the samples tested one by one, cover what the oracle
/// does on the whole 24 × 24 viewport and on the band of `h` rows from
/// `y0`.
fn whole_and_band(v: [(i64, i64); 3], y0: i64, h: i64) -> Result<(), TestCaseError> {
    let rows = (y0, (y0 + h - 1).min(23));
    for rows in [(0, 23), rows] {
        let want = oracle(v, 24, rows);
        prop_assert_eq!(kernel(v, 24, rows), want.clone());
        prop_assert_eq!(tested(v, 24, rows), want);
    }
    Ok(())
}

/// The farthest a vertex may lie around the 24 × 24 viewport (its first
/// pixel's corner is the origin here).
const FAR: i64 = GUARD as i64 - 24 * 16;

/// A vertex within `range` sub-pixels around a 24 × 24 viewport.
fn vertex(range: i64) -> impl Strategy<Value = (i64, i64)> {
    (-range..24 * 16 + range, -range..24 * 16 + range)
}

/// A position anywhere in the guard band.
fn guard() -> impl Strategy<Value = (i64, i64)> {
    let g = GUARD as i64;
    (-g..=g, -g..=g)
}

/// An attribute anywhere within its bound.
fn attr() -> impl Strategy<Value = i64> {
    -(ATTR as i64)..=ATTR as i64
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4096, ..ProptestConfig::default() })]

    /// Triangles of every size, with vertices up to the guard band's
    /// edge (a thousand pixels away).
    #[test]
    fn spans_cover_what_the_edge_functions_say(
        v in [vertex(64), vertex(64), vertex(64)],
        far in [vertex(FAR), vertex(FAR), vertex(FAR)],
        pick in 0u8..8,
    ) {
        // Mix near and far vertices (bit k: vertex k is far).
        let v: [(i64, i64); 3] = core::array::from_fn(|k| if pick >> k & 1 == 1 { far[k] } else { v[k] });
        whole_and_band(v, 5, 7)?;
    }

    /// Small triangles on a coarse grid: many shared vertex rows, horizontal
    /// edges and samples exactly on edges.
    #[test]
    fn ties_on_edges_and_horizontal_edges(
        v in [(0i64..13, 0i64..13), (0i64..13, 0i64..13), (0i64..13, 0i64..13)],
        y0 in 0i64..24,
        h in 1i64..6,
    ) {
        whole_and_band(v.map(|(x, y)| (x * 32 + 8, y * 32 + 8)), y0, h)?;
    }

    /// Tiny triangles, whole and in bands that cut them.
    #[test]
    fn tiny_triangles(
        o in vertex(32),
        d in [(0i64..40, 0i64..40), (0i64..40, 0i64..40), (0i64..40, 0i64..40)],
        y0 in 0i64..24,
        h in 1i64..3,
    ) {
        whole_and_band(d.map(|(x, y)| (o.0 + x, o.1 + y)), y0, h)?;
    }

    /// The small-box test (`src/triangle.rs`) rejects a triangle whose box
    /// holds at most 2 × 2 samples exactly when the oracle covers none of
    /// them: ties on edges and horizontal edges included.
    #[test]
    fn small_boxes_cover_none_as_the_oracle_says(
        o in (0i64..20 * 16, 0i64..20 * 16),
        d in [(0i64..40, 0i64..40), (0i64..40, 0i64..40), (0i64..40, 0i64..40)],
        snap in any::<bool>(),
    ) {
        // On a coarse grid half the time: samples on edges.
        let v = d.map(|(x, y)| if snap { (o.0 + x / 8 * 8, o.1 + y / 8 * 8) } else { (o.0 + x, o.1 + y) });
        let p = v.map(|(x, y)| [x as i32, y as i32, 0]);
        let a = edge(v[0], v[1], v[2]) as i32;
        let lo = |k: usize| (0..3).map(|j| p[j][k]).min().unwrap_or(0);
        let hi = |k: usize| (0..3).map(|j| p[j][k]).max().unwrap_or(0);
        let (cols, rows) = (((lo(0) + 7) >> 4, (hi(0) - 8) >> 4), ((lo(1) + 7) >> 4, (hi(1) - 8) >> 4));
        // (Boxes that hold no sample or more than 2 × 2 are not this test's.)
        if a == 0 || cols.0 > cols.1 || rows.0 > rows.1 || cols.1 - cols.0 > 1 || rows.1 - rows.0 > 1 {
            return Ok(());
        }
        let none = oracle(v, 24, (0, 23)).is_empty();
        prop_assert_eq!(covers_none(&p, a, cols, rows), none);
    }

    /// At the limits — vertices anywhere in the guard band, attributes to
    /// ±`ATTR` — every covered pixel's plane lies within the set-up's
    /// bound of the exact plane, `(½ + (|d₁| + |d₂|)·2⁻²⁴)·(|c − c₀| + |r −
    /// r₀| + 1) + 1` units (`src/setup.rs`), so within that of the vertices'
    /// range; the same in a band of the rows.
    #[test]
    fn planes_stay_near_the_exact_one(
        p in [guard(), guard(), guard()],
        a in [attr(), attr(), attr()],
        band in -48i32..45,
    ) {
        let v: [Vtx<1>; 3] = core::array::from_fn(|k| Vtx { x: p[k].0 as i32, y: p[k].1 as i32, a: [a[k] as i32] });
        let ar = area(&v);
        prop_assume!(ar != 0);
        let rect = Rect { c0: -48, c1: 47, r0: -48, r1: 47 };
        let d = [v[1].a[0] - v[0].a[0], v[2].a[0] - v[0].a[0]].map(|d| d.unsigned_abs() as f64);
        let rate = 0.5 + (d[0] + d[1]) / (1u64 << 24) as f64;
        let exact = |x: f64, y: f64| {
            let f = v.map(|v| (v.x as f64, v.y as f64, v.a[0] as f64));
            let e = |a: (f64, f64, f64), b: (f64, f64, f64)| (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0);
            let whole = e(f[0], f[1]) + e(f[1], f[2]) + e(f[2], f[0]);
            16.0 * (f[0].2 + e(f[2], f[0]) / whole * (f[1].2 - f[0].2) + e(f[0], f[1]) / whole * (f[2].2 - f[0].2))
        };
        let (c0, r0) = (v[0].x >> 4, v[0].y >> 4);
        let mut whole = Vec::new();
        for rows in [(rect.r0, rect.r1), (band, band + 3)] {
            let mut got = Vec::new();
            if let Some(Triangle { planes, walk: w }) = set_up_walked(&v, ar, &Rect { r0: rows.0, r1: rows.1, ..rect }, &mut MaybeUninit::uninit()) {
                w.run(planes, |s| {
                    for k in 0..s.n as i32 {
                        let (x, y) = (s.x0 + k, s.y);
                        let value = s.start()[0].wrapping_add(s.step()[0].wrapping_mul(k));
                        let e = exact((16 * x + 8) as f64, (16 * y + 8) as f64);
                        let bound = rate * ((x - c0).abs() + (y - r0).abs() + 1) as f64 + 1.0;
                        prop_assert!((value as f64 - e).abs() <= bound, "{v:?} at ({x}, {y}): {value} vs {e}");
                        got.push((x, y, value));
                    }
                    Ok(())
                })?;
            }
            if rows.0 == rect.r0 {
                whole = got;
            } else {
                // A band's pixels are the whole frame's, value for value.
                let want: Vec<_> = whole.iter().copied().filter(|p| p.1 >= rows.0 && p.1 <= rows.1).collect();
                prop_assert_eq!(got, want);
            }
        }
    }
}

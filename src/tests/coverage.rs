//! The rasterizer's coverage against a brute-force oracle: for random
//! triangles on the 1/16-pixel grid, small and large, inside and around a
//! small viewport, whole and band by band, the spans cover exactly the
//! pixels whose centre passes all three edge functions with the top-left
//! rule (SPEC.md 5), evaluated directly at every pixel.

use crate::rasterizer::{
    rasterize_rows, ClipRect, RasterVertex, ATTR_LIMIT, CLIP_LIMIT, DRIFT, GUARD,
};
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

/// The pixels the rasterizer covers in `rows`, in row-major order.
fn kernel(v: [(i64, i64); 3], size: i64, rows: (i64, i64)) -> Vec<(i64, i64)> {
    let rv = v.map(|(x, y)| RasterVertex { x, y, attr: [] });
    let clip = ClipRect::of_size(size as u32, size as u32).unwrap();
    let mut out = Vec::new();
    rasterize_rows(&rv, clip, (rows.0 as i32, rows.1 as i32), false, |s| {
        out.extend((s.x0..=s.x1).map(|x| (x as i64, s.y as i64)));
    });
    out
}

/// The rasterizer covers what the oracle does on the whole 24 × 24
/// viewport and on the band of `h` rows from `y0`.
fn whole_and_band(v: [(i64, i64); 3], y0: i64, h: i64) -> Result<(), TestCaseError> {
    prop_assert_eq!(kernel(v, 24, (0, 23)), oracle(v, 24, (0, 23)));
    let rows = (y0, (y0 + h - 1).min(23));
    prop_assert_eq!(kernel(v, 24, rows), oracle(v, 24, rows));
    Ok(())
}

/// The farthest a vertex may lie around the 24 × 24 viewport (its centre
/// pixel corner is 12·16 sub-pixels in).
const FAR: i64 = GUARD - 12 * 16;

/// A vertex within `range` sub-pixels around a 24 × 24 viewport.
fn vertex(range: i64) -> impl Strategy<Value = (i64, i64)> {
    (-range..24 * 16 + range, -range..24 * 16 + range)
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
        prop_assert_eq!(kernel(v, 24, (0, 23)), oracle(v, 24, (0, 23)));
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

    /// Tiny triangles (a box of at most a few pixel centres, which the
    /// set-up tests one by one before anything else), whole and in bands
    /// that cut them.
    #[test]
    fn tiny_triangles(
        o in vertex(32),
        d in [(0i64..40, 0i64..40), (0i64..40, 0i64..40), (0i64..40, 0i64..40)],
        y0 in 0i64..24,
        h in 1i64..3,
    ) {
        whole_and_band(d.map(|(x, y)| (o.0 + x, o.1 + y)), y0, h)?;
    }
}

/// The first pixel (row, column, attribute, value, allowed range) of the
/// spans `rasterize_rows` gives whose attribute (span start plus steps)
/// lies more than `DRIFT + k/2` (pixel `k` of the span) outside the range of the vertex values; `None` if
/// there is none.
#[allow(clippy::type_complexity)]
fn first_beyond_drift(
    rv: &[RasterVertex<2>; 3],
    vp: ClipRect,
    rows: (i32, i32),
) -> Option<(i32, i32, usize, i64, i64, i64)> {
    let mut bad = None;
    rasterize_rows(rv, vp, rows, false, |s| {
        for i in 0..2 {
            for k in 0..=(s.x1 - s.x0) as i64 {
                // DRIFT at the start, and half a unit each pixel on.
                let d = DRIFT + (k + 1) / 2;
                let lo = rv.iter().map(|v| v.attr[i]).min().unwrap() - d;
                let hi = rv.iter().map(|v| v.attr[i]).max().unwrap() + d;
                let a = s.start[i] + k * s.step[i];
                if !(lo..=hi).contains(&a) && bad.is_none() {
                    bad = Some((s.y, s.x0 + k as i32, i, a, lo, hi));
                }
            }
        }
    });
    bad
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4096, ..ProptestConfig::default() })]

    /// Every span keeps every attribute, at every pixel (start plus k
    /// steps), within `DRIFT + k/2` of the vertex values' range: the promise
    /// that lets the renderer skip per-span range checks. Triangles up to
    /// 300 pixels across, slivers included, attributes up to the limit,
    /// the rows of a band or the whole viewport.
    #[test]
    fn spans_stay_within_the_drift(
        v in [(-400i64..4800, -400i64..4800), (-400i64..4800, -400i64..4800), (-400i64..4800, -400i64..4800)],
        attr in [[-ATTR_LIMIT..=ATTR_LIMIT, 0i64..=1 << 22], [-ATTR_LIMIT..=ATTR_LIMIT, 0i64..=1 << 22], [-ATTR_LIMIT..=ATTR_LIMIT, 0i64..=1 << 22]],
        y0 in 0i32..300,
        h in 1i32..300,
    ) {
        let rv: [RasterVertex<2>; 3] = core::array::from_fn(|k| RasterVertex { x: v[k].0, y: v[k].1, attr: attr[k] });
        let vp = ClipRect::of_size(300, 300).unwrap();
        let rows = (y0, (y0 + h - 1).min(299));
        prop_assert_eq!(first_beyond_drift(&rv, vp, rows), None);
    }
}

/// A coordinate at or near the guard band's edges around the 24 × 24
/// viewport, or near the viewport.
fn limit_coord() -> impl Strategy<Value = i64> {
    let c = 12 * 16;
    prop_oneof![
        Just(c + GUARD),
        Just(c - GUARD),
        (c + GUARD - 4096..=c + GUARD),
        (c - GUARD..=c - GUARD + 4096),
        (-64i64..24 * 16 + 64),
    ]
}

/// An attribute at or near its limits.
fn limit_attr() -> impl Strategy<Value = i64> {
    prop_oneof![
        Just(ATTR_LIMIT),
        Just(-ATTR_LIMIT),
        (ATTR_LIMIT - 1024..=ATTR_LIMIT),
        (-ATTR_LIMIT..-ATTR_LIMIT + 1024),
        (-1024i64..1024),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4096, ..ProptestConfig::default() })]

    /// Vertices at the edges of the limits (the guard band's edges,
    /// attributes ±2^25, mixed with ones near the viewport): the coverage
    /// is the oracle's, whole and in bands, and every covered pixel's
    /// attributes (span start plus steps) lie within `DRIFT + k/2` of the vertex
    /// values' range. In a debug build (the default for `cargo test`) any
    /// overflow on the way panics and fails the case.
    #[test]
    fn vertices_at_the_limits(
        v in [(limit_coord(), limit_coord()), (limit_coord(), limit_coord()), (limit_coord(), limit_coord())],
        attr in [[limit_attr(), limit_attr()], [limit_attr(), limit_attr()], [limit_attr(), limit_attr()]],
        y0 in 0i64..24,
        h in 1i64..4,
    ) {
        whole_and_band(v, y0, h)?;
        let rv: [RasterVertex<2>; 3] = core::array::from_fn(|k| RasterVertex { x: v[k].0, y: v[k].1, attr: attr[k] });
        let vp = ClipRect::of_size(24, 24).unwrap();
        prop_assert_eq!(first_beyond_drift(&rv, vp, (0, 23)), None);
    }

    /// A vertex outside the limits, by any amount up to `i64`'s ends: the
    /// entry points draw nothing and say so (`None`), without panicking.
    #[test]
    fn vertices_beyond_the_limits_draw_nothing(
        v in [vertex(64), vertex(64), vertex(64)],
        k in 0usize..3,
        which in 0u8..3,
        beyond in prop_oneof![Just(i64::MAX), Just(i64::MIN), 1i64..1 << 40, -(1i64 << 40)..0],
    ) {
        let mut rv: [RasterVertex<1>; 3] = v.map(|(x, y)| RasterVertex { x, y, attr: [x - y] });
        let c = 12 * 16;
        let outside = |lim: i64| if beyond > 0 { lim.saturating_add(beyond) } else { (-lim - 1).saturating_add(beyond) };
        match which {
            0 => rv[k].x = outside(GUARD).saturating_add(c),
            1 => rv[k].y = outside(GUARD).saturating_add(c),
            _ => rv[k].attr[0] = outside(ATTR_LIMIT),
        }
        let vp = ClipRect::of_size(24, 24).unwrap();
        let mut drawn = 0;
        prop_assert_eq!(rasterize_rows(&rv, vp, (0, 23), false, |_| drawn += 1), None);
        prop_assert_eq!(drawn, 0);
    }
}

/// A clip rectangle beyond `CLIP_LIMIT` pixels a side is refused (`None`,
/// nothing drawn): its corners would lie outside the guard band around its
/// centre. At the limit a quad with its corners on the band's covers it,
/// every pixel once.
#[test]
fn clip_rectangles_beyond_the_limit_draw_nothing() {
    let side = CLIP_LIMIT as i32;
    let c = 16 * (side as i64 / 2);
    let corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)].map(|(x, y)| RasterVertex {
        x: c + x * GUARD,
        y: c + y * GUARD,
        attr: [],
    });
    let v = [corners[0], corners[1], corners[2]];
    for s in [side + 1, 1 << 20, i32::MAX] {
        let clip = ClipRect::of_size(s as u32, s as u32).unwrap();
        assert!(!clip.within_limits());
        let mut spans = 0;
        assert_eq!(
            rasterize_rows(&v, clip, (0, 100), false, |_| spans += 1),
            None
        );
        assert_eq!(spans, 0);
    }
    let clip = ClipRect::of_size(side as u32, side as u32).unwrap();
    assert!(clip.within_limits());
    let mut pixels = 0i64;
    for t in [v, [corners[0], corners[2], corners[3]]] {
        rasterize_rows(&t, clip, (0, side - 1), false, |s| {
            assert!(s.x0 >= 0 && s.x1 < side && (0..side).contains(&s.y));
            pixels += (s.x1 - s.x0 + 1) as i64;
        });
    }
    assert_eq!(pixels, side as i64 * side as i64);
}

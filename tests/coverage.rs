//! The rasterizer's coverage against a brute-force oracle: for random
//! triangles on the 1/16-pixel grid, small and large, inside and around a
//! small viewport, whole and band by band, the spans cover exactly the
//! pixels whose centre passes all three edge functions with the top-left
//! rule (SPEC.md 5), evaluated directly at every pixel.

use fixshade::rasterizer::{
    rasterize_rows, ClipRect, RasterVertex, Triangle, ATTR_LIMIT, CLIP_LIMIT, COORD_LIMIT, DRIFT,
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

/// A vertex within `range` sub-pixels around a 24 × 24 viewport.
fn vertex(range: i64) -> impl Strategy<Value = (i64, i64)> {
    (-range..24 * 16 + range, -range..24 * 16 + range)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4096, ..ProptestConfig::default() })]

    /// Triangles of every size, with vertices up to 10 000 pixels away.
    #[test]
    fn spans_cover_what_the_edge_functions_say(
        v in [vertex(64), vertex(64), vertex(64)],
        far in [vertex(160_000), vertex(160_000), vertex(160_000)],
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
/// spans `rasterize_rows` gives (only the bounded ones if `bounded_only`)
/// whose attribute (span start plus steps) lies more than `DRIFT` outside
/// the range of the vertex values; `None` if there is none.
#[allow(clippy::type_complexity)]
fn first_beyond_drift(
    rv: &[RasterVertex<2>; 3],
    vp: ClipRect,
    rows: (i32, i32),
    bounded_only: bool,
) -> Option<(i32, i32, usize, i64, i64, i64)> {
    let mut bad = None;
    rasterize_rows(rv, vp, rows, false, |s| {
        if bounded_only && !s.bounded {
            return;
        }
        for i in 0..2 {
            let lo = rv.iter().map(|v| v.attr[i]).min().unwrap() - DRIFT;
            let hi = rv.iter().map(|v| v.attr[i]).max().unwrap() + DRIFT;
            for k in 0..=(s.x1 - s.x0) as i64 {
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

    /// A span marked `bounded` keeps every attribute, at every pixel
    /// (start plus k steps), within `DRIFT` of the vertex values' range:
    /// the promise that lets the renderer skip per-span range checks.
    /// Triangles up to 300 pixels across (so both bounded and unbounded
    /// ones occur), slivers included, attributes up to 2^25, the rows of a
    /// band or the whole viewport.
    #[test]
    fn bounded_spans_stay_within_the_drift(
        v in [(-400i64..4800, -400i64..4800), (-400i64..4800, -400i64..4800), (-400i64..4800, -400i64..4800)],
        attr in [[-(1i64 << 25)..1i64 << 25, 0i64..1 << 22], [-(1i64 << 25)..1i64 << 25, 0i64..1 << 22], [-(1i64 << 25)..1i64 << 25, 0i64..1 << 22]],
        y0 in 0i32..300,
        h in 1i32..300,
    ) {
        let rv: [RasterVertex<2>; 3] = core::array::from_fn(|k| RasterVertex { x: v[k].0, y: v[k].1, attr: attr[k] });
        let vp = ClipRect::of_size(300, 300).unwrap();
        let rows = (y0, (y0 + h - 1).min(299));
        prop_assert_eq!(first_beyond_drift(&rv, vp, rows, true), None);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2048, ..ProptestConfig::default() })]

    /// A triangle set up in the band where it starts and resumed from its
    /// paused walk in each band below (what the band renderer does with
    /// cached vertices) gives exactly the spans, starts and steps of the
    /// uninterrupted walk: triangles of every size, slivers (which do not
    /// pause and are set up again) and far vertices included.
    #[test]
    fn resumed_walks_give_the_whole_walks_spans(
        v in [vertex(64), vertex(64), vertex(64)],
        far in [vertex(160_000), vertex(160_000), vertex(160_000)],
        pick in 0u8..8,
        attr in [[-(1i64 << 33)..1i64 << 33, 0i64..1 << 22], [-(1i64 << 33)..1i64 << 33, 0i64..1 << 22], [-(1i64 << 33)..1i64 << 33, 0i64..1 << 22]],
        h in 1i32..9,
    ) {
        let v: [(i64, i64); 3] = core::array::from_fn(|k| if pick >> k & 1 == 1 { far[k] } else { v[k] });
        let rv: [RasterVertex<2>; 3] = core::array::from_fn(|k| RasterVertex { x: v[k].0, y: v[k].1, attr: attr[k] });
        let vp = ClipRect::of_size(24, 24).unwrap();
        let mut whole = Vec::new();
        rasterize_rows(&rv, vp, (0, 23), false, |s| whole.push((s.y, s.x0, s.x1, s.start, s.step, s.bounded)));
        let mut banded = Vec::new();
        let mut walk = None;
        for y0 in (0..24).step_by(h as usize) {
            let rows = (y0, (y0 + h - 1).min(23));
            let mut push = |s: &fixshade::rasterizer::Span<2>| banded.push((s.y, s.x0, s.x1, s.start, s.step, s.bounded));
            walk = match walk.take() {
                Some(w) => fixshade::rasterizer::Walk::resume(w, rows, &mut push),
                None => Triangle::setup_rows(&rv, vp, rows, false).and_then(|t| t.walk_rows(&mut push)),
            };
        }
        prop_assert!(walk.is_none());
        prop_assert_eq!(banded, whole);
    }
}

/// The mark is given where it should be (else the property above would
/// hold vacuously): a small triangle with gentle gradients is bounded, one
/// wider than 256 pixels is not.
#[test]
fn small_gentle_triangles_are_bounded() {
    let tri = |w: i64| {
        [(8, 8), (8 + 16 * w, 8), (8, 8 + 16 * 40)].map(|(x, y)| RasterVertex {
            x,
            y,
            attr: [x << 8, y << 8],
        })
    };
    let vp = ClipRect::of_size(400, 400).unwrap();
    let marks = |w: i64| {
        let mut m = Vec::new();
        rasterize_rows(&tri(w), vp, (0, 399), false, |s| m.push(s.bounded));
        m
    };
    let small = marks(100);
    assert!(!small.is_empty() && small.iter().all(|&b| b));
    let wide = marks(300);
    assert!(!wide.is_empty() && wide.iter().all(|&b| !b));
}

/// A coordinate at or near the limits, or near the 24 × 24 viewport.
fn limit_coord() -> impl Strategy<Value = i64> {
    prop_oneof![
        Just(COORD_LIMIT),
        Just(-COORD_LIMIT),
        (COORD_LIMIT - 4096..=COORD_LIMIT),
        (-COORD_LIMIT..=-COORD_LIMIT + 4096),
        (-64i64..24 * 16 + 64),
    ]
}

/// An attribute at or near its limits.
fn limit_attr() -> impl Strategy<Value = i64> {
    prop_oneof![
        Just(ATTR_LIMIT - 1),
        Just(-ATTR_LIMIT),
        (ATTR_LIMIT - 1024..ATTR_LIMIT),
        (-ATTR_LIMIT..-ATTR_LIMIT + 1024),
        (-1024i64..1024),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4096, ..ProptestConfig::default() })]

    /// Vertices at the edges of the limits (coordinates ±2^28 sub-pixels,
    /// attributes −2^33 and 2^33 − 1, mixed with ones near the viewport):
    /// the coverage is the oracle's, whole and in bands, and every covered
    /// pixel's attributes (span start plus steps) lie within one unit of
    /// the vertex values' range. In a debug build (the default for
    /// `cargo test`) any overflow on the way panics and fails the case.
    #[test]
    fn vertices_at_the_limits(
        v in [(limit_coord(), limit_coord()), (limit_coord(), limit_coord()), (limit_coord(), limit_coord())],
        attr in [[limit_attr(), limit_attr()], [limit_attr(), limit_attr()], [limit_attr(), limit_attr()]],
        y0 in 0i64..24,
        h in 1i64..4,
    ) {
        whole_and_band(v, y0, h)?;
        let rv: [RasterVertex<2>; 3] = core::array::from_fn(|k| RasterVertex { x: v[k].0, y: v[k].1, attr: attr[k] });
        prop_assert!(rv.iter().all(RasterVertex::within_limits));
        let vp = ClipRect::of_size(24, 24).unwrap();
        prop_assert_eq!(first_beyond_drift(&rv, vp, (0, 23), false), None);
    }

    /// A vertex outside the limits, by any amount up to `i64`'s ends: the
    /// entry points draw nothing and say so (`None`), without panicking;
    /// the same triangle `clamped` draws what the triangle with that vertex
    /// at the limit draws.
    #[test]
    fn vertices_beyond_the_limits_draw_nothing(
        v in [vertex(64), vertex(64), vertex(64)],
        k in 0usize..3,
        which in 0u8..3,
        beyond in prop_oneof![Just(i64::MAX), Just(i64::MIN), 1i64..1 << 40, -(1i64 << 40)..0],
    ) {
        let mut rv: [RasterVertex<1>; 3] = v.map(|(x, y)| RasterVertex { x, y, attr: [x - y] });
        let outside = |lim: i64| if beyond > 0 { lim.saturating_add(beyond) } else { (-lim - 1).saturating_add(beyond) };
        match which {
            0 => rv[k].x = outside(COORD_LIMIT),
            1 => rv[k].y = outside(COORD_LIMIT),
            _ => rv[k].attr[0] = if beyond > 0 { (ATTR_LIMIT - 1).saturating_add(beyond) } else { (-ATTR_LIMIT - 1).saturating_add(beyond) },
        }
        prop_assert!(!rv[k].within_limits());
        let vp = ClipRect::of_size(24, 24).unwrap();
        let mut drawn = 0;
        prop_assert_eq!(rasterize_rows(&rv, vp, (0, 23), false, |_| drawn += 1), None);
        prop_assert!(Triangle::setup(&rv, vp, false).is_none());
        prop_assert_eq!(drawn, 0);
        let spans = |t: &[RasterVertex<1>; 3]| {
            let mut out = Vec::new();
            rasterize_rows(t, vp, (0, 23), false, |s| out.push((s.y, s.x0, s.x1, s.start, s.step)));
            out
        };
        let clamped = rv.map(RasterVertex::clamped);
        let mut at_limit = rv;
        match which {
            0 => at_limit[k].x = if beyond > 0 { COORD_LIMIT } else { -COORD_LIMIT },
            1 => at_limit[k].y = if beyond > 0 { COORD_LIMIT } else { -COORD_LIMIT },
            _ => at_limit[k].attr[0] = if beyond > 0 { ATTR_LIMIT - 1 } else { -ATTR_LIMIT },
        }
        prop_assert_eq!(spans(&clamped), spans(&at_limit));
    }
}

/// A clip rectangle beyond `CLIP_LIMIT` pixels a side is refused (`None`,
/// nothing drawn): there the row walk's attribute steps could leave `i64`
/// (found by an audit: a sliver with vertices at the limits, drawn in the
/// rows near 2^24 of a 2^25-pixel viewport). At the limit itself the same
/// triangles draw without overflow in a debug build.
#[test]
fn clip_rectangles_beyond_the_limit_draw_nothing() {
    let a = ATTR_LIMIT;
    let v = [
        RasterVertex {
            x: 0,
            y: COORD_LIMIT,
            attr: [a - 1],
        },
        RasterVertex {
            x: COORD_LIMIT,
            y: 1,
            attr: [-a],
        },
        RasterVertex {
            x: 67_108_863,
            y: 201_326_593,
            attr: [-a],
        },
    ];
    assert!(v.iter().all(RasterVertex::within_limits));
    for side in [1u32 << 24, 1 << 25, u32::MAX] {
        let clip = ClipRect::of_size(side, side).unwrap();
        assert!(!clip.within_limits());
        let mut spans = 0;
        let rows = ((1 << 24) - 3000, 1 << 24);
        assert_eq!(rasterize_rows(&v, clip, rows, false, |_| spans += 1), None);
        assert!(Triangle::setup(&v, clip, false).is_none());
        assert_eq!(spans, 0);
    }
    // At the limit: the same sliver and its mirror images, in every band
    // of 4096 rows; each covered row's span lies within the clip.
    let side = CLIP_LIMIT as u32;
    let clip = ClipRect::of_size(side, side).unwrap();
    assert!(clip.within_limits());
    for flip in 0..4 {
        let w = v.map(|mut p| {
            if flip & 1 == 1 {
                p.x = COORD_LIMIT - p.x;
            }
            if flip & 2 == 2 {
                p.y = COORD_LIMIT - p.y;
            }
            p
        });
        for y0 in (0..side as i32).step_by(4096) {
            rasterize_rows(&w, clip, (y0, y0 + 4095), false, |s| {
                assert!(s.x0 >= 0 && s.x1 < side as i32 && (y0..y0 + 4096).contains(&s.y));
            });
        }
    }
}

//! The Gouraud span shaders: every way of walking a span (whole rows,
//! pixel by pixel, skipping, through the depth test) gives the same pixels,
//! and those stay within the documented distance of the exact channel
//! values.

use crate::span::{PackedGouraud, PairGouraud, SpanShader, BLOCK_PAIRS};
use proptest::prelude::*;

const ONE: i64 = 1 << 16;
/// Field sizes (`Q.16`): red and blue 32, green 64.
const LIM: [i64; 3] = [32 * ONE, 64 * ONE, 32 * ONE];

/// The channels of a raw RGB565 pixel.
fn channels(p: u16) -> [i64; 3] {
    [(p >> 11) as i64, ((p >> 5) & 63) as i64, (p & 31) as i64]
}

/// A span whose channels stay well inside their fields: start and end
/// values in `[1/2, max + 1/2)` (the biased range of colours in [0, 1]).
fn span() -> impl Strategy<Value = ([i64; 3], [i64; 3], u32)> {
    (1u32..400, any::<[u32; 6]>()).prop_map(|(n, r)| {
        let mut c = [0; 3];
        let mut d = [0; 3];
        for k in 0..3 {
            let lo = ONE / 2;
            let hi = LIM[k] - ONE / 2;
            let a = lo + (r[k] as i64) % (hi - lo);
            let b = lo + (r[k + 3] as i64) % (hi - lo);
            c[k] = a;
            d[k] = if n > 1 { (b - a) / (n as i64 - 1) } else { 0 };
        }
        (c, d, n)
    })
}

/// The pixels of a fresh shader walked with `next`.
fn by_next(mut sh: impl SpanShader, n: u32) -> Vec<u16> {
    (0..n).map(|_| sh.next()).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2048))]

    /// `fill_row`, `next` and `skip` agree pixel for pixel, and each pair
    /// pixel is within 2⁻⁶ LSB (plus the lane's rounding) of the exact
    /// value: its channel is the floor of a value at most that far away.
    #[test]
    fn pair_shader_walks_agree_and_stay_close((c, d, n) in span(), cut in 0u32..400) {
        let sh = PairGouraud::new(c, d, n).expect("inside the fields");
        let mut row = vec![0u16; n as usize];
        sh.clone().fill_row(&mut row);
        prop_assert_eq!(&row, &by_next(sh.clone(), n));
        // Skip to a pixel, then fill the rest of the row.
        let cut = cut % n;
        let mut rest = vec![0u16; (n - cut) as usize];
        let mut skipped = sh.clone();
        skipped.skip(cut);
        skipped.fill_row(&mut rest);
        prop_assert_eq!(&rest[..], &row[cut as usize..]);
        // 2^-6 LSB from the step's rounding, 2^-10 from the lane's.
        let eps = (ONE >> 6) + (ONE >> 10);
        for (k, &p) in row.iter().enumerate() {
            let got = channels(p);
            for ch in 0..3 {
                let v = c[ch] + d[ch] * k as i64;
                let (lo, hi) = ((v - eps) >> 16, (v + eps) >> 16);
                prop_assert!(
                    (lo..=hi).contains(&got[ch]),
                    "pixel {} channel {}: {} not in {}..={}", k, ch, got[ch], lo, hi
                );
            }
        }
    }

    /// The depth-tested walk writes, where the test passes, exactly the
    /// pixels of the plain walk, and leaves the others alone; for both
    /// shaders.
    #[test]
    fn depth_rows_write_the_plain_pixels(
        (c, d, n) in span(),
        z0 in 0i64..(65535 << 8),
        dz in -4000i64..4000,
        seed in any::<u64>(),
    ) {
        let mut s = seed;
        let stored: Vec<u16> = (0..n)
            .map(|_| {
                s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                (s >> 48) as u16
            })
            .collect();
        let pair = PairGouraud::new(c, d, n).expect("inside the fields");
        let packed = PackedGouraud::new(c, d, n).expect("inside the fields");
        let plain = [by_next(pair.clone(), n), by_next(packed.clone(), n)];
        let written = [
            run_depth(pair, &stored, z0, dz),
            run_depth(packed, &stored, z0, dz),
        ];
        for (plain, (row, depth, count)) in plain.iter().zip(written) {
            let mut passed = 0;
            for k in 0..n as usize {
                let z16 = ((z0 + dz * k as i64) >> 8).clamp(0, 65535) as u16;
                if z16 < stored[k] {
                    passed += 1;
                    prop_assert_eq!(depth[k], z16);
                    prop_assert_eq!(row[k], plain[k]);
                } else {
                    prop_assert_eq!(depth[k], stored[k]);
                    prop_assert_eq!(row[k], 0xDEAD);
                }
            }
            prop_assert_eq!(count, passed);
        }
    }
}

fn run_depth(
    mut sh: impl SpanShader,
    stored: &[u16],
    z: i64,
    dz: i64,
) -> (Vec<u16>, Vec<u16>, u32) {
    let mut row = vec![0xDEADu16; stored.len()];
    let mut depth = stored.to_vec();
    let count = sh.depth_row(&mut row, &mut depth, z, dz);
    (row, depth, count)
}

/// A span that comes within the lanes' margin of a field's end is refused
/// (the caller then uses the clamped shader), and a long gentle gradient
/// is monotonic: no step beyond RGB565's own.
#[test]
fn pair_shader_refuses_edges_and_keeps_gradients_monotonic() {
    assert!(PairGouraud::new([0, ONE, ONE], [0; 3], 20).is_none());
    assert!(PairGouraud::new([ONE, LIM[1] - 1, ONE], [0; 3], 20).is_none());
    // Red from 0.5 to 31.4 over 4 × BLOCK_PAIRS × 2 + 7 pixels.
    let n = 8 * BLOCK_PAIRS + 7;
    let d = (31 * ONE - ONE / 10) / n as i64;
    let mut row = vec![0u16; n as usize];
    PairGouraud::new([ONE / 2, ONE, ONE], [d, 0, 0], n)
        .unwrap()
        .fill_row(&mut row);
    let reds: Vec<i64> = row.iter().map(|&p| channels(p)[0]).collect();
    assert!(reds.windows(2).all(|w| w[1] == w[0] || w[1] == w[0] + 1));
    let end = (ONE / 2 + d * (n as i64 - 1)) >> 16;
    assert_eq!((reds[0], *reds.last().unwrap()), (0, end));
}

/// Bad input to the public span functions and shaders (any step, any
/// depth, shaders stepped past their span or from the ends of their
/// fields' types): the checked constructors say `None`, the clamped paths
/// clamp, and nothing panics in a debug build (overflow checks on).
#[test]
fn extreme_steps_and_depths_do_not_panic() {
    use crate::depth::DepthBuffer;
    use crate::framebuffer::Framebuffer;
    use crate::span::{
        depth_row_pixels, emit, ClampedGouraud, FlatShader, FramebufferSink, PixelSink, SpanDepth,
        TargetSink,
    };
    use crate::Shade;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::prelude::{Point, Size};
    use embedded_graphics::primitives::Rectangle;

    // Checked constructors: a step whose product with the length leaves
    // i64, at both ends.
    for d in [1i64 << 50, i64::MAX, i64::MIN, -(1 << 50)] {
        assert!(PackedGouraud::new([ONE; 3], [d, 0, 0], 1 << 14).is_none());
        assert!(PairGouraud::new([ONE; 3], [0, d, 0], 1 << 14).is_none());
        assert!(PackedGouraud::new([ONE; 3], [0, 0, d], u32::MAX).is_none());
    }
    // Length 1: the step is never used (up to the rasterizer's steep
    // limit, 2^40; beyond it a 32-bit target refuses the span, which the
    // rasterizer cannot give).
    assert!(PackedGouraud::new([ONE; 3], [1 << 40; 3], 1).is_some());
    assert!(PairGouraud::new([ONE; 3], [-(1 << 40); 3], 1).is_some());

    // A pair shader walked far past the span it was made for: its block
    // anchors wrap, its pixels are garbage but nothing panics.
    let mut sh = PairGouraud::new([1 << 16, 6621, 1 << 16], [0, 4_186_115, 0], 2).unwrap();
    sh.fill_row(&mut [0u16; 600]);
    sh.skip(u32::MAX);
    sh.next();

    let flat = |x: i32| FlatShader {
        plain: 7,
        shade: Shade::BLACK,
        dither: true,
        x,
        y: 0,
    };
    let mut f = flat(i32::MAX);
    f.next();
    f.skip(u32::MAX);
    let mut g = ClampedGouraud {
        c: [i64::MAX, i64::MIN, 0],
        d: [1 << 40, -(1 << 40), i64::MAX],
        dither: true,
        x: i32::MAX,
        y: 0,
    };
    for _ in 0..4 {
        g.next();
        g.skip(1 << 24);
    }
    assert_eq!(g.c[0], i64::MAX, "saturated, not wrapped");

    // Depths and steps at the ends of i64: the depth is clamped per pixel.
    for (z, dz) in [
        (i64::MAX, 1),
        (i64::MIN, -1),
        (0, 1 << 61),
        (1 << 23, i64::MAX),
        (i64::MAX, i64::MIN),
    ] {
        let (mut row, mut drow) = ([0u16; 8], [u16::MAX; 8]);
        let mut sh = flat(0);
        let n = depth_row_pixels(&mut sh, &mut row, &mut drow, z, dz);
        assert!(n <= 8);
        sh.depth_row(&mut row, &mut drow, z, dz);
        for inside in [false, true] {
            let mut px = [0u16; 8];
            let mut fb = Framebuffer::new(&mut px, 8, 1).unwrap();
            let mut zs = [u16::MAX; 8];
            let mut depth = DepthBuffer::new(&mut zs, 8, 1).unwrap();
            let z = SpanDepth { z, dz, inside };
            // Framebuffer rows (in place) and a plain target (runs).
            emit(
                &mut FramebufferSink { fb: &mut fb },
                &mut depth,
                0,
                0,
                8,
                z,
                flat(0),
            )
            .unwrap();
            let mut sink = TargetSink {
                target: &mut fb.canvas(),
                origin: Point::zero(),
            };
            emit(&mut sink, &mut depth, 0, 0, 8, z, flat(0)).unwrap();
        }
    }
    // A depth of 0 at the first pixel stepping by +∞: only pixels whose
    // clamped depth passes are written.
    let (mut row, mut drow) = ([0u16; 4], [1u16; 4]);
    assert_eq!(
        depth_row_pixels(
            &mut FlatShader {
                dither: false,
                ..flat(0)
            },
            &mut row,
            &mut drow,
            0,
            i64::MAX
        ),
        1
    );
    assert_eq!((row, drow), ([7, 0, 0, 0], [0, 1, 1, 1]));

    // A target sink placed so that a span would end past i32::MAX (or its
    // origin plus the column overflows): not sent, no panic.
    let mut px = [0u16; 8];
    let mut fb = Framebuffer::new(&mut px, 8, 1).unwrap();
    for (origin, x0) in [
        (i32::MAX - 3, 0),
        (0, i32::MAX - 3),
        (1, i32::MAX),
        (-1, i32::MIN),
    ] {
        let mut sink = TargetSink {
            target: &mut fb.canvas(),
            origin: Point::new(origin, 0),
        };
        sink.fill(0, x0, 8, core::iter::repeat(0xFFFF)).unwrap();
    }
    assert_eq!(px, [0; 8]);
    // fill_solid far out: clipped in i64.
    let mut fb = Framebuffer::new(&mut px, 8, 1).unwrap();
    use embedded_graphics::draw_target::DrawTarget;
    fb.canvas()
        .fill_solid(
            &Rectangle::new(Point::new(i32::MAX - 1, 0), Size::new(10, 1)),
            Rgb565::new(1, 1, 1),
        )
        .unwrap();
    assert_eq!(px, [0; 8]);
}

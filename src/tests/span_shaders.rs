//! The span outputs: memory written in place and a `DrawTarget` through
//! `fill_contiguous` give the same pixels and depths, with and without a
//! depth test, whichever pixels pass it; the colour planes' pack is the
//! RGB565 rounding of SPEC.md 6 on every core's form.

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::{OriginDimensions, Pixel, Point, RawData, Size};
use proptest::prelude::*;

use crate::depth::{DepthBuffer, DepthTest, NoDepth};
use crate::planes::Planes;
use crate::span::{Flat, Gouraud, Memory, Out, TargetSink};
use crate::walk::Span;

/// A Gouraud span's start and step: depth and three channels, each inside
/// its field by the planes' margin over `n` pixels.
fn span() -> impl Strategy<Value = ([i32; 4], [i32; 4], u32)> {
    (1u32..150).prop_flat_map(|n| {
        let chan = |bits: u32| {
            let lim = (1i64 << (bits + 20)) - (1 << 19);
            (1i64 << 19..lim, 1i64 << 19..lim).prop_map(move |(a, b)| {
                let d = (b - a) / n.max(2) as i64;
                (a as i32, d as i32)
            })
        };
        (
            (0i32..1 << 28, -(1i32 << 20)..1 << 20),
            chan(5),
            chan(6),
            chan(5),
            Just(n),
        )
            .prop_map(|(z, r, g, b, n)| ([z.0, r.0, g.0, b.0], [z.1, r.1, g.1, b.1], n))
    })
}

/// The test target's width: spans cross blocks of pairs.
const W: usize = 160;

/// A `W` × 8 `DrawTarget` that refuses pixels outside it.
struct Display(Vec<u16>);

impl OriginDimensions for Display {
    fn size(&self) -> Size {
        Size::new(W as u32, 8)
    }
}

impl DrawTarget for Display {
    type Color = Rgb565;
    type Error = Point;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, pixels: I) -> Result<(), Point> {
        for Pixel(p, c) in pixels {
            let i = (0..W as i32).contains(&p.x).then_some(p.y * W as i32 + p.x);
            let v = i
                .and_then(|i| self.0.get_mut(usize::try_from(i).ok()?))
                .ok_or(p)?;
            *v = RawU16::from(c).into_inner();
        }
        Ok(())
    }
}

/// Draws span `(s, d, n)` on row 3 from column 2 of a `W` × 8 target into
/// memory and into a mock display, both with row 3's depths `stored`
/// beforehand (`None`: no depth test), and returns both targets' pixels
/// and depths.
fn both(s: [i32; 4], d: [i32; 4], n: u32, stored: Option<&[u16]>, dither: bool) -> [Vec<u16>; 4] {
    let sh = Gouraud { dither };
    // The planes at column 0 of row 0, so that the span's start is `s`.
    let planes = Planes {
        at: core::array::from_fn(|k| s[k].wrapping_sub(d[k].wrapping_mul(2))),
        gx: d,
        gy: [0; 4],
    };
    let span = Span {
        y: 3,
        x0: 2,
        n,
        dy: 0,
        planes: &planes,
    };
    let mut px = vec![0u16; W * 8];
    let (mut z1, mut z2) = (vec![0u16; W * 8], vec![0u16; W * 8]);
    let mut display = Display(vec![0u16; W * 8]);
    let mut out = Memory::new(&mut px, W as u32, 0, (0, 0));
    let mut sink = TargetSink {
        target: &mut display,
        corner: Point::zero(),
        origin: (0, 0),
    };
    let (w1, w2) = match stored {
        Some(row) => {
            let mut d1 = DepthBuffer::new(&mut z1, W as u32, 8).unwrap();
            let mut d2 = DepthBuffer::new(&mut z2, W as u32, 8).unwrap();
            d1.row(3, 0, W as u32).copy_from_slice(row);
            d2.row(3, 0, W as u32).copy_from_slice(row);
            (
                out.span(&mut d1, &span, &sh).unwrap(),
                sink.span(&mut d2, &span, &sh).unwrap(),
            )
        }
        None => (
            out.span(&mut NoDepth, &span, &sh).unwrap(),
            sink.span(&mut NoDepth, &span, &sh).unwrap(),
        ),
    };
    assert_eq!(w1, w2, "pixels written");
    [px, display.0, z1, z2]
}

proptest! {
    /// Without a depth test and through one that some pixels fail, dithered
    /// or not, both outputs write the same pixels, the same depths and the
    /// same count.
    #[test]
    fn memory_and_draw_target_agree((s, d, n) in span(), stored in prop::collection::vec(0u16..=u16::MAX, W)) {
        for dither in [false, true] {
            let [a, b, _, _] = both(s, d, n, None, dither);
            prop_assert_eq!(a, b);
            let [a, b, za, zb] = both(s, d, n, Some(&stored), dither);
            prop_assert_eq!(a, b);
            prop_assert_eq!(za, zb);
        }
    }

    /// Without a depth test, Gouraud spans go two pixels at a time in
    /// 16-bit lanes: each channel within one of its plane's `>> 20`.
    #[test]
    fn pairs_stay_within_one_of_the_planes((s, d, n) in span()) {
        let [px, _, _, _] = both(s, d, n, None, false);
        for k in 0..n as usize {
            let got = px[3 * W + 2 + k];
            let plane = |c: usize| s[c].wrapping_add(d[c].wrapping_mul(k as i32)) >> 20;
            let ch = [(got >> 11) as i32, (got >> 5 & 63) as i32, (got & 31) as i32];
            for c in 0..3 {
                prop_assert!((ch[c] - plane(c + 1)).abs() <= 1, "pixel {}: {:?} against {}", k, ch, plane(c + 1));
            }
        }
    }
}

/// The pack takes each channel's `>> 20`: every 5- and 6-bit value with
/// fractions around its edges, on the platform's form and the plain one.
#[test]
fn pack_is_the_channels_integer_parts() {
    for v in 0u32..64 {
        for f in [0u32, 1, (1 << 19) - 1, 1 << 19, (1 << 20) - 1] {
            let x = ((v << 20) + f) as i32;
            let r5 = (v & 31) << 20 | f;
            let p = crate::platform::pack_planes(r5 as i32, x, r5 as i32);
            let want = ((v & 31) << 11 | v << 5 | (v & 31)) as u16;
            assert_eq!(p, want, "{v} {f}");
        }
    }
}

/// The example from the docs of `NoDepth`: a later, farther span is drawn
/// over a nearer one.
#[test]
fn no_depth_draws_later_over_earlier() {
    assert!(!NoDepth::ENABLED && NoDepth.row(0, 0, 8).is_empty());
    let mut px = [0u16; 4];
    let mut out = Memory::new(&mut px, 4, 0, (0, 0));
    for (c, z) in [(1, 0), (2, 1 << 28)] {
        let sh = Flat {
            plain: c,
            shade: Default::default(),
            dither: false,
        };
        let planes = Planes {
            at: [z],
            gx: [0],
            gy: [0],
        };
        let span = Span {
            y: 0,
            x0: 0,
            n: 4,
            dy: 0,
            planes: &planes,
        };
        out.span(&mut NoDepth, &span, &sh).unwrap();
    }
    assert_eq!(px, [2; 4]); // the later, farther span is drawn over the nearer
}

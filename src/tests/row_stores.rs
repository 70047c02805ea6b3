//! The stores a draw's rows are handed to directly (`Out::fit_rows`,
//! `Out::row_stores`): found only where every pixel of the draw's rect
//! lies in both stores, laid out alike, and pointing at each row's
//! column 0 there.

use crate::depth::{DepthBand, DepthBuffer, DepthTest, NoDepth};
use crate::setup::Rect;
use crate::shade::rect_of;
use crate::span::{Memory, Out};

const W: u32 = 40;
const H: u32 = 30;

/// Row `y`'s column 0 (from the origin) in a store whose first row is
/// target row `y0`, origin `o`.
fn index(y: i32, y0: u32, o: (i32, i32)) -> isize {
    ((y + o.1 - y0 as i32) * W as i32 + o.0) as isize
}

/// Every row of `rect` handed out, each at its index in both stores.
fn all_rows_at<D: DepthTest>(
    out: &mut Memory,
    depth: &mut D,
    rect: &Rect,
    y0: u32,
    o: (i32, i32),
    c: *const u16,
    z: *const u16,
) {
    for y in rect.r0..=rect.r1 {
        let s = out.row_stores(depth, y).expect("a fitted row");
        assert_eq!(s.stride, 2 * W);
        assert_eq!(s.colour.cast_const(), c.wrapping_offset(index(y, y0, o)));
        assert_eq!(s.depth.cast_const(), z.wrapping_offset(index(y, y0, o)));
        // Its first and last columns inside both stores.
        let (first, last) = (
            index(y, y0, o) + rect.c0 as isize,
            index(y, y0, o) + rect.c1 as isize,
        );
        assert!(first >= 0 && last < (W * H) as isize);
    }
}

#[test]
fn a_whole_frame_fits() {
    let (o, rect) = rect_of((W, H));
    let (mut colour, mut z) = (vec![0u16; (W * H) as usize], vec![0u16; (W * H) as usize]);
    let (c, zp) = (colour.as_ptr(), z.as_ptr());
    let mut depth = DepthBuffer::new(&mut z, W, H).unwrap();
    let mut out = Memory::new(&mut colour, W, 0, o);
    assert!(out.row_stores(&mut depth, 0).is_none()); // not asked yet
    out.fit_rows(&mut depth, &rect);
    all_rows_at(&mut out, &mut depth, &rect, 0, o, c, zp);
    // Moved (a big target's tile): no longer.
    out.moved((3, 0));
    assert!(out.row_stores(&mut depth, 0).is_none());
    out.moved((-3, 0));
    assert!(out.row_stores(&mut depth, 0).is_some());
}

#[test]
fn stores_that_miss_a_pixel_do_not_fit() {
    let (o, rect) = rect_of((W, H));
    let mut colour = vec![0u16; (W * H) as usize];
    // A depth store a row short, then one as long but of another width.
    let mut short = vec![0u16; (W * (H - 1)) as usize];
    let mut depth = DepthBuffer::new(&mut short, W, H - 1).unwrap();
    let mut out = Memory::new(&mut colour, W, 0, o);
    out.fit_rows(&mut depth, &rect);
    assert!(out.row_stores(&mut depth, 0).is_none());
    let mut other = vec![0u16; (W * H) as usize];
    let mut depth = DepthBuffer::new(&mut other, H, W).unwrap();
    out.fit_rows(&mut depth, &rect);
    assert!(out.row_stores(&mut depth, 0).is_none());
    // A colour store a pixel short.
    let mut z = vec![0u16; (W * H) as usize];
    let mut depth = DepthBuffer::new(&mut z, W, H).unwrap();
    let mut out = Memory::new(&mut colour[1..], W, 0, o);
    out.fit_rows(&mut depth, &rect);
    assert!(out.row_stores(&mut depth, 0).is_none());
    // No depth test: nothing to hand out.
    let mut out = Memory::new(&mut colour, W, 0, o);
    out.fit_rows(&mut NoDepth, &rect);
    assert!(out.row_stores(&mut NoDepth, 0).is_none());
}

#[test]
fn a_band_fits_its_rows_only() {
    let (o, whole) = rect_of((W, H));
    let (y0, rows) = (12u32, 4u32);
    let mut colour = vec![0u16; (W * rows) as usize];
    let mut storage = vec![0u16; (W * rows) as usize];
    let (c, zp) = (colour.as_ptr(), storage.as_ptr());
    let mut depth = DepthBand::new(&mut storage);
    assert!(depth.start(W, y0, rows));
    let band = Rect {
        r0: y0 as i32 - o.1,
        r1: (y0 + rows) as i32 - 1 - o.1,
        ..whole
    };
    let mut out = Memory::new(&mut colour, W, y0, o);
    out.fit_rows(&mut depth, &band);
    for y in band.r0..=band.r1 {
        let s = out.row_stores(&mut depth, y).expect("a fitted row");
        assert_eq!(s.colour.cast_const(), c.wrapping_offset(index(y, y0, o)));
        assert_eq!(s.depth.cast_const(), zp.wrapping_offset(index(y, y0, o)));
    }
    // The whole frame's rect does not fit a band.
    out.fit_rows(&mut depth, &whole);
    assert!(out.row_stores(&mut depth, band.r0).is_none());
    // Nor a band rect a row longer, below or above (above, the row's
    // index wraps below the store's start: their distance tells).
    let longer = Rect {
        r1: band.r1 + 1,
        ..band
    };
    out.fit_rows(&mut depth, &longer);
    assert!(out.row_stores(&mut depth, band.r0).is_none());
    let higher = Rect {
        r0: band.r0 - 1,
        ..band
    };
    out.fit_rows(&mut depth, &higher);
    assert!(out.row_stores(&mut depth, band.r0).is_none());
}

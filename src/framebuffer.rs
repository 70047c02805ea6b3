//! A plain RGB565 framebuffer, which the renderer writes in place (an
//! output of [`Shaded::draw`](crate::Shaded::draw)) and which
//! [`Framebuffer::canvas`] makes an `embedded-graphics` `DrawTarget`, with
//! fast `fill_contiguous` and `fill_solid`: the host's and the emulated
//! firmware's target, and a model for a display driver's buffer.

use core::convert::Infallible;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{OriginDimensions, Size};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::RawData;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;

/// Why a framebuffer could not be made.
///
/// ```
/// use fixshade::framebuffer::{Framebuffer, FramebufferTooSmall};
/// let err = Framebuffer::new(&mut [0u16; 15], 8, 2).unwrap_err();
/// assert_eq!(err, FramebufferTooSmall);
/// assert_eq!(format!("{err}"), "framebuffer shorter than width × height");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FramebufferTooSmall;

impl core::fmt::Display for FramebufferTooSmall {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("framebuffer shorter than width × height")
    }
}

/// `width × height` raw RGB565 pixels (`u16`), row-major, borrowed.
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use fixshade::framebuffer::Framebuffer;
/// let mut px = [0u16; 8 * 2];
/// let mut fb = Framebuffer::new(&mut px, 8, 2).unwrap();
/// fb.clear(Rgb565::RED);
/// assert_eq!(fb.pixel(7, 1), Some(Rgb565::RED));
/// ```
#[derive(Debug, PartialEq, Eq)]
pub struct Framebuffer<'a> {
    buf: &'a mut [u16],
    width: u32,
    height: u32,
}

impl<'a> Framebuffer<'a> {
    /// Wraps `buf`, which must hold at least `width · height` pixels.
    ///
    /// ```
    /// use embedded_graphics::prelude::*;
    /// use fixshade::framebuffer::Framebuffer;
    /// let mut px = [0u16; 20];
    /// assert!(Framebuffer::new(&mut px[..15], 8, 2).is_err());
    /// let fb = Framebuffer::new(&mut px, 8, 2).unwrap(); // longer is fine
    /// assert_eq!(fb.size(), Size::new(8, 2));
    /// assert!(Framebuffer::new(&mut px, 1 << 16, 1 << 16).is_err()); // 2³², not 0
    /// ```
    pub fn new(buf: &'a mut [u16], width: u32, height: u32) -> Result<Self, FramebufferTooSmall> {
        if (buf.len() as u64) < width as u64 * height as u64 {
            return Err(FramebufferTooSmall);
        }
        Ok(Framebuffer { buf, width, height })
    }

    /// The raw pixels, row-major.
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
    /// use fixshade::framebuffer::Framebuffer;
    /// let mut px = [0u16; 3 * 2 + 1];
    /// let mut fb = Framebuffer::new(&mut px, 3, 2).unwrap();
    /// Pixel(Point::new(2, 1), Rgb565::WHITE).draw(&mut fb.canvas()).unwrap();
    /// assert_eq!(fb.as_slice(), &[0, 0, 0, 0, 0, 0xFFFF]); // (2, 1) at 1 · 3 + 2
    /// ```
    pub fn as_slice(&self) -> &[u16] {
        &self.buf[..(self.width as usize) * (self.height as usize)]
    }

    /// The pixel at `(x, y)`, or `None` outside.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb565;
    /// use fixshade::framebuffer::Framebuffer;
    /// let mut px = [0u16; 4 * 2];
    /// px[5] = 0b00001_000010_00011; // raw RGB565 at (1, 1)
    /// let fb = Framebuffer::new(&mut px, 4, 2).unwrap();
    /// assert_eq!(fb.pixel(1, 1), Some(Rgb565::new(1, 2, 3)));
    /// assert_eq!(fb.pixel(4, 0), None);
    /// assert_eq!(fb.pixel(0, 2), None);
    /// ```
    pub fn pixel(&self, x: u32, y: u32) -> Option<Rgb565> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let raw = self.buf[y as usize * self.width as usize + x as usize];
        Some(Rgb565::from(RawU16::new(raw)))
    }

    /// Row `y` from column `x0`, `n` pixels, if all of it is inside.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    /// use fixshade::framebuffer::Framebuffer;
    /// let mut px = [0u16; 4 * 2];
    /// let mut fb = Framebuffer::new(&mut px, 4, 2).unwrap();
    /// fb.row_mut(1, 2, 2).unwrap().fill(0xFFFF);
    /// assert_eq!(fb.pixel(3, 1), Some(Rgb565::WHITE));
    /// assert!(fb.row_mut(1, 2, 3).is_none()); // one pixel past the edge: none of it
    /// assert!(fb.row_mut(2, 0, 1).is_none());
    /// ```
    #[inline]
    pub fn row_mut(&mut self, y: u32, x0: u32, n: usize) -> Option<&mut [u16]> {
        // `x0 + n ≤ width` without the sum, which may wrap `usize` (a
        // negative column cast to `u32` on a 32-bit target).
        if y >= self.height || x0 > self.width || n > (self.width - x0) as usize {
            return None;
        }
        let start = y as usize * self.width as usize + x0 as usize;
        self.buf.get_mut(start..start + n)
    }

    /// The pixels and the row length, for the renderer's spans.
    #[inline(always)]
    pub(crate) fn parts(&mut self) -> (&mut [u16], u32) {
        (self.buf, self.width)
    }

    /// The part of `area` inside the buffer, as (x0, y0, width, height).
    /// In `i64`: an area may reach past `i32::MAX` (its corner plus its
    /// size), where `embedded-graphics`' own rectangle arithmetic overflows.
    fn clip(&self, area: &Rectangle) -> Option<(usize, usize, usize, usize)> {
        let span = |at: i32, len: u32, max: u32| {
            let lo = (at as i64).max(0);
            let hi = (at as i64 + len as i64).min(max as i64);
            (lo < hi).then_some((lo as usize, (hi - lo) as usize))
        };
        let (x0, w) = span(area.top_left.x, area.size.width, self.width)?;
        let (y0, h) = span(area.top_left.y, area.size.height, self.height)?;
        Some((x0, y0, w, h))
    }
}

impl OriginDimensions for Framebuffer<'_> {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

fn raw(c: Rgb565) -> u16 {
    RawU16::from(c).into_inner()
}

/// The framebuffer as an `embedded-graphics` `DrawTarget`
/// ([`Framebuffer::canvas`]): text, primitives and images drawn over or
/// under a rendered frame.
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::{PrimitiveStyle, Rectangle}};
/// use fixshade::framebuffer::Framebuffer;
/// let mut px = [0u16; 8 * 4];
/// let mut fb = Framebuffer::new(&mut px, 8, 4).unwrap();
/// Rectangle::new(Point::new(2, 1), Size::new(3, 2))
///     .into_styled(PrimitiveStyle::with_fill(Rgb565::GREEN))
///     .draw(&mut fb.canvas())
///     .unwrap();
/// assert_eq!(fb.pixel(4, 2), Some(Rgb565::GREEN));
/// assert_eq!(fb.pixel(5, 2), Some(Rgb565::BLACK));
/// ```
#[derive(Debug)]
pub struct Canvas<'f, 'a>(&'f mut Framebuffer<'a>);

impl OriginDimensions for Canvas<'_, '_> {
    fn size(&self) -> Size {
        self.0.size()
    }
}

impl DrawTarget for Canvas<'_, '_> {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb565>>,
    {
        self.0.put_iter(pixels);
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Rgb565>,
    {
        self.0.put_contiguous(area, colors);
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Rgb565) -> Result<(), Infallible> {
        self.0.put_solid(area, color);
        Ok(())
    }

    fn clear(&mut self, color: Rgb565) -> Result<(), Infallible> {
        self.0.clear(color);
        Ok(())
    }
}

impl<'a> Framebuffer<'a> {
    /// The framebuffer as a `DrawTarget`, for drawing other things into it.
    pub fn canvas(&mut self) -> Canvas<'_, 'a> {
        Canvas(self)
    }

    /// Fills every pixel with `color`.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    /// use fixshade::framebuffer::Framebuffer;
    /// let mut px = [0u16; 6];
    /// let mut fb = Framebuffer::new(&mut px, 3, 2).unwrap();
    /// fb.clear(Rgb565::BLUE);
    /// assert_eq!(fb.pixel(2, 1), Some(Rgb565::BLUE));
    /// ```
    pub fn clear(&mut self, color: Rgb565) {
        let n = (self.width as usize) * (self.height as usize);
        self.buf[..n].fill(raw(color));
    }

    fn put_iter<I>(&mut self, pixels: I)
    where
        I: IntoIterator<Item = Pixel<Rgb565>>,
    {
        for Pixel(p, c) in pixels {
            if p.x >= 0 && p.y >= 0 && (p.x as u32) < self.width && (p.y as u32) < self.height {
                self.buf[p.y as usize * self.width as usize + p.x as usize] = raw(c);
            }
        }
    }

    fn put_contiguous<I>(&mut self, area: &Rectangle, colors: I)
    where
        I: IntoIterator<Item = Rgb565>,
    {
        let full = area.size.width as usize;
        match self.clip(area) {
            // Fast path: the whole area is inside; copy row by row, or as
            // one run for whole rows.
            Some((x0, y0, w, h))
                if w == full
                    && h == area.size.height as usize
                    && x0 as i32 == area.top_left.x
                    && y0 as i32 == area.top_left.y =>
            {
                let mut it = colors.into_iter();
                let width = self.width as usize;
                if w == width {
                    // Whole rows (a band): one run of the buffer, so one
                    // loop, whose vector body leaves a scalar tail once
                    // instead of once per row (callgrind, S1 in 16-row
                    // bands on x86-64: 40.7 k instructions a frame fewer).
                    let run = &mut self.buf[y0 * width..][..h * width];
                    for (d, c) in run.iter_mut().zip(it) {
                        *d = raw(c);
                    }
                    return;
                }
                for y in y0..y0 + h {
                    let row = &mut self.buf[y * width + x0..][..w];
                    for (d, c) in row.iter_mut().zip(&mut it) {
                        *d = raw(c);
                    }
                }
            }
            Some((x0, y0, w, h)) => {
                // Partly inside: the colours run row-major over the whole
                // area; those of the clipped part are written (coordinates
                // in `i64`, see `clip`).
                let (ax, ay) = (area.top_left.x as i64, area.top_left.y as i64);
                let mut it = colors.into_iter();
                for y in ay..ay + area.size.height as i64 {
                    let mut row = it.by_ref().take(full);
                    if y < y0 as i64 || y >= (y0 + h) as i64 {
                        if row.count() < full {
                            break;
                        }
                        continue;
                    }
                    let skip = (x0 as i64 - ax) as usize;
                    let out = &mut self.buf[y as usize * self.width as usize + x0..][..w];
                    let mut inside = row.by_ref().skip(skip);
                    for d in out.iter_mut() {
                        match inside.next() {
                            Some(c) => *d = raw(c),
                            None => return,
                        }
                    }
                    if skip + w + inside.count() < full {
                        break;
                    }
                }
            }
            None => {}
        }
    }

    fn put_solid(&mut self, area: &Rectangle, color: Rgb565) {
        if let Some((x0, y0, w, h)) = self.clip(area) {
            let v = raw(color);
            for y in y0..y0 + h {
                self.buf[y * self.width as usize + x0..][..w].fill(v);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Framebuffer;
    use crate::tests::xorshift;
    use embedded_graphics::draw_target::DrawTarget;
    use embedded_graphics::pixelcolor::raw::RawU16;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::prelude::{Point, Size};
    use embedded_graphics::primitives::Rectangle;

    /// What `fill_contiguous` must do: the `k`-th colour goes to the `k`-th
    /// point of the area (row-major) if that point is inside.
    fn model(px: &mut [u16], w: i64, h: i64, area: &Rectangle, colours: &[u16]) {
        let (ax, ay) = (area.top_left.x as i64, area.top_left.y as i64);
        let aw = area.size.width as i64;
        for (k, &c) in colours.iter().enumerate() {
            if aw == 0 || k as i64 >= aw * area.size.height as i64 {
                break;
            }
            let (x, y) = (ax + k as i64 % aw, ay + k as i64 / aw);
            if (0..w).contains(&x) && (0..h).contains(&y) {
                px[(y * w + x) as usize] = c;
            }
        }
    }

    /// Areas inside (whole rows among them), partly outside on every side,
    /// wholly outside, empty, with colours that run out early, and areas
    /// whose far corner lies past `i32::MAX` (where `embedded-graphics`'
    /// rectangle arithmetic overflows): the model's pixels, and no panic in
    /// a debug build.
    #[test]
    fn fill_contiguous_clips_like_the_model() {
        let mut rnd = xorshift(0x00F1_11C0_0171_6005);
        let (w, h) = (16u32, 8u32);
        let far = [i32::MIN, i32::MIN + 3, i32::MAX - 3, i32::MAX];
        for case in 0..20_000 {
            let mut coord = |lim: i64| {
                if case % 10 == 0 {
                    far[(rnd() % 4) as usize]
                } else {
                    (rnd() % (2 * lim as u64 + 40)) as i32 - 20
                }
            };
            let (x, y) = (coord(w as i64), coord(h as i64));
            let size = Size::new((rnd() % 40) as u32, (rnd() % 20) as u32);
            let area = if case % 7 == 3 {
                // Whole rows inside (a band): the one-run path.
                let y = (rnd() % h as u64) as u32;
                let rows = (rnd() % (h - y + 1) as u64) as u32;
                Rectangle::new(Point::new(0, y as i32), Size::new(w, rows))
            } else {
                Rectangle::new(Point::new(x, y), size)
            };
            let size = area.size;
            let n = (size.width * size.height) as u64;
            let count = if rnd().is_multiple_of(4) {
                rnd() % (n + 1)
            } else {
                n
            } as usize;
            let colours: Vec<u16> = (0..count).map(|_| rnd() as u16).collect();
            let (mut got, mut want) = ([0u16; 128], [0u16; 128]);
            let mut fb = Framebuffer::new(&mut got, w, h).unwrap();
            fb.canvas()
                .fill_contiguous(&area, colours.iter().map(|&c| Rgb565::from(RawU16::new(c))))
                .unwrap();
            model(&mut want, w as i64, h as i64, &area, &colours);
            assert_eq!(got, want, "{area:?}, {count} colours");
            // fill_solid: the clipped part, one colour.
            let mut fb = Framebuffer::new(&mut got, w, h).unwrap();
            fb.canvas()
                .fill_solid(&area, Rgb565::from(RawU16::new(0xABCD)))
                .unwrap();
            let all = vec![0xABCD; n as usize];
            model(&mut want, w as i64, h as i64, &area, &all);
            assert_eq!(got, want, "{area:?} solid");
        }
    }

    /// `row_mut` rejects a row that does not fit, however large `n` is.
    #[test]
    fn row_mut_rejects_what_does_not_fit() {
        let mut px = [0u16; 8];
        let mut fb = Framebuffer::new(&mut px, 8, 1).unwrap();
        assert_eq!(fb.row_mut(0, 1, 7).map(|r| r.len()), Some(7));
        assert!(fb.row_mut(0, 1, 8).is_none());
        assert!(fb.row_mut(0, 1, usize::MAX).is_none());
        assert!(fb.row_mut(0, u32::MAX, 2).is_none());
        assert!(fb.row_mut(1, 0, 1).is_none());
        assert_eq!(fb.row_mut(0, 8, 0).map(|r| r.len()), Some(0));
    }
}

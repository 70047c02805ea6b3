//! A plain RGB565 framebuffer that is an `embedded-graphics` `DrawTarget`,
//! with fast `fill_contiguous` and `fill_solid`: the host's and the
//! emulated firmware's target, and a model for a display driver's buffer.

use core::convert::Infallible;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::Dimensions;
use embedded_graphics::geometry::{OriginDimensions, Size};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::RawData;
use embedded_graphics::primitives::{PointsIter, Rectangle};
use embedded_graphics::Pixel;

/// Why a framebuffer could not be made.
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
/// fb.clear(Rgb565::RED).unwrap();
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
    pub fn new(buf: &'a mut [u16], width: u32, height: u32) -> Result<Self, FramebufferTooSmall> {
        if (buf.len() as u64) < width as u64 * height as u64 {
            return Err(FramebufferTooSmall);
        }
        Ok(Framebuffer { buf, width, height })
    }

    /// The raw pixels, row-major.
    pub fn as_slice(&self) -> &[u16] {
        &self.buf[..(self.width as usize) * (self.height as usize)]
    }

    /// The pixel at `(x, y)`, or `None` outside.
    pub fn pixel(&self, x: u32, y: u32) -> Option<Rgb565> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let raw = self.buf[y as usize * self.width as usize + x as usize];
        Some(Rgb565::from(RawU16::new(raw)))
    }

    /// Row `y` from column `x0`, `n` pixels, if all of it is inside.
    #[inline]
    pub fn row_mut(&mut self, y: u32, x0: u32, n: usize) -> Option<&mut [u16]> {
        if y >= self.height || x0 as usize + n > self.width as usize {
            return None;
        }
        let start = y as usize * self.width as usize + x0 as usize;
        self.buf.get_mut(start..start + n)
    }

    /// The part of `area` inside the buffer, as (x0, y0, width, height).
    fn clip(&self, area: &Rectangle) -> Option<(usize, usize, usize, usize)> {
        let a = area.intersection(&self.bounding_box());
        if a.size.width == 0 || a.size.height == 0 {
            return None;
        }
        Some((
            a.top_left.x as usize,
            a.top_left.y as usize,
            a.size.width as usize,
            a.size.height as usize,
        ))
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

impl DrawTarget for Framebuffer<'_> {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb565>>,
    {
        for Pixel(p, c) in pixels {
            if p.x >= 0 && p.y >= 0 && (p.x as u32) < self.width && (p.y as u32) < self.height {
                self.buf[p.y as usize * self.width as usize + p.x as usize] = raw(c);
            }
        }
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Rgb565>,
    {
        let full = area.size.width as usize;
        match self.clip(area) {
            // Fast path: the whole area is inside; copy row by row.
            Some((x0, y0, w, h))
                if w == full
                    && h == area.size.height as usize
                    && x0 as i32 == area.top_left.x
                    && y0 as i32 == area.top_left.y =>
            {
                let mut it = colors.into_iter();
                for y in y0..y0 + h {
                    let row = &mut self.buf[y * self.width as usize + x0..][..w];
                    for (d, c) in row.iter_mut().zip(&mut it) {
                        *d = raw(c);
                    }
                }
                Ok(())
            }
            _ => self.draw_iter(area.points().zip(colors).map(|(p, c)| Pixel(p, c))),
        }
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Rgb565) -> Result<(), Infallible> {
        if let Some((x0, y0, w, h)) = self.clip(area) {
            let v = raw(color);
            for y in y0..y0 + h {
                self.buf[y * self.width as usize + x0..][..w].fill(v);
            }
        }
        Ok(())
    }

    fn clear(&mut self, color: Rgb565) -> Result<(), Infallible> {
        let n = (self.width as usize) * (self.height as usize);
        self.buf[..n].fill(raw(color));
        Ok(())
    }
}

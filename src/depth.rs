//! The optional depth buffer, in storage the caller provides.
//!
//! Depth is `z_w` (SPEC.md 1) quantised to `u16` as SPEC.md 5 states:
//! `d = ⌊z_w · 65535 + ½⌋` (clamped to 0 ..= 65535), cleared to 65535
//! (`z_w = 1`); a pixel is drawn where its `d` is less than the stored one,
//! and then stored. The renderer interpolates the attribute
//! `z_w · 65535 · 2⁸ + 2⁷` and takes `d` as its `>> 8` (the `2⁷` is the
//! half of the rounding), so the per-pixel work is one shift. A scene that
//! needs no depth test uses [`NoDepth`], which has no storage and whose
//! test the compiler removes.

/// A depth test: [`NoDepth`] or [`DepthBuffer`].
///
/// ```
/// use fixshade::depth::{DepthBuffer, DepthTest};
/// let mut storage = [0u16; 4 * 3];
/// let mut depth = DepthBuffer::new(&mut storage, 4, 3).unwrap();
/// assert!(DepthBuffer::ENABLED);
/// depth.row(1, 1, 2).fill(9);
/// assert_eq!(depth.row(1, 2, 10).len(), 2); // cut at the right edge
/// assert!(depth.row(3, 0, 1).is_empty()); // below the buffer
/// assert_eq!(depth.as_slice()[4..8], [u16::MAX, 9, 9, u16::MAX]); // new: all far
/// ```
pub trait DepthTest {
    /// Whether there is a test at all.
    const ENABLED: bool;
    /// The stored depths of row `y` from column `x0`, `len` of them, or an
    /// empty slice for [`NoDepth`].
    fn row(&mut self, y: u32, x0: u32, len: u32) -> &mut [u16];
    /// The storage as rows of a width from a first row, if it is laid out
    /// so (the renderer's spans then index it as they index the colour).
    #[doc(hidden)]
    #[inline(always)]
    fn flat(&mut self) -> Option<(&mut [u16], u32, u32)> {
        None
    }
}

impl<Z: DepthTest> DepthTest for &mut Z {
    const ENABLED: bool = Z::ENABLED;
    #[inline(always)]
    fn row(&mut self, y: u32, x0: u32, len: u32) -> &mut [u16] {
        (**self).row(y, x0, len)
    }
    #[inline(always)]
    fn flat(&mut self) -> Option<(&mut [u16], u32, u32)> {
        (**self).flat()
    }
}

/// No depth test: every pixel is drawn, later triangles over earlier ones.
///
/// ```
/// use fixshade::depth::{DepthTest, NoDepth};
/// assert!(!NoDepth::ENABLED && NoDepth.row(0, 0, 8).is_empty());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct NoDepth;

impl DepthTest for NoDepth {
    const ENABLED: bool = false;
    #[inline(always)]
    fn row(&mut self, _: u32, _: u32, _: u32) -> &mut [u16] {
        &mut []
    }
}

/// Why a depth buffer could not be made.
///
/// ```
/// use fixshade::depth::{DepthBuffer, DepthBufferTooSmall};
/// let err = DepthBuffer::new(&mut [0u16; 11], 4, 3).unwrap_err();
/// assert_eq!(err, DepthBufferTooSmall);
/// assert_eq!(format!("{err}"), "depth buffer shorter than width × height");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DepthBufferTooSmall;

impl core::fmt::Display for DepthBufferTooSmall {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("depth buffer shorter than width × height")
    }
}

/// A depth buffer of `width × height` `u16`s, row-major, borrowed.
///
/// ```
/// use fixshade::depth::DepthBuffer;
/// let mut storage = [0u16; 4 * 3];
/// let mut depth = DepthBuffer::new(&mut storage, 4, 3).unwrap();
/// depth.clear();
/// assert_eq!((depth.width(), depth.height()), (4, 3));
/// assert!(DepthBuffer::new(&mut [0u16; 5], 4, 3).is_err());
/// ```
#[derive(Debug, PartialEq, Eq)]
pub struct DepthBuffer<'a> {
    buf: &'a mut [u16],
    width: u32,
    height: u32,
}

impl<'a> DepthBuffer<'a> {
    /// Wraps `buf`, which must hold at least `width · height` values, and
    /// clears them to the far value: ready for a frame as made.
    ///
    /// ```
    /// use fixshade::depth::DepthBuffer;
    /// let mut storage = [0u16; 16];
    /// let z = DepthBuffer::new(&mut storage, 4, 3).unwrap();
    /// assert!(z.as_slice().iter().all(|&d| d == u16::MAX));
    /// assert!(DepthBuffer::new(&mut storage[..11], 4, 3).is_err());
    /// assert!(DepthBuffer::new(&mut storage[..12], 4, 3).is_ok());
    /// // Longer storage is fine; only the first width · height values are used.
    /// assert_eq!(DepthBuffer::new(&mut storage, 4, 3).unwrap().as_slice().len(), 12);
    /// // A product past u32 is still refused, not wrapped.
    /// assert!(DepthBuffer::new(&mut storage, 1 << 16, 1 << 16).is_err());
    /// ```
    pub fn new(buf: &'a mut [u16], width: u32, height: u32) -> Result<Self, DepthBufferTooSmall> {
        let need = width as u64 * height as u64;
        if (buf.len() as u64) < need {
            return Err(DepthBufferTooSmall);
        }
        let mut z = DepthBuffer { buf, width, height };
        z.clear();
        Ok(z)
    }

    /// Sets every depth to the far value (65535): before each frame.
    ///
    /// ```
    /// use fixshade::depth::{DepthBuffer, DepthTest};
    /// let mut storage = [0u16; 4 * 3 + 2];
    /// let mut depth = DepthBuffer::new(&mut storage, 4, 3).unwrap();
    /// depth.row(1, 0, 4).fill(7); // a frame's depths
    /// depth.clear();
    /// assert!(storage[..12].iter().all(|&z| z == u16::MAX));
    /// assert_eq!(storage[12..], [0, 0]); // past width × height: untouched
    /// ```
    pub fn clear(&mut self) {
        let n = (self.width as usize) * (self.height as usize);
        fill_far(&mut self.buf[..n]);
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The stored depths, row-major.
    ///
    /// ```
    /// use fixshade::depth::{DepthBuffer, DepthTest};
    /// let mut storage = [0u16; 3 * 2];
    /// let mut depth = DepthBuffer::new(&mut storage, 3, 2).unwrap();
    /// depth.clear();
    /// depth.row(1, 2, 1)[0] = 5; // (x, y) = (2, 1) is at 1 · 3 + 2
    /// assert_eq!(depth.as_slice(), &[u16::MAX, u16::MAX, u16::MAX, u16::MAX, u16::MAX, 5]);
    /// ```
    pub fn as_slice(&self) -> &[u16] {
        &self.buf[..(self.width as usize) * (self.height as usize)]
    }
}

impl DepthTest for DepthBuffer<'_> {
    const ENABLED: bool = true;
    /// Out-of-range requests give the part that exists (possibly empty);
    /// the renderer only asks for rows and columns inside the target, which
    /// it checks against the buffer's size before drawing.
    #[inline]
    fn row(&mut self, y: u32, x0: u32, len: u32) -> &mut [u16] {
        if y >= self.height || x0 >= self.width {
            return &mut [];
        }
        let start = y as usize * self.width as usize + x0 as usize;
        let len = len.min(self.width - x0) as usize;
        &mut self.buf[start..start + len]
    }
    #[inline(always)]
    fn flat(&mut self) -> Option<(&mut [u16], u32, u32)> {
        Some((&mut *self.buf, self.width, 0))
    }
}

/// A depth band: the depths of `rows` rows of a `width`-pixel-wide
/// viewport starting at row `y0`, in storage the caller provides (at least
/// `width × rows` values). A draw into [`Bands`](crate::band::Bands)
/// with it ([`Shaded::with_depth`](crate::Shaded::with_depth)) moves it
/// down the frame and clears it for each band.
///
/// ```
/// use fixshade::depth::{DepthBand, DepthTest};
/// let mut storage = [0u16; 4 * 2];
/// let mut band = DepthBand::new(&mut storage);
/// assert!(band.start(4, 6, 2)); // rows 6 and 7 of a 4-pixel-wide frame
/// assert_eq!(band.row(7, 1, 3), &[u16::MAX; 3]);
/// assert!(band.row(5, 0, 1).is_empty()); // outside the band
/// assert!(!band.start(4, 0, 3)); // 12 values do not fit in 8
/// ```
#[derive(Debug, PartialEq, Eq)]
pub struct DepthBand<'a> {
    buf: &'a mut [u16],
    width: u32,
    y0: u32,
    rows: u32,
}

impl<'a> DepthBand<'a> {
    /// Wraps `buf` (any length; [`DepthBand::start`] checks it).
    ///
    /// ```
    /// use fixshade::depth::{DepthBand, DepthTest};
    /// let mut band = DepthBand::new(&mut []);
    /// assert!(band.row(0, 0, 1).is_empty()); // no band until started
    /// assert!(band.start(0, 0, 16)); // an empty band fits
    /// assert!(!band.start(1, 0, 1));
    /// ```
    pub fn new(buf: &'a mut [u16]) -> Self {
        DepthBand {
            buf,
            width: 0,
            y0: 0,
            rows: 0,
        }
    }

    /// Makes this the band of rows `y0 .. y0 + rows` of a `width`-wide
    /// viewport and clears it to the far value. `false` (and an empty band)
    /// if the storage is shorter than `width × rows`.
    ///
    /// ```
    /// use fixshade::depth::{DepthBand, DepthTest};
    /// let mut storage = [0u16; 8];
    /// let mut band = DepthBand::new(&mut storage);
    /// assert!(band.start(4, 0, 2));
    /// band.row(1, 0, 4).fill(3);
    /// assert!(band.start(4, 2, 2)); // the next band, cleared
    /// assert_eq!(band.row(3, 0, 4), &[u16::MAX; 4]);
    /// assert!(!band.start(4, 4, 3));
    /// assert!(band.row(4, 0, 4).is_empty()); // refused: an empty band
    /// ```
    pub fn start(&mut self, width: u32, y0: u32, rows: u32) -> bool {
        let need = width as u64 * rows as u64;
        if (self.buf.len() as u64) < need {
            self.rows = 0;
            return false;
        }
        fill_far(&mut self.buf[..need as usize]);
        self.width = width;
        self.y0 = y0;
        self.rows = rows;
        true
    }

    /// The storage's length in values.
    ///
    /// ```
    /// use fixshade::depth::DepthBand;
    /// let mut storage = [0u16; 10];
    /// let mut band = DepthBand::new(&mut storage);
    /// assert!(band.start(2, 0, 3));
    /// assert_eq!(band.capacity(), 10); // the storage's, not the band's 6
    /// ```
    pub fn capacity(&self) -> usize {
        self.buf.len()
    }
}

/// Sets every depth of `buf` to the far value (65535).
#[inline]
fn fill_far(buf: &mut [u16]) {
    buf.fill(u16::MAX);
}

impl DepthTest for DepthBand<'_> {
    const ENABLED: bool = true;
    /// Rows outside the band, and columns outside the viewport, give the
    /// part that exists (possibly empty).
    #[inline]
    fn row(&mut self, y: u32, x0: u32, len: u32) -> &mut [u16] {
        let r = y.wrapping_sub(self.y0);
        if r >= self.rows || x0 >= self.width {
            return &mut [];
        }
        let start = r as usize * self.width as usize + x0 as usize;
        let len = len.min(self.width - x0) as usize;
        &mut self.buf[start..start + len]
    }
    #[inline(always)]
    fn flat(&mut self) -> Option<(&mut [u16], u32, u32)> {
        let n = self.width as usize * self.rows as usize;
        Some((self.buf.get_mut(..n)?, self.width, self.y0))
    }
}

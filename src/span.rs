//! Span shading and output: where a span's pixels go ([`PixelSink`]) and
//! how their colours are made ([`SpanShader`]), with the depth test between.
//!
//! Two sinks: any `DrawTarget` (one `fill_contiguous` per span, or per run
//! of pixels that pass the depth test), and a [`Framebuffer`] written in
//! place (the fast path: no per-span call, no bounds arithmetic).
//!
//! # Gouraud spans
//! A span of at least [`crate::render::PAIR_SPAN`] pixels is coloured two
//! pixels at a time by [`PairGouraud`]; a shorter one a pixel at a time by
//! [`PackedGouraud`]. Which one depends on the span's length only, so the
//! same span always gets the same pixels (band and whole-frame renders
//! agree, and so do the host and the Cortex-M builds).
//!
//! [`PackedGouraud`] steps the three channels together in one `u64`: red in
//! bits 43–63, green in bits 21–42, blue in bits 0–20, each with 16
//! fractional bits below its 5- or 6-bit RGB565 value and a bias of ½ (so
//! truncation is the rounding of SPEC.md 6). One wrapping add steps all
//! three: the packed value is `Σ vᵢ·2^offᵢ` with every `vᵢ` inside its
//! field at every pixel of the span (checked at the span's two ends; values
//! are linear in between), so modular addition of the packed step gives
//! exactly the packed values. The pixel gathers the three integer parts:
//! on 64-bit targets `((acc & MASK) · (1 + 2¹⁶ + 2³²)) >> 48` (an and, a
//! multiply and a shift; the six shifted fields are disjoint, so nothing
//! carries), elsewhere from the accumulator's two 32-bit halves with three
//! masks, two shifts and two ors (a 64-bit multiply is a library call on a
//! Cortex-M0).
//!
//! [`PairGouraud`] keeps each channel of two neighbouring pixels in the two
//! 16-bit lanes of one `u32` (red and blue `Q5.11`, green `Q6.10`, biased by
//! ½), so that per pair of pixels three 32-bit adds step all six values and
//! `(r & 0xF800F800) | ((g >> 5) & 0x07E007E0) | ((b >> 11) & 0x001F001F)`
//! is both pixels, stored as one word: no 64-bit arithmetic, which a
//! Cortex-M has not. The lanes' step is rounded to 2⁻¹¹ (green 2⁻¹⁰) of an
//! LSB per pair, so every [`BLOCK_PAIRS`] pairs the lanes are made anew
//! from the exact `Q.16` values: the step's rounding never adds more than
//! 2⁻⁶ of an LSB (measured: S2, a full-screen gradient, 99.4 % of pixels
//! equal to the reference, against 99.98 % with [`PackedGouraud`]; still at
//! most 1 LSB everywhere).

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::{Point, Size};
use embedded_graphics::primitives::Rectangle;

use embedded_graphics::prelude::RawData;

use crate::color::{pack565, Shade};
use crate::depth::DepthTest;
use crate::framebuffer::Framebuffer;
use crate::illumination::{Lighting, Viewer};
use crate::light::LightSet;
use crate::material::Specular;
use crate::normalize::normalize;
use crate::platform;
use crate::vector::{Unit3, Vec3};

/// Where a span's pixels go.
pub(crate) trait PixelSink {
    /// The sink's error.
    type Error;
    /// The raw pixels of row `y` from column `x0`, `n` of them, where the
    /// sink is memory the renderer may write directly.
    fn row(&mut self, y: i32, x0: i32, n: usize) -> Option<&mut [u16]>;
    /// Sends `n` pixels of row `y` from column `x0`.
    fn fill(
        &mut self,
        y: i32,
        x0: i32,
        n: u32,
        colors: impl Iterator<Item = u16>,
    ) -> Result<(), Self::Error>;
}

/// Any `DrawTarget`: one `fill_contiguous` per run, at the target's origin
/// offset.
pub(crate) struct TargetSink<'t, T> {
    /// The target.
    pub(crate) target: &'t mut T,
    /// The target's bounding box's top-left corner.
    pub(crate) origin: Point,
}

impl<T: DrawTarget<Color = Rgb565>> PixelSink for TargetSink<'_, T> {
    type Error = T::Error;
    #[inline(always)]
    fn row(&mut self, _: i32, _: i32, _: usize) -> Option<&mut [u16]> {
        None
    }
    #[inline]
    fn fill(
        &mut self,
        y: i32,
        x0: i32,
        n: u32,
        colors: impl Iterator<Item = u16>,
    ) -> Result<(), T::Error> {
        // The renderer checks that the target's box ends within `i32`
        // (`RenderError::TargetTooLarge`); a span placed past it by another
        // caller is not sent.
        let (Some(x), Some(y)) = (x0.checked_add(self.origin.x), y.checked_add(self.origin.y))
        else {
            return Ok(());
        };
        if x as i64 + n as i64 - 1 > i32::MAX as i64 {
            return Ok(());
        }
        let area = Rectangle::new(Point::new(x, y), Size::new(n, 1));
        self.target
            .fill_contiguous(&area, colors.map(|c| Rgb565::from(RawU16::new(c))))
    }
}

/// A [`Framebuffer`], written in place.
pub(crate) struct FramebufferSink<'t, 'a> {
    /// The framebuffer.
    pub(crate) fb: &'t mut Framebuffer<'a>,
}

impl PixelSink for FramebufferSink<'_, '_> {
    type Error = core::convert::Infallible;
    #[inline(always)]
    fn row(&mut self, y: i32, x0: i32, n: usize) -> Option<&mut [u16]> {
        // The rasterizer clips spans to the framebuffer's size.
        self.fb.row_mut(y as u32, x0 as u32, n)
    }
    fn fill(
        &mut self,
        y: i32,
        x0: i32,
        n: u32,
        colors: impl Iterator<Item = u16>,
    ) -> Result<(), Self::Error> {
        if let Some(row) = self.fb.row_mut(y as u32, x0 as u32, n as usize) {
            for (p, c) in row.iter_mut().zip(colors) {
                *p = c;
            }
        }
        Ok(())
    }
}

/// A colour band in memory: rows `y0 ..` of a `width`-pixel-wide viewport,
/// row-major, written in place (the band renderer's sink, with the same
/// fast path as [`FramebufferSink`]).
pub(crate) struct BandSink<'b> {
    /// The band's pixels (raw RGB565), `width` per row.
    pub(crate) buf: &'b mut [u16],
    /// Row length in pixels.
    pub(crate) width: u32,
    /// The viewport row of the band's first row.
    pub(crate) y0: i32,
}

impl PixelSink for BandSink<'_> {
    type Error = core::convert::Infallible;
    #[inline(always)]
    fn row(&mut self, y: i32, x0: i32, n: usize) -> Option<&mut [u16]> {
        // Row and column below 2^32, n at most the width: u64 does not
        // overflow (a negative row or column wraps to one past the band).
        let r = y.wrapping_sub(self.y0) as u32 as u64;
        let (x0, w) = (x0 as u32 as u64, self.width as u64);
        if x0.saturating_add(n as u64) > w {
            return None;
        }
        let start = r * w + x0;
        if start + (n as u64) > self.buf.len() as u64 {
            return None;
        }
        self.buf.get_mut(start as usize..start as usize + n)
    }
    fn fill(
        &mut self,
        y: i32,
        x0: i32,
        n: u32,
        colors: impl Iterator<Item = u16>,
    ) -> Result<(), Self::Error> {
        if let Some(row) = self.row(y, x0, n as usize) {
            for (p, c) in row.iter_mut().zip(colors) {
                *p = c;
            }
        }
        Ok(())
    }
}

/// Makes the colours of a span's pixels, left to right.
pub(crate) trait SpanShader {
    /// The colour of the current pixel (raw RGB565); moves to the next.
    fn next(&mut self) -> u16;
    /// Moves `n` pixels on without making colours.
    fn skip(&mut self, n: u32);
    /// Fills a whole row of pixels (no depth test).
    #[inline(always)]
    fn fill_row(&mut self, row: &mut [u16]) {
        for p in row.iter_mut() {
            *p = self.next();
        }
    }
    /// Runs the depth test along a row of pixels and their depths (`z`,
    /// `dz`: depth attribute at the first pixel and its step,
    /// `z_w·65535·2⁸ + 2⁷`, whose `>> 8` is the stored `d`),
    /// writing depth and colour where it passes; returns how many passed.
    /// Where the depth stays in `0 .. 65535 · 2⁸` on the whole row, this is
    /// [`SpanShader::depth_row_inside`]; elsewhere depths are clamped.
    #[inline(always)]
    fn depth_row(&mut self, row: &mut [u16], drow: &mut [u16], z: i64, dz: i64) -> u32
    where
        Self: Sized,
    {
        let len = row.len().min(drow.len());
        match depth_inside(z, dz, len) {
            Some((z, dz)) => self.depth_row_inside(row, drow, z, dz),
            None => depth_row_pixels(self, row, drow, z, dz),
        }
    }
    /// [`SpanShader::depth_row`] for a row whose depth the caller knows to
    /// stay in `0 .. 65535 · 2⁸` (so that `z`, `dz` fit `i32`): no clamp.
    #[inline(always)]
    fn depth_row_inside(&mut self, row: &mut [u16], drow: &mut [u16], z: i32, dz: i32) -> u32
    where
        Self: Sized,
    {
        let len = row.len().min(drow.len());
        let (row, drow) = (&mut row[..len], &mut drow[..len]);
        let (mut z, mut written) = (z, 0);
        for (p, d) in row.iter_mut().zip(drow.iter_mut()) {
            let z16 = (z >> 8) as u16;
            if z16 < *d {
                *d = z16;
                *p = self.next();
                written += 1;
            } else {
                self.skip(1);
            }
            z = z.wrapping_add(dz);
        }
        written
    }
}

/// `(z, dz)` as `i32` if the depth `z + k·dz` stays in `0 .. 65535 · 2⁸`
/// for `k < len` (it is linear: both ends inside suffice). There `z >> 8`
/// is 0 ..= 65534, the clamp's value, so skipping the clamp changes nothing.
#[inline(always)]
fn depth_inside(z: i64, dz: i64, len: usize) -> Option<(i32, i32)> {
    // Saturating: the rasterizer's spans keep |dz| ≤ 2^40 and len ≤ 2^20,
    // a caller's need not (a saturated end is outside the range).
    let z_end = dz.saturating_mul((len as i64 - 1).max(0)).saturating_add(z);
    let range = 0..65535 << 8;
    if range.contains(&z) && range.contains(&z_end) {
        // Inside, |dz| < 2^24 unless len = 1 (then it is never used).
        Some((z as i32, if len > 1 { dz as i32 } else { 0 }))
    } else {
        None
    }
}

/// [`SpanShader::depth_row`] a pixel at a time with the depth clamped to
/// `u16` at every pixel: a pixel that fails costs no colour.
#[inline(always)]
pub(crate) fn depth_row_pixels<S: SpanShader>(
    sh: &mut S,
    row: &mut [u16],
    drow: &mut [u16],
    z: i64,
    dz: i64,
) -> u32 {
    let len = row.len().min(drow.len());
    let (row, drow) = (&mut row[..len], &mut drow[..len]);
    let mut written = 0;
    let mut z = z;
    for (p, d) in row.iter_mut().zip(drow.iter_mut()) {
        let z16 = (z >> 8).clamp(0, 65535) as u16;
        if z16 < *d {
            *d = z16;
            *p = sh.next();
            written += 1;
        } else {
            sh.skip(1);
        }
        z = z.saturating_add(dz);
    }
    written
}

/// One colour for the whole span, or a dithered one.
pub(crate) struct FlatShader {
    /// The undithered colour.
    pub(crate) plain: u16,
    /// The shade, for dithering.
    pub(crate) shade: Shade,
    /// Dithering on.
    pub(crate) dither: bool,
    /// Current column and row (for the dither pattern).
    pub(crate) x: i32,
    /// Row.
    pub(crate) y: i32,
}

impl SpanShader for FlatShader {
    #[inline(always)]
    fn next(&mut self) -> u16 {
        let c = if self.dither {
            dither_shade(self.shade, self.x, self.y)
        } else {
            self.plain
        };
        // Wrapping: the dither pattern needs the column modulo 4 only.
        self.x = self.x.wrapping_add(1);
        c
    }
    #[inline(always)]
    fn skip(&mut self, n: u32) {
        self.x = self.x.wrapping_add(n as i32);
    }
}

/// 4 × 4 Bayer thresholds, `(m + ½)/16` in `Q.16`.
pub(crate) const BAYER: [[u32; 4]; 4] = {
    const M: [[u32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    let mut out = [[0u32; 4]; 4];
    let mut y = 0;
    while y < 4 {
        let mut x = 0;
        while x < 4 {
            out[y][x] = (2 * M[y][x] + 1) << 11;
            x += 1;
        }
        y += 1;
    }
    out
};

/// A shade quantised with ordered dithering at `(x, y)`: `⌊v·31 + t⌋` with
/// the Bayer threshold `t` in place of ½ (SPEC.md 6).
#[inline]
pub(crate) fn dither_shade(c: Shade, x: i32, y: i32) -> u16 {
    let t = BAYER[(y & 3) as usize][(x & 3) as usize];
    let b = c.to_bits();
    // v ≤ 2^16, v·63 + t < 2^23: no overflow.
    let q = |v: u32, m: u32| ((v * m + t) >> 16).min(m);
    pack565(q(b[0], 31), q(b[1], 63), q(b[2], 31))
}

/// The RGB565 pixel of a packed accumulator: red's integer part is bits
/// 59–63, green's 37–42, blue's 16–20 (see the module docs).
///
/// On 64-bit targets the masked accumulator times `1 + 2¹⁶ + 2³²` puts
/// red (times 1) in bits 59–63, green (times 2¹⁶) in 53–58 and blue (times
/// 2³²) in 48–52: the pixel is the top 16 bits. The other products land in
/// bits 16–20, 32–36 and 37–42 or beyond bit 63, all disjoint, so no carry
/// reaches the pixel (callgrind, S1 on x86-64: 2.783 M to 2.727 M
/// instructions a frame; three operations a pixel instead of nine).
///
/// Elsewhere, with `hi`/`lo` the accumulator's 32-bit halves, the pixel is
/// `((hi >> 16) & 0xF800) | (hi & 0x07E0) | ((lo >> 16) & 0x1F)`: 32-bit
/// operations only (a 64-bit multiply is a library call on a Cortex-M0, and
/// shifts-and-adds by `1 + 2¹⁶ + 2³²` get folded back into one).
#[inline(always)]
fn pixel_of(acc: u64) -> u16 {
    if platform::wide_pointer() {
        pixel_by_multiply(acc)
    } else {
        pixel_by_halves(acc)
    }
}

/// [`pixel_of`] with one 64-bit multiply.
#[inline(always)]
fn pixel_by_multiply(acc: u64) -> u16 {
    const MASK: u64 = (31 << 59) | (63 << 37) | (31 << 16);
    ((acc & MASK).wrapping_mul(1 + (1 << 16) + (1 << 32)) >> 48) as u16
}

/// [`pixel_of`] in 32-bit operations.
#[inline(always)]
fn pixel_by_halves(acc: u64) -> u16 {
    let (hi, lo) = ((acc >> 32) as u32, acc as u32);
    (((hi >> 16) & 0xF800) | (hi & 0x07E0) | ((lo >> 16) & 0x1F)) as u16
}

/// The value `c + d·last` at a span's last pixel, or `None` where the
/// checked shader constructors must refuse the span.
///
/// On 64-bit targets the product and sum are checked (`checked_mul`: a
/// multiply and an overflow test). Elsewhere, where a checked 64-bit
/// multiply is a library call of its own (on a Cortex-M0: S2 +17 %), the
/// span must be one the rasterizer can give: `|d| ≤ 2⁴⁰` (its steep
/// limit), `last < 2²⁰` (a clip rectangle's width) and `|c| ≤ 2⁶²` (its
/// planes' clamp), so the plain products cannot overflow. Every span the
/// rasterizer gives passes both forms with the same value; they differ
/// only on spans it cannot give. (The range tests on x86-64 cost S1 2 %,
/// from code layout.)
#[cfg(test)]
#[inline]
fn span_end(c: i64, d: i64, last: i64) -> Option<i64> {
    if platform::wide_pointer() {
        return d.checked_mul(last)?.checked_add(c);
    }
    if d.unsigned_abs() > 1 << 40 || last >= 1 << 20 || c.unsigned_abs() > 1 << 62 {
        return None;
    }
    Some(c + d * last)
}

/// Gouraud colours stepped in one packed `u64` (see the module docs).
#[derive(Clone, Debug)]
pub(crate) struct PackedGouraud {
    acc: u64,
    step: u64,
}

impl PackedGouraud {
    /// The shader for a span of `n` pixels whose scaled channels (`Q.16`
    /// of the 5/6-bit values, biased by ½) start at `c` and step by `d`, or
    /// `None` if a channel leaves its field somewhere on the span (then the
    /// clamped shader must be used).
    #[cfg(test)]
    #[inline]
    pub(crate) fn new(c: [i64; 3], d: [i64; 3], n: u32) -> Option<PackedGouraud> {
        let last = n.saturating_sub(1) as i64;
        let lim = [32i64 << 16, 64 << 16, 32 << 16];
        for k in 0..3 {
            let end = span_end(c[k], d[k], last)?;
            if c[k] < 0 || c[k] >= lim[k] || end < 0 || end >= lim[k] {
                return None;
            }
        }
        // Inside their fields: each value fits `i32`, and so does each step
        // of a span of two pixels or more (a single pixel's is not used).
        let d = if n > 1 { d.map(|v| v as i32) } else { [0; 3] };
        Some(Self::new_inside(c.map(|v| v as i32), d))
    }

    /// As [`PackedGouraud::new`] for channels the caller knows to stay
    /// inside their fields on the whole span (a span of a bounded triangle,
    /// see [`crate::render`]): no check.
    #[inline(always)]
    pub(crate) fn new_inside(c: [i32; 3], d: [i32; 3]) -> PackedGouraud {
        let pack = |v: [i32; 3]| {
            (v[0] as i64 as u64)
                .wrapping_shl(43)
                .wrapping_add((v[1] as i64 as u64).wrapping_shl(21))
                .wrapping_add(v[2] as i64 as u64)
        };
        PackedGouraud {
            acc: pack(c),
            step: pack(d),
        }
    }
}

impl SpanShader for PackedGouraud {
    #[inline(always)]
    fn next(&mut self) -> u16 {
        let p = pixel_of(self.acc);
        self.acc = self.acc.wrapping_add(self.step);
        p
    }
    #[inline(always)]
    fn skip(&mut self, n: u32) {
        self.acc = self.acc.wrapping_add(self.step.wrapping_mul(n as u64));
    }
    /// Four pixels per iteration (independent multiplies, less loop
    /// overhead).
    #[inline(always)]
    fn fill_row(&mut self, row: &mut [u16]) {
        let (s, s2, s3, s4) = (
            self.step,
            self.step.wrapping_mul(2),
            self.step.wrapping_mul(3),
            self.step.wrapping_mul(4),
        );
        let px = pixel_of;
        let mut chunks = row.chunks_exact_mut(4);
        for c in &mut chunks {
            let a = self.acc;
            c.copy_from_slice(&[
                px(a),
                px(a.wrapping_add(s)),
                px(a.wrapping_add(s2)),
                px(a.wrapping_add(s3)),
            ]);
            self.acc = a.wrapping_add(s4);
        }
        for p in chunks.into_remainder() {
            *p = self.next();
        }
    }
}

/// Pairs of pixels per block of [`PairGouraud`]: at each block's first
/// pixel the lanes are made anew from the exact `Q.16` values, so the
/// rounding of the per-pair step adds at most `BLOCK_PAIRS/2` lane units
/// (2⁻⁷ of an LSB for red and blue, 2⁻⁶ for green at 32) before it is
/// dropped.
pub(crate) const BLOCK_PAIRS: u32 = 32;

/// How far (in `Q.16`) a channel must stay inside its field for the lanes
/// to stay inside theirs: a lane deviates from the exact value by at most
/// ½ unit (the anchor's rounding) plus ½ unit per pair stepped, at most
/// `BLOCK_PAIRS/2` units of 2⁶ `Q.16` steps (green's lane, the coarser).
pub(crate) const LANE_MARGIN: i64 = 64 * BLOCK_PAIRS as i64 / 2 + 64;

/// Three `Q.16` channels (red, green, blue) as lane words: red and blue
/// `Q5.11` (`(v + 2⁴) >> 5`), green `Q6.10` (`(v + 2⁵) >> 6`).
#[inline(always)]
fn lane(v: [i32; 3]) -> [i32; 3] {
    // Wrapping: a block anchor past the span's end may wrap (see
    // `start_block`); its lanes are never shown.
    let r = |v: i32, h: i32, s: u32| v.wrapping_add(h) >> s;
    [r(v[0], 16, 5), r(v[1], 32, 6), r(v[2], 16, 5)]
}

/// Two pixels from the three lane words: the low half is the first (in
/// assembly on ARMv7-M, see [`platform::pack_565_pair`]).
#[inline(always)]
fn pair_of(l: [u32; 3]) -> u32 {
    platform::pack_565_pair(l[0], l[1], l[2])
}

#[inline(always)]
fn add_lanes(l: [u32; 3], s: [u32; 3]) -> [u32; 3] {
    [
        l[0].wrapping_add(s[0]),
        l[1].wrapping_add(s[1]),
        l[2].wrapping_add(s[2]),
    ]
}

/// Gouraud colours two pixels at a time in 16-bit lanes (see the module
/// docs): per pair three 32-bit adds, three masks and two ors.
#[derive(Clone, Debug)]
pub(crate) struct PairGouraud {
    /// The current pair's lane words (red, green, blue).
    lanes: [u32; 3],
    /// Their step per pair.
    step: [u32; 3],
    /// `Q.16` channels at the next block's first pixel.
    anchor: [i32; 3],
    /// `Q.16` step per pixel.
    d: [i32; 3],
    /// Pairs left in the current block, the current one included (≥ 1).
    pairs_left: u32,
    /// [`SpanShader::next`] has returned the current pair's first pixel.
    upper: bool,
}

impl PairGouraud {
    /// The shader for a span of `n` pixels whose scaled channels (`Q.16`
    /// of the 5/6-bit values, biased by ½) start at `c` and step by `d`, or
    /// `None` if a channel comes within `LANE_MARGIN` (about 2⁻⁶ of an LSB)
    /// of its field's ends
    /// somewhere on the span (then the clamped shader must be used).
    #[cfg(test)]
    #[inline]
    pub(crate) fn new(c: [i64; 3], d: [i64; 3], n: u32) -> Option<PairGouraud> {
        let last = n.saturating_sub(1) as i64;
        let lim = [32i64 << 16, 64 << 16, 32 << 16];
        for k in 0..3 {
            let end = span_end(c[k], d[k], last)?;
            let inside = |v: i64| (LANE_MARGIN..lim[k] - LANE_MARGIN).contains(&v);
            if !inside(c[k]) || !inside(end) {
                return None;
            }
        }
        // Inside their fields: each value fits `i32`, and so does each step
        // of a span of two pixels or more (a single pixel's is not used).
        let d = if n > 1 { d.map(|v| v as i32) } else { [0; 3] };
        Some(Self::new_inside(c.map(|v| v as i32), d, n))
    }

    /// As [`PairGouraud::new`] for channels the caller knows to stay at
    /// least `LANE_MARGIN` inside their fields on the whole span: no check.
    #[inline(always)]
    pub(crate) fn new_inside(c: [i32; 3], d: [i32; 3], n: u32) -> PairGouraud {
        // Both ends inside: |c| < 2^22, and |d| < 2^22 unless n = 1 (then
        // the step is never used).
        let d = if n > 1 { d } else { [0; 3] };
        let mut sh = PairGouraud {
            lanes: [0; 3],
            step: [0; 3],
            anchor: c,
            d,
            pairs_left: 0,
            upper: false,
        };
        // Per pair, two pixels' step in lane units, rounded; the same in
        // both lanes (packing is modular: a negative step borrows from the
        // upper lane exactly as the subtraction does).
        let s = lane([2 * d[0], 2 * d[1], 2 * d[2]]);
        sh.step = s.map(|s| (s as u32).wrapping_mul(0x1_0001));
        sh.start_block();
        sh
    }

    /// The lanes at the block anchor (pixel and pixel + 1), and the anchor
    /// moved to the next block (wrapping: past the span it is never used).
    #[inline(always)]
    fn start_block(&mut self) {
        let a = self.anchor;
        let (l0, l1) = (lane(a), lane(add3(a, self.d)));
        for k in 0..3 {
            // Both lanes in [0, 2^16) where a pixel of the span is (the
            // margin); a lane past the span's end may wrap, into the upper
            // half only.
            self.lanes[k] = (l0[k] as u32).wrapping_add((l1[k] as u32) << 16);
            self.anchor[k] = a[k].wrapping_add(self.d[k].wrapping_mul(2 * BLOCK_PAIRS as i32));
        }
        self.pairs_left = BLOCK_PAIRS;
    }

    /// Moves on by one pair.
    #[inline(always)]
    fn next_pair(&mut self) {
        self.pairs_left -= 1;
        if self.pairs_left == 0 {
            self.start_block();
        } else {
            self.lanes = add_lanes(self.lanes, self.step);
        }
    }

    /// Calls `f` with each two-pixel chunk of `row` (of even length) and
    /// the chunk's pixels, in order (the shader must be at a pair's first
    /// pixel). Blocks are walked with their lanes in locals; the shader's
    /// fields are written once per block.
    #[inline(always)]
    fn for_pairs(&mut self, row: &mut [u16], mut f: impl FnMut(&mut [u16], u32)) {
        let mut row = row;
        let s = self.step;
        let mut l = self.lanes;
        let mut left = self.pairs_left as usize;
        if row.len() / 2 >= left {
            // The current block ends within the row, then whole blocks (of
            // a constant length: no remainder loop), then a partial one.
            let (head, tail) = core::mem::take(&mut row).split_at_mut(2 * left);
            run_pairs(l, s, head, &mut f);
            self.start_block();
            row = tail;
            const BLOCK: usize = 2 * BLOCK_PAIRS as usize;
            while row.len() >= BLOCK {
                let (block, tail) = core::mem::take(&mut row).split_at_mut(BLOCK);
                // A constant length (the conversion always succeeds): no
                // remainder loop, and the compiler unrolls the block.
                if let Ok(block) = <&mut [u16; BLOCK]>::try_from(block) {
                    run_pairs(self.lanes, s, block, &mut f);
                }
                self.start_block();
                row = tail;
            }
            (l, left) = (self.lanes, BLOCK_PAIRS as usize);
        }
        self.lanes = run_pairs(l, s, row, &mut f);
        self.pairs_left = (left - row.len() / 2) as u32;
    }
}

/// The Gouraud span loop: `f` with each two-pixel chunk of `row` (of even
/// length) and its pixels from lanes `l` stepped by `s`; returns the lanes
/// after the last pair.
///
/// On ARMv7-M two pairs per iteration (with [`pair_of`]'s masks as
/// immediates: 10 instructions per pair against 11 for one pair per
/// iteration), kept at two by [`platform::keep_loop_rolled`]: unrolled
/// further, this loop spills its lanes. A whole block (a constant length)
/// is unrolled completely. QEMU count of the Cortex-M4 build, S2 (a
/// full-screen quad): `fill_row` 5.6 instructions per pixel, block and row
/// overheads included (7.0 with one pair per iteration and a loop per
/// block). Elsewhere one pair per iteration, which LLVM unrolls or
/// vectorises (the Cortex-M0+ and x86-64 do better that way).
#[inline(always)]
fn run_pairs(
    l: [u32; 3],
    s: [u32; 3],
    row: &mut [u16],
    f: &mut impl FnMut(&mut [u16], u32),
) -> [u32; 3] {
    let mut l = l;
    let row = if platform::armv7m() {
        let mut quads = row.chunks_exact_mut(4);
        for q in &mut quads {
            let (p0, p1) = q.split_at_mut(2);
            let w0 = pair_of(l);
            l = add_lanes(l, s);
            let w1 = pair_of(l);
            l = add_lanes(l, s);
            f(p0, w0);
            f(p1, w1);
            platform::keep_loop_rolled();
        }
        quads.into_remainder()
    } else {
        row
    };
    for p in row.chunks_exact_mut(2) {
        f(p, pair_of(l));
        l = add_lanes(l, s);
    }
    l
}

#[inline(always)]
fn add3(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    [
        a[0].wrapping_add(b[0]),
        a[1].wrapping_add(b[1]),
        a[2].wrapping_add(b[2]),
    ]
}

impl SpanShader for PairGouraud {
    #[inline(always)]
    fn next(&mut self) -> u16 {
        let w = pair_of(self.lanes);
        if self.upper {
            self.upper = false;
            self.next_pair();
            (w >> 16) as u16
        } else {
            self.upper = true;
            w as u16
        }
    }
    #[inline]
    fn skip(&mut self, n: u32) {
        let total = n as u64 + self.upper as u64;
        self.upper = total & 1 != 0;
        let mut pairs = total >> 1;
        while pairs >= self.pairs_left as u64 {
            pairs -= self.pairs_left as u64;
            self.start_block();
        }
        // pairs < BLOCK_PAIRS.
        let p = pairs as u32;
        self.pairs_left -= p;
        for k in 0..3 {
            self.lanes[k] = self.lanes[k].wrapping_add(self.step[k].wrapping_mul(p));
        }
    }
    /// Out of line: long spans only, kept apart from the triangle loop.
    #[inline(never)]
    fn fill_row(&mut self, row: &mut [u16]) {
        let mut row = row;
        if self.upper {
            if let Some((p, rest)) = core::mem::take(&mut row).split_first_mut() {
                *p = self.next();
                row = rest;
            }
        }
        let even = row.len() & !1;
        let (pairs, rest) = row.split_at_mut(even);
        self.for_pairs(pairs, |p, w| {
            p[0] = w as u16;
            p[1] = (w >> 16) as u16;
        });
        if let Some(p) = rest.first_mut() {
            *p = self.next();
        }
    }
    #[inline(never)]
    fn depth_row_inside(&mut self, row: &mut [u16], drow: &mut [u16], z: i32, dz: i32) -> u32 {
        let len = row.len().min(drow.len());
        if self.upper {
            return depth_row_pixels(self, row, drow, z as i64, dz as i64);
        }
        let (row, drow) = (&mut row[..len], &mut drow[..len]);
        let mut z = z;
        let mut written = 0;
        let even = len & !1;
        let (pairs, rest) = row.split_at_mut(even);
        let (dpairs, drest) = drow.split_at_mut(even);
        let mut dp = dpairs.chunks_exact_mut(2);
        self.for_pairs(pairs, |p, w| {
            if let Some(d) = dp.next() {
                for (k, px) in [w as u16, (w >> 16) as u16].into_iter().enumerate() {
                    let z16 = (z >> 8) as u16;
                    if z16 < d[k] {
                        d[k] = z16;
                        p[k] = px;
                        written += 1;
                    }
                    z = z.wrapping_add(dz);
                }
            }
        });
        if let (Some(p), Some(d)) = (rest.first_mut(), drest.first_mut()) {
            let z16 = (z >> 8) as u16;
            if z16 < *d {
                *d = z16;
                *p = self.next();
                written += 1;
            }
        }
        written
    }
}

/// Gouraud colours per channel with a clamp (slivers whose values leave
/// the fields by rounding) and optional dithering.
pub(crate) struct ClampedGouraud {
    /// Current scaled channels.
    pub(crate) c: [i64; 3],
    /// Step per pixel.
    pub(crate) d: [i64; 3],
    /// Dithering on.
    pub(crate) dither: bool,
    /// Column.
    pub(crate) x: i32,
    /// Row.
    pub(crate) y: i32,
}

impl SpanShader for ClampedGouraud {
    #[inline]
    fn next(&mut self) -> u16 {
        // The channels carry the bias ½; dithering swaps it for the Bayer
        // threshold.
        let t = if self.dither {
            BAYER[(self.y & 3) as usize][(self.x & 3) as usize] as i64 - (1 << 15)
        } else {
            0
        };
        let q = |v: i64, m: i64| (v.saturating_add(t) >> 16).clamp(0, m) as u32;
        let p = pack565(q(self.c[0], 31), q(self.c[1], 63), q(self.c[2], 31));
        self.skip(1);
        p
    }
    #[inline]
    fn skip(&mut self, n: u32) {
        // Saturating: the channels are clamped per pixel anyway.
        for (c, d) in self.c.iter_mut().zip(&self.d) {
            *c = c.saturating_add(d.saturating_mul(n as i64));
        }
        self.x = self.x.wrapping_add(n as i32);
    }
}

/// A span's depth: the attribute `z_w·65535·2⁸ + 2⁷` at its first pixel
/// and its step per pixel; the stored depth is the attribute `>> 8`, which
/// is `d = ⌊z_w·65535 + ½⌋` (SPEC.md 5, [`crate::depth`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SpanDepth {
    /// Depth at the first pixel.
    pub(crate) z: i64,
    /// Step per pixel.
    pub(crate) dz: i64,
    /// The caller knows that the depth stays in `0 .. 65535 · 2⁸` on the
    /// whole span (no range check, no clamp); `false` if it does not know.
    pub(crate) inside: bool,
}

/// Sends a span: runs the depth test (if any) and writes the pixels that
/// pass with colours from `sh`. Returns the number of pixels written.
#[inline(always)]
pub(crate) fn emit<P: PixelSink, D: DepthTest, S: SpanShader>(
    sink: &mut P,
    depth: &mut D,
    y: i32,
    x0: i32,
    n: u32,
    z: SpanDepth,
    mut sh: S,
) -> Result<u32, P::Error> {
    if !D::ENABLED {
        if let Some(row) = sink.row(y, x0, n as usize) {
            sh.fill_row(row);
            return Ok(n);
        }
        sink.fill(y, x0, n, (0..n).map(|_| sh.next()))?;
        return Ok(n);
    }
    let drow = depth.row(y as u32, x0 as u32, n);
    if let Some(row) = sink.row(y, x0, n as usize) {
        if z.inside {
            // Inside: |dz| < 2^24 unless n = 1 (then the step is not used).
            let dz = if n > 1 { z.dz as i32 } else { 0 };
            return Ok(sh.depth_row_inside(row, drow, z.z as i32, dz));
        }
        return Ok(sh.depth_row(row, drow, z.z, z.dz));
    }
    let SpanDepth { mut z, dz, .. } = z;
    let mut written = 0;
    // A display: one fill_contiguous per run of passing pixels. The depth
    // test of a run is done before its pixels are sent.
    let mut k = 0u32;
    let n = n.min(drow.len() as u32);
    let mut shaded = 0u32;
    while k < n {
        // Skip failing pixels.
        while k < n {
            let z16 = (z >> 8).clamp(0, 65535) as u16;
            if z16 < drow[k as usize] {
                break;
            }
            z = z.saturating_add(dz);
            k += 1;
        }
        let start = k;
        while k < n {
            let z16 = (z >> 8).clamp(0, 65535) as u16;
            let stored = &mut drow[k as usize];
            if z16 >= *stored {
                break;
            }
            *stored = z16;
            z = z.saturating_add(dz);
            k += 1;
        }
        if k > start {
            sh.skip(start - shaded);
            let len = k - start;
            // The column is `x0 as u32 + start`, below the depth row's
            // width (`drow` holds the run): wrapping `i32` is that value.
            let x = x0.wrapping_add(start as i32);
            sink.fill(y, x, len, (0..len).map(|_| sh.next()))?;
            shaded = k;
            written += len;
        }
    }
    Ok(written)
}

/// Phong shading per pixel: normal and eye position stepped, the normal
/// renormalised, the equation evaluated.
///
/// Only the renderer makes one, for one rasterizer span: its values start
/// within the vertex values (normals below 2²⁷ in `Q.26`, positions
/// within `i32`) and step by at most 2⁴⁰ for at most 2²⁰ pixels, so the
/// plain `i64` stepping of the per-pixel path cannot overflow (saturating
/// it cost S4 1.7 %).
pub(crate) struct PhongPixels<'l, S: Specular, V: Viewer, L: LightSet> {
    /// The frame's lighting.
    pub(crate) lighting: &'l Lighting<S, V, L>,
    /// Normal (`Q.26`) and eye position (`I8F24` raw) at the current pixel.
    pub(crate) cur: [i64; 6],
    /// Their steps.
    pub(crate) d: [i64; 6],
    /// Dithering on.
    pub(crate) dither: bool,
    /// Column.
    pub(crate) x: i32,
    /// Row.
    pub(crate) y: i32,
}

impl<S: Specular, V: Viewer, L: LightSet> SpanShader for PhongPixels<'_, S, V, L> {
    #[inline]
    fn next(&mut self) -> u16 {
        // The interpolated normal lies between unit vectors (below 2^27 in
        // Q.26); positions between I8F24 points: both fit i32.
        let sat = |v: i64| v.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        let c = &self.cur;
        let n = normalize([sat(c[0]), sat(c[1]), sat(c[2])]).unwrap_or(Unit3::ZERO);
        let p = Vec3::from_bits(sat(c[3]), sat(c[4]), sat(c[5]));
        let shade = self.lighting.shade(p, n);
        let px = if self.dither {
            dither_shade(shade, self.x, self.y)
        } else {
            RawU16::from(shade.to_rgb565()).into_inner()
        };
        self.skip(1);
        px
    }
    #[inline]
    fn skip(&mut self, n: u32) {
        for (c, d) in self.cur.iter_mut().zip(&self.d) {
            *c += d * n as i64;
        }
        self.x = self.x.wrapping_add(n as i32);
    }
}

#[cfg(test)]
mod tests {
    use super::{pixel_by_halves, pixel_by_multiply};
    use crate::rasterizer::tests::xorshift;

    /// The multiply's gather is the 32-bit one for every accumulator: each
    /// field at every value (the others random), and random accumulators.
    #[test]
    fn both_pixel_forms_agree() {
        let mut rnd = xorshift(0x5EED_0F5A_11AA);
        for (shift, width) in [(59, 5), (37, 6), (16, 5)] {
            for v in 0..1u64 << width {
                for _ in 0..64 {
                    let field = ((1u64 << width) - 1) << shift;
                    let acc = (rnd() & !field) | v << shift;
                    assert_eq!(pixel_by_multiply(acc), pixel_by_halves(acc), "{acc:#x}");
                }
            }
        }
        for acc in (0..1 << 20).map(|_| rnd()).chain([0, u64::MAX]) {
            assert_eq!(pixel_by_multiply(acc), pixel_by_halves(acc), "{acc:#x}");
        }
        // Red, green and blue land where RGB565 has them.
        let acc = (21u64 << 59) | (42 << 37) | (9 << 16);
        assert_eq!(pixel_by_multiply(acc), (21 << 11) | (42 << 5) | 9);
    }

    /// The example from the docs of `PixelSink`.
    #[test]
    fn doc_pixel_sink() {
        use crate::framebuffer::Framebuffer;
        use crate::span::{FramebufferSink, PixelSink};
        let mut px = [0u16; 4 * 2];
        let mut fb = Framebuffer::new(&mut px, 4, 2).unwrap();
        let mut sink = FramebufferSink { fb: &mut fb };
        sink.fill(1, 1, 3, [5, 6, 7].into_iter()).unwrap();
        sink.row(0, 2, 2).unwrap().fill(9); // memory: written directly
        assert_eq!(px, [0, 0, 9, 9, 0, 5, 6, 7]);
    }

    /// The example from the docs of `TargetSink`.
    #[test]
    fn doc_target_sink() {
        use crate::framebuffer::Framebuffer;
        use crate::span::{PixelSink, TargetSink};
        use embedded_graphics::prelude::Point;
        let mut px = [0u16; 6];
        let mut fb = Framebuffer::new(&mut px, 6, 1).unwrap();
        let mut canvas = fb.canvas(); // a DrawTarget
        let mut sink = TargetSink {
            target: &mut canvas,
            origin: Point::new(2, 0),
        };
        assert!(sink.row(0, 0, 1).is_none()); // no direct memory: always `fill`
        sink.fill(0, 1, 2, [4, 5].into_iter()).unwrap(); // column 1 of the box is 3
        assert_eq!(px, [0, 0, 0, 4, 5, 0]);
    }

    /// The example from the docs of `FramebufferSink`.
    #[test]
    fn doc_framebuffer_sink() {
        use crate::framebuffer::Framebuffer;
        use crate::span::{FramebufferSink, PixelSink};
        let mut px = [0u16; 4];
        let mut fb = Framebuffer::new(&mut px, 4, 1).unwrap();
        let mut sink = FramebufferSink { fb: &mut fb };
        assert_eq!(sink.row(0, 1, 3).map(|r| r.len()), Some(3));
        assert!(sink.row(0, 2, 3).is_none()); // spans must be clipped to the framebuffer
        sink.fill(0, 2, 3, [1, 2, 3].into_iter()).unwrap(); // so this one writes nothing
        assert_eq!(px, [0; 4]);
    }

    /// The example from the docs of `BandSink`.
    #[test]
    fn doc_band_sink() {
        use crate::span::{BandSink, PixelSink};
        let mut px = [0u16; 4 * 2];
        let mut sink = BandSink {
            buf: &mut px,
            width: 4,
            y0: 10,
        };
        sink.row(11, 1, 2).unwrap().fill(7);
        assert!(sink.row(9, 0, 1).is_none());
        assert_eq!(px, [0, 0, 0, 0, 0, 7, 7, 0]);
    }

    /// The example from the docs of `SpanShader`.
    #[test]
    fn doc_span_shader() {
        use crate::span::SpanShader;
        struct Count(u16); // colour = the pixel's index + 1
        impl SpanShader for Count {
            fn next(&mut self) -> u16 {
                self.0 += 1;
                self.0
            }
            fn skip(&mut self, n: u32) {
                self.0 += n as u16
            }
        }
        let mut row = [0u16; 4];
        Count(0).fill_row(&mut row);
        assert_eq!(row, [1, 2, 3, 4]);
        // Depth 0x10 at every pixel: the pixel whose stored depth is nearer keeps its colour.
        let (mut row, mut drow) = ([0u16; 4], [u16::MAX, 0x10, u16::MAX, u16::MAX]);
        assert_eq!(Count(0).depth_row(&mut row, &mut drow, 0x10 << 8, 0), 3);
        assert_eq!((row, drow), ([1, 0, 3, 4], [0x10; 4]));
    }

    /// The example from the docs of `depth_row_pixels`.
    #[test]
    fn doc_depth_row_pixels() {
        use crate::span::{depth_row_pixels, FlatShader};
        let mut sh = FlatShader {
            plain: 7,
            shade: Default::default(),
            dither: false,
            x: 0,
            y: 0,
        };
        // Depths -2, -1, 0, 1 (in units of 2⁸) clamp to 0, 0, 0, 1.
        let (mut row, mut drow) = ([0u16; 4], [1u16; 4]);
        assert_eq!(
            depth_row_pixels(&mut sh, &mut row, &mut drow, -2 << 8, 1 << 8),
            3
        );
        assert_eq!((row, drow), ([7, 7, 7, 0], [0, 0, 0, 1]));
        // Past the far end: clamped to 65535, never in front of a cleared buffer.
        let mut drow = [u16::MAX; 4];
        assert_eq!(
            depth_row_pixels(&mut sh, &mut row, &mut drow, 1 << 40, 0),
            0
        );
    }

    /// The example from the docs of `FlatShader`.
    #[test]
    fn doc_flat_shader() {
        use crate::span::{dither_shade, FlatShader, SpanShader};
        use crate::Shade;
        let shade = Shade::from_bits(1 << 15, 1 << 15, 1 << 15);
        let mut sh = FlatShader {
            plain: 0x8410,
            shade,
            dither: false,
            x: 5,
            y: 2,
        };
        assert_eq!([sh.next(), sh.next()], [0x8410; 2]);
        sh.dither = true;
        sh.skip(3); // now at column 10
        assert_eq!(sh.next(), dither_shade(shade, 10, 2));
        assert_eq!(sh.next(), dither_shade(shade, 11, 2));
    }

    /// The example from the docs of `BAYER`.
    #[test]
    fn doc_bayer() {
        use crate::span::BAYER;
        let mut t: Vec<u32> = BAYER.iter().flatten().copied().collect();
        t.sort();
        // Every m in 0 .. 16 once: thresholds 1/32, 3/32, .., 31/32, averaging ½.
        assert!(t
            .iter()
            .enumerate()
            .all(|(m, &v)| v == (2 * m as u32 + 1) << 11));
        assert_eq!(BAYER[0][0], 1 << 11);
    }

    /// The example from the docs of `dither_shade`.
    #[test]
    fn doc_dither_shade() {
        use crate::span::dither_shade;
        use crate::Shade;
        // Grey ½: 15.5 levels of red and blue, 31.5 of green.
        let half = Shade::from_bits(1 << 15, 1 << 15, 1 << 15);
        let tile: Vec<u16> = (0..16).map(|i| dither_shade(half, i % 4, i / 4)).collect();
        assert_eq!(
            tile.iter()
                .filter(|&&p| p == (16 << 11 | 32 << 5 | 16))
                .count(),
            8
        );
        assert_eq!(
            tile.iter()
                .filter(|&&p| p == (15 << 11 | 31 << 5 | 15))
                .count(),
            8
        );
        // Full channels stay full (no level past 31 or 63).
        assert_eq!(
            dither_shade(Shade::from_bits(1 << 16, 1 << 16, 1 << 16), 3, 3),
            0xFFFF
        );
    }

    /// The example from the docs of `PackedGouraud`.
    #[test]
    fn doc_packed_gouraud() {
        use crate::span::{PackedGouraud, SpanShader};
        let one = 1 << 16;
        // Green falls from 40.5 by ¾ per pixel (biased by ½); red and blue flat.
        let (c, d) = (
            [one / 2, 40 * one + one / 2, 31 * one],
            [0, -3 * one / 4, 0],
        );
        let mut sh = PackedGouraud::new(c, d, 9).unwrap();
        let mut row = [0u16; 9];
        sh.fill_row(&mut row);
        let green: Vec<u16> = row.iter().map(|p| p >> 5 & 63).collect();
        assert_eq!(green, [40, 39, 39, 38, 37, 36, 36, 35, 34]);
        assert!(row.iter().all(|p| p >> 11 == 0 && p & 31 == 31));
    }

    /// The example from the docs of `PackedGouraud::new`.
    #[test]
    fn doc_packed_gouraud_new() {
        use crate::span::{PackedGouraud, PairGouraud};
        let one = 1 << 16;
        let (c, d) = ([31 * one, 0, 0], [one / 2, 0, 0]);
        assert!(PackedGouraud::new(c, d, 2).is_some()); // red ends at 31.5
        assert!(PackedGouraud::new(c, d, 3).is_none()); // red would reach 32
        assert!(PackedGouraud::new([-1, 0, 0], [0; 3], 1).is_none());
        // The fields' very ends are allowed, unlike PairGouraud's margin.
        assert!(PackedGouraud::new([0; 3], [0; 3], 8).is_some());
        assert!(PairGouraud::new([0; 3], [0; 3], 8).is_none());
    }

    /// The example from the docs of `BLOCK_PAIRS`.
    #[test]
    fn doc_block_pairs() {
        use crate::span::{PackedGouraud, PairGouraud, SpanShader, BLOCK_PAIRS};
        // A span of several blocks; steps that no lane holds exactly.
        let n = 6 * BLOCK_PAIRS + 7;
        let (c, d) = ([1 << 15, 1 << 16, 30 << 16], [7919, 13001, -9001]);
        let (mut exact, mut pairs) = (vec![0u16; n as usize], vec![0u16; n as usize]);
        PackedGouraud::new(c, d, n).unwrap().fill_row(&mut exact);
        PairGouraud::new(c, d, n).unwrap().fill_row(&mut pairs);
        let ch = |p: u16| [p >> 11, p >> 5 & 63, p & 31];
        let diff = |(a, b): (&u16, &u16)| (0..3).all(|k| ch(*a)[k].abs_diff(ch(*b)[k]) <= 1);
        assert!(exact.iter().zip(&pairs).all(diff)); // still at most 1 LSB at the span's end
    }

    /// The example from the docs of `PairGouraud`.
    #[test]
    fn doc_pair_gouraud() {
        use crate::span::{PairGouraud, SpanShader};
        let one = 1 << 16;
        let (c, d) = ([one, 20 * one, 30 * one], [one / 3, one / 5, -one / 7]);
        let sh = PairGouraud::new(c, d, 40).unwrap();
        let mut row = [0u16; 40];
        sh.clone().fill_row(&mut row);
        // A pixel at a time, and skipping to an odd column, give the same pixels.
        let mut one_by_one = sh.clone();
        assert!(row.iter().all(|&p| p == one_by_one.next()));
        let mut skipped = sh;
        skipped.skip(37);
        assert_eq!([skipped.next(), skipped.next(), skipped.next()], row[37..]);
    }

    /// The example from the docs of `PairGouraud::new`.
    #[test]
    fn doc_pair_gouraud_new() {
        use crate::span::{PairGouraud, SpanShader};
        // Red from 0.5 to 30.5 (biased by ½) over 31 pixels, green and blue flat.
        let one = 1 << 16;
        let mut sh = PairGouraud::new([one / 2, 10 * one, 3 * one], [one, 0, 0], 31).unwrap();
        let mut row = [0u16; 31];
        sh.fill_row(&mut row);
        assert!(row
            .iter()
            .enumerate()
            .all(|(x, &p)| p == (x as u16) << 11 | 10 << 5 | 3));
    }

    /// The example from the docs of `ClampedGouraud`.
    #[test]
    fn doc_clamped_gouraud() {
        use crate::span::{ClampedGouraud, SpanShader};
        let one = 1 << 16;
        // Red from 29.5 up by one a pixel, blue from 0.5 down: both leave their fields.
        let c = [29 * one + one / 2, 0, one / 2];
        let mut sh = ClampedGouraud {
            c,
            d: [one, 0, -one],
            dither: false,
            x: 0,
            y: 0,
        };
        let px: Vec<u16> = (0..4).map(|_| sh.next()).collect();
        assert_eq!(px, [29 << 11, 30 << 11, 31 << 11, 31 << 11]); // blue 0, 0, 0, 0
        assert_eq!(sh.x, 4);
    }

    /// The example from the docs of `SpanDepth`.
    #[test]
    fn doc_span_depth() {
        use crate::depth::DepthBuffer;
        use crate::framebuffer::Framebuffer;
        use crate::span::{emit, FlatShader, FramebufferSink, SpanDepth};
        let (mut px, mut zs) = ([0u16; 4], [u16::MAX; 4]);
        let mut fb = Framebuffer::new(&mut px, 4, 1).unwrap();
        let mut depth = DepthBuffer::new(&mut zs, 4, 1).unwrap();
        let sh = FlatShader {
            plain: 1,
            shade: Default::default(),
            dither: false,
            x: 0,
            y: 0,
        };
        // z_w = ½ at the first pixel (2²³ = ½·65535·2⁸ + 2⁷), then 256/65535 further
        // per pixel: stored as d = ⌊z_w · 65535 + ½⌋.
        let z = SpanDepth {
            z: 1 << 23,
            dz: 1 << 16,
            inside: true,
        };
        emit(
            &mut FramebufferSink { fb: &mut fb },
            &mut depth,
            0,
            0,
            4,
            z,
            sh,
        )
        .unwrap();
        assert_eq!(zs, [0x8000, 0x8100, 0x8200, 0x8300]);
    }

    /// The example from the docs of `emit`.
    #[test]
    fn doc_emit() {
        use crate::depth::DepthBuffer;
        use crate::framebuffer::Framebuffer;
        use crate::span::{emit, FlatShader, FramebufferSink, SpanDepth};
        let mut px = [0u16; 8];
        let mut fb = Framebuffer::new(&mut px, 8, 1).unwrap();
        let mut zs = [u16::MAX; 8];
        let mut depth = DepthBuffer::new(&mut zs, 8, 1).unwrap();
        let sh = FlatShader {
            plain: 7,
            shade: Default::default(),
            dither: false,
            x: 2,
            y: 0,
        };
        let z = SpanDepth {
            z: 1 << 23,
            dz: 0,
            inside: false,
        };
        let n = emit(
            &mut FramebufferSink { fb: &mut fb },
            &mut depth,
            0,
            2,
            4,
            z,
            sh,
        )
        .unwrap();
        assert_eq!((n, px), (4, [0, 0, 7, 7, 7, 7, 0, 0]));
    }
}

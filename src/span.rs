//! Spans: the depth test, each pixel's colour ([`Shader`]) and where the
//! pixels go ([`Out`]).
//!
//! A span's attributes are the set-up's integer planes (`src/setup.rs`),
//! stepped by one wrapping add a pixel: attribute 0 is the depth (its
//! `>> 12` is SPEC.md 5's `d`, see `depth16`), the others the shading
//! mode's. Gouraud colours are three planes of `Q.20` values (the 5- or
//! 6-bit channel times 2²⁰, plus ½ for SPEC.md 6's rounding), each pixel's
//! channel its plane's `>> 20`: the planes keep a margin of 2¹⁹ inside
//! their fields at every covered pixel (the set-up's planes stray at most
//! 2¹²·⁶ units from the colours' range there, `src/setup.rs`), so they
//! need no clamp.
//!
//! Two outputs: memory written in place ([`Memory`]: a framebuffer or a
//! band, no call per span), and any `DrawTarget` ([`TargetSink`]: one
//! `fill_contiguous` a span, or a run of pixels that pass the depth test).

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::{Point, RawData, Size};
use embedded_graphics::primitives::Rectangle;

use crate::color::{pack565, Shade};
use crate::depth::DepthTest;
use crate::illumination::{Lighting, Viewer};
use crate::light::LightSet;
use crate::material::Specular;
use crate::num::widening::saturate_i32;
use crate::planes::{Planes, Row};
use crate::platform;
use crate::setup::Rect;
use crate::walk::Span;

/// A pixel's stored depth from its depth plane: `d = ⌊z/2¹²⌋`, clamped to
/// `u16` (a plane beyond the far plane reaches past 65535, one at the near
/// plane may stray below 0); an `i32`, compared with the stored `u16`
/// widened.
#[inline(always)]
fn depth16(z: i32) -> i32 {
    (z >> 12).clamp(0, 0xFFFF)
}

/// The colour of a span's pixel from its attributes, and the span's loops.
pub(crate) trait Shader<const N: usize>: Sized {
    /// The colour (raw RGB565) of the pixel at target column `x`, row `y`
    /// with attributes `a`.
    fn pixel(&self, a: &[i32; N], x: i32, y: i32) -> u16;

    /// Span `s`'s pixels into `row`, from target pixel `at` on.
    #[inline(always)]
    fn fill(&self, row: &mut [u16], s: &Span<N>, at: (i32, i32)) {
        fill(self, row, &s.start(), s.step(), at)
    }

    /// Span `s`'s colours in order, from target pixel `at` on, as
    /// [`Shader::fill`] writes them (for a `DrawTarget`).
    #[inline(always)]
    fn colours<'s>(&'s self, s: &Span<N>, at: (i32, i32)) -> impl Iterator<Item = u16> + 's {
        let (mut a, d, (mut x, y)) = (s.start(), *s.step(), at);
        (0..s.n).map(move |_| {
            let c = self.pixel(&a, x, y);
            step(&mut a, &d, 1);
            x = x.wrapping_add(1);
            c
        })
    }

    /// [`Shader::fill`] through the depth test against and into `zrow`:
    /// the pixels written.
    #[inline(always)]
    fn fill_depth(&self, row: &mut [u16], zrow: &mut [u16], s: &Span<N>, at: (i32, i32)) -> u32 {
        fill_depth(self, row, zrow, &s.start(), s.step(), at)
    }

    /// The rows of `table` on `planes` (the first `dy` rows below their
    /// first) through the depth test, colour and depth laid out alike
    /// (`Rows::new`'s contract), by a loop of the platform's: the pixels
    /// written, or `None` where this shader has none (the rows then go
    /// span by span).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn rows_depth(
        &self,
        planes: &Planes<N>,
        dy: i32,
        table: &[Row],
        buf: &mut [u16],
        zbuf: &mut [u16],
        first: i64,
        width: u32,
    ) -> Option<u32> {
        let _ = (planes, dy, table, buf, zbuf, first, width);
        None
    }

    /// [`Shader::rows_depth`] in stores that [`Out::fit_rows`] found the
    /// draw's rect in ([`Out::row_stores`]' `at`, column 0 of the table's
    /// first row): no check a table.
    ///
    /// # Safety
    /// Every row's span lies in the fitted rect, and `at` is
    /// [`Out::row_stores`]' for the table's first row.
    #[inline(always)]
    unsafe fn rows_stored(
        &self,
        planes: &Planes<N>,
        dy: i32,
        table: &[Row],
        at: &RowStores,
    ) -> Option<u32> {
        let _ = (planes, dy, table, at);
        None
    }
}

/// Gouraud colours: attributes 1–3 are the red, green and blue planes;
/// with `dither`, the 4 × 4 Bayer threshold in place of the planes' ½,
/// clamped to the channel. (One shader for both, chosen per span and per
/// table of rows: a draw's code is not made twice for a switch.)
pub(crate) struct Gouraud {
    pub(crate) dither: bool,
}

/// A dithered Gouraud pixel at target pixel `(x, y)`.
#[inline(always)]
fn dithered(a: &[i32; 4], x: i32, y: i32) -> u16 {
    let t = (BAYER[(y & 3) as usize][(x & 3) as usize] as i32) << 4;
    let c = |v: i32, max: i32| ((v - (1 << 19) + t) >> 20).clamp(0, max) as u32;
    pack565(c(a[1], 31), c(a[2], 63), c(a[3], 31))
}

impl Shader<4> for Gouraud {
    #[inline(always)]
    fn pixel(&self, a: &[i32; 4], x: i32, y: i32) -> u16 {
        if self.dither {
            dithered(a, x, y)
        } else {
            platform::pack_planes(a[1], a[2], a[3])
        }
    }

    /// Two pixels at a time ([`Pairs`]) where not dithered.
    #[inline(always)]
    fn fill(&self, row: &mut [u16], s: &Span<4>, at: (i32, i32)) {
        if self.dither {
            fill(self, row, &s.start(), s.step(), at)
        } else {
            Pairs::fill(row, s)
        }
    }

    #[inline(always)]
    fn colours<'s>(&'s self, s: &Span<4>, at: (i32, i32)) -> impl Iterator<Item = u16> + 's {
        let dither = self.dither;
        let (mut p, mut w) = (Pairs::of(s), 0);
        let (mut a, d, (mut x, y)) = (s.start(), *s.step(), at);
        (0..s.n).map(move |k| {
            if dither {
                let c = dithered(&a, x, y);
                step(&mut a, &d, 1);
                x = x.wrapping_add(1);
                c
            } else {
                if k & 1 == 0 {
                    w = p.next();
                }
                (w >> (16 * (k & 1))) as u16
            }
        })
    }

    /// The platform's loop (assembly on the Cortex-M cores) where not
    /// dithered.
    #[inline(always)]
    fn rows_depth(
        &self,
        planes: &Planes<4>,
        dy: i32,
        table: &[Row],
        buf: &mut [u16],
        zbuf: &mut [u16],
        first: i64,
        width: u32,
    ) -> Option<u32> {
        if self.dither {
            return None;
        }
        let mut run = platform::Rows::new(planes, dy, table, buf, zbuf, first, width);
        Some(platform::gouraud_depth_rows(&mut run))
    }

    #[inline(always)]
    unsafe fn rows_stored(
        &self,
        planes: &Planes<4>,
        dy: i32,
        table: &[Row],
        at: &RowStores,
    ) -> Option<u32> {
        if self.dither {
            return None;
        }
        // SAFETY: the caller's contract: every row's span in both stores.
        let mut run =
            unsafe { platform::Rows::at(planes, dy, table, at.colour, at.depth, at.stride) };
        Some(platform::gouraud_depth_rows(&mut run))
    }
}

/// Pairs of pixels per block of [`Pairs`]: at each block's first pixel
/// the lanes are made anew from the exact planes, so the rounding of the
/// per-pair step adds at most `BLOCK_PAIRS/2` lane units (2⁻⁶ of an LSB
/// for green, the coarser lane) before it is dropped.
pub(crate) const BLOCK_PAIRS: usize = 32;

/// Three `Q.20` colour planes' values as lanes: red and blue `Q5.11`,
/// green `Q6.10`, rounded. (Wrapping: an anchor past the span's end may
/// wrap; its lanes are never shown.)
#[inline(always)]
fn lanes(a: [i32; 3]) -> [u32; 3] {
    let r = |v: i32, s: u32| (v.wrapping_add(1 << (s - 1)) >> s) as u32;
    [r(a[0], 9), r(a[1], 10), r(a[2], 9)]
}

#[inline(always)]
fn add_lanes(l: [u32; 3], s: [u32; 3]) -> [u32; 3] {
    [0, 1, 2].map(|k| l[k].wrapping_add(s[k]))
}

/// Gouraud colours two pixels at a time, for spans without a depth test:
/// each channel of two neighbouring pixels in the two 16-bit lanes of one
/// `u32`, so that three 32-bit adds step six values and
/// [`platform::pack_pair`] makes both pixels in one word. The lanes' step
/// is rounded to 2⁻¹¹ (green 2⁻¹⁰) of an LSB a pair, so every
/// [`BLOCK_PAIRS`] pairs the lanes are made anew from the planes: they
/// stray at most 17 lane units from the planes, far inside the planes'
/// margin of 2¹⁹ `Q.20` units (2¹⁰ and 2⁹ lane units), so no lane leaves
/// its 16 bits at a covered pixel. A pixel's channel may differ from its
/// plane's `>> 20` by one where the plane lies within 2¹⁴ units of a step
/// (measured: S2, a full-screen gradient, 99.53 % of pixels equal to the
/// reference, at most 1 LSB everywhere: `cargo test --release -p
/// fixshade-host --test suite kernel_vs_reference -- --nocapture`). The same span gives the same
/// pixels in memory and through a `DrawTarget`: blocks start at the
/// span's first pixel.
#[derive(Clone, Debug)]
pub(crate) struct Pairs {
    /// The current pair's lanes (red, green, blue).
    lanes: [u32; 3],
    /// Their step a pair.
    step: [u32; 3],
    /// The planes at the next block's first pixel.
    anchor: [i32; 3],
    /// The planes' step a pixel.
    d: [i32; 3],
    /// Pairs left in the current block, the current one included (≥ 1).
    left: usize,
}

impl Pairs {
    /// The pairs of Gouraud span `s` (attributes 1–3 the colour planes).
    #[inline(always)]
    fn of(s: &Span<4>) -> Pairs {
        let (a, d) = (s.start(), s.step());
        let d = [d[1], d[2], d[3]];
        let step = lanes(d.map(|v| v.wrapping_mul(2)));
        let mut p = Pairs {
            lanes: [0; 3],
            // The same step in both lanes: packing is modular, so a
            // negative step borrows from the upper lane as a subtraction
            // of the packed values does.
            step: step.map(|s| s.wrapping_mul(0x1_0001)),
            anchor: [a[1], a[2], a[3]],
            d,
            left: 0,
        };
        p.start_block();
        p
    }

    /// The lanes at the anchor (its pixel and the next), and the anchor
    /// moved to the next block.
    #[inline(always)]
    fn start_block(&mut self) {
        self.lanes = pair_lanes(self.anchor, self.d);
        self.anchor = next_anchor(self.anchor, self.d);
        self.left = BLOCK_PAIRS;
    }

    /// The current pair's two pixels (the first in the low half), moving
    /// on to the next pair.
    #[inline(always)]
    fn next(&mut self) -> u32 {
        let w = platform::pack_pair(self.lanes);
        self.left -= 1;
        if self.left == 0 {
            self.start_block();
        } else {
            self.lanes = add_lanes(self.lanes, self.step);
        }
        w
    }

    /// Span `s`'s pixels into `row`, block by block, as [`Pairs::next`]
    /// makes them. (Out of line, from the span: the pairs in registers.)
    #[inline(never)]
    fn fill(row: &mut [u16], s: &Span<4>) {
        let p = Pairs::of(s);
        let (mut l, mut a) = (p.lanes, p.anchor);
        for block in row.chunks_mut(2 * BLOCK_PAIRS) {
            let end = platform::pair_run(l, p.step, block);
            if block.len() & 1 != 0 {
                if let Some(p) = block.last_mut() {
                    *p = platform::pack_pair(end) as u16;
                }
            }
            l = pair_lanes(a, p.d);
            a = next_anchor(a, p.d);
        }
    }
}

/// The lanes of the pair at planes `a`: its first pixel in the low halves.
#[inline(always)]
fn pair_lanes(a: [i32; 3], d: [i32; 3]) -> [u32; 3] {
    let (l0, l1) = (lanes(a), lanes(add3(a, d)));
    [0, 1, 2].map(|k| l0[k].wrapping_add(l1[k] << 16))
}

/// The planes a block on from `a`.
#[inline(always)]
fn next_anchor(a: [i32; 3], d: [i32; 3]) -> [i32; 3] {
    [0, 1, 2].map(|k| a[k].wrapping_add(d[k].wrapping_mul(2 * BLOCK_PAIRS as i32)))
}

#[inline(always)]
fn add3(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    [0, 1, 2].map(|k| a[k].wrapping_add(b[k]))
}

/// One colour for the whole triangle.
pub(crate) struct Flat {
    /// The undithered colour.
    pub(crate) plain: u16,
    /// The shade, for dithering.
    pub(crate) shade: Shade,
    /// Dithering on.
    pub(crate) dither: bool,
}

impl Shader<1> for Flat {
    #[inline(always)]
    fn pixel(&self, _: &[i32; 1], x: i32, y: i32) -> u16 {
        if self.dither {
            dither_shade(self.shade, x, y)
        } else {
            self.plain
        }
    }
}

/// Phong shading: attributes 1–3 the normal, 4–6 the eye position
/// relative to `origin` and shifted right by `shift` (`src/shade.rs`).
pub(crate) struct Phong<'l, S: Specular, V: Viewer, L: LightSet> {
    lighting: &'l Lighting<S, V, L>,
    origin: [i64; 3],
    shift: u32,
    /// `origin` as `i32` where `shift` is 0 (a triangle or piece less than
    /// a unit of the world across: the usual one) and it fits `i32`
    /// (corners are `I8F24` eye positions or mixes of them, so it does;
    /// the test keeps the form exact for any origin): the position is
    /// then an `i32` sum, saturating as the clamp of the `i64` one.
    near: Option<[i32; 3]>,
    dither: bool,
}

impl<'l, S: Specular, V: Viewer, L: LightSet> Phong<'l, S, V, L> {
    /// The shader of positions `origin + (a >> 4) << shift`.
    pub(crate) fn new(
        lighting: &'l Lighting<S, V, L>,
        origin: [i64; 3],
        shift: u32,
        dither: bool,
    ) -> Self {
        let fits = origin.iter().all(|&o| i32::try_from(o).is_ok());
        Phong {
            lighting,
            origin,
            shift,
            near: (fits && shift == 0).then(|| origin.map(|o| o as i32)),
            dither,
        }
    }
}

impl<S: Specular, V: Viewer, L: LightSet> Shader<7> for Phong<'_, S, V, L> {
    #[inline]
    fn pixel(&self, a: &[i32; 7], x: i32, y: i32) -> u16 {
        // The planes lie within 2¹⁵·² units of their vertex values'
        // range (`src/setup.rs`): the normal's between unit vectors (any
        // scale normalises), the position's between the corners'.
        let p = match self.near {
            Some(o) => [4, 5, 6].map(|k| (a[k] >> 4).saturating_add(o[k - 4])),
            None => [4, 5, 6].map(|k| {
                let v = (((a[k] >> 4) as i64) << self.shift) + self.origin[k - 4];
                saturate_i32(v)
            }),
        };
        let shade = self.lighting.shade_pixel(p, [a[1], a[2], a[3]]);
        if self.dither {
            dither_shade(shade, x, y)
        } else {
            RawU16::from(shade.to_rgb565()).into_inner()
        }
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

/// Steps the attributes from `first` on by one pixel.
#[inline(always)]
fn step<const N: usize>(a: &mut [i32; N], d: &[i32; N], first: usize) {
    for k in first..N {
        a[k] = a[k].wrapping_add(d[k]);
    }
}

/// Where a draw's spans go: spans in the set-up's coordinates (pixels from
/// its origin, at a target pixel the output knows).
pub(crate) trait Out {
    /// The target's error.
    type Error;

    /// Draws span `s` through depth test `D` with colours from `sh`
    /// (attribute 0 the depth); returns the pixels written.
    fn span<const N: usize, D: DepthTest, Sh: Shader<N>>(
        &mut self,
        depth: &mut D,
        s: &Span<N>,
        sh: &Sh,
    ) -> Result<u32, Self::Error>;

    /// Moves the set-up's origin by `by` pixels (a big target's tile on
    /// the rare path, `src/clip.rs`).
    fn moved(&mut self, by: (i32, i32));

    /// Finds, once a draw (or a band), whether every pixel of `rect` lies
    /// in a colour store and `depth`'s store laid out alike, so that
    /// [`Out::row_stores`] may hand them out for the draw's rows.
    #[inline(always)]
    fn fit_rows<D: DepthTest>(&mut self, depth: &mut D, rect: &Rect) {
        let _ = (depth, rect);
    }

    /// Column 0 of row `y` in the colour store and in `depth`'s, and the
    /// bytes from a row to the next, where [`Out::fit_rows`] found the
    /// draw's `rect` in both stores (and the origin has not moved since):
    /// every row of that rect, at each of its columns, lies in both.
    /// `depth` is the draw's, that `fit_rows` was asked with.
    #[inline(always)]
    fn row_stores<D: DepthTest>(&mut self, depth: &mut D, y: i32) -> Option<RowStores> {
        let _ = (depth, y);
        None
    }

    /// Draws the spans of `rows` (table row `j` is row `y + j`, `dy + j`
    /// below the planes' first, its columns within `cols`) through depth
    /// test `D` with colours from `sh`; returns the pixels written.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn rows<const N: usize, D: DepthTest, Sh: Shader<N>>(
        &mut self,
        depth: &mut D,
        rows: &[Row],
        (y, dy): (i32, i32),
        cols: (i32, i32),
        planes: &Planes<N>,
        sh: &Sh,
    ) -> Result<u32, Self::Error> {
        let _ = cols;
        each_span(self, depth, rows, (y, dy), planes, sh)
    }
}

/// [`Out::rows`] span by span.
#[inline(always)]
fn each_span<const N: usize, O: Out + ?Sized, D: DepthTest, Sh: Shader<N>>(
    out: &mut O,
    depth: &mut D,
    rows: &[Row],
    (y, dy): (i32, i32),
    planes: &Planes<N>,
    sh: &Sh,
) -> Result<u32, O::Error> {
    let mut written = 0u32;
    for (j, r) in rows.iter().enumerate() {
        if r.n > 0 {
            let span = Span {
                y: y + j as i32,
                x0: r.x0,
                n: r.n as u32,
                dy: dy + j as i32,
                planes,
            };
            written += out.span(depth, &span, sh)?;
        }
    }
    Ok(written)
}

/// Pixels in memory: rows `y0 ..` of a `width`-pixel-wide target, row-major
/// (a [`Framebuffer`](crate::framebuffer::Framebuffer)'s or a band's),
/// with the set-up's origin at target pixel `origin`.
pub(crate) struct Memory<'b> {
    buf: &'b mut [u16],
    width: u32,
    y0: u32,
    origin: (i32, i32),
    /// The index of the set-up's origin pixel in `buf` (negative in a band
    /// below it: wrapping).
    at: u32,
    /// The `at` for which [`Out::fit_rows`] found the draw's rect in both
    /// stores.
    fit: Option<u32>,
}

/// Column 0 of a row in a colour and a depth store laid out alike, and
/// the bytes from a row to the next ([`Out::row_stores`]).
pub(crate) struct RowStores {
    pub(crate) colour: *mut u16,
    pub(crate) depth: *mut u16,
    pub(crate) stride: u32,
}

impl<'b> Memory<'b> {
    /// Rows `y0 ..` of a `width`-pixel-wide target (at most 2²⁰ × 2²⁰
    /// pixels) in `buf`, the set-up's origin at target pixel `origin`.
    pub(crate) fn new(buf: &'b mut [u16], width: u32, y0: u32, origin: (i32, i32)) -> Self {
        let mut m = Memory {
            buf,
            width,
            y0,
            origin,
            at: 0,
            fit: None,
        };
        m.moved((0, 0));
        m
    }
}

impl Out for Memory<'_> {
    type Error = core::convert::Infallible;

    #[inline(always)]
    fn span<const N: usize, D: DepthTest, Sh: Shader<N>>(
        &mut self,
        depth: &mut D,
        s: &Span<N>,
        sh: &Sh,
    ) -> Result<u32, Self::Error> {
        // The walk keeps spans inside the target's rows and columns (at most
        // 2²⁰ each): the index is exact in wrapping `u32` arithmetic.
        let start = (s.y as u32)
            .wrapping_mul(self.width)
            .wrapping_add(s.x0 as u32)
            .wrapping_add(self.at) as usize;
        let end = start + s.n as usize;
        let Some(row) = self.buf.get_mut(start..end) else {
            return Ok(0);
        };
        let at = (s.x0 + self.origin.0, s.y + self.origin.1);
        if !D::ENABLED {
            sh.fill(row, s, at);
            return Ok(s.n);
        }
        // A depth store laid out as the colour (a buffer of the target's
        // width, a band of the same rows) takes the same index.
        let zrow = match depth.flat() {
            Some((z, w, y0)) if w == self.width && y0 == self.y0 => z.get_mut(start..end),
            _ => Some(depth.row(at.1 as u32, at.0 as u32, s.n)),
        };
        Ok(zrow.map_or(0, |z| sh.fill_depth(row, z, s, at)))
    }

    /// A shader with a loop of the platform's over a table, with a depth
    /// store laid out as the colour, runs it on the table at once: checked
    /// once that every row's span, within `cols`, lies in both buffers.
    #[inline(always)]
    fn rows<const N: usize, D: DepthTest, Sh: Shader<N>>(
        &mut self,
        depth: &mut D,
        rows: &[Row],
        (y, dy): (i32, i32),
        cols: (i32, i32),
        planes: &Planes<N>,
        sh: &Sh,
    ) -> Result<u32, Self::Error> {
        if D::ENABLED {
            // Where the draw's rect was found in both stores, which hold
            // every row of the set-up's (within the rect's columns).
            if let Some(at) = self.row_stores(depth, y) {
                // SAFETY: the rows and their columns lie in the rect that
                // `fit_rows` found in both stores; `at` is row `y`'s.
                if let Some(w) = unsafe { sh.rows_stored(planes, dy, rows, &at) } {
                    return Ok(w);
                }
            }
            if let Some((zbuf, w, y0)) = depth.flat() {
                if w == self.width && y0 == self.y0 {
                    // The index of column 0 of the first and last rows.
                    let first = (y as u32).wrapping_mul(self.width).wrapping_add(self.at) as i64;
                    // At most 31 rows of at most 2²⁰ pixels: the product
                    // fits u32 (a 64-bit product is a call on ARMv6-M).
                    let last = first + ((rows.len() as u32).saturating_sub(1) * self.width) as i64;
                    let len = self.buf.len().min(zbuf.len()) as i64;
                    if first + cols.0 as i64 >= 0 && last + (cols.1 as i64) < len {
                        if let Some(w) =
                            sh.rows_depth(planes, dy, rows, self.buf, zbuf, first, self.width)
                        {
                            return Ok(w);
                        }
                    }
                }
            }
        }
        each_span(self, depth, rows, (y, dy), planes, sh)
    }

    fn fit_rows<D: DepthTest>(&mut self, depth: &mut D, rect: &Rect) {
        self.fit = None;
        if !D::ENABLED || rect.r0 > rect.r1 || rect.c0 > rect.c1 {
            return;
        }
        let Some((zbuf, w, y0)) = depth.flat() else {
            return;
        };
        if w != self.width || y0 != self.y0 {
            return;
        }
        // Row r's column 0 at `first(r)`, as `rows` indexes it; linear from
        // the rect's first row to its last (no wrap between: their
        // distance is the exact one), so that every pixel of the rect lies
        // between its first row's first column and its last row's last.
        let first = |r: i32| (r as u32).wrapping_mul(self.width).wrapping_add(self.at) as i64;
        let (a, b) = (first(rect.r0), first(rect.r1));
        let len = self.buf.len().min(zbuf.len()) as i64;
        if b - a == (rect.r1 - rect.r0) as i64 * self.width as i64
            && a + rect.c0 as i64 >= 0
            && b + (rect.c1 as i64) < len
        {
            self.fit = Some(self.at);
        }
    }

    #[inline(always)]
    fn row_stores<D: DepthTest>(&mut self, depth: &mut D, y: i32) -> Option<RowStores> {
        if self.fit != Some(self.at) {
            return None;
        }
        let (zbuf, _, _) = depth.flat()?;
        // Inside both stores for a row of the fitted rect (`fit_rows`).
        let first = (y as u32).wrapping_mul(self.width).wrapping_add(self.at) as usize;
        Some(RowStores {
            colour: self.buf.as_mut_ptr().wrapping_add(first),
            depth: zbuf.as_mut_ptr().wrapping_add(first),
            stride: 2 * self.width,
        })
    }

    fn moved(&mut self, by: (i32, i32)) {
        self.origin = (self.origin.0 + by.0, self.origin.1 + by.1);
        self.at = (self.origin.1 as u32)
            .wrapping_sub(self.y0)
            .wrapping_mul(self.width)
            .wrapping_add(self.origin.0 as u32);
    }
}

/// The pixels of a span from target pixel `at` on, with attributes from `a`
/// stepped by `d` (attribute 0, the depth, not stepped).
///
/// Out of line: the pixel loop gets a register file of its own, not the
/// row walk's state (inlined, a Cortex-M4 reloaded the steps from the
/// stack at every pixel, and a span's entry and exit spilled and reloaded
/// the walk).
#[inline(never)]
fn fill<const N: usize, Sh: Shader<N>>(
    sh: &Sh,
    row: &mut [u16],
    a: &[i32; N],
    d: &[i32; N],
    at: (i32, i32),
) {
    let (mut a, (mut x, y)) = (*a, at);
    for p in row.iter_mut() {
        *p = sh.pixel(&a, x, y);
        step(&mut a, d, 1);
        x = x.wrapping_add(1);
        platform::keep_loop_rolled();
    }
}

/// [`fill`] through the depth test, against and into the stored depths
/// `zrow`: the pixels written.
///
/// While every pixel passes (a closed mesh with culling: all of them), a
/// loop that counts nothing; from the first that fails on, one that counts
/// what it writes. (Counting in the first loop takes a register it does
/// not have on a Cortex-M4 with the frame pointer in `r7`: four planes,
/// their steps, two pointers and a count, and two for the pixel.)
#[inline(never)]
fn fill_depth<const N: usize, Sh: Shader<N>>(
    sh: &Sh,
    row: &mut [u16],
    zrow: &mut [u16],
    a: &[i32; N],
    d: &[i32; N],
    at: (i32, i32),
) -> u32 {
    let (mut a, (mut x, y)) = (*a, at);
    let n = row.len().min(zrow.len());
    let (row, zrow) = (&mut row[..n], &mut zrow[..n]);
    let mut k = 0;
    while k < n {
        let d16 = depth16(a[0]);
        if d16 >= zrow[k] as i32 {
            break;
        }
        zrow[k] = d16 as u16;
        row[k] = sh.pixel(&a, x, y);
        step(&mut a, d, 0);
        x = x.wrapping_add(1);
        k += 1;
        platform::keep_loop_rolled();
    }
    let mut written = k as u32;
    while k < n {
        let d16 = depth16(a[0]);
        if d16 < zrow[k] as i32 {
            zrow[k] = d16 as u16;
            row[k] = sh.pixel(&a, x, y);
            written += 1;
        }
        step(&mut a, d, 0);
        x = x.wrapping_add(1);
        k += 1;
        platform::keep_loop_rolled();
    }
    written
}

/// Any `DrawTarget`: one `fill_contiguous` a span (or a run of pixels that
/// pass the depth test), at the target's origin offset.
pub(crate) struct TargetSink<'t, T> {
    pub(crate) target: &'t mut T,
    /// The target's bounding box's top-left corner.
    pub(crate) corner: Point,
    /// The set-up's origin, in pixels from that corner.
    pub(crate) origin: (i32, i32),
}

impl<T: DrawTarget<Color = Rgb565>> TargetSink<'_, T> {
    /// Sends `n` pixels of target row `y` from column `x`.
    #[inline]
    fn fill(
        &mut self,
        x: u32,
        y: u32,
        n: u32,
        colours: impl Iterator<Item = u16>,
    ) -> Result<(), T::Error> {
        // The renderer checks that the target's box ends within `i32`.
        let at = Point::new(
            self.corner.x.wrapping_add(x as i32),
            self.corner.y.wrapping_add(y as i32),
        );
        let area = Rectangle::new(at, Size::new(n, 1));
        self.target
            .fill_contiguous(&area, colours.map(|c| Rgb565::from(RawU16::new(c))))
    }
}

impl<T: DrawTarget<Color = Rgb565>> Out for TargetSink<'_, T> {
    type Error = T::Error;

    fn span<const N: usize, D: DepthTest, Sh: Shader<N>>(
        &mut self,
        depth: &mut D,
        s: &Span<N>,
        sh: &Sh,
    ) -> Result<u32, T::Error> {
        let (x, y) = ((s.x0 + self.origin.0) as u32, (s.y + self.origin.1) as u32);
        let d = s.step();
        if !D::ENABLED {
            self.fill(x, y, s.n, sh.colours(s, (x as i32, y as i32)))?;
            return Ok(s.n);
        }
        // Runs of pixels that pass the depth test, each tested (and its
        // depths stored) before its pixels are sent.
        let zrow = depth.row(y, x, s.n);
        let n = s.n.min(zrow.len() as u32);
        let mut a = s.start();
        let (mut k, mut written) = (0u32, 0u32);
        while k < n {
            while k < n && depth16(a[0]) >= zrow[k as usize] as i32 {
                step(&mut a, d, 0);
                k += 1;
            }
            let (first, from) = (k, a);
            while k < n {
                let (d16, z) = (depth16(a[0]), &mut zrow[k as usize]);
                if d16 >= *z as i32 {
                    break;
                }
                *z = d16 as u16;
                step(&mut a, d, 0);
                k += 1;
            }
            if k > first {
                let mut b = from;
                let mut px = (x + first) as i32;
                let colours = (first..k).map(|_| {
                    let c = sh.pixel(&b, px, y as i32);
                    step(&mut b, d, 0);
                    px = px.wrapping_add(1);
                    c
                });
                self.fill(x + first, y, k - first, colours)?;
                written += k - first;
            }
        }
        Ok(written)
    }

    fn moved(&mut self, by: (i32, i32)) {
        self.origin = (self.origin.0 + by.0, self.origin.1 + by.1);
    }
}

//! Band rendering: a whole frame, depth test included, through a colour
//! buffer (and a depth buffer) of a few rows.
//!
//! A draw into [`Bands`] ([`Shaded::draw`](crate::Shaded::draw)) renders the
//! frame in horizontal bands of `W × h` pixels, top to bottom. For each
//! band it clears the caller's colour band to the background and the depth
//! band to the far value, rasterizes the triangles that touch the band (the
//! same pipeline as a whole frame's, with its rows limited to the band),
//! and hands the finished band to the `DrawTarget` as one `fill_contiguous`
//! over the band's rectangle: one address window per band on an SPI
//! display.
//!
//! # Identical pixels
//! The viewport (projection, window mapping, the set-up's origin) is the
//! whole target's for every band; only the rows drawn change. A triangle
//! is set up again in each band it meets, with integer edges and planes
//! that give each row the same span and values as the whole-frame walk
//! (`src/walk.rs`); the
//! triangles of a band are drawn in mesh order, and each pixel is drawn by
//! exactly one band: the frame is bit for bit the whole-frame render
//! (`host/tests/suite/bands.rs` checks it on the standard scenes).
//!
//! # Vertex modes
//! - [`Cached`]: the vertices are transformed and projected once per frame
//!   into a caller-provided [`CachedVertex`] per mesh vertex (16 bytes: window
//!   position, depth, colour, flags; the whole frame's store), and lit once,
//!   when a visible triangle first needs them.
//! - [`Recomputed`]: no per-vertex storage; a vertex is transformed,
//!   projected and lit again whenever it is not among the last ones kept
//!   in a small table on the stack (64 entries by mesh index, direct
//!   mapped: consecutive triangles share most of their vertices, and a
//!   band revisits its runs' triangles).
//!
//! # Finding a band's triangles
//! A frame's triangles are split into [`CHUNKS`] runs of consecutive
//! triangles; a first pass records each run's rows (the union of its
//! visible triangles' rows, or the whole viewport for one with a vertex
//! for the rare path) in a table on the stack, and which of the run's
//! first 32 triangles can draw anything at all (a bit mask: back faces
//! when culling, triangles without area and triangles off-screen cannot).
//! A band visits only the runs whose rows it meets, skips the masked-out
//! triangles, and rejects the others by their rows before any set-up. Meshes whose consecutive triangles are close on screen (grids,
//! spheres, most scanned meshes) make this cheap; the worst case is every
//! triangle tested in every band.
//!
//! # Memory
//! The caller provides the colour band (`W × h` `u16`), the depth band
//! (`W × h` `u16`, if the scene has a depth test) and, in cached mode, one
//! [`CachedVertex`] per mesh vertex. A draw call keeps the run table
//! ([`CHUNKS`] × 12 bytes), in recomputed mode the table of recent
//! vertices (1 280 bytes), and a triangle's set-up on the stack; a
//! triangle that spans several bands is set up again in each (the 32-bit
//! set-up is exact row by row, so the pixels are the whole frame's).

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::{Point, RawData, Size};
use embedded_graphics::primitives::Rectangle;

use crate::depth::{DepthBand, DepthTest, NoDepth};
use crate::illumination::Viewer;
use crate::light::LightSet;
use crate::material::Specular;
use crate::mesh::Mesh;
use crate::options::{check_bounds, DrawStats, RenderError, ShadingKind, ShadingMode};
use crate::render::Prepared;
use crate::shade::Frame;
use crate::span::{Memory, Out};
use crate::vertex::CachedVertex;
pub use crate::vertex::{Cached, Recomputed, VertexMode};

/// How many runs of consecutive triangles a frame is split into for
/// finding each band's triangles (a table of `CHUNKS × 12` bytes on the
/// stack: rows and a visibility mask per run).
///
/// ```
/// use fixshade::band::CHUNKS;
/// // Per run: its first and last row (two i32) and a 32-bit mask.
/// assert_eq!(CHUNKS * (2 * 4 + 4), 1536);
/// ```
pub const CHUNKS: usize = 128;

/// A depth test the band renderer can move down the frame: [`NoDepth`] or
/// [`DepthBand`].
///
/// ```
/// use fixshade::band::BandDepth;
/// use fixshade::depth::{DepthBand, NoDepth};
/// assert_eq!(NoDepth.capacity(), u64::MAX);
/// assert!(NoDepth.start_band(1 << 20, 0, 1 << 20)); // no storage, never too small
/// let mut z = [0u16; 64];
/// let mut band = DepthBand::new(&mut z);
/// assert_eq!(BandDepth::capacity(&band), 64);
/// assert!(band.start_band(32, 0, 2));
/// assert!(!band.start_band(32, 2, 3)); // 96 depths do not fit in 64
/// ```
pub trait BandDepth: DepthTest {
    /// How many depths the storage holds (unbounded for [`NoDepth`]).
    fn capacity(&self) -> u64;
    /// Makes this the band of rows `y0 .. y0 + rows` of a `width`-wide
    /// viewport, cleared to the far value; `false` if it does not fit.
    fn start_band(&mut self, width: u32, y0: u32, rows: u32) -> bool;
}

impl<Z: BandDepth> BandDepth for &mut Z {
    #[inline(always)]
    fn capacity(&self) -> u64 {
        (**self).capacity()
    }
    #[inline(always)]
    fn start_band(&mut self, width: u32, y0: u32, rows: u32) -> bool {
        (**self).start_band(width, y0, rows)
    }
}

impl BandDepth for NoDepth {
    #[inline(always)]
    fn capacity(&self) -> u64 {
        u64::MAX
    }
    #[inline(always)]
    fn start_band(&mut self, _: u32, _: u32, _: u32) -> bool {
        true
    }
}

impl BandDepth for DepthBand<'_> {
    fn capacity(&self) -> u64 {
        DepthBand::capacity(self) as u64
    }
    fn start_band(&mut self, width: u32, y0: u32, rows: u32) -> bool {
        self.start(width, y0, rows)
    }
}

/// A draw's output in bands: the display, the caller's colour band
/// (`rows` rows of the display's width, raw RGB565), the background each
/// band is cleared to, and which bands this worker draws.
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565};
/// use fixshade::band::Bands;
/// let mut display = MockDisplay::<Rgb565>::new();
/// let mut colour = [0u16; 64 * 16];
/// // Bands of 16 rows; this worker draws the 1st, 3rd, … of them.
/// let bands = Bands::new(&mut display, &mut colour, 16).interleaved(0, 2);
/// # let _ = bands;
/// ```
#[derive(Debug)]
pub struct Bands<'t, 'b, T> {
    target: &'t mut T,
    colour: &'b mut [u16],
    height: u32,
    background: Rgb565,
    worker: u32,
    workers: u32,
}

impl<'t, 'b, T> Bands<'t, 'b, T> {
    /// Bands of `rows` rows into `target` through `colour`, which holds at
    /// least `width × rows` pixels (`rows` capped at the target's height);
    /// a black background; every band drawn.
    pub fn new(target: &'t mut T, colour: &'b mut [u16], rows: u32) -> Self {
        Bands {
            target,
            colour,
            height: rows,
            background: Rgb565::new(0, 0, 0),
            worker: 0,
            workers: 1,
        }
    }

    /// The colour of pixels no triangle covers.
    #[must_use]
    pub fn with_background(self, background: Rgb565) -> Self {
        Bands { background, ..self }
    }

    /// Draws only bands `worker`, `worker + workers`, `worker + 2·workers`,
    /// … (counted from the top, from 0), so that `workers` workers (cores,
    /// threads), each with its own colour band and vertex storage, split a
    /// frame; together they send every band once, each exactly as one
    /// worker drawing all of them would. `workers` 0 counts as 1; a
    /// `worker` at or above `workers` draws nothing.
    #[must_use]
    pub fn interleaved(self, worker: u32, workers: u32) -> Self {
        Bands {
            worker,
            workers: workers.max(1),
            ..self
        }
    }

    /// The display the bands go to.
    pub fn target(&mut self) -> &mut T {
        self.target
    }
}

/// The rows `[lo, hi]` (from the set-up's origin) of a triangle's pixel
/// centres, from its window `y`s (1/16 pixel).
#[inline(always)]
fn rows_of(y: [i32; 3]) -> (i32, i32) {
    let miny = y[0].min(y[1]).min(y[2]);
    let maxy = y[0].max(y[1]).max(y[2]);
    ((miny + 7) >> 4, (maxy - 8) >> 4)
}

/// The rows a triangle may draw (from the set-up's origin), or `None` when
/// it draws nothing (no area, culled, or no pixel centre in the target). A
/// triangle with a vertex for the rare path may draw any row. A sliver
/// that snapping turned over is kept here and dropped when a band draws it
/// (`src/triangle.rs` decides that for the whole frame and the bands
/// alike): this pass only spares work.
#[inline(always)]
fn visible_rows<S: Specular, V: Viewer, L: LightSet>(
    f: &Frame<'_, '_, S, V, L>,
    v: [CachedVertex; 3],
    cull: bool,
) -> Option<(i32, i32)> {
    let r = &f.rect;
    let [Some(a), Some(b), Some(c)] = v.map(|v| v.window()) else {
        return Some((r.r0, r.r1));
    };
    let area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if area == 0 || (area > 0 && cull) {
        return None;
    }
    let (lo, hi) = rows_of([a[1], b[1], c[1]]);
    let (xlo, xhi) = rows_of([a[0], b[0], c[0]]);
    let (lo, hi) = (lo.max(r.r0), hi.min(r.r1));
    if lo > hi || xlo > r.c1 || xhi < r.c0 {
        return None;
    }
    Some((lo, hi))
}

/// Rows per band actually used (at most the viewport's height) and the
/// checks of the caller's buffers.
fn check_band<E, T, D: BandDepth, X: VertexMode>(
    bb: Rectangle,
    bands: &Bands<T>,
    depth: &D,
    vertices: &mut X,
    n_vertices: usize,
) -> Result<u32, RenderError<E>> {
    let size = bb.size;
    check_bounds(&bb)?;
    if X::CACHED && vertices.cache().len() < n_vertices {
        return Err(RenderError::CacheTooSmall);
    }
    let rows = bands.height.min(size.height);
    let need = size.width as u64 * rows as u64;
    if bands.height == 0 || (bands.colour.len() as u64) < need {
        return Err(RenderError::BandTooSmall);
    }
    if D::ENABLED && depth.capacity() < need {
        return Err(RenderError::DepthTooSmall);
    }
    Ok(rows)
}

impl<S: Specular, V: Viewer, L: LightSet> Prepared<'_, S, V, L> {
    /// Renders the frame into `bands`' target band by band (see the
    /// [module docs](crate::band)): the pixels are those that clearing the
    /// target to the background, the depth buffer to the far value and
    /// drawing the whole frame gives.
    ///
    /// `depth` is [`NoDepth`] or a [`DepthBand`] of at least `width × h`
    /// values; `vertices` is [`Recomputed`] or [`Cached`] with one
    /// [`CachedVertex`] per mesh vertex. Each band goes to the target as one
    /// `fill_contiguous` of `width × h` pixels (the last band may be
    /// shorter). Buffers too small are errors and nothing is drawn. The
    /// counts are summed over the bands (a triangle drawn in two bands
    /// counts twice in `drawn`).
    pub(crate) fn draw_bands<M, T, D, X>(
        &self,
        mesh: &Mesh,
        bands: &mut Bands<T>,
        depth: &mut D,
        vertices: &mut X,
    ) -> Result<DrawStats, RenderError<T::Error>>
    where
        M: ShadingMode,
        T: DrawTarget<Color = Rgb565>,
        D: BandDepth,
        X: VertexMode,
    {
        mesh.validate().map_err(RenderError::Mesh)?;
        if M::KIND != ShadingKind::Flat && mesh.normals.is_none() {
            return Err(RenderError::NoNormals);
        }
        let bb = bands.target.bounding_box();
        let size = bb.size;
        let n = mesh.positions.len();
        let h = check_band(bb, bands, depth, vertices, n)?;
        let mut stats = DrawStats {
            triangles: u32::try_from(mesh.indices().len()).unwrap_or(u32::MAX),
            ..DrawStats::default()
        };
        let Some(mut frame) = self.frame(mesh, size)? else {
            return Ok(stats);
        };
        let cull = self.options().cull;
        let cache = &mut vertices.cache()[..if X::CACHED { n } else { 0 }];
        if X::CACHED {
            frame.stage.project_all(cache);
        }
        let runs = Runs::new(mesh.indices().len());
        let mut recent = RecentVertices::new();
        let mut bounds = [(i32::MAX, i32::MIN); CHUNKS];
        // Bit j: triangle j of the run may draw (j ≥ 32: always visited).
        let mut visible = [0u32; CHUNKS];
        for (t, tri) in mesh.indices().iter().enumerate() {
            let idx = tri.map(|i| i as usize);
            let v = if X::CACHED {
                idx.map(|i| cache.get(i).copied().unwrap_or_default())
            } else {
                recent.corners(&frame, idx)
            };
            if let Some((lo, hi)) = visible_rows(&frame, v, cull) {
                let (r, j) = (t / runs.per, t % runs.per);
                let b = &mut bounds[r];
                *b = (b.0.min(lo), b.1.max(hi));
                if j < 32 {
                    visible[r] |= 1 << j;
                }
            }
        }
        let job = Job {
            mesh,
            bb,
            h,
            runs,
            bounds: &bounds,
            visible: &visible,
        };
        job.run::<M, X, _, _, _, _, _>(&mut frame, cache, &mut recent, bands, depth, &mut stats)?;
        Ok(stats)
    }
}

/// A frame's band loop: what the first pass found.
struct Job<'a, 'm> {
    mesh: &'a Mesh<'m>,
    /// The target's box, read once per draw: a target whose box changes
    /// between calls cannot make a band disagree with its checked buffers.
    bb: Rectangle,
    h: u32,
    runs: Runs,
    bounds: &'a [(i32, i32); CHUNKS],
    visible: &'a [u32; CHUNKS],
}

impl Job<'_, '_> {
    /// Renders the bands top to bottom and hands each to `target`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn run<M, X, T, D, S, V, L>(
        &self,
        frame: &mut Frame<'_, '_, S, V, L>,
        cache: &mut [CachedVertex],
        recent: &mut RecentVertices,
        bands: &mut Bands<T>,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), RenderError<T::Error>>
    where
        M: ShadingMode,
        X: VertexMode,
        T: DrawTarget<Color = Rgb565>,
        D: BandDepth,
        S: Specular,
        V: Viewer,
        L: LightSet,
    {
        let bb = self.bb;
        let (w, height) = (bb.size.width, bb.size.height);
        let (indices, per) = (self.mesh.indices(), self.runs.per);
        let whole = frame.rect;
        let oy = frame.origin.1;
        // Bands to skip before this worker's next one (none ever for a
        // worker at or past `workers`: at most 2^20 bands).
        let mut skip = if bands.worker < bands.workers {
            bands.worker
        } else {
            u32::MAX
        };
        let mut y0 = 0u32;
        while y0 < height {
            let rows = self.h.min(height - y0);
            // Another worker's band (`Bands::interleaved`).
            let mine = skip == 0;
            skip = if mine { bands.workers - 1 } else { skip - 1 };
            if !mine {
                y0 += rows;
                continue;
            }
            // The band's rows from the set-up's origin.
            let (b0, b1) = (y0 as i32 - oy, (y0 + rows - 1) as i32 - oy);
            frame.rect.r0 = b0;
            frame.rect.r1 = b1;
            // w, rows ≤ 2^20 (check_size): below 2^40, in u64.
            let npx = (w as u64 * rows as u64) as usize;
            let raw_bg = RawU16::from(bands.background).into_inner();
            bands.colour[..npx].fill(raw_bg);
            if !depth.start_band(w, y0, rows) {
                return Err(RenderError::DepthTooSmall);
            }
            let mut out = Memory::new(&mut bands.colour[..npx], w, y0, frame.origin);
            out.fit_rows(depth, &frame.rect);
            for (r, &(lo, hi)) in self.bounds.iter().enumerate() {
                if hi < b0 || lo > b1 {
                    continue;
                }
                let (start, end) = (r * per, ((r + 1) * per).min(indices.len()));
                // The run's first 32 triangles by their set visibility
                // bits, the rest (a run longer than 32) all.
                let mut bits = self.visible[r];
                let first = core::iter::from_fn(move || {
                    let j = bits.trailing_zeros() as usize;
                    bits &= bits.wrapping_sub(1);
                    (j < 32).then_some(j)
                });
                for j in first.chain(32..end.saturating_sub(start)) {
                    let Some(tri) = indices.get(start + j) else {
                        continue;
                    };
                    let idx = tri.map(|i| i as usize);
                    let res = if X::CACHED {
                        band_triangle::<M, _, _, _, _>(
                            frame, cache, idx, idx, &mut out, depth, stats,
                        )
                    } else {
                        let mut three = recent.corners(frame, idx);
                        let res = band_triangle::<M, _, _, _, _>(
                            frame,
                            &mut three,
                            [0, 1, 2],
                            idx,
                            &mut out,
                            depth,
                            stats,
                        );
                        recent.keep(idx, &three);
                        res
                    };
                    let Ok(()) = res;
                }
            }
            let area = Rectangle::new(bb.top_left + Point::new(0, y0 as i32), Size::new(w, rows));
            bands
                .target
                .fill_contiguous(
                    &area,
                    bands.colour[..npx]
                        .iter()
                        .map(|&p| Rgb565::from(RawU16::new(p))),
                )
                .map_err(RenderError::Target)?;
            y0 += rows;
        }
        frame.rect = whole;
        Ok(())
    }
}

/// Runs of consecutive triangles.
struct Runs {
    /// Triangles per run.
    per: usize,
}

impl Runs {
    fn new(triangles: usize) -> Runs {
        Runs {
            per: triangles.div_ceil(CHUNKS).max(1),
        }
    }
}

/// Entries of [`RecentVertices`]: 64 vertices, 1 280 bytes of stack.
const MEMO: usize = 64;

/// The recently projected (and lit) vertices of a draw without a vertex
/// store ([`Recomputed`]): a small direct-mapped table by mesh index, on
/// the stack. Consecutive triangles share most of their vertices, and a
/// band revisits its runs' triangles, so most corners are found here
/// instead of being projected (and lit) again. An entry holds what
/// [`Stage::project`](crate::vertex::Stage::project) gives and what
/// lighting adds to it, so the pixels are those of projecting each time.
struct RecentVertices {
    tag: [u32; MEMO],
    v: [CachedVertex; MEMO],
}

impl RecentVertices {
    fn new() -> RecentVertices {
        RecentVertices {
            tag: [u32::MAX; MEMO],
            v: [CachedVertex::new(); MEMO],
        }
    }

    /// The corners of triangle `idx`: from the table, or projected into it.
    #[inline(always)]
    fn corners<S: Specular, V: Viewer, L: LightSet>(
        &mut self,
        f: &Frame<'_, '_, S, V, L>,
        idx: [usize; 3],
    ) -> [CachedVertex; 3] {
        idx.map(|i| {
            let k = i % MEMO;
            if self.tag[k] != i as u32 {
                self.tag[k] = i as u32;
                self.v[k] = f.stage.project(i);
            }
            self.v[k]
        })
    }

    /// Keeps what drawing triangle `idx` added to its corners `three`
    /// (their lit colours).
    #[inline(always)]
    fn keep(&mut self, idx: [usize; 3], three: &[CachedVertex; 3]) {
        for (i, v) in idx.iter().zip(three) {
            let k = i % MEMO;
            if self.tag[k] == *i as u32 {
                self.v[k] = *v;
            }
        }
    }
}

/// Draws triangle `vertex` (its corners at `slot` in `cache`) in the
/// current band, after rejecting it by its rows.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn band_triangle<M, D, S, V, L>(
    f: &Frame<'_, '_, S, V, L>,
    cache: &mut [CachedVertex],
    slot: [usize; 3],
    vertex: [usize; 3],
    out: &mut Memory,
    depth: &mut D,
    stats: &mut DrawStats,
) -> Result<(), core::convert::Infallible>
where
    M: ShadingMode,
    D: DepthTest,
    S: Specular,
    V: Viewer,
    L: LightSet,
{
    let w = slot.map(|s| cache.get(s).and_then(|v| v.window()));
    if let [Some(a), Some(b), Some(c)] = w {
        let (lo, hi) = rows_of([a[1], b[1], c[1]]);
        if hi < f.rect.r0 || lo > f.rect.r1 {
            return Ok(());
        }
    }
    if slot.iter().any(|&k| k >= cache.len()) {
        return Ok(());
    }
    // SAFETY: every slot was checked just above.
    unsafe { f.triangle::<M, _, D>(cache, slot, vertex, None, out, depth, stats) }
}

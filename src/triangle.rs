//! One triangle from its three projected vertices to its pieces: culling
//! and the cheap rejections of the lean path, before any lighting.
//!
//! The lean path takes a triangle whose three vertices have kept window
//! positions (in front of the near plane, inside the guard band: see
//! `src/vertex.rs`), in 32-bit arithmetic. Anything else — a vertex behind
//! the near plane or outside the guard band, a draw whose rows do not
//! allow the 32-bit vertex form — goes to the rare path (`src/clip.rs`).
//! The lean path draws the triangle whole
//! ([`Frame::whole`](crate::shade::Frame::whole)), the rare path what
//! clipping leaves of it ([`Frame::pieces`](crate::shade::Frame::pieces));
//! both end in the set-up and the walk. On ARMv7-M a cached Gouraud draw
//! into stores that hold its rows runs the lean path's whole triangle
//! loop in one routine of assembly ([`Frame::gouraud_run`]), which leaves
//! to [`Frame::triangle`] each triangle its tests do not take.
//!
//! # Facing
//! A triangle faces the way its unsnapped window positions do. One that
//! snapping to 1/16 pixel turns over (a sliver thinner than about √2/16
//! pixel) is degenerate and draws nothing, with culling on or off: a back
//! face that snaps to a front face is not drawn over the surface in front
//! of it, and a front face that snaps to a back face is not drawn as a
//! back face. The unsnapped facing is asked only where the snapped area is
//! small enough for snapping to have changed its sign ([`snap_may_flip`]).

use core::mem::MaybeUninit;

use crate::clip;
use crate::depth::DepthTest;
use crate::illumination::Viewer;
use crate::light::LightSet;
use crate::material::Specular;
use crate::num::division::recip_nodes;
use crate::options::{DrawStats, ShadingMode};
use crate::planes::{Planes, Row};
use crate::platform::{self, Found};
use crate::setup::Samples;
use crate::shade::{Corners, Frame};
use crate::span::Out;
use crate::vertex::CachedVertex;
use crate::walk::{EdgeFunctions, CHUNK};

impl<S: Specular, V: Viewer, L: LightSet> Frame<'_, '_, S, V, L> {
    /// Culls, lights and draws one triangle: mesh vertices `vertex`,
    /// projected into `cache[slot]`; `known`, where the caller has found it
    /// (`platform::skip_culled`), the doubled area of its kept window
    /// positions, neither 0 nor culled, for a triangle the lean path takes
    /// (and their box, where the scan makes it).
    /// (The corners are gathered only for a triangle that passes the cheap
    /// tests: built for every triangle, they were stored to the stack for
    /// every triangle.)
    ///
    /// # Safety
    /// Every `slot[k] < cache.len()`: the whole-frame draw hands a
    /// validated mesh's indices into the cache of its vertices
    /// ([`Mesh::validate`] runs before every draw) or `[0, 1, 2]` into
    /// three corners; the bands check theirs. (Three bounds checks a
    /// triangle were 2.7 % of a fine mesh's frame on the Cortex-M0+.)
    ///
    /// [`Mesh::validate`]: crate::mesh::Mesh::validate
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) unsafe fn triangle<M: ShadingMode, O: Out, D: DepthTest>(
        &self,
        cache: &mut [CachedVertex],
        slot: [usize; 3],
        vertex: [usize; 3],
        known: Option<Found>,
        out: &mut O,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), O::Error> {
        debug_assert!(slot.iter().all(|&k| k < cache.len()));
        // SAFETY: the caller's contract.
        let [v0, v1, v2] = slot.map(|k| unsafe { cache.get_unchecked(k) });
        let rare = v0.rare_bits() | v1.rare_bits() | v2.rare_bits();
        // Without the rare path only contained draws get here
        // (`Prepared::frame`), whose every vertex the lean path keeps.
        debug_assert!(platform::CLIP || rare == 0);
        if platform::CLIP && rare != 0 {
            let c = &mut Corners {
                cache,
                slot,
                vertex,
            };
            return clip::triangle::<M, O, D, S, V, L>(self, c, out, depth, stats);
        }
        let area = match known {
            Some(f) => f.area,
            None => {
                let xy = [v0.xy(), v1.xy(), v2.xy()];
                let area = (xy[1][0] - xy[0][0]) * (xy[2][1] - xy[0][1])
                    - (xy[2][0] - xy[0][0]) * (xy[1][1] - xy[0][1]);
                if area == 0 || (area > 0 && self.options.cull) {
                    return Ok(());
                }
                area
            }
        };
        // The positions and depths only where they are read: a triangle
        // culling keeps, whose box the scan has not made or which has few
        // samples (the lean Gouraud set-up reads its entries itself).
        let corners = || [v0.position(), v1.position(), v2.position()];
        let (lo, hi, p) = match known {
            // Each half of the packed corners, sign-extended.
            Some(f) if platform::BOX_IN_SCAN => {
                let xy = |w: u32| ((w as i32) << 16 >> 16, w as i32 >> 16);
                (xy(f.lo), xy(f.hi), None)
            }
            _ => {
                let p = corners();
                let lo = |k: usize| p[0][k].min(p[1][k]).min(p[2][k]);
                let hi = |k: usize| p[0][k].max(p[1][k]).max(p[2][k]);
                ((lo(0), lo(1)), (hi(0), hi(1)), Some(p))
            }
        };
        // The samples the box holds, if any: the cheap test that spares
        // off-screen and tiny triangles their lighting and set-up; the
        // set-up takes them as found here.
        let Some(s) = Samples::of_box(lo, hi, &self.rect).filter(|s| s.cols.0 <= s.cols.1) else {
            return Ok(());
        };
        let (cols, rows) = (s.cols, s.rows);
        // A box of at most 2 × 2 pixel centres: the samples tested one by
        // one, and a triangle that covers none of them (most of a fine
        // mesh's far from the centre of the view) is neither lit nor set up.
        if cols.1 - cols.0 <= 1
            && rows.1 - rows.0 <= 1
            && covers_none(&p.unwrap_or_else(corners), area, cols, rows)
        {
            return Ok(());
        }
        if snap_may_flip(area, (hi.0 - lo.0, hi.1 - lo.1)) && self.turned_over(vertex, area) {
            return Ok(());
        }
        let c = &mut Corners {
            cache,
            slot,
            vertex,
        };
        // SAFETY: the caller's contract: every slot indexes the cache.
        unsafe { self.whole::<M, O, D>(c, p, area, &s, out, depth, stats) }
    }

    /// The cached whole-frame loop of a Gouraud draw in its lean form
    /// ([`platform::gouraud_run`]) where the draw's rect lies in stores
    /// that take its rows directly (`Out::row_stores`): each triangle it
    /// leaves drawn by [`Frame::triangle`], the loop resumed after it.
    /// Returns where the caller's loop goes on: the end of `tris`, or the
    /// triangle after one that left the stores' rect unfit.
    ///
    /// # Safety
    /// `tris` is the validated mesh's triangles, `cache` its vertices'
    /// entries ([`Frame::triangle`]'s contract); without `rare`, no entry
    /// has the rare path's flag.
    #[allow(clippy::too_many_arguments)]
    pub(crate) unsafe fn gouraud_run<M: ShadingMode, O: Out, D: DepthTest>(
        &self,
        cache: &mut [CachedVertex],
        tris: &[[u16; 3]],
        rare: bool,
        out: &mut O,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<*const [u16; 3], O::Error> {
        let (mut at, end) = (tris.as_ptr(), tris.as_ptr_range().end);
        // Nothing done where there is no routine (the caller's loop then
        // takes every triangle) or no stores to hand it.
        let Some(first) = out.row_stores(depth, 0).filter(|_| platform::GOURAUD_RUN) else {
            return Ok(at);
        };
        let mut planes = MaybeUninit::<Planes<4>>::uninit();
        let mut table = [MaybeUninit::<Row>::uninit(); CHUNK];
        let r = &self.rect;
        let o = &self.options;
        let mut run = platform::GouraudRun {
            set_up: platform::GouraudSetUp {
                entries: [core::ptr::null(); 3],
                area: 0,
                first_row: 0,
                last_row: 0,
                nodes: recip_nodes(),
                planes: planes.as_mut_ptr(),
                table: table.as_mut_ptr().cast::<Row>(),
                cbase: core::ptr::null_mut(),
                stride: first.stride,
                zbase: core::ptr::null_mut(),
            },
            rect: [r.c0, r.c1, r.r0, r.r1],
            cbase: first.colour,
            zbase: first.depth,
            frame: (self as *const Self).cast(),
            stats: core::ptr::null_mut(),
            light: Self::light_corner,
            mode: o.cull as u32 | (rare as u32) << 1 | (o.two_sided as u32) << 2,
            area: 0,
            lo: 0,
            hi: 0,
            drawn: 0,
            pixels: 0,
        };
        let resume = loop {
            // Made anew for each run: the triangles between write through
            // `out`, `cache` and `stats`.
            run.stats = (stats as *mut DrawStats).cast();
            // SAFETY: the contract above; the set-up's constants are a
            // table of 32 rows, a slot for the planes and the reciprocals'
            // nodes, the stores hold the rect (`row_stores`, made anew
            // after a triangle drawn through `out`), and `light_corner`
            // is given this frame and the draw's statistics.
            let next =
                unsafe { platform::gouraud_run(&mut run, at, end, cache.as_mut_ptr().cast()) };
            if next == end {
                break end;
            }
            // SAFETY: `next` lies in `tris`, before its end.
            let idx = unsafe { *next }.map(usize::from);
            let found = Found {
                area: run.area,
                lo: run.lo,
                hi: run.hi,
            };
            // SAFETY: the mesh is validated: its indices index the cache.
            unsafe { self.triangle::<M, O, D>(cache, idx, idx, Some(found), out, depth, stats)? };
            // SAFETY: `next` is before `end`.
            at = unsafe { next.add(1) };
            let Some(s) = out.row_stores(depth, 0) else {
                break at;
            };
            (run.cbase, run.zbase) = (s.colour, s.depth);
        };
        // The loop's counts, added once (saturating additions of counts:
        // the same sums in any order).
        stats.drawn = stats.drawn.saturating_add(run.drawn);
        stats.pixels = stats.pixels.saturating_add(run.pixels);
        Ok(resume)
    }

    /// [`platform::gouraud_run`]'s lighting of a corner: mesh vertex `i`,
    /// its entry `v`, for the front face; 1 where the entry now holds that
    /// colour ([`Stage::lit_front`](crate::vertex::Stage::lit_front)).
    ///
    /// # Safety
    /// `frame` is this frame, `stats` the draw's statistics and `v` the
    /// cache entry of vertex `i`, none of them borrowed elsewhere.
    unsafe extern "C" fn light_corner(frame: *const (), stats: *mut (), v: *mut u8, i: u32) -> u32 {
        // SAFETY: the contract above.
        let (frame, stats, v) = unsafe {
            (
                &*frame.cast::<Self>(),
                &mut *stats.cast::<DrawStats>(),
                &mut *v.cast::<CachedVertex>(),
            )
        };
        u32::from(frame.stage.lit_front(v, i as usize, stats))
    }

    /// Whether the unsnapped triangle faces otherwise than its snapped
    /// doubled area `a` says, or has no area (rare, out of line).
    #[inline(never)]
    fn turned_over(&self, vertex: [usize; 3], a: i32) -> bool {
        let rows = &self.stage.rows;
        let f = vertex.map(|i| rows.fine(self.stage.position(i)));
        let [Some(f0), Some(f1), Some(f2)] = f else {
            return true;
        };
        // Positions within 2²⁶: differences within 2²⁷, products 2⁵⁴.
        let fine = (f1[0] - f0[0]) * (f2[1] - f0[1]) - (f2[0] - f0[0]) * (f1[1] - f0[1]);
        fine == 0 || (fine < 0) != (a < 0)
    }
}

/// Whether the triangle of window positions `p` (doubled area `area`, not
/// 0) covers none of the samples of columns `cols` and rows `rows`, by
/// SPEC.md 5's rule as the walk applies it ([`EdgeFunctions`]).
#[inline(always)]
pub(crate) fn covers_none(
    p: &[[i32; 3]; 3],
    area: i32,
    cols: (i32, i32),
    rows: (i32, i32),
) -> bool {
    let xy = p.map(|v| (v[0], v[1]));
    let mut first = EdgeFunctions::new(xy, area, (16 * cols.0 + 8, 16 * rows.0 + 8));
    for _ in rows.0..=rows.1 {
        let mut e = first;
        for _ in cols.0..=cols.1 {
            if e.covers() {
                return false;
            }
            e.next_col();
        }
        first.next_row();
    }
    true
}

/// Whether snapping may have given a triangle of window positions whose
/// box measures `extent` a doubled area `a` of another sign than its
/// unsnapped positions have, or made it zero.
///
/// Each unsnapped coordinate `x` becomes `X`, within `½ + ε` of it (`ε`
/// the unsnapped value's own error, far below 1/16). The snapped corner is
/// `Sₖ = Pₖ + eₖ`, both components of `eₖ` within `½ + ε`. The doubled
/// area is the cyclic sum `a = Σ Sₖ × Sₖ₊₁`, so the unsnapped one is
/// `A = a − Σ eₖ × (Sₖ₊₁ − Sₖ₋₁) + Σ eₖ × eₖ₊₁`. Each `eₖ × d` is at most
/// `(½ + ε)(|d_x| + |d_y|)`, and the last sum is the doubled area of a
/// triangle inside a square of side `1 + 2ε`: `|A − a|` is at most
/// `(½ + ε)·p + (1 + 2ε)²`, `p` the sum of `|dx| + |dy|` over the three
/// sides. With `ε ≤ 1/16`, when `2|a| > p + p/8 + 3`, `A` has `a`'s sign.
/// Around a triangle the sides' `|dx|` add up to twice its box's width
/// (each coordinate is passed twice, from its minimum to its maximum and
/// back), so `p` is twice the box's width and height. Coordinates within
/// the guard band: `p < 2¹⁸`.
#[inline(always)]
fn snap_may_flip(a: i32, extent: (i32, i32)) -> bool {
    let p = 2 * (extent.0 + extent.1);
    2 * a.unsigned_abs() <= (p + (p >> 3) + 3) as u32
}

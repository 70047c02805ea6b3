//! A triangle's shading: the attributes its mode interpolates (the depth,
//! and the lit colours of Gouraud shading, the normal and eye position of
//! Phong shading) or its one colour (flat shading), at the corners of the
//! pieces it is drawn in, handed to the set-up, the walk and the spans.
//! The lean path (`src/triangle.rs`) draws a triangle as one piece; the
//! rare path (`src/clip.rs`) draws what clipping leaves of it.

use embedded_graphics::pixelcolor::raw::{RawData, RawU16};

use crate::color::Shade;
use crate::depth::DepthTest;
use crate::illumination::Viewer;
use crate::light::LightSet;
use crate::material::Specular;
use crate::mesh::face_normal;
use crate::num::division::floor_div;
use crate::options::{DrawStats, RenderOptions, ShadingKind, ShadingMode};
use crate::setup::{self, Rect, Vtx};
use crate::span::{self, Out, Shader};
use crate::vector::{Unit3, Vec3};
use crate::vertex::{CachedVertex, Stage};
use crate::walk::{Planes, Span};

/// One draw's constants and what it draws into: the vertex stage, the
/// switches, the pixels drawn.
pub(crate) struct Frame<'a, 'm, S: Specular, V: Viewer, L: LightSet> {
    pub(crate) stage: Stage<'a, 'm, S, V, L>,
    pub(crate) options: RenderOptions,
    /// The target's size.
    pub(crate) size: (u32, u32),
    /// The target pixel at the set-up's origin (its centre, rounded down).
    pub(crate) origin: (i32, i32),
    /// The pixels drawn, from the origin: the target's, or a band's rows.
    pub(crate) rect: Rect,
}

/// Where a triangle's vertices are: `cache[slot[k]]` is mesh vertex
/// `vertex[k]`, projected.
pub(crate) struct Corners<'c> {
    pub(crate) cache: &'c mut [CachedVertex],
    pub(crate) slot: [usize; 3],
    pub(crate) vertex: [usize; 3],
}

/// The target pixel at the set-up's origin (the centre, rounded down) and
/// the target's pixels from there, for a target of `size` (at most 2²⁰ a
/// side).
pub(crate) fn rect_of(size: (u32, u32)) -> ((i32, i32), Rect) {
    let (w, h) = (size.0 as i32, size.1 as i32);
    let origin = (w >> 1, h >> 1);
    let rect = Rect {
        c0: -origin.0,
        c1: w - 1 - origin.0,
        r0: -origin.1,
        r1: h - 1 - origin.1,
    };
    (origin, rect)
}

impl<S: Specular, V: Viewer, L: LightSet> Frame<'_, '_, S, V, L> {
    /// Lights and draws the triangles `tris` (corner indices into
    /// `corners`: window position and depth attribute from the set-up's
    /// origin) cut from the triangle `c`, whose facing is `area`'s sign;
    /// corner `k`'s other attributes are the triangle's vertices' mixed by
    /// `mix` (`src/clip.rs`; [`Same`] for the triangle itself). The
    /// corners are from pixel `tile` of the set-up's origin (a big
    /// target's tile centre on the rare path), drawn on `rect` (pixels from
    /// there).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn pieces<M: ShadingMode, O: Out, D: DepthTest, X: Mix>(
        &self,
        c: &mut Corners,
        corners: &[(i32, i32, i32)],
        mix: X,
        tris: &[[usize; 3]],
        area: i32,
        (rect, tile): (&Rect, (i32, i32)),
        out: &mut O,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), O::Error> {
        let back = area > 0 && self.options.two_sided;
        let first = if D::ENABLED { 0 } else { 1 };
        let dither = self.options.dither;
        match M::KIND {
            ShadingKind::Gouraud => {
                let s = self.stage_shades(c, back, stats);
                // The 5/6-bit channel times 2¹⁶, plus ½ (SPEC.md 6): at most
                // 63.5·2¹⁶ < 2²², at least 2¹⁵ inside the field.
                let ch = |v: u32, m: u32| (v * m + (1 << 15)) as i32;
                let va = s.map(|s| {
                    let b = s.to_bits();
                    [0, ch(b[0], 31), ch(b[1], 63), ch(b[2], 31)]
                });
                let attr = |k: usize| {
                    let (x, y, z) = corners[k];
                    let mut a = mix.mix(k, &va);
                    a[0] = z;
                    Vtx { x, y, a }
                };
                for t in tris {
                    let v = [attr(t[0]), attr(t[1]), attr(t[2])];
                    if dither {
                        self.draw(
                            &v,
                            first,
                            (rect, tile),
                            out,
                            depth,
                            stats,
                            &span::GouraudDithered,
                        )?;
                    } else {
                        self.draw(&v, first, (rect, tile), out, depth, stats, &span::Gouraud)?;
                    }
                }
                Ok(())
            }
            ShadingKind::Flat => {
                let e = c.vertex.map(|i| self.stage.eye(i));
                let n = face_normal(e[0], e[1], e[2]).unwrap_or(Unit3::ZERO);
                let n = if back { n.neg() } else { n };
                let shade = self.stage.lighting.shade(centroid(e), n);
                stats.lit = stats.lit.saturating_add(1);
                let sh = span::Flat {
                    plain: RawU16::from(shade.to_rgb565()).into_inner(),
                    shade,
                    dither,
                };
                for t in tris {
                    let v = t.map(|k| {
                        let (x, y, z) = corners[k];
                        Vtx { x, y, a: [z] }
                    });
                    self.draw(&v, first, (rect, tile), out, depth, stats, &sh)?;
                }
                Ok(())
            }
            ShadingKind::Phong => {
                let en = c.vertex.map(|i| {
                    let n = self.stage.eye_normal(i);
                    (self.stage.eye(i), if back { n.neg() } else { n })
                });
                // Eye positions relative to vertex 0's, shifted right until
                // every difference is below 2²⁴ (the set-up's attributes
                // stay within ±2²⁵): full precision for a small triangle,
                // 2⁻²⁴ of its extent for a large one.
                let origin = en[0].0.to_bits().map(i64::from);
                let mut spread = 0u64;
                for (e, _) in &en[1..] {
                    let b = e.to_bits();
                    for k in 0..3 {
                        spread = spread.max((b[k] as i64 - origin[k]).unsigned_abs());
                    }
                }
                let shift = (64 - spread.leading_zeros()).saturating_sub(24);
                let sh = span::Phong {
                    lighting: self.stage.lighting,
                    origin,
                    shift,
                    dither,
                };
                let va = en.map(|(e, n)| {
                    let (e, n) = (e.to_bits(), n.to_bits());
                    // Normals with 8 more fractional bits (Q.22, below 2²³).
                    let rel = |j: usize| ((e[j] as i64 - origin[j]) >> shift) as i32;
                    let n = n.map(|v| (v as i32) << 8);
                    [0, n[0], n[1], n[2], rel(0), rel(1), rel(2)]
                });
                let attr = |k: usize| {
                    let (x, y, z) = corners[k];
                    let mut a = mix.mix(k, &va);
                    a[0] = z;
                    Vtx { x, y, a }
                };
                for t in tris {
                    let v = [attr(t[0]), attr(t[1]), attr(t[2])];
                    self.draw(&v, first, (rect, tile), out, depth, stats, &sh)?;
                }
                Ok(())
            }
        }
    }

    /// The three corners' lit colours (Gouraud), for the back if `back`.
    #[inline(always)]
    fn stage_shades(&self, c: &mut Corners, back: bool, stats: &mut DrawStats) -> [Shade; 3] {
        let mut s = [Shade::BLACK; 3];
        for ((s, &slot), &i) in s.iter_mut().zip(&c.slot).zip(&c.vertex) {
            if let Some(v) = c.cache.get_mut(slot) {
                *s = self.stage.shade(v, i, back, stats);
            }
        }
        s
    }

    /// Sets up and walks one triangle `v` (attributes from `first`) on
    /// `rect`, sending each span, moved by `tile`, through `sh`. Out of
    /// line: its row and pixel loops get the registers, not the triangle
    /// loop's state.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn draw<const N: usize, O: Out, D: DepthTest, Sh: Shader<N>>(
        &self,
        v: &[Vtx<N>; 3],
        first: usize,
        (rect, tile): (&Rect, (i32, i32)),
        out: &mut O,
        depth: &mut D,
        stats: &mut DrawStats,
        sh: &Sh,
    ) -> Result<(), O::Error> {
        let area = setup::area(v);
        if area == 0 {
            return Ok(());
        }
        let mut planes = Planes::default();
        let Some(walk) = setup::set_up(v, area, first, rect, &mut planes) else {
            return Ok(());
        };
        stats.drawn = stats.drawn.saturating_add(1);
        // A triangle's pixels are at most 2¹¹ × 2¹¹: no overflow.
        let mut pixels = 0u32;
        let res = walk.run(&planes, |s: &Span<N>| {
            let moved;
            let s = if tile == (0, 0) {
                s
            } else {
                moved = Span {
                    y: s.y + tile.1,
                    x0: s.x0 + tile.0,
                    ..*s
                };
                &moved
            };
            pixels += out.span(depth, s, sh)?;
            Ok(())
        });
        stats.pixels = stats.pixels.saturating_add(pixels);
        res
    }
}

/// How a polygon's corners take the attributes of the triangle's three
/// vertices.
pub(crate) trait Mix {
    /// Corner `k`'s attributes from the vertices' `a`.
    fn mix<const N: usize>(&self, k: usize, a: &[[i32; N]; 3]) -> [i32; N];
}

/// The triangle itself: corner `k` is vertex `k`.
pub(crate) struct Same;

impl Mix for Same {
    #[inline(always)]
    fn mix<const N: usize>(&self, k: usize, a: &[[i32; N]; 3]) -> [i32; N] {
        a[k]
    }
}

/// The centroid of three eye-space points (sums in `i64`, rounded).
fn centroid(e: [Vec3; 3]) -> Vec3 {
    let b = e.map(|v| v.to_bits());
    let c = [0, 1, 2].map(|k| {
        let s = b[0][k] as i64 + b[1][k] as i64 + b[2][k] as i64;
        floor_div(2 * s + 3, 6) as i32
    });
    Vec3::from_bits(c[0], c[1], c[2])
}

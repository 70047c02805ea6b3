//! The pipeline's façade: a draw's prepared constants, and the whole frame
//! drawn into a `DrawTarget` or a framebuffer. One triangle's way from the
//! mesh to pixels is a stage a file:
//!
//! | stage | file |
//! | --- | --- |
//! | per vertex: window position, depth, lit colour | `src/vertex.rs` |
//! | per triangle: culling and cheap rejections | `src/triangle.rs` |
//! | the rare path: near and guard-band clipping, big targets | `src/clip.rs` |
//! | the mode's attributes (lighting the corners) | `src/shade.rs` |
//! | set-up: edges and planes | `src/setup.rs` |
//! | the row walk | `src/walk.rs` |
//! | spans: depth test, colours, output | `src/span.rs` |
//! | bands of a few rows | `src/band.rs` |
//!
//! Output goes through [`DrawTarget::fill_contiguous`], one call per span
//! (or per run of pixels that pass the depth test), never per pixel; a
//! [`Framebuffer`] is written in place.
//!
//! The shading mode ([`Flat`], [`Gouraud`], [`PhongShading`],
//! [`Renderer::with_shading`](crate::Renderer::with_shading)) and the
//! depth test are values whose types select the code of
//! [`Shaded::draw`](crate::Shaded::draw): a mode or a depth test a scene
//! does not use is not compiled.
//!
//! # Stack
//! No recursion, no heap; the stack is bounded by one triangle's set-up
//! and clip polygons at a time. It is measured by painting it
//! (`scripts/firmware.sh` on the Cortex-M cores; docs/PERFORMANCE.md).

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::{Point, Size};
use embedded_graphics::primitives::Rectangle;

use crate::camera::Camera;
use crate::color::Rgb;
use crate::depth::DepthTest;
use crate::framebuffer::Framebuffer;
use crate::illumination::{Lighting, Viewer};
use crate::light::LightSet;
use crate::material::{Material, Specular};
use crate::mesh::Mesh;
use crate::options::check_bounds;
use crate::platform;
use crate::shade::{rect_of, Frame};
use crate::span::{Memory, Out, TargetSink};
use crate::vector::Mat4;
use crate::vertex::{Stage, VertexMode};

pub use crate::depth::NoDepth;
pub use crate::options::{
    DrawStats, Flat, Gouraud, PhongShading, RenderError, RenderOptions, ShadingKind, ShadingMode,
    MAX_TARGET_SIDE,
};
pub use crate::vertex::CachedVertex;

/// A draw's prepared constants: camera, model-view matrix, lighting in eye
/// space and options ([`crate::Renderer`] makes one a draw). Public only
/// as [`Output`](crate::Output)'s hidden method's argument.
#[doc(hidden)]
#[derive(Clone, Debug)]
pub struct Prepared<'c, S: Specular, V: Viewer, L: LightSet> {
    lighting: Lighting<S, V, L>,
    // Borrowed, not copied: a camera in flash stays a constant that the
    // projection's set-up folds away.
    camera: &'c Camera,
    modelview: Mat4,
    /// [`Camera::world_reach`] of the model.
    world: u64,
    options: RenderOptions,
}

impl<'c, S: Specular, V: Viewer, L: LightSet> Prepared<'c, S, V, L> {
    /// Lights to eye space and the model-view matrix.
    pub(crate) fn new(
        camera: &'c Camera,
        model: &Mat4,
        material: &Material<S>,
        global_ambient: Rgb,
        lights: &L,
        options: RenderOptions,
    ) -> Self {
        Prepared {
            lighting: Lighting::new(material, global_ambient, lights, &camera.view),
            camera,
            modelview: camera.view.mul(model),
            world: camera.world_reach(model),
            options,
        }
    }

    /// The render switches.
    pub(crate) fn options(&self) -> RenderOptions {
        self.options
    }

    /// The frame of `mesh` on a target of `size` (at most
    /// [`MAX_TARGET_SIDE`] a side), all its rows drawn; `None` for an
    /// empty target or a mesh of which nothing is drawn (`Rows::outside`).
    ///
    /// Inlined into its callers (one a draw path): the frame, 328 bytes on
    /// a 32-bit core, is then made where the caller keeps it rather than
    /// copied out of the result (the scene configurations measured 0.3 to
    /// 0.9 KB smaller on the M0+, about 1.1 KB on the M4F: single builds of
    /// `firmware/qemu`'s `fixshade-config`, `arm-none-eabi-size`).
    #[inline(always)]
    pub(crate) fn frame<'a, 'm, E>(
        &'a self,
        mesh: &'a Mesh<'m>,
        size: Size,
    ) -> Result<Option<Frame<'a, 'm, S, V, L>>, RenderError<E>> {
        let (w, h) = (size.width, size.height);
        if w == 0 || h == 0 {
            return Ok(None);
        }
        let proj = self
            .camera
            .projection_for(w, h)
            .map_err(RenderError::Camera)?;
        if !self
            .camera
            .resolves_modelview(&self.modelview, self.world, &mesh.bounds, h)
        {
            return Err(RenderError::SceneTooSmall);
        }
        let normal_m =
            Stage::<S, V, L>::normal_matrix(&self.modelview).ok_or(RenderError::DegenerateModel)?;
        let (origin, rect) = rect_of((w, h));
        let frame = Frame {
            stage: Stage::new(&self.lighting, mesh, &self.modelview, normal_m, &proj, w, h),
            options: self.options,
            size: (w, h),
            origin,
            rect,
        };
        if frame.stage.rows.outside() {
            return Ok(None);
        }
        if !platform::CLIP && !frame.stage.rows.contained() {
            return Err(RenderError::NeedsClipping);
        }
        Ok(Some(frame))
    }

    /// Draws `mesh` into the target `T` through `DrawTarget` (one
    /// `fill_contiguous` per span).
    pub(crate) fn draw_target<M, T, D, X>(
        &self,
        mesh: &Mesh,
        target: &mut T,
        depth: &mut D,
        vertices: &mut X,
    ) -> Result<DrawStats, RenderError<T::Error>>
    where
        M: ShadingMode,
        T: DrawTarget<Color = Rgb565>,
        D: DepthTest,
        X: VertexMode,
    {
        let bb = target.bounding_box();
        let (origin, _) = rect_of((bb.size.width, bb.size.height));
        let mut out = TargetSink {
            target,
            corner: bb.top_left,
            origin,
        };
        self.draw_into::<M, _, D, X>(mesh, &mut out, bb, depth, vertices)
    }

    /// As [`Prepared::draw_target`], into a [`Framebuffer`] written in
    /// place: the fast path (no `fill_contiguous` call per span). The
    /// pixels are the same.
    pub(crate) fn draw_framebuffer<M, D, X>(
        &self,
        mesh: &Mesh,
        fb: &mut Framebuffer,
        depth: &mut D,
        vertices: &mut X,
    ) -> Result<DrawStats, RenderError<core::convert::Infallible>>
    where
        M: ShadingMode,
        D: DepthTest,
        X: VertexMode,
    {
        let size = embedded_graphics::geometry::OriginDimensions::size(fb);
        let (origin, _) = rect_of((size.width, size.height));
        let (buf, width) = fb.parts();
        let mut out = Memory::new(buf, width, 0, origin);
        let bb = Rectangle::new(Point::zero(), size);
        self.draw_into::<M, _, D, X>(mesh, &mut out, bb, depth, vertices)
    }

    fn draw_into<M, O, D, X>(
        &self,
        mesh: &Mesh,
        out: &mut O,
        bb: Rectangle,
        depth: &mut D,
        vertices: &mut X,
    ) -> Result<DrawStats, RenderError<O::Error>>
    where
        M: ShadingMode,
        O: Out,
        D: DepthTest,
        X: VertexMode,
    {
        mesh.validate().map_err(RenderError::Mesh)?;
        let n = mesh.positions.len();
        let cache = vertices.cache();
        if X::CACHED && cache.len() < n {
            return Err(RenderError::CacheTooSmall);
        }
        check_bounds(&bb)?;
        let size = bb.size;
        let (w, h) = (size.width, size.height);
        if D::ENABLED && w > 0 && h > 0 && depth.row(h - 1, w - 1, 1).is_empty() {
            return Err(RenderError::DepthTooSmall);
        }
        let mut stats = DrawStats {
            triangles: u32::try_from(mesh.indices().len()).unwrap_or(u32::MAX),
            ..DrawStats::default()
        };
        let Some(frame) = self.frame(mesh, size)? else {
            return Ok(stats);
        };
        // Once a draw: the stores' rows, for the loops that take them
        // directly (`Out::row_stores`).
        out.fit_rows(depth, &frame.rect);
        let cache = &mut cache[..if X::CACHED { n } else { 0 }];
        if X::CACHED {
            frame.stage.project_all(cache);
        }
        let tris = mesh.indices();
        if X::CACHED {
            let end = tris.as_ptr_range().end;
            let mut at = tris.as_ptr();
            // Where the scan is assembly (`None` elsewhere: the loop below).
            // Whether an entry may have the rare path's flag: not in a
            // contained draw, whose every vertex the lean path keeps.
            let rare = platform::CLIP && !frame.stage.rows.contained();
            debug_assert!(rare || cache.iter().all(|v| v.rare_bits() == 0));
            if platform::GOURAUD_RUN && M::KIND == ShadingKind::Gouraud && !frame.options.dither {
                // SAFETY: the mesh is validated, its indices below the
                // cache's length; `rare` as below.
                at = unsafe {
                    frame.gouraud_run::<M, O, D>(cache, tris, rare, out, depth, &mut stats)
                }
                .map_err(RenderError::Target)?;
            }
            // SAFETY: `at ..= end` lies in `tris` (each pass moves `at` past a
            // triangle before `end`); the mesh is validated, so every index
            // is below the cache's length, `n`; without `rare`, no entry has
            // the flag (above).
            while let Some((next, found)) = unsafe {
                platform::skip_culled(at, end, cache.as_ptr().cast(), frame.options.cull, rare)
            } {
                if next == end {
                    return Ok(stats);
                }
                // SAFETY: `next` lies in `tris`, before its end.
                let idx = unsafe { *next }.map(|i| i as usize);
                // SAFETY: as below; `area` is the kept triangle's (a rare
                // one finds its own).
                unsafe {
                    frame.triangle::<M, O, D>(cache, idx, idx, Some(found), out, depth, &mut stats)
                }
                .map_err(RenderError::Target)?;
                // SAFETY: `next` is before `end`.
                at = unsafe { next.add(1) };
            }
        }
        for tri in tris {
            let idx = tri.map(|i| i as usize);
            // SAFETY: the mesh is validated above, so every index is below
            // `n`, the cache's length; three corners take `[0, 1, 2]`.
            unsafe {
                if X::CACHED {
                    frame.triangle::<M, O, D>(cache, idx, idx, None, out, depth, &mut stats)
                } else {
                    let mut three = idx.map(|i| frame.stage.project(i));
                    frame.triangle::<M, O, D>(
                        &mut three,
                        [0, 1, 2],
                        idx,
                        None,
                        out,
                        depth,
                        &mut stats,
                    )
                }
            }
            .map_err(RenderError::Target)?;
        }
        Ok(stats)
    }
}

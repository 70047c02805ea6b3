//! The pipeline: from a mesh, a model transform and a camera to RGB565
//! pixels in any `embedded-graphics` `DrawTarget`.
//!
//! Per vertex, once per frame (`src/vertex.rs`, a 16-byte
//! [`CachedVertex`] each): model-view transform (the mesh's `i16`
//! positions through the model-view matrix with the mesh's box folded in,
//! to `I8F24`), projection to clip space, snapping to 1/16 pixel (the
//! whole frame and the band renderer's cached mode do every mesh vertex in
//! one pass before its triangles; its recomputed mode, those of each
//! triangle it draws). The normal transform (of
//! the packed normal's octahedral point, 16 × 16-bit products)
//! and lighting (Gouraud) are done later, and only for vertices of
//! triangles that survive culling and touch the target. Triangles that
//! cross the near plane are clipped in clip space (SPEC.md 5); the rest of
//! the frustum is left to the rasterizer's clipping to the target's bounds.
//!
//! # Facing
//! A triangle faces the way its unsnapped window positions do. One that
//! snapping to 1/16 pixel turns over (a sliver thinner than about √2/16
//! pixel, whose corners each move up to 1/32 pixel on each axis) is
//! degenerate and draws nothing, with culling on or off: a back face that
//! snaps to a front face is not drawn over the surface in front of it, and
//! a front face that snaps to a back face is not drawn as a back face
//! (with culling off). The exact facing is the sign of a clip-space
//! determinant (`clip_orientation`), taken only where the snapped area is
//! small enough for snapping to have changed its sign (`snap_may_flip`)
//! and for triangles that cross the near plane; the whole frame and the
//! band renderer decide it in the same place (`Frame::triangle`). Where
//! such a sliver lies inside a surface, its neighbours overlap across it
//! once snapped, and the pixel centres under it are covered twice (docs/ACCURACY.md,
//! "Stiff and extreme cases").
//!
//! Output goes through [`DrawTarget::fill_contiguous`], one call per span
//! (or per run of pixels that pass the depth test), never per pixel; a
//! [`Framebuffer`] is written in place.
//!
//! # Cost selection
//! The shading mode ([`Flat`], [`Gouraud`], [`PhongShading`],
//! [`Renderer::with_shading`]) and the depth test (none, a
//! [`DepthBuffer`](crate::depth::DepthBuffer) or a
//! [`DepthBand`](crate::depth::DepthBand), [`Shaded::with_depth`]) are
//! values whose types select the code of [`Shaded::draw`]: a mode or a
//! depth test a scene does not use is not compiled.
//!
//! [`Renderer::with_shading`]: crate::Renderer::with_shading
//! [`Shaded::with_depth`]: crate::Shaded::with_depth
//! [`Shaded::draw`]: crate::Shaded::draw
//!
//! # Stack
//! No recursion, no heap; the stack is bounded by the set-up triangles and
//! clip polygons of one triangle at a time. It is measured by painting it
//! (`scripts/firmware.sh` on the Cortex-M cores; docs/PERFORMANCE.md).

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::OriginDimensions;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::{Point, RawData, Size};
use embedded_graphics::primitives::Rectangle;

use crate::band::VertexMode;
use crate::camera::{Camera, CameraError, ProjectionCoeffs};
use crate::color::{Rgb, Shade};
use crate::depth::DepthTest;
pub use crate::depth::NoDepth;
use crate::framebuffer::Framebuffer;
use crate::illumination::{Lighting, Viewer};
use crate::light::LightSet;
use crate::material::{Material, Specular};
use crate::mesh::{face_normal, Mesh, MeshError};
use crate::num::division::floor_div;
use crate::num::widening::{mul_i32, mul_narrow};
use crate::rasterizer::{coverage, ClipRect, Cover, RasterVertex, CLIP_LIMIT, DRIFT, TINY};
use crate::setup;
use crate::span::{
    emit, ClampedGouraud, FlatShader, FramebufferSink, PackedGouraud, PairGouraud, PhongPixels,
    PixelSink, SpanDepth, SpanShader, TargetSink, LANE_MARGIN,
};
use crate::vector::{normal_matrix, Mat4, Unit3, Vec3};
pub use crate::vertex::CachedVertex;
use crate::vertex::{Corners, Fold, Win};

/// Which shading mode a type selects.
///
/// ```
/// use fixshade::render::{Flat, Gouraud, PhongShading, ShadingKind, ShadingMode};
/// assert_eq!(Flat::KIND, ShadingKind::Flat);
/// assert_eq!(Gouraud::KIND, ShadingKind::Gouraud);
/// assert_eq!(PhongShading::KIND, ShadingKind::Phong);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShadingKind {
    /// One colour per triangle.
    Flat,
    /// Colours per vertex, interpolated.
    Gouraud,
    /// Normals and positions interpolated, lit per pixel.
    Phong,
}

/// A shading mode, chosen by type: [`Flat`], [`Gouraud`] or
/// [`PhongShading`].
///
/// The mode is a value ([`Renderer::with_shading`](crate::Renderer::with_shading))
/// whose type selects the span code, so that a program that draws in one
/// mode compiles only that mode's:
///
/// ```
/// # use fixshade::prelude::*;
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
/// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// let material = Material::new();
/// let renderer = Renderer::new(&camera, &material, &sun);
/// let (mut a, mut b) = ([0u16; 32 * 32], [0u16; 32 * 32]);
/// let mut fb = Framebuffer::new(&mut a, 32, 32).unwrap();
/// MESH.shaded(&renderer.with_shading(Flat)).draw(&mut fb).unwrap();
/// let mut fb = Framebuffer::new(&mut b, 32, 32).unwrap();
/// MESH.shaded(&renderer.with_shading(PhongShading)).draw(&mut fb).unwrap();
/// // A flat triangle with equal vertex normals: every mode agrees.
/// assert_eq!(a, b);
/// ```
pub trait ShadingMode {
    /// The mode.
    const KIND: ShadingKind;
}

/// Flat shading: the equation at each triangle's centroid with its face
/// normal (SPEC.md 4).
///
/// ```
/// # use fixshade::prelude::*;
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
/// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// let material = Material::new();
/// let renderer = Renderer::new(&camera, &material, &sun).with_shading(Flat);
/// let mut px = [0u16; 32 * 32];
/// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
/// MESH.shaded(&renderer).draw(&mut fb).unwrap();
/// // One colour for the whole triangle.
/// let lit: Vec<u16> = px.iter().copied().filter(|&p| p != 0).collect();
/// assert!(lit.len() > 50 && lit.iter().all(|&p| p == lit[0]));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Flat;
impl ShadingMode for Flat {
    const KIND: ShadingKind = ShadingKind::Flat;
}

/// Gouraud shading: the equation per vertex, colours interpolated with
/// integer arithmetic (16 fractional bits below the RGB565 step; 11, 10
/// for green, on spans of at least [`PAIR_SPAN`] pixels, see
/// `src/span.rs`).
///
/// ```
/// use embedded_graphics::{pixelcolor::raw::RawU16, prelude::*};
/// # use fixshade::prelude::*;
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z, PackedNormal::Z, PackedNormal::Y];
/// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// let material = Material::new();
/// let renderer = Renderer::new(&camera, &material, &sun); // Gouraud by default
/// let mut px = [0u16; 32 * 32];
/// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
/// MESH.shaded(&renderer).draw(&mut fb).unwrap();
/// // The top vertex's normal faces away from the light: darker towards it.
/// let green = |x: usize, y: usize| Rgb565::from(RawU16::new(px[y * 32 + x])).g();
/// assert!(green(16, 10) < green(16, 20));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Gouraud;
impl ShadingMode for Gouraud {
    const KIND: ShadingKind = ShadingKind::Gouraud;
}

/// Phong shading: normal and eye position interpolated, the normal
/// renormalised and the equation evaluated per pixel.
///
/// ```
/// use embedded_graphics::{pixelcolor::raw::RawU16, prelude::*};
/// # use fixshade::prelude::*;
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z, PackedNormal::Z, PackedNormal::Y];
/// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// let material = Material::new();
/// let renderer = Renderer::new(&camera, &material, &sun).with_shading(PhongShading);
/// let mut px = [0u16; 32 * 32];
/// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
/// MESH.shaded(&renderer).draw(&mut fb).unwrap();
/// let green = |x: usize, y: usize| Rgb565::from(RawU16::new(px[y * 32 + x])).g();
/// assert!(green(16, 10) < green(16, 20));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct PhongShading;
impl ShadingMode for PhongShading {
    const KIND: ShadingKind = ShadingKind::Phong;
}

/// Render switches that cost nothing to keep at run time.
///
/// ```
/// use fixshade::render::RenderOptions;
/// let o = RenderOptions { dither: true, ..RenderOptions::default() };
/// assert!(o.cull && !o.two_sided && o.dither);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RenderOptions {
    /// Drop back faces (SPEC.md 5).
    pub cull: bool,
    /// Light back faces with the negated normal (SPEC.md 3).
    pub two_sided: bool,
    /// 4 × 4 ordered dithering when quantising to RGB565 (off in every
    /// comparison with the reference).
    pub dither: bool,
}

impl Default for RenderOptions {
    /// Culling on, one-sided lighting, no dithering.
    fn default() -> Self {
        RenderOptions {
            cull: true,
            two_sided: false,
            dither: false,
        }
    }
}

/// Why a draw call failed. Nothing was drawn unless the error is
/// [`RenderError::Target`].
///
/// ```
/// # use fixshade::prelude::*;
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
/// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// # let material = Material::new();
/// # let renderer = Renderer::new(&camera, &material, &sun);
/// let mut px = [0u16; 32 * 32];
/// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
/// let mut zs = [0u16; 16 * 16];
/// let mut depth = DepthBuffer::new(&mut zs, 16, 16).unwrap(); // smaller than the target
/// let e = MESH.shaded(&renderer).with_depth(&mut depth).draw(&mut fb);
/// assert_eq!(e, Err(RenderError::DepthTooSmall));
/// assert!(px.iter().all(|&p| p == 0)); // nothing drawn
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RenderError<E> {
    /// The mesh is inconsistent.
    Mesh(MeshError),
    /// The camera's projection does not fit the target.
    Camera(CameraError),
    /// The vertex cache is shorter than the mesh's vertex count.
    CacheTooSmall,
    /// The mesh has no normals, and Gouraud or Phong shading needs them
    /// (compute them with [`vertex_normals`](crate::mesh::vertex_normals),
    /// or draw it with [`Flat`] shading, which uses face normals).
    NoNormals,
    /// The depth buffer is smaller than the target (or, for
    /// [`Bands`](crate::band::Bands), the depth band than the band).
    DepthTooSmall,
    /// The band renderer's colour band holds fewer than `width × h`
    /// pixels, or its height `h` is 0.
    BandTooSmall,
    /// The target is wider or taller than 2²⁰ pixels, or its bounding box
    /// reaches past `i32::MAX` (its last column or row is not a `Point`).
    TargetTooLarge,
    /// The target reported an error.
    Target(E),
}

impl<E> RenderError<E> {
    /// The target's own error apart (`Err`), or the renderer's (`Ok`).
    pub(crate) fn split(self) -> Result<RenderError<core::convert::Infallible>, E> {
        Ok(match self {
            RenderError::Mesh(m) => RenderError::Mesh(m),
            RenderError::Camera(c) => RenderError::Camera(c),
            RenderError::CacheTooSmall => RenderError::CacheTooSmall,
            RenderError::NoNormals => RenderError::NoNormals,
            RenderError::DepthTooSmall => RenderError::DepthTooSmall,
            RenderError::BandTooSmall => RenderError::BandTooSmall,
            RenderError::TargetTooLarge => RenderError::TargetTooLarge,
            RenderError::Target(e) => return Err(e),
        })
    }
}

impl RenderError<core::convert::Infallible> {
    /// An error of a sink that cannot fail (memory) as another target's.
    pub(crate) fn lift<E>(self) -> RenderError<E> {
        match self {
            RenderError::Mesh(m) => RenderError::Mesh(m),
            RenderError::Camera(c) => RenderError::Camera(c),
            RenderError::CacheTooSmall => RenderError::CacheTooSmall,
            RenderError::NoNormals => RenderError::NoNormals,
            RenderError::DepthTooSmall => RenderError::DepthTooSmall,
            RenderError::BandTooSmall => RenderError::BandTooSmall,
            RenderError::TargetTooLarge => RenderError::TargetTooLarge,
            RenderError::Target(e) => match e {},
        }
    }
}

impl<E: core::fmt::Debug> core::fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RenderError::Mesh(e) => write!(f, "mesh: {e}"),
            RenderError::Camera(e) => write!(f, "camera: {e}"),
            RenderError::CacheTooSmall => f.write_str("vertex cache shorter than the vertex count"),
            RenderError::NoNormals => {
                f.write_str("mesh without normals (Gouraud and Phong shading need them)")
            }
            RenderError::DepthTooSmall => f.write_str("depth buffer smaller than the target"),
            RenderError::BandTooSmall => f.write_str("colour band smaller than width x height"),
            RenderError::TargetTooLarge => {
                f.write_str("target larger than 2^20 pixels a side, or ending past i32::MAX")
            }
            RenderError::Target(e) => write!(f, "target: {e:?}"),
        }
    }
}

/// Counts of one draw call.
///
/// Each count saturates at `u32::MAX` (a draw call into a target of 2²⁰ ×
/// 2²⁰ pixels, or one cut in many bands, can pass it).
///
/// ```
/// # use fixshade::prelude::*;
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
/// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// # let material = Material::new();
/// # let renderer = Renderer::new(&camera, &material, &sun);
/// let mut px = [0u16; 32 * 32];
/// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
/// let s = MESH.shaded(&renderer).draw(&mut fb).unwrap();
/// assert_eq!((s.triangles, s.drawn, s.clipped, s.lit), (1, 1, 0, 3));
/// assert_eq!(s.pixels as usize, px.iter().filter(|&&p| p != 0).count());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct DrawStats {
    /// Triangles in the mesh.
    pub triangles: u32,
    /// Triangles (or clipped pieces) that were rasterized.
    pub drawn: u32,
    /// Triangles clipped by the near plane.
    pub clipped: u32,
    /// Pixels sent to the target.
    pub pixels: u32,
    /// Vertices lit.
    pub lit: u32,
}

/// A bound on the doubled area (in 1/256 pixel²) of a triangle whose box
/// holds at most [`TINY`] pixel centres, `c_x` columns by `c_y` rows: its
/// box is under `16(c_x + 1)` by `16(c_y + 1)` units, a triangle covers at
/// most half its box, and `(c_x + 1)(c_y + 1) ≤ 2(TINY + 1)` as
/// `c_x + c_y ≤ c_x·c_y + 1 ≤ TINY + 1` (from `(c_x − 1)(c_y − 1) ≥ 0`).
/// A triangle at least this large skips [`Frame::tiny_cover`] with one
/// comparison (most of S1's); one whose box the viewport cuts to a few
/// centres may skip it too, and the set-up then draws what it covers.
const TINY_AREA: u64 = 256 * 2 * (TINY as u64 + 1);

/// A polygon's pixel centres in the target: columns and rows (inclusive,
/// rows limited to those drawn), and whether those rows are all of the
/// box's rows in the viewport ([`Frame::pixel_box`]).
type PixelBox = ((i32, i32), (i32, i32), bool);

/// The largest target side in pixels.
///
/// ```
/// use embedded_graphics::prelude::*;
/// # use fixshade::prelude::*;
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
/// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// # let material = Material::new();
/// # let renderer = Renderer::new(&camera, &material, &sun);
/// use fixshade::render::MAX_TARGET_SIDE;
/// // A target that only reports its size (it is never drawn into).
/// struct Wide;
/// impl OriginDimensions for Wide {
///     fn size(&self) -> Size {
///         Size::new(MAX_TARGET_SIDE + 1, 1)
///     }
/// }
/// impl DrawTarget for Wide {
///     type Color = Rgb565;
///     type Error = ();
///     fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), ()> {
///         Err(())
///     }
/// }
/// let e = MESH.shaded(&renderer).draw(&mut Wide);
/// assert_eq!(e, Err(RenderError::TargetTooLarge));
/// ```
pub const MAX_TARGET_SIDE: u32 = 1 << 20;

/// The largest side of a tile. A target wider or taller than this is drawn
/// a tile at a time, each tile with the guard band around its own centre
/// (whole pixels: a tile's columns and rows shift by integers); a smaller
/// one is one tile. The grid is the viewport's, whatever rows a band
/// draws, so bands and whole frames clip every triangle alike.
/// (The rasterizer's clip rectangle limit: inside the guard band's clip
/// planes with a pixel to spare, `Frame::guard_clip`.)
const TILE: i32 = CLIP_LIMIT as i32;

/// The tile of a viewport side `len` that holds pixel `at`: its first and
/// last pixels and its centre pixel.
fn tile(len: i32, at: i32) -> (i32, i32, i32) {
    if len <= TILE {
        (0, len - 1, len >> 1)
    } else {
        let lo = at - at % TILE;
        (lo, (lo + TILE - 1).min(len - 1), lo + TILE / 2)
    }
}

/// A draw's prepared constants: camera, model-view and normal matrices,
/// lighting in eye space and options ([`crate::Renderer`] makes one a
/// draw). Public only as [`Output`](crate::Output)'s hidden method's
/// argument.
#[doc(hidden)]
#[derive(Clone, Debug)]
pub struct Prepared<'c, S: Specular, V: Viewer, L: LightSet> {
    lighting: Lighting<S, V, L>,
    // Borrowed, not copied: a camera in flash stays a constant that the
    // projection's set-up folds away.
    camera: &'c Camera,
    modelview: Mat4,
    pub(crate) normal_m: [[i16; 3]; 3],
    options: RenderOptions,
}

impl<'c, S: Specular, V: Viewer, L: LightSet> Prepared<'c, S, V, L> {
    /// Lights to eye space, model-view and normal matrices. A singular
    /// model matrix gives zero normals (lit by `E + A·Ka` only).
    pub(crate) fn new(
        camera: &'c Camera,
        model: &Mat4,
        material: &Material<S>,
        global_ambient: Rgb,
        lights: &L,
        options: RenderOptions,
    ) -> Self {
        let modelview = camera.view.mul(model);
        Prepared {
            lighting: Lighting::new(material, global_ambient, lights, &camera.view),
            camera,
            modelview,
            normal_m: normal_matrix(&modelview).unwrap_or([[0; 3]; 3]),
            options,
        }
    }

    /// The prepared illumination equation.
    pub(crate) fn lighting(&self) -> &Lighting<S, V, L> {
        &self.lighting
    }

    /// The render switches.
    pub(crate) fn options(&self) -> RenderOptions {
        self.options
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
        let mut sink = TargetSink {
            target,
            origin: bb.top_left,
        };
        self.draw_into::<M, _, D, X>(mesh, &mut sink, bb, depth, vertices)
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
        let bb = Rectangle::new(Point::zero(), fb.size());
        self.draw_into::<M, _, D, X>(mesh, &mut FramebufferSink { fb }, bb, depth, vertices)
    }

    fn draw_into<M, P, D, X>(
        &self,
        mesh: &Mesh,
        sink: &mut P,
        bb: Rectangle,
        depth: &mut D,
        vertices: &mut X,
    ) -> Result<DrawStats, RenderError<P::Error>>
    where
        M: ShadingMode,
        P: PixelSink,
        D: DepthTest,
        X: VertexMode,
    {
        mesh.validate().map_err(RenderError::Mesh)?;
        let n = mesh.positions.len();
        let cache = vertices.cache();
        if X::CACHED && cache.len() < n {
            return Err(RenderError::CacheTooSmall);
        }
        let size = bb.size;
        let (w, h) = (size.width, size.height);
        check_bounds(&bb)?;
        if D::ENABLED
            && depth
                .row(h.saturating_sub(1), w.saturating_sub(1), 1)
                .is_empty()
            && w > 0
            && h > 0
        {
            return Err(RenderError::DepthTooSmall);
        }
        let mut stats = DrawStats {
            triangles: u32::try_from(mesh.indices.len()).unwrap_or(u32::MAX),
            ..DrawStats::default()
        };
        // An empty target draws nothing (and has no aspect ratio).
        let modelview = self.mesh_modelview(mesh);
        let Some(mut frame) = self.frame(mesh, &modelview, size)? else {
            return Ok(stats);
        };
        // Every vertex projected up front: a mesh's vertices are (nearly)
        // all used, and the triangle loop then tests no flag (callgrind,
        // S3 on x86-64: 0.17 M instructions a frame).
        if X::CACHED {
            frame.project_all(&mut cache[..n]);
        }
        frame.each_tile(|frame| {
            for tri in mesh.indices {
                let idx = tri.map(|i| i as usize);
                if X::CACHED {
                    let mut c = Corners::of(cache, idx);
                    frame.triangle::<M, P, D>(&mut c, sink, depth, &mut stats)?;
                } else {
                    let mut three = frame.project3(idx);
                    let mut c = Corners::of_three(&mut three, idx);
                    frame.triangle::<M, P, D>(&mut c, sink, depth, &mut stats)?;
                }
            }
            Ok(())
        })?;
        Ok(stats)
    }

    /// The model-view matrix with `mesh`'s box folded in: it takes the
    /// mesh's `i16` positions to eye space ([`Bounds::fold`]), once a draw.
    ///
    /// [`Bounds::fold`]: crate::mesh::Bounds::fold
    pub(crate) fn mesh_modelview(&self, mesh: &Mesh) -> Mat4 {
        mesh.bounds.fold(&self.modelview)
    }

    /// The per-draw constants for a viewport of `size` at the origin,
    /// drawing all its rows, `modelview` from [`Prepared::mesh_modelview`];
    /// `None` for an empty viewport.
    pub(crate) fn frame<'a, 'm, E>(
        &'a self,
        mesh: &'a Mesh<'m>,
        modelview: &'a Mat4,
        size: Size,
    ) -> Result<Option<Frame<'a, 'm, S, V, L>>, RenderError<E>> {
        let (w, h) = (size.width, size.height);
        let Some(viewport) = ClipRect::of_size(w, h) else {
            return Ok(None);
        };
        let proj = self
            .camera
            .projection_for(w, h)
            .map_err(RenderError::Camera)?;
        Ok(Some(Frame {
            r: self,
            mesh,
            modelview,
            fold: Fold::new(modelview, &proj, w as i64, h as i64),
            proj,
            w: w as i64,
            h: h as i64,
            viewport,
            rows: (viewport.y0, viewport.y1),
            cols: (viewport.x0, viewport.x1),
            origin: (0, 0),
        }))
    }
}

/// The signed doubled area of the triangle of window positions `win[k]`,
/// `k` in `corners` (see [`area2`](crate::rasterizer::area2)).
#[inline(always)]
fn win_area(win: &[Win], corners: [usize; 3]) -> i64 {
    let [a, b, c] = corners.map(|j| win[j]);
    // Window positions are within ±2^28 (`window` clamps them): the
    // differences fit i32, the products 2^58.
    mul_i32(b[0] - a[0], c[1] - a[1]) - mul_i32(b[1] - a[1], c[0] - a[0])
}

/// Whether snapping may have given the triangle of window positions `w`
/// (its first three) a doubled area `a` ([`win_area`]) of another sign
/// than its unsnapped positions have, or made it zero: then
/// [`turned_over`] decides.
///
/// Each unsnapped coordinate `x` (1/16 pixel, [`Frame::homogeneous`])
/// becomes `X`, within `½ + ε` of it: `ε ≤ 1/16` for `|x| ≤ 2²⁴`
/// ([`Recip::div_scaled`](crate::rasterizer::Recip)'s error). The snapped
/// corner is `Sₖ = Pₖ + eₖ`, both components of `eₖ` within `½ + ε`. The
/// doubled area is the cyclic sum `a = Σ Sₖ × Sₖ₊₁`, so the unsnapped one
/// is `A = Σ (Sₖ − eₖ) × (Sₖ₊₁ − eₖ₊₁) = a − Σ eₖ × (Sₖ₊₁ − Sₖ₋₁) + Σ eₖ ×
/// eₖ₊₁`. Each `eₖ × d` is at most `(½ + ε)(|d_x| + |d_y|)`, and the last
/// sum is the doubled area of a triangle inside a square of side `1 + 2ε`,
/// at most `(1 + 2ε)²`: `|A − a| ≤ (½ + ε)·p + (1 + 2ε)²`, `p` the sum of
/// `|dx| + |dy|` over the three sides. With `ε = 1/16`, when `2|a| > p +
/// p/8 + 3` (above `(1 + 2ε)·p + 2·(1 + 2ε)²`), `A` is not zero and has
/// `a`'s sign. A sliver of longest side `L` and height `h` (its other two
/// sides summing to about `L`) has `2|a| = 2Lh` and `p` at most about
/// `2√2·L`: only slivers less than about 1/10 pixel thick, and triangles a
/// few 1/16 pixel across, ask for the exact sign.
///
/// Ranges: coordinates within ±2²⁸ (`window` clamps them), so each
/// difference is within ±2²⁹ and is the difference of the low 32 bits
/// (`i32`, one instruction on a 32-bit core), each side's `|dx| + |dy|` is
/// at most 2³⁰, `p` below 2³² and `p + p/8 + 3` below 2³³ (`u64`); `2|a|`
/// is below 2⁶¹. A corner beyond ±2²⁴ (clamped, or `ε` above 1/16) is
/// further off than the bound covers: such a triangle keeps its snapped
/// orientation unless the bound asks.
#[inline(always)]
fn snap_may_flip(a: i64, w: &[Win]) -> bool {
    let d = |j: usize, k: usize, i: usize| w[k][i].wrapping_sub(w[j][i]);
    let side = |j: usize, k: usize| d(j, k, 0).unsigned_abs() + d(j, k, 1).unsigned_abs();
    let p = u64::from(side(0, 1) + side(1, 2) + side(2, 0));
    2 * a.unsigned_abs() <= p + (p >> 3) + 3
}

/// The sign of the doubled window-space area ([`win_area`]: −1 for a front
/// face, 1 for a back face, 0 for none) of the triangle whose clip-space
/// corners are `c`, before snapping: the facing of a triangle that the
/// near plane cuts.
///
/// The window position of `(x, y, w)` is `16·(x_w, y_w) = (8W·(x/w + 1),
/// 8H·(1 − y/w))` ([`Frame::window`] before its rounding), so the doubled
/// area of three corners is `−64WH·D / (w₀w₁w₂)` with `D` the determinant
/// of the rows `(xₖ, yₖ, wₖ)`: with every `w > 0` (corners in front of
/// the near plane) its sign is `D`'s, negated. For a triangle the near
/// plane cuts this is also the sign of each piece in front of it: clip
/// space is linear, a piece's corners are `Λ·c` with `Λ` their barycentric
/// coordinates (kept in the triangle's order by the clipping, `det Λ > 0`)
/// and their determinant is `det Λ · D` (up to the rounding of the cut
/// points, which moves them by at most half a clip unit).
///
/// Ranges ([`ProjectionCoeffs::clip`]): `|x|, |y| < 2³⁹` (a product below
/// 2⁶² shifted by 24, plus a translation below 2³¹) and `|w| ≤ 2³¹` (an
/// `I8F24` coordinate, or 2²⁴): each 2 × 2 minor is below 2⁷¹ (with `w`)
/// or 2⁷⁹ (`x` by `y`), each term below 2¹¹⁰, `D` below 2¹¹²: `i128`.
///
/// [`ProjectionCoeffs::clip`]: crate::camera::ProjectionCoeffs::clip
#[inline(never)]
fn clip_orientation(c: &[[i64; 4]; 3]) -> i64 {
    let [x, y, w] = [0, 1, 3].map(|i| c.map(|p| p[i] as i128));
    -det3(x, y, w).signum() as i64
}

/// The determinant of the rows `(xₖ, yₖ, wₖ)`, in `i128` (the callers
/// bound it).
fn det3(x: [i128; 3], y: [i128; 3], w: [i128; 3]) -> i128 {
    x[0] * (y[1] * w[2] - y[2] * w[1]) - y[0] * (x[1] * w[2] - x[2] * w[1])
        + w[0] * (x[1] * y[2] - x[2] * y[1])
}

/// Whether the unclipped triangle of corners `c` faces otherwise than its
/// snapped doubled area `a` says: the exact test behind
/// [`snap_may_flip`], out of line (it is rare).
///
/// Its window positions before rounding are `(Xₖ/(wₖ·2^dx) + 8W,
/// Yₖ/(wₖ·2^dy) + 8H)` ([`Frame::homogeneous`]), so the doubled area is
/// `D/(w₀w₁w₂·2^(dx + dy))` with `D` the determinant of the rows `(Xₖ,
/// Yₖ, wₖ)` (the translation drops out), of `D`'s sign with every `w > 0`.
/// `|X|, |Y| < 2⁴⁶` and `|w| ≤ 2³¹`: each minor with `w` is below 2⁷⁸,
/// each term below 2¹²⁴, `D` below 2¹²⁶, in `i128`.
#[inline(never)]
fn turned_over<S: Specular, V: Viewer, L: LightSet>(
    c: &Corners,
    f: &Frame<'_, '_, S, V, L>,
    a: i64,
) -> bool {
    let h = [0, 1, 2].map(|k| f.homogeneous(c.vertex(k)));
    let [x, y, w] = [0, 1, 2].map(|i| h.map(|p| p[i] as i128));
    det3(x, y, w).signum() as i64 != a.signum()
}

/// `TargetTooLarge` for a side above [`MAX_TARGET_SIDE`].
pub(crate) fn check_size<E>(size: Size) -> Result<(), RenderError<E>> {
    if size.width > MAX_TARGET_SIDE || size.height > MAX_TARGET_SIDE {
        return Err(RenderError::TargetTooLarge);
    }
    Ok(())
}

/// [`check_size`] for a target's bounding box, which must also end within
/// `i32` (its last column and row are `Point`s the renderer sends).
pub(crate) fn check_bounds<E>(bb: &Rectangle) -> Result<(), RenderError<E>> {
    check_size(bb.size)?;
    let end = |at: i32, len: u32| at as i64 + len as i64 - 1 <= i32::MAX as i64;
    if !end(bb.top_left.x, bb.size.width) || !end(bb.top_left.y, bb.size.height) {
        return Err(RenderError::TargetTooLarge);
    }
    Ok(())
}

/// Per-draw constants.
pub(crate) struct Frame<'a, 'm, S: Specular, V: Viewer, L: LightSet> {
    pub(crate) r: &'a Prepared<'a, S, V, L>,
    pub(crate) mesh: &'a Mesh<'m>,
    /// The model-view matrix with the mesh's box folded in
    /// ([`Prepared::mesh_modelview`]), by reference: a pointer, not 64
    /// bytes, in the struct the triangle loop reads.
    pub(crate) modelview: &'a Mat4,
    pub(crate) proj: ProjectionCoeffs,
    /// The projection's `x`, `y` rows folded with the viewport and
    /// `modelview`.
    pub(crate) fold: Fold,
    pub(crate) w: i64,
    pub(crate) h: i64,
    /// The viewport: projection, window mapping and the attribute planes'
    /// anchor.
    pub(crate) viewport: ClipRect,
    /// The rows drawn (all of the viewport's, or a band's; within a tile
    /// while [`Frame::each_tile`] runs).
    pub(crate) rows: (i32, i32),
    /// The columns drawn: the tile's.
    cols: (i32, i32),
    /// The tile's centre in 1/16 pixel, the guard band's centre.
    origin: (i64, i64),
}

/// Where a vertex of a near-clipped polygon comes from: an original vertex,
/// or the point `a + t·(b − a)` on edge `a → b` (a inside, b outside) with
/// `t = num / den = d_a / (d_a − d_b)`, `d = z_c + w_c`.
#[derive(Clone, Copy, Debug)]
enum PolyVert {
    Orig(usize),
    Cut {
        a: usize,
        b: usize,
        num: i64,
        den: i64,
    },
}

/// `round(x · num / den)` for `0 ≤ num ≤ den`, `den > 0`, in `i128`
/// (`|x| < 2⁶³`, `num < 2⁶³`: the product is below 2¹²⁶).
#[inline]
fn lerp_part(x: i64, num: i64, den: i64) -> i64 {
    let p = x as i128 * num as i128;
    let d = den as i128;
    let q = if p >= 0 {
        (2 * p + d) / (2 * d)
    } else {
        -((-2 * p + d) / (2 * d))
    };
    q as i64
}

/// The clip-space point where the near plane cuts edge `a → b`.
fn cut(a: &[i64; 4], b: &[i64; 4], num: i64, den: i64) -> [i64; 4] {
    [0, 1, 2, 3].map(|k| a[k] + lerp_part(b[k] - a[k], num, den))
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

impl<S: Specular, V: Viewer, L: LightSet> Frame<'_, '_, S, V, L> {
    /// Clips, culls, lights and rasterizes one triangle (its rows in
    /// `self.rows`).
    ///
    /// Inlined into its callers (one per instantiation). On 32-bit targets
    /// LLVM stopped doing so on its own once the draw call's checks grew
    /// (QEMU counts: M4 S1 4.68 M out of line, 4.63 M inlined; M0+ S1 8.33 M
    /// and 8.05 M, S3 89.0 M and 83.9 M); on x86-64 once tiny boxes' masks
    /// set up their walks (callgrind, S1 in cached 16-row bands: 3.113 M out
    /// of line, 3.060 M inlined).
    #[inline(always)]
    pub(crate) fn triangle<M: ShadingMode, P: PixelSink, D: DepthTest>(
        &self,
        c: &mut Corners,
        sink: &mut P,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), RenderError<P::Error>> {
        let inside = [c.inside(0), c.inside(1), c.inside(2)];
        if !inside.iter().any(|&i| i) {
            return Ok(());
        }
        // An unclipped triangle is tested for tiny coverage here (or, if
        // its area rules out a tiny box, not at all), so the set-up skips
        // that test.
        let tested = inside.iter().all(|&i| i);
        let (poly, win, count, a) = if tested {
            // The common case, culled from its three window positions
            // before anything else is built (S1 culls 1 618 of 2 208
            // triangles: a 96-byte clear and two copies each spared on a
            // Cortex-M4).
            let w = c.wins(self);
            let a = win_area(&w, [0, 1, 2]);
            if self.rejects(a, &w) {
                return Ok(());
            }
            let poly = [0, 1, 2, 0].map(PolyVert::Orig);
            (poly, [w[0], w[1], w[2], w[0]], 3, a)
        } else {
            // The polygon after near clipping (Sutherland–Hodgman, one
            // plane).
            let mut poly = [PolyVert::Orig(0); 4];
            let mut win = [[0i32; 3]; 4];
            let mut count = 0;
            stats.clipped = stats.clipped.saturating_add(1);
            let clip = [c.clip(self, 0), c.clip(self, 1), c.clip(self, 2)];
            let d = clip.map(|c| c[2] + c[3]);
            for a in 0..3 {
                let b = (a + 1) % 3;
                if inside[a] {
                    poly[count] = PolyVert::Orig(a);
                    count += 1;
                }
                if inside[a] != inside[b] {
                    let (i, o) = if inside[a] { (a, b) } else { (b, a) };
                    poly[count] = PolyVert::Cut {
                        a: i,
                        b: o,
                        num: d[i],
                        den: d[i] - d[o],
                    };
                    count += 1;
                }
            }
            for (k, p) in poly[..count].iter().enumerate() {
                win[k] = match *p {
                    PolyVert::Orig(i) => c.win(self, i),
                    PolyVert::Cut { a, b, num, den } => {
                        self.window(&cut(&clip[a], &clip[b], num, den))
                    }
                };
            }
            // Facing is shared by every piece: decided (and culled) once,
            // from the unsnapped triangle; a piece that snapping turned
            // the other way draws nothing (`pieces`).
            let a = clip_orientation(&clip);
            if self.rejects(a, &win[..count]) {
                return Ok(());
            }
            (poly, win, count, a)
        };
        let cover = if !tested {
            Cover::Untested
        } else if a.unsigned_abs() < TINY_AREA {
            self.tiny_cover(a, &win)
        } else {
            Cover::Skip
        };
        if cover == Cover::Mask(0) {
            return Ok(());
        }
        // A sliver that snapping may have turned over is drawn only if it
        // still faces the way its unsnapped corners do (a clipped polygon's
        // facing is the unsnapped one already).
        if tested && snap_may_flip(a, &win) && turned_over(c, self, a) {
            return Ok(());
        }
        let lit_back = a > 0 && self.r.options.two_sided;
        // Every piece faces as the triangle does, or draws nothing.
        let front = a < 0;
        let poly = &poly[..count];
        // A corner outside the guard band (rare: a triangle reaching far
        // past the viewport) has the polygon clipped to it, from its
        // clip-space corners.
        let guarded = win[..count].iter().all(|w| self.in_guard(w, D::ENABLED));
        let direct = tested && guarded;
        let mut clip_buf = [[0i64; 4]; 4];
        let clips = if guarded {
            None
        } else {
            let orig = [c.clip(self, 0), c.clip(self, 1), c.clip(self, 2)];
            for (k, p) in poly.iter().enumerate() {
                clip_buf[k] = match *p {
                    PolyVert::Orig(i) => orig[i],
                    PolyVert::Cut { a, b, num, den } => cut(&orig[a], &orig[b], num, den),
                };
            }
            Some(&clip_buf[..count])
        };
        match M::KIND {
            ShadingKind::Flat => {
                let e = [
                    c.eye_normal(self, 0, false).0,
                    c.eye_normal(self, 1, false).0,
                    c.eye_normal(self, 2, false).0,
                ];
                let n = face_normal(e[0], e[1], e[2]).unwrap_or(Unit3::ZERO);
                let n = if lit_back { n.neg() } else { n };
                let colour = self.r.lighting.shade(centroid(e), n);
                let plain = RawU16::from(colour.to_rgb565()).into_inner();
                stats.lit = stats.lit.saturating_add(1);
                self.pieces(
                    poly,
                    &win,
                    direct,
                    clips,
                    front,
                    D::ENABLED,
                    stats,
                    |_| [0],
                    |sp, st| self.span_flat(sp, colour, plain, sink, depth, st),
                )
            }
            ShadingKind::Gouraud => {
                // Three calls, not `[0, 1, 2].map(..)`: LLVM kept the map
                // out of line, a call with its arguments in memory for
                // every drawn triangle (callgrind, S3: 0.52 M a frame).
                let cols = [
                    c.shade(self, 0, lit_back, stats),
                    c.shade(self, 1, lit_back, stats),
                    c.shade(self, 2, lit_back, stats),
                ];
                self.pieces(
                    poly,
                    &win,
                    direct,
                    clips,
                    front,
                    D::ENABLED,
                    stats,
                    |i| {
                        let b = cols[i].to_bits();
                        // Scaled so that the 5/6-bit channel is `v >> 16`,
                        // rounded as SPEC.md 6 says: v·31 + ½ (≤ 2^21).
                        [
                            0,
                            (b[0] * 31 + (1 << 15)) as i64,
                            (b[1] * 63 + (1 << 15)) as i64,
                            (b[2] * 31 + (1 << 15)) as i64,
                        ]
                    },
                    |sp, st| self.span_gouraud(sp, sink, depth, st),
                )
            }
            ShadingKind::Phong => {
                let en = [
                    c.eye_normal(self, 0, true),
                    c.eye_normal(self, 1, true),
                    c.eye_normal(self, 2, true),
                ];
                // Eye positions relative to corner 0's, shifted right until
                // every difference is below 2²⁴ (the set-up's attributes
                // stay within ±2²⁵): full precision for a small triangle,
                // 2⁻²⁴ of its extent for a large one. The shaders get them
                // back in `I8F24` (`unpack` above).
                let origin = en[0].0.to_bits().map(i64::from);
                let mut spread = 0u64;
                for (e, _) in &en[1..] {
                    let b = e.to_bits();
                    for k in 0..3 {
                        spread = spread.max((b[k] as i64 - origin[k]).unsigned_abs());
                    }
                }
                let shift = (64 - spread.leading_zeros()).saturating_sub(24);
                self.pieces(
                    poly,
                    &win,
                    direct,
                    clips,
                    front,
                    D::ENABLED,
                    stats,
                    |i| {
                        let (e, n) = en[i];
                        let n = if lit_back { n.neg() } else { n }.to_bits();
                        let e = e.to_bits();
                        // Normals get 10 more fractional bits (Q.24, at most 2²⁴).
                        [
                            0,
                            (n[0] as i64) << 10,
                            (n[1] as i64) << 10,
                            (n[2] as i64) << 10,
                            (e[0] as i64 - origin[0]) >> shift,
                            (e[1] as i64 - origin[1]) >> shift,
                            (e[2] as i64 - origin[2]) >> shift,
                        ]
                    },
                    |sp, st| {
                        // Back to the shader's units: normals in `Q.26`,
                        // positions `I8F24` raw.
                        let mut cur = [0i64; 6];
                        let mut d = [0i64; 6];
                        for k in 0..3 {
                            cur[k] = (sp.start[k + 1] as i64) << 2;
                            d[k] = (sp.step[k + 1] as i64) << 2;
                            cur[k + 3] = ((sp.start[k + 4] as i64) << shift) + origin[k];
                            d[k + 3] = (sp.step[k + 4] as i64) << shift;
                        }
                        self.span_phong(sp, cur, d, sink, depth, st)
                    },
                )
            }
        }
    }

    /// Whether a polygon of signed doubled area `a` (negative: a front
    /// face, y down) is dropped: no area, a culled back face, or no pixel
    /// centre inside the target.
    #[inline(always)]
    fn rejects(&self, a: i64, win: &[Win]) -> bool {
        a == 0 || (a > 0 && self.r.options.cull) || self.pixel_box(win).is_none()
    }

    /// For an unclipped triangle that [`Self::rejects`] keeps (`w`: its
    /// window positions, then the first again) whose box holds at most
    /// [`TINY`] pixel centres, all in the rows drawn: which of them it
    /// covers ([`Cover::Mask`]; none: it is dropped before its vertices are
    /// lit and its raster vertices built); else [`Cover::Skip`]. The
    /// set-up draws a mask's spans without setting up edges. (S3: 1 812 of
    /// the 8 966 triangles that pass the box test cover no centre; testing
    /// them here spares 396 of 4 952 vertex lightings and 1 812 triangles'
    /// raster vertices.)
    #[inline(always)]
    fn tiny_cover(&self, a: i64, w: &[Win; 4]) -> Cover {
        let Some((xs, ys, whole)) = self.pixel_box(&w[..3]) else {
            return Cover::Mask(0);
        };
        // Sides within the viewport's (at most `MAX_TARGET_SIDE`): the
        // product fits. Oriented as the set-up orients it (positive area).
        let side = |s: (i32, i32)| i64::from(s.1 - s.0 + 1);
        if whole && mul_narrow(side(xs), side(ys)) <= TINY {
            let wide = |s: (i32, i32)| (i64::from(s.0), i64::from(s.1));
            Cover::Mask(coverage(
                if a < 0 { [0, 2, 1] } else { [0, 1, 2] }
                    .map(|k| (i64::from(w[k][0]), i64::from(w[k][1]))),
                wide(xs),
                wide(ys),
            ))
        } else {
            Cover::Skip
        }
    }

    /// The pixel centres inside the target that the polygon's bounding box
    /// holds, as column and row ranges (rows limited to those drawn), and
    /// whether those rows are all of the box's rows in the viewport; `None`
    /// if there are none: the cheap test that spares tiny and off-screen
    /// triangles their lighting and set-up. Sample `16x + 8` lies in
    /// `[min, max]` for `x ∈ [⌈(min − 8)/16⌉, ⌊(max − 8)/16⌋]`.
    #[inline]
    fn pixel_box(&self, win: &[Win]) -> Option<PixelBox> {
        let (mut minx, mut maxx, mut miny, mut maxy) = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
        for v in win {
            minx = minx.min(v[0]);
            maxx = maxx.max(v[0]);
            miny = miny.min(v[1]);
            maxy = maxy.max(v[1]);
        }
        let c = self.viewport;
        // ⌈(m − 8)/16⌉ = (m + 7) >> 4, ⌊(m − 8)/16⌋ = (m − 8) >> 4 (arithmetic).
        let (u_lo, u_hi) = (((minx + 7) >> 4).max(c.x0), ((maxx - 8) >> 4).min(c.x1));
        let (v_lo, v_hi) = (((miny + 7) >> 4).max(c.y0), ((maxy - 8) >> 4).min(c.y1));
        let (x_lo, x_hi) = (u_lo.max(self.cols.0), u_hi.min(self.cols.1));
        let (y_lo, y_hi) = (v_lo.max(self.rows.0), v_hi.min(self.rows.1));
        (x_lo <= x_hi && y_lo <= y_hi).then_some((
            (x_lo, x_hi),
            (y_lo, y_hi),
            y_lo == v_lo && y_hi == v_hi && x_lo == u_lo && x_hi == u_hi,
        ))
    }

    /// Whether window position `w` lies inside the guard band around the
    /// tile's centre (and, with a depth test, its depth attribute
    /// inside the set-up's range): such a corner goes to the 32-bit set-up
    /// as it is.
    #[inline(always)]
    fn in_guard(&self, w: &Win, depth: bool) -> bool {
        let (ox, oy) = self.origin;
        let g = setup::GUARD as u32;
        (w[0] - ox as i32).unsigned_abs() <= g
            && (w[1] - oy as i32).unsigned_abs() <= g
            && (!depth || w[2] < setup::ATTR)
    }

    /// Calls `f` with the frame limited to each tile ([`TILE`]) that the
    /// rows drawn meet, in turn: one call for a target of at most
    /// [`TILE`] pixels a side.
    pub(crate) fn each_tile<E>(
        &mut self,
        mut f: impl FnMut(&Self) -> Result<(), E>,
    ) -> Result<(), E> {
        let (rows, vp) = (self.rows, self.viewport);
        let (w, h) = (self.w as i32, self.h as i32);
        let mut y = rows.0;
        let mut res = Ok(());
        while y <= rows.1 && res.is_ok() {
            let (_, y1, cy) = tile(h, y);
            self.rows = (y, y1.min(rows.1));
            let mut x = vp.x0;
            while x <= vp.x1 && res.is_ok() {
                let (_, x1, cx) = tile(w, x);
                self.cols = (x, x1);
                self.origin = (16 * cx as i64, 16 * cy as i64);
                res = f(self);
                x = x1 + 1;
            }
            y = y1 + 1;
        }
        self.rows = rows;
        res
    }

    /// Clips polygon `p` (clip-space corners `c`) against the guard band's
    /// planes and, with a depth test, the plane `z_w = 1.5` beyond the far
    /// plane (a pixel there is never drawn: its depth is past 65535), into
    /// `out`; returns the corner count (at most 9: a polygon of 4 and five
    /// planes). A corner on a cut edge gets its window position from its
    /// clip coordinates and its attributes interpolated linearly in window
    /// space, so that every pixel inside the band sees the plane the
    /// unclipped triangle had (SPEC.md 4).
    ///
    /// Each cut is computed from the edge's inside corner to its outside
    /// one, whichever way the polygon runs: two triangles sharing an edge
    /// cut it at the same point, and stay watertight.
    #[inline(never)]
    fn guard_clip<const N: usize>(
        &self,
        p: &[RasterVertex<N>],
        c: &[[i64; 4]],
        depth: bool,
        out: &mut [RasterVertex<N>; 9],
    ) -> usize {
        let mut a = [([0i64; 4], p[0]); 9];
        let mut b = a;
        let mut n = p.len();
        for k in 0..n {
            a[k] = (c[k], p[k]);
        }
        // The guard planes `|x_w − o_x| ≤ G` (1/16 pixel, two pixels and
        // a half to spare), with `x_w = S·x_c/w + S`, `S = 8W`:
        // `(G + o_x − S)·w − S·x_c ≥ 0` and `(G − o_x + S)·w + S·x_c ≥ 0`;
        // `y_w = S′ − S′·y_c/w` (`S′ = 8H`) likewise with `y_c` negated.
        // `|G ± (o − S)| < 2²⁵` (`o`, `S` ≤ 2²⁴), `w ≤ 2³¹`, `S·|x_c| <
        // 2²³·2³⁹` (`window`'s ranges): each distance is below
        // 2⁶² + 2⁵⁶, in `i64`.
        let g = (setup::GUARD - 40) as i64;
        let (sx, sy) = (8 * self.w, 8 * self.h);
        let (ox, oy) = self.origin;
        let (px, mx, py, my) = (g + ox - sx, g - ox + sx, g + oy - sy, g - oy + sy);
        let planes = if depth { 5 } else { 4 };
        for plane in 0..planes {
            let dist = |q: &[i64; 4]| match plane {
                0 => px * q[3] - sx * q[0],
                1 => mx * q[3] + sx * q[0],
                2 => my * q[3] - sy * q[1],
                3 => py * q[3] + sy * q[1],
                _ => 2 * q[3] - q[2],
            };
            let mut m = 0;
            for k in 0..n {
                let (u, v) = (&a[k], &a[(k + 1) % n]);
                let (du, dv) = (dist(&u.0), dist(&v.0));
                if du >= 0 {
                    b[m] = *u;
                    m += 1;
                }
                if (du >= 0) != (dv >= 0) {
                    let ((i, di), (o, dout)) = if du >= 0 {
                        ((u, du), (v, dv))
                    } else {
                        ((v, dv), (u, du))
                    };
                    b[m] = self.guard_cut(i, o, di, dout);
                    m += 1;
                }
            }
            n = m;
            a[..n].copy_from_slice(&b[..n]);
            if n < 3 {
                return 0;
            }
        }
        // A cut corner's clip position is rounded to a unit, which moves
        // its window position by up to `8W / 2w` sixteenths: near a tiny
        // `w` (a near plane close to the eye, a wide target) that is
        // pixels, and the corner can land past the band. Such a corner is
        // moved onto the band's edge (a clamp of a position already that
        // far off), which the set-up's ranges need.
        let (ox, oy) = self.origin;
        let band = setup::GUARD as i64;
        for k in 0..n {
            let mut p = a[k].1;
            p.x = p.x.clamp(ox - band, ox + band);
            p.y = p.y.clamp(oy - band, oy + band);
            p.attr[0] = p.attr[0].clamp(1 - Z_GUARD, Z_GUARD - 1);
            out[k] = p;
        }
        n
    }

    /// The corner where a plane cuts edge `i → o` (`di ≥ 0 > dout`, the
    /// plane's distances): clip position at `t = di / (di − dout)` along
    /// the edge, window position from it, attributes at the matching
    /// window-space fraction `s = di·w_o / (di·w_o − dout·w_i)`.
    fn guard_cut<const N: usize>(
        &self,
        i: &([i64; 4], RasterVertex<N>),
        o: &([i64; 4], RasterVertex<N>),
        di: i64,
        dout: i64,
    ) -> ([i64; 4], RasterVertex<N>) {
        let q = cut(&i.0, &o.0, di, di - dout);
        let w = self.window(&q);
        // With both corners in front of `w = 0`, `0 ≤ s ≤ 1` and the
        // denominator is positive. A corner at or behind it (a raw
        // camera's clip space, where a window position is no position)
        // has no window-space fraction: the clip-space one stands in
        // (`di − dout > 0`).
        let (num, den) = if i.0[3] > 0 && o.0[3] > 0 {
            let num = di as i128 * o.0[3] as i128;
            (num, num - dout as i128 * i.0[3] as i128)
        } else {
            (di as i128, (di - dout) as i128)
        };
        let mut attr = i.1.attr;
        for (a, b) in attr.iter_mut().zip(o.1.attr) {
            let x = (b - *a) as i128 * num;
            let r = if x >= 0 {
                (2 * x + den) / (2 * den)
            } else {
                -((-2 * x + den) / (2 * den))
            };
            *a += r as i64;
        }
        attr[0] = w[2].into();
        (
            q,
            RasterVertex {
                x: w[0].into(),
                y: w[1].into(),
                attr,
            },
        )
    }

    /// A set-up vertex from a window position inside the guard band
    /// (`in_guard`) and its attributes (depth first): relative to the
    /// tile's centre. Without a depth test the depth is not drawn, and not
    /// bounded by the guard band: left out of the set-up.
    #[inline(always)]
    fn setup_vertex<const N: usize>(
        &self,
        x: i32,
        y: i32,
        mut attr: [i64; N],
        depth: bool,
    ) -> setup::Vertex<N> {
        if !depth {
            attr[0] = 0;
        }
        let (ox, oy) = self.origin;
        setup::Vertex {
            x: x - ox as i32,
            y: y - oy as i32,
            a: attr.map(|a| {
                debug_assert!(a.unsigned_abs() <= setup::ATTR as u64);
                a as i32
            }),
        }
    }

    /// Sets up triangle `v` ([`Frame::setup_vertex`]) on the tile's columns
    /// and the rows drawn, calling `span` for each span until it fails.
    #[inline(always)]
    fn set_up<const N: usize, E>(
        &self,
        v: &[setup::Vertex<N>; 3],
        stats: &mut DrawStats,
        span: &mut impl FnMut(&setup::Span<N>, &mut DrawStats) -> Result<(), E>,
    ) -> Result<(), E> {
        let (ox, oy) = self.origin;
        let (cx, cy) = ((ox >> 4) as i32, (oy >> 4) as i32);
        let cols = (self.cols.0 - cx, self.cols.1 - cx);
        let rows = (self.rows.0 - cy, self.rows.1 - cy);
        let mut res = Ok(());
        let drawn = setup::draw(v, cols, rows, (cx, cy), |s| {
            if res.is_ok() {
                res = span(s, stats);
            }
        });
        if drawn {
            stats.drawn = stats.drawn.saturating_add(1);
        }
        res
    }

    /// Draws the polygon `poly` (window positions `win`, attributes of
    /// its original corners from `of`, depth first): the triangle as it
    /// is when `direct` (unclipped, every corner inside the guard band),
    /// else the fan `(p0, p1, p2), (p0, p2, p3), …` of its pieces, the
    /// polygon clipped to the guard band first when a corner lies outside
    /// it (`clips`: its clip-space corners). Every piece faces as the
    /// polygon does (`front`) or draws nothing: culling was decided once,
    /// and a piece that snapping turned over is dropped. Calls `span` for
    /// each span until it fails. (One set-up call site: the span code is
    /// inlined into it once.)
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn pieces<const N: usize, E>(
        &self,
        poly: &[PolyVert],
        win: &[Win; 4],
        direct: bool,
        clips: Option<&[[i64; 4]]>,
        front: bool,
        depth: bool,
        stats: &mut DrawStats,
        of: impl Fn(usize) -> [i64; N],
        mut span: impl FnMut(&setup::Span<N>, &mut DrawStats) -> Result<(), E>,
    ) -> Result<(), E> {
        let at = |k: usize| {
            let mut a = of(k);
            a[0] = win[k][2].into();
            self.setup_vertex(win[k][0], win[k][1], a, depth)
        };
        let (verts, mut clipped);
        let (fan, tris): (&[RasterVertex<N>], usize) = if direct {
            (&[], 1)
        } else {
            verts = raster_verts::<N>(poly, win, &of);
            let p = match clips {
                None => &verts[..poly.len()],
                Some(c) => {
                    clipped = [verts[0]; 9];
                    let n = self.guard_clip(&verts[..poly.len()], c, depth, &mut clipped);
                    &clipped[..n]
                }
            };
            (p, p.len().saturating_sub(2))
        };
        let none = setup::Vertex {
            x: 0,
            y: 0,
            a: [0; N],
        };
        let first = if direct {
            [at(0), at(1), at(2)]
        } else {
            [none; 3]
        };
        let mut res = Ok(());
        for k in 0..tris {
            let v = if direct {
                first
            } else {
                let v = [&fan[0], &fan[k + 1], &fan[k + 2]].map(|p| {
                    debug_assert!(self.in_guard(&[p.x, p.y, p.attr[0]].map(|v| v as i32), depth));
                    // Inside the guard band: positions and attributes fit `i32`.
                    self.setup_vertex(p.x as i32, p.y as i32, p.attr, depth)
                });
                // Inside the guard band the doubled area fits `i32`
                // (`setup`'s ranges); negative is a front face (y down).
                let area =
                    (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
                if area == 0 || (area < 0) != front {
                    continue;
                }
                v
            };
            res = self.set_up(&v, stats, &mut span);
            if res.is_err() {
                break;
            }
        }
        res
    }

    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn span_flat<P: PixelSink, D: DepthTest>(
        &self,
        s: &setup::Span<1>,
        colour: Shade,
        plain: u16,
        sink: &mut P,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), RenderError<P::Error>> {
        let sh = FlatShader {
            plain,
            shade: colour,
            dither: self.r.options.dither,
            x: s.x0,
            y: s.y,
        };
        self.send(s, sink, depth, stats, sh)
    }

    /// Gouraud spans of at least [`PAIR_SPAN`] pixels are coloured two
    /// pixels at a time ([`PairGouraud`]: cheaper per pixel, dearer to set
    /// up); shorter ones one at a time ([`PackedGouraud`]). Which one a span
    /// takes depends on its length only, so bands and whole frames agree.
    ///
    /// Undithered spans need no range check: vertex colours are at least
    /// ½ LSB (2¹⁵) inside their fields, more than a span's drift
    /// ([`DRIFT`], plus ½ a pixel across at most a tile's columns) plus the
    /// pair shader's lane margin. Dithered ones are clamped per pixel
    /// ([`ClampedGouraud`]).
    #[inline(always)]
    fn span_gouraud<P: PixelSink, D: DepthTest>(
        &self,
        s: &setup::Span<4>,
        sink: &mut P,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), RenderError<P::Error>> {
        const { assert!(DRIFT + CLIP_LIMIT / 2 + LANE_MARGIN < 1 << 15) };
        let dither = self.r.options.dither;
        let c = [s.start[1], s.start[2], s.start[3]];
        let d = [s.step[1], s.step[2], s.step[3]];
        let n = (s.x1 - s.x0 + 1) as u32;
        if !dither {
            return if n >= PAIR_SPAN {
                self.send(s, sink, depth, stats, PairGouraud::new_inside(c, d, n))
            } else {
                self.send(s, sink, depth, stats, PackedGouraud::new_inside(c, d))
            };
        }
        let sh = ClampedGouraud {
            c: c.map(i64::from),
            d: d.map(i64::from),
            dither,
            x: s.x0,
            y: s.y,
        };
        self.send(s, sink, depth, stats, sh)
    }

    /// A Phong span: `cur` and `d` are the normal (`Q.26`) and the eye
    /// position (`I8F24` raw) at its first pixel and their steps.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn span_phong<P: PixelSink, D: DepthTest>(
        &self,
        s: &setup::Span<7>,
        cur: [i64; 6],
        d: [i64; 6],
        sink: &mut P,
        depth: &mut D,
        stats: &mut DrawStats,
    ) -> Result<(), RenderError<P::Error>> {
        let sh = PhongPixels {
            lighting: &self.r.lighting,
            cur,
            d,
            dither: self.r.options.dither,
            x: s.x0,
            y: s.y,
        };
        self.send(s, sink, depth, stats, sh)
    }

    /// One span through the depth test (attribute 0) into the sink.
    #[inline(always)]
    fn send<const N: usize, P: PixelSink, D: DepthTest, Sh: SpanShader>(
        &self,
        s: &setup::Span<N>,
        sink: &mut P,
        depth: &mut D,
        stats: &mut DrawStats,
        sh: Sh,
    ) -> Result<(), RenderError<P::Error>> {
        let n = (s.x1 - s.x0 + 1) as u32;
        // The depth attribute is `z_w·65535·2⁸ + 2⁷` (`window`); in
        // `0 .. 65535·2⁸` its `>> 8` is 0 ..= 65534, a `u16` below the
        // cleared 65535, and the span needs no clamp. Stepped by a rounded
        // step it strays up to ½ a pixel from the plane, so the span's two
        // ends decide (it is linear along the span). Both ends lie within
        // `±(ATTR + DRIFT + 2¹⁰)` (`setup`'s ranges, `n` at most a tile's
        // 2 032 columns), inside `i32`: the wrapping sum is that value.
        let (z, dz) = (s.start[0], s.step[0]);
        let last = z.wrapping_add((n as i32 - 1).wrapping_mul(dz));
        let range = 0..65535 << 8;
        let z = SpanDepth {
            z: z as i64,
            dz: dz as i64,
            inside: range.contains(&z) && range.contains(&last),
        };
        let w = emit(sink, depth, s.y, s.x0, n, z, sh).map_err(RenderError::Target)?;
        stats.pixels = stats.pixels.saturating_add(w);
        Ok(())
    }
}

/// The depth attribute's bound in the set-up (`setup::ATTR`): a corner
/// past it (beyond `z_w = 2`, so never drawn) is clipped at `z_w = 1.5`.
const Z_GUARD: i64 = setup::ATTR as i64;

/// The shortest Gouraud span coloured two pixels at a time. The pair
/// shader's set-up (three lanes from `Q.16`, the per-pair step) costs more
/// than the one-pixel shader's, so short spans keep the latter; 16 is a
/// judgement, not a measured break-even (S1, whose spans are short, counts
/// the same instructions with 16 or 32 here: callgrind, `band_cost`).
pub const PAIR_SPAN: u32 = 16;

/// Raster vertices of a clipped polygon: window position, depth as
/// attribute 0, the other attributes from `of` for original vertices and
/// interpolated along the cut edge (linearly in clip space, as SPEC.md's
/// clipping does) for new ones.
fn raster_verts<const N: usize>(
    poly: &[PolyVert],
    win: &[Win; 4],
    of: &impl Fn(usize) -> [i64; N],
) -> [RasterVertex<N>; 4] {
    let mut out = [RasterVertex {
        x: 0,
        y: 0,
        attr: [0i64; N],
    }; 4];
    for (k, p) in poly.iter().enumerate() {
        let mut attr = match *p {
            PolyVert::Orig(i) => of(i),
            PolyVert::Cut { a, b, num, den } => {
                let (va, vb) = (of(a), of(b));
                let mut m = [0i64; N];
                for j in 0..N {
                    m[j] = va[j] + lerp_part(vb[j] - va[j], num, den);
                }
                m
            }
        };
        attr[0] = win[k][2].into();
        out[k] = RasterVertex {
            x: win[k][0].into(),
            y: win[k][1].into(),
            attr,
        };
    }
    out
}

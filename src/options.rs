//! What a draw is asked and what it answers: the shading modes, the
//! switches, the counts and the errors. Every stage of the pipeline reads
//! these; [`render`](crate::render) is their public home.

use embedded_graphics::prelude::Size;
use embedded_graphics::primitives::Rectangle;

use crate::camera::CameraError;
use crate::mesh::MeshError;

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
/// integer arithmetic (20 fractional bits below the RGB565 step, see
/// `src/setup.rs`).
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
    /// The scene is too small for the world's absolute formats on this
    /// target: by [`Camera::resolves`](crate::camera::Camera::resolves)'s
    /// estimate, the steps of 2⁻²⁴ world units would move its pixels by
    /// more than about 1/512 px. Express it in smaller units (larger
    /// numbers), nearer the world's origin.
    SceneTooSmall,
    /// The scene has lights (they read normals, in every shading mode),
    /// and the model-view matrix has no
    /// [`normal_matrix`](crate::vector::normal_matrix): it is singular at
    /// its entries' precision, or scales one direction more than about
    /// [`MAX_ANISOTROPY`](crate::vector::MAX_ANISOTROPY) times another.
    DegenerateModel,
    /// The mesh may need clipping, and the crate was built without its
    /// `clip` feature: nothing was drawn. Without the feature a draw goes
    /// ahead only where the mesh's box (its [`Bounds`](crate::mesh::Bounds)
    /// placed by the model-view: a loose box is refused sooner) lies wholly
    /// in front of the near plane, not far past the far plane, inside the
    /// guard band (1 023 pixels each way from the target's centre, so a
    /// target over 2 044 pixels a side has pixels past it) and not so near
    /// the eye that the vertex stage's 32-bit form loses precision. A box
    /// wholly behind the near plane or past one side of the band draws
    /// nothing, without this error. Build with the feature (a default one)
    /// to draw the rest.
    NeedsClipping,
    /// The target reported an error.
    Target(E),
}

impl<E> RenderError<E> {
    /// The same error for a target of error type `F`, or the target's own
    /// (`Err`).
    fn convert<F>(self) -> Result<RenderError<F>, E> {
        Ok(match self {
            RenderError::Mesh(m) => RenderError::Mesh(m),
            RenderError::Camera(c) => RenderError::Camera(c),
            RenderError::CacheTooSmall => RenderError::CacheTooSmall,
            RenderError::NoNormals => RenderError::NoNormals,
            RenderError::DepthTooSmall => RenderError::DepthTooSmall,
            RenderError::BandTooSmall => RenderError::BandTooSmall,
            RenderError::TargetTooLarge => RenderError::TargetTooLarge,
            RenderError::SceneTooSmall => RenderError::SceneTooSmall,
            RenderError::DegenerateModel => RenderError::DegenerateModel,
            RenderError::NeedsClipping => RenderError::NeedsClipping,
            RenderError::Target(e) => return Err(e),
        })
    }

    /// The target's own error apart (`Err`), or the renderer's (`Ok`).
    pub(crate) fn split(self) -> Result<RenderError<core::convert::Infallible>, E> {
        self.convert()
    }
}

impl RenderError<core::convert::Infallible> {
    /// An error of a sink that cannot fail (memory) as another target's.
    pub(crate) fn lift<E>(self) -> RenderError<E> {
        match self.convert() {
            Ok(e) => e,
            Err(never) => match never {},
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
            RenderError::SceneTooSmall => f.write_str(
                "scene too small for the world's 2^-24 steps on this target: express it in smaller units",
            ),
            RenderError::DegenerateModel => {
                f.write_str("model matrix singular or scaling one axis over 2^11 times another")
            }
            RenderError::NeedsClipping => f.write_str(
                "mesh may need clipping (near plane, guard band), and the crate was built without its clip feature",
            ),
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

//! The draw call: a [`Renderer`] (camera, material, lights and the choices
//! made at compile time), a mesh [`Shaded`] by it, and the [`Output`] it
//! goes to.
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565};
//! use fixshade::prelude::*;
//!
//! // A triangle in the box [−2, 2)³, where q = ±16384 is ±1.
//! static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
//! static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
//! const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
//!
//! let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
//! let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
//! let material = Material::new();
//! let renderer = Renderer::new(&camera, &material, &sun);
//! let mut display = MockDisplay::<Rgb565>::new();
//! let stats = MESH.shaded(&renderer).draw(&mut display).unwrap();
//! assert!(stats.pixels > 100);
//! ```
//!
//! What is chosen where, every type inferred from the values:
//!
//! | choice | made by | options |
//! | --- | --- | --- |
//! | specular model | the [`Material`] | none, [`Phong`](crate::material::Phong), [`BlinnPhong`](crate::material::BlinnPhong) |
//! | lights | the lights value | one light, a tuple, an array, [`AnyLight`](crate::light::AnyLight)s |
//! | viewer | [`Renderer::with_viewer`] | [`InfiniteViewer`] (default), [`LocalViewer`](crate::illumination::LocalViewer) |
//! | shading | [`Renderer::with_shading`] | [`Flat`](crate::render::Flat), [`Gouraud`] (default), [`PhongShading`](crate::render::PhongShading) |
//! | depth test | [`Shaded::with_depth`] | none (default), [`DepthBuffer`], [`DepthBand`] |
//! | vertex storage | [`Shaded::with_cache`] | recomputed (default), one [`CachedVertex`] per vertex |
//! | output | the argument of [`Shaded::draw`] | any `DrawTarget`, a [`Framebuffer`] (written in place), [`Bands`] |
//!
//! What a scene does not use is not compiled.
//!
//! [`Bands`]: crate::band::Bands
//! [`DepthBuffer`]: crate::depth::DepthBuffer
//! [`Framebuffer`]: crate::framebuffer::Framebuffer
//! [`DepthBand`]: crate::depth::DepthBand

use core::convert::Infallible;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::Drawable;

use crate::band::{Cached, Recomputed, VertexMode};
use crate::camera::Camera;
use crate::color::Rgb;
use crate::depth::{DepthTest, NoDepth};
use crate::illumination::{InfiniteViewer, Lighting, Viewer};
use crate::light::LightSet;
use crate::material::{Material, Specular};
use crate::mesh::Mesh;
use crate::render::CachedVertex;
use crate::render::{DrawStats, Gouraud, RenderError, RenderOptions, ShadingMode};
use crate::vector::Mat4;

pub use crate::output::{FrameDepth, Output};

/// How a scene is drawn: the camera, the material, the lights, the global
/// ambient light, the viewer, the shading mode and the switches. Built once
/// and shared by every mesh of a frame ([`Mesh::shaded`]); the lights are
/// taken to eye space once a draw.
///
/// ```
/// use fixshade::prelude::*;
/// let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// let sun = DirectionalLight::new([1.0, 1.0, 1.0]).unwrap();
/// let material = Material::new();
/// let renderer = Renderer::new(&camera, &material, &sun)
///     .with_ambient(Rgb::grey(0.1))
///     .with_viewer(LocalViewer)
///     .with_shading(Flat);
/// assert!(renderer.options().cull);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Renderer<'l, S: Specular, L: LightSet, V: Viewer = InfiniteViewer, M = Gouraud> {
    camera: &'l Camera,
    material: &'l Material<S>,
    lights: &'l L,
    ambient: Rgb,
    options: RenderOptions,
    viewer: V,
    shading: M,
}

impl<'l, S: Specular, L: LightSet> Renderer<'l, S, L> {
    /// A renderer of `material` under `lights` (world space) seen by
    /// `camera`: no global ambient light, the infinite viewer, Gouraud
    /// shading, [`RenderOptions::default`].
    ///
    /// It borrows all three, as the draw does: a camera, material or
    /// lights that are constants stay constants, whose set-up the
    /// compiler folds into the program (a copy would hide them from it).
    pub fn new(camera: &'l Camera, material: &'l Material<S>, lights: &'l L) -> Self {
        Renderer {
            camera,
            material,
            lights,
            ambient: Rgb::BLACK,
            options: RenderOptions::default(),
            viewer: InfiniteViewer,
            shading: Gouraud,
        }
    }
}

impl<'l, S: Specular, L: LightSet, V: Viewer, M: ShadingMode> Renderer<'l, S, L, V, M> {
    /// The global ambient light `A` (SPEC.md 3).
    #[must_use]
    pub fn with_ambient(self, ambient: Rgb) -> Self {
        Renderer { ambient, ..self }
    }

    /// The viewer: [`InfiniteViewer`] or
    /// [`LocalViewer`](crate::illumination::LocalViewer).
    pub fn with_viewer<W: Viewer>(self, viewer: W) -> Renderer<'l, S, L, W, M> {
        Renderer {
            camera: self.camera,
            material: self.material,
            lights: self.lights,
            ambient: self.ambient,
            options: self.options,
            viewer,
            shading: self.shading,
        }
    }

    /// The shading mode: [`Flat`](crate::render::Flat), [`Gouraud`] or
    /// [`PhongShading`](crate::render::PhongShading).
    pub fn with_shading<N: ShadingMode>(self, shading: N) -> Renderer<'l, S, L, V, N> {
        Renderer {
            camera: self.camera,
            material: self.material,
            lights: self.lights,
            ambient: self.ambient,
            options: self.options,
            viewer: self.viewer,
            shading,
        }
    }

    /// Culling, two-sided lighting and dithering.
    #[must_use]
    pub fn with_options(self, options: RenderOptions) -> Self {
        Renderer { options, ..self }
    }

    /// The camera.
    pub fn camera(&self) -> &Camera {
        self.camera
    }

    /// The switches.
    ///
    /// ```
    /// use fixshade::prelude::*;
    /// let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    /// let material = Material::new();
    /// let renderer = Renderer::new(&camera, &material, &sun);
    /// assert_eq!(renderer.options(), RenderOptions::default());
    /// ```
    pub fn options(&self) -> RenderOptions {
        self.options
    }

    /// The illumination equation prepared for the camera: what a vertex or
    /// pixel is lit by (eye space).
    ///
    /// ```
    /// use fixshade::prelude::*;
    /// let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    /// let material = Material::new();
    /// let renderer = Renderer::new(&camera, &material, &sun);
    /// // A surface facing the light: 0.8 diffuse.
    /// let s = renderer.lighting().shade(Vec3::ZERO, Unit3::Z);
    /// assert_eq!(s.to_rgb565(), embedded_graphics::pixelcolor::Rgb565::new(25, 50, 25));
    /// // No global ambient light by default.
    /// assert_eq!(renderer.lighting().ambient(), fixshade::Shade::BLACK);
    /// ```
    pub fn lighting(&self) -> Lighting<S, V, L> {
        Lighting::new(self.material, self.ambient, self.lights, &self.camera.view)
    }
}

impl<'m> Mesh<'m> {
    /// This mesh drawn by `renderer`: the draw call's builder (model
    /// matrix, depth test, vertex storage), drawn by [`Shaded::draw`].
    pub fn shaded<'a, R>(&'a self, renderer: &'a R) -> Shaded<'a, 'm, R> {
        Shaded {
            mesh: self,
            renderer,
            model: Mat4::IDENTITY,
            depth: NoDepth,
            vertices: Recomputed,
        }
    }
}

/// A mesh shaded by a [`Renderer`] ([`Mesh::shaded`]), with its model
/// matrix, its depth test and where its vertices are kept, ready to draw
/// into an [`Output`].
///
/// Without a depth test or a vertex cache it is an `embedded-graphics`
/// [`Drawable`] as well.
#[derive(Debug)]
pub struct Shaded<'a, 'm, R, D = NoDepth, C = Recomputed> {
    mesh: &'a Mesh<'m>,
    renderer: &'a R,
    model: Mat4,
    depth: D,
    vertices: C,
}

impl<'a, 'm, R, D, C> Shaded<'a, 'm, R, D, C> {
    /// The model matrix, object to world space (default: the identity).
    /// Where the scene has lights (they read normals, in every shading
    /// mode), a singular one, or one that scales a direction more than about
    /// [`MAX_ANISOTROPY`](crate::vector::MAX_ANISOTROPY) times another,
    /// is refused ([`RenderError::DegenerateModel`](crate::render::RenderError::DegenerateModel)):
    /// the normals would have no direction. Without lights it draws.
    ///
    /// ```
    /// use fixshade::prelude::*;
    /// use fixshade::render::RenderError;
    /// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
    /// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
    /// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
    /// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    /// let glow = Material::new().with_emission(Rgb::grey(0.5));
    /// // Flattens z: singular, though the triangle (at z = 0) keeps its shape.
    /// let m = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0; 4], [0.0, 0.0, 0.0, 1.0]];
    /// let squash = Mat4::from_f32(m).unwrap();
    /// let mut px = [0u16; 32 * 32];
    /// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
    /// let lit = Renderer::new(&camera, &glow, &sun);
    /// let e = MESH.shaded(&lit).with_model(squash).draw(&mut fb);
    /// assert_eq!(e, Err(RenderError::DegenerateModel));
    /// // Its shadow, say, drawn without lights: the emission alone.
    /// let unlit = Renderer::new(&camera, &glow, &());
    /// let s = MESH.shaded(&unlit).with_model(squash).draw(&mut fb).unwrap();
    /// assert!(s.pixels > 50 && px.iter().all(|&p| p == 0 || p == px[16 * 32 + 16]));
    /// ```
    #[must_use]
    pub fn with_model(self, model: Mat4) -> Self {
        Shaded { model, ..self }
    }

    /// Tests and writes `depth`: a [`DepthBuffer`](crate::depth::DepthBuffer)
    /// of the target's size for a whole frame, a
    /// [`DepthBand`](crate::depth::DepthBand) for [`Bands`](crate::band::Bands). Clearing a
    /// depth buffer between frames is the caller's
    /// ([`DepthBuffer::clear`](crate::depth::DepthBuffer::clear)).
    pub fn with_depth<'z, Z: DepthTest>(self, depth: &'z mut Z) -> Shaded<'a, 'm, R, &'z mut Z, C> {
        Shaded {
            mesh: self.mesh,
            renderer: self.renderer,
            model: self.model,
            depth,
            vertices: self.vertices,
        }
    }

    /// Transforms, projects and lights each vertex once, into `cache` (one
    /// [`CachedVertex`] per mesh vertex, 16 bytes each), instead of once
    /// per triangle that uses it.
    pub fn with_cache<'c>(self, cache: &'c mut [CachedVertex]) -> Shaded<'a, 'm, R, D, Cached<'c>> {
        Shaded {
            mesh: self.mesh,
            renderer: self.renderer,
            model: self.model,
            depth: self.depth,
            vertices: Cached(cache),
        }
    }
}

impl<S, L, V, M, D, C> Shaded<'_, '_, Renderer<'_, S, L, V, M>, D, C>
where
    S: Specular,
    L: LightSet,
    V: Viewer,
    M: ShadingMode,
    C: VertexMode,
{
    /// Draws the mesh into `output`: any `DrawTarget<Color = Rgb565>` (one
    /// `fill_contiguous` per span), a [`Framebuffer`](crate::framebuffer::Framebuffer) (written in place),
    /// or [`Bands`](crate::band::Bands). Clearing the target is the caller's, except for
    /// bands, each cleared to its background.
    ///
    /// ```
    /// use fixshade::prelude::*;
    /// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
    /// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
    /// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
    /// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    /// let material = Material::new();
    /// let renderer = Renderer::new(&camera, &material, &sun);
    /// let (mut px, mut z) = ([0u16; 32 * 32], [0u16; 32 * 32]);
    /// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
    /// let mut depth = DepthBuffer::new(&mut z, 32, 32).unwrap(); // cleared
    /// let mut cache = [CachedVertex::new(); 3];
    /// let spin = Mat4::rotation_y(0.3);
    /// MESH.shaded(&renderer)
    ///     .with_model(spin)
    ///     .with_depth(&mut depth)
    ///     .with_cache(&mut cache)
    ///     .draw(&mut fb)
    ///     .unwrap();
    /// assert_eq!(fb.pixel(16, 16), Some(Rgb565::new(24, 48, 24)));
    /// ```
    ///
    /// A `DrawTarget` gets no pixel outside its bounding box (the
    /// viewport, SPEC.md 1) and none twice (a `MockDisplay`, 64 × 64,
    /// panics on either), and the count is of the pixels sent:
    ///
    /// ```
    /// use embedded_graphics::{mock_display::MockDisplay, prelude::*};
    /// use fixshade::prelude::*;
    /// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
    /// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
    /// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
    /// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    /// let material = Material::new();
    /// let renderer = Renderer::new(&camera, &material, &sun);
    /// let mut display = MockDisplay::<Rgb565>::new();
    /// let s = MESH.shaded(&renderer).draw(&mut display).unwrap();
    /// let drawn = (0..64)
    ///     .flat_map(|y| (0..64).map(move |x| Point::new(x, y)))
    ///     .filter(|&p| display.get_pixel(p).is_some())
    ///     .count();
    /// assert_eq!(s.pixels as usize, drawn);
    /// ```
    ///
    /// A [`Framebuffer`](crate::framebuffer::Framebuffer) is written in place (no `fill_contiguous` call per
    /// span): the same pixels as through its `DrawTarget`,
    /// [`Framebuffer::canvas`](crate::framebuffer::Framebuffer::canvas):
    ///
    /// ```
    /// use fixshade::prelude::*;
    /// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
    /// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
    /// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
    /// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    /// let material = Material::new();
    /// let renderer = Renderer::new(&camera, &material, &sun);
    /// let (mut a, mut b) = ([0u16; 32 * 32], [0u16; 32 * 32]);
    /// let mut fb = Framebuffer::new(&mut a, 32, 32).unwrap();
    /// MESH.shaded(&renderer).draw(&mut fb.canvas()).unwrap();
    /// let mut fb = Framebuffer::new(&mut b, 32, 32).unwrap();
    /// MESH.shaded(&renderer).draw(&mut fb).unwrap();
    /// assert_eq!(a, b);
    /// ```
    ///
    /// [`Bands`](crate::band::Bands) render the frame a few rows at a time through a small
    /// colour band (and a [`DepthBand`](crate::depth::DepthBand)), each
    /// band sent to the display as one `fill_contiguous`: the pixels of the
    /// whole frame drawn over the background, with cached or recomputed
    /// vertices. A buffer too small is an error, and nothing is drawn:
    ///
    /// ```
    /// use embedded_graphics::prelude::*;
    /// use fixshade::prelude::*;
    /// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
    /// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
    /// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
    /// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    /// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    /// let material = Material::new();
    /// let renderer = Renderer::new(&camera, &material, &sun);
    /// // The display: here a framebuffer's canvas; any DrawTarget<Color = Rgb565>.
    /// let mut px = [0u16; 32 * 32];
    /// let mut display = Framebuffer::new(&mut px, 32, 32).unwrap();
    /// // A band of 32 × 4 pixels, colour and depth: 512 bytes.
    /// let (mut colour, mut z) = ([0u16; 32 * 4], [0u16; 32 * 4]);
    /// let mut cache = [CachedVertex::new(); 3];
    /// MESH.shaded(&renderer)
    ///     .with_depth(&mut DepthBand::new(&mut z))
    ///     .with_cache(&mut cache)
    ///     .draw(&mut Bands::new(&mut display.canvas(), &mut colour, 4).with_background(Rgb565::BLUE))
    ///     .unwrap();
    /// assert_eq!(display.pixel(16, 16), Some(Rgb565::new(25, 50, 25)));
    /// assert_eq!(display.pixel(0, 0), Some(Rgb565::BLUE));
    ///
    /// // The whole frame, cleared to the background, with a depth buffer.
    /// let (mut whole, mut zs) = ([0u16; 32 * 32], [0u16; 32 * 32]);
    /// let mut fb = Framebuffer::new(&mut whole, 32, 32).unwrap();
    /// fb.clear(Rgb565::BLUE);
    /// let mut depth = DepthBuffer::new(&mut zs, 32, 32).unwrap();
    /// MESH.shaded(&renderer).with_depth(&mut depth).draw(&mut fb).unwrap();
    /// assert_eq!(display.as_slice(), fb.as_slice());
    ///
    /// // No vertex storage at all: the same pixels.
    /// display.clear(Rgb565::BLACK);
    /// MESH.shaded(&renderer)
    ///     .with_depth(&mut DepthBand::new(&mut z))
    ///     .draw(&mut Bands::new(&mut display.canvas(), &mut colour, 4).with_background(Rgb565::BLUE))
    ///     .unwrap();
    /// assert_eq!(display.as_slice(), fb.as_slice());
    ///
    /// // A depth band too small for the band.
    /// display.clear(Rgb565::BLACK);
    /// let e = MESH
    ///     .shaded(&renderer)
    ///     .with_depth(&mut DepthBand::new(&mut z[..100]))
    ///     .draw(&mut Bands::new(&mut display.canvas(), &mut colour, 4));
    /// assert_eq!(e, Err(RenderError::DepthTooSmall));
    /// assert!(px.iter().all(|&p| p == 0));
    /// ```
    #[inline(always)]
    pub fn draw<O: Output<D>>(self, output: &mut O) -> Result<DrawStats, RenderError<O::Error>> {
        // Taken apart: a pointer into the builder would keep it in memory
        // through the draw, and with it the addresses of the lights and
        // the material, whose constants would then no longer fold.
        let Shaded {
            mesh,
            renderer: r,
            model,
            depth,
            mut vertices,
        } = self;
        crate::explicit::draw::<M, V, S, L, O, D, C>(
            r.camera,
            r.material,
            r.lights,
            r.ambient,
            r.options,
            mesh,
            model,
            depth,
            &mut vertices,
            output,
        )
    }
}

impl<S, L, V, M> Drawable for Shaded<'_, '_, Renderer<'_, S, L, V, M>>
where
    S: Specular,
    L: LightSet,
    V: Viewer,
    M: ShadingMode,
{
    type Color = Rgb565;
    /// The draw's counts, or why nothing was drawn (the target's own
    /// errors are `draw`'s).
    type Output = Result<DrawStats, RenderError<Infallible>>;

    fn draw<T: DrawTarget<Color = Rgb565>>(
        &self,
        target: &mut T,
    ) -> Result<Self::Output, T::Error> {
        let r = self.renderer;
        let drawn = crate::explicit::draw::<M, V, S, L, T, NoDepth, Recomputed>(
            r.camera,
            r.material,
            r.lights,
            r.ambient,
            r.options,
            self.mesh,
            self.model,
            NoDepth,
            &mut Recomputed,
            target,
        );
        match drawn {
            Ok(stats) => Ok(Ok(stats)),
            Err(e) => e.split().map(Err),
        }
    }
}

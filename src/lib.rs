//! Shaded 3D meshes on microcontroller displays: a `no_std`,
//! allocation-free, fixed-point renderer that lights, shades and
//! rasterizes triangle meshes into any `embedded-graphics` `DrawTarget` in
//! RGB565, within one LSB of an f64 reference, on cores with or without an
//! FPU.
//!
//! ```
//! use embedded_graphics::mock_display::MockDisplay; // or your display driver
//! use fixshade::prelude::*;
//!
//! // A tetrahedron in the cube [−1, 1)³ (positions are fractions of the box).
//! static POSITIONS: [[i16; 3]; 4] =
//!     [[0, 32767, 0], [-28000, -16000, 16000], [28000, -16000, 16000], [0, -16000, -32767]];
//! static TRIANGLES: [[u16; 3]; 4] = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]];
//! const MESH: Mesh = Mesh::new(&POSITIONS, Bounds::cube(1.0), &TRIANGLES);
//!
//! let camera = Camera::look_at([0.0, 0.5, 3.0], [0.0; 3], [0.0, 1.0, 0.0])?;
//! let sun = DirectionalLight::new([1.0, 1.0, 1.0])?;
//! let material = Material::new().with_diffuse(Rgb::clamped(1.0, 0.5, 0.2));
//! let renderer = Renderer::new(&camera, &material, &sun).with_shading(Flat);
//!
//! let mut display = MockDisplay::<Rgb565>::new();
//! let stats = MESH.shaded(&renderer).with_model(Mat4::rotation_y(0.5)).draw(&mut display)?;
//! assert!(stats.pixels > 300);
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```
//!
//! A [`Renderer`] holds what a frame shares (camera, material, lights,
//! viewer, shading mode); [`Mesh::shaded`](mesh::Mesh::shaded) starts a
//! draw, with its model matrix, depth test and vertex storage; the output
//! passed to [`Shaded::draw`] decides how the frame is made: any
//! `DrawTarget`, a [`Framebuffer`](framebuffer::Framebuffer) written in
//! place, or [`Bands`](band::Bands) of a few rows through a small buffer.
//! Every choice is a value whose type the compiler infers, and what a scene
//! does not use is not compiled (the table is in [`Shaded`]'s module,
//! [`renderer`]).
//!
//! # The pipeline
//! One triangle from mesh to pixels, a module a stage:
//!
//! | stage | module |
//! | --- | --- |
//! | mesh in flash: `i16` positions in a box, packed normals, `u16` indices | [`mesh`] |
//! | camera, projection | [`camera`] |
//! | per draw: model-view, projection, window mapping and the mesh's box folded into four rows | `vertex` |
//! | per vertex: window position, depth; lighting | `vertex`, [`illumination`], `light_term`, [`light`], [`material`], `specular_table`, `normalize` |
//! | per triangle: culling, cheap rejections, facing | `triangle` |
//! | the rare path: near and guard-band clipping, big targets | `clip` |
//! | the shading mode's attributes at the corners | `shade` |
//! | set-up: edges and attribute planes | `setup`, `planes` |
//! | coverage: the exact edge walk, rows in tables of up to 32 | `walk`, `planes` |
//! | spans: depth test, shading, RGB565 | `span`, [`depth`], [`color`] |
//! | output: a `DrawTarget`, a framebuffer, bands | [`renderer`], `output`, [`render`], [`framebuffer`], [`band`] |
//!
//! Numbers are fixed-point throughout ([`num`], [`vector`]); each format's
//! range and overflow proof is stated where it is defined. What differs by
//! target (`cfg`s, assembly) is in one module, `platform`. The conventions
//! (coordinate systems, the illumination equation, rounding) are the
//! project's SPEC.md, shipped in the package's `docs/`.
//!
//! # Features
//! - `clip` (default): the rare path, which clips triangles against the
//!   near plane and the guard band (1 023 pixels each way from the
//!   target's centre): 8.5 KB of flash in S1's configuration on a
//!   Cortex-M0+. Without it (`default-features = false`) a draw whose mesh
//!   may need clipping (its box, placed by the model-view, reaches behind
//!   the near plane or past the guard band: decided once a draw) is refused
//!   with [`RenderError::NeedsClipping`](render::RenderError::NeedsClipping)
//!   before any pixel is written; every other draw gives the same frame.
//!
//! # Public items
//!
//! Every public item, by module (the crate root re-exports the most used;
//! [`prelude`] has what a program needs):
//!
//! | module | what | items |
//! | --- | --- | --- |
//! | [`renderer`] | the draw call | [`FrameDepth`](renderer::FrameDepth), [`Output`](renderer::Output), [`Renderer`](renderer::Renderer), [`Shaded`](renderer::Shaded) |
//! | [`render`] | shading modes, options, errors | [`CachedVertex`](render::CachedVertex), [`DrawStats`](render::DrawStats), [`Flat`](render::Flat), [`Gouraud`](render::Gouraud), [`PhongShading`](render::PhongShading), [`RenderError`](render::RenderError), [`RenderOptions`](render::RenderOptions), [`ShadingKind`](render::ShadingKind), [`ShadingMode`](render::ShadingMode), [`MAX_TARGET_SIDE`](render::MAX_TARGET_SIDE) |
//! | [`mesh`] | the mesh in flash | [`Aligned`](mesh::Aligned), [`Bounds`](mesh::Bounds), [`Mesh`](mesh::Mesh), [`MeshError`](mesh::MeshError), [`PackedNormal`](mesh::PackedNormal), [`FLAG_NORMALS`](mesh::FLAG_NORMALS), [`HEADER_LEN`](mesh::HEADER_LEN), [`MAGIC`](mesh::MAGIC), [`VERSION`](mesh::VERSION), [`face_normal`](mesh::face_normal), [`vertex_normals`](mesh::vertex_normals) |
//! | [`camera`] | view and projection | [`Camera`](camera::Camera), [`CameraError`](camera::CameraError), [`Projection`](camera::Projection), [`ProjectionCoeffs`](camera::ProjectionCoeffs) |
//! | [`material`] | surfaces | [`BlinnPhong`](material::BlinnPhong), [`Material`](material::Material), [`NoSpecular`](material::NoSpecular), [`Phong`](material::Phong), [`Specular`](material::Specular) |
//! | [`light`] | lights and their building blocks | [`AnyLight`](light::AnyLight), [`AreaLight`](light::AreaLight), [`Attenuation`](light::Attenuation), [`DirectionalLight`](light::DirectionalLight), [`Falloff`](light::Falloff), [`LightError`](light::LightError), [`LightSet`](light::LightSet), [`NoAttenuation`](light::NoAttenuation), [`PointLight`](light::PointLight), [`PreparedAny`](light::PreparedAny), [`PreparedArea`](light::PreparedArea), [`PreparedDirectional`](light::PreparedDirectional), [`PreparedLights`](light::PreparedLights), [`PreparedPoint`](light::PreparedPoint), [`SpotCone`](light::SpotCone), [`SpotLight`](light::SpotLight), [`unit_from_f32`](light::unit_from_f32), [`unit_from_f64`](light::unit_from_f64) |
//! | [`illumination`] | the illumination equation | [`Gain`](illumination::Gain), [`Gains`](illumination::Gains), [`InfiniteViewer`](illumination::InfiniteViewer), [`Lighting`](illumination::Lighting), [`LocalViewer`](illumination::LocalViewer), [`Surface`](illumination::Surface), [`Viewer`](illumination::Viewer), [`FACTOR_ONE`](illumination::FACTOR_ONE), [`add_light`](illumination::add_light), [`view_dir`](illumination::view_dir) |
//! | [`depth`] | depth tests | [`DepthBand`](depth::DepthBand), [`DepthBuffer`](depth::DepthBuffer), [`DepthBufferTooSmall`](depth::DepthBufferTooSmall), [`DepthTest`](depth::DepthTest), [`NoDepth`](depth::NoDepth) |
//! | [`framebuffer`] | an in-memory target | [`Canvas`](framebuffer::Canvas), [`Framebuffer`](framebuffer::Framebuffer), [`FramebufferTooSmall`](framebuffer::FramebufferTooSmall) |
//! | [`band`] | band rendering | [`BandDepth`](band::BandDepth), [`Bands`](band::Bands), [`Cached`](band::Cached), [`Recomputed`](band::Recomputed), [`VertexMode`](band::VertexMode), [`CHUNKS`](band::CHUNKS) |
//! | [`color`] | colours | [`Rgb`](color::Rgb), [`Shade`](color::Shade), [`RGB_MAX`](color::RGB_MAX), [`SHADE_ONE`](color::SHADE_ONE), [`pack565`](color::pack565) |
//! | [`vector`] | fixed-point vectors and matrices | [`FormatError`](vector::FormatError), [`Mat4`](vector::Mat4), [`Unit3`](vector::Unit3), [`Vec3`](vector::Vec3), [`COORD_FRAC`](vector::COORD_FRAC), [`MAX_ANISOTROPY`](vector::MAX_ANISOTROPY), [`UNIT_ONE`](vector::UNIT_ONE), [`coord_from_f32`](vector::coord_from_f32), [`coord_from_f64`](vector::coord_from_f64), [`normal_matrix`](vector::normal_matrix) |
//! | [`num`] | number formats | [`MiniFloat`](num::MiniFloat), [`WidePoint`](num::WidePoint) |
//!
//! At the root: [`Renderer`], [`Shaded`], [`Output`], [`FrameDepth`], [`Rgb`],
//! [`Shade`], [`Lighting`], [`Material`], [`Mat4`], [`Unit3`], [`Vec3`], the specular
//! exponent [`Exponent`] and the macro [`include_mesh!`].
// The unit tests use the standard library (its prelude, `Vec`, threads).
#![cfg_attr(not(test), no_std)]
#![warn(missing_docs)]
// The public-items list links each item by its module's path, also those
// the root re-exports.
#![allow(rustdoc::redundant_explicit_links)]

pub mod band;
pub mod camera;
mod clip;
pub mod color;
pub mod depth;
// The draw call's last step; public, as the firmware's baseline, only
// with `--cfg fixshade_explicit_draw`.
#[cfg(fixshade_explicit_draw)]
#[doc(hidden)]
pub mod explicit;
#[cfg(not(fixshade_explicit_draw))]
mod explicit;
pub mod framebuffer;
pub mod illumination;
pub mod light;
mod light_term;
pub mod material;
pub mod mesh;
mod normalize;
pub mod num;
mod options;
mod output;
mod planes;
mod platform;
pub mod render;
pub mod renderer;
mod setup;
mod shade;
mod span;
mod specular_table;
mod triangle;
pub mod vector;
mod vertex;
mod walk;

#[cfg(test)]
mod tests;

pub use renderer::{FrameDepth, Output, Renderer, Shaded};

pub use color::{Rgb, Shade};
pub use illumination::Lighting;
pub use material::Material;
pub use specular_table::Exponent;
pub use vector::{Mat4, Unit3, Vec3};

// Every error is a `core::error::Error`, so that `?` reaches a `Box<dyn
// Error>` or an application's own error type.
impl core::error::Error for camera::CameraError {}
impl core::error::Error for depth::DepthBufferTooSmall {}
impl core::error::Error for framebuffer::FramebufferTooSmall {}
impl core::error::Error for light::LightError {}
impl core::error::Error for mesh::MeshError {}
impl<E: core::fmt::Debug> core::error::Error for render::RenderError<E> {}
impl core::error::Error for vector::FormatError {}

/// What a program that draws meshes needs, in one `use`.
///
/// ```
/// use fixshade::prelude::*;
/// let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// let _renderer = Renderer::new(&camera, &Material::new(), &sun).with_shading(Flat);
/// ```
pub mod prelude {
    pub use embedded_graphics::pixelcolor::Rgb565;
    pub use embedded_graphics::Drawable as _;

    pub use crate::band::Bands;
    pub use crate::camera::{Camera, Projection};
    pub use crate::depth::{DepthBand, DepthBuffer};
    pub use crate::framebuffer::Framebuffer;
    pub use crate::illumination::{InfiniteViewer, LocalViewer};
    pub use crate::light::{
        AreaLight, Attenuation, DirectionalLight, PointLight, SpotCone, SpotLight,
    };
    pub use crate::material::{BlinnPhong, Material, Phong};
    pub use crate::mesh::{Bounds, Mesh, PackedNormal};
    pub use crate::render::{
        CachedVertex, Flat, Gouraud, PhongShading, RenderError, RenderOptions,
    };
    pub use crate::{Exponent, Mat4, Renderer, Rgb, Unit3, Vec3};
}

/// The README's code runs as a doc test.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

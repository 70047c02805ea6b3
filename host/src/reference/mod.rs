//! The `f64` reference of the illumination model and rasterizer.
//!
//! It follows SPEC.md to the letter, in double precision, and shares no code
//! with the fixed-point kernel: the kernel's output is compared with
//! [`render`]'s pixel by pixel ([`crate::error_measure::compare`]).
//!
//! * [`lighting`]: the illumination equation ([`illuminate`]) and the
//!   world-to-eye conversion of lights ([`eye_lights`]).
//! * [`raster`]: transforms, near-plane clipping, snapping to 1/16 pixel,
//!   top-left coverage, depth test and the three shading modes ([`render`]).
//!
//! ```
//! use fixshade_host::generate::sphere;
//! use fixshade_host::reference::render;
//! use fixshade_host::scene_desc::{CameraDesc, LightDesc, Projection, SceneDesc};
//!
//! let camera = CameraDesc {
//!     eye: [0.0, 0.0, 4.0], target: [0.0; 3], up: [0.0, 1.0, 0.0],
//!     near: 0.5, far: 10.0, projection: Projection::Perspective { fovy_deg: 40.0 },
//! };
//! let mut scene = SceneDesc::new(32, 32, camera, sphere(24, 12, 1.0));
//! scene.lights.push(LightDesc::directional([1.0, 1.0, 1.0]));
//! let frame = render(&scene).unwrap();
//! assert!(frame.pixel(16, 16).is_some()); // centre covered
//! assert!(frame.pixel(0, 0).is_none());   // corner not
//! ```

pub mod lighting;
mod math;
pub mod raster;

pub use lighting::{
    eye_lights, illuminate, illuminate_with_margin, EyeLight, EyeLights, LightingModel,
};
pub use raster::{
    look_at, orthographic, perspective, quantize_depth, quantize_rgb565, render, vertex_normals,
    RefFrame, STEP_MARGIN,
};

#![doc = include_str!("../README.md")]
// The unit tests use the standard library (its prelude, `Vec`, threads).
#![cfg_attr(not(test), no_std)]
#![warn(missing_docs)]

pub mod band;
pub mod camera;
pub mod color;
pub mod depth;
pub mod framebuffer;
pub mod illumination;
pub mod light;
pub mod material;
pub mod mesh;
pub mod normalize;
pub mod num;
mod platform;
pub mod rasterizer;
pub mod render;
mod setup;
pub mod span;
pub mod specular_table;
pub mod vector;
mod vertex;

pub use color::{Rgb, Shade};
pub use illumination::Lighting;
pub use material::Material;
pub use specular_table::Exponent;
pub use vector::{Mat4, Unit3, Vec3};

#![doc = include_str!("../README.md")]
#![cfg_attr(not(feature = "std"), no_std)]
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
#[cfg(feature = "reference")]
pub mod scene_kernel;
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

#[cfg(feature = "reference")]
pub mod error_measure;
#[cfg(feature = "reference")]
pub mod generate;
#[cfg(feature = "reference")]
pub mod mesh_convert;
#[cfg(feature = "reference")]
pub mod reference;
#[cfg(feature = "reference")]
pub mod scene_desc;
#[cfg(feature = "scene-file")]
pub mod scene_file;
#[cfg(feature = "reference")]
pub mod standard_scenes;

//! fixshade: a `no_std`, allocation-free, fixed-point shading kernel.
#![cfg_attr(not(feature = "std"), no_std)]
#![warn(missing_docs)]

pub mod vector;

pub use vector::{Mat4, Unit3, Vec3};

#[cfg(feature = "reference")]
pub mod error_measure;
#[cfg(feature = "reference")]
pub mod generate;
#[cfg(feature = "reference")]
pub mod reference;
#[cfg(feature = "reference")]
pub mod scene_desc;

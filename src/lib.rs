//! fixshade: a `no_std`, allocation-free, fixed-point shading kernel.
#![cfg_attr(not(feature = "std"), no_std)]
#![warn(missing_docs)]

pub mod normalize;
pub mod vector;

pub use vector::{Mat4, Unit3, Vec3};

//! Number formats beyond the vectors' fixed-point ones, and the arithmetic
//! helpers that keep every format's operations cheap on every core.
//!
//! - [`WidePoint`]: points with `I40F24` components, for positions far
//!   outside the `I8F24` range of [`Vec3`](crate::Vec3) (lights).
//! - [`MiniFloat`]: a 32-bit-mantissa unsigned float for the attenuation
//!   polynomial, whose terms span more than any fixed-point format.
//! - `widening`: products wider than their operands, from 16 × 16 → 32-bit
//!   multiplies where the core has no 32 × 32 → 64-bit one.
//! - `Wide`: an `i64` mantissa and an exponent, once a draw and on the
//!   rare path.
//! - `division`: exact floor divisions, and reciprocals without a
//!   division, where a 64-bit division is a library call.

pub(crate) mod division;
mod mini_float;
mod wide;
mod wide_point;
pub(crate) mod widening;

pub use mini_float::MiniFloat;
pub(crate) use wide::Wide;
pub use wide_point::WidePoint;
pub(crate) use wide_point::{clamp_wide, step_wide};

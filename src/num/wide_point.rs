//! Points with 40 integer bits: positions far outside the `I8F24` range of
//! [`Vec3`], and the clamp that keeps values derived from them in range.

use fixed::types::I40F24;

use crate::vector::{FormatError, Vec3};

/// A point (or displacement) with `I40F24` components: range ±2³⁸ (about
/// ±2.7·10¹¹), resolution 2⁻²⁴. Used for light positions.
///
/// ```
/// use fixshade::num::WidePoint;
/// let p = WidePoint::from_f32([1e4, 0.0, -2.5]).unwrap();
/// assert_eq!(p.to_bits()[2], -(5 << 23));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct WidePoint {
    c: [i64; 3],
}

/// The largest magnitude of a [`WidePoint`] component in raw units: 2⁶²
/// (2³⁸ ≈ 2.7·10¹¹ in value), so a difference of two stays below 2⁶³.
const WIDE_LIMIT: i64 = 1 << 62;

impl WidePoint {
    /// From raw `I40F24` bits, each clamped to ±2⁶² (±2³⁸ in value).
    ///
    /// ```
    /// use fixshade::num::WidePoint;
    /// let p = WidePoint::from_bits(i64::MAX, -5, i64::MIN);
    /// assert_eq!(p.to_bits(), [1 << 62, -5, -(1 << 62)]);
    /// ```
    pub const fn from_bits(x: i64, y: i64, z: i64) -> Self {
        const fn cl(v: i64) -> i64 {
            if v > WIDE_LIMIT {
                WIDE_LIMIT
            } else if v < -(WIDE_LIMIT) {
                -(WIDE_LIMIT)
            } else {
                v
            }
        }
        WidePoint {
            c: [cl(x), cl(y), cl(z)],
        }
    }

    /// From floats; NaN/∞ and magnitudes of 2³⁸ or more are errors.
    ///
    /// ```
    /// use fixshade::num::WidePoint;
    /// use fixshade::vector::FormatError;
    /// let p = WidePoint::from_f32([1.5, -0.25, 65536.0]).unwrap();
    /// assert_eq!(p.to_bits(), [3 << 23, -(1 << 22), 1 << 40]);
    /// assert_eq!(WidePoint::from_f32([0.0, 0.0, 3.0e11]), Err(FormatError::OutOfRange));
    /// assert_eq!(WidePoint::from_f32([f32::INFINITY, 0.0, 0.0]), Err(FormatError::NotFinite));
    /// ```
    pub fn from_f32(v: [f32; 3]) -> Result<Self, FormatError> {
        WidePoint::from_f64(v.map(f64::from))
    }

    /// As [`WidePoint::from_f32`], from `f64`s.
    ///
    /// ```
    /// use fixshade::num::WidePoint;
    /// use fixshade::vector::FormatError;
    /// let limit = (1u64 << 38) as f64;
    /// let edge = WidePoint::from_f64([limit - 1.0, 0.0, 0.0]).unwrap();
    /// assert_eq!(edge.to_bits()[0], (1 << 62) - (1 << 24));
    /// assert_eq!(WidePoint::from_f64([0.0, -limit, 0.0]), Err(FormatError::OutOfRange));
    /// ```
    pub fn from_f64(v: [f64; 3]) -> Result<Self, FormatError> {
        let mut c = [0i64; 3];
        for (o, x) in c.iter_mut().zip(v) {
            if !x.is_finite() {
                return Err(FormatError::NotFinite);
            }
            if x.abs() >= (1u64 << 38) as f64 {
                return Err(FormatError::OutOfRange);
            }
            *o = I40F24::from_num(x).to_bits();
        }
        Ok(WidePoint { c })
    }

    /// From a [`Vec3`] (always fits).
    ///
    /// ```
    /// use fixshade::num::WidePoint;
    /// use fixshade::Vec3;
    /// let p = WidePoint::from_vec3(Vec3::from_f32(1.0, -2.0, 0.5).unwrap());
    /// assert_eq!(p, WidePoint::from_f32([1.0, -2.0, 0.5]).unwrap());
    /// // Same 24 fraction bits: the raw value carries over unchanged.
    /// let min = WidePoint::from_vec3(Vec3::from_bits(i32::MIN, 0, 0));
    /// assert_eq!(min.to_bits(), [i32::MIN as i64, 0, 0]);
    /// ```
    pub const fn from_vec3(v: Vec3) -> Self {
        let b = v.to_bits();
        WidePoint {
            c: [b[0] as i64, b[1] as i64, b[2] as i64],
        }
    }

    /// Raw `I40F24` bits.
    pub const fn to_bits(self) -> [i64; 3] {
        self.c
    }
}

/// `v` clamped to the [`WidePoint`] component range (±2⁶² raw units), for
/// values computed in `i128` from wide points.
#[inline(always)]
pub(crate) fn clamp_wide(v: i128) -> i64 {
    v.clamp(-(WIDE_LIMIT as i128), WIDE_LIMIT as i128) as i64
}

/// `x + step` clamped to the [`WidePoint`] component range (`|x|,
/// |step| ≤ 2⁶²`, so the saturating sum cannot wrap): a coordinate stepped
/// from a wide point (an area light's samples) is exact while it stays in
/// the range and clamped past it, as positions are.
#[inline(always)]
pub(crate) fn step_wide(x: i64, step: i64) -> i64 {
    x.saturating_add(step).clamp(-WIDE_LIMIT, WIDE_LIMIT)
}

//! Fixed-point vectors and matrices of the pipeline.
//!
//! Three formats carry geometry through the kernel; each one's range and
//! precision is stated here, with the reason no product or sum made from it
//! overflows.
//!
//! | type | storage | format | range | resolution |
//! | --- | --- | --- | --- | --- |
//! | [`Vec3`] (positions, object/world/eye space) | `i32` ×3 | `I8F24` | [−128, 128) | 2⁻²⁴ ≈ 6·10⁻⁸ |
//! | [`Unit3`] (unit normals, light and view directions) | `i16` ×3 | `I2F14` | [−1, 1] (invariant) | 2⁻¹⁴ ≈ 6·10⁻⁵ |
//! | [`Mat4`] entries (model, view transforms) | `i32` | `I8F24` | [−128, 128) | 2⁻²⁴ |
//!
//! Why `I8F24` for positions: a light 10⁻³ units from a surface must still
//! give a direction good to 10⁻⁴ (`2⁻²⁴ / 10⁻³ ≈ 6·10⁻⁵`), while the
//! standard scenes (bunny included) fit in ±128 units. Positions outside that
//! range are rejected when a float is converted ([`Vec3::from_f32`]) and
//! saturate where a transform produces them.
//!
//! Why `I2F14` in an `i16` for unit vectors: a dot product of two of them is a
//! sum of three 16 × 16 → 32-bit products, one instruction each on a
//! Cortex-M0. Each component is at most 2¹⁴ in magnitude (the invariant of
//! [`Unit3`]), so each product is at most 2²⁸ and the sum of three at most
//! 3·2²⁸ < 2³¹: no overflow in `i32`.
//!
//! Products of `I8F24` values go through `i64`: `|a·b| < 2⁷·2⁷ = 2¹⁴` in
//! value, `2⁶²` in raw units, and a sum of four such products stays below
//! `2⁶⁴`… which is why [`Mat4::transform_point`] sums at most four products
//! of values that are each below 2⁷ and saturates the result to `I8F24`.

use crate::num::division::DivInt;
use crate::num::widening::{mul_i32, mul_i32_i16, saturate_i32};
use crate::num::Wide;
use crate::platform;
use fixed::types::{I2F14, I8F24};

/// Raw value of 1.0 in the `I2F14` format of [`Unit3`].
///
/// ```
/// use fixshade::vector::UNIT_ONE;
/// use fixshade::Unit3;
/// assert_eq!(Unit3::X.to_bits(), [UNIT_ONE, 0, 0]);
/// assert_eq!(Unit3::X.to_fixed()[0].to_num::<f32>(), 1.0);
/// ```
pub const UNIT_ONE: i16 = 1 << 14;

/// Fractional bits of the `I8F24` position format.
///
/// ```
/// use fixshade::vector::COORD_FRAC;
/// use fixshade::Vec3;
/// let half = Vec3::from_f32(0.5, 0.0, 0.0).unwrap();
/// assert_eq!(half.to_bits()[0], 1 << (COORD_FRAC - 1));
/// ```
pub const COORD_FRAC: u32 = 24;

/// A position or displacement, three `I8F24` components.
///
/// Range [−128, 128) per component, resolution 2⁻²⁴.
///
/// ```
/// use fixshade::Vec3;
/// let p = Vec3::from_f32(1.0, -2.5, 0.25).unwrap();
/// assert_eq!(p.to_f32(), [1.0, -2.5, 0.25]);
/// assert!(Vec3::from_f32(200.0, 0.0, 0.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Vec3 {
    /// x component.
    pub x: I8F24,
    /// y component.
    pub y: I8F24,
    /// z component.
    pub z: I8F24,
}

/// Why a float could not become a fixed-point value.
///
/// ```
/// use fixshade::vector::{coord_from_f32, FormatError};
/// assert_eq!(coord_from_f32(f32::NAN), Err(FormatError::NotFinite));
/// assert_eq!(coord_from_f32(128.0), Err(FormatError::OutOfRange));
/// assert_eq!(FormatError::OutOfRange.to_string(), "value outside the fixed-point range");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FormatError {
    /// The value was NaN or infinite.
    NotFinite,
    /// The value lies outside the format's range.
    OutOfRange,
}

impl core::fmt::Display for FormatError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FormatError::NotFinite => f.write_str("value is NaN or infinite"),
            FormatError::OutOfRange => f.write_str("value outside the fixed-point range"),
        }
    }
}

/// Converts an `f32` to `I8F24`, rounding to nearest; errors for NaN, ±∞ and
/// values outside [−128, 128).
///
/// ```
/// use fixshade::vector::coord_from_f32;
/// assert_eq!(coord_from_f32(-128.0).unwrap().to_bits(), i32::MIN);
/// assert_eq!(coord_from_f32(1.5).unwrap().to_num::<f32>(), 1.5);
/// assert!(coord_from_f32(f32::INFINITY).is_err());
/// ```
pub fn coord_from_f32(v: f32) -> Result<I8F24, FormatError> {
    coord_from_f64(v as f64)
}

/// As [`coord_from_f32`], from an `f64`.
///
/// ```
/// use fixshade::vector::coord_from_f64;
/// // Rounded to the nearest 2^-24.
/// assert_eq!(coord_from_f64(0.6 / 16_777_216.0).unwrap().to_bits(), 1);
/// assert!(coord_from_f64(127.999_999_99).is_err()); // rounds to 128
/// ```
pub fn coord_from_f64(v: f64) -> Result<I8F24, FormatError> {
    if !v.is_finite() {
        return Err(FormatError::NotFinite);
    }
    I8F24::checked_from_num(v).ok_or(FormatError::OutOfRange)
}

impl Vec3 {
    /// The origin.
    ///
    /// ```
    /// use fixshade::Vec3;
    /// assert_eq!(Vec3::ZERO, Vec3::default());
    /// assert_eq!(Vec3::ZERO.to_bits(), [0; 3]);
    /// ```
    pub const ZERO: Vec3 = Vec3::from_bits(0, 0, 0);

    /// Builds a vector from raw `I8F24` bits (usable in `const` and `static`
    /// mesh data).
    ///
    /// ```
    /// use fixshade::Vec3;
    /// const ONE_X: Vec3 = Vec3::from_bits(1 << 24, 0, 0);
    /// assert_eq!(ONE_X.to_f32(), [1.0, 0.0, 0.0]);
    /// ```
    pub const fn from_bits(x: i32, y: i32, z: i32) -> Self {
        Vec3 {
            x: I8F24::from_bits(x),
            y: I8F24::from_bits(y),
            z: I8F24::from_bits(z),
        }
    }

    /// Builds a vector from floats; see [`coord_from_f32`] for the errors.
    ///
    /// ```
    /// use fixshade::vector::FormatError;
    /// use fixshade::Vec3;
    /// assert_eq!(Vec3::from_f32(1.0, 2.0, 3.0).unwrap().to_f32(), [1.0, 2.0, 3.0]);
    /// assert_eq!(Vec3::from_f32(0.0, f32::NAN, 0.0), Err(FormatError::NotFinite));
    /// ```
    pub fn from_f32(x: f32, y: f32, z: f32) -> Result<Self, FormatError> {
        Ok(Vec3 {
            x: coord_from_f32(x)?,
            y: coord_from_f32(y)?,
            z: coord_from_f32(z)?,
        })
    }

    /// Builds a vector from `f64`s; see [`coord_from_f64`].
    ///
    /// ```
    /// use fixshade::vector::FormatError;
    /// use fixshade::Vec3;
    /// assert_eq!(Vec3::from_f64([-1.0, 0.5, 127.0]).unwrap().to_f32(), [-1.0, 0.5, 127.0]);
    /// assert_eq!(Vec3::from_f64([0.0, 0.0, -129.0]), Err(FormatError::OutOfRange));
    /// ```
    pub fn from_f64(v: [f64; 3]) -> Result<Self, FormatError> {
        Ok(Vec3 {
            x: coord_from_f64(v[0])?,
            y: coord_from_f64(v[1])?,
            z: coord_from_f64(v[2])?,
        })
    }

    /// The raw `I8F24` bits of the three components.
    ///
    /// ```
    /// use fixshade::Vec3;
    /// assert_eq!(Vec3::from_f32(1.0, -1.0, 0.0).unwrap().to_bits(), [1 << 24, -(1 << 24), 0]);
    /// ```
    pub const fn to_bits(self) -> [i32; 3] {
        [self.x.to_bits(), self.y.to_bits(), self.z.to_bits()]
    }

    /// The components as `f32` (host-side inspection).
    ///
    /// ```
    /// use fixshade::Vec3;
    /// assert_eq!(Vec3::from_bits(1, 0, -(3 << 22)).to_f32(), [2f32.powi(-24), 0.0, -0.75]);
    /// ```
    pub fn to_f32(self) -> [f32; 3] {
        [self.x.to_num(), self.y.to_num(), self.z.to_num()]
    }
}

/// A unit vector: three `I2F14` components whose length is 1 to within the
/// rounding of each component.
///
/// Invariant: every component lies in [−2¹⁴, 2¹⁴] raw, i.e. [−1, 1]. The only
/// ways to make one are [`Unit3::new_clamped`] (which enforces the bound), the
/// kernel's normalisation (`src/normalize.rs`; for users,
/// [`unit_from_f32`](crate::light::unit_from_f32) and
/// [`unit_from_f64`](crate::light::unit_from_f64)), and the axis constants.
///
/// ```
/// use fixshade::Unit3;
/// let z = Unit3::Z;
/// assert_eq!(z.dot(Unit3::Z), 1 << 28);
/// assert_eq!(z.neg().to_bits(), [0, 0, -(1 << 14)]);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Unit3 {
    c: [i16; 3],
}

impl Unit3 {
    /// +X.
    ///
    /// ```
    /// use fixshade::Unit3;
    /// assert_eq!(Unit3::X.dot(Unit3::Y), 0);
    /// assert_eq!(Unit3::X.dot(Unit3::X), 1 << 28);
    /// ```
    pub const X: Unit3 = Unit3 {
        c: [UNIT_ONE, 0, 0],
    };
    /// +Y.
    ///
    /// ```
    /// use fixshade::Unit3;
    /// assert_eq!(Unit3::Y.to_bits(), [0, 1 << 14, 0]);
    /// ```
    pub const Y: Unit3 = Unit3 {
        c: [0, UNIT_ONE, 0],
    };
    /// +Z (the infinite viewer's direction in eye space).
    ///
    /// ```
    /// use fixshade::Unit3;
    /// assert_eq!(Unit3::Z.dot(Unit3::Z.neg()), -(1 << 28));
    /// ```
    pub const Z: Unit3 = Unit3 {
        c: [0, 0, UNIT_ONE],
    };
    /// The zero vector: what normalising a zero-length vector gives in the
    /// places where SPEC.md makes the term it feeds 0.
    ///
    /// ```
    /// use fixshade::light::{unit_from_f64, LightError};
    /// use fixshade::Unit3;
    /// assert_eq!(unit_from_f64([0.0; 3]), Err(LightError::ZeroDirection));
    /// assert!(Unit3::ZERO.is_zero() && Unit3::ZERO.dot(Unit3::X) == 0);
    /// ```
    pub const ZERO: Unit3 = Unit3 { c: [0, 0, 0] };

    /// Builds a unit vector from raw `I2F14` bits, clamping each component
    /// to [−2¹⁴, 2¹⁴]. The caller is responsible for the length being 1; the
    /// clamp only guarantees the overflow invariant.
    ///
    /// ```
    /// use fixshade::Unit3;
    /// let u = Unit3::new_clamped(i16::MAX, i16::MIN, 100);
    /// assert_eq!(u.to_bits(), [1 << 14, -(1 << 14), 100]);
    /// ```
    pub const fn new_clamped(x: i16, y: i16, z: i16) -> Self {
        const fn cl(v: i16) -> i16 {
            if v > UNIT_ONE {
                UNIT_ONE
            } else if v < -UNIT_ONE {
                -UNIT_ONE
            } else {
                v
            }
        }
        Unit3 {
            c: [cl(x), cl(y), cl(z)],
        }
    }

    /// The raw `I2F14` bits.
    ///
    /// ```
    /// use fixshade::Unit3;
    /// assert_eq!(Unit3::new_clamped(0, -8192, 0).to_bits(), [0, -8192, 0]);
    /// ```
    pub const fn to_bits(self) -> [i16; 3] {
        self.c
    }

    /// The components as fixed-point numbers.
    ///
    /// ```
    /// use fixshade::Unit3;
    /// let f = Unit3::new_clamped(0, -8192, 1 << 14).to_fixed();
    /// assert_eq!(f.map(|c| c.to_num::<f32>()), [0.0, -0.5, 1.0]);
    /// ```
    pub fn to_fixed(self) -> [I2F14; 3] {
        self.c.map(I2F14::from_bits)
    }

    /// Whether this is the zero vector (a normalisation of nothing).
    ///
    /// ```
    /// use fixshade::Unit3;
    /// assert!(Unit3::ZERO.is_zero());
    /// assert!(!Unit3::new_clamped(0, 0, 1).is_zero());
    /// ```
    pub const fn is_zero(self) -> bool {
        self.c[0] == 0 && self.c[1] == 0 && self.c[2] == 0
    }

    /// The opposite direction (the invariant is symmetric, so this cannot
    /// overflow).
    ///
    /// ```
    /// use fixshade::Unit3;
    /// let u = Unit3::new_clamped(-(1 << 14), 5, 0);
    /// assert_eq!(u.neg().to_bits(), [1 << 14, -5, 0]);
    /// assert_eq!(u.neg().neg(), u);
    /// ```
    pub const fn neg(self) -> Self {
        Unit3 {
            c: [-self.c[0], -self.c[1], -self.c[2]],
        }
    }

    /// Dot product in `Q.28` (1.0 = 2²⁸). Three 16 × 16 → 32-bit products;
    /// no overflow by the invariant (see the module docs).
    #[inline]
    ///
    /// ```
    /// use fixshade::light::unit_from_f64;
    /// use fixshade::Unit3;
    /// let d = unit_from_f64([1.0, 1.0, 0.0]).unwrap(); // 45° from X
    /// let cos = d.dot(Unit3::X) as f64 / (1u32 << 28) as f64;
    /// assert!((cos - 0.5f64.sqrt()).abs() < 1e-4);
    /// ```
    pub const fn dot(self, o: Unit3) -> i32 {
        self.c[0] as i32 * o.c[0] as i32
            + self.c[1] as i32 * o.c[1] as i32
            + self.c[2] as i32 * o.c[2] as i32
    }

    /// `|a − b|² / 2` in `Q.28`, which for unit vectors equals `1 − a·b`.
    ///
    /// Computed from the difference vector, this keeps its relative precision
    /// as the angle goes to 0, where `1 − a·b` from a rounded dot product
    /// would be swamped by the rounding of the vectors' lengths. It is what
    /// steep powers (`x^2048`) need. Each difference is at most 2¹⁵, each
    /// square 2³⁰, the sum of three below 2³² (`u32`), halved below 2³¹.
    #[inline]
    ///
    /// ```
    /// use fixshade::light::unit_from_f64;
    /// use fixshade::Unit3;
    /// let a = unit_from_f64([1_048_576.0, 1.0, 0.0]).unwrap(); // about 2^-20 rad from X
    /// assert_eq!(Unit3::X.half_dist_sq(Unit3::X), 0);
    /// assert_eq!(Unit3::X.half_dist_sq(Unit3::X.neg()), 2 << 28); // 1 − (−1)
    /// assert_eq!(Unit3::X.half_dist_sq(a) as i64, (1 << 28) - Unit3::X.dot(a) as i64);
    /// ```
    pub const fn half_dist_sq(self, o: Unit3) -> u32 {
        let dx = (self.c[0] as i32 - o.c[0] as i32).unsigned_abs();
        let dy = (self.c[1] as i32 - o.c[1] as i32).unsigned_abs();
        let dz = (self.c[2] as i32 - o.c[2] as i32).unsigned_abs();
        (dx * dx + dy * dy + dz * dz) >> 1
    }
}

/// A 4 × 4 affine or projective matrix with `I8F24` entries, row-major;
/// applied to column vectors (`p' = M · p`).
///
/// ```
/// use fixshade::{Mat4, Vec3};
/// let m = Mat4::translation(Vec3::from_f32(1.0, 2.0, 3.0).unwrap());
/// let p = m.transform_point(Vec3::from_f32(0.5, 0.5, 0.5).unwrap());
/// assert_eq!(p.to_f32(), [1.5, 2.5, 3.5]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Mat4 {
    /// Entries as raw `I8F24`, `m[row][col]`.
    pub m: [[i32; 4]; 4],
}

const ONE24: i32 = 1 << COORD_FRAC;

/// `x` modulo `τ = 2π` as an `f32` (`0x40C9_0FDB` = `T·2⁻²¹`,
/// `T = 0xC9_0FDB`) for a finite `x`, exactly (the remainder `fmod`
/// gives: in (−τ, τ), with the sign of `x`). Used by [`Mat4::rotation`]
/// for `|x| ≥ 2³³`. Integer arithmetic only: the same bits everywhere, no
/// division.
fn rem_tau(x: f32) -> f32 {
    const T: u32 = 0x00C9_0FDB;
    let b = x.to_bits();
    let exp = (b >> 23) & 0xFF;
    if exp < 129 {
        // |x| < 4 < τ (zero and subnormals included): already reduced.
        return x;
    }
    // x = ±M·2^(exp − 150), M < 2^24 with its hidden bit (x is normal).
    // M < 2^24 < 2T, so one subtraction gives M mod T.
    let m = (b & 0x7F_FFFF) | 0x80_0000;
    let mut r = if m >= T { m - T } else { m };
    // x mod τ = 2^−21 · (M·2^(exp − 129) mod T): double exp − 129 times
    // (at most 125, for exp = 254), each r < T < 2^24 so 2r < 2^25.
    let mut k = exp - 129;
    while k > 0 {
        r <<= 1;
        if r >= T {
            r -= T;
        }
        k -= 1;
    }
    // r < 2^24 is exact in f32, and so is the product by 2^−21.
    let v = r as f32 * (1.0 / (1u32 << 21) as f32);
    if b >> 31 == 1 {
        -v
    } else {
        v
    }
}

impl Default for Mat4 {
    fn default() -> Self {
        Mat4::IDENTITY
    }
}

impl Mat4 {
    /// The identity.
    ///
    /// ```
    /// use fixshade::{Mat4, Vec3};
    /// let p = Vec3::from_f32(1.5, -2.0, 3.25).unwrap();
    /// assert_eq!(Mat4::IDENTITY.transform_point(p), p);
    /// assert_eq!(Mat4::IDENTITY.mul(&Mat4::IDENTITY), Mat4::IDENTITY);
    /// ```
    pub const IDENTITY: Mat4 = Mat4 {
        m: [
            [ONE24, 0, 0, 0],
            [0, ONE24, 0, 0],
            [0, 0, ONE24, 0],
            [0, 0, 0, ONE24],
        ],
    };

    /// A translation by `t`.
    ///
    /// ```
    /// use fixshade::{Mat4, Vec3};
    /// let t = Mat4::translation(Vec3::from_f32(1.0, 2.0, 3.0).unwrap());
    /// let p = t.transform_point(Vec3::from_f32(0.5, 0.5, 0.5).unwrap());
    /// assert_eq!(p.to_f32(), [1.5, 2.5, 3.5]);
    /// assert_eq!(t.transform_dir_wide([1 << 14, 0, 0]), [1 << 38, 0, 0]); // directions ignore it
    /// ```
    pub const fn translation(t: Vec3) -> Mat4 {
        let mut m = Mat4::IDENTITY;
        m.m[0][3] = t.x.to_bits();
        m.m[1][3] = t.y.to_bits();
        m.m[2][3] = t.z.to_bits();
        m
    }

    /// Builds a matrix from `f32` entries (row-major); errors as
    /// [`coord_from_f32`].
    ///
    /// ```
    /// use fixshade::vector::FormatError;
    /// use fixshade::Mat4;
    /// let mut rows = [[0.0; 4]; 4];
    /// for i in 0..4 {
    ///     rows[i][i] = 1.0;
    /// }
    /// assert_eq!(Mat4::from_f32(rows), Ok(Mat4::IDENTITY));
    /// rows[0][3] = 500.0;
    /// assert_eq!(Mat4::from_f32(rows), Err(FormatError::OutOfRange));
    /// ```
    pub fn from_f32(rows: [[f32; 4]; 4]) -> Result<Mat4, FormatError> {
        Mat4::from_f64(rows.map(|r| r.map(f64::from)))
    }

    /// A rotation by `angle` radians about the x (`axis = 0`), y (`1`) or z
    /// (`2`) axis, right-handed, for animating a model on the device.
    ///
    /// The sine and cosine come from `micromath` (an approximation with a
    /// maximum error of 0.002, so the angle is off by up to about 0.002
    /// radian), then the pair is scaled by one Newton step towards
    /// `sin² + cos² = 1`, so the matrix is a rotation to about 10⁻⁵. Basic
    /// `f32` arithmetic is IEEE-exact, so the matrix is the same bits on
    /// the host and on a Cortex-M. An `axis` above 2 counts as z; a
    /// non-finite angle gives the identity.
    ///
    /// Every finite angle gives a rotation matrix with entries in [−1, 1].
    /// Below 2³³ in magnitude the angle is reduced to [−π, π] by
    /// subtracting the nearest multiple of 2π; from 2³³ on (where one `f32`
    /// step is 1024 radians, so the angle no longer says which way the
    /// model faces, and the nearest multiple would not fit an `i32`) it is
    /// first reduced exactly modulo 2π as an `f32` (`6.2831855`), the
    /// remainder of `fmod`, by integer arithmetic.
    ///
    /// ```
    /// use fixshade::{Mat4, Vec3};
    /// let quarter = Mat4::rotation_y(core::f32::consts::FRAC_PI_2);
    /// let p = quarter.transform_point(Vec3::from_f32(1.0, 0.0, 0.0).unwrap()).to_f32();
    /// assert!(p[0].abs() < 0.003 && (p[2] + 1.0).abs() < 1e-4);
    /// ```
    pub(crate) fn rotation(axis: u8, angle: f32) -> Mat4 {
        if !angle.is_finite() {
            return Mat4::IDENTITY;
        }
        // Reduce to [-π, π] so the approximation stays in its best range.
        // micromath's round (and its cos's floor) convert to i32, which
        // saturates once |angle / τ| nears 2^31. Below 2^33, |angle / τ| <
        // 1.4·10^9 and the rounding of τ·n leaves |a| within π plus a few
        // f32 steps (2^10 at 2^33), which the cos's own floor reduces
        // (host/tests/suite/bad_input.rs checks every magnitude). From 2^33, fmod first.
        const HUGE: f32 = (1u64 << 33) as f32;
        let tau = 2.0 * core::f32::consts::PI;
        let angle = if angle < HUGE && angle > -HUGE {
            angle
        } else {
            rem_tau(angle)
        };
        let a = angle - tau * micromath::F32Ext::round(angle / tau);
        let (s, c) = (micromath::F32Ext::sin(a), micromath::F32Ext::cos(a));
        // 1/√(s² + c²) ≈ (3 − (s² + c²)) / 2 near 1 (one Newton step from 1).
        let k = 0.5 * (3.0 - (s * s + c * c));
        let (s, c) = (s * k, c * k);
        // |s|, |c| ≤ 1: micromath's cos of a reduced argument is in [−1, 1]
        // and t·(3 − t²)/2 ≤ 1 (less with the other term in k). The clamp
        // (a no-op for every angle the tests try) makes |q| ≤ 2^24 hold
        // whatever the last bit of rounding, so `-s` cannot overflow.
        let q = |v: f32| ((v * (1u32 << COORD_FRAC) as f32) as i32).clamp(-ONE24, ONE24);
        let (s, c, one) = (q(s), q(c), ONE24);
        let m = match axis {
            0 => [[one, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, one]],
            1 => [[c, 0, s, 0], [0, one, 0, 0], [-s, 0, c, 0], [0, 0, 0, one]],
            _ => [[c, -s, 0, 0], [s, c, 0, 0], [0, 0, one, 0], [0, 0, 0, one]],
        };
        Mat4 { m }
    }

    /// A rotation by `angle` radians about the x axis (y toward z).
    ///
    /// ```
    /// use fixshade::{Mat4, Vec3};
    /// let p = Mat4::rotation_x(core::f32::consts::FRAC_PI_2).transform_point(Vec3::from_f32(0.0, 1.0, 0.0).unwrap());
    /// assert!((p.to_f32()[2] - 1.0).abs() < 1e-4);
    /// ```
    pub fn rotation_x(angle: f32) -> Mat4 {
        Mat4::rotation(0, angle)
    }

    /// A rotation by `angle` radians about the y axis (z toward x).
    ///
    /// ```
    /// use fixshade::{Mat4, Vec3};
    /// let p = Mat4::rotation_y(core::f32::consts::FRAC_PI_2).transform_point(Vec3::from_f32(0.0, 0.0, 1.0).unwrap());
    /// assert!((p.to_f32()[0] - 1.0).abs() < 1e-4);
    /// ```
    pub fn rotation_y(angle: f32) -> Mat4 {
        Mat4::rotation(1, angle)
    }

    /// A rotation by `angle` radians about the z axis (x toward y).
    ///
    /// ```
    /// use fixshade::{Mat4, Vec3};
    /// let p = Mat4::rotation_z(core::f32::consts::FRAC_PI_2).transform_point(Vec3::from_f32(1.0, 0.0, 0.0).unwrap());
    /// assert!((p.to_f32()[1] - 1.0).abs() < 1e-4);
    /// ```
    pub fn rotation_z(angle: f32) -> Mat4 {
        Mat4::rotation(2, angle)
    }

    /// A uniform scale by `s` (`I8F24`, saturating).
    ///
    /// ```
    /// use fixed::types::I8F24;
    /// use fixshade::{Mat4, Vec3};
    /// let twice = Mat4::scale(I8F24::from_num(2));
    /// let p = twice.transform_point(Vec3::from_f32(1.0, -3.0, 100.0).unwrap());
    /// assert_eq!(p.to_f32()[..2], [2.0, -6.0]);
    /// assert_eq!(p.z.to_bits(), i32::MAX); // 200 saturates to just below 128
    /// ```
    pub const fn scale(s: I8F24) -> Mat4 {
        let v = s.to_bits();
        Mat4 {
            m: [[v, 0, 0, 0], [0, v, 0, 0], [0, 0, v, 0], [0, 0, 0, ONE24]],
        }
    }

    /// Builds a matrix from `f64` entries (row-major), rounding to nearest;
    /// errors as [`coord_from_f32`].
    ///
    /// ```
    /// use fixshade::vector::FormatError;
    /// use fixshade::Mat4;
    /// let mut rows = [[0.0; 4]; 4];
    /// rows[3][3] = 1.0;
    /// assert_eq!(Mat4::from_f64(rows).unwrap().m[3][3], 1 << 24);
    /// rows[1][1] = f64::NAN;
    /// assert_eq!(Mat4::from_f64(rows), Err(FormatError::NotFinite));
    /// ```
    pub fn from_f64(rows: [[f64; 4]; 4]) -> Result<Mat4, FormatError> {
        let mut m = [[0i32; 4]; 4];
        for (r, row) in rows.iter().enumerate() {
            for (c, v) in row.iter().enumerate() {
                m[r][c] = coord_from_f64(*v)?.to_bits();
            }
        }
        Ok(Mat4 { m })
    }

    /// The product `self · o`, saturating each entry to `I8F24`.
    ///
    /// ```
    /// use fixed::types::I8F24;
    /// use fixshade::{Mat4, Vec3};
    /// let t = Mat4::translation(Vec3::from_f32(1.0, 0.0, 0.0).unwrap());
    /// let s = Mat4::scale(I8F24::from_num(3));
    /// let p = Vec3::from_f32(1.0, 1.0, 1.0).unwrap();
    /// // `a.mul(&b)` applies `b` first.
    /// assert_eq!(t.mul(&s).transform_point(p).to_f32(), [4.0, 3.0, 3.0]);
    /// assert_eq!(s.mul(&t).transform_point(p).to_f32(), [6.0, 3.0, 3.0]);
    /// // Entries saturate: 100 · 100 is beyond I8F24.
    /// let big = Mat4::scale(I8F24::from_num(100));
    /// assert_eq!(big.mul(&big).m[0][0], i32::MAX);
    /// ```
    pub fn mul(&self, o: &Mat4) -> Mat4 {
        let mut m = [[0i32; 4]; 4];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, out) in row.iter_mut().enumerate() {
                let mut acc: i64 = 0;
                for k in 0..4 {
                    // |a|,|b| < 2^31 raw, product < 2^62; four of them can
                    // reach 2^64, so accumulate saturating.
                    acc = acc.saturating_add(self.m[r][k] as i64 * o.m[k][c] as i64);
                }
                *out = sat_shift24(acc);
            }
        }
        Mat4 { m }
    }

    /// Applies the affine part (rows 0..3) to a point (w = 1), saturating the
    /// result to `I8F24`.
    #[inline]
    ///
    /// ```
    /// use fixshade::{Mat4, Vec3};
    /// let m = Mat4::from_f32([
    ///     [0.0, -1.0, 0.0, 2.0],
    ///     [1.0, 0.0, 0.0, 0.0],
    ///     [0.0, 0.0, 1.0, 0.0],
    ///     [0.0, 0.0, 0.0, 1.0],
    /// ]).unwrap(); // a quarter turn about z, then 2 along x
    /// let p = m.transform_point(Vec3::from_f32(1.0, 0.0, 5.0).unwrap());
    /// assert_eq!(p.to_f32(), [2.0, 1.0, 5.0]);
    /// // Far outside the range, the result saturates instead of wrapping.
    /// let q = m.transform_point(Vec3::from_f32(0.0, -127.0, 0.0).unwrap());
    /// assert_eq!(q.x.to_bits(), i32::MAX);
    /// ```
    pub fn transform_point(&self, p: Vec3) -> Vec3 {
        let b = p.to_bits();
        let row = |r: usize| {
            let m = &self.m[r];
            // Each product is at most 2^62 in magnitude (2^62 only as
            // i32::MIN²) and the translation, shifted up, at most 2^55: the
            // back pair's sum fits i64; the front pair's leaves it only as
            // 2^62 + 2^62. Saturating the front sum and the total gives the
            // result of the exact sum: where one saturates, the exact sum
            // is beyond ±2^63 on that side (the front) or the terms left,
            // at most 2^62 + 2^55, cannot bring the saturated or the exact
            // value back within ±2^61; both then round to beyond ±2^37 and
            // clamp to the same `I8F24` bound. (So did the four terms summed
            // saturating one by one, its earlier form,
            // which a unit test compares it with.)
            let front = mul_i32(m[0], b[0]).saturating_add(mul_i32(m[1], b[1]));
            let back = mul_i32(m[2], b[2]) + ((m[3] as i64) << COORD_FRAC);
            sat_shift24(front.saturating_add(back))
        };
        Vec3::from_bits(row(0), row(1), row(2))
    }

    /// Applies the affine part (rows 0..3) to a mesh's quantised position
    /// `q`, read as `Q.15` fractions ([`crate::mesh`]; the matrix is the
    /// model-view matrix with the mesh's box folded in,
    /// [`Bounds::fold`](crate::mesh::Bounds::fold)): `Σ m[r][c]·q[c]/2¹⁵ +
    /// m[r][3]`, rounded to nearest and saturated to `I8F24`, the same as
    /// [`Mat4::transform_point`] of the point `q / 2¹⁵` (`q·2⁹` raw).
    ///
    /// No sum can overflow and none saturates: each product is at most
    /// `2³¹·2¹⁵ = 2⁴⁶`, the translation in the products' units (`·2¹⁵`) at
    /// most 2⁴⁶, their sum below 2⁴⁸; rounded to units of 2⁻²⁴ it is below
    /// 2³⁴ and clamps to `i32`. On a Cortex-M0 each product is two 16 × 16 →
    /// 32-bit multiplies (one `i16` operand) where an `I8F24` coordinate's
    /// took four.
    #[inline]
    ///
    /// ```
    /// use fixshade::{Mat4, Vec3};
    /// let m = Mat4::translation(Vec3::from_f32(0.0, 0.0, -5.0).unwrap());
    /// assert_eq!(m.transform_quantised([16384, -32768, 0]).to_f32(), [0.5, -1.0, -5.0]);
    /// let p = Vec3::from_bits(16384 << 9, -32768 << 9, 0);
    /// assert_eq!(m.transform_quantised([16384, -32768, 0]), m.transform_point(p));
    /// ```
    pub fn transform_quantised(&self, q: [i16; 3]) -> Vec3 {
        let row = |r: usize| self.quantised_row(r, q);
        Vec3::from_bits(row(0), row(1), row(2))
    }

    /// Row `r` of [`Mat4::transform_quantised`] (raw `I8F24`): for the
    /// vertex stage, which needs the depth row alone.
    #[inline(always)]
    pub(crate) fn quantised_row(&self, r: usize, q: [i16; 3]) -> i32 {
        const Q15: u32 = 15;
        let m = &self.m[r];
        let acc = mul_i32_i16(m[0], q[0])
            + mul_i32_i16(m[1], q[1])
            + mul_i32_i16(m[2], q[2])
            + ((m[3] as i64) << Q15);
        let r = ((acc >> (Q15 - 1)) + 1) >> 1;
        saturate_i32(r)
    }

    /// Applies the 3 × 3 linear part to a direction (w = 0), returning raw
    /// `i64` sums in the input's units times 2²⁴ (no rounding, no overflow:
    /// each product is below 2⁶², three of them below 2⁶³·1.5, summed
    /// saturating).
    #[inline]
    ///
    /// ```
    /// use fixed::types::I8F24;
    /// use fixshade::Mat4;
    /// // A scale by 2 doubles the input's raw units, times 2^24.
    /// let twice = Mat4::scale(I8F24::from_num(2));
    /// assert_eq!(twice.transform_dir_wide([3, -5, 0]), [6 << 24, -10 << 24, 0]);
    /// ```
    pub fn transform_dir_wide(&self, d: [i32; 3]) -> [i64; 3] {
        let row = |r: usize| {
            let m = &self.m[r];
            (m[0] as i64 * d[0] as i64)
                .saturating_add(m[1] as i64 * d[1] as i64)
                .saturating_add(m[2] as i64 * d[2] as i64)
        };
        [row(0), row(1), row(2)]
    }
}

/// Rounds an `i64` in `Q.48` to `Q.24` and saturates it to `i32`.
#[inline]
pub(crate) fn sat_shift24(acc: i64) -> i32 {
    let r = (acc >> (COORD_FRAC - 1)).saturating_add(1) >> 1;
    saturate_i32(r)
}

impl core::ops::Mul for Mat4 {
    type Output = Mat4;
    /// The product `self · o` ([`Mat4::mul`]): `o` applies first.
    ///
    /// ```
    /// use fixshade::{Mat4, Vec3};
    /// let m = Mat4::translation(Vec3::from_f32(1.0, 0.0, 0.0).unwrap()) * Mat4::rotation_z(0.0);
    /// assert_eq!(m.transform_point(Vec3::ZERO).to_f32(), [1.0, 0.0, 0.0]);
    /// ```
    fn mul(self, o: Mat4) -> Mat4 {
        Mat4::mul(&self, &o)
    }
}

/// The inverse transpose of the 3 × 3 linear part of `m`, scaled so that its
/// largest entry is below 1 in magnitude, as `I2F14` (`i16`) entries: the
/// matrix that takes normals to eye space (SPEC.md 1). The scale is free
/// because the result is renormalised.
///
/// It is the cofactor matrix, computed exactly from the entries (so an
/// axis scaled far below the others keeps its normals), with the sign of
/// the determinant. Returns `None` where the normals' directions would be
/// lost: for a matrix singular at the entries' precision, or one that
/// scales a direction more than about [`MAX_ANISOTROPY`] times another
/// (a normal's 2⁻¹⁵ steps in the mesh and this matrix's 2⁻¹⁴ would turn
/// its direction by more than the lighting's bound allows).
///
/// ```
/// use fixed::types::I8F24;
/// use fixshade::vector::normal_matrix;
/// use fixshade::Mat4;
/// let scale = |x: f32, y: f32, z: f32| {
///     Mat4::from_f32([[x, 0.0, 0.0, 0.0], [0.0, y, 0.0, 0.0], [0.0, 0.0, z, 0.0], [0.0, 0.0, 0.0, 1.0]])
///         .unwrap()
/// };
/// // A non-uniform scale: normals scale by the inverse (x by 1/2 against z by 1).
/// let n = normal_matrix(&scale(2.0, 1.0, 1.0)).unwrap();
/// assert_eq!(n[0][0] * 2, n[2][2]);
/// // z flattened 1000 times: normals turn towards z.
/// assert_eq!(normal_matrix(&scale(1.0, 1.0, 1e-3)).unwrap()[2][2], 1 << 14);
/// assert_eq!(normal_matrix(&scale(1.0, 1.0, 1e-5)), None); // too flat
/// assert_eq!(normal_matrix(&Mat4::scale(I8F24::ZERO)), None); // singular
/// ```
pub fn normal_matrix(m: &Mat4) -> Option<[[i16; 3]; 3]> {
    // Entries within ±(2³¹ − 1) (i32::MIN moved by one unit of 2⁻²⁴):
    // each product of two below 2⁶² − 2³², each cofactor, a difference of
    // two, below 2⁶³: `i64` holds them exactly.
    let a = |r: usize, c: usize| m.m[r][c].max(-i32::MAX);
    let mut cof = [[0i64; 3]; 3];
    // The largest cofactor and the largest entry, in magnitude.
    let (mut max, mut entries) = (0u64, 0u32);
    for (r, row) in cof.iter_mut().enumerate() {
        for (c, out) in row.iter_mut().enumerate() {
            let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
            let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
            *out = mul_i32(a(r1, c1), a(r2, c2)) - mul_i32(a(r1, c2), a(r2, c1));
            max = max.max(out.unsigned_abs());
            entries = entries.max(m.m[r][c].unsigned_abs());
            // Once a draw: nine passes of one body, not nine bodies.
            platform::keep_loop_rolled();
        }
    }
    let bits = |v: u64| 64 - v.leading_zeros() as i32;
    let (sign, det_bits) = det_sign_bits([a(0, 0), a(0, 1), a(0, 2)], cof[0])?;
    // κ = ‖M‖·‖M⁻¹‖ with ‖M⁻¹‖ = ‖cof‖/|det|, from the largest entries'
    // and the determinant's bit lengths: within a factor of 36 of the
    // 2-norm's (a factor 9 from the norms, 4 from the bit lengths).
    if bits(entries as u64) + bits(max) - det_bits > MAX_ANISOTROPY.ilog2() as i32 + 1 {
        return None;
    }
    // All brought below 2⁴⁸ by one shift (floors: within a unit of 2⁻⁴⁸
    // of the largest, below the output's 2⁻¹⁴), then `v·2¹⁴/max`: the
    // quotient in [−2¹⁴, 2¹⁴], the product below 2⁶².
    let sh = (bits(max) - 48).max(0);
    let max = (max >> sh) as i64;
    let mut out = [[0i16; 3]; 3];
    for (o, v) in out.iter_mut().flatten().zip(cof.iter().flatten()) {
        *o = ((((v >> sh) * sign) << 14).quot(max)) as i16;
        // Once a draw: nine passes of one division, not nine bodies.
        platform::keep_loop_rolled();
    }
    Some(out)
}

/// How much more [`normal_matrix`] lets a matrix scale one direction than
/// another (its condition number, estimated within a factor of 36; 1 for
/// a rotation and a uniform scale). A sphere flattened 1 000 times draws
/// within the bound and one flattened 10⁴ times is refused
/// (`host/tests/suite/stiff_cases.rs` asserts both); drawn before this
/// limit existed, the 10⁴ one was 2 LSB away from the reference in Phong
/// shading (measured once; no test can repeat it with the limit on).
pub const MAX_ANISOTROPY: u32 = 1 << 11;

/// The sign and bit length of the determinant of the matrix whose first
/// row is `a` and whose first row's cofactors are `cof` (`|a| < 2³¹`,
/// `|cof| < 2⁶³`), if the sum decides them: its three products within a
/// relative 2⁻⁶⁰ ([`Wide`]), the sum within 2⁻⁵⁷ of the largest, so
/// beyond 2⁻⁵⁵ of it the sign is the exact one and the bit length within
/// one. `None` for a matrix singular at this precision.
fn det_sign_bits(a: [i32; 3], cof: [i64; 3]) -> Option<(i64, i32)> {
    let terms = [0, 1, 2].map(|c| Wide::new(cof[c], 0).mul(a[c] as i64));
    let top = terms.iter().map(|t| t.bits()).max().unwrap_or(0);
    let det = terms[0].add(&terms[1]).add(&terms[2]);
    (det.m != 0 && det.bits() > top - 55).then_some((det.m.signum(), det.bits()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::xorshift;

    /// The normal matrix is the cofactor matrix (exact, in `i128`) with the
    /// determinant's sign, scaled so its largest entry is 2¹⁴, within one
    /// unit, for random matrices with rows and columns scaled apart by up
    /// to 2²⁴; it is refused only past `MAX_ANISOTROPY` (the Frobenius
    /// condition number, within 3 of the 2-norm's, above 2¹⁰·⁵) and
    /// given below 2¹⁸.
    #[test]
    fn normal_matrix_is_the_scaled_inverse_transpose() {
        let mut next = xorshift(0x1234_5678_9abc_def1);
        let (mut given, mut refused) = (0, 0);
        for i in 0..40_000 {
            let mut m = Mat4::IDENTITY;
            let row_sh = [0, 1, 2].map(|_| (next() % 25) as u32 * (i % 2));
            let col_sh = [0, 1, 2].map(|_| (next() % 25) as u32 * (i % 3 / 2));
            for (row, rs) in m.m.iter_mut().zip(row_sh) {
                for (e, cs) in row.iter_mut().zip(col_sh) {
                    let v = (next() as i32) >> (next() % 8);
                    *e = v >> (rs + cs).min(31);
                }
            }
            let a = |r: usize, c: usize| m.m[r][c].max(-i32::MAX) as i128;
            let cof = |r: usize, c: usize| {
                let (r1, r2, c1, c2) = ((r + 1) % 3, (r + 2) % 3, (c + 1) % 3, (c + 2) % 3);
                a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1)
            };
            let det: i128 = (0..3).map(|c| a(0, c) * cof(0, c)).sum();
            let frob = |f: &dyn Fn(usize) -> f64| (0..9).map(|k| f(k).powi(2)).sum::<f64>().sqrt();
            let kappa = frob(&|k| a(k / 3, k % 3) as f64) * frob(&|k| cof(k / 3, k % 3) as f64)
                / (det as f64).abs();
            match normal_matrix(&m) {
                Some(n) => {
                    given += 1;
                    assert!(kappa < 2f64.powi(18), "{m:?}: κ {kappa}");
                    let big = (0..9).map(|k| cof(k / 3, k % 3).abs()).max().unwrap();
                    for k in 0..9 {
                        let want = cof(k / 3, k % 3) * det.signum() * 16384 / big;
                        let got = n[k / 3][k % 3] as i128;
                        assert!(
                            (got - want).abs() <= 1,
                            "{m:?}: entry {k} {got} against {want}"
                        );
                    }
                }
                None => {
                    refused += 1;
                    assert!(det == 0 || kappa > 2f64.powf(10.5), "{m:?}: κ {kappa}");
                }
            }
        }
        assert!(
            given > 20_000 && refused > 2_000,
            "{given} given, {refused} refused"
        );
    }

    /// `transform_point`'s row by exact `i128` sums, and by the four terms
    /// summed saturating one by one (its earlier form).
    fn reference_rows(m: &Mat4, p: Vec3) -> ([i32; 3], [i32; 3]) {
        let b = p.to_bits();
        let exact = [0, 1, 2].map(|r| {
            let row = &m.m[r];
            let acc: i128 = (0..3).map(|c| row[c] as i128 * b[c] as i128).sum::<i128>()
                + ((row[3] as i128) << COORD_FRAC);
            let q = ((acc >> (COORD_FRAC - 1)) + 1) >> 1;
            q.clamp(i32::MIN as i128, i32::MAX as i128) as i32
        });
        let stepwise = [0, 1, 2].map(|r| {
            let row = &m.m[r];
            let acc = (row[0] as i64 * b[0] as i64)
                .saturating_add(row[1] as i64 * b[1] as i64)
                .saturating_add(row[2] as i64 * b[2] as i64)
                .saturating_add((row[3] as i64) << COORD_FRAC);
            sat_shift24(acc)
        });
        (exact, stepwise)
    }

    #[test]
    fn transform_point_is_the_exact_sum_clamped() {
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        let edge = [
            i32::MIN,
            i32::MIN + 1,
            -(1 << 30),
            -(1 << 24),
            -1,
            0,
            1,
            1 << 24,
            1 << 30,
            i32::MAX,
        ];
        let pick = |v: u64| edge[(v % edge.len() as u64) as usize];
        let mut saturated = 0;
        for k in 0..20_000 {
            let (v, w) = (next(), next());
            let mut m = Mat4::IDENTITY;
            for (r, row) in m.m[..3].iter_mut().enumerate() {
                for (c, x) in row.iter_mut().enumerate() {
                    let u = v.rotate_left((16 * r + 5 * c) as u32);
                    // Extreme entries half of the time, random ones else.
                    *x = if (u >> 3) & 1 == 0 {
                        pick(u >> 8)
                    } else {
                        (u >> 16) as i32
                    };
                }
            }
            let p = if k % 2 == 0 {
                Vec3::from_bits(pick(w), pick(w >> 8), pick(w >> 16))
            } else {
                Vec3::from_bits(
                    w as i32,
                    (w >> 21) as i32,
                    (w >> 40) as i32 ^ (w << 9) as i32,
                )
            };
            let got = m.transform_point(p).to_bits();
            let (exact, stepwise) = reference_rows(&m, p);
            assert_eq!(got, exact, "{m:?} {p:?}");
            assert_eq!(got, stepwise, "{m:?} {p:?}");
            saturated += got
                .iter()
                .filter(|&&x| x == i32::MAX || x == i32::MIN)
                .count();
        }
        // The sweep reaches the clamps (and so the saturated sums).
        assert!(saturated > 1000, "{saturated}");
    }

    #[test]
    fn quantised_points_are_the_exact_sum_rounded() {
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        let edge = [
            i32::MIN,
            i32::MIN + 1,
            -(1 << 24),
            -1,
            0,
            1,
            1 << 24,
            i32::MAX,
        ];
        let qs = [i16::MIN, i16::MIN + 1, -1, 0, 1, i16::MAX];
        let mut clamped = 0;
        for k in 0..20_000 {
            let (v, w) = (next(), next());
            let mut m = Mat4::IDENTITY;
            for (r, row) in m.m[..3].iter_mut().enumerate() {
                for (c, x) in row.iter_mut().enumerate() {
                    let u = v.rotate_left((16 * r + 5 * c) as u32);
                    *x = if k % 2 == 0 {
                        edge[(u % edge.len() as u64) as usize]
                    } else {
                        (u >> 16) as i32
                    };
                }
            }
            let q = if k % 3 == 0 {
                [0, 1, 2].map(|i| qs[((w >> (8 * i)) % qs.len() as u64) as usize])
            } else {
                [w as i16, (w >> 16) as i16, (w >> 32) as i16]
            };
            let got = m.transform_quantised(q);
            let exact = [0, 1, 2].map(|r| {
                let row = &m.m[r];
                let acc: i128 = (0..3).map(|c| row[c] as i128 * q[c] as i128).sum::<i128>()
                    + ((row[3] as i128) << 15);
                let x = ((acc >> 14) + 1) >> 1;
                x.clamp(i32::MIN as i128, i32::MAX as i128) as i32
            });
            assert_eq!(got.to_bits(), exact, "{m:?} {q:?}");
            let p = Vec3::from_bits((q[0] as i32) << 9, (q[1] as i32) << 9, (q[2] as i32) << 9);
            assert_eq!(got, m.transform_point(p), "{m:?} {q:?}");
            clamped += exact
                .iter()
                .filter(|&&x| x == i32::MAX || x == i32::MIN)
                .count();
        }
        // The sweep reaches the clamps.
        assert!(clamped > 1000, "{clamped}");
    }
}

//! A small unsigned floating-point format for products whose magnitudes
//! span more than any one fixed-point format holds.

use crate::num::widening::mul_u32;
use crate::platform;

/// A small unsigned float for the attenuation polynomial, whose terms span
/// 10⁻¹² to 10²⁰: value = `m · 2^e`, `m` normalised to [2³¹, 2³²) or 0.
///
/// The exponent stays in [`MiniFloat::E_MIN`, `MiniFloat::E_MAX`] =
/// [−2²⁹, 2²⁹] (the attenuation uses −111 to 80), so the sum of two
/// exponents plus 32 in [`MiniFloat::mul`] is within ±(2³⁰ + 32): no
/// overflow in `i32`. At the ends ([`MiniFloat::from_u64`] with an extreme
/// `frac`, long chains of products) a value whose exponent would pass
/// `E_MAX` saturates to the largest value (`m = 2³² − 1`, `e = E_MAX`), and
/// one whose exponent would fall below `E_MIN` flushes to zero; both are
/// far beyond what [`MiniFloat::to_q32_saturating`] distinguishes
/// (`u64::MAX` and 0).
///
/// ```
/// use fixshade::num::MiniFloat;
/// let huge = MiniFloat::from_u64(1, -i32::MAX);
/// assert_eq!(huge, MiniFloat::MAX);
/// assert_eq!(huge.mul(huge).to_q32_saturating(), u64::MAX);
/// let tiny = MiniFloat::from_u64(1, i32::MAX);
/// assert_eq!(tiny, MiniFloat::ZERO);
/// assert_eq!(MiniFloat::from_u64(3, 1).to_q32_saturating(), 3 << 31); // 1.5
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MiniFloat {
    m: u32,
    e: i32,
}

impl MiniFloat {
    /// The smallest exponent: values below `2^(E_MIN + 31)` flush to zero.
    ///
    /// ```
    /// use fixshade::num::MiniFloat;
    /// // 1 · 2^-frac: 2^(E_MIN + 31) is the smallest value kept, half of it flushes.
    /// let frac = -MiniFloat::E_MIN - 31;
    /// assert_ne!(MiniFloat::from_u64(1, frac), MiniFloat::ZERO);
    /// assert_eq!(MiniFloat::from_u64(1, frac + 1), MiniFloat::ZERO);
    /// ```
    pub const E_MIN: i32 = -(1 << 29);
    /// The largest exponent: values of `2^(E_MAX + 32)` or more saturate
    /// to [`MiniFloat::MAX`].
    ///
    /// ```
    /// use fixshade::num::MiniFloat;
    /// // 1 · 2^-frac: 2^(E_MAX + 31) is kept, 2^(E_MAX + 32) saturates.
    /// assert_ne!(MiniFloat::from_u64(1, -MiniFloat::E_MAX - 31), MiniFloat::MAX);
    /// assert_eq!(MiniFloat::from_u64(1, -MiniFloat::E_MAX - 32), MiniFloat::MAX);
    /// ```
    pub const E_MAX: i32 = 1 << 29;
    /// Zero.
    ///
    /// ```
    /// use fixshade::num::MiniFloat;
    /// assert_eq!(MiniFloat::from_u64(0, 7), MiniFloat::ZERO);
    /// assert_eq!(MiniFloat::from_u64(3, 0).mul(MiniFloat::ZERO), MiniFloat::ZERO);
    /// assert_eq!(MiniFloat::ZERO.to_q32_saturating(), 0);
    /// ```
    pub const ZERO: MiniFloat = MiniFloat { m: 0, e: 0 };
    /// The largest value, `(2³² − 1) · 2^E_MAX`.
    ///
    /// ```
    /// use fixshade::num::MiniFloat;
    /// let one = MiniFloat::from_u64(1, 0);
    /// assert_eq!(MiniFloat::MAX.mul(one), MiniFloat::MAX);
    /// assert_eq!(MiniFloat::MAX.mul(MiniFloat::MAX), MiniFloat::MAX);
    /// assert_eq!(MiniFloat::MAX.to_q32_saturating(), u64::MAX);
    /// ```
    pub const MAX: MiniFloat = MiniFloat {
        m: u32::MAX,
        e: MiniFloat::E_MAX,
    };

    /// `m · 2^e` for a normalised `m` (or 0) and an exponent `e` known to
    /// lie within ±(2³⁰ + 32): saturated above [`MiniFloat::E_MAX`],
    /// flushed to zero below [`MiniFloat::E_MIN`].
    #[inline(always)]
    const fn clamped(m: u32, e: i32) -> MiniFloat {
        if e > MiniFloat::E_MAX {
            MiniFloat::MAX
        } else if e < MiniFloat::E_MIN {
            MiniFloat::ZERO
        } else {
            MiniFloat { m, e }
        }
    }

    /// Whether this is 0: a zero mantissa, whose exponent every operation
    /// makes 0 ([`MiniFloat::ZERO`]).
    #[inline(always)]
    pub(crate) const fn is_zero(self) -> bool {
        self.m == 0
    }

    /// `v · 2^-frac`, truncated to 32 significant bits; saturated or
    /// flushed to zero where the exponent leaves [`MiniFloat::E_MIN`,
    /// `MiniFloat::E_MAX`] (any `frac` is accepted).
    ///
    /// ```
    /// use fixshade::num::MiniFloat;
    /// assert_eq!(MiniFloat::from_u64(5, 32).to_q32_saturating(), 5); // 5 · 2⁻³²
    /// // Only the top 32 significant bits of `v` are kept (truncated).
    /// assert_eq!(MiniFloat::from_u64(u64::MAX, 32).to_q32_saturating(), u64::MAX << 32);
    /// // Any `frac`: far out of range saturates (or flushes to zero).
    /// assert_eq!(MiniFloat::from_u64(7, i32::MIN), MiniFloat::MAX);
    /// ```
    pub const fn from_u64(v: u64, frac: i32) -> MiniFloat {
        let (m, lz) = MiniFloat::normalise(v);
        if m == 0 {
            return MiniFloat::ZERO;
        }
        // 32 − lz ∈ [−31, 32]; the saturating difference is then clamped
        // to [E_MIN, E_MAX], which are far inside i32.
        MiniFloat::clamped(m, (32 - lz).saturating_sub(frac))
    }

    /// [`MiniFloat::from_u64`] for `|frac| ≤ 64`, without the clamp: the
    /// exponent `32 − lz − frac` is within [−95, 96], inside `E_MIN ..=
    /// E_MAX`. For the attenuation.
    #[inline(always)]
    pub(crate) const fn from_u64_small_frac(v: u64, frac: i32) -> MiniFloat {
        let (m, lz) = MiniFloat::normalise(v);
        if m == 0 {
            return MiniFloat::ZERO;
        }
        MiniFloat {
            m,
            e: 32 - lz - frac,
        }
    }

    /// The top 32 significant bits of `v` (0 for `v = 0`) and its leading
    /// zeros (in [0, 63] for `v ≠ 0`).
    ///
    /// From `v`'s 32-bit halves: a 64-bit variable shift and leading-zero
    /// count are library calls on ARMv6-M.
    #[inline(always)]
    const fn normalise(v: u64) -> (u32, i32) {
        let (hi, lo) = ((v >> 32) as u32, v as u32);
        if hi != 0 {
            let lz = platform::leading_zeros(hi);
            // lz ≤ 31: the top 32 bits of `v << lz`.
            let m = if lz == 0 {
                hi
            } else {
                (hi << lz) | (lo >> (32 - lz))
            };
            (m, lz as i32)
        } else if lo != 0 {
            let lz = platform::leading_zeros(lo);
            (lo << lz, 32 + lz as i32)
        } else {
            (0, 0)
        }
    }

    /// The product, truncated to 32 significant bits (one 32 × 32 → 64
    /// multiply); saturated or flushed to zero where the exponent leaves
    /// [`MiniFloat::E_MIN`, `MiniFloat::E_MAX`].
    ///
    /// ```
    /// use fixshade::num::MiniFloat;
    /// let (a, b) = (MiniFloat::from_u64(3, 1), MiniFloat::from_u64(5, 1)); // 1.5, 2.5
    /// assert_eq!(a.mul(b).to_q32_saturating(), 15 << 30); // 3.75
    /// // A product below 2^(E_MIN + 31) flushes to zero.
    /// let small = MiniFloat::from_u64(1, 1 << 28); // 2^-(2²⁸)
    /// assert_ne!(small, MiniFloat::ZERO);
    /// assert_eq!(small.mul(small), MiniFloat::ZERO);
    /// ```
    #[inline]
    pub const fn mul(self, o: MiniFloat) -> MiniFloat {
        let (m, e) = self.mul_parts(o);
        MiniFloat::clamped(m, e)
    }

    /// [`MiniFloat::mul`] without the clamp, for factors whose product's
    /// exponent is known to lie within `E_MIN ..= E_MAX` (the
    /// attenuation's: all its exponents are within [−111, 80]).
    #[inline(always)]
    pub(crate) const fn mul_in_range(self, o: MiniFloat) -> MiniFloat {
        let (m, e) = self.mul_parts(o);
        MiniFloat { m, e }
    }

    /// The product's mantissa and exponent, unclamped (0 and 0 for zero).
    /// Both exponents are within ±2²⁹, so the sums are within ±(2³⁰ + 32).
    #[inline(always)]
    const fn mul_parts(self, o: MiniFloat) -> (u32, i32) {
        if self.m == 0 || o.m == 0 {
            return (0, 0);
        }
        let p = mul_u32(self.m, o.m); // in [2^62, 2^64)
        if p >> 63 == 1 {
            ((p >> 32) as u32, self.e + o.e + 32)
        } else {
            ((p >> 31) as u32, self.e + o.e + 31)
        }
    }

    /// The value in `Q.32`, saturating at `u64::MAX`.
    ///
    /// ```
    /// use fixshade::num::MiniFloat;
    /// assert_eq!(MiniFloat::from_u64(1, 0).to_q32_saturating(), 1 << 32);
    /// assert_eq!(MiniFloat::from_u64(1, -31).to_q32_saturating(), 1 << 63); // 2³¹
    /// assert_eq!(MiniFloat::from_u64(1, -32).to_q32_saturating(), u64::MAX); // 2³² saturates
    /// assert_eq!(MiniFloat::from_u64(1, 33).to_q32_saturating(), 0); // 2⁻³³ truncates to 0
    /// ```
    #[inline]
    pub const fn to_q32_saturating(self) -> u64 {
        if self.m == 0 {
            return 0;
        }
        // e ≤ E_MAX = 2^29: no overflow. The shifts on 32-bit halves (a
        // 64-bit variable shift is a library call on ARMv6-M).
        let (m, s) = (self.m, self.e + 32);
        if s > 32 {
            u64::MAX
        } else if s == 32 {
            (m as u64) << 32
        } else if s > 0 {
            // m·2ˢ: its high half m >> (32 − s), its low half m << s.
            (((m >> (32 - s)) as u64) << 32) | (m << s) as u64
        } else if s > -32 {
            (m >> (-s)) as u64
        } else {
            // m < 2³²: 0 once shifted right by 32 or more.
            0
        }
    }
}

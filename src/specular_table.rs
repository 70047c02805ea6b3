//! Powers `x^n` for specular highlights and spot lights, in integers only.
//!
//! # Input: `δ = 1 − x`, not `x`
//!
//! A steep power cannot be evaluated from `x` itself: at `n = 1000`,
//! `x^n` falls from 1 to 0.37 between `x = 1` and `x = 0.999`, and at
//! `n = 2048` it is below 10⁻³ once `1 − x > 0.0034`. A rounded dot
//! product near 1 has lost exactly the digits that matter. So the main entry
//! point, [`pow_from_delta`], takes `δ = 1 − x` in `Q.28` (`u32`, 1.0 = 2²⁸),
//! as produced with full relative precision by
//! [`Unit3::half_dist_sq`](crate::Unit3::half_dist_sq). `δ ∈ [0, 2]`
//! (raw `0 ..= 2²⁹`) covers `x ∈ [−1, 1]`; `δ ≥ 1` means `x ≤ 0`.
//! `pow_from_cos` (the tests') is the convenience form for callers that only have `x`.
//!
//! # Method
//!
//! `x^n = exp(−n·t)` with `t = −ln x`. No floats and no division at run time.
//!
//! 1. **Normalise.** `x = m·2⁻ᵏ` with `m ∈ (1/2, 1]`, `k ∈ [0, 28]`
//!    (`k = leading_zeros(x_raw − 1) − 4`, one shift). Then
//!    `t = d·h(d) + k·ln 2` with `d = 1 − m ∈ [0, 1/2)` and
//!    `h(d) = −ln(1 − d)/d = 1 + d/2 + d²/3 + …`, smooth on `[0, 1/2]`.
//!    For `x > 1/2` (`k = 0`), `d = δ` exactly, so `t` keeps the relative
//!    precision of `δ` however close `x` is to 1.
//! 2. **`h` by table.** `h(d) = 1 + d/2 + q(d)`; the linear part is exact
//!    and `H_CURVE` holds `q = d²/3 + d³/4 + …`: 129 entries in `Q.18`
//!    (`u16`) at `d = i/256`, linear interpolation with a 20-bit weight,
//!    kept to `Q.20`. `d·h(d) = d + d·(h − 1)` is formed in `Q.32` with three
//!    32-bit multiplies (the product is split into 16- and 3-bit pieces, so
//!    no widening multiply is needed).
//! 3. **`u = n·t`.** One `32 × 32 → 64` multiply (`t` in `Q.32` when
//!    `k = 0`, in `Q.27` when `k ≥ 1`, `n` in `Q.8`). If `u ≥ 16`,
//!    `e^−u < 2⁻²³` and the result is 0.
//! 4. **`exp(−u) = e^−⌊u⌋ · e^−frac(u)`.** `1 − e^−f = (161/256)·f + r(f)`
//!    for `f ∈ [0, 1)`; `EXP_RESIDUAL` holds `r ∈ [0, 0.08]`: 257 entries in
//!    `Q.19` (`u16`) at `f = i/256`, linear interpolation with a 16-bit
//!    weight, kept to `Q.35`. Tabulating the residual rather than `e^−f`
//!    gains three bits, and keeps 1.0 exact at `f = 0`. `EXP_NEG_INT`:
//!    15 entries of `e^−k`, `k = 1 ..= 15`, in `Q.32` (`u32`), applied with
//!    a second `32 × 32 → 64` multiply only when `u ≥ 1`. The result is
//!    rounded once, to `Q.15`.
//!
//! All three tables are `static` arrays filled at compile time by `const fn`
//! (series in `f64`: `Σ dʲ/(j+1)` for `h` and `Σ xʲ/j!` for `eˣ`). Each
//! interpolation node is moved by half the interpolation's worst error
//! (`∓f''Δ²/16`), which centres that error. Compile-time assertions check
//! the monotonicity and bounds that the run-time range proofs rely on.
//!
//! # Size and cost
//!
//! | table | entries | type | bytes |
//! | --- | --- | --- | --- |
//! | `H_CURVE` (`h(d) − 1 − d/2`, `Q.18`) | 129 | `u16` | 258 |
//! | `EXP_RESIDUAL` (`1 − e^−f − 161f/256`, `Q.19`) | 257 | `u16` | 514 |
//! | `EXP_NEG_INT` (`e^−k`, `Q.32`) | 15 | `u32` | 60 |
//! | **total** | | | **832** |
//!
//! Per call (general case `0 < δ < 2²⁸`, `n > 0`): one `leading_zeros`
//! (a short software sequence on Cortex-M0, which has no `CLZ`); one
//! `32 × 32 → 64` multiply (`n·t`), plus a second one (`e^−k · e^−f`) only
//! when `u = n·t ≥ 1`; at most six `32 × 32 → 32` multiplies (`q`
//! interpolation, three pieces of `d·(h−1)`, `k·ln 2` only when `x ≤ 1/2`,
//! `161·f`, `r` interpolation); and at most five table reads (two of
//! `H_CURVE`, two of `EXP_RESIDUAL`, one of `EXP_NEG_INT`). No division, no
//! loop. `n = 0`, `δ = 0`, `x ≤ 0` and `u ≥ 16` return early. Built for
//! `thumbv6m-none-eabi` in release, [`pow_from_delta`] is about 150 Thumb
//! instructions, calls `__clzsi2` once and `__aeabi_lmul` once or twice,
//! and has no panic path left in it.
//!
//! # Accuracy
//!
//! Result in `Q.15` (1.0 = 32768). Measured against the f64 reference
//! `max(1 − δ/2²⁸, 0)^n` (with `0⁰ = 1`):
//!
//! - test `max_error_all_integer_exponents` (`src/tests/specular_table.rs`): every
//!   integer `n` in `0 ..= 2048`, plus `n` = 1/256, 1/128, 1/4, 1/2, 3/4,
//!   10.25, 7.30, 1171.88 and 4096, on a `δ` grid per exponent (0 ..= 32,
//!   geometric steps of 2^(1/16) up to 2²⁹ jittered per exponent, 256
//!   points across the exponent's fall-off `n·δ ≤ 12`, and points at and
//!   above 2²⁸), 1.57 million points: max error **0.568 LSB of `Q.15`
//!   = 1.73·10⁻⁵ ≈ 2⁻¹⁵·⁸**;
//! - the ignored test `extended_search`: `n` in steps of 1/4 up to 2048 and
//!   4096, 5000 random `δ` each (41 million points): max 0.5675 LSB.
//!
//! Of that, 0.5 LSB is the final rounding to `Q.15`; the arithmetic itself
//! adds at most 0.07 LSB ≈ 2⁻¹⁹. The tests assert `< 0.6` LSB, and the
//! required 1/512 of full scale (64 LSB). Sources: `t`'s relative error
//! ε ≲ 4·10⁻⁶ (`q` rounding 2⁻¹⁹, interpolation) costs at most `ε/e` in the
//! result, since `|d(e^−u)| = u·e^−u·ε ≤ ε/e`; the `e^−f` part contributes
//! ≤ 2⁻²⁰ of rounding and ≤ 2⁻²⁰ of centred interpolation error.
//!
//! Everything is `u32` arithmetic (`u64` for the two widening products)
//! with every intermediate bounded in the comments below, so no input (any
//! `u32` δ, any exponent) can overflow or panic, in debug builds included.

use crate::num::widening::mul_u32;
use crate::platform;
use crate::vector::FormatError;

/// Raw value of 1.0 in the `Q.28` input format.
const ONE_Q28: u32 = 1 << 28;

/// Raw value of 1.0 in the `Q.15` output format.
const ONE_Q15: u16 = 1 << 15;

/// Raw `Q.8` value of the largest exponent, 4096.
const MAX_BITS: u32 = 4096 << 8;

/// A power exponent: the material's shininess `n` or a spot light's exponent
/// `p`. Unsigned fixed point with 8 fractional bits (`raw = round(n·256)`),
/// range `[0, 4096]`.
///
/// ```
/// use fixshade::Exponent;
/// let n = Exponent::from_f32(10.25).unwrap();
/// assert_eq!(n.to_bits(), 2624);
/// assert_eq!(Exponent::from_int(32), Exponent::from_bits(32 * 256));
/// assert!(Exponent::default().is_zero());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Exponent(u32);

impl Exponent {
    /// The exponent 0: `x^0 = 1` for every `x`, including `x ≤ 0`.
    pub const ZERO: Exponent = Exponent(0);

    /// The largest exponent, 4096 (raw `4096 · 256 = 2²⁰`).
    ///
    /// ```
    /// use fixshade::Exponent;
    /// assert_eq!(Exponent::MAX.to_bits(), 1 << 20);
    /// assert_eq!(Exponent::from_int(60000), Exponent::MAX);
    /// ```
    pub const MAX: Exponent = Exponent(MAX_BITS);

    /// An integer exponent, clamped to [`Exponent::MAX`].
    ///
    /// ```
    /// use fixshade::Exponent;
    /// assert_eq!(Exponent::from_int(100).to_bits(), 25600);
    /// assert_eq!(Exponent::from_int(5000), Exponent::MAX);
    /// ```
    pub const fn from_int(n: u16) -> Exponent {
        // n ≤ 65535, so n·256 < 2^24: no overflow before the clamp.
        Exponent::from_bits((n as u32) << 8)
    }

    /// An exponent from its raw `Q.8` bits (`n · 256`), clamped to
    /// [`Exponent::MAX`].
    ///
    /// ```
    /// use fixshade::Exponent;
    /// assert_eq!(Exponent::from_bits(128).to_bits(), 128); // n = 0.5
    /// assert_eq!(Exponent::from_bits(u32::MAX), Exponent::MAX);
    /// ```
    pub const fn from_bits(raw_q8: u32) -> Exponent {
        if raw_q8 > MAX_BITS {
            Exponent::MAX
        } else {
            Exponent(raw_q8)
        }
    }

    /// An exponent from a float, rounded to the nearest 1/256 (halves up);
    /// a non-zero exponent below 1/512 becomes 1/256, not 0, because SPEC.md
    /// makes `x^0 = 1` even where `x ≤ 0` while `x^n = 0` there for any
    /// `n > 0`.
    ///
    /// Errors: [`FormatError::NotFinite`] for NaN and ±∞,
    /// [`FormatError::OutOfRange`] for negative values and values above 4096.
    /// `−0.0` is accepted as 0.
    ///
    /// ```
    /// use fixshade::{Exponent, vector::FormatError};
    /// assert_eq!(Exponent::from_f32(0.5).unwrap().to_bits(), 128);
    /// assert_eq!(Exponent::from_f32(1e-4).unwrap().to_bits(), 1);
    /// assert_eq!(Exponent::from_f32(4096.0), Ok(Exponent::MAX));
    /// assert_eq!(Exponent::from_f32(f32::NAN), Err(FormatError::NotFinite));
    /// assert_eq!(Exponent::from_f32(-1.0), Err(FormatError::OutOfRange));
    /// assert_eq!(Exponent::from_f32(4096.5), Err(FormatError::OutOfRange));
    /// ```
    pub fn from_f32(n: f32) -> Result<Exponent, FormatError> {
        Exponent::from_f64(n as f64)
    }

    /// As [`Exponent::from_f32`], from an `f64`.
    ///
    /// ```
    /// use fixshade::{vector::FormatError, Exponent};
    /// assert_eq!(Exponent::from_f64(10.25), Exponent::from_f32(10.25));
    /// assert_eq!(Exponent::from_f64(1e-300).unwrap().to_bits(), 1); // non-zero stays non-zero
    /// assert_eq!(Exponent::from_f64(-0.0), Ok(Exponent::ZERO));
    /// assert_eq!(Exponent::from_f64(f64::INFINITY), Err(FormatError::NotFinite));
    /// assert_eq!(Exponent::from_f64(4096.001), Err(FormatError::OutOfRange));
    /// ```
    pub fn from_f64(n: f64) -> Result<Exponent, FormatError> {
        if !n.is_finite() {
            return Err(FormatError::NotFinite);
        }
        if !(0.0..=4096.0).contains(&n) {
            return Err(FormatError::OutOfRange);
        }
        // 0 ≤ s ≤ 2^20; s + 0.5 is exact enough in f64 (53 bits) and its
        // floor is round-half-up of s.
        let s = n * 256.0;
        let raw = (s + 0.5) as u32;
        let raw = if raw == 0 && n > 0.0 { 1 } else { raw };
        Ok(Exponent::from_bits(raw))
    }

    /// The raw `Q.8` bits (`n · 256`), in `0 ..= 2²⁰`.
    ///
    /// ```
    /// use fixshade::Exponent;
    /// assert_eq!(Exponent::from_int(3).to_bits(), 768);
    /// ```
    pub const fn to_bits(self) -> u32 {
        self.0
    }

    /// Whether this is the exponent 0 (the power is then 1 everywhere).
    ///
    /// ```
    /// use fixshade::Exponent;
    /// assert!(Exponent::ZERO.is_zero());
    /// assert!(!Exponent::from_bits(1).is_zero());
    /// ```
    pub const fn is_zero(self) -> bool {
        self.0 == 0
    }
}

// ---------------------------------------------------------------------------
// Compile-time tables.
// ---------------------------------------------------------------------------

/// `h(d) = −ln(1 − d)/d = Σ_{j≥0} dʲ/(j+1)`, for `0 ≤ d ≤ 1/2` (terms below
/// `2⁻⁸⁰/81` are dropped, far under f64 resolution).
const fn h_series(d: f64) -> f64 {
    let mut sum = 0.0;
    let mut p = 1.0;
    let mut j = 0;
    while j < 80 {
        sum += p / (j + 1) as f64;
        p *= d;
        j += 1;
    }
    sum
}

/// `h''(d) = Σ_{j≥2} j(j−1)·dʲ⁻²/(j+1)`, for `0 ≤ d ≤ 1/2`.
const fn h_second_derivative(d: f64) -> f64 {
    let mut sum = 0.0;
    let mut p = 1.0;
    let mut j = 2;
    while j < 90 {
        sum += p * (j * (j - 1)) as f64 / (j + 1) as f64;
        p *= d;
        j += 1;
    }
    sum
}

/// `eˣ = Σ xʲ/j!` for `0 ≤ x ≤ 16`: all terms positive, the largest about
/// `16¹⁶/16! ≈ 8.9·10⁵`, and after 120 terms the remainder is below 10⁻⁴⁰
/// of the sum.
const fn exp_series(x: f64) -> f64 {
    let mut sum = 0.0;
    let mut term = 1.0;
    let mut j = 1;
    while j <= 120 {
        sum += term;
        term = term * x / j as f64;
        j += 1;
    }
    sum
}

/// Rounds a non-negative f64 below 2¹⁶ to the nearest `u16` (halves up).
const fn round_u16(v: f64) -> u16 {
    (v + 0.5) as u16
}

/// Interval count of the `h` table over `d ∈ [0, 1/2]`.
const H_INTERVALS: usize = 128;

/// `H_CURVE[i] = round(q(i/256) · 2¹⁸)`, `i = 0 ..= 128`, where
/// `q(d) = h(d) − 1 − d/2 = d²/3 + d³/4 + … ∈ [0, 2 ln 2 − 5/4]`. The linear
/// part `1 + d/2` is added exactly at run time, so the table only holds the
/// curvature and fits `Q.18` in a `u16`. Largest entry
/// `(2 ln 2 − 5/4)·2¹⁸ ≈ 35729`.
static H_CURVE: [u16; H_INTERVALS + 1] = {
    let mut t = [0u16; H_INTERVALS + 1];
    let mut i = 0;
    while i <= H_INTERVALS {
        let d = i as f64 / 256.0;
        // Linear interpolation of the convex q lies above it by up to
        // q''·Δ²/8 mid-interval (Δ = 1/256, q'' = h''); lowering each node
        // by half of that centres the error. Node 0 stays exactly 0.
        let drop = if i == 0 {
            0.0
        } else {
            h_second_derivative(d) / (16.0 * 65_536.0)
        };
        t[i] = round_u16((h_series(d) - 1.0 - 0.5 * d - drop) * 262_144.0);
        i += 1;
    }
    t
};

/// Interval count of the `e^−f` table over `f ∈ [0, 1]`.
const EXP_INTERVALS: usize = 256;

/// Slope of the linear part of `1 − e^−f`: `EXP_SLOPE_Q8 / 256 = 0.62890625`,
/// a little below the chord slope `1 − e⁻¹ = 0.63212…`, so that the residual
/// tabulated in [`EXP_RESIDUAL`] is non-negative on `[0, 1]`.
const EXP_SLOPE_Q8: u32 = 161;

/// `EXP_RESIDUAL[i] = round(r(i/256) · 2¹⁹)`, `i = 0 ..= 256`, where
/// `r(f) = 1 − e^−f − (161/256)·f ∈ [0, 0.0795]`. Entry 0 is exactly 0 (so
/// `e^0 = 1` is exact); the largest is 41641. Tabulating the residual rather
/// than `1 − e^−f` itself buys three bits of precision in a `u16`.
static EXP_RESIDUAL: [u16; EXP_INTERVALS + 1] = {
    let mut t = [0u16; EXP_INTERVALS + 1];
    let mut i = 0;
    while i <= EXP_INTERVALS {
        let f = i as f64 / 256.0;
        let slope = EXP_SLOPE_Q8 as f64 / 256.0;
        let e = 1.0 / exp_series(f);
        // Linear interpolation of the concave r (r'' = −e^−f) lies below it
        // by up to e^−f·Δ²/8 mid-interval (Δ = 1/256); raising each node by
        // half of that centres the error: ±e^−f·Δ²/16 instead of [0, Δ²/8].
        // Node 0 stays exactly 0 so that u = 0 gives exactly 1.
        let lift = if i == 0 { 0.0 } else { e / (16.0 * 65_536.0) };
        t[i] = round_u16((1.0 - e - slope * f + lift) * 524_288.0);
        i += 1;
    }
    t
};

/// `EXP_NEG_INT[k − 1] = round(e^−k · 2³²)`, `k = 1 ..= 15`.
/// Largest entry `e⁻¹·2³² ≈ 1.58·10⁹ < 2³¹`.
static EXP_NEG_INT: [u32; 15] = {
    let mut t = [0u32; 15];
    let mut k = 1;
    while k <= 15 {
        t[k - 1] = (4_294_967_296.0 / exp_series(k as f64) + 0.5) as u32;
        k += 1;
    }
    t
};

/// `ln 2` in `Q.27`: `round(0.693147… · 2²⁷) = 93032640`.
const LN2_Q27: u32 = {
    // ln 2 = Σ_{j≥1} 1/(j·2ʲ) = (1/2)·h(1/2).
    let v = 0.5 * h_series(0.5) * 134_217_728.0;
    (v + 0.5) as u32
};

/// Checks, at compile time, the facts the run-time range proofs use.
// rustc before 1.88 does not count its use in a `const _` as a use.
#[allow(dead_code)]
const fn tables_ok() -> bool {
    // H_CURVE: starts at 0, non-decreasing, steps below 2^11, ends ≤ 35729.
    if H_CURVE[0] != 0 || H_CURVE[H_INTERVALS] > 35_729 {
        return false;
    }
    let mut i = 0;
    while i < H_INTERVALS {
        let (a, b) = (H_CURVE[i], H_CURVE[i + 1]);
        if b < a || b - a >= 1 << 11 {
            return false;
        }
        i += 1;
    }
    // Residual of 1 − e^−f: starts at 0, steps below 2^10 either way,
    // at most 41641.
    if EXP_RESIDUAL[0] != 0 {
        return false;
    }
    let mut i = 0;
    while i < EXP_INTERVALS {
        let (a, b) = (EXP_RESIDUAL[i], EXP_RESIDUAL[i + 1]);
        if a > 41_641 || b > 41_641 || a.abs_diff(b) >= 1 << 10 {
            return false;
        }
        i += 1;
    }
    // e^−k < 2^31 for k ≥ 1.
    EXP_NEG_INT[0] < 1 << 31 && LN2_Q27 == 93_032_640
}

const _: () = assert!(tables_ok());

// ---------------------------------------------------------------------------
// Run time: integers only.
// ---------------------------------------------------------------------------

/// `max(x, 0)^n` with `x = 1 − δ`, `δ = delta_q28 / 2²⁸` (so `0 ..= 2²⁹`
/// covers `x` from 1 down to −1). Result in `Q.15`: `0 ..= 32768`
/// (1.0 = 32768).
///
/// `n = 0` gives 32768 for every `δ` (`x⁰ = 1`, also for `x ≤ 0`); for
/// `n > 0`, `δ ≥ 2²⁸` (`x ≤ 0`) gives 0 and `δ = 0` gives 32768. Never
/// panics; see the module docs for the method, cost and measured accuracy.
pub(crate) fn pow_from_delta(delta_q28: u32, n: Exponent) -> u16 {
    let n_q8 = n.0; // ≤ 2^20 by the type's invariant.
    if n_q8 == 0 || delta_q28 == 0 {
        return ONE_Q15;
    }
    if delta_q28 >= ONE_Q28 {
        return 0;
    }
    // x ∈ [1, 2^28 − 1] (Q.28), since δ ∈ [1, 2^28 − 1].
    let x = ONE_Q28 - delta_q28;

    // Normalise: m = x·2^k ∈ (2^27, 2^28]. x − 1 ∈ [0, 2^28) so
    // lz ∈ [4, 32] and k ∈ [0, 28]. If x − 1 > 0 its top bit is bit 31 − lz,
    // so 2^(27−k) ≤ x − 1 < 2^(28−k), i.e. 2^(27−k) < x ≤ 2^(28−k); if
    // x = 1 then k = 28. Either way x << k ∈ (2^27, 2^28]: no bits lost.
    // (Where the core counts leading zeros in software, x > 2^27, the
    // usual case, takes k = 0 without the count.)
    let k = if platform::SOFT_MUL64 && x > 1 << 27 {
        0
    } else {
        platform::leading_zeros(x - 1) - 4
    };
    let m = x << k;
    // d = 1 − m ∈ [0, 2^27) in Q.28, i.e. [0, 1/2). For k = 0, d = δ.
    let d = ONE_Q28 - m;

    // g = h(d) − 1 = d/2 + q(d) in Q.20. q by linear interpolation at
    // d = i/256 + w/2^28: i = d >> 20 ∈ [0, 127], so i + 1 ≤ 128 is in the
    // table. The interpolation is kept to Q.20 (two bits below the table)
    // rather than rounded to the table's Q.18.
    // (The mask is a no-op by that bound; it lets the compiler drop the
    // bounds checks.)
    let i = ((d >> 20) & 127) as usize;
    let w = d & 0xF_FFFF; // < 2^20
    let q0 = H_CURVE[i] as u32;
    let q1 = H_CURVE[i + 1] as u32;
    // 0 ≤ q1 − q0 < 2^11 (checked at compile time): (q1 − q0)·w + 2^17
    // < 2^31 + 2^17. q0 << 2 ≤ 4·35729, and the interpolated q20 ≤ 4·q1.
    let q20 = (q0 << 2) + (((q1 - q0) * w + (1 << 17)) >> 18);
    // d/2 in Q.20 = d >> 9 < 2^18 (truncation < 2^−20).
    // g20 < 2^18 + 4·35729 + 1 < 2^19.
    let g20 = (d >> 9) + q20;

    // s = t for k = 0 = d·h(d) = d + d·g, in Q.32: d is Q.28, d·g20 is Q.48,
    // Q.48 → Q.32 is >> 16. d·g20 < 2^27·2^19 would overflow u32, so split
    // d = dh·2^16 + dl (dh < 2^11, dl < 2^16) and g20 = gh·8 + gl
    // (gh < 2^16, gl < 8):
    //   (d·g20) >> 16 ≈ dh·g20 + (dl·gh) >> 13 + (dl·gl) >> 16,
    // exact up to two truncations (< 2·2^−32).
    // dh·g20 < 2^30; dl·gh < 2^32; dl·gl < 2^19; d << 4 < 2^31.
    // Sum < 2^31 + 2^30 + 2^19 + 2^3 < 2^32.
    let dh = d >> 16;
    let dl = d & 0xFFFF;
    let gh = g20 >> 3;
    let gl = g20 & 7;
    let s = (d << 4) + dh * g20 + ((dl * gh) >> 13) + ((dl * gl) >> 16);

    // u = n·t in Q.24, t = s + k·ln 2. Saturate at u ≥ 16 (e^−16 < 2^−23).
    let u_q24 = if k == 0 {
        // t = s in Q.32; n in Q.8: product in Q.40, < 2^20·2^32 = 2^52.
        match q40_to_q24(n_q8, s) {
            Some(u) => u,
            None => return 0,
        }
    } else {
        // t in Q.27: s >> 5 < 2^27; k·LN2_Q27 ≤ 28·93032640 < 2.61·10^9;
        // sum < 2.74·10^9 < 2^32.
        let t_q27 = (s >> 5) + k * LN2_Q27;
        // Product in Q.35, < 2^20·2^32 = 2^52.
        let p = mul_u32(n_q8, t_q27);
        if p >= 16u64 << 35 {
            return 0;
        }
        // p < 2^39 so p >> 11 < 2^28.
        (p >> 11) as u32
    };

    exp_neg_q24(u_q24)
}

/// `⌊n·s/2¹⁶⌋` for `n ≤ 2²⁰` (`Q.8`) and `s` (`Q.32`): `u` in `Q.24`, or
/// `None` from `u ≥ 16` on (`e^−16` is below the result's unit). Where a
/// 64-bit product is a library call and `n < 2¹⁶` (an exponent below 256),
/// from `s`'s 16-bit halves ([`q40_to_q24_halves`]); else from the 64-bit
/// product. The same value either way.
#[inline(always)]
fn q40_to_q24(n: u32, s: u32) -> Option<u32> {
    if platform::SOFT_MUL64 && n < 1 << 16 {
        q40_to_q24_halves(n, s)
    } else {
        let p = mul_u32(n, s);
        // p < 2^44 once tested, so p >> 16 < 2^28.
        (p < 16u64 << 40).then_some((p >> 16) as u32)
    }
}

/// [`q40_to_q24`] for `n < 2¹⁶`: `⌊n·s/2¹⁶⌋ = n·sₕ + ⌊n·sₗ/2¹⁶⌋`, two
/// 32-bit products, and `p ≥ 16·2⁴⁰` is that quotient `≥ 2²⁸`.
#[inline(always)]
fn q40_to_q24_halves(n: u32, s: u32) -> Option<u32> {
    let hi = n * (s >> 16);
    if hi >= 1 << 28 {
        return None;
    }
    // hi < 2^28 and the low term < 2^16: no overflow.
    let q = hi + ((n * (s & 0xFFFF)) >> 16);
    (q < 1 << 28).then_some(q)
}

/// `e^−u` in `Q.15` for `u = u_q24 / 2²⁴ ∈ [0, 16)`.
fn exp_neg_q24(u_q24: u32) -> u16 {
    // u_q24 < 2^28, so ku = ⌊u⌋ ∈ [0, 15] (the mask is a no-op that lets
    // the compiler drop the bounds check below); f = frac(u) in Q.24.
    let ku = ((u_q24 >> 24) & 15) as usize;
    let f = u_q24 & 0xFF_FFFF;
    // i ∈ [0, 255], so i + 1 ≤ 256 is in the table; w < 2^16.
    let i = (f >> 16) as usize;
    let w = f & 0xFFFF;
    let a = EXP_RESIDUAL[i] as u32;
    let b = EXP_RESIDUAL[i + 1] as u32;
    // Residual r(f) in Q.35, interpolated. |b − a| < 2^10 (checked at
    // compile time), so |b − a|·w < 2^26; a, b ≤ 41641, so the result lies
    // between a·2^16 and b·2^16, below 41641·2^16 < 2.73·10^9 < 2^32.
    let r_q35 = if b >= a {
        (a << 16) + (b - a) * w
    } else {
        (a << 16) - (a - b) * w
    };
    // om = 1 − e^−f in Q.32 = (161/256)·f + r. 161·f < 161·2^24 < 2.71·10^9;
    // (r_q35 + 4) >> 3 < 3.5·10^8; sum < 3.06·10^9 < 2^32.
    let om = EXP_SLOPE_Q8 * f + ((r_q35 + 4) >> 3);
    if ku == 0 {
        // Result = 1 − om/2^32, rounded (halves up) to Q.15:
        // ⌊(2^32 − om + 2^16) / 2^17⌋ = 2^15 − ⌈(om − 2^16) / 2^17⌉
        //                           = 2^15 − ⌊(om + 2^16 − 1) / 2^17⌋,
        // valid for every om ≥ 0 (both sides are 2^15 when om < 2^16).
        // om + 0xFFFF < 2^32; the subtrahend is < 2^32 >> 17 = 2^15.
        ONE_Q15 - ((om + 0xFFFF) >> 17) as u16
    } else {
        // e^−ku·e^−f = E − E·om/2^32 in Q.32, E = e^−ku in Q.32 < 2^31.
        // E·om < 2^63; (E·om) >> 32 < E since om < 2^32: no underflow.
        let e = EXP_NEG_INT[ku - 1];
        let v = e - (mul_u32(e, om) >> 32) as u32;
        // v < 2^31; rounded (halves up) to Q.15: < 2^14.
        ((v + (1 << 16)) >> 17) as u16
    }
}

/// `max(x, 0)^n` from a cosine `x` in `Q.28` (`i32`, 1.0 = 2²⁸; e.g. a
/// [`Unit3::dot`](crate::Unit3::dot)), for callers that only have `x`.
/// Values above 1.0 clamp to 1. Result in `Q.15` as [`pow_from_delta`].
///
/// Prefer [`pow_from_delta`] with
/// [`Unit3::half_dist_sq`](crate::Unit3::half_dist_sq) for steep exponents:
/// `1 − x` formed from a rounded dot product near 1 has lost its relative
/// precision.
#[cfg(test)]
pub(crate) fn pow_from_cos(x_q28: i32, n: Exponent) -> u16 {
    if n.is_zero() {
        return ONE_Q15;
    }
    if x_q28 <= 0 {
        return 0;
    }
    // x ∈ (0, 2^28] after the clamp, so δ = 2^28 − x ∈ [0, 2^28).
    let x = (x_q28 as u32).min(ONE_Q28);
    pow_from_delta(ONE_Q28 - x, n)
}

#[cfg(test)]
mod tests {
    /// The two forms of `u = n·t` agree, and with the 64-bit product:
    /// every exponent below 2¹⁶ at its ends and at random `s`, and the
    /// threshold `u ≥ 16` on both sides.
    #[test]
    fn q24_forms_agree() {
        use super::{q40_to_q24, q40_to_q24_halves};
        let mut next = crate::tests::xorshift(0x005e_ed0f_7a1e_u64);
        let ns = [0u32, 1, 255, 256, 1 << 15, (1 << 16) - 1];
        for i in 0..200_000u32 {
            let n = if i < 6 {
                ns[i as usize]
            } else {
                (next() as u32) >> (16 + i % 16)
            };
            let s = match i % 4 {
                0 => u32::MAX,
                1 => (next() as u32) >> (i % 32),
                // Near the threshold: n·s ≈ 2^44.
                _ => {
                    ((1u64 << 44) / (n.max(1) as u64)).min(u32::MAX as u64) as u32
                        ^ (next() as u32 & 3)
                }
            };
            let p = n as u64 * s as u64;
            let want = (p < 16 << 40).then_some((p >> 16) as u32);
            assert_eq!(q40_to_q24_halves(n, s), want, "{n} {s}");
            assert_eq!(q40_to_q24(n, s), want, "{n} {s}");
        }
    }

    /// The example from the docs of `Exponent::ZERO`.
    #[test]
    fn doc_exponent_zero() {
        use crate::{specular_table::pow_from_delta, Exponent};
        assert_eq!(pow_from_delta(1 << 29, Exponent::ZERO), 32768);
    }

    /// The example from the docs of `pow_from_delta`.
    #[test]
    fn doc_pow_from_delta() {
        use crate::{specular_table::pow_from_delta, Exponent};
        let n = Exponent::from_int(1000);
        assert_eq!(pow_from_delta(0, n), 32768);
        // x = 0.999: 0.999^1000 = 0.36770…, i.e. 12048.9 in Q.15.
        let delta = (0.001 * (1u64 << 28) as f64).round() as u32;
        assert!((pow_from_delta(delta, n) as i32 - 12049).abs() <= 1);
        // x = 0.5, n = 2: 0.25.
        assert_eq!(pow_from_delta(1 << 27, Exponent::from_int(2)), 8192);
        // x ≤ 0.
        assert_eq!(pow_from_delta(3 << 27, n), 0);
    }

    /// The example from the docs of `pow_from_cos`.
    #[test]
    fn doc_pow_from_cos() {
        use crate::{specular_table::pow_from_cos, Exponent, Unit3};
        let n = Exponent::from_int(8);
        assert_eq!(pow_from_cos(Unit3::Z.dot(Unit3::Z), n), 32768);
        assert_eq!(pow_from_cos(1 << 27, n), 128); // 0.5^8 = 1/256
        assert_eq!(pow_from_cos(-(1 << 27), n), 0);
        assert_eq!(pow_from_cos(-(1 << 27), Exponent::ZERO), 32768);
        assert_eq!(pow_from_cos(i32::MAX, n), 32768); // clamped to 1
    }
}

//! Normalisation without floats: unit vectors (and lengths) from integer
//! vectors, and the cosine of the angle between two ([`one_minus_cos`],
//! Blinn's `1 − N·H`), by a table-seeded reciprocal square root and one
//! Newton step; and, for Phong shading's pixels, directions kept as
//! integer vectors with the reciprocals of their lengths ([`Dir`]), whose
//! cosines need no unit vector.
//!
//! # Method
//!
//! 1. Take the magnitudes `|v_i|` (`unsigned_abs`, so `i32::MIN` / `i64::MIN`
//!    are fine) and shift all three by the same amount so that the largest
//!    lies in `[2¹⁹, 2²⁰]` (left shifts are exact; right shifts round to
//!    nearest). Call the result `b`. The shift does not change the direction;
//!    the rounding moves the output by at most `(√3/2)·2⁻¹⁹`, i.e. 0.027 ULP
//!    of the 2⁻¹⁴ output, and only for inputs wider than 20 bits.
//! 2. `S = ⌊|b|² / 2¹⁰⌋`, computed exactly with six 32 × 32 → 32-bit
//!    multiplies: each `b_i = h_i·2¹⁰ + l_i` and `b_i² = (b_i·h_i)·2¹⁰ + b_i·l_i`.
//!    `S ∈ [2²⁸, 2³²)`; shifting it left by 2 when below 2³⁰ (which halves
//!    the root exactly) puts it in `[2³⁰, 2³²)`.
//! 3. [`rsqrt_q`]: `1/√X` for the mantissa `X = S/2³² ∈ [¼, 1)` from a
//!    49-entry `u16` table (98 bytes) by linear interpolation (relative error
//!    ≤ 2⁻¹²·³), then one Newton step `y ← y + y·(1 − X·y²)/2` with the residual
//!    computed to 2⁻³⁰: relative error ≤ 2⁻²³·⁵.
//! 4. Each output `b_i / |b|` is formed with two 32-bit multiplies and
//!    rounded to nearest `I2F14`; the sign is put back afterwards, so
//!    `normalize(−v) == −normalize(v)` exactly.
//!
//! # Accuracy (measured by `src/tests/normalize.rs`)
//!
//! Worst component error against the f64 value `v_i/|v|` (1 ULP = 2⁻¹⁴;
//! run `cargo test -p fixshade --lib tests::normalize -- --nocapture` for the
//! figures):
//!
//! | test | vectors | max error | exactly rounded |
//! | --- | --- | --- | --- |
//! | `report_max_error`, [`normalize`], all scales | 10⁶ | 0.514 ULP | 99.82 % |
//! | `report_max_error`, [`normalize_len`], all scales | 10⁶ | 0.515 ULP | 99.76 % |
//! | `phong_range_sweep`, lengths 2¹⁴..2²¹ | 3.4·10⁵ | 0.509 ULP | 99.91 % |
//!
//! That is round-to-nearest plus at most 0.015 ULP; the analysis above bounds
//! the excess by 0.027 ULP (input rounding, wide inputs only) + 0.008 ULP
//! (reciprocal root and final product). No component is ever a full ULP off
//! (asserted by every sweep and property test). [`rsqrt_q`]'s relative error
//! is 2⁻²³·⁵³ over all 3·2³⁰ inputs (ignored test `rsqrt_q_exhaustive`).
//!
//! The length of [`normalize_len`] is the exactly rounded `|v|` when every
//! `|v_i| < 2³¹` (asserted against a 128-bit integer square root), and within
//! a relative 2⁻²⁹ of `|v|` otherwise (bound from the analysis, asserted;
//! 2⁻²⁹·⁹ measured): better than the "±1 raw unit or 2⁻²⁴ relative"
//! requirement.
//!
//! # Cost
//!
//! [`normalize`] (the per-pixel path) on ARMv6-M: 18 multiplies, all 32 × 32 → 32
//! (one `MULS` each on a Cortex-M0), two table reads, one `leading_zeros`
//! (a short compiler-builtins routine on thumbv6m, which has no `CLZ`), no
//! division, no 64-bit arithmetic. [`rsqrt_q`] alone is 6 multiplies and two
//! table reads.
//!
//! [`normalize_len`] does the same for the direction, plus, for the length,
//! three 64-bit squares, a second [`rsqrt_q`], a division-free Newton
//! correction and an exact rounding fix-up: 24 `MULS` and 7 64-bit multiplies
//! and about a dozen 64-bit variable shifts, which are library calls on
//! thumbv6m. It is meant for light vectors, not for the inner loop.
//!
//! (Counts from the thumbv6m release assembly of out-of-line copies.)
//!
//! # Zero
//!
//! The zero vector has no direction: both functions return `None` for it
//! (callers that want the [`Unit3::ZERO`] convention write
//! `normalize(v).unwrap_or(Unit3::ZERO)`). No input panics or overflows.

use crate::num::widening::{
    mul_hi32, mul_i32_u32, mul_i32_u32_shr26, mul_i32_u32_shr31, mul_u32, mul_u32_shr12,
    sum_sq3_shr10,
};
use crate::platform;
use crate::vector::{Unit3, UNIT_ONE};

/// `round((1/√X_k − c_k)·2¹⁵)` at the nodes `X_k = ¼ + k/64`, `k = 0..=48`,
/// where `c_k = f''(X_k)·(1/64)²/16` lowers each node by half the chord error
/// of linear interpolation, so the interpolant straddles `1/√X` instead of
/// lying above it. Decreasing; the largest entry (65524) leaves `y0² < 2³²`.
const RSQRT_TABLE: [u16; 49] = [
    65524, 63569, 61779, 60132, 58610, 57198, 55884, 54656, 53506, 52425, 51407, 50446, 49538,
    48676, 47858, 47080, 46339, 45631, 44956, 44309, 43689, 43095, 42524, 41975, 41447, 40939,
    40449, 39976, 39519, 39077, 38650, 38237, 37836, 37448, 37072, 36707, 36352, 36008, 35673,
    35347, 35030, 34721, 34421, 34128, 33842, 33564, 33292, 33027, 32768,
];

/// Bit position the largest magnitude is brought to before the unit-vector
/// core: `b_max ∈ [2^B_TOP, 2^(B_TOP+1)]`.
const B_TOP: u32 = 19;

/// Reciprocal square root of a normalised mantissa, in fixed point.
///
/// `x` is read as `X = x / 2³²` and must lie in `[2³⁰, 2³²)`, i.e.
/// `X ∈ [¼, 1)`; smaller inputs are treated as `2³⁰`. The result is
/// `1/√X` in `Q2.30` (`2³⁰` = 1.0), so it lies in `(2³⁰, 2³¹]`, with relative
/// error below `2⁻²³` (the test `rsqrt_q_accuracy` measures 2⁻²³·⁵ over a dense
/// sweep of the whole domain).
///
/// To get `1/√n` of an arbitrary `n`, shift `n` left by an even amount `2k`
/// into `[2³⁰, 2³²)`; then `1/√n = rsqrt_q(n << 2k) · 2^(k − 46)`.
///
/// Cost: two table reads and six 32 × 32 → 32-bit multiplies.
#[inline]
pub(crate) fn rsqrt_q(x: u32) -> u32 {
    let (y0, e) = rsqrt_seed(x);
    // Newton: y1 = y0 + y0·e/2. (e >> 6) is Q.24 with |·| ≤ 2^14, y0 < 2^16,
    // so the product is below 2^30 in magnitude; Q.39 → Q.30 and /2 is >> 10.
    // |corr| ≤ 2^20; y0 << 15 ∈ [2^30, 2^31 − 2^18], so adding it stays in
    // (0, 2^32).
    let corr = (y0 as i32 * (e >> 6)) >> 10;
    let y1 = (y0 << 15).wrapping_add_signed(corr);
    // 1/√X ≤ 2 and Newton from any start undershoots: y1 ≤ 2³¹ for every
    // input (`rsqrt_q_exhaustive` holds it over all of them; 137 units
    // below at x = 2³⁰, the largest).
    debug_assert!(y1 <= 1 << 31);
    y1
}

/// [`rsqrt_q`]'s seed `y0 ≈ 1/√X` (`Q1.15`, from the table) and its
/// residual `e = 1 − X·y0²` (`Q.30`), `x` taken into `[2³⁰, 2³²)` first.
/// `|e| < 2¹⁸·⁷` for every input (`rsqrt_q_exhaustive` holds `|e| ≤ 2²⁰`,
/// the bound the Newton step's ranges take, over all of them).
#[inline(always)]
pub(crate) fn rsqrt_seed(x: u32) -> (u32, i32) {
    let x = if x < 1 << 30 { 1 << 30 } else { x };
    // x ∈ [2^30, 2^32): top 6 bits ∈ [16, 64), so i ∈ [0, 48) and i + 1 ≤ 48.
    let i = ((x >> 26) - 16) as usize;
    let f = (x >> 10) & 0xFFFF; // position inside the interval, Q0.16
    let t0 = RSQRT_TABLE[i] as u32;
    let t1 = RSQRT_TABLE[i + 1] as u32;
    // The table decreases by at most 1955 per step, so (t0 − t1)·f < 2^27,
    // and y0 ∈ [t1, t0] ⊂ [2^15, 65524]: Q1.15, relative error ≤ 2^-12.3.
    let y0 = t0 - (((t0 - t1) * f) >> 16);
    // y0 ≤ 65524 → y0² < 2^32. Q2.30.
    let sq = y0 * y0;
    // X·y0² in Q2.30 (Q0.32 × Q2.30 → Q2.62, high word, to within 1); ≈ 2^30·(1 ± 2^-11.3),
    // so < 2^31 and the difference below fits i32.
    let p = mul_hi32(x, sq);
    let e = (1i32 << 30) - p as i32;
    debug_assert!(e.unsigned_abs() <= 1 << 20);
    (y0, e)
}

/// The unit vector of `b` (magnitudes, largest in `[2¹⁹, 2²⁰]`), with the
/// signs `neg` put back. The core of both public functions.
#[inline(always)]
fn unit_core(b: [u32; 3], neg: [bool; 3]) -> Unit3 {
    // |b|² = Σ (b·h)·2^10 + b·l with h = b >> 10 ≤ 2^10 and l < 2^10:
    // each b·h ≤ 2^30 and each b·l < 2^30, so both sums are < 3·2^30.
    // S = ⌊|b|²/2^10⌋ exactly. |b|² ≥ 2^38 (largest b ≥ 2^19), so S ≥ 2^28;
    // S < 3·2^30 + 3·2^20 < 2^32.
    let s = sum_sq3_shr10(b);
    // Bring S into [2^30, 2^32) by an even shift; `half` records that the
    // root of the shifted value is twice the root of S.
    let (s, half) = if s < 1 << 30 { (s << 2, 1) } else { (s, 0) };
    // |b| = √(S·2^10) = √(X·2^32)·2^(5 − half) = √X·2^(21 − half), so
    // 2^14·b/|b| = b·Y·2^(half − 7) with Y = y/2^30 ≈ 1/√X.
    let y = rsqrt_q(s) >> 8; // Y in Q.22, ≤ 2^23
    let mut out = [0i16; 3];
    for k in 0..3 {
        // b ≤ 2^20, y ≤ 2^23: t = ⌊b·y/2^12⌋ < 2^31 + 2^20.
        let t = mul_u32_shr12(b[k], y);
        // 2^14·b/|b| = t·2^(half − 17), rounded to nearest; t + 2^16 < 2^32.
        let sh = 17 - half;
        let r = (t + (1 << (sh - 1))) >> sh;
        // b/|b| ≤ 1, so r ≤ 2^14 up to the error analysed in the module docs;
        // the min keeps the invariant (and the i16) unconditionally.
        let r = if r > UNIT_ONE as u32 {
            UNIT_ONE
        } else {
            r as i16
        };
        out[k] = if neg[k] { -r } else { r };
    }
    Unit3::new_clamped(out[0], out[1], out[2])
}

/// The unit vector in the direction of `v`, for any `i32` vector at any
/// scale; `None` for the zero vector (which has no direction).
///
/// Components are rounded to nearest `I2F14`, within 0.54 ULP (0.514 measured) of the exact
/// `v_i/|v|` (see the module docs), and `normalize(−v) == −normalize(v)`
/// whenever `−v` is representable. On ARMv6-M only 32-bit multiplies
/// (18 of them); where the core has a 64-bit product, its squares and
/// its three final products take it (the same values).
#[inline]
pub(crate) fn normalize(v: [i32; 3]) -> Option<Unit3> {
    let a = v.map(i32::unsigned_abs); // each ≤ 2^31
    let m = a[0] | a[1] | a[2]; // same top bit as the largest
    if m == 0 {
        return None;
    }
    let top = 31 - platform::leading_zeros(m); // m ≥ 1 → top ∈ [0, 31]
    let b = if top <= B_TOP {
        // a < 2^(top+1) → b < 2^20, exact.
        let sh = B_TOP - top;
        a.map(|x| x << sh)
    } else {
        // sh ∈ [1, 12]; x + 2^(sh−1) ≤ 2^31 + 2^11 < 2^32, and
        // b = round(x/2^sh) ≤ 2^20 because x < 2^(top+1).
        let sh = top - B_TOP;
        a.map(|x| (x + (1 << (sh - 1))) >> sh)
    };
    Some(unit_core(b, v.map(|x| x < 0)))
}

/// `1 − cos θ` in `Q.28` (`0 ..= 2²⁹`) for the angle `θ` between a unit
/// vector `n` (raw `I2F14`, its squared length within 2⁻¹³ of 1, as
/// [`normalize`] makes them) and a vector `s` whose components lie within
/// ±2¹⁵ (the sum of two unit vectors: Blinn's `L + V`), or `None` where
/// `s` is zero (no direction).
///
/// The cosine is `n·s/(|n|·|s|)`: `1/|s|` from one reciprocal square
/// root ([`rsqrt_q`]) of `|s|²`, and `n`'s length to first order, `|n| ≈
/// 2¹⁴·(1 + ε)` with `ε = (|n|² − 2²⁸)/2²⁹` (the error `ε²` below 2⁻²⁴), so
/// that its components' rounding cancels: no unit vector is made. The
/// result is within about 2⁻²³ of `1 − cos θ` where `|s|² ≥ 2²⁸` (`|L +
/// V| ≥ 1/2`), and within `2^(k/2)` units where `|s|²` needs an even shift
/// `k` into [2³⁰, 2³²). (A normalised `H` carries its components' 2⁻¹⁵
/// rounding into `1 − N·H`.) Only 32-bit arithmetic, and the same on
/// every core.
///
/// Ranges: each `|nᵢsᵢ| ≤ 2²⁹`, so `n·s` and its partial sums lie within
/// 3·2²⁹ (`i32`); `|n|² ≤ 3·2²⁸`, `|s|² ≤ 3·2³⁰` (`u32`); `t = ⌊n·s·r/2³¹⌋`
/// is the cosine in `Q.28` times `(1 + ε)·2^(1 − k/2)`, so `t·2^(k/2 − 1)`
/// stays below 2²⁹ + 2¹⁴; `(v/2¹⁴)·(|n|² − 2²⁸)`, the latter clamped to
/// ±2¹⁵, within 2³⁰.
pub(crate) fn one_minus_cos(n: [i32; 3], s: [i32; 3]) -> Option<u32> {
    let dot = n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
    let nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    let sq = |v: i32| v.unsigned_abs() * v.unsigned_abs();
    let ss = sq(s[0]) + sq(s[1]) + sq(s[2]);
    if ss == 0 {
        return None;
    }
    let k = platform::leading_zeros(ss) & !1;
    // r = 2³⁰/√X, X = ss·2ᵏ/2³², so 1/|s| = r·2^(k/2 − 46) and, with
    // 1/|n| ≈ 2⁻¹⁴·(1 − ε), the cosine in Q.28 is n·s·r·2^(k/2 − 32)·(1 − ε).
    let r = rsqrt_q(ss << k);
    let t = mul_i32_u32_shr31(dot, r);
    let v = if k >= 2 { t << (k / 2 - 1) } else { t >> 1 };
    // `normalize`'s vectors lie within 2¹⁵ of 2²⁸ in |n|²; one farther
    // from unit length (any `Unit3` may be given) is taken at 2¹⁵.
    let dev = (nn - (1 << 28)).clamp(-(1 << 15), 1 << 15);
    let c = v - (((v >> 14) * dev) >> 15);
    Some(((1 << 28) - c).clamp(0, 1 << 29) as u32)
}

/// A direction in the form the per-pixel lighting takes: an integer
/// vector `d` whose largest magnitude lies in `[2¹³, 2¹⁴]`, its squared
/// length `dd` and `u = 2⁴⁴/|d|` (within a relative 2⁻²³, [`rsqrt_q`] of
/// the exact `dd`), so that `d·u/2⁴⁴` is the unit vector. No unit vector
/// is rounded: the cosine of two directions ([`Dir::cos`]) takes their
/// integer dot product and both `u`, so a length's rounding does not reach
/// `1 − cos` near 0, where steep powers read it (the rounding of `d`'s
/// components turns the direction by at most 2⁻¹³, which moves `1 − cos`
/// to second order there).
///
/// Ranges: `|dᵢ| ≤ 2¹⁴`, `2²⁶ ≤ dd ≤ 3·2²⁸`, `u ∈ (2²⁹, 2³¹]`; the dot
/// product of two directions is at most `|a|·|b| ≤ 3·2²⁸` in magnitude.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Dir {
    d: [i32; 3],
    dd: u32,
    u: u32,
}

impl Dir {
    /// `+Z`: the infinite viewer's `V`.
    pub(crate) const Z: Dir = Dir {
        d: [0, 0, 1 << 14],
        dd: 1 << 28,
        u: 1 << 30,
    };

    /// The components of `v` divided by `2^s`, rounded, with `s` such that
    /// the largest magnitude lands in `[2¹³, 2¹⁴]`, and `s`; `None` for the
    /// zero vector. (Only shifts: the sign of a dot product with the result
    /// is known before [`Dir::new`] takes the root.)
    #[inline(always)]
    pub(crate) fn reduce(v: [i32; 3]) -> Option<([i32; 3], i32)> {
        // `c ^ (c >> 31)` is `|c|`, or `|c| − 1` for a negative `c` (one
        // instruction on ARMv7-M, against four for the magnitude): the top
        // bit of their union is the largest magnitude's, or one lower
        // where that is a negative power of two, `−2ᵏ`, which is then
        // reduced to `−2¹⁴`; so every |vᵢ| ≤ 2^(top + 1) and the largest
        // lands in [2¹³, 2¹⁴] either way.
        let m = [0, 1, 2].map(|i| (v[i] ^ (v[i] >> 31)) as u32);
        let m = match m[0] | m[1] | m[2] {
            0 if v == [0; 3] => return None,
            // Components of 0 and −1 only: top bit 0, as for 1.
            0 => 1,
            m => m,
        };
        let s = 31 - platform::leading_zeros(m) as i32 - 13;
        let d = if s > 0 {
            // vᵢ >> (s − 1) lies within ±2¹⁵: adding 1 cannot overflow, and
            // the rounded half within ±2¹⁴.
            v.map(|c| ((c >> (s - 1)) + 1) >> 1)
        } else {
            // Exact: |vᵢ| < 2^(13 + s + 1), shifted left by −s ≤ 13.
            v.map(|c| c << -s)
        };
        Some((d, s))
    }

    /// [`Dir::reduce`] of a wide vector (a light farther than 2⁷ units):
    /// first taken to 30 bits (a rounding of 2⁻²⁹ of the largest
    /// component, far below the direction's own 2⁻¹⁴).
    pub(crate) fn reduce_wide(v: [i64; 3]) -> Option<([i32; 3], i32)> {
        if let (Ok(x), Ok(y), Ok(z)) = (
            i32::try_from(v[0]),
            i32::try_from(v[1]),
            i32::try_from(v[2]),
        ) {
            return Dir::reduce([x, y, z]);
        }
        let m = v[0].unsigned_abs() | v[1].unsigned_abs() | v[2].unsigned_abs();
        // Some |vᵢ| ≥ 2³¹: t ≥ 2, and vᵢ >> (t − 1) lies within ±2³¹, its
        // rounded half within ±2³⁰.
        let t = 63 - m.leading_zeros() as i32 - 29;
        let w = v.map(|c| (((c >> (t - 1)) + 1) >> 1) as i32);
        let (d, s) = Dir::reduce(w)?;
        Some((d, s + t))
    }

    /// The direction of reduced components `d` (largest magnitude in
    /// `[2¹³, 2¹⁴]`: [`Dir::reduce`]'s, or a unit vector's `I2F14` bits,
    /// whose largest is at least `2¹⁴/√3`).
    #[inline(always)]
    pub(crate) fn new(d: [i32; 3]) -> Dir {
        // Each square at most 2²⁸: the sum within [2²⁶, 3·2²⁸].
        let dd = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) as u32;
        // An even shift k into [2³⁰, 2³²): 4 below 2²⁸, else 2. Then
        // rsqrt_q = 2⁴⁶/√(dd·2ᵏ) = 2^(46 − k/2)/|d|, and u = 2⁴⁴/|d| is
        // it shifted right by 2 − k/2.
        let (x, half) = if dd < 1 << 28 {
            (dd << 4, 0)
        } else {
            (dd << 2, 1)
        };
        Dir {
            d,
            dd,
            u: rsqrt_q(x) >> half,
        }
    }

    /// The direction of a unit vector `u` (its squared length within 2⁻¹²
    /// of 1, as [`normalize`] and the lights' preparation make them; one
    /// farther is taken at 2⁻¹²), without a root: `u = 2³⁰·(1 + e)^(−½)`
    /// for `dd = 2²⁸·(1 + e)` is `2³⁰ − 2·(dd − 2²⁸)` within `(3/8)e²·2³⁰`:
    /// 6 units (a relative 2⁻²⁷) where `|e| ≤ 2⁻¹³`.
    pub(crate) fn of_unit(u: Unit3) -> Dir {
        let d = u.to_bits().map(i32::from);
        let dd = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) as u32;
        // (Within 2¹⁶ − 1 above: one `SSAT` on ARMv7-M; a unit vector
        // within 2⁻¹³ never reaches either end.)
        let e = (dd as i32 - (1 << 28)).clamp(-(1 << 16), (1 << 16) - 1);
        Dir {
            d,
            dd,
            u: ((1i32 << 30) - 2 * e) as u32,
        }
    }

    /// The integer dot product with `o` (at most `3·2²⁸` in magnitude):
    /// the cosine's sign, before any root.
    #[inline(always)]
    pub(crate) fn dot_d(d: &[i32; 3], o: &Dir) -> i32 {
        d[0] * o.d[0] + d[1] * o.d[1] + d[2] * o.d[2]
    }

    /// The components.
    #[inline(always)]
    pub(crate) fn d(&self) -> &[i32; 3] {
        &self.d
    }

    /// The cosine of the angle to `o`, `Q.30`.
    #[inline(always)]
    pub(crate) fn cos(&self, o: &Dir) -> i32 {
        self.cos_of_dot(Dir::dot_d(&self.d, o), o)
    }

    /// The cosine of the angle to `o` from the dot product `dot` of the
    /// two (`Q.30`): `dot·u·u′/2⁸⁸`. `u·u′ ≤ 2⁶²`, its high word `uu ≤
    /// 2³⁰` (truncated: a relative 2⁻²⁹), and `|dot·uu| < 2⁶⁰`; the cosine
    /// is within a relative 2⁻²² of the reduced vectors' (at most `2³⁰·(1
    /// + 2⁻²²)` in magnitude).
    #[inline(always)]
    pub(crate) fn cos_of_dot(&self, dot: i32, o: &Dir) -> i32 {
        let uu = mul_hi32(self.u, o.u);
        mul_i32_u32_shr26(dot, uu)
    }

    /// [`Dir::cos`] with `+Z` ([`Dir::Z`], `u = 2³⁰`): `d_z·u/2¹⁴`, one
    /// product (`|d_z·u| ≤ 2⁴⁵`).
    #[inline(always)]
    pub(crate) fn cos_z(&self) -> i32 {
        (mul_i32_u32(self.d[2], self.u) >> 14) as i32
    }

    /// The cosine of the angle to `o` from a positive dot product `dot` of
    /// the two, in `Q.15`, clamped to 1: the diffuse factor, from six 32-bit
    /// products on every core (the same value everywhere). `uu = u·u′/2³²`
    /// from 16-bit halves (`≤ 2³⁰ + 2¹⁷`, within 3 units: the low
    /// halves' product and two floors), then `dot·uu/2³⁰` from 15-bit
    /// halves (`dot ≤ 3·2²⁸`: each product below 2³⁰, the middle sum below
    /// 2³¹; within 2 units), its `2⁻¹¹` rounded: within about half a unit
    /// of 2⁻¹⁵ of the cosine.
    #[inline(always)]
    pub(crate) fn cos15(&self, dot: i32, o: &Dir) -> u32 {
        let (ah, al) = (self.u >> 16, self.u & 0xFFFF);
        let (bh, bl) = (o.u >> 16, o.u & 0xFFFF);
        let uu = ah * bh + ((ah * bl) >> 16) + ((al * bh) >> 16);
        let dot = dot as u32;
        let (dh, dl) = (dot >> 15, dot & 0x7FFF);
        let (uh, ul) = (uu >> 15, uu & 0x7FFF);
        let c = dh * uh + ((dh * ul + dl * uh) >> 15);
        ((c + (1 << 10)) >> 11).min(1 << 15)
    }

    /// `|d|·2^s` (for `d` reduced from `v` by `s`: `v`'s length in its own
    /// units, within a relative 2⁻¹³, the rounding of `d`), saturating.
    /// `dd·u = |d|·2⁴⁴` is below 2⁵⁹.
    #[inline(always)]
    pub(crate) fn length(&self, s: i32) -> u64 {
        let p = mul_u32(self.dd, self.u);
        let sh = 44 - s;
        if sh >= 0 {
            p >> sh.min(63)
        } else if p > u64::MAX >> -sh {
            u64::MAX
        } else {
            p << -sh
        }
    }
}

/// `1 − x` in `Q.28` (`0 ..= 2²⁹`), rounded, of a cosine `x` in `Q.30`
/// taken within [−1, 1].
#[inline(always)]
pub(crate) fn one_minus_q28(x: i32) -> u32 {
    // 2³⁰ − x ∈ [1, 2³¹] (u32). The upper end 2³⁰ − 1 rather than 2³⁰
    // (one `SSAT` on ARMv7-M) gives the same result: (1 + 2) >> 2 = 0.
    let x = x.clamp(-(1 << 30), (1 << 30) - 1);
    ((1u32 << 30).wrapping_sub(x as u32) + 2) >> 2
}

/// The unit vector in the direction of a wide vector and its length in `v`'s
/// own raw units, rounded to nearest; `None` for the zero vector.
///
/// The unit vector is as accurate as [`normalize`]'s. The length is the
/// exactly rounded `|v|` when every `|v_i| < 2³¹`, and within a relative
/// `2⁻²⁹` otherwise. It always fits: `|v| ≤ √3·2⁶³ < 2⁶⁴`.
pub(crate) fn normalize_len(v: [i64; 3]) -> Option<(Unit3, u64)> {
    let a = v.map(i64::unsigned_abs); // each ≤ 2^63
    let m = a[0] | a[1] | a[2];
    if m == 0 {
        return None;
    }
    let top = 63 - m.leading_zeros(); // ∈ [0, 63]

    // Direction: the same 20-bit reduction as `normalize`.
    let b = if top <= B_TOP {
        let sh = B_TOP - top;
        a.map(|x| (x << sh) as u32) // < 2^20
    } else {
        // sh ∈ [1, 44]; (x >> (sh−1)) < 2^21, +1 no overflow; result ≤ 2^20.
        let sh = top - B_TOP;
        a.map(|x| (((x >> (sh - 1)) + 1) >> 1) as u32)
    };
    let unit = unit_core(b, v.map(|x| x < 0));

    // Length: reduce to at most 31 bits (w ≤ 2^31), so Σw² ≤ 3·2^62 < 2^64.
    let (w, sh2) = if top <= 30 {
        (a, 0)
    } else {
        // sh2 ∈ [1, 33]; (x >> (sh2−1)) < 2^32, so w ≤ 2^31 (≤ 2^30 when
        // top = 63, because then x ≤ 2^63).
        let sh2 = top - 30;
        (a.map(|x| ((x >> (sh2 - 1)) + 1) >> 1), sh2)
    };
    let s = w[0] * w[0] + w[1] * w[1] + w[2] * w[2]; // ≥ 1 since m ≠ 0
    let n = round_sqrt(s);
    // n·2^sh2 ≈ |v| ≤ √3·2^63 (see the bound on w above): never saturates.
    let len = if n > u64::MAX >> sh2 {
        u64::MAX
    } else {
        n << sh2
    };
    Some((unit, len))
}

/// `round(√s)` exactly, for `1 ≤ s ≤ 3·2⁶²`, without division.
fn round_sqrt(s: u64) -> u64 {
    // Even shift into [2^62, 2^64); k2 = half the shift.
    let k2 = s.leading_zeros() / 2; // ≤ 31
    let sn = s << (2 * k2);
    let x = (sn >> 32) as u32; // ∈ [2^30, 2^32)
    let y = rsqrt_q(x) as u64; // 2^30/√X, X = x/2^32, ≤ 2^31
                               // √sn ≈ 2^32·√X = 2^32·X·(1/√X) = x·y/2^30 (x·y < 2^63). Relative error
                               // ≤ 2^-22, so r0 < 2^32 up to rounding; clamp to keep r0² < 2^64.
    let r0 = ((x as u64 * y) >> 30).min(u32::MAX as u64);
    // Residual d = sn − r0²: |d| ≤ 2^64·2^-21 = 2^43 (the clamp to 2^44 never
    // acts). The wrapping difference reinterpreted as i64 is exact since the
    // true value is far inside i64.
    let d = (sn.wrapping_sub(r0 * r0) as i64).clamp(-(1 << 44), 1 << 44);
    // Newton without division: r1 = r0 + d/(2√sn) = r0 + d·y/2^63, kept in
    // Q.8. (d >> 13)·y: |·| ≤ 2^31·2^31 = 2^62. The result's error is below
    // 2^-3 (in units of √s after the shift below).
    let corr8 = ((d >> 13) * y as i64) >> 42;
    let r1 = ((r0 as i64) << 8) + corr8; // ≈ √sn·2^8 ∈ [2^39, 2^40 + 2^9)
                                         // Back to √s: divide by 2^(k2 + 8), rounding. r1 > 0.
    let q = 8 + k2;
    let mut n = (((r1 as u64) + (1 << (q - 1))) >> q).min(u32::MAX as u64);
    // |n − √s| < 0.5 + 2^-3, so n is round(√s) or off by one. Exact fix-up:
    // n = round(√s) ⇔ n² − n < s ≤ n² + n. n < 2^32 → n² + n < 2^64.
    let nn = n * n;
    if n > 0 && nn - n >= s {
        n -= 1;
    } else if nn + n < s {
        n += 1;
    }
    n
}

#[cfg(test)]
mod tests {
    /// The example from the docs of `rsqrt_q`.
    #[test]
    fn doc_rsqrt_q() {
        use crate::normalize::rsqrt_q;
        // X = 1/4 → 1/√X = 2, i.e. 2^31 in Q2.30 (to within 2^-23 relative).
        let y = rsqrt_q(1 << 30) as i64;
        assert!((y - (1i64 << 31)).abs() < 1 << 8);
        // X = 9/16 → 4/3.
        let y = rsqrt_q(9 << 28) as i64;
        assert!((y - (4i64 << 30) / 3).abs() < 1 << 8);
    }

    /// The example from the docs of `normalize`.
    #[test]
    fn doc_normalize() {
        use crate::{normalize::normalize, Unit3};
        assert_eq!(normalize([0, 0, 5]), Some(Unit3::Z));
        assert_eq!(normalize([0, 0, 0]), None);
        // (3, 4, 0)/5 = (0.6, 0.8, 0): 0.6·2^14 = 9830.4, 0.8·2^14 = 13107.2.
        assert_eq!(
            normalize([-300, 400, 0]).unwrap().to_bits(),
            [-9830, 13107, 0]
        );
        // Extremes are fine: |i32::MIN| is taken without overflow.
        assert_eq!(normalize([i32::MIN, 0, 0]), Some(Unit3::X.neg()));
    }

    /// The example from the docs of `normalize_len`.
    #[test]
    fn doc_normalize_len() {
        use crate::normalize::normalize_len;
        let (u, len) = normalize_len([0, -3 << 40, 4 << 40]).unwrap();
        assert_eq!(len, 5 << 40);
        assert_eq!(u.to_bits(), [0, -9830, 13107]);
        assert_eq!(normalize_len([1, 1, 1]).unwrap().1, 2); // √3 = 1.73…
        assert_eq!(normalize_len([0, 0, 0]), None);
    }
}

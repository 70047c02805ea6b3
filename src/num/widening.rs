//! Products wider than their operands, cheap on every core.
//!
//! On a Cortex-M0/M0+ (and M23) there is no 32 × 32 → 64-bit multiply
//! instruction: `a as i64 * b as i64` is a call to `__aeabi_lmul`, a full
//! 64 × 64-bit product of 37 instructions a call (QEMU count, S1). These
//! functions build the same products from 16 × 16 → 32-bit multiplies (one
//! `muls` each), inline, on those targets
//! ([`platform::SOFT_MUL64`]), and are the plain product everywhere else. Both
//! forms are compiled on every target and the unit tests hold the limb
//! forms to the plain products; CI also runs the whole test suite on the
//! host with the limb forms (`RUSTFLAGS="--cfg fixshade_soft_mul64"`),
//! where a debug build checks every call's operand ranges.

use crate::platform;

/// `a · b`, exactly (`|a · b| ≤ 2⁶²`).
#[inline(always)]
pub(crate) fn mul_i32(a: i32, b: i32) -> i64 {
    if platform::SOFT_MUL64 {
        mul_i32_limbs(a, b)
    } else {
        a as i64 * b as i64
    }
}

/// `a · b`, exactly (below 2⁶⁴).
#[inline(always)]
pub(crate) const fn mul_u32(a: u32, b: u32) -> u64 {
    if platform::SOFT_MUL64 {
        mul_u32_limbs(a, b)
    } else {
        a as u64 * b as u64
    }
}

/// `a · b`, exactly (`|a·b| < 2⁶³`): on the targets without a 32 × 32 →
/// 64-bit multiply, four 16 × 16 → 32-bit products (`aₕ` signed, the other
/// halves unsigned: `|aₕ·bₕ|`, `|aₕ·bₗ| < 2³¹`, `aₗ·bₕ`, `aₗ·bₗ < 2³²`).
#[inline(always)]
pub(crate) fn mul_i32_u32(a: i32, b: u32) -> i64 {
    if platform::SOFT_MUL64 {
        mul_i32_u32_limbs(a, b)
    } else {
        a as i64 * b as i64
    }
}

/// `⌊a·b / 2³¹⌋`, exactly, for `a > i32::MIN` and a result that fits
/// `i32` (a quotient estimate's high part: the window position, the
/// depth).
#[inline(always)]
pub(crate) fn mul_i32_u32_shr31(a: i32, b: u32) -> i32 {
    if platform::SOFT_MUL64 {
        mul_i32_u32_shr31_limbs(a, b)
    } else {
        ((a as i64 * b as i64) >> 31) as i32
    }
}

/// `⌊a·b / 2²⁶⌋` as `i32` (wrapped where it does not fit), for `|a| ≤
/// 3·2²⁸` and `b ≤ 2³⁰`: a cosine from a dot product and two reciprocal
/// lengths (`Dir::cos_of_dot`). Its own decomposition beside
/// [`mul_i32_u32_shr31`]'s: these operands keep the two middle products'
/// sum within `i32`, which the full range does not (the shared form
/// measured M0+ S4 +1.25 %).
#[inline(always)]
pub(crate) fn mul_i32_u32_shr26(a: i32, b: u32) -> i32 {
    debug_assert!(a.unsigned_abs() <= 3 << 28 && b <= 1 << 30);
    if platform::SOFT_MUL64 {
        mul_i32_u32_shr26_limbs(a, b)
    } else {
        ((a as i64 * b as i64) >> 26) as i32
    }
}

/// [`mul_i32_u32_shr26`] from four 16 × 16-bit products. With `a =
/// aₕ·2¹⁶ + aₗ` (`|aₕ| ≤ 3·2¹²`, `0 ≤ aₗ < 2¹⁶`) and `b` likewise (`bₕ ≤
/// 2¹⁴`), `a·b = aₕbₕ·2³² + m·2¹⁶ + l` with `m = aₕbₗ + aₗbₕ` (below
/// `3·2²⁸ + 2³⁰ < 2³¹` in magnitude) and `l = aₗbₗ < 2³²`; so the floor by
/// 2²⁶ is `aₕbₕ·2⁶ + ⌊m/2¹⁰⌋ + ⌊(m mod 2¹⁰ + ⌊l/2¹⁶⌋)/2¹⁰⌋` (the fraction
/// that `l`'s low half leaves out cannot carry past a multiple of 2¹⁰),
/// summed modulo 2³².
#[inline(always)]
pub(crate) fn mul_i32_u32_shr26_limbs(a: i32, b: u32) -> i32 {
    let (ah, al) = (a >> 16, (a & 0xFFFF) as u32);
    let (bh, bl) = ((b >> 16) as i32, b & 0xFFFF);
    let m = ah * bl as i32 + (al * bh as u32) as i32;
    let l = al * bl;
    let low = (((m & 0x3FF) as u32 + (l >> 16)) >> 10) as i32;
    (ah * bh)
        .wrapping_mul(64)
        .wrapping_add(m >> 10)
        .wrapping_add(low)
}

/// [`mul_i32_u32_shr31`] from four 16 × 16-bit products. With `a =
/// aₕ·2¹⁶ + aₗ` (`|aₕ| ≤ 2¹⁵`, `0 ≤ aₗ < 2¹⁶`) and `b` likewise
/// (unsigned), `x₁ = aₕbₗ` (`|x₁| < 2³¹`), `x₂ = aₗbₕ` and `x₃ = aₗbₗ`
/// (below 2³², split in halves): `a·b = (aₕbₕ + x₂ₕ)·2³² + (x₁ + x₂ₗ +
/// x₃ₕ)·2¹⁶ + x₃ₗ`. The last term, below 2¹⁶, cannot change the floor by
/// 2³¹ of a multiple of 2¹⁶, so `⌊a·b/2³¹⌋ = 2(aₕbₕ + x₂ₕ) + ⌊(x₁ + x₂ₗ +
/// x₃ₕ)/2¹⁵⌋`, the last floor taken as `⌊x₁/2¹⁵⌋ + ⌊(x₁ mod 2¹⁵ + x₂ₗ +
/// x₃ₕ)/2¹⁵⌋` (no sum past 2¹⁸), the terms summed modulo 2³².
#[inline(always)]
pub(crate) fn mul_i32_u32_shr31_limbs(a: i32, b: u32) -> i32 {
    let (ah, al) = (a >> 16, (a & 0xFFFF) as u32);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let x1 = ah * bl as i32;
    let (x2, x3) = (al * bh, al * bl);
    let low = (x1 & 0x7FFF) as u32 + (x2 & 0xFFFF) + (x3 >> 16);
    // Modulo 2³²: the terms may pass i32's ends, the sum does not.
    let hi = (ah * bh as i32).wrapping_add((x2 >> 16) as i32);
    hi.wrapping_mul(2)
        .wrapping_add(x1 >> 15)
        .wrapping_add((low >> 15) as i32)
}

/// [`mul_i32_u32`] from 16-bit halves.
#[inline(always)]
pub(crate) fn mul_i32_u32_limbs(a: i32, b: u32) -> i64 {
    let (ah, al) = (a >> 16, (a & 0xFFFF) as u32);
    let (bh, bl) = ((b >> 16) as i32, b & 0xFFFF);
    let mid = (ah * bl as i32) as i64 + (al * bh as u32) as i64;
    (((ah * bh) as i64) << 32) + (mid << 16) + (al * bl) as i64
}

/// [`mul_i32`] from 16-bit halves: `a = aₕ·2¹⁶ + aₗ` with `aₕ` signed
/// (`|aₕ| ≤ 2¹⁵`) and `0 ≤ aₗ < 2¹⁶`, likewise `b`. Each partial product
/// fits 32 bits: `|aₕbₕ| ≤ 2³⁰`, `|aₕbₗ| < 2³¹` (so `aₕbₗ + aₗbₕ` is summed
/// in `i64`), `aₗbₗ < 2³²` unsigned.
#[inline(always)]
pub(crate) fn mul_i32_limbs(a: i32, b: i32) -> i64 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let mid = (ah * bl) as i64 + (al * bh) as i64;
    (((ah * bh) as i64) << 32) + (mid << 16) + (al as u32 * bl as u32) as i64
}

/// [`mul_u32`] from 16-bit halves: `aₗbₗ + (aₕbₗ + aₗbₕ)·2¹⁶ + aₕbₕ·2³²`,
/// each partial product below 2³², the middle sum's carry kept.
#[inline(always)]
pub(crate) const fn mul_u32_limbs(a: u32, b: u32) -> u64 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let (mid, carry) = (ah * bl).overflowing_add(al * bh);
    let hi = ((ah * bh) as u64 + ((carry as u64) << 16)) << 32;
    hi + (al * bl) as u64 + ((mid as u64) << 16)
}

/// `a · b`, exactly (`|a · b| ≤ 2⁴⁶`): on the targets without a 32 × 32 →
/// 64-bit multiply, two 16 × 16 → 32-bit products, with `a = aₕ·2¹⁶ + aₗ`
/// (`|aₕ| ≤ 2¹⁵`, `0 ≤ aₗ < 2¹⁶`): `|aₕ·b| ≤ 2³⁰` and `|aₗ·b| < 2³¹` fit
/// `i32` (the plain product elsewhere).
#[inline(always)]
pub(crate) fn mul_i32_i16(a: i32, b: i16) -> i64 {
    if platform::SOFT_MUL64 {
        mul_i32_i16_limbs(a, b)
    } else {
        a as i64 * b as i64
    }
}

/// `a · b`, exactly, for `b` an `i16`'s value kept in an `i32` (`|b| <
/// 2¹⁵`, `|a · b| < 2⁴⁷`): on the targets without a 32 × 32 → 64-bit
/// multiply, two 16 × 16 → 32-bit products, `aₕ·b` and `aₗ·b` (the halves
/// `aₕ`, `aₗ < 2¹⁶` unsigned: each product below 2³¹ in magnitude).
#[inline(always)]
pub(crate) fn mul_u32_i16(a: u32, b: i32) -> i64 {
    debug_assert!(b.unsigned_abs() < 1 << 15);
    if platform::SOFT_MUL64 {
        mul_u32_i16_limbs(a, b)
    } else {
        mul_i32_u32(b, a)
    }
}

/// [`mul_u32_i16`] from 16-bit halves of `a`.
#[inline(always)]
pub(crate) fn mul_u32_i16_limbs(a: u32, b: i32) -> i64 {
    ((((a >> 16) as i32 * b) as i64) << 16) + ((a & 0xFFFF) as i32 * b) as i64
}

/// `⌊a·b/2ᵏ⌋` (`|b| < 2¹⁵`, `k ≤ 31`) where it fits `i32`: where a
/// 64-bit product is made from 16-bit ones, from the halves' products
/// alone ([`mul_u32_i16_shr_limbs`]); elsewhere the product, shifted.
#[inline(always)]
pub(crate) fn mul_u32_i16_shr(a: u32, b: i32, k: u32) -> Option<i32> {
    if platform::SOFT_MUL64 {
        mul_u32_i16_shr_limbs(a, b, k)
    } else {
        shr_to_i32(mul_u32_i16(a, b), k)
    }
}

/// `⌊p/2ᵏ⌋` (`k ≤ 31`) if it fits `i32`: from `p`'s 32-bit halves, a
/// variable 64-bit shift being a sequence of its own on a 32-bit core.
#[inline(always)]
pub(crate) fn shr_to_i32(p: i64, k: u32) -> Option<i32> {
    let (lo, hi) = (p as u32, (p >> 32) as i32);
    let q = ((lo >> k) | (((hi as u32) << 1) << (31 - k))) as i32;
    // It fits where the high half holds nothing but the sign beyond it.
    ((hi >> k) == (q >> 31)).then_some(q)
}

/// `x` clamped to `i32`'s range: on a 32-bit core a comparison of the
/// high word with the low word's sign, where an `i64` clamp is two 64-bit
/// comparisons.
#[inline(always)]
pub(crate) fn saturate_i32(x: i64) -> i32 {
    let lo = x as i32;
    if (x >> 32) as i32 == lo >> 31 {
        lo
    } else if x < 0 {
        i32::MIN
    } else {
        i32::MAX
    }
}

/// [`mul_u32_i16_shr`]'s value from the halves' products `h = aₕ·b` and `l = aₗ·b` (each below 2³¹ in
/// magnitude, and of `b`'s sign) without their 64-bit sum: for `k ≥ 16`
/// it is `⌊(h + ⌊l/2¹⁶⌋)/2ᵏ⁻¹⁶⌋` (the sum below `(2¹⁵ − 1)(2¹⁶ − 1) +
/// 2¹⁵ < 2³¹`, so it always fits), else `h·2¹⁶⁻ᵏ + ⌊l/2ᵏ⌋` (`h·2¹⁶` a
/// multiple of `2ᵏ`), which fits where the shift and the sum do: the two
/// terms share a sign, so a shift past `i32` is a sum past it too.
#[inline(always)]
pub(crate) fn mul_u32_i16_shr_limbs(a: u32, b: i32, k: u32) -> Option<i32> {
    let (h, l) = ((a >> 16) as i32 * b, (a & 0xFFFF) as i32 * b);
    if k >= 16 {
        return Some((h + (l >> 16)) >> (k - 16));
    }
    let s = 16 - k;
    let hs = h << s;
    if hs >> s != h {
        return None;
    }
    hs.checked_add(l >> k)
}

/// `⌊(a·x + b·y + 8)/16⌋` modulo 2³² (`|x|, |y| ≤ 2¹⁴`): a sum of two
/// products rounded to sixteenths, kept as the low 32 bits. Where a 64-bit
/// product is made from 16-bit ones, in 32-bit arithmetic: with `a` split
/// as `aₕ·2¹⁶ + aₗ` (`aₗ` unsigned) and `b` likewise, the sum is `H·2¹⁶ +
/// L`, with `H = aₕx + bₕy` and `L = aₗx + bₗy` each at most `2·2¹⁵·2¹⁴`
/// and `2·(2¹⁶ − 1)·2¹⁴ = 2³¹ − 2¹⁵` in magnitude (so `L + 8` fits too);
/// as `H·2¹⁶` is a multiple of 16, the quotient is `H·2¹² + ⌊(L +
/// 8)/16⌋`.
#[inline(always)]
pub(crate) fn dot2_round16(a: i32, x: i32, b: i32, y: i32) -> i32 {
    debug_assert!(x.unsigned_abs() <= 1 << 14 && y.unsigned_abs() <= 1 << 14);
    if platform::SOFT_MUL64 {
        dot2_round16_limbs(a, x, b, y)
    } else {
        ((a as i64 * x as i64 + b as i64 * y as i64 + 8) >> 4) as i32
    }
}

/// `⌊(l₁·d₁ + l₂·d₂ + 2²³)/2²⁴⌋` for `|d| < 2¹⁵` (any `i32` `l`): a set-up
/// gradient from two barycentric ones (`src/setup.rs`), always within
/// ±2²³. Where a 64-bit product is made from 16-bit ones, in 32-bit
/// arithmetic: with `l = lₕ·2¹⁶ + lₗ` (`lₗ` unsigned), the sum `S` is
/// `H·2¹⁶ + L₁ + L₂`, `H = Σ dlₕ` (each term below 2³⁰) and `Lᵢ = dᵢlᵢₗ`
/// (each below 2³¹ in magnitude); `M = ⌊(L₁ + L₂ + 2²³)/2¹⁶⌋` from the
/// `Lᵢ`'s halves, and then the value is `⌊(H + M)/2⁸⌋`. `H + M` is `⌊(S +
/// 2²³)/2¹⁶⌋`, below 2³¹ in magnitude (`|S| ≤ 2·(2¹⁵ − 1)·2³¹`), so the
/// wrapping sums are exact.
#[inline(always)]
pub(crate) fn dot2_round_shr24(l1: i32, d1: i32, l2: i32, d2: i32) -> i32 {
    debug_assert!(d1.unsigned_abs() < 1 << 15 && d2.unsigned_abs() < 1 << 15);
    if platform::SOFT_MUL64 {
        dot2_round_shr24_limbs(l1, d1, l2, d2)
    } else {
        ((l1 as i64 * d1 as i64 + l2 as i64 * d2 as i64 + (1 << 23)) >> 24) as i32
    }
}

/// [`dot2_round_shr24`] from 16-bit halves.
#[inline(always)]
pub(crate) fn dot2_round_shr24_limbs(l1: i32, d1: i32, l2: i32, d2: i32) -> i32 {
    let h = (d1 * (l1 >> 16)).wrapping_add(d2 * (l2 >> 16));
    let (m1, m2) = (d1 * (l1 & 0xFFFF), d2 * (l2 & 0xFFFF));
    let m = (m1 >> 16) + (m2 >> 16) + (((m1 & 0xFFFF) + (m2 & 0xFFFF) + (1 << 23)) >> 16);
    h.wrapping_add(m) >> 8
}

/// [`dot2_round16`] from 16-bit halves.
#[inline(always)]
pub(crate) fn dot2_round16_limbs(a: i32, x: i32, b: i32, y: i32) -> i32 {
    let h = (a >> 16) * x + (b >> 16) * y;
    let l = (a & 0xFFFF) * x + (b & 0xFFFF) * y;
    (h << 12).wrapping_add((l + 8) >> 4)
}

/// [`mul_i32_i16`] from 16-bit halves of `a` (`aₗ` unsigned).
#[inline(always)]
pub(crate) fn mul_i32_i16_limbs(a: i32, b: i16) -> i64 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let b = b as i32;
    (((ah * b) as i64) << 16) + (al * b) as i64
}

/// `⌊(b₀² + b₁² + b₂²) / 2¹⁰⌋` for `bᵢ ≤ 2²⁰` (below 2³²), exactly:
/// where a 64-bit product is a library call, from 10-bit halves, `bᵢ² =
/// (bᵢ·hᵢ)·2¹⁰ + bᵢ·lᵢ` with `hᵢ = bᵢ >> 10 ≤ 2¹⁰` and `lᵢ < 2¹⁰`, so each
/// sum of three products stays below 3·2³⁰ (`u32`); else from the 64-bit
/// sum of squares.
#[inline(always)]
pub(crate) fn sum_sq3_shr10(b: [u32; 3]) -> u32 {
    if platform::SOFT_MUL64 {
        sum_sq3_shr10_limbs(b)
    } else {
        let s: u64 = b.iter().map(|&bi| bi as u64 * bi as u64).sum();
        (s >> 10) as u32
    }
}

/// [`sum_sq3_shr10`] from 10-bit halves.
#[inline(always)]
pub(crate) fn sum_sq3_shr10_limbs(b: [u32; 3]) -> u32 {
    let mut hi = 0u32;
    let mut lo = 0u32;
    for &bi in &b {
        hi += bi * (bi >> 10);
        lo += bi * (bi & 0x3FF);
    }
    hi + (lo >> 10)
}

/// `⌊a·y / 2¹²⌋` for `a ≤ 2²⁰` and `y < 2²⁴` (below 2³²), exactly: from
/// `y`'s 12-bit halves (`a·yₕ ≤ 2³²`, `a·yₗ < 2³²`) where a 64-bit product
/// is a library call, else from the 64-bit product.
#[inline(always)]
pub(crate) fn mul_u32_shr12(a: u32, y: u32) -> u32 {
    if platform::SOFT_MUL64 {
        mul_u32_shr12_limbs(a, y)
    } else {
        ((a as u64 * y as u64) >> 12) as u32
    }
}

/// [`mul_u32_shr12`] from `y`'s 12-bit halves.
#[inline(always)]
pub(crate) fn mul_u32_shr12_limbs(a: u32, y: u32) -> u32 {
    a * (y >> 12) + ((a * (y & 0xFFF)) >> 12)
}

/// `⌊(a·b − aₗbₗ) / 2³²⌋` (`aₗ`, `bₗ` the low halves): `⌊a·b / 2³²⌋` or
/// one less, the same value on every core. Where a 64-bit product is a
/// library call (thumbv6m), from three 16 × 16 → 32-bit products; else
/// from the 64-bit one.
///
/// The low × low product is left out: it is below 2³², so it can only carry
/// 1 into the high word. (The exact four-product form is also what LLVM
/// recognises and turns back into a call to `__aeabi_lmul`.)
#[inline(always)]
pub(crate) fn mul_hi32(a: u32, b: u32) -> u32 {
    if platform::SOFT_MUL64 {
        mul_hi32_limbs(a, b)
    } else {
        // The same value: `a·b − aₗbₗ = aₕbₕ·2³² + (aₕbₗ + aₗbₕ)·2¹⁶`, whose
        // floor by 2³² the limbs below sum.
        ((a as u64 * b as u64 - (a & 0xFFFF) as u64 * (b & 0xFFFF) as u64) >> 32) as u32
    }
}

/// [`mul_hi32`] from 16-bit halves.
#[inline(always)]
pub(crate) fn mul_hi32_limbs(a: u32, b: u32) -> u32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // Each factor < 2^16, so each product < 2^32.
    let hh = ah * bh;
    let hl = ah * bl;
    let lh = al * bh;
    // The carry into bit 32 from the middle terms: < 2^17.
    let mid = (hl & 0xFFFF) + (lh & 0xFFFF);
    // The partial sums never exceed the true high word, which is < 2^32.
    hh + (hl >> 16) + (lh >> 16) + (mid >> 16)
}

#[cfg(test)]
mod tests {
    use super::{
        dot2_round16_limbs, dot2_round_shr24_limbs, mul_hi32, mul_hi32_limbs, mul_i32_i16_limbs,
        mul_i32_limbs, mul_i32_u32_limbs, mul_i32_u32_shr31_limbs, mul_u32_i16_limbs,
        mul_u32_i16_shr_limbs, mul_u32_limbs, mul_u32_shr12, mul_u32_shr12_limbs, sum_sq3_shr10,
        sum_sq3_shr10_limbs,
    };
    use crate::tests::xorshift;

    /// Edge operands and xorshift ones of every magnitude.
    fn operands() -> impl Iterator<Item = u64> {
        let edges = [
            0u64,
            1,
            0xFFFF,
            0x1_0000,
            0x7FFF_FFFF,
            0x8000_0000,
            0xFFFF_FFFF,
        ];
        let edges = edges.into_iter().flat_map(|e| [e, e.wrapping_neg()]);
        let mut next = xorshift(0x9E37_79B9_7F4A_7C15);
        // Magnitudes from 1 bit to 64.
        let random = (0..20_000).map(move |i| next() >> (i % 64));
        edges.chain(random)
    }

    /// The squares' sum and the 12-bit product take the same values in
    /// both forms, over their operands' ranges and at their ends.
    /// `mul_i32_u32_shr26`'s halves are the 64-bit product's floor, over
    /// its domain's ends and random values of every magnitude.
    #[test]
    fn shr26_halves_are_the_floor() {
        use super::mul_i32_u32_shr26_limbs;
        let a_max = 3i64 << 28;
        let ends = [
            0i64,
            1,
            -1,
            a_max,
            -a_max,
            a_max - 1,
            -a_max + 1,
            1 << 16,
            -(1 << 16),
        ];
        let mut next = crate::tests::xorshift(0x2626_2626_dead_beef);
        for i in 0..300_000u64 {
            let a = if i < 81 {
                ends[(i % 9) as usize]
            } else {
                (next() as i64 >> (34 + i % 30)).clamp(-a_max, a_max)
            };
            let b = if i < 81 {
                [
                    0u64,
                    1,
                    1 << 30,
                    (1 << 30) - 1,
                    1 << 16,
                    0xFFFF,
                    12345,
                    1 << 29,
                    3 << 28,
                ][(i / 9) as usize]
            } else {
                (next() >> (34 + i % 30)).min(1 << 30)
            };
            let want = ((a * b as i64) >> 26) as i32;
            assert_eq!(mul_i32_u32_shr26_limbs(a as i32, b as u32), want, "{a} {b}");
        }
    }

    /// `saturate_i32` is the clamp to `i32`'s range, at its ends and at
    /// random values of every magnitude.
    #[test]
    fn saturate_i32_is_the_clamp() {
        let ends = [i64::MIN, i64::MAX, 0, -1, 1];
        let near = [i32::MIN as i64, i32::MAX as i64]
            .into_iter()
            .flat_map(|e| [e - 1, e, e + 1]);
        let random = operands().map(|v| v as i64);
        for x in ends.into_iter().chain(near).chain(random) {
            let want = x.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
            assert_eq!(super::saturate_i32(x), want, "{x}");
        }
    }

    #[test]
    fn normalisation_products_agree() {
        let mut next = xorshift(0x2545_F491_4F6C_DD1D);
        let ends = [0u32, 1, 0x3FF, 0x400, (1 << 19) + 1, 1 << 20];
        for i in 0..200_000 {
            let b = [0, 1, 2].map(|k| {
                if i % 7 == 0 {
                    ends[(i / 7 + k) % ends.len()]
                } else {
                    (next() % ((1 << 20) + 1)) as u32
                }
            });
            let s: u64 = b.iter().map(|&x| x as u64 * x as u64).sum();
            // Debug builds check each of the limb forms' sums.
            assert_eq!(sum_sq3_shr10_limbs(b) as u64, s >> 10);
            assert_eq!(sum_sq3_shr10(b) as u64, s >> 10);
            let y = (next() % (1 << 24)) as u32;
            let want = (b[0] as u64 * y as u64) >> 12;
            assert_eq!(mul_u32_shr12_limbs(b[0], y) as u64, want);
            assert_eq!(mul_u32_shr12(b[0], y) as u64, want);
        }
    }

    #[test]
    fn limb_products_are_the_plain_ones() {
        let ops: Vec<u64> = operands().collect();
        for (k, &a) in ops.iter().enumerate() {
            // Each operand against its neighbours and a few far ones.
            for &b in ops
                .iter()
                .skip(k.saturating_sub(3))
                .take(7)
                .chain(&ops[..14])
            {
                let (a32, b32) = (a as i32, b as i32);
                assert_eq!(
                    mul_i32_limbs(a32, b32),
                    a32 as i64 * b32 as i64,
                    "{a32} {b32}"
                );
                assert_eq!(
                    mul_u32_limbs(a as u32, b as u32),
                    (a as u32) as u64 * (b as u32) as u64
                );
                for b16 in [b as i16, i16::MIN, i16::MAX] {
                    assert_eq!(mul_i32_i16_limbs(a32, b16), a32 as i64 * b16 as i64);
                }
                for x in [b as i16 as i32 >> 1, -(1 << 14), 1 << 14, 8, -8] {
                    let y = [a as i16 as i32 >> 1, 1 << 14, -(1 << 14)][k % 3];
                    let want = (a32 as i64 * x as i64 + b as i32 as i64 * y as i64 + 8) >> 4;
                    let got = dot2_round16_limbs(a32, x, b as i32, y);
                    assert_eq!(got, want as i32, "{a32} {x} {b} {y}");
                }
                for d in [b as i16 as i32, -(1 << 15) + 1, (1 << 15) - 1, 0, 1] {
                    let d = d.max(-(1 << 15) + 1);
                    // The second difference its own too, at the ends.
                    let e = [a as i16 as i32, (1 << 15) - 1, -(1 << 15) + 1][k % 3];
                    let e = e.max(-(1 << 15) + 1);
                    for (l1, l2, d2) in [
                        (a32, b as i32, d),
                        (a32, i32::MIN, -d),
                        (i32::MIN, i32::MIN, d),
                        (i32::MAX, b as i32, e),
                        (i32::MIN, a32, e),
                    ] {
                        let want = (l1 as i64 * d as i64 + l2 as i64 * d2 as i64 + (1 << 23)) >> 24;
                        let got = dot2_round_shr24_limbs(l1, d, l2, d2);
                        assert_eq!(got as i64, want, "{l1} {d} {l2} {d2}");
                    }
                }
                for b15 in [b as i16 as i32 / 2, -(1 << 15) + 1, (1 << 15) - 1] {
                    let want = (a as u32) as i64 * b15 as i64;
                    assert_eq!(mul_u32_i16_limbs(a as u32, b15), want, "{a} {b15}");
                    for k in 0..32 {
                        let q = i32::try_from(want >> k).ok();
                        let got = mul_u32_i16_shr_limbs(a as u32, b15, k);
                        assert_eq!(got, q, "{a} {b15} {k}");
                    }
                }
                let h = mul_hi32(a as u32, b as u32);
                let exact = ((a as u32 as u64 * b as u32 as u64) >> 32) as u32;
                assert!(h == exact || h + 1 == exact, "{a} {b}");
                assert_eq!(mul_hi32_limbs(a as u32, b as u32), h, "{a} {b}");
                assert_eq!(
                    mul_i32_u32_limbs(a32, b as u32),
                    a32 as i64 * (b as u32) as i64
                );
                // Within its domain: a > i32::MIN, the quotient within i32.
                for a in [a32.max(-i32::MAX), a32 >> 1, a32 >> 2] {
                    let p = (a as i64 * (b as u32) as i64) >> 31;
                    if i32::try_from(p).is_ok() {
                        assert_eq!(mul_i32_u32_shr31_limbs(a, b as u32) as i64, p, "{a} {b}");
                    }
                }
            }
        }
    }
}

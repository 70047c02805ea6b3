//! Exact integer division, cheap on every core.
//!
//! - [`floor_div`]: `⌊a / b⌋` in `i32` or `i64` (the rare path, exact
//!   fallbacks).
//! - [`recip_fast`]: `2⁶³ / d` within a relative 2⁻²⁷ for a normalised
//!   32-bit `d`, without a division: the one reciprocal of a vertex's `w`
//!   and of a triangle's area.
//! - [`Divisor`]: several exact floors by one 32-bit divisor (an edge's
//!   quotients): the hardware division where the core has one, else the
//!   reciprocal corrected by the remainders.
//! - [`div_rem_u64`]: a 64-bit quotient and remainder (the rare path's,
//!   once a draw's): the core's division on a 64-bit core, else from
//!   32-bit divisions.
//! - [`floor_third`]: `⌊b/3⌋` by a multiply or by shifts (the flat
//!   shader's centroid).
//!
//! A 64-bit division is one instruction on a 64-bit core and a library call
//! on a 32-bit one: about 330 instructions on a Cortex-M0 and 180 on a
//! Cortex-M4 (which divides only 32-bit numbers in hardware), and about a
//! kilobyte of flash, which [`div_rem_u64`] spares; a 32-bit one is a
//! library call on the Cortex-M0. [`recip_fast`] makes a reciprocal
//! from a table and one Newton step, with 32 × 32 → 64-bit products only;
//! [`Divisor`] shares one among several exact floors, corrected by their
//! remainders. The values are the same on every target (unit tests hold
//! the reciprocal to its bound over its whole domain, which CI runs in
//! release, and the floors to the plain division; CI runs the whole suite
//! on the host with `--cfg fixshade_soft_div32`), so frames stay
//! bit-exact.

use core::ops::{Add, Div, Rem, Sub};

use crate::num::widening::{mul_hi32, mul_u32};
use crate::platform;

/// The operations [`floor_div`] needs: `i32` and `i64`.
pub(crate) trait DivInt:
    Copy
    + PartialOrd
    + From<i8>
    + Add<Output = Self>
    + Div<Output = Self>
    + Rem<Output = Self>
    + Sub<Output = Self>
{
    /// Whether [`floor_div`] takes [`floor_div_shifted`]'s form: where a
    /// 64-bit multiply is a library call (the other form's remainder is
    /// one), and for `i64` where a 64-bit division is not the core's.
    const SHIFTED: bool;

    /// The quotient rounded toward zero (`b > 0`).
    fn quot(self, b: Self) -> Self;
}

impl DivInt for i32 {
    const SHIFTED: bool = platform::SOFT_MUL64;

    #[inline(always)]
    fn quot(self, b: i32) -> i32 {
        self / b
    }
}

impl DivInt for i64 {
    const SHIFTED: bool = platform::SOFT_MUL64 || !platform::NATIVE_DIV64;

    /// [`div_rem_u64`] of the magnitude, signed again.
    #[inline(always)]
    fn quot(self, b: i64) -> i64 {
        // Wrapping: `i64::MIN / 1`'s magnitude is 2⁶³.
        let q = div_rem_u64(self.unsigned_abs(), b as u64).0 as i64;
        if self < 0 {
            q.wrapping_neg()
        } else {
            q
        }
    }
}

/// `(⌊n/d⌋, n mod d)` for `d > 0`: the core's division on a 64-bit core;
/// on a 32-bit one, where a 64-bit division is a library routine of
/// about a kilobyte, from 32-bit divisions or shifts and subtractions
/// ([`div_rem_u64_in_32_bits`]).
#[inline(never)]
pub(crate) fn div_rem_u64(n: u64, d: u64) -> (u64, u64) {
    debug_assert!(d > 0);
    if platform::NATIVE_DIV64 || d == 0 {
        return (n.checked_div(d).unwrap_or(0), n.checked_rem(d).unwrap_or(n));
    }
    div_rem_u64_in_32_bits(n, d)
}

/// [`div_rem_u64`] on a 32-bit core (`d > 0`): where the core divides
/// 32-bit numbers, a divisor below 2³² takes the high word's quotient by
/// one 32-bit division and the rest by [`div_rem_digits`]; otherwise a
/// shift and subtraction a bit of the quotient (where the core divides in
/// software, its divisions are only the rare path's and a few a draw,
/// and the library's 32-bit division and the digits' code took a
/// kilobyte of flash).
fn div_rem_u64_in_32_bits(n: u64, d: u64) -> (u64, u64) {
    if platform::hardware_div32() && d >> 32 == 0 {
        let d = d as u32;
        let hi = (n >> 32) as u32;
        let (qh, rh) = (hi / d, hi % d);
        let (ql, r) = div_rem_digits(rh, n as u32, d);
        return (((qh as u64) << 32) | ql as u64, r as u64);
    }
    if n < d {
        return (0, n);
    }
    // d·2ᵏ has n's top bit: the quotient has at most k + 1 bits (a
    // divisor of 2³² or more: at most 32).
    let k = d.leading_zeros() - n.leading_zeros();
    let (mut rem, mut div, mut q) = (n, d << k, 0u64);
    for _ in 0..=k {
        q <<= 1;
        if rem >= div {
            rem -= div;
            q |= 1;
        }
        div >>= 1;
    }
    (q, rem)
}

/// `⌊(u₁·2³² + u₀)/v⌋` and the remainder, for `u₁ < v` (so the quotient
/// fits 32 bits): long division in 16-bit digits by the normalised
/// divisor (`v·2ˢ ≥ 2³¹`), each digit estimated from the divisor's high
/// half and corrected down at most twice (Knuth's algorithm D, as
/// Warren's *Hacker's Delight* lays it out for two digits). Every product
/// below 2³² where it is formed: an estimate is tested against `2¹⁶`
/// before it is multiplied, and a partial remainder is below `v·2ˢ`
/// (wrapping sums elsewhere).
fn div_rem_digits(u1: u32, u0: u32, v: u32) -> (u32, u32) {
    const B: u32 = 1 << 16;
    let s = v.leading_zeros();
    let v = v << s;
    let (vn1, vn0) = (v >> 16, v & 0xFFFF);
    let un32 = if s == 0 {
        u1
    } else {
        (u1 << s) | (u0 >> (32 - s))
    };
    let un10 = u0 << s;
    let (un1, un0) = (un10 >> 16, un10 & 0xFFFF);
    let digit = |top: u32, next: u32| {
        let mut q = top / vn1;
        let mut rhat = top - q * vn1;
        while q >= B || q * vn0 > (rhat << 16) + next {
            q -= 1;
            rhat += vn1;
            if rhat >= B {
                break;
            }
        }
        q
    };
    let q1 = digit(un32, un1);
    let un21 = (un32 << 16)
        .wrapping_add(un1)
        .wrapping_sub(q1.wrapping_mul(v));
    let q0 = digit(un21, un0);
    let r = (un21 << 16)
        .wrapping_add(un0)
        .wrapping_sub(q0.wrapping_mul(v))
        >> s;
    ((q1 << 16) | q0, r)
}

/// ⌊a / b⌋ for `b > 0` and `a − b` within the type, in `i32` or `i64`:
/// [`floor_div_shifted`] where the type says so ([`DivInt::SHIFTED`]: a
/// 64-bit multiply or, for `i64`, a 64-bit division not the core's), else
/// [`floor_div_rem`] (the same value).
#[inline]
pub(crate) fn floor_div<T: DivInt>(a: T, b: T) -> T {
    if T::SHIFTED {
        floor_div_shifted(a, b)
    } else {
        floor_div_rem(a, b)
    }
}

/// [`floor_div`] from the remainder: division truncates, and a negative
/// remainder means the quotient was rounded up.
#[inline]
fn floor_div_rem<T: DivInt>(a: T, b: T) -> T {
    let q = a / b;
    if a % b < T::from(0) {
        q - T::from(1)
    } else {
        q
    }
}

/// [`floor_div`] without the remainder, which LLVM takes as `a − q·b` (a
/// call to `__aeabi_lmul` on a Cortex-M0): a negative `a` is divided as
/// `a − (b − 1)`, whose truncated quotient is the floor.
#[inline]
fn floor_div_shifted<T: DivInt>(a: T, b: T) -> T {
    if a < T::from(0) {
        (a - b + T::from(1)).quot(b)
    } else {
        a.quot(b)
    }
}

/// Exact floors `⌊n/d⌋` of any `i32` numerators by one divisor `d ∈ [1,
/// 2³¹)`: the core's division where it has one, else a shared reciprocal
/// `r ≈ 2⁶³/(d·2ˢ)` ([`recip_fast`], `d·2ˢ ∈ [2³¹, 2³²)`) and a correction.
/// The same values on every core.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Divisor {
    d: u32,
    r: u32,
    s: u32,
}

impl Divisor {
    /// The divisor `d` (`1 ≤ d < 2³¹`).
    #[inline(always)]
    pub(crate) fn new(d: i32) -> Divisor {
        debug_assert!(d > 0);
        if platform::hardware_div32() {
            return Divisor {
                d: d as u32,
                r: 0,
                s: 0,
            };
        }
        let s = platform::leading_zeros(d as u32);
        let r = recip_fast((d as u32) << s);
        Divisor { d: d as u32, r, s }
    }

    /// `⌊n/d⌋`.
    #[inline(always)]
    pub(crate) fn floor(&self, n: i32) -> i32 {
        if platform::hardware_div32() {
            floor_div(n, self.d as i32)
        } else {
            self.floor_by_reciprocal(n)
        }
    }

    /// [`Divisor::floor`] without a division. With `a = |n| ≤ 2³¹`, `q =
    /// ⌊a·r/2⁶³⁻ˢ⌋` (from [`mul_hi32`], which may be one short) is within
    /// `a/d·2⁻²⁷ ≤ 2⁴` of `a/d` (`r` within a relative `2⁻²⁷`: `a/d <
    /// 2³¹`), plus `2ˢ⁻³¹` for the short product and 1 for the floor: below
    /// `⌊a/d⌋ + 18` and above `⌊a/d⌋ − 18`, and within 2 where `d ≥ 2⁵`
    /// (the edges' divisors are larger still, mostly). The remainder `a −
    /// q·d` is exact in wrapping `u32` arithmetic when it lies within
    /// `±2³¹`: `18d < 2³¹` for `d < 2²⁶` (the set-up's `dy < 2¹⁵`), `2d <
    /// 2³²` otherwise (`q` within 2 once `d ≥ 2²⁶`, as `a/d < 2⁶`); it is
    /// stepped into `[0, d)` both ways.
    #[inline(always)]
    fn floor_by_reciprocal(&self, n: i32) -> i32 {
        let a = n.unsigned_abs();
        let mut q = mul_hi32(a, self.r) >> (31 - self.s);
        let mut rem = a.wrapping_sub(q.wrapping_mul(self.d)) as i32;
        while rem < 0 {
            q -= 1;
            rem += self.d as i32;
        }
        while rem as u32 >= self.d {
            q += 1;
            rem -= self.d as i32;
        }
        if n >= 0 {
            q as i32
        } else if rem == 0 {
            (q as i32).wrapping_neg()
        } else {
            (q as i32).wrapping_neg() - 1
        }
    }

    /// `⌈n/d⌉` (`n > i32::MIN`).
    #[inline(always)]
    pub(crate) fn ceil(&self, n: i32) -> i32 {
        -self.floor(-n)
    }
}

/// `⌊n/d⌋` for `d ≥ 2¹⁶` (a quotient of at most 2¹⁶): the core's
/// division where it has one, else [`recip_fast`]'s reciprocal of `d·2ˢ ∈
/// [2³¹, 2³²)` and a correction; the same value on every core.
///
/// `q = ⌊⌊n·r/2³²⌋/2³¹⁻ˢ⌋` ([`mul_hi32`], which may be one short) is
/// within `n/d·2⁻²⁷ ≤ 2⁻¹¹` of `n/d` above (`r` within a relative 2⁻²⁷)
/// and within 2 below, so `q − 1` is at most `⌊n/d⌋`: its product with
/// `d` is at most `n` (no overflow), and the remainder is stepped down
/// into `[0, d)`, a few steps at most.
#[inline(always)]
pub(crate) fn quotient_u32(n: u32, d: u32) -> u32 {
    debug_assert!(d >= 1 << 16);
    if platform::hardware_div32() {
        n / d
    } else {
        quotient_u32_by_reciprocal(n, d)
    }
}

/// [`quotient_u32`] without a division.
#[inline(always)]
fn quotient_u32_by_reciprocal(n: u32, d: u32) -> u32 {
    let s = platform::leading_zeros(d);
    let r = recip_fast(d << s);
    let mut q = (mul_hi32(n, r) >> (31 - s)).saturating_sub(1);
    let mut rem = n - q * d;
    while rem >= d {
        q += 1;
        rem -= d;
    }
    q
}

/// `⌊b/3⌋` without a division: for `u < 2³²`, `⌊u/3⌋ = ⌊u·(2³³ + 1)/3 /
/// 2³³⌋` (`0xAAAA_AAAB = (2³³ + 1)/3`; the excess `u/(3·2³³)` stays below
/// the gap to the next third), or where a 64-bit product is made from
/// 16-bit ones, [`third_by_shifts`]; for `b < 0`, `⌊b/3⌋ = −1 − ⌊(−1 −
/// b)/3⌋`, `−1 − x` being `!x`.
#[inline(always)]
pub(crate) fn floor_third(b: i32) -> i32 {
    let m = b >> 31;
    let u = (b ^ m) as u32;
    let q = if platform::SOFT_MUL64 {
        third_by_shifts(u)
    } else {
        (mul_u32(u, 0xAAAA_AAAB) >> 33) as u32
    };
    (q as i32) ^ m
}

/// `⌊u/3⌋` by shifts and adds: `q ≈ u·(1/4 + 1/16 + …)` (`1/3` in binary,
/// `0.0101…`), below `u/3` by at most 5, then the remainder `u − 3q ≤
/// 15`'s third, `⌊11r/32⌋` (Warren, *Hacker's Delight*, `divu3`).
#[inline(always)]
fn third_by_shifts(u: u32) -> u32 {
    let mut q = (u >> 2) + (u >> 4);
    q += q >> 4;
    q += q >> 8;
    q += q >> 16;
    let r = u - 3 * q;
    q + ((11 * r) >> 5)
}

/// `2⁶³/d` at the nodes `d = 2³¹ + k·2²⁵` (`k = 0..=64`), floored; the
/// first (2³²) capped to `u32::MAX`. 260 bytes, computed by the compiler;
/// a `static`, so that the set-up's assembly reads the same table
/// ([`recip_nodes`]).
static RECIP_NODES: [u32; 65] = {
    let mut t = [0u32; 65];
    let mut k = 0;
    while k < 65 {
        let y = (1u64 << 63) / ((1u64 << 31) + ((k as u64) << 25));
        t[k] = if y > u32::MAX as u64 {
            u32::MAX
        } else {
            y as u32
        };
        k += 1;
    }
    t
};

/// `2⁶³/d` within a relative `2⁻²⁷`, for `d ∈ [2³¹, 2³²)`: the chord
/// between the two [`RECIP_NODES`] around `d` (within `Y·2⁻¹⁴`, `Y =
/// 2⁶³/d`: a relative `(Δd/d)²/4` for `Y` convex, `Δd/d ≤ 2⁻⁶`), then one
/// Newton step, `y ← y + 2·⌊y·e/2³²⌋` with `e = 2³¹ − ⌊d·y/2³²⌋` (the error
/// squared, `2⁻²⁸`, plus a few units for the floors).
/// Exact 32 × 32 → 64-bit products only, so the value is the same on every
/// core. Its callers need no exact reciprocal: [`Divisor`] corrects its
/// quotients, the vertex stage resolves its roundings near a half
/// exactly, and the set-up's planes take a common factor within 2⁻²⁷.
#[inline(always)]
pub(crate) fn recip_fast(d: u32) -> u32 {
    debug_assert!(d >= 1 << 31);
    let y = chord(d);
    let e = (1u32 << 31).wrapping_sub((mul_u32(d, y) >> 32) as u32) as i32;
    // |e| ≤ 2^18, so the step is at most 2^19, and y ≥ 2^31 − 2^19; near d =
    // 2^31, where Y reaches 2^32, the sum is capped.
    let step = 2 * (mul_u32(y, e.unsigned_abs()) >> 32) as u32;
    if e < 0 {
        y - step
    } else {
        y.saturating_add(step)
    }
}

/// [`RECIP_NODES`] for code that reads it by address (the Gouraud set-up's
/// assembly, `platform::gouraud_set_up`, which makes [`recip_fast`]'s
/// value from it with the same steps).
pub(crate) fn recip_nodes() -> *const u32 {
    RECIP_NODES.as_ptr()
}

/// `2⁶³/d` from the chord between the two [`RECIP_NODES`] around `d ∈
/// [2³¹, 2³²)`: within `Y·2⁻¹⁴` (see [`recip_fast`]).
#[inline(always)]
fn chord(d: u32) -> u32 {
    let x = d - (1 << 31);
    let k = (x >> 25) as usize & 63;
    let frac = (x >> 9) & 0xFFFF;
    let (t0, t1) = (RECIP_NODES[k], RECIP_NODES[k + 1]);
    // t0 − t1 < 2^32/65 < 2^26: the product is below 2^32.
    t0 - ((((t0 - t1) >> 10) * frac) >> 6)
}

#[cfg(test)]
mod tests {
    use super::{
        div_rem_u64_in_32_bits, floor_div_rem, floor_div_shifted, floor_third, recip_fast,
        third_by_shifts, Divisor,
    };
    use crate::tests::xorshift;

    /// The 32-bit cores' 64-bit division is the division: divisors of
    /// every size (below 2³² by digits where the core divides 32-bit
    /// numbers, by steps otherwise and above 2³²; `FIXSHADE_LIMBS=1` takes
    /// the steps throughout), normalised or not, numerators at both ends
    /// and around the divisor's multiples.
    #[test]
    fn division_in_32_bits_is_the_division() {
        let mut next = xorshift(0x243f_6a88_85a3_08d3);
        let mut ds: Vec<u64> = vec![1, 2, 3, 6, 0xFFFF, 0x1_0000, 0x8000_0000, 0xFFFF_FFFF];
        ds.extend([1 << 32, (1 << 32) + 1, u64::MAX, 1 << 63, (1 << 46) - 1]);
        ds.extend((0..4000).map(|_| (next() >> (next() % 64)).max(1)));
        let mut count = 0;
        for d in ds {
            let mut ns = vec![0, 1, d - 1, d, d.wrapping_add(1), u64::MAX, u64::MAX - 1];
            ns.extend([d.wrapping_mul(0xFFFF_FFFF), d.wrapping_mul(0x1_0000_0001)]);
            ns.extend((0..40).map(|_| next() >> (next() % 64)));
            let q = next() >> (next() % 64);
            if let Some(m) = q.checked_mul(d) {
                ns.extend([m, m.wrapping_sub(1), m.wrapping_add(1)]);
            }
            for n in ns {
                assert_eq!(div_rem_u64_in_32_bits(n, d), (n / d, n % d), "{n} / {d}");
                count += 1;
            }
        }
        assert!(count > 150_000, "{count}");
    }

    /// A third without a division is the floor division, at `i32`'s ends
    /// and between; the shifts' form (the M0+'s) over every magnitude.
    #[test]
    fn thirds_are_the_division() {
        let mut next = xorshift(0x1319_8a2e_0370_7344);
        let ends = [
            0,
            1,
            2,
            3,
            -1,
            -2,
            -3,
            -4,
            i32::MAX,
            i32::MIN,
            i32::MAX - 1,
            i32::MIN + 1,
        ];
        for b in ends
            .into_iter()
            .chain((0..200_000).map(|_| next() as i32 >> (next() % 32)))
        {
            assert_eq!(floor_third(b) as i64, (b as i64).div_euclid(3), "{b}");
            let u = b as u32;
            assert_eq!(third_by_shifts(u), u / 3, "{u}");
        }
    }

    /// The floor division of the Cortex-M0 (no remainder) is the one that
    /// takes the remainder, in `i64` and `i32`: numerators of both signs and
    /// every magnitude, exact multiples and their neighbours, divisors from
    /// 1 up.
    #[test]
    fn shifted_floor_division_is_the_remainder_one() {
        let mut next = xorshift(0x5851_f42d_4c95_7f2d);
        for _ in 0..100_000 {
            let b = (next() >> (1 + next() % 62)).max(1) as i64;
            let q = (next() >> (1 + next() % 63)) as i64 / b;
            let sign = if next() & 1 == 0 { 1 } else { -1 };
            for a in [sign * q * b - 1, sign * q * b, sign * q * b + 1] {
                if a.checked_sub(b).is_none() {
                    continue;
                }
                assert_eq!(floor_div_shifted(a, b), floor_div_rem(a, b), "{a} / {b}");
                assert_eq!(floor_div_rem(a, b), a.div_euclid(b), "{a} / {b}");
                let (a32, b32) = (a as i32, (b as i32).max(1));
                if a32.checked_sub(b32).is_some() {
                    assert_eq!(floor_div_shifted(a32, b32), floor_div_rem(a32, b32));
                }
            }
        }
    }

    /// The reciprocal form of [`Divisor`] is the division: numerators at
    /// both ends of `i32` and around multiples, divisors of every size.
    #[test]
    fn divisor_floors_are_the_division() {
        let mut next = xorshift(0x0bad_5eed_1234_5678);
        let mut ds: Vec<i32> = vec![1, 2, 3, 15, 16, 17, i32::MAX, i32::MAX - 1, 1 << 30];
        ds.extend((0..3000).map(|_| ((next() >> (33 + next() % 31)) as i32).max(1)));
        for d in ds {
            let s = d.leading_zeros();
            let v = Divisor {
                d: d as u32,
                r: recip_fast((d as u32) << s),
                s,
            };
            let mut ns = vec![
                0,
                1,
                -1,
                i32::MAX,
                i32::MIN,
                i32::MIN + 1,
                d,
                -d,
                d - 1,
                1 - d,
            ];
            ns.extend((0..60).map(|_| (next() >> (next() % 33)) as i32));
            for n in ns {
                let want = (n as i64).div_euclid(d as i64);
                assert_eq!(v.floor_by_reciprocal(n) as i64, want, "{n} / {d}");
                assert_eq!(v.floor(n) as i64, want, "{n} / {d}");
                if n != i32::MIN {
                    assert_eq!(v.ceil(n) as i64, -((-(n as i64)).div_euclid(d as i64)));
                }
            }
        }
    }

    /// The reciprocal form of [`quotient_u32`] is the division: divisors
    /// from 2¹⁶ up (powers of two and their neighbours, random ones),
    /// numerators at both ends and around the divisor's multiples.
    #[test]
    fn quotient_u32_is_the_division() {
        let mut next = xorshift(0x6a09_e667_f3bc_c909);
        let mut divisors: Vec<u32> = vec![1 << 16, (1 << 16) + 1, u32::MAX, 1 << 31, (1 << 31) - 1];
        for k in 16..32 {
            divisors.extend([(1u32 << k) - 1, 1 << k, (1 << k) + 1]);
        }
        for _ in 0..20_000 {
            divisors.push(((next() >> 32) as u32).max(1 << 16));
        }
        for &d in &divisors {
            let mut numerators = vec![0, 1, u32::MAX, u32::MAX - 1, d - 1, d];
            for _ in 0..20 {
                let m = (next() >> 48) as u32 % (u32::MAX / d + 1);
                let n = m.wrapping_mul(d);
                numerators.extend([
                    n,
                    n.wrapping_sub(1),
                    n.wrapping_add(1),
                    (next() >> 32) as u32,
                ]);
            }
            for n in numerators {
                assert_eq!(super::quotient_u32_by_reciprocal(n, d), n / d, "{n} / {d}");
            }
        }
    }

    /// The fast reciprocal is within its relative bound, `2⁻²⁷`, at the
    /// ends, at every power of two's neighbours, at the nodes and at random
    /// divisors (all of them: `recip_fast_exhaustive`).
    #[test]
    fn fast_reciprocal_is_within_its_bound() {
        let mut ds: Vec<u32> = vec![1 << 31, (1 << 31) + 1, u32::MAX, u32::MAX - 1];
        for k in 0..65u64 {
            let node = ((1u64 << 31) + (k << 25)).min(u32::MAX as u64) as u32;
            ds.extend([node.saturating_sub(1), node, node.saturating_add(1)]);
        }
        let mut next = xorshift(0x51de_5eed_dead_beef);
        ds.extend((0..500_000).map(|_| (next() as u32) | 1 << 31));
        for d in ds.into_iter().filter(|&d| d >= 1 << 31) {
            check_fast(d);
        }
    }

    fn check_fast(d: u32) {
        let exact = (1u128 << 63) as f64 / d as f64;
        let got = recip_fast(d) as f64;
        assert!(
            (got - exact).abs() <= exact / (1u64 << 27) as f64,
            "{d}: {got} {exact}"
        );
    }

    /// [`recip_fast`] over every divisor: run with
    /// `cargo test --release --lib -- --ignored recip_fast_exhaustive`.
    #[test]
    #[ignore = "2^31 divisors (CI runs it)"]
    fn recip_fast_exhaustive() {
        for d in (1u32 << 31)..=u32::MAX {
            check_fast(d);
        }
    }
}

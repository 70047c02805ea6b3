//! `Wide`: a value `m·2^e` with a 61-bit mantissa, for what is computed
//! once a draw or on the rare path, where magnitudes span more than any
//! fixed-point format: the composition of the vertex stage's rows, and the
//! clipping planes' distances.

/// A value `m·2^e` (`|m| < 2⁶²`): the per-draw composition of the vertex
/// stage's rows, and the rare path's plane distances, in `i64` alone. Its
/// operations are out of line: none runs per vertex or per triangle on the
/// lean path, and inlined they cost kilobytes of flash.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Wide {
    pub(crate) m: i64,
    pub(crate) e: i32,
}

impl Wide {
    pub(crate) const ZERO: Wide = Wide { m: 0, e: 0 };

    pub(crate) fn new(m: i64, e: i32) -> Wide {
        Wide { m, e }.norm()
    }

    /// The same value with `|m|` in `[2⁶⁰, 2⁶¹)` (a right shift floors).
    #[inline(never)]
    pub(crate) fn norm(&self) -> Wide {
        if self.m == 0 {
            return Wide::ZERO;
        }
        let s = self.m.unsigned_abs().leading_zeros() as i32 - 3;
        if s >= 0 {
            Wide {
                m: self.m << s,
                e: self.e - s,
            }
        } else {
            Wide {
                m: self.m >> -s,
                e: self.e - s,
            }
        }
    }

    /// `self·b` for `|b| < 2³¹`, within 2⁻⁶⁰ of the product: from 31-bit
    /// halves of the mantissa (`|aₕ·b| < 2⁶⁰`, `0 ≤ aₗ·b < 2⁶²`), the high
    /// product moved up as far as it fits and the low one down to meet it.
    #[inline(never)]
    pub(crate) fn mul(&self, b: i64) -> Wide {
        debug_assert!(b.unsigned_abs() < 1 << 31);
        let a = self.norm();
        let (ah, al) = (a.m >> 31, a.m & ((1 << 31) - 1));
        let (hi, lo) = (ah * b, al * b);
        let k = (hi.unsigned_abs().leading_zeros() as i32 - 3).clamp(0, 31);
        Wide::new((hi << k) + (lo >> (31 - k)), a.e + 31 - k)
    }

    /// `self·o`, from 31-bit halves of both mantissas (`aₕbₕ < 2⁶⁰`, the
    /// middle terms below 2⁶¹ each), the low × low product left out:
    /// within 2⁻⁵⁸ of the product.
    #[inline(never)]
    pub(crate) fn times(&self, o: &Wide) -> Wide {
        let (a, b) = (self.norm(), o.norm());
        let (ah, al) = (a.m >> 31, a.m & ((1 << 31) - 1));
        let (bh, bl) = (b.m >> 31, b.m & ((1 << 31) - 1));
        let mid = ((ah * bl) >> 31) + ((al * bh) >> 31);
        Wide::new(ah * bh + mid, a.e + b.e + 62)
    }

    #[inline(never)]
    pub(crate) fn add(&self, o: &Wide) -> Wide {
        let (a, b) = (self.norm(), o.norm());
        if a.m == 0 {
            return b;
        }
        if b.m == 0 {
            return a;
        }
        let e = a.e.max(b.e);
        let at = |w: Wide| w.m >> (e - w.e).min(63);
        Wide::new(at(a) + at(b), e)
    }

    pub(crate) fn neg(self) -> Wide {
        Wide {
            m: -self.m,
            e: self.e,
        }
    }

    /// `|value| < 2^bits()` (a very negative number for zero).
    #[inline(never)]
    pub(crate) fn bits(&self) -> i32 {
        if self.m == 0 {
            return -(1 << 20);
        }
        64 - self.m.unsigned_abs().leading_zeros() as i32 + self.e
    }

    /// The value in units of `2^e`, rounded half up (the caller picks `e`
    /// so that it fits).
    #[inline(never)]
    pub(crate) fn at(&self, e: i32) -> i64 {
        let s = self.e - e;
        if s >= 0 {
            self.m << s.min(62)
        } else if s <= -62 {
            0
        } else {
            (self.m + (1 << (-s - 1))) >> -s
        }
    }
}

//! STUB (replaced by the spectable branch).
#![allow(missing_docs)]
extern crate std;
use crate::vector::FormatError;
use std::prelude::rust_2021::*;
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Exponent(u32);
impl Exponent {
    pub const ZERO: Exponent = Exponent(0);
    pub const MAX: Exponent = Exponent(4096 << 8);
    pub const fn from_int(n: u16) -> Exponent {
        Exponent::from_bits((n as u32) << 8)
    }
    pub const fn from_bits(raw: u32) -> Exponent {
        if raw > 4096 << 8 {
            Exponent(4096 << 8)
        } else {
            Exponent(raw)
        }
    }
    pub fn from_f32(n: f32) -> Result<Exponent, FormatError> {
        if !n.is_finite() {
            return Err(FormatError::NotFinite);
        }
        if !(0.0..=4096.0).contains(&n) {
            return Err(FormatError::OutOfRange);
        }
        Ok(Exponent((n * 256.0 + 0.5) as u32))
    }
    pub const fn to_bits(self) -> u32 {
        self.0
    }
    pub const fn is_zero(self) -> bool {
        self.0 == 0
    }
}
pub fn pow_from_delta(delta_q28: u32, n: Exponent) -> u16 {
    if n.0 == 0 {
        return 32768;
    }
    let x = 1.0 - delta_q28 as f64 / (1u64 << 28) as f64;
    if x <= 0.0 {
        return 0;
    }
    (x.powf(n.0 as f64 / 256.0) * 32768.0).round() as u16
}
pub fn pow_from_cos(x_q28: i32, n: Exponent) -> u16 {
    pow_from_delta(((1i64 << 28) - x_q28 as i64).clamp(0, 1 << 29) as u32, n)
}

//! STUB (replaced by the normalize branch).
#![allow(missing_docs)]
extern crate std;
use crate::vector::Unit3;
use std::prelude::rust_2021::*;
pub fn normalize(v: [i32; 3]) -> Option<Unit3> {
    normalize_len([v[0] as i64, v[1] as i64, v[2] as i64]).map(|x| x.0)
}
pub fn normalize_len(v: [i64; 3]) -> Option<(Unit3, u64)> {
    let f = v.map(|c| c as f64);
    let l = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
    if l == 0.0 {
        return None;
    }
    let q = f.map(|c| (c / l * 16384.0).round() as i16);
    Some((Unit3::new_clamped(q[0], q[1], q[2]), l.round() as u64))
}

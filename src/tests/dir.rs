//! The per-pixel lighting's directions (`crate::normalize::Dir`) and the
//! specular base made from their cosines, against f64.

use crate::light_term::specular_delta_of;
use crate::material::{BlinnPhong, Phong};
use crate::normalize::{one_minus_q28, Dir};
use crate::tests::xorshift;

/// A random vector of `bits`-bit signed components.
fn vector(next: &mut impl FnMut() -> u64, bits: u32) -> [i32; 3] {
    [0; 3].map(|_| ((next() >> (64 - bits)) as i64 - (1i64 << (bits - 1))) as i32)
}

fn dir(v: [i32; 3]) -> Option<(Dir, i32)> {
    Dir::reduce(v).map(|(d, s)| (Dir::new(d), s))
}

fn f(d: &Dir) -> [f64; 3] {
    d.d().map(f64::from)
}

fn cos_f64(a: [f64; 3], b: [f64; 3]) -> f64 {
    let dot: f64 = (0..3).map(|k| a[k] * b[k]).sum();
    let len = |v: [f64; 3]| v.iter().map(|c| c * c).sum::<f64>().sqrt();
    dot / (len(a) * len(b))
}

/// Every scale and the ends of `i32`: the reduced components within half
/// a unit of `v/2^s`, the largest in `[2¹³, 2¹⁴]`, the length within its
/// bound; zero has none.
#[test]
fn reduced_directions_hold_their_ranges() {
    let mut next = xorshift(0x9E37_79B9_7F4A_7C15);
    let ends = [i32::MIN, i32::MIN + 1, -1, 0, 1, i32::MAX];
    let mut cases: Vec<[i32; 3]> = Vec::new();
    for &x in &ends {
        for &y in &ends {
            for &z in &ends {
                cases.push([x, y, z]);
            }
        }
    }
    for _ in 0..100_000 {
        let bits = 1 + (next() % 32) as u32;
        cases.push(vector(&mut next, bits));
    }
    // A negative power of two as the largest magnitude, which the top bit
    // of `c ^ (c >> 31)` puts one lower, beside smaller components.
    for k in 0..31 {
        let p = -(1i32 << k);
        cases.extend([[p, 0, 0], [0, p, -1], [p, !p, p >> 1], [p / 2, p, 0]]);
    }
    for v in cases {
        let Some((d, s)) = dir(v) else {
            assert_eq!(v, [0; 3]);
            continue;
        };
        let c = d.d();
        let top = c.iter().map(|c| c.unsigned_abs()).max().unwrap();
        assert!((1 << 13..=1 << 14).contains(&top), "{v:?}: {c:?}");
        for k in 0..3 {
            let exact = v[k] as f64 / 2f64.powi(s);
            assert!((c[k] as f64 - exact).abs() <= 0.5, "{v:?}: {c:?} s {s}");
        }
        let rel = |got: f64, want: f64| (got / want - 1.0).abs();
        // u from rsqrt_q (2^-23) and the halving of its Q2.30 form.
        assert!(
            rel(d.cos(&d) as f64, 2f64.powi(30)) < 2f64.powi(-21),
            "{v:?}"
        );
        let vl = v.iter().map(|&c| (c as f64).powi(2)).sum::<f64>().sqrt();
        // The length: the components' rounding (2⁻¹³ of the largest), and
        // its floor in v's units.
        let len_err = (d.length(s) as f64 - vl).abs();
        assert!(
            len_err < vl * 2f64.powi(-12) + 1.0,
            "{v:?}: {}",
            d.length(s)
        );
    }
    // Wide vectors: the same through the 30-bit step.
    for _ in 0..20_000 {
        let sh = (next() % 32) as u32;
        let v = vector(&mut next, 32).map(|c| (c as i64) << sh);
        let (d, s) = Dir::reduce_wide(v).unwrap_or_else(|| panic!("{v:?}"));
        let d = Dir::new(d);
        let vl = v.iter().map(|&c| (c as f64).powi(2)).sum::<f64>().sqrt();
        assert!(
            (d.length(s) as f64 / vl - 1.0).abs() < 2f64.powi(-12),
            "{v:?}"
        );
    }
    assert_eq!(Dir::reduce_wide([0; 3]), None);
    // The ends of i64: a length of √2·2⁶³, within the bound.
    let (d, sh) = Dir::reduce_wide([i64::MIN, i64::MAX, 0]).expect("not zero");
    let len = Dir::new(d).length(sh) as f64;
    assert!(
        (len / (2f64.sqrt() * 2f64.powi(63)) - 1.0).abs() < 2f64.powi(-12),
        "{len}"
    );
}

/// The cosine of two directions within 2⁻²¹ of the reduced vectors'
/// (the reciprocal lengths' error; the reduction's turn of the directions,
/// up to 2⁻¹³, is the reduced vectors'), and of parallel vectors within
/// 2⁻²¹ of 1: no length's rounding reaches `1 − cos` at 0. The diffuse
/// form within two units of 2⁻¹⁵.
#[test]
fn cosines_within_their_bounds() {
    let mut next = xorshift(0xD1B5_4A32_D192_ED03);
    let mut worst = 0f64;
    for i in 0..200_000 {
        let (ba, bb) = (1 + (next() % 31) as u32, 1 + (next() % 31) as u32);
        let a = vector(&mut next, ba);
        let b = if i % 8 == 0 {
            // Parallel, at another scale: rounded differently.
            a.map(|c| c.saturating_mul(3))
        } else {
            vector(&mut next, bb)
        };
        let (Some((da, _)), Some((db, _))) = (dir(a), dir(b)) else {
            continue;
        };
        let want = cos_f64(f(&da), f(&db));
        let got = da.cos(&db) as f64 / 2f64.powi(30);
        let err = (got - want).abs();
        assert!(err < 2f64.powi(-21), "{a:?} {b:?}: {got} against {want}");
        worst = worst.max(err);
        if i % 8 == 0 && a.iter().all(|c| c.unsigned_abs() < 1 << 29) {
            assert!(1.0 - got < 2f64.powi(-21), "parallel {a:?}: {got}");
        }
        let dot = Dir::dot_d(da.d(), &db);
        if dot > 0 {
            let c15 = da.cos15(dot, &db) as f64;
            let want = (want * 2f64.powi(15)).min(2f64.powi(15));
            assert!(
                (c15 - want).abs() <= 1.0,
                "{a:?} {b:?}: {c15} against {want}"
            );
        }
    }
    println!("Dir::cos: worst error 2^{:.2}", worst.log2());
}

/// A unit vector's direction without a root within a relative 2⁻²⁶ of
/// the exact reciprocal length, for every vector `normalize` makes.
#[test]
fn unit_vectors_without_a_root() {
    let mut next = xorshift(0x4F1B_BCDC_BFA5_3E0B);
    for _ in 0..100_000 {
        let bits = 2 + (next() % 30) as u32;
        let Some(u) = crate::normalize::normalize(vector(&mut next, bits)) else {
            continue;
        };
        let d = Dir::of_unit(u);
        let len: f64 = f(&d).iter().map(|c| c * c).sum::<f64>().sqrt();
        let got = d.cos(&Dir::Z) as f64;
        let z = d.d()[2] as f64 / len * 2f64.powi(30);
        assert!(
            (got - z).abs() <= 2f64.powi(30 - 26) + 1.0,
            "{u:?}: {got} against {z}"
        );
        assert!(
            (d.cos(&d) as f64 / 2f64.powi(30) - 1.0).abs() < 2f64.powi(-26),
            "{u:?}"
        );
    }
}

/// `1 − x` in `Q.28` at its ends and beyond.
#[test]
fn one_minus_at_the_ends() {
    assert_eq!(one_minus_q28(1 << 30), 0);
    assert_eq!(one_minus_q28((1 << 30) - 1), 0);
    assert_eq!(one_minus_q28(i32::MAX), 0);
    assert_eq!(one_minus_q28(0), 1 << 28);
    assert_eq!(one_minus_q28(-(1 << 30)), 1 << 29);
    assert_eq!(one_minus_q28(i32::MIN), 1 << 29);
}

/// Blinn's `1 − N·H` and Phong's `1 − R·V` from the three cosines within
/// 2⁻²⁰ of f64's from the same directions (as `Q.28` units: 256) where
/// `|L + V| ≥ 1/2` (nearer `L = −V` the half vector is ill-conditioned in
/// any arithmetic), also where `N` lies along `H` (`L` and `V` mirrored
/// about `N`: `1 − N·H` near 0, where steep powers read it); `None` where
/// `L = −V`.
#[test]
fn specular_bases_from_cosines() {
    let mut next = xorshift(0x2545_F491_4F6C_DD1D);
    for i in 0..100_000 {
        let mut v3 = |bits| vector(&mut next, bits);
        let (n, l) = (v3(20), v3(20));
        // Every fourth V mirrors L about N: H along N.
        let v = if i % 4 == 0 {
            let nf = n.map(f64::from);
            let k = 2.0 * (0..3).map(|j| nf[j] * l[j] as f64).sum::<f64>()
                / nf.iter().map(|c| c * c).sum::<f64>();
            [0, 1, 2].map(|j| (k * nf[j] - l[j] as f64).round() as i32)
        } else {
            v3(20)
        };
        let (Some((dn, _)), Some((dl, _)), Some((dv, _))) = (dir(n), dir(l), dir(v)) else {
            continue;
        };
        let (nl, nv, lv) = (dn.cos(&dl), dn.cos(&dv), dl.cos(&dv));
        let (fn_, fl, fv) = (f(&dn), f(&dl), f(&dv));
        let unit = |x: [f64; 3]| {
            let len = x.iter().map(|c| c * c).sum::<f64>().sqrt();
            x.map(|c| c / len)
        };
        let (un, ul, uv) = (unit(fn_), unit(fl), unit(fv));
        let h = [0, 1, 2].map(|j| ul[j] + uv[j]);
        let blinn = 1.0 - cos_f64(un, h);
        let cnl = cos_f64(un, ul);
        let rv: f64 = (0..3).map(|j| (2.0 * cnl * un[j] - ul[j]) * uv[j]).sum();
        let phong = 1.0 - rv.clamp(-1.0, 1.0);
        let q28 = 2f64.powi(28);
        let got = specular_delta_of::<BlinnPhong>(nl, nv, lv);
        if h.iter().map(|c| c * c).sum::<f64>() >= 0.25 {
            let got = got.expect("L + V is not zero") as f64;
            let want = blinn * q28;
            assert!(
                (got - want).abs() <= 256.0,
                "n {n:?} l {l:?} v {v:?}: {got} against {want}"
            );
        } else if let Some(d) = got {
            assert!(d <= 1 << 29);
        }
        let got = specular_delta_of::<Phong>(nl, nv, lv).expect("Phong's is defined") as f64;
        assert!(
            (got - phong * q28).abs() <= 256.0,
            "n {n:?} l {l:?} v {v:?}: {got} against {}",
            phong * q28
        );
    }
    let (l, _) = dir([3, -4, 12]).expect("not zero");
    let (v, _) = dir([-3, 4, -12]).expect("not zero");
    assert_eq!(specular_delta_of::<BlinnPhong>(0, 0, l.cos(&v)), None);
}

//! Accuracy and robustness of `crate::normalize` against an f64 (and, for
//! lengths, an exact 128-bit integer) reference.

use crate::normalize::{normalize, normalize_len, one_minus_cos, rsqrt_q, rsqrt_seed};
use crate::Unit3;
use proptest::prelude::*;

const ONE: f64 = (1u32 << 14) as f64;

/// Error statistics over many vectors.
#[derive(Default, Debug)]
struct Stats {
    components: u64,
    exact: u64,
    max_ulp: f64,
    max_len_rel: f64,
}

impl Stats {
    fn exact_pct(&self) -> f64 {
        100.0 * self.exact as f64 / self.components as f64
    }
}

/// Checks one unit vector against the exact direction of `v` (given as f64,
/// which is exact for i32 and within 2^-53 for i64): every component within
/// 1 ULP, the invariant, and the sign of each component.
fn check_unit(u: Unit3, v: [f64; 3], st: &mut Stats, what: &dyn Fn() -> String) {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    for (k, &c) in u.to_bits().iter().enumerate() {
        assert!(
            (-(1 << 14)..=(1 << 14)).contains(&c),
            "invariant: {}",
            what()
        );
        let exact = v[k] / len * ONE;
        let err = (c as f64 - exact).abs();
        assert!(err < 1.0, "component {k} = {c}, exact {exact}: {}", what());
        if v[k] != 0.0 {
            assert!(c == 0 || (c < 0) == (v[k] < 0.0), "sign: {}", what());
        } else {
            assert_eq!(c, 0, "zero component: {}", what());
        }
        st.components += 1;
        if c as f64 == exact.round() {
            st.exact += 1;
        }
        if err > st.max_ulp {
            st.max_ulp = err;
        }
    }
}

fn check_i32(v: [i32; 3], st: &mut Stats) {
    let what = || format!("normalize({v:?})");
    if v == [0; 3] {
        assert_eq!(normalize(v), None);
        return;
    }
    let u = normalize(v).unwrap_or_else(|| panic!("None for {v:?}"));
    check_unit(u, v.map(|x| x as f64), st, &what);
    // The i64 path gives the same direction for the same vector.
    let (u2, _) = normalize_len(v.map(|x| x as i64)).unwrap();
    assert_eq!(u, u2, "{}", what());
}

/// Exact `round(√s)` for a u128.
fn round_sqrt_u128(s: u128) -> u128 {
    let mut n = (s as f64).sqrt() as u128;
    while n * n > s {
        n -= 1;
    }
    while (n + 1) * (n + 1) <= s {
        n += 1;
    }
    // round up iff s > n² + n (then s ≥ (n + 1/2)² + 3/4).
    if s - n * n > n {
        n + 1
    } else {
        n
    }
}

fn check_i64(v: [i64; 3], st: &mut Stats) {
    let what = || format!("normalize_len({v:?})");
    if v == [0; 3] {
        assert_eq!(normalize_len(v), None);
        return;
    }
    let (u, len) = normalize_len(v).unwrap_or_else(|| panic!("None for {v:?}"));
    check_unit(u, v.map(|x| x as f64), st, &what);
    let a = v.map(|x| x.unsigned_abs() as u128);
    let exact = round_sqrt_u128(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    assert!(exact <= u64::MAX as u128);
    let diff = (len as i128 - exact as i128).unsigned_abs();
    let rel = diff as f64 / exact as f64;
    if a.iter().all(|&x| x < 1 << 31) {
        assert_eq!(len as u128, exact, "length not exactly rounded: {}", what());
    } else {
        // The requirement (±1 or 2^-24 relative), and the documented 2^-29.
        assert!(diff <= 1 || rel <= 2f64.powi(-24), "{}", what());
        assert!(rel <= 2f64.powi(-29), "rel {rel:e}: {}", what());
    }
    if rel > st.max_len_rel {
        st.max_len_rel = rel;
    }
}

/// xorshift64*: a small deterministic generator for the sweeps.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// A value with a random magnitude of at most `bits` bits and a random sign.
    fn signed(&mut self, bits: u32) -> i64 {
        let r = self.next();
        let mag = if bits >= 64 {
            r >> 1
        } else {
            (r >> 1) & ((1u64 << bits) - 1)
        };
        if r & 1 == 0 {
            mag as i64
        } else {
            -(mag as i64)
        }
    }
}

/// Random i32 vectors whose components share a bit width (1..=32), so all
/// scales are covered, plus vectors with one component much smaller.
fn sweep_i32(st: &mut Stats, n: usize, seed: u64) {
    let mut rng = Rng(seed);
    for i in 0..n {
        let bits = 1 + (i as u32 % 32);
        let mut v = [0i32; 3];
        for (k, c) in v.iter_mut().enumerate() {
            let b = if i % 7 == k {
                1 + (rng.next() % bits as u64) as u32
            } else {
                bits
            };
            *c = rng.signed(b.min(31)) as i32;
        }
        check_i32(v, st);
    }
}

fn sweep_i64(st: &mut Stats, n: usize, seed: u64) {
    let mut rng = Rng(seed);
    for i in 0..n {
        let bits = 1 + (i as u32 % 64);
        let mut v = [0i64; 3];
        for (k, c) in v.iter_mut().enumerate() {
            let b = if i % 7 == k {
                1 + (rng.next() % bits as u64) as u32
            } else {
                bits
            };
            *c = rng.signed(b);
        }
        check_i64(v, st);
    }
}

#[test]
fn small_vectors_exhaustive() {
    let mut st = Stats::default();
    for x in -20..=20 {
        for y in -20..=20 {
            for z in -20..=20 {
                check_i32([x, y, z], &mut st);
                check_i64([x as i64, y as i64, z as i64], &mut st);
            }
        }
    }
    assert!(st.max_ulp <= 0.52, "{st:?}");
}

#[test]
fn phong_range_sweep() {
    // Interpolated normals: lengths from 2^14 to 2^20, directions on a grid
    // of the sphere (latitude × longitude), every scale in between.
    let mut st = Stats::default();
    for e in 14..=20 {
        for scale in [1.0, 1.3, 1.7] {
            let r = (1u64 << e) as f64 * scale;
            for i in 0..=90 {
                let th = i as f64 * core::f64::consts::PI / 90.0;
                for j in 0..180 {
                    let ph = j as f64 * core::f64::consts::PI / 90.0;
                    let v = [
                        (r * th.sin() * ph.cos()).round() as i32,
                        (r * th.sin() * ph.sin()).round() as i32,
                        (r * th.cos()).round() as i32,
                    ];
                    check_i32(v, &mut st);
                }
            }
        }
    }
    println!(
        "phong range: {} components, max error {:.4} ULP, {:.3}% exactly rounded",
        st.components,
        st.max_ulp,
        st.exact_pct()
    );
    assert!(st.max_ulp <= 0.52, "{st:?}");
    assert!(st.exact_pct() > 99.0, "{st:?}");
}

#[test]
fn all_scales_i32() {
    let mut st = Stats::default();
    sweep_i32(&mut st, 300_000, 0x1234_5678_9ABC_DEF1);
    assert!(st.max_ulp <= 0.55, "{st:?}");
    assert!(st.exact_pct() > 99.0, "{st:?}");
}

#[test]
fn all_scales_i64() {
    let mut st = Stats::default();
    sweep_i64(&mut st, 300_000, 0x0F1E_2D3C_4B5A_6978);
    assert!(st.max_ulp <= 0.55, "{st:?}");
    assert!(st.exact_pct() > 99.0, "{st:?}");
}

#[test]
fn light_vectors_i64() {
    // light − P in I8F24 / I40F24 raw units: lengths 2^14 .. 2^50.
    let mut st = Stats::default();
    let mut rng = Rng(77);
    for i in 0..100_000 {
        let bits = 14 + (i % 37) as u32;
        let v = [rng.signed(bits), rng.signed(bits), rng.signed(bits)];
        check_i64(v, &mut st);
    }
    assert!(st.max_ulp <= 0.55, "{st:?}");
}

#[test]
fn lengths_exact_below_2_31() {
    // Perfect squares, their neighbours and the rounding boundaries.
    let mut st = Stats::default();
    for n in [1i64, 2, 3, 7, 1000, 46340, 46341, 1 << 20, (1 << 31) - 1] {
        for d in -2..=2 {
            check_i64([n + d, 0, 0], &mut st);
            check_i64([n, n + d, 0], &mut st);
            check_i64([n, n, n + d], &mut st);
        }
    }
    // Pythagorean quadruples: exact integer lengths.
    for (x, y, z, l) in [
        (1, 2, 2, 3),
        (2, 3, 6, 7),
        (1, 4, 8, 9),
        (4, 4, 7, 9),
        (2, 6, 9, 11),
    ] {
        for sh in [0, 10, 20, 27, 40, 59] {
            let v = [x << sh, -(y << sh), z << sh];
            assert_eq!(normalize_len(v).unwrap().1, (l as u64) << sh, "{v:?}");
        }
    }
    assert_eq!(st.max_len_rel.max(0.0), st.max_len_rel);
}

#[test]
fn edge_cases() {
    let mut st = Stats::default();
    let m = i32::MIN;
    let mx = i32::MAX;
    for v in [
        [m, m, m],
        [mx, mx, mx],
        [m, mx, 0],
        [m, 0, 0],
        [mx, 0, 0],
        [m, 1, -1],
        [mx, 1, -1],
        [m, m, mx],
        [1, 0, 0],
        [-1, 0, 0],
        [0, 1, 0],
        [0, 0, -1],
        [1, 1, 1],
        [-1, -1, -1],
        [1, 1, 0],
        [1, -1, 0],
        [1 << 19, 1, 0],
        [(1 << 20) - 1, 1, 1],
        [1 << 20, 1, 1],
        [(1 << 20) + 1, -1, 1],
    ] {
        check_i32(v, &mut st);
    }
    let m = i64::MIN;
    let mx = i64::MAX;
    for v in [
        [m, m, m],
        [mx, mx, mx],
        [m, mx, 0],
        [m, 0, 0],
        [mx, 0, 0],
        [m, 1, -1],
        [0, 0, m],
        [1, 0, 0],
        [-1, 0, 0],
        [1, 1, 1],
        [1 << 62, 1 << 62, 1 << 62],
        [(1 << 31) - 1, (1 << 31) - 1, (1 << 31) - 1],
        [1 << 31, 0, 0],
    ] {
        check_i64(v, &mut st);
    }

    assert_eq!(normalize([1, 0, 0]), Some(Unit3::X));
    assert_eq!(normalize([-1, 0, 0]), Some(Unit3::X.neg()));
    assert_eq!(normalize([0, i32::MIN, 0]), Some(Unit3::Y.neg()));
    assert_eq!(normalize([0, 0, i32::MAX]), Some(Unit3::Z));
    // 2^14/√3 = 9459.19…
    assert_eq!(normalize([1, 1, 1]).unwrap().to_bits(), [9459; 3]);
    assert_eq!(normalize([i32::MIN / 2, 0, 0]), Some(Unit3::X.neg()));
    assert_eq!(normalize([i32::MIN; 3]).unwrap().to_bits(), [-9459; 3]);
    let (u, len) = normalize_len([i64::MIN, 0, 0]).unwrap();
    assert_eq!((u, len), (Unit3::X.neg(), 1 << 63));
    let (u, len) = normalize_len([i64::MIN; 3]).unwrap();
    assert_eq!(u.to_bits(), [-9459; 3]);
    // √3·2^63 = 15975348984942515101.4…; components ≥ 2^31, so the length is
    // only promised to a relative 2^-29.
    let exact = 15_975_348_984_942_515_101u64;
    assert!(len.abs_diff(exact) <= exact >> 29, "{len}");
    let (_, len) = normalize_len([i64::MAX; 3]).unwrap();
    let exact = round_sqrt_u128(3 * (i64::MAX as u128).pow(2)) as u64;
    assert!(len.abs_diff(exact) <= exact >> 29);
    assert_eq!(normalize_len([1, 0, 0]), Some((Unit3::X, 1)));
    assert_eq!(normalize_len([-1, 0, 0]), Some((Unit3::X.neg(), 1)));
    assert_eq!(normalize_len([1, 1, 1]).unwrap().1, 2);
    assert_eq!(normalize_len([1, 1, 0]).unwrap().1, 1);
}

#[test]
fn zero_is_none() {
    assert_eq!(normalize([0, 0, 0]), None);
    assert_eq!(normalize_len([0, 0, 0]), None);
    // The smallest non-zero vectors are fine.
    assert!(normalize([0, 0, 1]).is_some());
    assert!(normalize_len([0, -1, 0]).is_some());
}

#[test]
fn rsqrt_q_accuracy() {
    // Dense stride over the whole domain plus every table node and its
    // neighbours. Relative error of 1/√X, X = x/2^32.
    let mut worst = 0f64;
    let mut check = |x: u32| {
        let y = rsqrt_q(x) as f64 / (1u64 << 30) as f64;
        let exact = 1.0 / (x as f64 / 4294967296.0).sqrt();
        let rel = (y / exact - 1.0).abs();
        assert!(rel < 2f64.powi(-23), "x = {x}: {y} vs {exact}");
        assert!(rsqrt_q(x) <= 1 << 31);
        worst = worst.max(rel);
    };
    let mut x = 1u64 << 30;
    while x < 1 << 32 {
        check(x as u32);
        x += 1021;
    }
    for k in 16u64..64 {
        for d in [-2i64, -1, 0, 1, 2, 1 << 25, (1 << 26) - 1] {
            let x = (k << 26) as i64 + d;
            if (1 << 30..1 << 32).contains(&x) {
                check(x as u32);
            }
        }
    }
    check(u32::MAX);
    println!("rsqrt_q: max relative error 2^{:.2}", worst.log2());
    // Out-of-domain inputs are clamped, not a panic.
    assert_eq!(rsqrt_q(0), rsqrt_q(1 << 30));
    assert_eq!(rsqrt_q(12345), rsqrt_q(1 << 30));
}

/// Every 509th mantissa (every one with `FIXSHADE_EXTENDED=1`: about a
/// minute in release mode).
#[test]
fn rsqrt_q_exhaustive() {
    let stride = if std::env::var_os("FIXSHADE_EXTENDED").is_some() {
        1
    } else {
        509
    };
    let mut worst = 0f64;
    for x in ((1u32 << 30)..=u32::MAX).step_by(stride) {
        // Within (2³⁰, 2³¹] with no cap: Newton's step undershoots; the
        // seed's residual within the ±2²⁰ its step's ranges take.
        assert!(rsqrt_q(x) <= 1 << 31, "{x}");
        assert!(rsqrt_seed(x).1.unsigned_abs() <= 1 << 20, "{x}");
        let y = rsqrt_q(x) as f64 / (1u64 << 30) as f64;
        let exact = 1.0 / (x as f64 / 4294967296.0).sqrt();
        worst = worst.max((y / exact - 1.0).abs());
    }
    println!(
        "rsqrt_q exhaustive: max relative error 2^{:.3}",
        worst.log2()
    );
    assert!(worst < 2f64.powi(-23));
}

#[test]
fn sign_and_permutation_symmetry() {
    let mut rng = Rng(99);
    for i in 0..50_000 {
        let bits = 1 + (i % 31) as u32;
        let v = [
            rng.signed(bits) as i32,
            rng.signed(bits) as i32,
            rng.signed(bits) as i32,
        ];
        let Some(u) = normalize(v) else { continue };
        assert_eq!(normalize(v.map(|x| -x)), Some(u.neg()), "{v:?}");
        let b = u.to_bits();
        let p = normalize([v[2], v[0], v[1]]).unwrap().to_bits();
        assert_eq!(p, [b[2], b[0], b[1]], "{v:?}");
        let w = v.map(|x| x as i64 * 3 - 1);
        if let Some((u, l)) = normalize_len(w) {
            assert_eq!(normalize_len(w.map(|x| -x)), Some((u.neg(), l)), "{w:?}");
        }
    }
}

/// The figures quoted in the module docs: run with `--nocapture`.
#[test]
fn report_max_error() {
    let mut s32 = Stats::default();
    sweep_i32(&mut s32, 1_000_000, 0xDEAD_BEEF_1234_5678);
    let mut s64 = Stats::default();
    sweep_i64(&mut s64, 1_000_000, 0x8765_4321_FEED_F00D);
    println!(
        "normalize: {} components, max error {:.4} ULP, {:.3}% exactly rounded",
        s32.components,
        s32.max_ulp,
        s32.exact_pct()
    );
    println!(
        "normalize_len: {} components, max error {:.4} ULP, {:.3}% exactly rounded, \
         max length relative error {:e} (2^{:.1})",
        s64.components,
        s64.max_ulp,
        s64.exact_pct(),
        s64.max_len_rel,
        s64.max_len_rel.log2()
    );
    assert!(s32.max_ulp <= 0.55 && s64.max_ulp <= 0.55);
}

fn scaled_i32() -> impl Strategy<Value = [i32; 3]> {
    (any::<[i32; 3]>(), 0u32..32).prop_map(|(v, s)| v.map(|x| x >> s))
}

fn scaled_i64() -> impl Strategy<Value = [i64; 3]> {
    (any::<[i64; 3]>(), 0u32..64).prop_map(|(v, s)| v.map(|x| x >> s))
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 20_000,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn prop_normalize(v in scaled_i32()) {
        let mut st = Stats::default();
        check_i32(v, &mut st);
        prop_assert!(st.max_ulp <= 0.55);
    }

    #[test]
    fn prop_normalize_len(v in scaled_i64()) {
        let mut st = Stats::default();
        check_i64(v, &mut st);
        prop_assert!(st.max_ulp <= 0.55);
    }

    #[test]
    fn prop_mixed_scales(v in any::<[i64; 3]>(), s in any::<[u8; 3]>()) {
        // Components of very different magnitudes.
        let v = [v[0] >> (s[0] % 64), v[1] >> (s[1] % 64), v[2] >> (s[2] % 64)];
        let mut st = Stats::default();
        check_i64(v, &mut st);
        if let (Ok(a), Ok(b), Ok(c)) = (i32::try_from(v[0]), i32::try_from(v[1]), i32::try_from(v[2])) {
            check_i32([a, b, c], &mut st);
        }
    }
}

/// `one_minus_cos` against the f64 angle between `normalize`'s unit
/// vectors and sums of two of them: within 2⁻²³ (32 units of 2⁻²⁸) where
/// `|s| ≥ 1/2`, within `2^(k/2) + 32` units below that; `None` only for
/// `s = 0`; and any `I2F14` vector (far from unit length, at the
/// components' ends) in range without overflow, its result in
/// `0 ..= 2²⁹`.
#[test]
fn one_minus_cos_is_the_angle() {
    let mut rng = Rng(0x5DEE_CE66_D1CE_4E5B);
    let unit = |rng: &mut Rng| loop {
        let v = [0; 3].map(|_| rng.signed(20) as i32);
        if let Some(u) = normalize(v) {
            return u.to_bits().map(i32::from);
        }
    };
    let (mut worst, mut cases) = (0f64, 0);
    for i in 0..200_000 {
        let n = unit(&mut rng);
        let (a, b) = (unit(&mut rng), unit(&mut rng));
        // Every fourth `b` near `−a`: a short `s`.
        let b = if i % 4 == 0 {
            a.map(|c| -c + (rng.signed(4) as i32))
        } else {
            b
        };
        let s = [0, 1, 2].map(|k| (a[k] + b[k]).clamp(-(1 << 15), 1 << 15));
        let got = one_minus_cos(n, s);
        let ss: f64 = s.iter().map(|&c| (c as f64).powi(2)).sum();
        if ss == 0.0 {
            assert_eq!(got, None);
            continue;
        }
        let nf = n.map(f64::from);
        let dot: f64 = (0..3).map(|k| nf[k] * s[k] as f64).sum();
        let nn: f64 = nf.iter().map(|c| c * c).sum();
        let want = (1.0 - dot / (nn.sqrt() * ss.sqrt())) * 2f64.powi(28);
        let k = (ss as u32).leading_zeros() & !1;
        let bound = if ss >= 2f64.powi(28) {
            32.0
        } else {
            2f64.powi(k as i32 / 2) + 32.0
        };
        let err = (got.expect("s is not zero") as f64 - want.clamp(0.0, 2f64.powi(29))).abs();
        assert!(err <= bound, "n {n:?} s {s:?}: {got:?} against {want}");
        if ss >= 2f64.powi(28) {
            worst = worst.max(err);
        }
        cases += 1;
    }
    println!("{cases} cases, worst {worst} units of 2^-28 where |s| >= 1/2");
    // Any I2F14 vectors: the ends of the components, far from unit length.
    let ends = [-(1 << 14), -1, 0, 1, 1 << 14];
    for &x in &ends {
        for &y in &ends {
            for &z in &ends {
                for s in [[1 << 15; 3], [-(1 << 15), 1 << 15, 0], [1, 0, 0], [x, y, z]] {
                    if let Some(d) = one_minus_cos([x, y, z], s) {
                        assert!(d <= 1 << 29);
                    }
                }
            }
        }
    }
}

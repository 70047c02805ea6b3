//! One light's term of the illumination equation (SPEC.md 3): the shaded
//! point ([`Surface`], or per pixel [`PixelSurface`]), the light's colour
//! gains ([`Gains`]) and the
//! diffuse and specular term they add (`s·f·(Id·Kd·max(N·L, 0) +
//! Is·Ks·spec)`). Below both the light kinds (`light`), which work out `L`,
//! `s` and `f`, and the whole equation (`illumination`), which sums them;
//! `illumination` re-exports its public items.

use crate::color::Rgb;
use crate::material::Specular;
use crate::normalize::{normalize, one_minus_cos, one_minus_q28, rsqrt_q, Dir};
use crate::num::widening::{mul_i32, mul_i32_u32, saturate_i32, shr_to_i32};
use crate::platform;
use crate::specular_table::{pow_from_delta, Exponent};
use crate::vector::{Unit3, Vec3};

/// `Q.15` raw value of 1.0, the format of the per-light factors.
///
/// ```
/// use fixshade::illumination::{Gain, FACTOR_ONE};
/// assert_eq!(FACTOR_ONE, 1 << 15);
/// // A factor of 1 passes a gain through unchanged (here 3.0, in Q.16).
/// assert_eq!(Gain::of_product(3 << 16, 1 << 16).apply(FACTOR_ONE), 3 << 16);
/// ```
pub const FACTOR_ONE: u32 = 1 << 15;

/// A per-light colour gain (`Id·Kd` or `Is·Ks` of one channel), as a 16-bit
/// mantissa and a shift: value = `mant / 2^(sh + 1)`, `sh ≤ 31`.
///
/// Range: 0 and [2⁻³², 256]; products above 256 are clamped to 256 (see
/// [`crate::color`] for why that clamp is invisible). Gains of 2⁻¹⁶ and more
/// keep 16 significant bits; below 2⁻¹⁶ (`sh = 31`, e.g. an area light's
/// 1/k² share on a dark material) the gain is the exact `Q.32` product,
/// with fewer bits.
///
/// ```
/// use fixshade::illumination::Gain;
/// // Id · Kd = 0.001 · 1: the mantissa keeps 16 significant bits.
/// let g = Gain::of_product(66, 1 << 16);
/// let (mant, den) = g.parts();
/// assert!(mant >= 1 << 15);
/// assert_eq!(mant as u64 * (1 << 32) / den, 66 << 16);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Gain {
    mant: u16,
    sh: u8,
    /// `2^sh / 2` (0 for `sh = 0`), the rounding [`Gain::apply`] adds.
    half: u32,
}

impl Gain {
    /// The gain `mant / 2^(sh + 1)` (`sh ≤ 31`).
    const fn new(mant: u16, sh: u32) -> Gain {
        Gain {
            mant,
            sh: sh as u8,
            half: (1u32 << sh) >> 1,
        }
    }

    /// The gain of two `U16F16` values' product, given as the exact `Q.32`
    /// product (`u64`).
    ///
    /// ```
    /// use fixshade::illumination::Gain;
    /// assert_eq!(Gain::from_q32(1 << 32).parts(), (1 << 15, 1 << 15)); // 1.0
    /// assert_eq!(Gain::from_q32(0).parts().0, 0);
    /// // Above 256 the gain is clamped to 256.
    /// assert_eq!(Gain::from_q32(u64::MAX), Gain::from_q32(256 << 32));
    /// ```
    pub const fn from_q32(p: u64) -> Gain {
        let p = if p > (256u64 << 32) { 256u64 << 32 } else { p };
        if p == 0 {
            return Gain::new(0, 0);
        }
        // bits ∈ [1, 41] since p ≤ 2^40.
        let bits = 64 - p.leading_zeros();
        // mant = p >> (31 − sh) should have 16 bits: sh = 47 − bits, at most 31.
        let sh = if 47 - bits > 31 { 31 } else { 47 - bits };
        let s = 31 - sh;
        let m = if s == 0 {
            p
        } else {
            (p + (1u64 << (s - 1))) >> s
        };
        if m >= 1 << 16 {
            // Rounding carried into bit 16: halve (exact, m = 2^16) with one
            // shift less. sh ≥ 6 here because bits ≤ 41.
            Gain::new((m >> 1) as u16, sh - 1)
        } else {
            Gain::new(m as u16, sh)
        }
    }

    /// The gain of `a · b` for two `U16F16` raw values.
    ///
    /// ```
    /// use fixshade::illumination::Gain;
    /// // 2.0 · 0.25 = 0.5, the same gain as its exact Q.32 product.
    /// let g = Gain::of_product(2 << 16, 1 << 14);
    /// assert_eq!(g, Gain::from_q32(1 << 31));
    /// assert_eq!(g.parts(), (1 << 15, 1 << 16));
    /// ```
    pub const fn of_product(a: u32, b: u32) -> Gain {
        Gain::from_q32(a as u64 * b as u64)
    }

    /// Applies the gain to a `Q.15` factor `x`, giving `Q.16`, rounded to
    /// nearest.
    ///
    /// A factor above 1 (`x > 2¹⁵`, outside the factors' range) is clamped
    /// to 1 first (one `min`), so the result is at most the gain itself.
    ///
    /// ```
    /// use fixshade::color::SHADE_ONE;
    /// use fixshade::illumination::{Gain, FACTOR_ONE};
    /// let one = Gain::of_product(1 << 16, 1 << 16);
    /// assert_eq!(one.apply(FACTOR_ONE / 2), SHADE_ONE / 2);
    /// assert_eq!(one.apply(u32::MAX), SHADE_ONE); // the factor is clamped to 1 first
    /// let half = Gain::of_product(1 << 15, 1 << 16);
    /// assert_eq!(half.apply(1), 1); // 0.5 · 2 Q.16 units, rounded to nearest
    /// ```
    #[inline(always)]
    pub const fn apply(self, x: u32) -> u32 {
        let x = if x > FACTOR_ONE { FACTOR_ONE } else { x };
        self.apply_in_range(x)
    }

    /// [`Gain::apply`] for a factor `x ≤ 2¹⁵` the caller has proved, without
    /// the clamp: `mant · x ≤ (2¹⁶ − 1)·2¹⁵ < 2³¹` and the rounding half is
    /// at most `2³⁰` (`sh ≤ 31`), so the sum stays below `2³²`.
    #[inline(always)]
    pub(crate) const fn apply_in_range(self, x: u32) -> u32 {
        (self.mant as u32 * x + self.half) >> self.sh
    }

    /// The gain's value as exact rational parts: `(mant, 2^(sh + 1))`,
    /// value = `mant / 2^(sh + 1)`. The denominator is a `u64` because it
    /// reaches 2³² for gains below 2⁻¹⁶ (`sh = 31`).
    ///
    /// ```
    /// use fixshade::illumination::Gain;
    /// assert_eq!(Gain::from_q32(3 << 32).parts(), (49152, 1 << 14)); // 3 = 49152 / 2^14
    /// // 2^-32, the smallest gain: the denominator reaches 2^32.
    /// assert_eq!(Gain::from_q32(1).parts(), (1, 1 << 32));
    /// ```
    pub const fn parts(self) -> (u16, u64) {
        (self.mant, 1u64 << (self.sh as u32 + 1))
    }
}

/// The diffuse and specular gains of one light for one material.
///
/// ```
/// use fixshade::illumination::{Gain, Gains};
/// use fixshade::Rgb;
/// let g = Gains::new(Rgb::WHITE, Rgb::WHITE, Rgb::grey(0.5), Rgb::BLACK);
/// assert_eq!(g.diffuse, [Gain::of_product(1 << 16, 1 << 15); 3]);
/// assert_eq!(g.specular, [Gain::default(); 3]); // no specular colour
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Gains {
    /// `Id_c · Kd_c` per channel.
    pub diffuse: [Gain; 3],
    /// `Is_c · Ks_c` per channel (all zero when the material has no specular).
    pub specular: [Gain; 3],
}

impl Gains {
    /// The gains of a light with intensities `id`, `is` on a material with
    /// colours `kd`, `ks`.
    ///
    /// ```
    /// use fixshade::illumination::{Gains, FACTOR_ONE};
    /// use fixshade::Rgb;
    /// let id = Rgb::clamped(2.0, 1.0, 0.0);
    /// let kd = Rgb::clamped(0.25, 0.5, 1.0);
    /// let g = Gains::new(id, Rgb::WHITE, kd, Rgb::grey(0.5));
    /// // Per channel Id·Kd = 0.5, 0.5, 0, and Is·Ks = 0.5, as Q.16 for a factor of 1.
    /// assert_eq!(g.diffuse.map(|d| d.apply(FACTOR_ONE)), [32768, 32768, 0]);
    /// assert_eq!(g.specular.map(|s| s.apply(FACTOR_ONE)), [32768; 3]);
    /// ```
    pub fn new(id: Rgb, is: Rgb, kd: Rgb, ks: Rgb) -> Gains {
        let (id, is, kd, ks) = (id.to_bits(), is.to_bits(), kd.to_bits(), ks.to_bits());
        Gains {
            diffuse: [0, 1, 2].map(|c| Gain::of_product(id[c], kd[c])),
            specular: [0, 1, 2].map(|c| Gain::of_product(is[c], ks[c])),
        }
    }
}

/// Where light is evaluated: a surface point and its unit normal (eye
/// space), the direction to the viewer, and the material's shininess.
///
/// ```
/// use fixshade::illumination::{add_light, Gains, Surface, FACTOR_ONE};
/// use fixshade::material::BlinnPhong;
/// use fixshade::{Exponent, Rgb, Unit3, Vec3};
/// let w = Rgb::WHITE;
/// let g = Gains::new(w, w, w, w);
/// let mut s = Surface { position: Vec3::ZERO, normal: Unit3::Z, view: Unit3::Z,
///                       shininess: Exponent::from_int(32) };
/// let mut acc = [0; 3];
/// add_light::<BlinnPhong>(&s, Unit3::Z, FACTOR_ONE, &g, &mut acc);
/// assert_eq!(acc, [2 << 16; 3]); // diffuse 1 + specular 1
/// s.view = Unit3::ZERO; // undefined V: no specular
/// let mut acc = [0; 3];
/// add_light::<BlinnPhong>(&s, Unit3::Z, FACTOR_ONE, &g, &mut acc);
/// assert_eq!(acc, [1 << 16; 3]);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    /// Eye-space position `P`.
    pub position: Vec3,
    /// Unit normal `N` (eye space), already negated for a back face where
    /// two-sided lighting asks for it.
    pub normal: Unit3,
    /// `V`: unit vector towards the eye, or zero where it is undefined (a
    /// local viewer at the point itself), which turns specular off.
    pub view: Unit3,
    /// Shininess `n`.
    pub shininess: Exponent,
}

/// Adds one light's contribution to `acc` (`Q.16` per channel), given the
/// unit vector `l` towards the light and the product `sf = s·f` of the spot
/// and attenuation factors (`Q.15`, at most 2¹⁵; a larger `sf`, which a
/// custom [`Falloff`](crate::light::Falloff) could return, is clamped to
/// 2¹⁵).
///
/// This is the body of the sum in SPEC.md 3, shared by every light kind.
///
/// ```
/// use fixshade::illumination::{add_light, Gains, Surface, FACTOR_ONE};
/// use fixshade::material::NoSpecular;
/// use fixshade::{Exponent, Rgb, Unit3, Vec3};
/// let g = Gains::new(Rgb::WHITE, Rgb::BLACK, Rgb::WHITE, Rgb::BLACK);
/// let s = Surface { position: Vec3::ZERO, normal: Unit3::Z, view: Unit3::ZERO,
///                   shininess: Exponent::ZERO };
/// let mut acc = [100; 3];
/// add_light::<NoSpecular>(&s, Unit3::Z, FACTOR_ONE / 2, &g, &mut acc); // s·f = 0.5
/// assert_eq!(acc, [100 + (1 << 15); 3]);
/// add_light::<NoSpecular>(&s, Unit3::Z.neg(), FACTOR_ONE, &g, &mut acc); // from behind
/// assert_eq!(acc, [100 + (1 << 15); 3]);
/// ```
#[inline(always)]
pub fn add_light<S: Specular>(ctx: &Surface, l: Unit3, sf: u32, g: &Gains, acc: &mut [u32; 3]) {
    add_light_with::<S>(ctx, l, sf, g, acc, |nl| specular_delta::<S>(ctx, l, nl));
}

/// As [`add_light`] with `sf = 1`, for Blinn–Phong with `V = (0, 0, 1)`
/// (the infinite viewer), given `half = H = normalise(L + V)` computed
/// once for the frame (`None` where `L + V = 0`): `1 − N·H` from `N − H`
/// without a normalisation per vertex. (The general path takes it from
/// the angle between `N` and `L + V`; the two agree within 32 units of
/// 2⁻¹⁶, `src/illumination.rs`'s test.)
#[inline(always)]
pub(crate) fn add_light_half<S: Specular>(
    ctx: &Surface,
    l: Unit3,
    half: Option<Unit3>,
    g: &Gains,
    acc: &mut [u32; 3],
) {
    add_light_with::<S>(ctx, l, FACTOR_ONE, g, acc, |_| {
        half.map(|h| ctx.normal.half_dist_sq(h))
    });
}

/// The half vector `normalise(L + (0, 0, 1))` of a light direction `l`
/// under the infinite viewer (`None` where it is undefined).
pub(crate) fn infinite_half(l: Unit3) -> Option<Unit3> {
    let (lb, v) = (l.to_bits(), Unit3::Z.to_bits());
    normalize([0, 1, 2].map(|i| lb[i] as i32 + v[i] as i32))
}

/// The body of [`add_light`]; `delta(N·L)` gives the specular base's
/// `1 − x` (see [`specular_delta`]).
#[inline(always)]
fn add_light_with<S: Specular>(
    ctx: &Surface,
    l: Unit3,
    sf: u32,
    g: &Gains,
    acc: &mut [u32; 3],
    delta: impl FnOnce(i32) -> Option<u32>,
) {
    let nl = ctx.normal.dot(l);
    if nl <= 0 || sf == 0 {
        return;
    }
    // nl ≤ 2^28 + a few units of rounding: Q.28 → Q.15, clamped to 1.
    let nl15 = ((nl as u32 + (1 << 12)) >> 13).min(FACTOR_ONE);
    add_term::<S>(nl15, sf, ctx.shininess, g, acc, || {
        if ctx.view.is_zero() {
            None
        } else {
            delta(nl)
        }
    });
}

/// A light's term from its factors: `nl15 = max(N·L, 0)` and `sf = s·f`
/// (`Q.15`, each at most 2¹⁵; a larger `sf` is clamped) and `delta()`, the
/// specular base's `1 − x` in `Q.28` (`None`: no specular term).
#[inline(always)]
fn add_term<S: Specular>(
    nl15: u32,
    sf: u32,
    shininess: Exponent,
    g: &Gains,
    acc: &mut [u32; 3],
    delta: impl FnOnce() -> Option<u32>,
) {
    // sf ≤ 2^15 (documented clamp; every light of the crate already gives
    // at most 2^15, so this changes nothing for them).
    let sf = sf.min(FACTOR_ONE);
    // The specular term first: the power's call leaves nothing of the
    // diffuse one to keep across it. sp ≤ 2^15 (pow_from_delta's range),
    // so spec ≤ 2^15, and so is diff below (nl15·sf ≤ 2^30), as
    // Gain::apply_in_range needs.
    let s = match S::ENABLED.then(delta).flatten() {
        Some(delta) => {
            let sp = pow_from_delta(delta, shininess) as u32;
            let spec = (sp * sf + (1 << 14)) >> 15;
            g.specular.map(|gs| gs.apply_in_range(spec))
        }
        None => [0; 3],
    };
    let diff = (nl15 * sf + (1 << 14)) >> 15;
    // Each term at most 2²⁴ (a gain at most 256 times a factor at most
    // 1, in Q.16): a channel's two sum without overflow, and one
    // saturating add gives what two would (the addends are not negative).
    for c in 0..3 {
        acc[c] = acc[c].saturating_add(g.diffuse[c].apply_in_range(diff) + s[c]);
    }
}

/// The shaded point in the form Phong shading's per-pixel lighting takes:
/// the eye position, the normal and the direction to the viewer as
/// [`Dir`]s (integer directions with their reciprocal lengths: no unit
/// vector is made), the cosine between those two and the shininess. Made
/// by the kernel; a light set that does not take it
/// ([`PreparedLights::SCALAR`](crate::light::PreparedLights::SCALAR)) is
/// shaded through a [`Surface`] instead.
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct PixelSurface {
    /// Eye-space position `P`, raw `I8F24`.
    pub(crate) position: [i32; 3],
    /// `N`, already turned for a back face.
    pub(crate) n: Dir,
    /// `V`, `None` where it is undefined (a local viewer at the point) or
    /// no specular term is computed.
    pub(crate) view: Option<Dir>,
    /// `N·V` in `Q.30` (0 without `view`).
    pub(crate) cos_nv: i32,
    /// Shininess `n`.
    pub(crate) shininess: Exponent,
    /// `V` is the infinite viewer's `+Z`.
    pub(crate) view_z: bool,
}

/// [`add_light`] at a [`PixelSurface`]: the light in direction `l`, `nl`
/// the integer dot product of `N`'s and `l`'s components
/// ([`Dir::dot_d`]), `sf` as there, and `delta(N·L)` the specular base's
/// `1 − x` (`Q.28`) from the cosine `N·L` (`Q.30`), asked only where `V`
/// is defined. The cosines from the directions' reciprocal lengths.
#[inline(always)]
pub(crate) fn add_light_at<S: Specular>(
    at: &PixelSurface,
    l: &Dir,
    nl: i32,
    sf: u32,
    g: &Gains,
    acc: &mut [u32; 3],
    delta: impl FnOnce(i32, &Dir) -> Option<u32>,
) {
    if nl <= 0 || sf == 0 {
        return;
    }
    let nl15 = at.n.cos15(nl, l);
    add_term::<S>(nl15, sf, at.shininess, g, acc, || {
        let v = at.view.as_ref()?;
        delta(at.n.cos_of_dot(nl, l), v)
    });
}

/// `1 − x` in `Q.28` for the specular base `x` from the cosines (`Q.30`)
/// between `N`, `L` and `V`. Blinn's `N·H = (N·L + N·V)/|L + V|` with
/// `|L + V| = 2·√W`, `W = (1 + L·V)/2`; Phong's `R·V = 2(N·L)(N·V) − L·V`.
/// `None` where `H` is undefined: `L + V = 0` to within the cosine's
/// rounding (`|L + V| < 2⁻¹⁰`, a light straight behind the point as the
/// viewer sees it).
#[inline(always)]
pub(crate) fn specular_delta_of<S: Specular>(nl: i32, nv: i32, lv: i32) -> Option<u32> {
    // (`one_minus_q28` takes the value within ±2³⁰: out of `i32`, the
    // value saturates.)
    let x = if S::BLINN {
        // W in Q.32, L·V taken below 1 so that it fits: 0 ..= 2³² − 2.
        let w = (lv.clamp(-(1 << 30), (1 << 30) - 1) + (1 << 30)) as u32 * 2;
        if w < 1 << 10 {
            return None;
        }
        // An even shift k into [2³⁰, 2³²), at most 20 as w ≥ 2¹⁰: r =
        // 2³⁰/√(w·2ᵏ/2³²), so 1/√W = r·2^(k/2 − 30).
        // (Where the core counts leading zeros in software, the usual
        // W ≥ 2³⁰ takes k = 0 without the count.)
        let k = if platform::SOFT_MUL64 && w >= 1 << 30 {
            0
        } else {
            platform::leading_zeros(w) & !1
        };
        let r = rsqrt_q(w << k);
        // N·H = s/√W with s = (N·L + N·V)/2, |s| ≤ 2³⁰·(1 + 2⁻²²): in Q.30
        // s·r·2^(k/2 − 30), |s·r| < 2⁶² shifted right by 20 to 30.
        let s = (nl >> 1) + (nv >> 1);
        let p = mul_i32_u32(s, r);
        shr_to_i32(p, 30 - k / 2).unwrap_or(if p < 0 { i32::MIN } else { i32::MAX })
    } else {
        // |2(N·L)(N·V) − L·V| ≤ 3 + ε: i64 in Q.30.
        saturate_i32((mul_i32(nl, nv) >> 29) - lv as i64)
    };
    Some(one_minus_q28(x))
}

/// `1 − x` in `Q.28` for the specular base `x` (`N·H` or `R·V`), computed as
/// half the squared distance of two unit vectors (see
/// [`Unit3::half_dist_sq`]). `None` where `H` is undefined (`L + V = 0`).
#[inline(always)]
fn specular_delta<S: Specular>(ctx: &Surface, l: Unit3, nl: i32) -> Option<u32> {
    let v = ctx.view.to_bits();
    let lb = l.to_bits();
    if S::BLINN {
        // 1 − N·H without H: the angle between N and L + V.
        let sum = [0, 1, 2].map(|i| lb[i] as i32 + v[i] as i32);
        one_minus_cos(ctx.normal.to_bits().map(i32::from), sum)
    } else {
        // R = 2(N·L)N − L. nl ≤ 2^28(1+ε); (nl >> 14) ≤ 2^14 + 1, times
        // 2·N_i (≤ 2^15) is below 2^30; minus L_i·2^14 stays below 2^31.
        let k = (nl + (1 << 13)) >> 14;
        let n = ctx.normal.to_bits();
        let r = [0, 1, 2].map(|i| {
            let q28 = 2 * k * n[i] as i32 - ((lb[i] as i32) << 14);
            ((q28 + (1 << 13)) >> 14).clamp(-(1 << 14), 1 << 14) as i16
        });
        Some(Unit3::new_clamped(r[0], r[1], r[2]).half_dist_sq(ctx.view))
    }
}

//! The illumination equation of SPEC.md section 3, per RGB channel, in fixed
//! point.
//!
//! ```text
//! I_c = E_c + A_c·Ka_c + Σ_i s_i·f_i·( Id_ic·Kd_c·max(N·L_i, 0) + Is_ic·Ks_c·spec_i )
//! ```
//!
//! # How the arithmetic is laid out
//! - `E + A·Ka` is one constant per frame ([`Lighting::new`]).
//! - The products `Id·Kd` and `Is·Ks` are constants per light and frame,
//!   prepared once as a [`Gain`]: a 16-bit mantissa and a shift, so that a
//!   gain of 0.001 keeps as many significant bits as a gain of 100.
//! - Per vertex (or per pixel, in Phong shading) and per light, the factors
//!   `max(N·L, 0)`, `spec`, `s` and `f` are `Q.15` numbers in [0, 1]
//!   (`u32`, at most 2¹⁵). A product of two factors is at most 2³⁰; a gain
//!   applied to a factor is `mantissa · factor ≤ (2¹⁶ − 1)·2¹⁵ < 2³¹`, then
//!   shifted. All are 32 × 32 → 32-bit multiplies: one instruction on a
//!   Cortex-M0.
//! - The sum is a `Q.16` `u32` per channel, added with saturation (every
//!   term is non-negative and the result is clamped to 1 = 2¹⁶, so
//!   saturation at 2³² − 1 is exact), then clamped to [0, 1] as a
//!   [`Shade`].
//!
//! # Choosing the terms
//! [`Lighting`] is generic over the specular term `S` (see
//! [`crate::material`]), the viewer `V` ([`InfiniteViewer`] or
//! [`LocalViewer`]) and the light set `L` (see [`crate::light`]). A term
//! that the types leave out is not compiled.

use core::marker::PhantomData;

use crate::color::{Rgb, Shade, SHADE_ONE};
use crate::light::LightSet;
use crate::light::PreparedLights;
use crate::material::{Material, Specular};
use crate::normalize::normalize;
use crate::specular_table::{pow_from_delta, Exponent};
use crate::vector::{Mat4, Unit3, Vec3};

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
}

impl Gain {
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
            return Gain { mant: 0, sh: 0 };
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
            Gain {
                mant: (m >> 1) as u16,
                sh: (sh - 1) as u8,
            }
        } else {
            Gain {
                mant: m as u16,
                sh: sh as u8,
            }
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
        (self.mant as u32 * x + ((1u32 << self.sh) >> 1)) >> self.sh
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
/// once for the frame (`None` where `L + V = 0`): the same arithmetic on
/// the same `H`, so the same colour, without a normalisation per vertex.
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
    // sf ≤ 2^15 (documented clamp; every light of the crate already gives
    // at most 2^15, so this changes nothing for them).
    let sf = sf.min(FACTOR_ONE);
    // nl ≤ 2^28 + a few units of rounding: Q.28 → Q.15, clamped to 1.
    let nl15 = ((nl as u32 + (1 << 12)) >> 13).min(FACTOR_ONE);
    // nl15·sf ≤ 2^30: diff ≤ 2^15, and so is spec below (sp ≤ 2^15, the
    // range of pow_from_delta), as Gain::apply_in_range needs.
    let diff = (nl15 * sf + (1 << 14)) >> 15;
    for (a, gd) in acc.iter_mut().zip(g.diffuse.iter()) {
        *a = a.saturating_add(gd.apply_in_range(diff));
    }
    if S::ENABLED && !ctx.view.is_zero() {
        let Some(delta) = delta(nl) else {
            return;
        };
        let sp = pow_from_delta(delta, ctx.shininess) as u32;
        let spec = (sp * sf + (1 << 14)) >> 15;
        for (a, gs) in acc.iter_mut().zip(g.specular.iter()) {
            *a = a.saturating_add(gs.apply_in_range(spec));
        }
    }
}

/// `1 − x` in `Q.28` for the specular base `x` (`N·H` or `R·V`), computed as
/// half the squared distance of two unit vectors (see
/// [`Unit3::half_dist_sq`]). `None` where `H` is undefined (`L + V = 0`).
#[inline(always)]
fn specular_delta<S: Specular>(ctx: &Surface, l: Unit3, nl: i32) -> Option<u32> {
    let v = ctx.view.to_bits();
    let lb = l.to_bits();
    if S::BLINN {
        let sum = [0, 1, 2].map(|i| lb[i] as i32 + v[i] as i32);
        let h = normalize(sum)?;
        Some(ctx.normal.half_dist_sq(h))
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

/// Where the viewer is: selects how `V` is computed.
///
/// ```
/// use fixshade::illumination::{InfiniteViewer, LocalViewer, Viewer};
/// assert!(LocalViewer::LOCAL);
/// assert!(!InfiniteViewer::LOCAL);
/// ```
pub trait Viewer: Copy + Default {
    /// `true` for a local viewer (`V = normalise(−P)`), `false` for the
    /// infinite viewer (`V = (0, 0, 1)`).
    const LOCAL: bool;
}

/// The infinite viewer: `V = (0, 0, 1)` everywhere (cheaper).
///
/// ```
/// use fixshade::illumination::{view_dir, InfiniteViewer};
/// use fixshade::{Unit3, Vec3};
/// let p = Vec3::from_f32(5.0, -1.0, -3.0).unwrap();
/// assert_eq!(view_dir::<InfiniteViewer>(p), Unit3::Z);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct InfiniteViewer;
impl Viewer for InfiniteViewer {
    const LOCAL: bool = false;
}

/// The local viewer: `V = normalise(−P)`, the eye at the eye-space origin.
///
/// ```
/// use fixshade::illumination::{view_dir, LocalViewer};
/// use fixshade::{Unit3, Vec3};
/// let p = Vec3::from_f32(0.0, 0.0, -2.0).unwrap();
/// assert_eq!(view_dir::<LocalViewer>(p), Unit3::Z);
/// assert_eq!(view_dir::<LocalViewer>(Vec3::ZERO), Unit3::ZERO); // at the eye: undefined
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct LocalViewer;
impl Viewer for LocalViewer {
    const LOCAL: bool = true;
}

/// `V` at eye-space point `p` for viewer `V` (zero where undefined).
///
/// ```
/// use fixshade::illumination::{view_dir, InfiniteViewer, LocalViewer};
/// use fixshade::{Unit3, Vec3};
/// let p = Vec3::from_f32(3.0, 0.0, -4.0).unwrap();
/// // −P / |P| = (−0.6, 0, 0.8) in I2F14.
/// assert_eq!(view_dir::<LocalViewer>(p).to_bits(), [-9830, 0, 13107]);
/// assert_eq!(view_dir::<InfiniteViewer>(p), Unit3::Z);
/// ```
#[inline]
pub fn view_dir<V: Viewer>(p: Vec3) -> Unit3 {
    if V::LOCAL {
        // −P; saturating (−i32::MIN does not fit), a change far below the
        // I2F14 result's precision.
        let b = p.to_bits().map(|c| c.saturating_neg());
        normalize(b).unwrap_or(Unit3::ZERO)
    } else {
        Unit3::Z
    }
}

/// The illumination equation prepared for one frame: material, global
/// ambient and lights in eye space.
///
/// Build it once per frame (or whenever the camera, lights or material
/// change) with [`Lighting::new`], then call [`Lighting::shade`] per vertex
/// or per pixel.
///
/// ```
/// use fixshade::{Lighting, Material, Mat4, Rgb, Unit3, Vec3};
/// use fixshade::illumination::InfiniteViewer;
/// use fixshade::light::DirectionalLight;
///
/// let material = Material::new()
///     .with_ambient(Rgb::clamped(1.0, 0.5, 0.2))
///     .with_diffuse(Rgb::clamped(1.0, 0.5, 0.2));
/// let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// let lighting: Lighting<_, InfiniteViewer, _> =
///     Lighting::new(&material, Rgb::grey(0.1), &sun, &Mat4::IDENTITY);
/// // A surface facing the light: ambient 0.1·Ka + Kd.
/// let c = lighting.shade(Vec3::ZERO, Unit3::Z).to_bits();
/// assert!((c[0] as i64 - 65536).abs() <= 2);            // 0.1 + 1.0, clamped to 1
/// assert!((c[1] as i64 - (0.55f64 * 65536.0) as i64).abs() <= 2);
/// ```
#[derive(Clone, Debug)]
pub struct Lighting<S: Specular, V: Viewer, L: LightSet> {
    base: [u32; 3],
    shininess: Exponent,
    lights: L::Prepared,
    _model: PhantomData<(S, V)>,
}

impl<S: Specular, V: Viewer, L: LightSet> Lighting<S, V, L> {
    /// Prepares the equation: `view` takes the lights' world-space
    /// positions and directions to eye space.
    ///
    /// ```
    /// use fixshade::illumination::InfiniteViewer;
    /// use fixshade::light::DirectionalLight;
    /// use fixshade::{Lighting, Mat4, Material, Rgb, Unit3, Vec3};
    /// let m = Material::new();
    /// let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    /// let none = Rgb::BLACK;
    /// let lit: Lighting<_, InfiniteViewer, _> = Lighting::new(&m, none, &sun, &Mat4::IDENTITY);
    /// assert!(lit.shade(Vec3::ZERO, Unit3::Z).to_bits()[0] > 52000); // Kd = 0.8
    /// // A view turned half-way round about x puts the light behind the surface.
    /// let turned = Mat4::rotation_x(core::f32::consts::PI);
    /// let dark: Lighting<_, InfiniteViewer, _> = Lighting::new(&m, none, &sun, &turned);
    /// assert_eq!(dark.shade(Vec3::ZERO, Unit3::Z).to_bits(), [0; 3]);
    /// ```
    pub fn new(material: &Material<S>, global_ambient: Rgb, lights: &L, view: &Mat4) -> Self {
        let (e, a, ka) = (
            material.emission.to_bits(),
            global_ambient.to_bits(),
            material.ambient.to_bits(),
        );
        // E ≤ 2^24 raw, A·Ka ≤ 2^48 in Q.32 → ≤ 2^32 after the shift:
        // sum in u64, saturate to u32 (anything above 1.0 is clamped anyway).
        let base = [0, 1, 2].map(|c| {
            let sum = e[c] as u64 + ((a[c] as u64 * ka[c] as u64 + (1 << 15)) >> 16);
            sum.min(u32::MAX as u64) as u32
        });
        let ks = if S::ENABLED {
            material.specular.color()
        } else {
            Rgb::BLACK
        };
        Lighting {
            base,
            shininess: material.specular.shininess(),
            lights: lights.prepare(view, material.diffuse, ks),
            _model: PhantomData,
        }
    }

    /// The colour at eye-space point `p` with unit normal `n` (SPEC.md 3),
    /// clamped to [0, 1]. A zero normal lights nothing but `E + A·Ka`.
    ///
    /// ```
    /// use fixshade::illumination::InfiniteViewer;
    /// use fixshade::light::DirectionalLight;
    /// use fixshade::{Lighting, Mat4, Material, Rgb, Unit3, Vec3};
    /// let m = Material::new();
    /// let four = Rgb::grey(4.0);
    /// let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap().with_diffuse(four);
    /// let a = Rgb::grey(0.5);
    /// let lit: Lighting<_, InfiniteViewer, _> = Lighting::new(&m, a, &sun, &Mat4::IDENTITY);
    /// assert_eq!(lit.shade(Vec3::ZERO, Unit3::Z).to_bits(), [1 << 16; 3]); // 0.1 + 3.2, clamped
    /// assert_eq!(lit.shade(Vec3::ZERO, Unit3::ZERO), lit.ambient()); // zero normal
    /// ```
    #[inline]
    pub fn shade(&self, p: Vec3, n: Unit3) -> Shade {
        let mut acc = self.base;
        if !n.is_zero() {
            let ctx = Surface {
                position: p,
                normal: n,
                view: if S::ENABLED {
                    view_dir::<V>(p)
                } else {
                    Unit3::ZERO
                },
                shininess: self.shininess,
            };
            self.lights.shade::<S>(&ctx, &mut acc);
        }
        Shade::from_bits(
            acc[0].min(SHADE_ONE),
            acc[1].min(SHADE_ONE),
            acc[2].min(SHADE_ONE),
        )
    }

    /// `E + A·Ka` alone, as `Q.16` (what a surface no light reaches shows).
    ///
    /// ```
    /// use fixshade::illumination::InfiniteViewer;
    /// use fixshade::light::DirectionalLight;
    /// use fixshade::{Lighting, Mat4, Material, Rgb};
    /// let m = Material::new().with_emission(Rgb::grey(0.25)); // Ka = 0.2
    /// let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
    /// let a = Rgb::grey(0.5);
    /// let lit: Lighting<_, InfiniteViewer, _> = Lighting::new(&m, a, &sun, &Mat4::IDENTITY);
    /// // E + A·Ka = 0.25 + 0.5 · 0.2 = 0.35, i.e. 22937.6 in Q.16.
    /// assert!((lit.ambient().to_bits()[0] as i64 - 22938).abs() <= 1);
    /// ```
    pub fn ambient(&self) -> Shade {
        Shade::from_bits(self.base[0], self.base[1], self.base[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::{unit_from_f64, DirectionalLight};
    use crate::material::BlinnPhong;
    use crate::normalize::normalize_len;

    fn rgb(c: [f64; 3]) -> Rgb {
        Rgb::from_f64(c).expect("colour")
    }

    /// Blinn–Phong under the infinite viewer: the directional light's half
    /// vector, computed once when the light is prepared, gives bit for bit the
    /// colour of the general path ([`add_light`], which normalises `L + V` at
    /// every call), over random normals and directions, including a light
    /// straight behind the surface (`L = −V`, where `H` is undefined).
    #[test]
    fn directional_half_vector_prepared_once_is_the_per_vertex_one() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut dirs: Vec<[f64; 3]> = vec![[0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]];
        for _ in 0..60 {
            dirs.push([next(), next(), next()]);
        }
        let (id, is) = (rgb([0.9, 0.7, 0.5]), rgb([1.0, 0.8, 0.6]));
        let (kd, ks) = (rgb([0.8, 0.6, 0.4]), rgb([0.7, 0.7, 0.7]));
        let mut checked = 0;
        for &d in &dirs {
            let Ok(dir) = unit_from_f64(d) else { continue };
            let light = DirectionalLight {
                direction: dir,
                diffuse: id,
                specular: is,
            };
            for shininess in [1u16, 32, 500] {
                let material = Material::new()
                    .with_ambient(Rgb::BLACK)
                    .with_diffuse(kd)
                    .with_specular(BlinnPhong {
                        color: ks,
                        shininess: Exponent::from_int(shininess),
                    });
                let lighting: Lighting<_, InfiniteViewer, _> =
                    Lighting::new(&material, Rgb::BLACK, &light, &Mat4::IDENTITY);
                // The light's eye-space direction as the kernel prepares it.
                let b = dir.to_bits().map(i32::from);
                let l = normalize_len(Mat4::IDENTITY.transform_dir_wide(b))
                    .unwrap()
                    .0;
                let gains = Gains::new(id, is, kd, ks);
                for _ in 0..200 {
                    let Ok(n) = unit_from_f64([next(), next(), next()]) else {
                        continue;
                    };
                    let ctx = Surface {
                        position: Vec3::ZERO,
                        normal: n,
                        view: Unit3::Z,
                        shininess: Exponent::from_int(shininess),
                    };
                    let mut acc = [0u32; 3];
                    add_light::<BlinnPhong>(&ctx, l, 1 << 15, &gains, &mut acc);
                    let general = acc.map(|c| c.min(1 << 16));
                    assert_eq!(
                        lighting.shade(Vec3::ZERO, n).to_bits(),
                        general,
                        "light {d:?} normal {:?} n = {shininess}",
                        n.to_bits()
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 30_000, "{checked} cases");
    }
}

//! The lights: directional, point, spot and area, with distance attenuation,
//! and the sets that hold any number of them without allocating.
//!
//! # Paying only for what a scene uses
//! Each kind of light is its own type, so a scene's light set decides at
//! compile time which code exists:
//! - [`DirectionalLight`] computes no distance and no attenuation;
//! - [`PointLight`] computes distance and attenuation; with the falloff
//!   [`NoAttenuation`] the attenuation code is gone too;
//! - only [`SpotLight`] computes the spot factor;
//! - [`AreaLight`] is k × k point lights sampled at the cells' centres.
//!
//! A light set ([`LightSet`]) is one light, a tuple of lights of different
//! kinds (`(sun, lamp)`), an array `[L; N]` or a `heapless::Vec<L, N>` of one
//! kind, or of [`AnyLight`] when the kinds are only known at run time.
//!
//! # Spaces and formats
//! Light positions and directions are given in **world space**; preparing a
//! light for a frame ([`LightSet::prepare`]) takes them to eye space with the
//! view matrix. Positions are [`WidePoint`]s (`I40F24`: range ±2³⁸, 2⁻²⁴
//! resolution), so a light 10⁴ units away and one 10⁻³ units from the
//! surface are both represented well; the vector from a surface point to the
//! light is formed in `i64` and normalised with its length.

use fixed::types::U32F32;

use crate::color::Rgb;
use crate::light_term::{
    add_light, add_light_at, add_light_half, infinite_half, specular_delta_of, Gains, PixelSurface,
    Surface, FACTOR_ONE,
};
use crate::material::Specular;
use crate::normalize::{normalize, normalize_len, one_minus_q28, Dir};
use crate::num::division::quotient_u32;
use crate::num::widening::mul_i32_i16;
use crate::num::{clamp_wide, step_wide, MiniFloat, WidePoint};
use crate::specular_table::{pow_from_delta, Exponent};
use crate::vector::{FormatError, Mat4, Unit3, COORD_FRAC};

/// Why a light could not be built.
///
/// ```
/// use fixshade::light::{unit_from_f32, LightError, SpotCone};
/// assert_eq!(unit_from_f32([0.0; 3]), Err(LightError::ZeroDirection));
/// assert_eq!(unit_from_f32([f32::NAN, 0.0, 1.0]), Err(LightError::NotFinite));
/// assert_eq!(SpotCone::new([0.0, -1.0, 0.0], 95.0, 1.0), Err(LightError::BadCutoff));
/// assert_eq!(LightError::BadCutoff.to_string(), "spot cutoff outside [0, 90] degrees");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LightError {
    /// A number was NaN or infinite.
    NotFinite,
    /// A position or constant lies outside its format's range.
    OutOfRange,
    /// A direction or axis of length zero.
    ZeroDirection,
    /// A spot cutoff outside [0°, 90°].
    BadCutoff,
    /// A negative or too large spot exponent.
    BadExponent,
    /// An area light with k = 0 or k > [`AreaLight::MAX_K`].
    BadSamples,
}

impl From<FormatError> for LightError {
    fn from(e: FormatError) -> Self {
        match e {
            FormatError::NotFinite => LightError::NotFinite,
            FormatError::OutOfRange => LightError::OutOfRange,
        }
    }
}

impl core::fmt::Display for LightError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            LightError::NotFinite => "light parameter is NaN or infinite",
            LightError::OutOfRange => "light parameter out of range",
            LightError::ZeroDirection => "light direction or axis has zero length",
            LightError::BadCutoff => "spot cutoff outside [0, 90] degrees",
            LightError::BadExponent => "spot exponent negative or above 4096",
            LightError::BadSamples => "area light samples_k must be 1 to 64",
        })
    }
}

/// `view · p` for a point (w = 1), `p` and the result in `I40F24` raw units.
/// Products of an `I8F24` entry (< 2³¹) and a coordinate (< 2⁶³) need
/// `i128`; done once per light per frame.
fn point_to_eye(view: &Mat4, p: [i64; 3], w: bool) -> [i64; 3] {
    let mut out = [0i64; 3];
    for (r, o) in out.iter_mut().enumerate() {
        let m = &view.m[r];
        let mut acc: i128 = 0;
        for k in 0..3 {
            acc += m[k] as i128 * p[k] as i128;
        }
        if w {
            acc += (m[3] as i128) << COORD_FRAC;
        }
        let v = (acc + (1 << (COORD_FRAC - 1))) >> COORD_FRAC;
        *o = clamp_wide(v);
    }
    out
}

/// A unit direction rotated by the view's linear part and renormalised.
fn dir_to_eye(view: &Mat4, d: Unit3) -> Unit3 {
    let b = d.to_bits();
    let v = view.transform_dir_wide([b[0] as i32, b[1] as i32, b[2] as i32]);
    normalize_len(v).map(|(u, _)| u).unwrap_or(Unit3::ZERO)
}

/// A unit vector from a float direction of any length; zero, NaN and ∞ are
/// errors.
///
/// ```
/// use fixshade::light::unit_from_f32;
/// let u = unit_from_f32([0.0, 3.0, 4.0]).unwrap();
/// assert_eq!(u.to_bits(), [0, 9830, 13107]);
/// ```
pub fn unit_from_f32(v: [f32; 3]) -> Result<Unit3, LightError> {
    unit_from_f64(v.map(f64::from))
}

/// As [`unit_from_f32`], from `f64`s.
///
/// ```
/// use fixshade::light::{unit_from_f64, LightError};
/// use fixshade::Unit3;
/// // Any length, however small or large.
/// assert_eq!(unit_from_f64([1e-300, 0.0, 0.0]), Ok(Unit3::X));
/// assert_eq!(unit_from_f64([0.0, -1e300, 0.0]), Ok(Unit3::Y.neg()));
/// assert_eq!(unit_from_f64([0.0; 3]), Err(LightError::ZeroDirection));
/// assert_eq!(unit_from_f64([0.0, f64::INFINITY, 0.0]), Err(LightError::NotFinite));
/// ```
pub fn unit_from_f64(v: [f64; 3]) -> Result<Unit3, LightError> {
    if v.iter().any(|x| !x.is_finite()) {
        return Err(LightError::NotFinite);
    }
    let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 {
        return Err(LightError::ZeroDirection);
    }
    // Scale the largest component to ±2^30: the others keep 30 bits.
    let s = v.map(|x| ((x / m) * (1u32 << 30) as f64) as i32);
    normalize(s).ok_or(LightError::ZeroDirection)
}

// ---------------------------------------------------------------------------
// Attenuation
// ---------------------------------------------------------------------------

/// How a point-like light's intensity falls with distance `d`.
///
/// ```
/// use fixshade::light::Falloff;
/// // Full intensity up to 4 units, none beyond.
/// #[derive(Clone, Copy, Debug)]
/// struct Range;
/// impl Falloff for Range {
///     type Prepared = ();
///     fn prepare(&self) {}
///     fn factor(_: &(), d_q24: u64) -> u32 { if d_q24 <= 4 << 24 { 1 << 15 } else { 0 } }
/// }
/// assert_eq!(Range::factor(&Range.prepare(), 3 << 24), 1 << 15);
/// assert_eq!(Range::factor(&(), 5 << 24), 0);
/// ```
pub trait Falloff: Copy + core::fmt::Debug {
    /// Per-frame form of the falloff.
    type Prepared: Copy + core::fmt::Debug;
    /// Prepares the constants.
    fn prepare(&self) -> Self::Prepared;
    /// The factor `f` in `Q.15` (0 ..= 2¹⁵) at distance `d` (`I40F24` raw
    /// units, i.e. `Q.24`).
    fn factor(p: &Self::Prepared, d_q24: u64) -> u32;

    /// [`Falloff::factor`] at the distance `d()`, made only where the
    /// falloff reads it (`d` is called at most once): Phong shading's
    /// pixels make a light's distance for this alone.
    ///
    /// ```
    /// use fixshade::light::{Attenuation, Falloff};
    /// let constant = Attenuation::new(2.0, 0.0, 0.0).unwrap().prepare();
    /// // 1 / 2 at any distance, which is not asked for.
    /// assert_eq!(Attenuation::factor_of(&constant, || unreachable!()), 1 << 14);
    /// ```
    #[inline(always)]
    fn factor_of(p: &Self::Prepared, d: impl FnOnce() -> u64) -> u32 {
        Self::factor(p, d())
    }
}

/// No attenuation: `f = 1`; the distance is not used.
///
/// ```
/// use fixshade::light::{Falloff, NoAttenuation, PointLight};
/// let lamp = PointLight::new([0.0, 1.0, 0.0]).unwrap().without_attenuation();
/// assert_eq!(lamp.attenuation, NoAttenuation);
/// // f = 1 (2¹⁵ in `Q.15`) at any distance.
/// assert_eq!(NoAttenuation::factor(&(), u64::MAX), 1 << 15);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct NoAttenuation;

impl Falloff for NoAttenuation {
    type Prepared = ();
    fn prepare(&self) {}
    #[inline(always)]
    fn factor(_: &(), _: u64) -> u32 {
        FACTOR_ONE
    }
}

/// `f = min(1, 1 / (c0 + c1·d + c2·d²))` (SPEC.md 3); `f = 1` where the
/// denominator is 0. Constants in [0, 2³²) with 2⁻³² resolution, which
/// covers 10⁻⁶ to 10⁶: `c0` as `U32F32`, `c1` and `c2` as the mini floats
/// the factor multiplies by (their 32 most significant bits), made when the
/// attenuation is built, so that a draw only copies them.
///
/// ```
/// use fixshade::light::{Attenuation, Falloff};
/// let a = Attenuation::new(1.0, 0.0, 0.25).unwrap();
/// assert!(Attenuation::new(-1.0, 0.0, 0.0).is_err());
/// // 1 / (1 + d²/4) is 0.5 at d = 2 (`Q.24`); the factor is `Q.15`.
/// assert_eq!(Attenuation::factor(&a.prepare(), 2 << 24), 1 << 14);
/// // 1 / (1 + d²) is 0.2 at d = 2.
/// let p = Attenuation::new(1.0, 0.0, 1.0).unwrap().prepare();
/// assert_eq!(Attenuation::factor(&p, 2 << 24), 6554);
/// assert_eq!(Attenuation::factor(&p, 1000 << 24), 0); // 10⁻⁶: below 2⁻¹⁶
/// // min(1, ·): 1 / (0.5 + 0.25²) would exceed 1.
/// let near = Attenuation::new(0.5, 0.0, 1.0).unwrap().prepare();
/// assert_eq!(Attenuation::factor(&near, 1 << 22), 1 << 15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Attenuation {
    /// `c0` in `Q.32`.
    c0: u64,
    /// `c1`, `c2`: exponents in [−63, 0] (from `Q.32`).
    c1: MiniFloat,
    c2: MiniFloat,
}

impl Default for Attenuation {
    fn default() -> Self {
        Attenuation::NONE
    }
}

impl Attenuation {
    /// `(1, 0, 0)`: `f = 1`, SCENE_FORMAT.md's default.
    ///
    /// ```
    /// use fixshade::light::{Attenuation, Falloff};
    /// assert_eq!(Attenuation::default(), Attenuation::NONE);
    /// assert_eq!(Attenuation::new(1.0, 0.0, 0.0), Ok(Attenuation::NONE));
    /// let p = Attenuation::NONE.prepare();
    /// assert_eq!(Attenuation::factor(&p, 1_000_000 << 24), 1 << 15);
    /// ```
    pub const NONE: Attenuation = Attenuation::from_bits([1 << 32, 0, 0]);

    /// From floats: each in [0, 2³²); NaN/∞ and negatives are errors.
    ///
    /// ```
    /// use fixshade::light::{Attenuation, LightError};
    /// let a = Attenuation::new(1.0, 0.5, 0.25).unwrap();
    /// assert_eq!(a.coefficients().map(|c| c.to_bits()), [1 << 32, 1 << 31, 1 << 30]);
    /// assert_eq!(Attenuation::new(1.0, -0.1, 0.0), Err(LightError::OutOfRange));
    /// assert_eq!(Attenuation::new(5.0e9, 0.0, 0.0), Err(LightError::OutOfRange));
    /// assert_eq!(Attenuation::new(1.0, 0.0, f32::NAN), Err(LightError::NotFinite));
    /// ```
    pub fn new(c0: f32, c1: f32, c2: f32) -> Result<Self, LightError> {
        Attenuation::from_f64([c0 as f64, c1 as f64, c2 as f64])
    }

    /// As [`Attenuation::new`], from `f64`s.
    ///
    /// ```
    /// use fixshade::light::{Attenuation, LightError};
    /// let a = Attenuation::from_f64([1.0, 1e-6, 1e6]).unwrap();
    /// assert_eq!(a.coefficients()[1].to_bits(), 4295); // 10⁻⁶ · 2³², rounded
    /// assert_eq!(a.coefficients()[2].to_num::<f64>(), 1e6);
    /// // Even a negative that would round to 0 is an error.
    /// assert_eq!(Attenuation::from_f64([1.0, -1e-12, 0.0]), Err(LightError::OutOfRange));
    /// ```
    pub fn from_f64(c: [f64; 3]) -> Result<Self, LightError> {
        let [c0, c1, c2] = c;
        let f = |v: f64| -> Result<u64, LightError> {
            if !v.is_finite() {
                return Err(LightError::NotFinite);
            }
            // A negative value that rounds to 0 (above −2⁻³³) is still
            // negative: an error, as for every other negative.
            if v < 0.0 {
                return Err(LightError::OutOfRange);
            }
            U32F32::checked_from_num(v)
                .map(U32F32::to_bits)
                .ok_or(LightError::OutOfRange)
        };
        Ok(Attenuation::from_bits([f(c0)?, f(c1)?, f(c2)?]))
    }

    /// From the raw `U32F32` bits of `c0`, `c1`, `c2` (every `u64` is
    /// one); `const`, for lights written as constants.
    ///
    /// ```
    /// use fixshade::light::Attenuation;
    /// const HALF: Attenuation = Attenuation::from_bits([1 << 32, 1 << 31, 0]);
    /// assert_eq!(Attenuation::new(1.0, 0.5, 0.0), Ok(HALF));
    /// ```
    pub const fn from_bits(c: [u64; 3]) -> Attenuation {
        Attenuation {
            c0: c[0],
            c1: MiniFloat::from_u64_small_frac(c[1], 32),
            c2: MiniFloat::from_u64_small_frac(c[2], 32),
        }
    }

    /// `c0`, `c1`, `c2` as the factor uses them: `c1` and `c2` to their 32
    /// most significant bits.
    ///
    /// ```
    /// use fixshade::light::Attenuation;
    /// // 2³¹ + 2⁻³² has 64 significant bits: the factor keeps the top 32.
    /// let a = Attenuation::from_bits([0, (1 << 63) + 1, 3]);
    /// assert_eq!(a.coefficients().map(|c| c.to_bits()), [0, 1 << 63, 3]);
    /// ```
    pub const fn coefficients(&self) -> [U32F32; 3] {
        [
            U32F32::from_bits(self.c0),
            U32F32::from_bits(self.c1.to_q32_saturating()),
            U32F32::from_bits(self.c2.to_q32_saturating()),
        ]
    }
}

impl Falloff for Attenuation {
    /// Built in the form the factor reads.
    type Prepared = Attenuation;
    #[inline(always)]
    fn prepare(&self) -> Attenuation {
        *self
    }

    /// Without the distance where `c1 = c2 = 0` (a spot light's usual
    /// attenuation): [`Falloff::factor`] does not read it there.
    #[inline(always)]
    fn factor_of(p: &Attenuation, d: impl FnOnce() -> u64) -> u32 {
        let constant = p.c1.is_zero() && p.c2.is_zero();
        Self::factor(p, if constant { 0 } else { d() })
    }

    #[inline]
    fn factor(p: &Attenuation, d_q24: u64) -> u32 {
        // Exponents: c1, c2 ∈ [−63, 0] (frac 32), d ∈ [−55, 8],
        // c1·d ∈ [−87, 40], c2·d·d ∈ [−111, 80]: far inside MiniFloat's
        // range, so the clamps of `from_u64` and `mul` are left out here.
        let den = if p.c1.is_zero() && p.c2.is_zero() {
            // A constant factor (a spot light's, often): no distance.
            p.c0
        } else {
            let d = MiniFloat::from_u64_small_frac(d_q24, COORD_FRAC as i32);
            p.c0.saturating_add(p.c1.mul_in_range(d).to_q32_saturating())
                .saturating_add(p.c2.mul_in_range(d).mul_in_range(d).to_q32_saturating())
        };
        if den <= 1 << 32 {
            // den ≤ 1 (including den = 0): f = 1.
            return FACTOR_ONE;
        }
        if den >= 1 << 48 {
            // f < 2^-16: below half a Q.15 unit.
            return 0;
        }
        // f = 2^32/den in Q.15 = 2^31 / (den >> 16); den >> 16 ∈ (2^16, 2^32)
        // keeps 17+ significant bits. 2^31 + den16/2 < 2^32: no overflow.
        let den16 = (den >> 16) as u32;
        quotient_u32((1u32 << 31) + den16 / 2, den16)
    }
}

// ---------------------------------------------------------------------------
// Traits
// ---------------------------------------------------------------------------

/// A light prepared for a frame, in eye space, with its gains for the
/// frame's material.
///
/// ```
/// use fixshade::light::{DirectionalLight, LightSet, PreparedLights};
/// use fixshade::{illumination::Surface, material::NoSpecular, Exponent, Mat4, Rgb, Unit3, Vec3};
/// let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// let prepared = sun.prepare(&Mat4::IDENTITY, Rgb::WHITE, Rgb::BLACK);
/// let (normal, view, shininess) = (Unit3::Z, Unit3::Z, Exponent::ZERO);
/// let ctx = Surface { position: Vec3::ZERO, normal, view, shininess };
/// let mut acc = [0; 3];
/// prepared.shade::<NoSpecular>(&ctx, &mut acc);
/// assert_eq!(acc, [1 << 16; 3]); // N·L = 1, Id·Kd = 1
/// let mut full = [u32::MAX - 1; 3];
/// prepared.shade::<NoSpecular>(&ctx, &mut full);
/// assert_eq!(full, [u32::MAX; 3]); // saturating
/// ```
pub trait PreparedLights: Clone + core::fmt::Debug {
    /// No light at all (`()`, or sets of `()`): the colour is `E + A·Ka`
    /// everywhere, so nothing of a surface (its normal, its position) is
    /// made for it.
    const EMPTY: bool = false;
    /// Whether a light here reads the surface's position (a point-like
    /// light's direction and distance): where none does, the vertex stage
    /// does not make the eye position for the lighting.
    const READS_POSITION: bool = true;
    /// Adds this light's (or these lights') contribution at `ctx` to `acc`
    /// (`Q.16` per channel, saturating).
    fn shade<S: Specular>(&self, ctx: &Surface, acc: &mut [u32; 3]);
    /// Whether [`PreparedLights::shade_at`] is this set's own: Phong
    /// shading then lights each pixel in that form, and otherwise through
    /// [`PreparedLights::shade`] with a unit normal and view vector made at
    /// each pixel. Every light of the crate has it; a set of your own
    /// keeps the default (`false`: its `shade_at` is never called).
    const SCALAR: bool = false;
    /// [`PreparedLights::shade`] at a point in the per-pixel form (the
    /// kernel's; called only where [`PreparedLights::SCALAR`] holds).
    #[doc(hidden)]
    #[inline(always)]
    fn shade_at<S: Specular>(&self, at: &PixelSurface, acc: &mut [u32; 3]) {
        let _ = (at, acc);
    }
}

/// Any number of lights: one light, a tuple, an array, a `heapless::Vec`.
///
/// ```
/// use fixshade::light::{DirectionalLight, LightSet};
/// use fixshade::{illumination::InfiniteViewer, Lighting, Material, Mat4, Rgb, Unit3, Vec3};
/// fn lit<L: LightSet>(lights: &L) -> [u32; 3] {
///     let m = Material::new().with_diffuse(Rgb::WHITE);
///     let l = Lighting::<_, InfiniteViewer, _>::new(&m, Rgb::BLACK, lights, &Mat4::IDENTITY);
///     l.shade(Vec3::ZERO, Unit3::Z).to_bits()
/// }
/// let quarter = Rgb::grey(0.25);
/// let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap().with_diffuse(quarter);
/// assert_eq!(lit(&(sun, [sun; 2])), lit(&sun).map(|c| 3 * c)); // a tuple holding an array
/// assert_eq!(lit(&()), [0; 3]);
/// ```
pub trait LightSet {
    /// The lights in eye space with their gains.
    type Prepared: PreparedLights;
    /// Takes the lights to eye space with `view` and multiplies their
    /// intensities with the material's diffuse colour `kd` and specular
    /// colour `ks`.
    fn prepare(&self, view: &Mat4, kd: Rgb, ks: Rgb) -> Self::Prepared;
}

// ---------------------------------------------------------------------------
// Directional
// ---------------------------------------------------------------------------

/// A light at infinity (SPEC.md 2): constant direction, no distance, no
/// attenuation.
///
/// ```
/// use fixshade::light::DirectionalLight;
/// use fixshade::Rgb;
/// let sun = DirectionalLight::new([1.0, 1.0, 1.0]).unwrap()
///     .with_specular(Rgb::grey(0.5));
/// assert_eq!(sun.diffuse, Rgb::WHITE);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DirectionalLight {
    /// Unit direction towards the light, world space.
    pub direction: Unit3,
    /// Diffuse intensity `Id`.
    pub diffuse: Rgb,
    /// Specular intensity `Is`.
    pub specular: Rgb,
}

impl DirectionalLight {
    /// A white light shining from `towards_light` (any length but zero).
    ///
    /// ```
    /// use fixshade::light::{DirectionalLight, LightError};
    /// use fixshade::{Rgb, Unit3};
    /// let sun = DirectionalLight::new([0.0, 0.0, 5.0]).unwrap();
    /// assert_eq!(sun.direction, Unit3::Z); // normalised
    /// assert_eq!((sun.diffuse, sun.specular), (Rgb::WHITE, Rgb::WHITE));
    /// assert_eq!(DirectionalLight::new([0.0; 3]), Err(LightError::ZeroDirection));
    /// ```
    pub fn new(towards_light: [f32; 3]) -> Result<Self, LightError> {
        Ok(DirectionalLight::from_unit(unit_from_f32(towards_light)?))
    }
    /// A white light from a unit direction.
    ///
    /// ```
    /// use fixshade::light::DirectionalLight;
    /// use fixshade::{Rgb, Unit3};
    /// const TOP: DirectionalLight = DirectionalLight::from_unit(Unit3::Y);
    /// assert_eq!((TOP.direction, TOP.diffuse), (Unit3::Y, Rgb::WHITE));
    /// assert_eq!(DirectionalLight::new([0.0, 2.0, 0.0]), Ok(TOP));
    /// ```
    pub const fn from_unit(direction: Unit3) -> Self {
        DirectionalLight {
            direction,
            diffuse: Rgb::WHITE,
            specular: Rgb::WHITE,
        }
    }
    /// Sets the diffuse intensity.
    ///
    /// ```
    /// use fixshade::light::DirectionalLight;
    /// use fixshade::Rgb;
    /// let red = Rgb::clamped(1.0, 0.0, 0.0);
    /// let sun = DirectionalLight::new([0.0, 1.0, 0.0]).unwrap().with_diffuse(red);
    /// assert_eq!((sun.diffuse, sun.specular), (red, Rgb::WHITE));
    /// ```
    pub const fn with_diffuse(mut self, c: Rgb) -> Self {
        self.diffuse = c;
        self
    }
    /// Sets the specular intensity.
    ///
    /// ```
    /// use fixshade::light::DirectionalLight;
    /// use fixshade::{Rgb, Unit3};
    /// const MATT_SUN: DirectionalLight =
    ///     DirectionalLight::from_unit(Unit3::Z).with_specular(Rgb::BLACK);
    /// assert_eq!((MATT_SUN.diffuse, MATT_SUN.specular), (Rgb::WHITE, Rgb::BLACK));
    /// ```
    pub const fn with_specular(mut self, c: Rgb) -> Self {
        self.specular = c;
        self
    }
}

/// [`DirectionalLight`] prepared.
///
/// ```
/// use fixshade::light::DirectionalLight;
/// use fixshade::{illumination::InfiniteViewer, Lighting, Material, Mat4, Rgb, Unit3, Vec3};
/// let view = Mat4::rotation_y(core::f32::consts::FRAC_PI_2); // +x (world) → −z (eye)
/// let sun = DirectionalLight::new([1.0, 0.0, 0.0]).unwrap();
/// let m = Material::new().with_diffuse(Rgb::WHITE);
/// // `Lighting::new` prepares the sun: a `PreparedDirectional`, in eye space.
/// let l: Lighting<_, InfiniteViewer, _> = Lighting::new(&m, Rgb::BLACK, &sun, &view);
/// assert!(l.shade(Vec3::ZERO, Unit3::Z.neg()).to_bits()[0] > 65_400); // facing it: ≈ 1
/// assert_eq!(l.shade(Vec3::ZERO, Unit3::Z).to_bits(), [0; 3]); // facing away
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PreparedDirectional {
    l: Unit3,
    /// `H` for the infinite viewer (`normalise(L + (0, 0, 1))`), the same
    /// at every vertex, so computed here once.
    half: Option<Unit3>,
    gains: Gains,
}

impl PreparedLights for PreparedDirectional {
    const READS_POSITION: bool = false;
    #[inline]
    fn shade<S: Specular>(&self, ctx: &Surface, acc: &mut [u32; 3]) {
        if S::BLINN && ctx.view == Unit3::Z {
            add_light_half::<S>(ctx, self.l, self.half, &self.gains, acc);
        } else {
            add_light::<S>(ctx, self.l, FACTOR_ONE, &self.gains, acc);
        }
    }
    const SCALAR: bool = true;
    #[inline]
    fn shade_at<S: Specular>(&self, at: &PixelSurface, acc: &mut [u32; 3]) {
        // L and the infinite viewer's H in the per-pixel form here, not
        // when the light is prepared: a draw without Phong shading keeps
        // no code and no field for them (a few products a pixel, no
        // root; made once a draw, they cost S1's configuration 364 bytes).
        let l = &Dir::of_unit(self.l);
        let nl = Dir::dot_d(at.n.d(), l);
        add_light_at::<S>(at, l, nl, FACTOR_ONE, &self.gains, acc, |nl, v| {
            if S::BLINN && at.view_z {
                // 1 − N·H with the infinite viewer's H, made once a draw.
                Some(one_minus_q28(at.n.cos(&Dir::of_unit(self.half?))))
            } else {
                specular_delta_of::<S>(nl, at.cos_nv, l.cos(v))
            }
        });
    }
}

impl LightSet for DirectionalLight {
    type Prepared = PreparedDirectional;
    fn prepare(&self, view: &Mat4, kd: Rgb, ks: Rgb) -> PreparedDirectional {
        let l = dir_to_eye(view, self.direction);
        PreparedDirectional {
            l,
            half: infinite_half(l),
            gains: Gains::new(self.diffuse, self.specular, kd, ks),
        }
    }
}

// ---------------------------------------------------------------------------
// Point and spot
// ---------------------------------------------------------------------------

/// A point light with falloff `A` ([`Attenuation`] by default).
///
/// ```
/// use fixshade::light::{Attenuation, PointLight};
/// let lamp = PointLight::new([0.0, 2.0, 1.0]).unwrap()
///     .with_attenuation(Attenuation::new(1.0, 0.1, 0.01).unwrap());
/// let cheap = PointLight::new([0.0, 2.0, 1.0]).unwrap().without_attenuation();
/// # let _ = (lamp, cheap);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PointLight<A: Falloff = Attenuation> {
    /// World-space position.
    pub position: WidePoint,
    /// Diffuse intensity `Id`.
    pub diffuse: Rgb,
    /// Specular intensity `Is`.
    pub specular: Rgb,
    /// Distance falloff.
    pub attenuation: A,
}

impl PointLight<Attenuation> {
    /// A white light at `position` with attenuation `(1, 0, 0)`.
    ///
    /// ```
    /// use fixshade::light::{Attenuation, LightError, PointLight};
    /// use fixshade::num::WidePoint;
    /// let lamp = PointLight::new([0.0, 2.0, 1.0]).unwrap();
    /// assert_eq!(lamp.position, WidePoint::from_f32([0.0, 2.0, 1.0]).unwrap());
    /// assert_eq!(lamp.attenuation, Attenuation::NONE);
    /// assert_eq!(PointLight::new([0.0, 3.0e11, 0.0]), Err(LightError::OutOfRange));
    /// assert_eq!(PointLight::new([f32::NAN, 0.0, 0.0]), Err(LightError::NotFinite));
    /// ```
    pub fn new(position: [f32; 3]) -> Result<Self, LightError> {
        Ok(PointLight {
            position: WidePoint::from_f32(position)?,
            diffuse: Rgb::WHITE,
            specular: Rgb::WHITE,
            attenuation: Attenuation::NONE,
        })
    }
}

impl<A: Falloff> PointLight<A> {
    /// Sets the diffuse intensity.
    ///
    /// ```
    /// use fixshade::light::PointLight;
    /// use fixshade::Rgb;
    /// let warm = Rgb::clamped(1.0, 0.8, 0.6);
    /// let lamp = PointLight::new([0.0, 2.0, 0.0]).unwrap().without_attenuation();
    /// let lamp = lamp.with_diffuse(warm); // any falloff
    /// assert_eq!((lamp.diffuse, lamp.specular), (warm, Rgb::WHITE));
    /// ```
    pub const fn with_diffuse(mut self, c: Rgb) -> Self {
        self.diffuse = c;
        self
    }
    /// Sets the specular intensity.
    ///
    /// ```
    /// use fixshade::light::PointLight;
    /// use fixshade::Rgb;
    /// let half = Rgb::grey(0.5);
    /// let lamp = PointLight::new([0.0, 2.0, 0.0]).unwrap().with_specular(half);
    /// assert_eq!(lamp.specular.to_bits(), [1 << 15; 3]);
    /// assert_eq!(lamp.diffuse, Rgb::WHITE);
    /// ```
    pub const fn with_specular(mut self, c: Rgb) -> Self {
        self.specular = c;
        self
    }
    /// Sets an attenuation.
    ///
    /// ```
    /// use fixshade::light::{Attenuation, PointLight};
    /// use fixshade::Rgb;
    /// let a = Attenuation::new(1.0, 0.1, 0.01).unwrap();
    /// let cheap = PointLight::new([0.0, 2.0, 0.0]).unwrap().with_diffuse(Rgb::BLACK);
    /// let cheap = cheap.without_attenuation();
    /// let lamp: PointLight<Attenuation> = cheap.with_attenuation(a);
    /// assert_eq!(lamp.attenuation, a);
    /// assert_eq!((lamp.position, lamp.diffuse), (cheap.position, Rgb::BLACK));
    /// ```
    pub fn with_attenuation(self, a: Attenuation) -> PointLight<Attenuation> {
        PointLight {
            position: self.position,
            diffuse: self.diffuse,
            specular: self.specular,
            attenuation: a,
        }
    }
    /// Removes attenuation from the type: `f = 1`, no attenuation code.
    ///
    /// ```
    /// use fixshade::light::{Attenuation, NoAttenuation, PointLight};
    /// use fixshade::Rgb;
    /// let lamp = PointLight::new([0.0, 2.0, 0.0]).unwrap()
    ///     .with_diffuse(Rgb::grey(0.5))
    ///     .with_attenuation(Attenuation::new(1.0, 0.0, 1.0).unwrap());
    /// let cheap: PointLight<NoAttenuation> = lamp.without_attenuation();
    /// assert_eq!(cheap.attenuation, NoAttenuation); // the constants are dropped
    /// assert_eq!((cheap.position, cheap.diffuse), (lamp.position, lamp.diffuse));
    /// ```
    pub fn without_attenuation(self) -> PointLight<NoAttenuation> {
        PointLight {
            position: self.position,
            diffuse: self.diffuse,
            specular: self.specular,
            attenuation: NoAttenuation,
        }
    }
}

/// A spot's cone: `s = 0` outside the cutoff angle, `cos^p γ` inside.
///
/// ```
/// use fixshade::light::SpotCone;
/// use fixshade::{Exponent, Unit3};
/// let cone = SpotCone::new([0.0, -2.0, 0.0], 60.0, 8.0).unwrap();
/// assert_eq!(cone.axis, Unit3::Y.neg());
/// assert_eq!(cone.delta_cutoff, 1 << 27); // 1 − cos 60° = 0.5 in `Q.28`
/// assert_eq!(cone.exponent, Exponent::from_int(8));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SpotCone {
    /// Unit axis (the direction the spot shines), world space.
    pub axis: Unit3,
    /// `1 − cos(cutoff)` in `Q.28`.
    pub delta_cutoff: u32,
    /// The spot exponent `p`.
    pub exponent: Exponent,
}

impl SpotCone {
    /// A cone from an axis, a cutoff in degrees ([0, 90]) and an exponent
    /// ([0, 4096]).
    ///
    /// ```
    /// use fixshade::light::{LightError, SpotCone};
    /// let down = [0.0, -1.0, 0.0];
    /// assert_eq!(SpotCone::new(down, 90.0, 0.0).unwrap().delta_cutoff, 1 << 28); // cos 90° = 0
    /// assert_eq!(SpotCone::new(down, 90.5, 1.0), Err(LightError::BadCutoff));
    /// assert_eq!(SpotCone::new(down, 30.0, 4097.0), Err(LightError::BadExponent));
    /// assert_eq!(SpotCone::new(down, 30.0, -1.0), Err(LightError::BadExponent));
    /// assert_eq!(SpotCone::new([0.0; 3], 30.0, 1.0), Err(LightError::ZeroDirection));
    /// ```
    pub fn new(axis: [f32; 3], cutoff_deg: f32, exponent: f32) -> Result<Self, LightError> {
        SpotCone::from_f64(axis.map(f64::from), cutoff_deg as f64, exponent as f64)
    }

    /// As [`SpotCone::new`], from `f64`s.
    ///
    /// ```
    /// use fixshade::light::{LightError, SpotCone};
    /// use fixshade::Exponent;
    /// let pencil = SpotCone::from_f64([0.0, 0.0, -1.0], 0.0, 0.5).unwrap();
    /// assert_eq!(pencil.delta_cutoff, 0); // cutoff 0°: the axis alone
    /// assert_eq!(pencil.exponent, Exponent::from_bits(128)); // 0.5 in `Q.8`
    /// let bad = SpotCone::from_f64([0.0, 0.0, -1.0], f64::INFINITY, 1.0);
    /// assert_eq!(bad, Err(LightError::NotFinite));
    /// ```
    pub fn from_f64(axis: [f64; 3], cutoff_deg: f64, exponent: f64) -> Result<Self, LightError> {
        if !cutoff_deg.is_finite() || !exponent.is_finite() {
            return Err(LightError::NotFinite);
        }
        if !(0.0..=90.0).contains(&cutoff_deg) {
            return Err(LightError::BadCutoff);
        }
        Ok(SpotCone {
            axis: unit_from_f64(axis)?,
            delta_cutoff: one_minus_cos_q28(cutoff_deg),
            exponent: Exponent::from_f64(exponent).map_err(|_| LightError::BadExponent)?,
        })
    }
}

/// `1 − cos(deg°) = 2 sin²(deg°/2)` in `Q.28`, for `deg` in [0, 90], by a
/// Taylor series (once per light; no libm in `no_std`).
fn one_minus_cos_q28(deg: f64) -> u32 {
    let x = deg * core::f64::consts::PI / 360.0; // half angle, ≤ π/4
    let (mut term, mut sum) = (x, x);
    for k in 1..12 {
        term *= -x * x / ((2 * k) as f64 * (2 * k + 1) as f64);
        sum += term;
    }
    let v = 2.0 * sum * sum * (1u64 << 28) as f64 + 0.5;
    v as u32
}

/// A spot light: a point light with a cone.
///
/// ```
/// use fixshade::light::SpotLight;
/// let spot = SpotLight::new([0.0, 3.0, 0.0], [0.0, -1.0, 0.0], 30.0, 8.0).unwrap();
/// assert!(SpotLight::new([0.0, 3.0, 0.0], [0.0, -1.0, 0.0], 120.0, 8.0).is_err());
/// # let _ = spot;
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SpotLight<A: Falloff = Attenuation> {
    /// The light without its cone.
    pub light: PointLight<A>,
    /// The cone.
    pub cone: SpotCone,
}

impl SpotLight<Attenuation> {
    /// A white spot at `position` shining along `axis`, attenuation `(1, 0, 0)`.
    ///
    /// ```
    /// use fixshade::light::{Attenuation, LightError, SpotCone, SpotLight};
    /// let spot = SpotLight::new([0.0, 3.0, 0.0], [0.0, -1.0, 0.0], 30.0, 8.0).unwrap();
    /// assert_eq!(spot.cone, SpotCone::new([0.0, -1.0, 0.0], 30.0, 8.0).unwrap());
    /// assert_eq!(spot.light.attenuation, Attenuation::NONE);
    /// let far = SpotLight::new([3.0e11, 0.0, 0.0], [0.0, -1.0, 0.0], 30.0, 8.0);
    /// assert_eq!(far, Err(LightError::OutOfRange));
    /// ```
    pub fn new(
        position: [f32; 3],
        axis: [f32; 3],
        cutoff_deg: f32,
        exponent: f32,
    ) -> Result<Self, LightError> {
        Ok(SpotLight {
            light: PointLight::new(position)?,
            cone: SpotCone::new(axis, cutoff_deg, exponent)?,
        })
    }
}

impl<A: Falloff> SpotLight<A> {
    /// Sets the diffuse intensity.
    ///
    /// ```
    /// use fixshade::light::SpotLight;
    /// use fixshade::Rgb;
    /// let blue = Rgb::clamped(0.2, 0.4, 1.0);
    /// let spot = SpotLight::new([0.0, 3.0, 0.0], [0.0, -1.0, 0.0], 30.0, 8.0).unwrap();
    /// let spot = spot.with_diffuse(blue);
    /// assert_eq!((spot.light.diffuse, spot.light.specular), (blue, Rgb::WHITE));
    /// ```
    pub const fn with_diffuse(mut self, c: Rgb) -> Self {
        self.light.diffuse = c;
        self
    }
    /// Sets the specular intensity.
    ///
    /// ```
    /// use fixshade::light::SpotLight;
    /// use fixshade::Rgb;
    /// let spot = SpotLight::new([0.0, 3.0, 0.0], [0.0, -1.0, 0.0], 30.0, 8.0).unwrap();
    /// let matt = spot.with_specular(Rgb::BLACK);
    /// assert_eq!((matt.light.diffuse, matt.light.specular), (Rgb::WHITE, Rgb::BLACK));
    /// assert_eq!(matt.cone, spot.cone);
    /// ```
    pub const fn with_specular(mut self, c: Rgb) -> Self {
        self.light.specular = c;
        self
    }
    /// Sets an attenuation.
    ///
    /// ```
    /// use fixshade::light::{Attenuation, SpotLight};
    /// let spot = SpotLight::new([0.0, 3.0, 0.0], [0.0, -1.0, 0.0], 30.0, 8.0).unwrap();
    /// let a = Attenuation::new(1.0, 0.0, 0.1).unwrap();
    /// let dim = spot.with_attenuation(a);
    /// assert_eq!(dim.light.attenuation, a);
    /// assert_eq!((dim.light.position, dim.cone), (spot.light.position, spot.cone));
    /// ```
    pub fn with_attenuation(self, a: Attenuation) -> SpotLight<Attenuation> {
        SpotLight {
            light: self.light.with_attenuation(a),
            cone: self.cone,
        }
    }
}

/// A point or spot light prepared: eye-space position, gains, falloff, and
/// the cone in eye space for a spot.
///
/// ```
/// use fixshade::light::SpotLight;
/// use fixshade::{illumination::InfiniteViewer, Lighting, Material, Mat4, Rgb, Unit3, Vec3};
/// let spot = SpotLight::new([0.0, 0.0, 2.0], [0.0, 0.0, -1.0], 20.0, 1.0).unwrap();
/// let m = Material::new().with_diffuse(Rgb::WHITE);
/// // `Lighting::new` prepares the spot: a `PreparedPoint<Attenuation, true>`.
/// let l: Lighting<_, InfiniteViewer, _> = Lighting::new(&m, Rgb::BLACK, &spot, &Mat4::IDENTITY);
/// let lit = |x| l.shade(Vec3::from_f32(x, 0.0, 0.0).unwrap(), Unit3::Z).to_bits()[0];
/// assert_eq!(lit(0.0), 1 << 16); // on the axis, 2 units below the spot
/// assert_eq!(lit(1.5), 0); // 37° off the axis: outside the 20° cone
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PreparedPoint<A: Falloff, const SPOT: bool> {
    pos: [i64; 3],
    gains: Gains,
    att: A::Prepared,
    cone: SpotCone,
    /// `pos` where it fits `i32`.
    pos32: Option<[i32; 3]>,
}

/// `p` where each coordinate fits `i32`.
#[inline(always)]
fn fits_i32(p: &[i64; 3]) -> Option<[i32; 3]> {
    let c = |i: usize| i32::try_from(p[i]).ok();
    Some([c(0)?, c(1)?, c(2)?])
}

/// The factor `s·f` (`Q.15`) and direction of a point-like light at `pos`
/// (eye space, `I40F24`) seen from the surface; `None` where `d = 0` or
/// where the surface faces away from the light.
#[inline(always)]
fn point_factor<A: Falloff, const SPOT: bool>(
    ctx: &Surface,
    pos: &[i64; 3],
    att: &A::Prepared,
    cone: &SpotCone,
) -> Option<(Unit3, u32)> {
    let p = ctx.position.to_bits();
    // |pos| ≤ 2^62, |p| < 2^31: the difference cannot overflow.
    let v = [0, 1, 2].map(|i| pos[i] - p[i] as i64);
    if faces_away(ctx.normal, &v) {
        return None;
    }
    let (l, d) = light_vector(v)?;
    let mut sf = A::factor(att, d);
    if SPOT {
        let delta = l.neg().half_dist_sq(cone.axis);
        if delta > cone.delta_cutoff {
            return None;
        }
        let s = pow_from_delta(delta, cone.exponent) as u32;
        sf = (s * sf + (1 << 14)) >> 15;
    }
    Some((l, sf))
}

/// Whether `N·v ≤ 0` for a light `v` away (`I40F24` raw) within 128
/// units (every component fits `i32`), so that the light adds nothing
/// (SPEC.md 3: no term where `N·L ≤ 0`): the exact sign, decided before
/// `v` is normalised. (From the normalised `L` the sign is the same but
/// where `|N·L|` is within its rounding, about 2⁻¹⁴, of 0: there the
/// model steps, and the exact sign is the reference's.) A farther light
/// is not tested here.
#[inline(always)]
fn faces_away(n: Unit3, v: &[i64; 3]) -> bool {
    if !v.iter().all(|c| c.unsigned_abs() < 1 << 31) {
        return false;
    }
    let b = n.to_bits();
    // |v_i| < 2^31, |n_i| ≤ 2^14: each product below 2^45.
    let dot = (0..3).fold(0i64, |s, i| s + mul_i32_i16(v[i] as i32, b[i]));
    dot <= 0
}

/// The unit vector and length of `v` (`I40F24` raw). Where every component
/// fits `i32` (the light within 128 units of the point, the usual case) the
/// 32-bit normalisation is used and the length is `v·l`: `l` is `v/|v|` to
/// within 0.52 ULP per component, so `v·l = |v|·(1 + ε)` with `|ε| < 2⁻¹⁴`,
/// far below what the attenuation needs. Otherwise the 64-bit path.
#[inline(always)]
fn light_vector(v: [i64; 3]) -> Option<(Unit3, u64)> {
    let fits = v.iter().all(|c| c.unsigned_abs() < 1 << 31);
    if !fits {
        return normalize_len(v);
    }
    let w = [v[0] as i32, v[1] as i32, v[2] as i32];
    let l = normalize(w)?;
    let b = l.to_bits();
    // |v_i| < 2^31, |l_i| ≤ 2^14: each product below 2^45.
    let dot = mul_i32_i16(w[0], b[0]) + mul_i32_i16(w[1], b[1]) + mul_i32_i16(w[2], b[2]);
    Some((l, (dot.max(0) >> 14) as u64))
}

/// [`point_factor`] at a point in the per-pixel form: the direction
/// towards the light, the dot product of `N`'s and its components, and
/// `s·f`; `None` where `d = 0`, where the surface faces away from the
/// light (the sign of the reduced vectors' dot product, which differs from
/// the exact one only where `|N·L|` is below about 2⁻¹³) or outside the
/// cone.
#[inline(always)]
fn point_factor_at<A: Falloff, const SPOT: bool>(
    at: &PixelSurface,
    pos: &[i64; 3],
    pos32: Option<[i32; 3]>,
    att: &A::Prepared,
    cone: &SpotCone,
) -> Option<(Dir, i32, u32)> {
    let p = at.position;
    // |pos| ≤ 2^62, |p| < 2^31: the difference cannot overflow. Where the
    // light's position fits i32 (`pos32`) and the difference too (the
    // usual case), in 32 bits.
    let near = pos32.and_then(|q| {
        let d = |i: usize| q[i].checked_sub(p[i]);
        Some([d(0)?, d(1)?, d(2)?])
    });
    let (d, s) = match near {
        Some(v) => Dir::reduce(v),
        None => Dir::reduce_wide([0, 1, 2].map(|i| pos[i] - p[i] as i64)),
    }?;
    let nl = Dir::dot_d(&d, &at.n);
    if nl <= 0 {
        return None;
    }
    let l = Dir::new(d);
    let mut sf = A::factor_of(att, || l.length(s));
    if SPOT {
        // 1 − cos γ with cos γ = −L·S (the axis in the per-pixel form
        // here: a draw without Phong shading keeps no code for it).
        let delta = one_minus_q28(-l.cos(&Dir::of_unit(cone.axis)));
        if delta > cone.delta_cutoff {
            return None;
        }
        let s = pow_from_delta(delta, cone.exponent) as u32;
        sf = (s * sf + (1 << 14)) >> 15;
    }
    Some((l, nl, sf))
}

impl<A: Falloff, const SPOT: bool> PreparedLights for PreparedPoint<A, SPOT> {
    #[inline]
    fn shade<S: Specular>(&self, ctx: &Surface, acc: &mut [u32; 3]) {
        if let Some((l, sf)) = point_factor::<A, SPOT>(ctx, &self.pos, &self.att, &self.cone) {
            add_light::<S>(ctx, l, sf, &self.gains, acc);
        }
    }
    const SCALAR: bool = true;
    #[inline]
    fn shade_at<S: Specular>(&self, at: &PixelSurface, acc: &mut [u32; 3]) {
        let (pos, pos32) = (&self.pos, self.pos32);
        if let Some((l, nl, sf)) = point_factor_at::<A, SPOT>(at, pos, pos32, &self.att, &self.cone)
        {
            add_light_at::<S>(at, &l, nl, sf, &self.gains, acc, |nl, v| {
                specular_delta_of::<S>(nl, at.cos_nv, l.cos(v))
            });
        }
    }
}

fn prepare_point<A: Falloff, const SPOT: bool>(
    view: &Mat4,
    l: &PointLight<A>,
    cone: SpotCone,
    kd: Rgb,
    ks: Rgb,
) -> PreparedPoint<A, SPOT> {
    let axis = dir_to_eye(view, cone.axis);
    let pos = point_to_eye(view, l.position.to_bits(), true);
    PreparedPoint {
        pos,
        pos32: fits_i32(&pos),
        gains: Gains::new(l.diffuse, l.specular, kd, ks),
        att: l.attenuation.prepare(),
        cone: SpotCone { axis, ..cone },
    }
}

impl<A: Falloff> LightSet for PointLight<A> {
    type Prepared = PreparedPoint<A, false>;
    fn prepare(&self, view: &Mat4, kd: Rgb, ks: Rgb) -> Self::Prepared {
        let no_cone = SpotCone {
            axis: Unit3::ZERO,
            delta_cutoff: 0,
            exponent: Exponent::ZERO,
        };
        prepare_point(view, self, no_cone, kd, ks)
    }
}

impl<A: Falloff> LightSet for SpotLight<A> {
    type Prepared = PreparedPoint<A, true>;
    fn prepare(&self, view: &Mat4, kd: Rgb, ks: Rgb) -> Self::Prepared {
        prepare_point(view, &self.light, self.cone, kd, ks)
    }
}

// ---------------------------------------------------------------------------
// Area
// ---------------------------------------------------------------------------

/// A rectangular area light (centre and two edge vectors), sampled as k × k
/// point lights at the centres of its cells, each carrying 1/k² of its
/// intensity (SPEC.md 3).
///
/// ```
/// use fixshade::light::AreaLight;
/// let panel = AreaLight::new([0.0, 3.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 3).unwrap();
/// assert!(AreaLight::new([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0).is_err());
/// # let _ = panel;
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AreaLight<A: Falloff = Attenuation> {
    /// Centre, world space.
    pub center: WidePoint,
    /// First edge vector (the rectangle spans `center ± edge_u/2 ± edge_v/2`).
    pub edge_u: WidePoint,
    /// Second edge vector.
    pub edge_v: WidePoint,
    /// Samples per edge, 1 ..= [`AreaLight::MAX_K`].
    pub samples_k: u8,
    /// Diffuse intensity of the whole light.
    pub diffuse: Rgb,
    /// Specular intensity of the whole light.
    pub specular: Rgb,
    /// Falloff of each sample.
    pub attenuation: A,
}

impl AreaLight<Attenuation> {
    /// The largest k: 4096 samples.
    ///
    /// ```
    /// use fixshade::light::{AreaLight, LightError};
    /// let (c, u, v) = ([0.0, 3.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    /// assert!(AreaLight::new(c, u, v, AreaLight::MAX_K).is_ok());
    /// assert_eq!(AreaLight::new(c, u, v, AreaLight::MAX_K + 1), Err(LightError::BadSamples));
    /// ```
    pub const MAX_K: u8 = 64;

    /// A white area light, attenuation `(1, 0, 0)`.
    ///
    /// ```
    /// use fixshade::light::{AreaLight, LightError};
    /// use fixshade::num::WidePoint;
    /// use fixshade::Rgb;
    /// let panel = AreaLight::new([0.0, 3.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 1.0], 4).unwrap();
    /// assert_eq!(panel.edge_u, WidePoint::from_f32([2.0, 0.0, 0.0]).unwrap());
    /// assert_eq!((panel.samples_k, panel.diffuse), (4, Rgb::WHITE));
    /// let far = AreaLight::new([0.0, 3.0e11, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 4);
    /// assert_eq!(far, Err(LightError::OutOfRange));
    /// ```
    pub fn new(
        center: [f32; 3],
        edge_u: [f32; 3],
        edge_v: [f32; 3],
        samples_k: u8,
    ) -> Result<Self, LightError> {
        if samples_k == 0 || samples_k > Self::MAX_K {
            return Err(LightError::BadSamples);
        }
        Ok(AreaLight {
            center: WidePoint::from_f32(center)?,
            edge_u: WidePoint::from_f32(edge_u)?,
            edge_v: WidePoint::from_f32(edge_v)?,
            samples_k,
            diffuse: Rgb::WHITE,
            specular: Rgb::WHITE,
            attenuation: Attenuation::NONE,
        })
    }
}

impl<A: Falloff> AreaLight<A> {
    /// Sets the diffuse intensity.
    ///
    /// ```
    /// use fixshade::light::AreaLight;
    /// use fixshade::Rgb;
    /// let panel = AreaLight::new([0.0, 3.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 2).unwrap();
    /// // The whole light's intensity: each of the k² samples carries 1/k² of it.
    /// let dim = panel.with_diffuse(Rgb::grey(0.5));
    /// assert_eq!(dim.diffuse.to_bits(), [1 << 15; 3]);
    /// assert_eq!(dim.specular, Rgb::WHITE);
    /// ```
    pub const fn with_diffuse(mut self, c: Rgb) -> Self {
        self.diffuse = c;
        self
    }
    /// Sets the specular intensity.
    ///
    /// ```
    /// use fixshade::light::AreaLight;
    /// use fixshade::Rgb;
    /// let panel = AreaLight::new([0.0, 3.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 2).unwrap();
    /// let matt = panel.with_specular(Rgb::BLACK);
    /// assert!(matt.specular.is_black());
    /// assert_eq!((matt.diffuse, matt.samples_k), (Rgb::WHITE, 2));
    /// ```
    pub const fn with_specular(mut self, c: Rgb) -> Self {
        self.specular = c;
        self
    }
    /// Sets the attenuation.
    ///
    /// ```
    /// use fixshade::light::{AreaLight, Attenuation};
    /// let panel = AreaLight::new([0.0, 3.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 3).unwrap();
    /// let a = Attenuation::new(1.0, 0.5, 0.0).unwrap();
    /// let dim = panel.with_attenuation(a);
    /// assert_eq!(dim.attenuation, a);
    /// assert_eq!((dim.center, dim.edge_v, dim.samples_k), (panel.center, panel.edge_v, 3));
    /// ```
    pub fn with_attenuation(self, a: Attenuation) -> AreaLight<Attenuation> {
        AreaLight {
            center: self.center,
            edge_u: self.edge_u,
            edge_v: self.edge_v,
            samples_k: self.samples_k,
            diffuse: self.diffuse,
            specular: self.specular,
            attenuation: a,
        }
    }
}

/// [`AreaLight`] prepared: the first sample and the steps between samples,
/// in eye space.
///
/// ```
/// use fixshade::light::{AreaLight, LightSet, PointLight};
/// use fixshade::{illumination::InfiniteViewer, Lighting, Material, Mat4, Rgb, Unit3, Vec3};
/// fn lit<L: LightSet>(lights: &L) -> u32 {
///     let m = Material::new().with_diffuse(Rgb::WHITE);
///     let l = Lighting::<_, InfiniteViewer, _>::new(&m, Rgb::BLACK, lights, &Mat4::IDENTITY);
///     l.shade(Vec3::ZERO, Unit3::Z).to_bits()[0]
/// }
/// // 4 × 4 samples, all at the centre (zero edges), 1/16 each: as one point light.
/// let area = AreaLight::new([0.0, 0.0, 2.0], [0.0; 3], [0.0; 3], 4).unwrap();
/// let lamp = PointLight::new([0.0, 0.0, 2.0]).unwrap();
/// assert!(lit(&area).abs_diff(lit(&lamp)) <= 1); // the sum is divided once
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PreparedArea<A: Falloff> {
    first: [i64; 3],
    step_u: [i64; 3],
    step_v: [i64; 3],
    k: u8,
    gains: Gains,
    att: A::Prepared,
}

impl<A: Falloff> LightSet for AreaLight<A> {
    type Prepared = PreparedArea<A>;
    fn prepare(&self, view: &Mat4, kd: Rgb, ks: Rgb) -> PreparedArea<A> {
        let k = self.samples_k.clamp(1, AreaLight::MAX_K) as i64;
        let c = point_to_eye(view, self.center.to_bits(), true);
        let u = point_to_eye(view, self.edge_u.to_bits(), false);
        let v = point_to_eye(view, self.edge_v.to_bits(), false);
        // Cell centre (i, j): c + ((i + ½)/k − ½)·u + ((j + ½)/k − ½)·v
        //                   = c + (1 − k)/(2k)·(u + v) + i·u/k + j·v/k.
        let div = |x: i64, d: i64| (x + x.signum() * d / 2) / d;
        // |c|, |u|, |v| ≤ 2^62: (1 − k)(u + v) needs i128 (up to 63·2^63);
        // the first sample is clamped to the WidePoint range like every
        // light position.
        let first = [0, 1, 2].map(|i| {
            let d = 2 * k as i128;
            let x = (1 - k as i128) * (u[i] as i128 + v[i] as i128);
            let off = (x + x.signum() * d / 2) / d;
            clamp_wide(c[i] as i128 + off)
        });
        PreparedArea {
            first,
            step_u: u.map(|x| div(x, k)),
            step_v: v.map(|x| div(x, k)),
            k: k as u8,
            // The whole light's gains: the 1/k² share is applied once to
            // the sum (see `PreparedArea::shade`).
            gains: Gains::new(self.diffuse, self.specular, kd, ks),
            att: self.attenuation.prepare(),
        }
    }
}

impl<A: Falloff> PreparedArea<A> {
    /// The cone of a sample: none.
    const NO_CONE: SpotCone = SpotCone {
        axis: Unit3::ZERO,
        delta_cutoff: 0,
        exponent: Exponent::ZERO,
    };

    /// Adds the light to `acc`, `sample(pos, sum)` adding the whole light's
    /// contribution from the sample at `pos` to `sum`.
    #[inline(always)]
    fn add_samples(&self, acc: &mut [u32; 3], mut sample: impl FnMut(&[i64; 3], &mut [u32; 3])) {
        // Each sample adds the whole light's contribution, rounded to Q.16
        // (error ≤ ½ unit); the sum is divided by k² once, rounded: the
        // mean of the k² roundings plus the division's stays within 1 Q.16
        // unit (2⁻¹⁶), for every k, where a share of 1/k² in each sample's
        // gain would add up to k²/2 units.
        //
        // Ranges: a gain is at most 256 (Gain::from_q32), so one sample
        // adds at most 2 · 256 · 2¹⁶ = 2²⁵ (diffuse and specular); a row of
        // k ≤ 64 samples at most 2³¹, so `row_sum` never saturates; k rows
        // at most 2³⁷ in u64.
        let k = self.k as u64;
        let mut sum = [0u64; 3];
        let mut row = self.first;
        for _ in 0..self.k {
            let mut pos = row;
            let mut row_sum = [0u32; 3];
            for _ in 0..self.k {
                sample(&pos, &mut row_sum);
                pos = [0, 1, 2].map(|i| step_wide(pos[i], self.step_v[i]));
            }
            for (s, r) in sum.iter_mut().zip(row_sum) {
                *s += r as u64;
            }
            row = [0, 1, 2].map(|i| step_wide(row[i], self.step_u[i]));
        }
        let k2 = k * k;
        for (a, s) in acc.iter_mut().zip(sum) {
            // (2^37 + 2^11) / k² < 2^32 for k ≥ 2; for k = 1 the sum is a
            // single sample, below 2^26.
            *a = a.saturating_add(((s + k2 / 2) / k2) as u32);
        }
    }
}

impl<A: Falloff> PreparedLights for PreparedArea<A> {
    fn shade<S: Specular>(&self, ctx: &Surface, acc: &mut [u32; 3]) {
        self.add_samples(acc, |pos, sum| {
            if let Some((l, sf)) = point_factor::<A, false>(ctx, pos, &self.att, &Self::NO_CONE) {
                add_light::<S>(ctx, l, sf, &self.gains, sum);
            }
        });
    }
    const SCALAR: bool = true;
    fn shade_at<S: Specular>(&self, at: &PixelSurface, acc: &mut [u32; 3]) {
        self.add_samples(acc, |pos, sum| {
            let f = point_factor_at::<A, false>(at, pos, fits_i32(pos), &self.att, &Self::NO_CONE);
            if let Some((l, nl, sf)) = f {
                add_light_at::<S>(at, &l, nl, sf, &self.gains, sum, |nl, v| {
                    specular_delta_of::<S>(nl, at.cos_nv, l.cos(v))
                });
            }
        });
    }
}

// ---------------------------------------------------------------------------
// Any light, and collections
// ---------------------------------------------------------------------------

/// A light whose kind is chosen at run time (scene files): pays for every
/// kind's code. Prefer the concrete types in firmware.
///
/// ```
/// use fixshade::light::{AnyLight, DirectionalLight, LightSet, PointLight};
/// use fixshade::{illumination::InfiniteViewer, Lighting, Material, Mat4, Rgb, Unit3, Vec3};
/// fn lit<L: LightSet>(lights: &L) -> [u32; 3] {
///     let m = Material::new();
///     let l = Lighting::<_, InfiniteViewer, _>::new(&m, Rgb::BLACK, lights, &Mat4::IDENTITY);
///     l.shade(Vec3::ZERO, Unit3::Z).to_bits()
/// }
/// let sun = DirectionalLight::new([0.0, 1.0, 1.0]).unwrap();
/// let lamp = PointLight::new([0.0, 0.0, 2.0]).unwrap().with_diffuse(Rgb::grey(0.5));
/// let any = [AnyLight::Directional(sun), AnyLight::Point(lamp)];
/// assert_eq!(lit(&any), lit(&(sun, lamp))); // the same colour as the concrete types
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AnyLight {
    /// A directional light.
    Directional(DirectionalLight),
    /// A point light.
    Point(PointLight),
    /// A spot light.
    Spot(SpotLight),
    /// An area light.
    Area(AreaLight),
}

/// [`AnyLight`] prepared.
///
/// ```
/// use fixshade::light::{AnyLight, LightSet, PointLight, PreparedAny};
/// use fixshade::{Mat4, Rgb};
/// let lamp = PointLight::new([0.0, 0.0, 2.0]).unwrap();
/// let view = Mat4::translation(fixshade::Vec3::from_f32(0.0, 0.0, -5.0).unwrap());
/// let any = AnyLight::Point(lamp).prepare(&view, Rgb::WHITE, Rgb::BLACK);
/// assert_eq!(any, PreparedAny::Point(lamp.prepare(&view, Rgb::WHITE, Rgb::BLACK)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PreparedAny {
    /// A directional light.
    Directional(PreparedDirectional),
    /// A point light.
    Point(PreparedPoint<Attenuation, false>),
    /// A spot light.
    Spot(PreparedPoint<Attenuation, true>),
    /// An area light.
    Area(PreparedArea<Attenuation>),
}

impl LightSet for AnyLight {
    type Prepared = PreparedAny;
    fn prepare(&self, view: &Mat4, kd: Rgb, ks: Rgb) -> PreparedAny {
        match self {
            AnyLight::Directional(l) => PreparedAny::Directional(l.prepare(view, kd, ks)),
            AnyLight::Point(l) => PreparedAny::Point(l.prepare(view, kd, ks)),
            AnyLight::Spot(l) => PreparedAny::Spot(l.prepare(view, kd, ks)),
            AnyLight::Area(l) => PreparedAny::Area(l.prepare(view, kd, ks)),
        }
    }
}

impl PreparedLights for PreparedAny {
    fn shade<S: Specular>(&self, ctx: &Surface, acc: &mut [u32; 3]) {
        match self {
            PreparedAny::Directional(l) => l.shade::<S>(ctx, acc),
            PreparedAny::Point(l) => l.shade::<S>(ctx, acc),
            PreparedAny::Spot(l) => l.shade::<S>(ctx, acc),
            PreparedAny::Area(l) => l.shade::<S>(ctx, acc),
        }
    }
    const SCALAR: bool = true;
    fn shade_at<S: Specular>(&self, at: &PixelSurface, acc: &mut [u32; 3]) {
        match self {
            PreparedAny::Directional(l) => l.shade_at::<S>(at, acc),
            PreparedAny::Point(l) => l.shade_at::<S>(at, acc),
            PreparedAny::Spot(l) => l.shade_at::<S>(at, acc),
            PreparedAny::Area(l) => l.shade_at::<S>(at, acc),
        }
    }
}

/// No lights at all: `E + A·Ka` only.
impl LightSet for () {
    type Prepared = ();
    fn prepare(&self, _: &Mat4, _: Rgb, _: Rgb) {}
}

impl PreparedLights for () {
    const EMPTY: bool = true;
    const READS_POSITION: bool = false;
    #[inline(always)]
    fn shade<S: Specular>(&self, _: &Surface, _: &mut [u32; 3]) {}
    const SCALAR: bool = true;
}

macro_rules! tuple_sets {
    ($(($($t:ident $i:tt),+)),+ $(,)?) => {$(
        impl<$($t: LightSet),+> LightSet for ($($t,)+) {
            type Prepared = ($($t::Prepared,)+);
            fn prepare(&self, view: &Mat4, kd: Rgb, ks: Rgb) -> Self::Prepared {
                ($(self.$i.prepare(view, kd, ks),)+)
            }
        }
        impl<$($t: PreparedLights),+> PreparedLights for ($($t,)+) {
            const EMPTY: bool = $($t::EMPTY)&&+;
            const READS_POSITION: bool = $($t::READS_POSITION)||+;
            #[inline]
            fn shade<S: Specular>(&self, ctx: &Surface, acc: &mut [u32; 3]) {
                $(self.$i.shade::<S>(ctx, acc);)+
            }
            const SCALAR: bool = $($t::SCALAR)&&+;
            #[inline]
            fn shade_at<S: Specular>(&self, at: &PixelSurface, acc: &mut [u32; 3]) {
                $(self.$i.shade_at::<S>(at, acc);)+
            }
        }
    )+};
}

tuple_sets!(
    (A 0),
    (A 0, B 1),
    (A 0, B 1, C 2),
    (A 0, B 1, C 2, D 3),
    (A 0, B 1, C 2, D 3, E 4),
    (A 0, B 1, C 2, D 3, E 4, F 5),
    (A 0, B 1, C 2, D 3, E 4, F 5, G 6),
    (A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7),
);

impl<L: LightSet, const N: usize> LightSet for [L; N] {
    type Prepared = [L::Prepared; N];
    fn prepare(&self, view: &Mat4, kd: Rgb, ks: Rgb) -> Self::Prepared {
        self.each_ref().map(|l| l.prepare(view, kd, ks))
    }
}

impl<P: PreparedLights, const N: usize> PreparedLights for [P; N] {
    const EMPTY: bool = P::EMPTY || N == 0;
    const READS_POSITION: bool = P::READS_POSITION && N > 0;
    #[inline]
    fn shade<S: Specular>(&self, ctx: &Surface, acc: &mut [u32; 3]) {
        for l in self {
            l.shade::<S>(ctx, acc);
        }
    }
    const SCALAR: bool = P::SCALAR;
    #[inline]
    fn shade_at<S: Specular>(&self, at: &PixelSurface, acc: &mut [u32; 3]) {
        for l in self {
            l.shade_at::<S>(at, acc);
        }
    }
}

impl<L: LightSet, const N: usize> LightSet for heapless::Vec<L, N> {
    type Prepared = heapless::Vec<L::Prepared, N>;
    fn prepare(&self, view: &Mat4, kd: Rgb, ks: Rgb) -> Self::Prepared {
        let mut out = heapless::Vec::new();
        for l in self {
            // Same capacity as `self`: a push cannot fail.
            let _ = out.push(l.prepare(view, kd, ks));
        }
        out
    }
}

impl<P: PreparedLights, const N: usize> PreparedLights for heapless::Vec<P, N> {
    const READS_POSITION: bool = P::READS_POSITION;
    #[inline]
    fn shade<S: Specular>(&self, ctx: &Surface, acc: &mut [u32; 3]) {
        for l in self {
            l.shade::<S>(ctx, acc);
        }
    }
    const SCALAR: bool = P::SCALAR;
    #[inline]
    fn shade_at<S: Specular>(&self, at: &PixelSurface, acc: &mut [u32; 3]) {
        for l in self {
            l.shade_at::<S>(at, acc);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{faces_away, unit_from_f64};
    use crate::tests::xorshift;

    /// `faces_away` is the exact sign of `N·v` for a light within `i32`
    /// (ties, `N·v = 0`, included), and never says so of a farther one.
    #[test]
    fn faces_away_is_the_exact_sign() {
        let mut next = xorshift(0x3c6e_f372_fe94_f82b);
        let mut signed = |bits: u64| {
            let m = next() >> (64 - bits);
            if next() & 1 == 0 {
                m as i64
            } else {
                -(m as i64)
            }
        };
        let (mut away, mut toward) = (0, 0);
        for i in 0..200_000 {
            let Ok(n) = unit_from_f64([0, 1, 2].map(|_| signed(20) as f64)) else {
                continue;
            };
            let b = n.to_bits();
            // Within i32 mostly; ties from a vector across the normal.
            let mut v = [0, 1, 2].map(|_| signed(1 + (i % 31) as u64));
            if i % 5 == 0 {
                v = [b[1] as i64 * 3, -(b[0] as i64) * 3, 0];
            }
            if i % 97 == 0 {
                v[i % 3] = 1 << 31;
            }
            let fits = v.iter().all(|c| c.unsigned_abs() < 1 << 31);
            let dot: i128 = (0..3).map(|k| v[k] as i128 * b[k] as i128).sum();
            let want = fits && dot <= 0;
            assert_eq!(faces_away(n, &v), want, "{v:?} {b:?}");
            if want {
                away += 1;
            } else {
                toward += 1;
            }
        }
        assert!(away > 50_000 && toward > 50_000, "{away} {toward}");
    }
}

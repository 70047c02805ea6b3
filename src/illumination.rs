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
use crate::light_term::PixelSurface;
use crate::material::{Material, Specular};
use crate::normalize::{normalize, Dir};
use crate::specular_table::Exponent;
use crate::vector::{Mat4, Unit3, Vec3};

pub use crate::light_term::{add_light, Gain, Gains, Surface, FACTOR_ONE};

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

    /// The colour at eye-space point `p` (raw `I8F24`) with the normal
    /// `normal` (any scale: Phong shading's interpolated one; zero lights
    /// nothing but `E + A·Ka`), clamped to [0, 1]: the equation per pixel.
    /// Light sets of the crate take it in the per-pixel form (`N`, `V`
    /// and each `L` as [`Dir`]s, the cosines from their reciprocal lengths,
    /// [`PreparedLights::shade_at`]); others through [`Lighting::shade`]
    /// with the unit vectors made here.
    #[inline]
    pub(crate) fn shade_pixel(&self, p: [i32; 3], normal: [i32; 3]) -> Shade {
        if !<L::Prepared as PreparedLights>::SCALAR {
            let n = normalize(normal).unwrap_or(Unit3::ZERO);
            return self.shade(Vec3::from_bits(p[0], p[1], p[2]), n);
        }
        let mut acc = self.base;
        if let Some((n, _)) = Dir::reduce(normal) {
            let n = Dir::new(n);
            let view = if !S::ENABLED {
                None
            } else if V::LOCAL {
                // −P; saturating, as `view_dir`'s.
                // (`max` then a wrapping negation: the saturating one, in
                // fewer instructions on ARMv6-M.)
                Dir::reduce(p.map(|c| c.max(-i32::MAX).wrapping_neg())).map(|(v, _)| Dir::new(v))
            } else {
                Some(Dir::Z)
            };
            let at = PixelSurface {
                position: p,
                n,
                cos_nv: match &view {
                    Some(_) if !V::LOCAL => n.cos_z(),
                    Some(v) => n.cos(v),
                    None => 0,
                },
                view,
                shininess: self.shininess,
                view_z: !V::LOCAL,
            };
            self.lights.shade_at::<S>(&at, &mut acc);
        }
        Shade::from_bits(
            acc[0].min(SHADE_ONE),
            acc[1].min(SHADE_ONE),
            acc[2].min(SHADE_ONE),
        )
    }

    /// Whether [`Lighting::shade`] reads its position: a light that does
    /// (a point-like one), or the local viewer's `V` for a specular term.
    /// Where it does not, a caller may pass any position.
    pub(crate) const READS_POSITION: bool =
        <L::Prepared as PreparedLights>::READS_POSITION || (S::ENABLED && V::LOCAL);

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
    /// vector, normalised once when the light is prepared, gives the colour
    /// of the general path ([`add_light`], which takes `1 − N·H` from the
    /// angle between `N` and `L + V` at every call) within 32 units of
    /// 2⁻¹⁶ (a 64th of a 5-bit step; 21 measured), over random normals and
    /// directions, including a light straight behind the surface (`L =
    /// −V`, where `H` is undefined).
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
        let (mut checked, mut worst) = (0, 0);
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
                    let once = lighting.shade(Vec3::ZERO, n).to_bits();
                    for c in 0..3 {
                        worst = worst.max(once[c].abs_diff(general[c]));
                    }
                    assert!(
                        (0..3).all(|c| once[c].abs_diff(general[c]) <= 32),
                        "light {d:?} normal {:?} n = {shininess}: {once:?} {general:?}",
                        n.to_bits()
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 30_000, "{checked} cases");
        println!("{checked} cases, worst difference {worst} units of 2^-16");
    }
}

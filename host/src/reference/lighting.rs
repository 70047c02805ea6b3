//! The illumination model of SPEC.md section 3, in `f64`, in eye space.
//!
//! Decisions where SPEC.md is silent (the kernel follows the same ones):
//!
//! * A zero-length normal makes `N·L = 0` for every light: no diffuse and no
//!   specular (emission and ambient remain). Otherwise the normal is
//!   normalised here.
//! * A point or spot light at distance `d = 0` from the point contributes
//!   nothing. An attenuation denominator of exactly 0 gives `f = 1`;
//!   otherwise `f = min(1, 1/den)`.
//! * Spot: `cosγ = (−L)·S`; `s = 0` if `cosγ < cos(cutoff)`, else `cosγ^p`.
//! * Infinite viewer `V = (0, 0, 1)`; local viewer `V = normalise(−P)`, and at
//!   `P = 0` the specular term is 0.
//! * Phong `R = 2(N·L)N − L`, `spec = max(R·V, 0)^n`; Blinn
//!   `H = normalise(L + V)` (`L + V = 0` gives `spec = 0`),
//!   `spec = max(N·H, 0)^n`; `spec = 0` where `N·L ≤ 0`.
//! * `x^0 = 1`, also for `x = 0`.
//! * An area light becomes `k × k` point lights at its cell centres
//!   `center + ((i + ½)/k − ½)·edge_u + ((j + ½)/k − ½)·edge_v`, each with
//!   1/k² of the intensities and the same attenuation.

use super::math::{add, dot, length, normalize, scale, sub, transform_dir, transform_point};
use crate::scene_desc::{LightDesc, MaterialDesc, SpecularModel, Viewer};

/// A light in eye space, ready for [`illuminate`]. Built by [`eye_lights`].
///
/// ```
/// use fixshade_host::reference::{eye_lights, look_at, EyeLight};
/// use fixshade_host::scene_desc::{LightDesc, DEFAULT_ATTENUATION, WHITE};
/// let view = look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0]); // a shift by −5 along Z
/// let spot = LightDesc::Spot { position: [0.0, 2.0, 0.0], axis: [0.0, -3.0, 0.0],
///     cutoff_deg: 90.0, exponent: 1.0, diffuse: WHITE, specular: WHITE,
///     attenuation: DEFAULT_ATTENUATION };
/// let lights = eye_lights(&[spot], &view);
/// let [EyeLight::Spot { position, axis, cos_cutoff, .. }] = &lights[..] else { panic!() };
/// assert_eq!(*position, [0.0, 2.0, -5.0]);
/// assert_eq!((*axis, *cos_cutoff), ([0.0, -1.0, 0.0], 0.0)); // unit axis; cos 90° is exactly 0
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum EyeLight {
    /// A light at infinity.
    Directional {
        /// Unit vector towards the light (eye space).
        to_light: [f64; 3],
        /// Diffuse intensity `Id`.
        diffuse: [f64; 3],
        /// Specular intensity `Is`.
        specular: [f64; 3],
    },
    /// A point light.
    Point {
        /// Position (eye space).
        position: [f64; 3],
        /// Diffuse intensity `Id`.
        diffuse: [f64; 3],
        /// Specular intensity `Is`.
        specular: [f64; 3],
        /// Attenuation `[c0, c1, c2]`.
        attenuation: [f64; 3],
    },
    /// A spot light.
    Spot {
        /// Position (eye space).
        position: [f64; 3],
        /// Unit axis, the direction the spot shines (eye space).
        axis: [f64; 3],
        /// Cosine of the cutoff angle.
        cos_cutoff: f64,
        /// Spot exponent `p`.
        exponent: f64,
        /// Diffuse intensity `Id`.
        diffuse: [f64; 3],
        /// Specular intensity `Is`.
        specular: [f64; 3],
        /// Attenuation `[c0, c1, c2]`.
        attenuation: [f64; 3],
    },
}

/// Lights already transformed into eye space (what [`eye_lights`] returns).
///
/// ```
/// use fixshade_host::reference::{eye_lights, look_at, EyeLight, EyeLights};
/// use fixshade_host::scene_desc::{LightDesc, DEFAULT_ATTENUATION};
/// let view = look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0]);
/// let (edge_u, edge_v) = ([2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
/// let area = LightDesc::Area { center: [0.0; 3], edge_u, edge_v, samples_k: 2,
///     diffuse: [1.0; 3], specular: [0.5; 3], attenuation: DEFAULT_ATTENUATION };
/// let lights: EyeLights = eye_lights(&[area], &view);
/// assert_eq!(lights.len(), 2 * 2); // k × k point lights
/// let EyeLight::Point { position, diffuse, .. } = &lights[0] else { panic!() };
/// assert_eq!((*position, *diffuse), ([-0.5, -0.5, -5.0], [0.25; 3])); // a cell centre, 1/k²
/// ```
pub type EyeLights = Vec<EyeLight>;

/// Everything [`illuminate`] needs besides the point and the normal.
///
/// ```
/// use fixshade_host::reference::{illuminate, EyeLight, LightingModel};
/// use fixshade_host::scene_desc::{MaterialDesc, SpecularModel, Viewer};
/// let material = MaterialDesc { emission: [0.1, 0.0, 0.0], ..MaterialDesc::default() };
/// let lights = [EyeLight::Directional { to_light: [0.0, 0.0, 1.0], diffuse: [1.0; 3],
///     specular: [1.0; 3] }];
/// let m = LightingModel { material: &material, global_ambient: [0.5; 3], lights: &lights,
///     specular_model: SpecularModel::Blinn, viewer: Viewer::Infinite };
/// // A zero normal: E + A·Ka only (0.1 + 0.5 · 0.2 in red), no diffuse or specular.
/// let c = illuminate(&m, [0.0, 0.0, -1.0], [0.0; 3]);
/// assert!((c[0] - 0.2).abs() < 1e-12 && (c[1] - 0.1).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct LightingModel<'a> {
    /// The material.
    pub material: &'a MaterialDesc,
    /// Global ambient intensity `A`.
    pub global_ambient: [f64; 3],
    /// Lights in eye space.
    pub lights: &'a [EyeLight],
    /// Phong or Blinn–Phong specular.
    pub specular_model: SpecularModel,
    /// Local or infinite viewer.
    pub viewer: Viewer,
}

/// Transforms world-space lights into eye space with the view matrix `view`
/// (row-major, column vectors).
///
/// Positions are transformed as points; directions and spot axes by the
/// view's 3 × 3 part, then normalised (a zero vector stays zero). The cutoff
/// becomes its cosine (exactly 0 for 90°). An area light expands to `k × k`
/// point lights at its cell centres, each carrying `1/k²` of its diffuse and
/// specular intensity.
///
/// ```
/// use fixshade_host::reference::{eye_lights, look_at, EyeLight};
/// use fixshade_host::scene_desc::LightDesc;
/// let view = look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0]);
/// let lights = eye_lights(&[LightDesc::point([0.0, 0.0, 1.0])], &view);
/// match &lights[0] {
///     EyeLight::Point { position, .. } => assert!((position[2] + 4.0).abs() < 1e-12),
///     _ => unreachable!(),
/// }
/// ```
pub fn eye_lights(lights: &[LightDesc], view: &[[f64; 4]; 4]) -> Vec<EyeLight> {
    let mut out = Vec::with_capacity(lights.len());
    for light in lights {
        match light {
            LightDesc::Directional {
                direction,
                diffuse,
                specular,
            } => out.push(EyeLight::Directional {
                to_light: normalize(transform_dir(view, *direction)),
                diffuse: *diffuse,
                specular: *specular,
            }),
            LightDesc::Point {
                position,
                diffuse,
                specular,
                attenuation,
            } => out.push(EyeLight::Point {
                position: transform_point(view, *position),
                diffuse: *diffuse,
                specular: *specular,
                attenuation: *attenuation,
            }),
            LightDesc::Spot {
                position,
                axis,
                cutoff_deg,
                exponent,
                diffuse,
                specular,
                attenuation,
            } => out.push(EyeLight::Spot {
                position: transform_point(view, *position),
                axis: normalize(transform_dir(view, *axis)),
                cos_cutoff: cos_deg(*cutoff_deg),
                exponent: *exponent,
                diffuse: *diffuse,
                specular: *specular,
                attenuation: *attenuation,
            }),
            LightDesc::Area {
                center,
                edge_u,
                edge_v,
                samples_k,
                diffuse,
                specular,
                attenuation,
            } => {
                let k = (*samples_k).max(1);
                let kf = f64::from(k);
                let share = 1.0 / (kf * kf);
                for i in 0..k {
                    let a = (f64::from(i) + 0.5) / kf - 0.5;
                    for j in 0..k {
                        let b = (f64::from(j) + 0.5) / kf - 0.5;
                        let world = add(add(*center, scale(*edge_u, a)), scale(*edge_v, b));
                        out.push(EyeLight::Point {
                            position: transform_point(view, world),
                            diffuse: scale(*diffuse, share),
                            specular: scale(*specular, share),
                            attenuation: *attenuation,
                        });
                    }
                }
            }
        }
    }
    out
}

/// Cosine of an angle in degrees, exact at 0° and 90°.
fn cos_deg(deg: f64) -> f64 {
    if deg == 90.0 {
        0.0
    } else {
        deg.to_radians().cos()
    }
}

/// `x^e` with `x^0 = 1` for every `x` (including 0).
fn pow0(x: f64, e: f64) -> f64 {
    if e == 0.0 {
        1.0
    } else {
        x.powf(e)
    }
}

/// `min(1, 1/den)`, with `f = 1` where the denominator is exactly 0.
fn attenuation_factor(c: [f64; 3], d: f64) -> f64 {
    let den = c[0] + c[1] * d + c[2] * d * d;
    if den == 0.0 {
        1.0
    } else {
        (1.0 / den).min(1.0)
    }
}

/// Evaluates SPEC.md section 3 at eye-space point `p` with normal `n`.
///
/// `n` is the normal to use, already negated by the caller for a lit back
/// face; it is normalised here (zero length: no diffuse or specular). The
/// result is clamped to [0, 1] per channel. [`illuminate_with_margin`] also
/// says how close the point is to a step of the model.
///
/// ```
/// use fixshade_host::reference::{illuminate, EyeLight, LightingModel};
/// use fixshade_host::scene_desc::{MaterialDesc, SpecularModel, Viewer};
/// let material = MaterialDesc::default();
/// let lights = [EyeLight::Directional {
///     to_light: [0.0, 0.0, 1.0], diffuse: [1.0; 3], specular: [1.0; 3],
/// }];
/// let m = LightingModel {
///     material: &material, global_ambient: [0.2; 3], lights: &lights,
///     specular_model: SpecularModel::Blinn, viewer: Viewer::Infinite,
/// };
/// let c = illuminate(&m, [0.0, 0.0, -2.0], [0.0, 0.0, 1.0]);
/// assert!((c[0] - (0.2 * 0.2 + 0.8)).abs() < 1e-12);
/// ```
pub fn illuminate(m: &LightingModel, p: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    illuminate_with_margin(m, p, n).0
}

/// [`illuminate`], and the point's distance from the nearest step of the
/// model (SPEC.md 7), `f64::INFINITY` where there is none.
///
/// The equation jumps, rather than changing continuously, in two places:
/// at a spot's cone edge (the spot factor falls from `cos(cutoff)^p` to 0
/// where `cosγ` crosses `cos(cutoff)`) and at a specular term's cut-off
/// (the specular term falls to 0 where `N·L` crosses 0). A fixed-point
/// evaluation that lands on the other side of such a step differs by the
/// step's height, however small its own error, so the error measure counts
/// those pixels apart. The margin is the smallest of `|cosγ − cos(cutoff)|`
/// over the spots whose step has a height here (`N·L > 0`, so the spot
/// lights the point on its inner side, and `cos(cutoff)^p > 0`) and `|N·L|`
/// over the lights whose specular term has a height here (inside any cone,
/// a non-zero `Is·Ks` and specular base). A zero normal lights nothing:
/// no step.
///
/// ```
/// use fixshade_host::reference::{illuminate_with_margin, EyeLight, LightingModel};
/// use fixshade_host::scene_desc::{MaterialDesc, SpecularModel, Viewer};
/// let material = MaterialDesc { specular: [0.5; 3], shininess: 8.0, ..MaterialDesc::default() };
/// // A spot 1 unit above the origin shining down, 30° cone; points on the
/// // plane y = 0 facing up.
/// let lights = [EyeLight::Spot {
///     position: [0.0, 1.0, 0.0], axis: [0.0, -1.0, 0.0], cos_cutoff: 30f64.to_radians().cos(),
///     exponent: 1.0, diffuse: [1.0; 3], specular: [0.0; 3], attenuation: [1.0, 0.0, 0.0],
/// }];
/// let m = LightingModel { material: &material, global_ambient: [0.0; 3], lights: &lights,
///     specular_model: SpecularModel::Blinn, viewer: Viewer::Infinite };
/// let up = [0.0, 1.0, 0.0];
/// let (_, centre) = illuminate_with_margin(&m, [0.0; 3], up);
/// assert!((centre - (1.0 - 30f64.to_radians().cos())).abs() < 1e-12); // cosγ = 1
/// let edge = 30f64.to_radians().tan();
/// let (_, at_edge) = illuminate_with_margin(&m, [edge + 1e-9, 0.0, 0.0], up);
/// assert!(at_edge < 1e-9);
/// // Seen from below, the spot does not light the point on either side.
/// let (_, below) = illuminate_with_margin(&m, [edge, 0.0, 0.0], [0.0, -1.0, 0.0]);
/// assert_eq!(below, f64::INFINITY);
/// ```
pub fn illuminate_with_margin(m: &LightingModel, p: [f64; 3], n: [f64; 3]) -> ([f64; 3], f64) {
    let mat = m.material;
    let mut out: [f64; 3] =
        std::array::from_fn(|c| mat.emission[c] + m.global_ambient[c] * mat.ambient[c]);
    let mut margin = f64::INFINITY;
    let n_len = length(n);
    if n_len > 0.0 && n_len.is_finite() {
        let n = scale(n, 1.0 / n_len);
        let v = match m.viewer {
            Viewer::Infinite => Some([0.0, 0.0, 1.0]),
            Viewer::Local => {
                let minus_p = scale(p, -1.0);
                let len = length(minus_p);
                (len > 0.0).then(|| scale(minus_p, 1.0 / len))
            }
        };
        let ks_on = mat.specular.iter().any(|&k| k > 0.0);
        for light in m.lights {
            let Some(LightTerms {
                l,
                f,
                s,
                id,
                is,
                cone,
            }) = light_terms(light, p)
            else {
                continue;
            };
            let n_dot_l = dot(n, l);
            if let Some(Cone {
                cos_gamma,
                cos_cutoff,
                edge,
            }) = cone
            {
                if n_dot_l > 0.0 && edge > 0.0 {
                    margin = margin.min((cos_gamma - cos_cutoff).abs());
                }
            }
            if cone.is_some_and(|c| c.cos_gamma < c.cos_cutoff) {
                // Outside the cone: no light, and no specular step.
                continue;
            }
            let spec = match v {
                None => 0.0,
                Some(v) => specular_base(m, n, l, v, n_dot_l),
            };
            if ks_on && is.iter().any(|&x| x > 0.0) && s * f * spec > 0.0 {
                margin = margin.min(n_dot_l.abs());
            }
            if n_dot_l <= 0.0 {
                continue;
            }
            for (c, o) in out.iter_mut().enumerate() {
                *o += s * f * (id[c] * mat.diffuse[c] * n_dot_l + is[c] * mat.specular[c] * spec);
            }
        }
    }
    let colour = out.map(|x| if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) });
    (colour, margin)
}

/// The specular base raised to the shininess: Phong `max(R·V, 0)^n` with
/// `R = 2(N·L)N − L`, Blinn `max(N·H, 0)^n` with `H = normalise(L + V)`
/// (0 where `L + V = 0`). Evaluated for either sign of `N·L`: the caller
/// uses it as the height of the specular step at `N·L = 0` as well as the
/// term where `N·L > 0`.
fn specular_base(m: &LightingModel, n: [f64; 3], l: [f64; 3], v: [f64; 3], n_dot_l: f64) -> f64 {
    let shininess = m.material.shininess;
    match m.specular_model {
        SpecularModel::Phong => {
            let r = sub(scale(n, 2.0 * n_dot_l), l);
            pow0(dot(r, v).max(0.0), shininess)
        }
        SpecularModel::Blinn => {
            let h = add(l, v);
            let h_len = length(h);
            if h_len > 0.0 {
                pow0(dot(n, scale(h, 1.0 / h_len)).max(0.0), shininess)
            } else {
                0.0
            }
        }
    }
}

/// Where a point lies against a spot's cone.
#[derive(Clone, Copy)]
struct Cone {
    /// `cosγ = (−L)·S`.
    cos_gamma: f64,
    cos_cutoff: f64,
    /// The spot factor just inside the edge, `cos(cutoff)^p`: the step's
    /// height (0 for a 90° cone with `p > 0`, where there is no step).
    edge: f64,
}

/// The per-light quantities of the equation at one point.
struct LightTerms {
    /// Unit vector towards the light.
    l: [f64; 3],
    /// Attenuation factor.
    f: f64,
    /// Spot factor.
    s: f64,
    /// Diffuse intensity.
    id: [f64; 3],
    /// Specular intensity.
    is: [f64; 3],
    /// For a spot, where the point lies against its cone.
    cone: Option<Cone>,
}

/// The terms of one light at `p`, or `None` where it contributes nothing
/// and has no step (light on the point). Outside a spot's cone the spot
/// factor `s` is 0.
fn light_terms(light: &EyeLight, p: [f64; 3]) -> Option<LightTerms> {
    match light {
        EyeLight::Directional {
            to_light,
            diffuse,
            specular,
        } => Some(LightTerms {
            l: *to_light,
            f: 1.0,
            s: 1.0,
            id: *diffuse,
            is: *specular,
            cone: None,
        }),
        EyeLight::Point {
            position,
            diffuse,
            specular,
            attenuation,
        } => {
            let (l, d) = towards(*position, p)?;
            Some(LightTerms {
                l,
                f: attenuation_factor(*attenuation, d),
                s: 1.0,
                id: *diffuse,
                is: *specular,
                cone: None,
            })
        }
        EyeLight::Spot {
            position,
            axis,
            cos_cutoff,
            exponent,
            diffuse,
            specular,
            attenuation,
        } => {
            let (l, d) = towards(*position, p)?;
            let cos_gamma = -dot(l, *axis);
            let s = if cos_gamma < *cos_cutoff {
                0.0
            } else {
                pow0(cos_gamma.max(0.0), *exponent)
            };
            Some(LightTerms {
                l,
                f: attenuation_factor(*attenuation, d),
                s,
                id: *diffuse,
                is: *specular,
                cone: Some(Cone {
                    cos_gamma,
                    cos_cutoff: *cos_cutoff,
                    edge: pow0(cos_cutoff.max(0.0), *exponent),
                }),
            })
        }
    }
}

/// Unit vector from `p` to `light` and the distance, or `None` at distance 0.
fn towards(light: [f64; 3], p: [f64; 3]) -> Option<([f64; 3], f64)> {
    let d = sub(light, p);
    let len = length(d);
    (len > 0.0 && len.is_finite()).then(|| (scale(d, 1.0 / len), len))
}

//! The material: emission, ambient, diffuse and specular colours, and the
//! shininess, with the specular model chosen by type.
//!
//! The specular term is a type parameter of [`Material`]: [`NoSpecular`]
//! (the default), [`BlinnPhong`] (`(N·H)^n`) or [`Phong`] (`(R·V)^n`). A
//! material without specular compiles neither the specular table nor any of
//! the specular arithmetic: the code that evaluates it is guarded by
//! [`Specular::ENABLED`], a constant that monomorphisation folds away.

use crate::color::Rgb;
use crate::specular_table::Exponent;

/// A specular term: which model, and its colour and shininess.
///
/// Implemented by [`NoSpecular`], [`BlinnPhong`] and [`Phong`]; the
/// illumination code reads only these items, so the choice costs nothing at
/// run time.
///
/// ```
/// use fixshade::material::{BlinnPhong, NoSpecular, Phong, Specular};
/// use fixshade::{Exponent, Rgb};
/// assert!(BlinnPhong::ENABLED && BlinnPhong::BLINN);
/// assert!(Phong::ENABLED && !Phong::BLINN);
/// let p = Phong { color: Rgb::WHITE, shininess: Exponent::from_int(8) };
/// assert_eq!((p.color(), p.shininess()), (Rgb::WHITE, Exponent::from_int(8)));
/// assert_eq!((NoSpecular.color(), NoSpecular.shininess()), (Rgb::BLACK, Exponent::ZERO));
/// ```
pub trait Specular: Copy {
    /// Whether the term exists at all (false only for [`NoSpecular`]).
    const ENABLED: bool;
    /// `true` for Blinn–Phong `(N·H)^n`, `false` for Phong `(R·V)^n`.
    const BLINN: bool;
    /// The specular colour `Ks`.
    fn color(&self) -> Rgb;
    /// The shininess `n`.
    fn shininess(&self) -> Exponent;
}

/// No specular term: the scene pays nothing for specular highlights.
///
/// ```
/// use fixshade::material::{Material, NoSpecular, Specular};
/// let m: Material<NoSpecular> = Material::new();
/// assert!(!NoSpecular::ENABLED);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct NoSpecular;

impl Specular for NoSpecular {
    const ENABLED: bool = false;
    const BLINN: bool = false;
    fn color(&self) -> Rgb {
        Rgb::BLACK
    }
    fn shininess(&self) -> Exponent {
        Exponent::ZERO
    }
}

/// Blinn–Phong specular: `Ks · max(N·H, 0)^n` with `H = normalise(L + V)`.
///
/// ```
/// use fixshade::{Material, Rgb};
/// use fixshade::material::BlinnPhong;
/// use fixshade::Exponent;
/// let m = Material::new().with_specular(BlinnPhong {
///     color: Rgb::grey(0.5),
///     shininess: Exponent::from_int(32),
/// });
/// assert_eq!(m.specular.shininess, Exponent::from_int(32));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct BlinnPhong {
    /// Specular colour `Ks`.
    pub color: Rgb,
    /// Shininess `n`.
    pub shininess: Exponent,
}

impl Specular for BlinnPhong {
    const ENABLED: bool = true;
    const BLINN: bool = true;
    fn color(&self) -> Rgb {
        self.color
    }
    fn shininess(&self) -> Exponent {
        self.shininess
    }
}

/// Phong specular: `Ks · max(R·V, 0)^n` with `R = 2(N·L)N − L`.
///
/// ```
/// use fixshade::{Material, Rgb};
/// use fixshade::material::Phong;
/// use fixshade::Exponent;
/// let m = Material::new().with_specular(Phong { color: Rgb::WHITE, shininess: Exponent::from_int(100) });
/// assert_eq!(m.specular.color, Rgb::WHITE);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Phong {
    /// Specular colour `Ks`.
    pub color: Rgb,
    /// Shininess `n`.
    pub shininess: Exponent,
}

impl Specular for Phong {
    const ENABLED: bool = true;
    const BLINN: bool = false;
    fn color(&self) -> Rgb {
        self.color
    }
    fn shininess(&self) -> Exponent {
        self.shininess
    }
}

/// A material (SPEC.md 3): emission `E`, ambient `Ka`, diffuse `Kd`, and a
/// specular term `S`.
///
/// [`Material::new`] gives SCENE_FORMAT.md's defaults: no emission, ambient
/// 0.2, diffuse 0.8, no specular.
///
/// ```
/// use fixshade::{Material, Rgb};
/// let m = Material::new()
///     .with_ambient(Rgb::clamped(1.0, 0.5, 0.2))
///     .with_diffuse(Rgb::clamped(1.0, 0.5, 0.2));
/// assert_eq!(m.emission, Rgb::BLACK);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Material<S: Specular = NoSpecular> {
    /// Emission `E`.
    pub emission: Rgb,
    /// Ambient colour `Ka`.
    pub ambient: Rgb,
    /// Diffuse colour `Kd`.
    pub diffuse: Rgb,
    /// The specular term.
    pub specular: S,
}

impl Default for Material<NoSpecular> {
    fn default() -> Self {
        Material::new()
    }
}

impl Material<NoSpecular> {
    /// SCENE_FORMAT.md's default material, without specular.
    ///
    /// ```
    /// use fixshade::{Material, Rgb};
    /// let m = Material::new();
    /// assert_eq!(m.emission, Rgb::BLACK);
    /// assert_eq!(m.ambient, Rgb::grey(0.2));
    /// assert_eq!(m.diffuse, Rgb::grey(0.8));
    /// assert_eq!(m, Material::default());
    /// ```
    pub const fn new() -> Self {
        Material {
            emission: Rgb::BLACK,
            ambient: Rgb::from_bits(13107, 13107, 13107),
            diffuse: Rgb::from_bits(52429, 52429, 52429),
            specular: NoSpecular,
        }
    }
}

impl<S: Specular> Material<S> {
    /// Sets the emission.
    ///
    /// ```
    /// use fixshade::{Material, Rgb};
    /// const GLOW: Material = Material::new().with_emission(Rgb::WHITE);
    /// assert_eq!(GLOW.emission, Rgb::WHITE);
    /// assert_eq!(GLOW.diffuse, Material::new().diffuse); // the rest is unchanged
    /// ```
    pub const fn with_emission(mut self, c: Rgb) -> Self {
        self.emission = c;
        self
    }
    /// Sets the ambient colour.
    ///
    /// ```
    /// use fixshade::{Material, Rgb};
    /// let m = Material::new().with_ambient(Rgb::BLACK);
    /// assert!(m.ambient.is_black());
    /// assert_eq!((m.emission, m.diffuse), (Material::new().emission, Material::new().diffuse));
    /// ```
    pub const fn with_ambient(mut self, c: Rgb) -> Self {
        self.ambient = c;
        self
    }
    /// Sets the diffuse colour.
    ///
    /// ```
    /// use fixshade::{Material, Rgb};
    /// let red = Rgb::clamped(1.0, 0.0, 0.0);
    /// let m = Material::new().with_diffuse(red);
    /// assert_eq!(m.diffuse, red);
    /// assert_eq!(m.ambient, Material::new().ambient);
    /// ```
    pub const fn with_diffuse(mut self, c: Rgb) -> Self {
        self.diffuse = c;
        self
    }
    /// Replaces the specular term (and so the material's type).
    ///
    /// ```
    /// use fixshade::material::{NoSpecular, Phong};
    /// use fixshade::{Exponent, Material, Rgb};
    /// let base = Material::new().with_diffuse(Rgb::grey(0.5));
    /// let shiny: Material<Phong> =
    ///     base.with_specular(Phong { color: Rgb::WHITE, shininess: Exponent::from_int(16) });
    /// assert_eq!(shiny.diffuse, base.diffuse); // colours are kept
    /// assert_eq!(shiny.with_specular(NoSpecular), base); // and the term can be dropped again
    /// ```
    pub fn with_specular<T: Specular>(self, specular: T) -> Material<T> {
        Material {
            emission: self.emission,
            ambient: self.ambient,
            diffuse: self.diffuse,
            specular,
        }
    }
}

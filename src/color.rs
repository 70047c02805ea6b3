//! Colour formats: inputs (material colours, light intensities), the
//! illumination result, and the RGB565 output.
//!
//! | type | storage | format | range | resolution |
//! | --- | --- | --- | --- | --- |
//! | [`Rgb`] (material colours, intensities) | `u32` ×3 | `U16F16` | [0, 256] (clamped) | 2⁻¹⁶ |
//! | [`Shade`] (illumination result) | `u32` ×3 | `Q.16`, 1.0 = 2¹⁶ | [0, 1] (clamped) | 2⁻¹⁶ |
//! | RGB565 output | `u16` | 5-6-5 | SPEC.md 6 | 1/31, 1/63 |
//!
//! Inputs above 1 are allowed (a bright light, a material that reflects more
//! than it receives, as SCENE_FORMAT.md allows); they are clamped to 256,
//! where any product with a factor of at least 2⁻⁸ is already past the
//! result's clamp at 1, so the clamp changes nothing visible for factors
//! above 2⁻⁸ and is documented here as the kernel's one departure.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use fixed::types::U16F16;

use crate::vector::FormatError;

/// The largest channel value an [`Rgb`] holds: inputs above clamp to it.
///
/// ```
/// use fixshade::{color::RGB_MAX, Rgb};
/// assert_eq!(RGB_MAX, 256 << 16);
/// assert_eq!(Rgb::grey_f32(1.0e6).unwrap().to_bits(), [RGB_MAX; 3]);
/// assert_eq!(Rgb::from_bits(u32::MAX, 0, 0).to_bits()[0], RGB_MAX);
/// ```
pub const RGB_MAX: u32 = 256 << 16;

/// A linear RGB colour or light intensity with `U16F16` channels, each in
/// [0, 256].
///
/// ```
/// use fixshade::Rgb;
/// let c = Rgb::from_f32(1.0, 0.5, 0.2).unwrap();
/// assert_eq!(c.to_bits()[1], 1 << 15);
/// assert!(Rgb::from_f32(f32::NAN, 0.0, 0.0).is_err());
/// assert_eq!(Rgb::from_f32(1000.0, 0.0, 0.0).unwrap().to_bits()[0], 256 << 16);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rgb {
    c: [u32; 3],
}

impl Rgb {
    /// Black (0, 0, 0).
    ///
    /// ```
    /// use fixshade::Rgb;
    /// assert!(Rgb::BLACK.is_black());
    /// assert_eq!(Rgb::BLACK, Rgb::default());
    /// assert_eq!(Rgb::BLACK, Rgb::grey_f32(0.0).unwrap());
    /// ```
    pub const BLACK: Rgb = Rgb { c: [0; 3] };
    /// White (1, 1, 1).
    ///
    /// ```
    /// use fixshade::Rgb;
    /// assert_eq!(Rgb::WHITE.to_bits(), [1 << 16; 3]);
    /// assert_eq!(Rgb::WHITE, Rgb::from_f32(1.0, 1.0, 1.0).unwrap());
    /// ```
    pub const WHITE: Rgb = Rgb { c: [1 << 16; 3] };

    /// A colour from raw `U16F16` bits, each clamped to [`RGB_MAX`].
    ///
    /// ```
    /// use fixshade::Rgb;
    /// const HALF_GREY: Rgb = Rgb::from_bits(1 << 15, 1 << 15, 1 << 15);
    /// assert_eq!(HALF_GREY, Rgb::grey_f32(0.5).unwrap());
    /// ```
    pub const fn from_bits(r: u32, g: u32, b: u32) -> Rgb {
        const fn cl(v: u32) -> u32 {
            if v > RGB_MAX {
                RGB_MAX
            } else {
                v
            }
        }
        Rgb {
            c: [cl(r), cl(g), cl(b)],
        }
    }

    /// A colour from fixed-point channels (clamped to 256).
    ///
    /// ```
    /// use fixed::types::U16F16;
    /// use fixshade::color::{Rgb, RGB_MAX};
    /// let c = Rgb::new(U16F16::from_num(0.5), U16F16::ONE, U16F16::MAX);
    /// // U16F16::MAX (just under 65536) is clamped to 256.
    /// assert_eq!(c.to_bits(), [1 << 15, 1 << 16, RGB_MAX]);
    /// ```
    pub const fn new(r: U16F16, g: U16F16, b: U16F16) -> Rgb {
        Rgb::from_bits(r.to_bits(), g.to_bits(), b.to_bits())
    }

    /// A colour from floats, rounded to nearest. NaN and ±∞ are errors;
    /// negative values are [`FormatError::OutOfRange`]; values above 256
    /// clamp to 256.
    ///
    /// ```
    /// use fixshade::{vector::FormatError, Rgb};
    /// // 2/3 · 2^16 = 43690.67 rounds up to 43691.
    /// assert_eq!(Rgb::from_f32(2.0 / 3.0, 0.25, 0.0).unwrap().to_bits(), [43691, 16384, 0]);
    /// assert_eq!(Rgb::from_f32(0.0, f32::INFINITY, 0.0), Err(FormatError::NotFinite));
    /// assert_eq!(Rgb::from_f32(0.0, 0.0, -0.5), Err(FormatError::OutOfRange));
    /// assert_eq!(Rgb::from_f32(300.0, 0.0, 0.0), Ok(Rgb::from_bits(256 << 16, 0, 0)));
    /// ```
    pub fn from_f32(r: f32, g: f32, b: f32) -> Result<Rgb, FormatError> {
        Rgb::from_f64([r as f64, g as f64, b as f64])
    }

    /// As [`Rgb::from_f32`], from `f64`s.
    ///
    /// ```
    /// use fixshade::{color::RGB_MAX, vector::FormatError, Rgb};
    /// assert_eq!(Rgb::from_f64([0.25, 2.0, 1e9]).unwrap().to_bits(), [16384, 131072, RGB_MAX]);
    /// assert_eq!(Rgb::from_f64([0.5, 0.5, 0.5]), Rgb::from_f32(0.5, 0.5, 0.5));
    /// assert_eq!(Rgb::from_f64([f64::NAN, 0.0, 0.0]), Err(FormatError::NotFinite));
    /// ```
    pub fn from_f64(c: [f64; 3]) -> Result<Rgb, FormatError> {
        Ok(Rgb {
            c: [chan(c[0])?, chan(c[1])?, chan(c[2])?],
        })
    }

    /// A colour from floats, for `const` data and literals: each channel
    /// rounded to the nearest `2⁻¹⁶` (ties to even, as [`Rgb::from_f32`])
    /// and clamped to [0, 256]; NaN is 0.
    ///
    /// ```
    /// use fixshade::Rgb;
    /// const ORANGE: Rgb = Rgb::clamped(1.0, 0.5, 0.2);
    /// assert_eq!(Ok(ORANGE), Rgb::from_f32(1.0, 0.5, 0.2));
    /// assert_eq!(Rgb::clamped(-1.0, f32::NAN, 1e9).to_bits(), [0, 0, 256 << 16]);
    /// ```
    pub const fn clamped(r: f32, g: f32, b: f32) -> Rgb {
        Rgb {
            c: [chan_clamped(r), chan_clamped(g), chan_clamped(b)],
        }
    }

    /// The same value in all three channels, as [`Rgb::clamped`].
    ///
    /// ```
    /// use fixshade::Rgb;
    /// const DIM: Rgb = Rgb::grey(0.1);
    /// assert_eq!(Ok(DIM), Rgb::grey_f32(0.1));
    /// ```
    pub const fn grey(v: f32) -> Rgb {
        Rgb::clamped(v, v, v)
    }

    /// The same value in all three channels; see [`Rgb::from_f32`].
    ///
    /// ```
    /// use fixshade::{vector::FormatError, Rgb};
    /// assert_eq!(Rgb::grey_f32(0.5), Rgb::from_f32(0.5, 0.5, 0.5));
    /// assert_eq!(Rgb::grey_f32(0.5).unwrap().to_bits(), [1 << 15; 3]);
    /// assert_eq!(Rgb::grey_f32(-1.0), Err(FormatError::OutOfRange));
    /// ```
    pub fn grey_f32(v: f32) -> Result<Rgb, FormatError> {
        Rgb::from_f32(v, v, v)
    }

    /// The raw `U16F16` bits of the channels.
    ///
    /// ```
    /// use fixshade::Rgb;
    /// assert_eq!(Rgb::from_bits(1, 2, 3).to_bits(), [1, 2, 3]);
    /// assert_eq!(Rgb::grey_f32(1.5).unwrap().to_bits(), [3 << 15; 3]);
    /// ```
    pub const fn to_bits(self) -> [u32; 3] {
        self.c
    }

    /// Whether every channel is 0.
    ///
    /// ```
    /// use fixshade::Rgb;
    /// assert!(Rgb::BLACK.is_black());
    /// assert!(!Rgb::from_bits(0, 0, 1).is_black());
    /// assert!(Rgb::WHITE.scaled(0, 4).is_black());
    /// ```
    pub const fn is_black(self) -> bool {
        self.c[0] == 0 && self.c[1] == 0 && self.c[2] == 0
    }

    /// The channels scaled by `num / den`, rounded to nearest and clamped to [`RGB_MAX`] like every
    /// channel. `den == 0` gives black.
    ///
    /// ```
    /// use fixshade::{color::RGB_MAX, Rgb};
    /// // A quarter:
    /// assert_eq!(Rgb::WHITE.scaled(1, 4).to_bits(), [1 << 14; 3]);
    /// // 1.5 → 2, 0.5 → 1
    /// assert_eq!(Rgb::from_bits(3, 1, 0).scaled(1, 2).to_bits(), [2, 1, 0]);
    /// assert_eq!(Rgb::WHITE.scaled(1000, 1).to_bits(), [RGB_MAX; 3]);
    /// assert_eq!(Rgb::WHITE.scaled(1, 0), Rgb::BLACK);
    /// ```
    pub fn scaled(self, num: u32, den: u32) -> Rgb {
        if den == 0 {
            return Rgb::BLACK;
        }
        // v·num ≤ 2^24·(2^32 − 1) and den/2 < 2^31: below 2^57, no overflow
        // in u64. The quotient can exceed u32 (up to 2^56): clamp before
        // narrowing.
        let s = |v: u32| {
            ((v as u64 * num as u64 + den as u64 / 2) / den as u64).min(RGB_MAX as u64) as u32
        };
        Rgb::from_bits(s(self.c[0]), s(self.c[1]), s(self.c[2]))
    }
}

fn chan(v: f64) -> Result<u32, FormatError> {
    if !v.is_finite() {
        return Err(FormatError::NotFinite);
    }
    if v < 0.0 {
        return Err(FormatError::OutOfRange);
    }
    if v >= 256.0 {
        return Ok(RGB_MAX);
    }
    Ok(U16F16::from_num(v).to_bits())
}

/// Raw value of 1.0 in a [`Shade`] channel.
///
/// ```
/// use fixshade::{color::SHADE_ONE, Shade};
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// assert_eq!(SHADE_ONE, 65536);
/// assert_eq!(Shade::from_bits(u32::MAX, 0, 0).to_bits(), [SHADE_ONE, 0, 0]);
/// assert_eq!(Shade::from_bits(SHADE_ONE, SHADE_ONE, SHADE_ONE).to_rgb565(), Rgb565::WHITE);
/// ```
pub const SHADE_ONE: u32 = 1 << 16;

/// The result of the illumination equation: three `Q.16` channels clamped to
/// [0, 1] (0 ..= 65536).
///
/// ```
/// use fixshade::Shade;
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// assert_eq!(Shade::from_bits(65536, 0, 65536).to_rgb565(), Rgb565::MAGENTA);
/// // SPEC.md 6: r5 = round(r · 31), halves rounded up.
/// assert_eq!(Shade::from_bits(32768, 32768, 32768).to_rgb565(), Rgb565::new(16, 32, 16));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Shade {
    c: [u32; 3],
}

impl Shade {
    /// Black.
    ///
    /// ```
    /// use fixshade::Shade;
    /// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    /// assert_eq!(Shade::BLACK, Shade::default());
    /// assert_eq!(Shade::BLACK.to_rgb565(), Rgb565::BLACK);
    /// ```
    pub const BLACK: Shade = Shade { c: [0; 3] };

    /// A shade from raw `Q.16` bits, each clamped to 1.0.
    ///
    /// ```
    /// use fixshade::Shade;
    /// assert_eq!(Shade::from_bits(70000, 65536, 1).to_bits(), [65536, 65536, 1]);
    /// ```
    pub const fn from_bits(r: u32, g: u32, b: u32) -> Shade {
        const fn cl(v: u32) -> u32 {
            if v > SHADE_ONE {
                SHADE_ONE
            } else {
                v
            }
        }
        Shade {
            c: [cl(r), cl(g), cl(b)],
        }
    }

    /// A shade from raw bits already within `0 ..= 65536` (a shade kept
    /// in a vertex cache): no clamp.
    #[inline(always)]
    pub(crate) const fn from_bits_in_range(r: u32, g: u32, b: u32) -> Shade {
        debug_assert!(r <= SHADE_ONE && g <= SHADE_ONE && b <= SHADE_ONE);
        Shade { c: [r, g, b] }
    }

    /// The raw channels, each in 0 ..= 65536.
    ///
    /// ```
    /// use fixshade::Shade;
    /// assert_eq!(Shade::from_bits(1, 32768, 65536).to_bits(), [1, 32768, 65536]);
    /// ```
    pub const fn to_bits(self) -> [u32; 3] {
        self.c
    }

    /// Quantises to RGB565 as SPEC.md section 6 says: `round(v · 31)` (or
    /// 63), halves rounded up. `v ≤ 2¹⁶`, so `v · 63 < 2²²`: no overflow.
    ///
    /// ```
    /// use fixshade::Shade;
    /// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    /// assert_eq!(Shade::from_bits(65536, 65536, 65536).to_rgb565(), Rgb565::WHITE);
    /// // A quarter: 0.25 · 31 = 7.75 → 8 and 0.25 · 63 = 15.75 → 16.
    /// assert_eq!(Shade::from_bits(16384, 16384, 16384).to_rgb565(), Rgb565::new(8, 16, 8));
    /// // Just below half a red step stays 0: 1057/65536 · 31 = 0.49997.
    /// assert_eq!(Shade::from_bits(1057, 0, 0).to_rgb565(), Rgb565::BLACK);
    /// ```
    pub const fn to_rgb565(self) -> Rgb565 {
        let r = (self.c[0] * 31 + (1 << 15)) >> 16;
        let g = (self.c[1] * 63 + (1 << 15)) >> 16;
        let b = (self.c[2] * 31 + (1 << 15)) >> 16;
        Rgb565::new(r as u8, g as u8, b as u8)
    }
}

/// A channel of [`Rgb::clamped`]: `v · 2¹⁶` is exact in `f64` (an `f32`
/// has 24 significant bits), rounded to the nearest, ties to even; the
/// `as` casts saturate (NaN to 0).
const fn chan_clamped(v: f32) -> u32 {
    let x = v as f64 * 65536.0;
    if x.is_nan() || x <= 0.0 {
        return 0;
    }
    if x >= RGB_MAX as f64 {
        return RGB_MAX;
    }
    // 0 < x < 2^24: the truncation and the fraction are exact.
    let t = x as u32;
    let frac = x - t as f64;
    if frac > 0.5 || (frac == 0.5 && t & 1 == 1) {
        t + 1
    } else {
        t
    }
}

impl From<Rgb> for Rgb565 {
    /// Clamped to 1 and quantised as SPEC.md 6 says (as [`Shade::to_rgb565`]).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    /// use fixshade::Rgb;
    /// assert_eq!(Rgb565::from(Rgb::clamped(2.0, 0.25, 0.0)), Rgb565::new(31, 16, 0));
    /// ```
    fn from(c: Rgb) -> Rgb565 {
        Shade::from_bits(c.c[0], c.c[1], c.c[2]).to_rgb565()
    }
}

impl From<Rgb> for Rgb888 {
    /// Clamped to 1, `round(v · 255)` (halves up).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    /// use fixshade::Rgb;
    /// assert_eq!(Rgb888::from(Rgb::clamped(1.0, 0.5, 9.0)), Rgb888::new(255, 128, 255));
    /// ```
    fn from(c: Rgb) -> Rgb888 {
        // v ≤ 2^16 after the clamp: v · 255 < 2^24.
        let q = |v: u32| ((v.min(SHADE_ONE) * 255 + (1 << 15)) >> 16) as u8;
        Rgb888::new(q(c.c[0]), q(c.c[1]), q(c.c[2]))
    }
}

impl From<Rgb565> for Rgb {
    /// Each channel's fraction of its maximum (`r/31`, `g/63`, `b/31`),
    /// rounded to `2⁻¹⁶`: converting back gives the same `Rgb565`.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    /// use fixshade::Rgb;
    /// assert_eq!(Rgb::from(Rgb565::WHITE), Rgb::WHITE);
    /// let c = Rgb565::new(3, 40, 17);
    /// assert_eq!(Rgb565::from(Rgb::from(c)), c);
    /// ```
    fn from(c: Rgb565) -> Rgb {
        let f = |v: u8, max: u32| (v as u32 * SHADE_ONE + max / 2) / max;
        Rgb::from_bits(f(c.r(), 31), f(c.g(), 63), f(c.b(), 31))
    }
}

impl From<Rgb888> for Rgb {
    /// Each channel over 255, rounded to `2⁻¹⁶`: converting back gives the
    /// same `Rgb888`.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    /// use fixshade::Rgb;
    /// assert_eq!(Rgb::from(Rgb888::WHITE), Rgb::WHITE);
    /// let c = Rgb888::new(1, 128, 254);
    /// assert_eq!(Rgb888::from(Rgb::from(c)), c);
    /// ```
    fn from(c: Rgb888) -> Rgb {
        let f = |v: u8| (v as u32 * SHADE_ONE + 127) / 255;
        Rgb::from_bits(f(c.r()), f(c.g()), f(c.b()))
    }
}

/// Packs 5-6-5 channel values into the raw `u16` of an RGB565 pixel.
///
/// ```
/// use fixshade::color::pack565;
/// use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
/// use embedded_graphics::prelude::*;
/// assert_eq!(pack565(31, 63, 31), 0xFFFF);
/// assert_eq!(pack565(31, 0, 0), 0xF800);
/// assert_eq!(pack565(1, 2, 3), Rgb565::new(1, 2, 3).into_storage());
/// ```
#[inline]
pub const fn pack565(r: u32, g: u32, b: u32) -> u16 {
    ((r << 11) | (g << 5) | b) as u16
}

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

use embedded_graphics::pixelcolor::Rgb565;
use fixed::types::U16F16;

use crate::vector::FormatError;

/// The largest channel value an [`Rgb`] holds: inputs above clamp to it.
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
    pub const BLACK: Rgb = Rgb { c: [0; 3] };
    /// White (1, 1, 1).
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
    pub const fn new(r: U16F16, g: U16F16, b: U16F16) -> Rgb {
        Rgb::from_bits(r.to_bits(), g.to_bits(), b.to_bits())
    }

    /// A colour from floats, rounded to nearest. NaN and ±∞ are errors;
    /// negative values are [`FormatError::OutOfRange`]; values above 256
    /// clamp to 256.
    pub fn from_f32(r: f32, g: f32, b: f32) -> Result<Rgb, FormatError> {
        Rgb::from_f64([r as f64, g as f64, b as f64])
    }

    /// As [`Rgb::from_f32`], from `f64`s.
    pub fn from_f64(c: [f64; 3]) -> Result<Rgb, FormatError> {
        Ok(Rgb {
            c: [chan(c[0])?, chan(c[1])?, chan(c[2])?],
        })
    }

    /// The same value in all three channels; see [`Rgb::from_f32`].
    pub fn grey_f32(v: f32) -> Result<Rgb, FormatError> {
        Rgb::from_f32(v, v, v)
    }

    /// The raw `U16F16` bits of the channels.
    pub const fn to_bits(self) -> [u32; 3] {
        self.c
    }

    /// Whether every channel is 0.
    pub const fn is_black(self) -> bool {
        self.c[0] == 0 && self.c[1] == 0 && self.c[2] == 0
    }

    /// The channels scaled by `num / den` (used for the k × k samples of an
    /// area light), rounded to nearest and clamped to [`RGB_MAX`] like every
    /// channel. `den == 0` gives black.
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
    pub const BLACK: Shade = Shade { c: [0; 3] };

    /// A shade from raw `Q.16` bits, each clamped to 1.0.
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

    /// The raw channels, each in 0 ..= 65536.
    pub const fn to_bits(self) -> [u32; 3] {
        self.c
    }

    /// Quantises to RGB565 as SPEC.md section 6 says: `round(v · 31)` (or
    /// 63), halves rounded up. `v ≤ 2¹⁶`, so `v · 63 < 2²²`: no overflow.
    pub const fn to_rgb565(self) -> Rgb565 {
        let r = (self.c[0] * 31 + (1 << 15)) >> 16;
        let g = (self.c[1] * 63 + (1 << 15)) >> 16;
        let b = (self.c[2] * 31 + (1 << 15)) >> 16;
        Rgb565::new(r as u8, g as u8, b as u8)
    }
}

/// Packs 5-6-5 channel values into the raw `u16` of an RGB565 pixel.
#[inline]
pub const fn pack565(r: u32, g: u32, b: u32) -> u16 {
    ((r << 11) | (g << 5) | b) as u16
}

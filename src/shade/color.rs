//! Colours: channel units to pixels, and the saturating sums of colour terms.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

use super::rules::{Tracer, with_rules};
use crate::{Color, Rules, Scalar};

/// Converts a colour in channel units to a pixel: `round(clamp(c, 0, 255))` per channel,
/// ties away from zero.
pub fn to_rgb888<S: Scalar>(c: Color<S>) -> Rgb888 {
    let channel = |v: S| -> u8 {
        clamp_channel(v)
            .round_to_i32()
            .and_then(|i| u8::try_from(i).ok())
            .unwrap_or(u8::MAX)
    };
    Rgb888::new(channel(c[0]), channel(c[1]), channel(c[2]))
}

/// Converts a colour in channel units to a pixel by a scene's rules: [`to_rgb888`]
/// (rounding) under the `fixray` rules, truncation `floor(clamp(c, 0, 255))` under the
/// `course` rules (`COURSE-RULES.md` §3). Each rule set's own mapping is in its module
/// (`fixray.rs`, `course.rs`).
pub fn to_pixel<S: Scalar>(rules: Rules, c: Color<S>) -> Rgb888 {
    with_rules!(rules, pixel_by::<S>(c))
}

fn pixel_by<S: Scalar, R: Tracer>(c: Color<S>) -> Rgb888 {
    R::to_pixel(c)
}

/// `[0, 255]` in the format (or its largest value), what a channel is clamped to.
pub(crate) fn clamp_channel<S: Scalar>(v: S) -> S {
    let max = S::from_i32(255).unwrap_or(S::MAX);
    v.max(S::ZERO).min(max)
}

/// Adds two non-negative colour terms; a sum beyond the format saturates (it is far above
/// 255 channel units, so the pixel is at full intensity either way).
pub(crate) fn add_sat<S: Scalar>(a: S, b: S) -> S {
    a.checked_add(b).unwrap_or(S::MAX)
}

/// `k × Σ` style product chain that saturates: a term too large for the format is far
/// brighter than 255.
pub(crate) fn term<S: Scalar>(factors: [S; 3]) -> S {
    factors
        .iter()
        .skip(1)
        .try_fold(factors[0], |acc, f| acc.checked_mul(*f))
        .unwrap_or(S::MAX)
}

/// The colour depth a frame's pixels must be exact in ([`crate::Frame::with_depth`]):
/// each channel's largest value, as an `embedded-graphics` colour type of that depth has
/// it (`Rgb565`: 31, 63, 31). A pixel of a frame drawn for a depth converts to the colour
/// the exact pixel converts to, channel by channel as `embedded-graphics` converts from
/// `Rgb888`: `round(v·max/255)`. The default, [`Depth::RGB888`], asks for the exact
/// pixels themselves.
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
/// use fixray::Depth;
///
/// assert_eq!(Depth::of::<Rgb565>(), Depth::RGB565);
/// // Two pixels of one Rgb565 colour have one key.
/// let (a, b) = (Rgb888::new(200, 100, 8), Rgb888::new(198, 101, 6));
/// assert_eq!(Rgb565::from(a), Rgb565::from(b));
/// assert_eq!(Depth::RGB565.key(a), Depth::RGB565.key(b));
/// assert_ne!(Depth::RGB888.key(a), Depth::RGB888.key(b));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Depth {
    max: [u8; 3],
    /// Each channel's scale ([`Depth::key`]): `⌊max·2²⁴/255⌋`, and `2²⁴` where `max`
    /// is 255 (the channel itself).
    scale: [u32; 3],
}

impl Default for Depth {
    fn default() -> Self {
        Self::RGB888
    }
}

impl Depth {
    /// Eight bits a channel: the exact pixels.
    pub const RGB888: Self = Self::new(255, 255, 255);
    /// Six bits a channel (`Rgb666`, `Bgr666`).
    pub const RGB666: Self = Self::new(63, 63, 63);
    /// Five bits of red and blue, six of green (`Rgb565`, `Bgr565`: ST7789 and ILI9341
    /// panels).
    pub const RGB565: Self = Self::new(31, 63, 31);
    /// Five bits a channel (`Rgb555`, `Bgr555`).
    pub const RGB555: Self = Self::new(31, 31, 31);

    /// The depth whose channels' largest values are `red`, `green` and `blue` (a
    /// channel of 0 is taken as 1: one bit).
    pub const fn new(red: u8, green: u8, blue: u8) -> Self {
        const fn one(v: u8) -> u8 {
            if v == 0 { 1 } else { v }
        }
        const fn scale(max: u8) -> u32 {
            if max == u8::MAX {
                1 << 24
            } else {
                // `2²⁴ = 255·65_793 + 1`, so `⌊max·2²⁴/255⌋ = max·65_793` for `max < 255`.
                max as u32 * SCALE_PER_MAX
            }
        }
        let max = [one(red), one(green), one(blue)];
        Self {
            max,
            scale: [scale(max[0]), scale(max[1]), scale(max[2])],
        }
    }

    /// The depth of an `embedded-graphics` RGB colour type (its `MAX_R`, `MAX_G`,
    /// `MAX_B`). Its conversion from `Rgb888` must be `embedded-graphics`' own, channel by
    /// channel, as it is for the crate's types.
    pub fn of<C: RgbColor>() -> Self {
        Self::new(C::MAX_R, C::MAX_G, C::MAX_B)
    }

    /// Each channel's largest value.
    pub const fn max(self) -> [u8; 3] {
        self.max
    }

    /// The pixel's colour in this depth as one number (`red << 16 | green << 8 | blue`,
    /// each channel `round(v·max/255)`): two pixels have one key exactly where they
    /// convert to one colour. Each channel's part does not decrease as the channel grows.
    pub fn key(self, pixel: Rgb888) -> u32 {
        // `embedded-graphics`' conversion: `v·⌊max·2²⁴/255⌋`, rounded off its 24 bits;
        // with a scale of `2²⁴` (`max` 255) that is `v` itself (`255·2²⁴ + 2²³ < 2³²`).
        let [r, g, b] = self.scale;
        let c = |v: u8, scale: u32| -> u32 { (u32::from(v) * scale + (1 << 23)) >> 24 };
        (c(pixel.r(), r) << 16) | (c(pixel.g(), g) << 8) | c(pixel.b(), b)
    }
}

/// `⌊2²⁴/255⌋`: a depth channel's scale per unit of its largest value ([`Depth::key`]).
const SCALE_PER_MAX: u32 = (1 << 24) / 255;

#[cfg(test)]
mod tests {
    /// Every depth's key is `embedded-graphics`' formula, its quotient included, for
    /// every channel value and every largest value of a channel.
    #[test]
    fn a_key_is_the_formula_with_its_quotient() {
        for max in 1..=255u8 {
            let depth = super::Depth::new(max, max, max);
            for v in 0..=255u8 {
                let c = if max == u8::MAX {
                    u32::from(v)
                } else {
                    (u32::from(v) * ((u32::from(max) << 24) / 255) + (1 << 23)) >> 24
                };
                let pixel = super::Rgb888::new(v, v, v);
                assert_eq!(depth.key(pixel), c << 16 | c << 8 | c, "{max} {v}");
            }
        }
    }

    /// A channel of largest value 255 keys as itself.
    #[test]
    fn the_exact_depths_key_is_the_pixel() {
        let depth = super::Depth::RGB888;
        for v in 0..=255u8 {
            let pixel = super::Rgb888::new(v, 255 - v, v / 2);
            let key = u32::from(v) << 16 | u32::from(255 - v) << 8 | u32::from(v / 2);
            assert_eq!(depth.key(pixel), key);
        }
    }
}

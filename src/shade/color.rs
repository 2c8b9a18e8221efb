//! Colours: channel units to pixels, and the saturating sums of colour terms.

use embedded_graphics_core::pixelcolor::Rgb888;

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

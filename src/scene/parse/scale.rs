//! The scale rule over a parse ([`crate::scene::MIN_SCALE_DELTAS`],
//! [`crate::scene::MIN_RADIUS_SQ_DELTAS`]): each pixel pitch and sphere the scene derives
//! is checked against the number format's resolution at the scene's magnitude, and on a
//! host the first one the format does not resolve is kept until the parse is over, with
//! the formats that resolve every one of them.

use super::error::{Quantity, QuotedNumber, SceneError, SceneErrorKind};
use super::hints::HINTS;
#[cfg(not(target_os = "none"))]
use super::hints::resolvers;
use super::lexer::quote_number;
use super::{Number, Result};
use crate::Scalar;

/// The error of a radius whose square is beyond the range of `format`.
#[cold]
#[inline(never)]
pub(super) fn radius_sq_beyond(r: &Number<'_>, format: &'static str) -> SceneError {
    r.pos.error(SceneErrorKind::BeyondRange {
        quantity: Quantity::RadiusSq,
        number: kept(r),
        format,
    })
}

/// A number as a scale error keeps it: only where its message shows it ([`HINTS`]).
fn kept(n: &Number<'_>) -> QuotedNumber {
    if HINTS {
        quote_number(n.text)
    } else {
        QuotedNumber::new()
    }
}

/// The scale rule over a parse: each length through [`Scales::check`], the parse's
/// result through [`Scales::finish`]. On a host ([`HINTS`]) a length the format does
/// not resolve does not end the parse: the first is kept and returned when the parse is
/// over, or at a later error (which lies after it in the file), with the formats that
/// resolve every pitch and sphere of the scene (`BelowResolution`'s `formats`), so that
/// its message names no format that a later sphere rules out. On bare metal the error
/// returns at once, as every other one, and this type is empty (no stack for a kept
/// error: the fields exist only where [`HINTS`] holds).
pub(super) struct Scales {
    /// The first length the format does not resolve.
    #[cfg(not(target_os = "none"))]
    first: Option<SceneError>,
    /// The formats of `MAIN` that resolve every length checked (bit `i`: `MAIN[i]`).
    #[cfg(not(target_os = "none"))]
    formats: u8,
}

impl Scales {
    /// Nothing checked yet.
    pub(super) const fn new() -> Self {
        Self {
            #[cfg(not(target_os = "none"))]
            first: None,
            #[cfg(not(target_os = "none"))]
            formats: u8::MAX,
        }
    }

    /// [`resolved`], kept on a host (see the type).
    pub(super) fn check<S: Scalar>(
        &mut self,
        q: S,
        magnitude: S,
        at: &Number<'_>,
        quantity: Quantity,
        pixels: u16,
    ) -> Result<()> {
        let verdict = resolved(q, magnitude, at, quantity, pixels);
        #[cfg(not(target_os = "none"))]
        {
            self.formats &= resolvers(quantity, &at.value, pixels, order_of(magnitude));
            if let Err(e) = verdict {
                self.first.get_or_insert(e);
                return Ok(());
            }
        }
        verdict
    }

    /// The parse's result: the first length kept, with the formats that resolve every
    /// length, or else `result`.
    pub(super) fn finish(&mut self, result: Result<()>) -> Result<()> {
        #[cfg(not(target_os = "none"))]
        if let Some(mut e) = self.first.take() {
            if let SceneErrorKind::BelowResolution { formats, .. } = &mut e.kind {
                *formats = self.formats;
            }
            return Err(e);
        }
        result
    }
}

/// Checks that a length (`q` over `pixels`: a pitch is a window's width over its pixels)
/// is at least [`Quantity::min_deltas`] ulps of `magnitude` ([`Scalar::ulp`]): as
/// `q ≥ deltas·ulp·pixels` (no division), [`crate::scene::MIN_SCALE_DELTAS`] of them,
/// [`crate::scene::MIN_RADIUS_SQ_DELTAS`] for a radius²; the error is at the number `at`
/// it is derived from.
// Out of line: one copy in flash, not one per call.
#[inline(never)]
fn resolved<S: Scalar>(
    q: S,
    magnitude: S,
    at: &Number<'_>,
    quantity: Quantity,
    pixels: u16,
) -> Result<()> {
    let deltas = quantity.min_deltas() * i32::from(pixels);
    if magnitude
        .ulp()
        .checked_mul_int(deltas)
        .is_some_and(|min| q >= min)
    {
        return Ok(());
    }
    Err(at.pos.error(SceneErrorKind::BelowResolution {
        quantity,
        number: kept(at),
        pixels,
        formats: 0,
        format: S::NAME,
    }))
}

/// The binary order of a magnitude: it is below 2^order (what a float's ulp scales
/// with; 32 beyond `i32`).
#[cfg(not(target_os = "none"))]
fn order_of<S: Scalar>(magnitude: S) -> u8 {
    let whole = magnitude.floor_to_i32().and_then(|m| u32::try_from(m).ok());
    let order = whole.map_or(32, |m| 32 - m.leading_zeros());
    u8::try_from(order).unwrap_or(u8::MAX)
}

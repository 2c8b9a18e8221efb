//! A scene's numbers into the number format, checked against their attribute's domain:
//! the conversion (its error at the number that does not fit), the domains (`> 0`,
//! `>= 0`, a format's positive value), colours (displayed ones in channel units) and the
//! precision epsilon.

use super::error::SceneErrorKind;
use super::{Number, Result, Value, quote};
use crate::num::Decimal;
use crate::{Color, Rules, Scalar, Vec3};

/// Converts a number into the format, times `scale` (exact, in decimal).
// Out of line: one copy in flash, not one per call.
#[inline(never)]
pub(super) fn convert<S: Scalar>(n: &Number<'_>, scale: u64) -> Result<S> {
    S::from_decimal(n.value.times(scale)).ok_or_else(|| {
        n.pos.error(SceneErrorKind::DoesNotFit {
            value: quote(n.text),
            format: S::NAME,
        })
    })
}

// Out of line: one copy in flash, not one per call.
#[inline(never)]
pub(super) fn vector<S: Scalar>(v: &Value<'_>) -> Result<Vec3<S>> {
    Ok(Vec3::new(
        convert(&v.nums[0], 1)?,
        convert(&v.nums[1], 1)?,
        convert(&v.nums[2], 1)?,
    ))
}

/// `> 0`.
pub(super) fn positive_value(d: &Decimal) -> bool {
    !d.negative && !d.is_zero()
}

/// `>= 0` (`-0` included).
pub(super) fn non_negative_value(d: &Decimal) -> bool {
    !d.negative || d.is_zero()
}

pub(super) fn in_domain(
    n: &Number<'_>,
    ok: impl Fn(&Decimal) -> bool,
    attribute: &'static str,
    rule: &'static str,
) -> Result<()> {
    if ok(&n.value) {
        Ok(())
    } else {
        Err(n.pos.error(SceneErrorKind::OutOfDomain { attribute, rule }))
    }
}

/// A number that must be > 0 and stay > 0 in the format.
// Out of line: one copy in flash, not one per call.
#[inline(never)]
pub(super) fn positive<S: Scalar>(n: &Number<'_>, attribute: &'static str) -> Result<S> {
    in_domain(n, positive_value, attribute, "> 0")?;
    let x = convert::<S>(n, 1)?;
    if x > S::ZERO {
        Ok(x)
    } else {
        Err(n.pos.error(SceneErrorKind::OutOfDomain {
            attribute,
            rule: "> 0 (it rounds to 0 in this number format)",
        }))
    }
}

/// Three reals ≥ 0.
fn non_negative3<S: Scalar>(v: &Value<'_>, attribute: &'static str) -> Result<[S; 3]> {
    let mut c = [S::ZERO; 3];
    for (ck, n) in c.iter_mut().zip(&v.nums) {
        in_domain(n, non_negative_value, attribute, ">= 0")?;
        *ck = convert(n, 1)?;
    }
    Ok(c)
}

/// Three colour reals: ≥ 0 under the `fixray` rules; the course reads any value (a
/// negative one darkens, and a pixel below 0 shows 0).
pub(super) fn colour3<S: Scalar>(
    v: &Value<'_>,
    attribute: &'static str,
    rules: Rules,
) -> Result<[S; 3]> {
    if rules == Rules::Fixray {
        return non_negative3(v, attribute);
    }
    Ok([
        convert(&v.nums[0], 1)?,
        convert(&v.nums[1], 1)?,
        convert(&v.nums[2], 1)?,
    ])
}

/// A displayed colour (ambient, background) in channel units: 255 × the value, computed
/// exactly in decimal. The value itself must fit the format; if 255 × it does not, it
/// saturates at the format's maximum (or minimum), which displays as 255 (or 0) exactly
/// like the value would. Negative values only under the course rules.
pub(super) fn channel_colour<S: Scalar>(
    nums: &[Number<'_>; 3],
    attribute: &'static str,
    rules: Rules,
) -> Result<Color<S>> {
    let mut c = [S::ZERO; 3];
    for (ck, n) in c.iter_mut().zip(nums) {
        if rules == Rules::Fixray {
            in_domain(n, non_negative_value, attribute, ">= 0")?;
        }
        convert::<S>(n, 1)?;
        let limit = if n.value.negative {
            S::MAX.checked_neg().unwrap_or(S::ZERO)
        } else {
            S::MAX
        };
        *ck = convert(n, 255).unwrap_or(limit);
    }
    Ok(c)
}

/// The precision epsilon: a real > 0 that must stay > 0 in the format.
pub(super) fn precision<S: Scalar>(n: &Number<'_>) -> Result<S> {
    in_domain(n, positive_value, "precision", "> 0")?;
    let eps = convert::<S>(n, 1)?;
    if eps > S::ZERO {
        Ok(eps)
    } else {
        Err(n.pos.error(SceneErrorKind::OutOfDomain {
            attribute: "precision",
            rule: "at least the number format's resolution (it rounds to 0)",
        }))
    }
}

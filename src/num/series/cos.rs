//! cos x by its Taylor series to x¹⁴/14! in a format's own arithmetic (spotlight cones of
//! the fixed formats), in Horner form:
//! `1 − x²/2 (1 − x²/12 (1 − x²/30 (1 − x²/56 (1 − x²/90 (1 − x²/132 (1 − x²/182))))))`.

use crate::Scalar;

/// The truncation error of [`cos`] on [−π/2, π/2] (the first term left out, x¹⁶/16!, is
/// 6.6e-11 there; the bound is stated with margin). Each of the seven Horner steps rounds
/// once more in the format: about 2 DELTAs each in the fixed formats.
pub const MAX_ERROR: f64 = 1e-8;

/// cos x for |x| ≤ π; `None` when a step overflows.
pub fn cos<S: Scalar>(x: S) -> Option<S> {
    let x2 = x.checked_mul(x)?;
    // Σ (−1)^k x^2k / (2k)!, k = 0..=7, from the inside out.
    let mut acc = S::ONE;
    for d in [182, 132, 90, 56, 30, 12, 2] {
        acc = S::ONE.checked_sub(x2.checked_mul(acc)?.checked_div(S::from_i32(d)?)?)?;
    }
    Some(acc)
}

/// cos x for any x, through [`crate::num::Series::cos`] (the series above in the fixed
/// formats, `libm` in the floats) on the angle reduced to [−π/2, π/2]: `x − 2πk` with
/// `k = round(x / 2π)`, then `cos y = −cos(π − |y|)` for `|y| > π/2`. The reduction
/// rounds `2π k` (and π) in the format: the reduced angle is off by about `(1 + 7|k|) δ`,
/// and so is the cosine. `None` when a step overflows. The profiles of the course's
/// `revsurf` (`surfer 2` and `3`) take their cosines and sines here.
pub fn cos_any<S: Scalar>(x: S) -> Option<S> {
    use core::f64::consts::{PI, TAU};
    let k = x.checked_mul(S::from_f64(1.0 / TAU)?)?.round_to_i32()?;
    let y = x.checked_sub(S::from_f64(TAU)?.checked_mul_int(k)?)?;
    let pi = S::from_f64(PI)?;
    if y.abs() <= S::from_f64(PI / 2.0)? {
        y.cos()
    } else {
        pi.checked_sub(y.abs())?.cos()?.checked_neg()
    }
}

/// sin x for any x: `cos(x − π/2)` by [`cos_any`].
pub fn sin_any<S: Scalar>(x: S) -> Option<S> {
    cos_any(x.checked_sub(S::from_f64(core::f64::consts::FRAC_PI_2)?)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I20F12, I32F32};

    /// (x, cos x) at the angles a spotlight's θ in (0°, 90°] gives.
    const VECTORS: [(f64, f64); 6] = [
        (0.0, 1.0),
        (core::f64::consts::FRAC_PI_6 / 2.0, 0.965_925_826_289_068_3), // 15°
        (core::f64::consts::FRAC_PI_6, 0.866_025_403_784_438_6),       // 30°
        (
            core::f64::consts::FRAC_PI_4,
            core::f64::consts::FRAC_1_SQRT_2,
        ), // 45°
        (core::f64::consts::FRAC_PI_3, 0.5),                           // 60°
        (core::f64::consts::FRAC_PI_2, 0.0),                           // 90°
    ];

    fn vectors<S: Scalar>(deltas: f64) {
        for (x, want) in VECTORS {
            let got = cos(S::from_f64(x).unwrap()).unwrap().to_f64();
            let bound = MAX_ERROR + deltas * S::DELTA.to_f64();
            assert!((got - want).abs() <= bound, "{}: cos {x} = {got}", S::NAME);
        }
    }

    #[test]
    fn the_series_is_within_its_stated_error() {
        // f64: the truncation alone (its rounding is far below).
        vectors::<f64>(16.0);
        // The fixed formats: truncation plus a rounding per Horner step and the input's.
        vectors::<I16F16>(16.0);
        vectors::<I20F12>(16.0);
        vectors::<I32F32>(16.0);
    }

    /// Any angle: the reduction's rounding (`(1 + 7|k|) δ`, `|k| ≤ 2` here) and the
    /// series' on [−π/2, π/2], in every fixed format and f64.
    fn any_angle<S: Scalar>() {
        for i in -400..=400 {
            let x = f64::from(i) * 0.031;
            let xs = S::from_f64(x).unwrap();
            let bound = MAX_ERROR + 40.0 * S::DELTA.to_f64();
            let c = cos_any(xs).unwrap().to_f64();
            let s = sin_any(xs).unwrap().to_f64();
            let exact = xs.to_f64();
            assert!(
                (c - exact.cos()).abs() <= bound,
                "{}: cos {x} = {c}",
                S::NAME
            );
            assert!(
                (s - exact.sin()).abs() <= bound,
                "{}: sin {x} = {s}",
                S::NAME
            );
        }
    }

    #[test]
    fn any_angle_is_reduced_within_its_error() {
        any_angle::<f64>();
        any_angle::<I16F16>();
        any_angle::<I20F12>();
        any_angle::<I32F32>();
    }

    #[test]
    fn truncation_error_on_the_whole_interval() {
        let mut worst = 0.0f64;
        for i in -200..=200 {
            let x = core::f64::consts::FRAC_PI_2 * f64::from(i) / 200.0;
            worst = worst.max((cos(x).unwrap() - x.cos()).abs());
        }
        assert!(worst <= MAX_ERROR, "{worst}");
    }
}

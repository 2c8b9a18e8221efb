//! `x^e` for `x` in [0, 1] and `e ≥ 1` in a format's own arithmetic (the specular term of
//! the fixed formats): `x^⌊e⌋` by repeated squaring, exact up to rounding, times the
//! interpolation `x^f ≈ 1 − f + f·x` for the fraction `f = e − ⌊e⌋`.
//!
//! The interpolation is the chord of the convex `x^f` in `f`, so it never undershoots and
//! its error is largest at `x = ½`, `f = log₂(1/ln 4) ≈ 0.47`: `1 − f/2 − 2^−f = 0.0430`
//! ([`FRACTION_MAX_ERROR`]).
//! Times `x^⌊e⌋ ≤ x` that is at most `0.0215` of the result ([`MAX_ERROR`], at `x = ½`,
//! `e ≈ 1.47`). It vanishes for integer exponents and shrinks as `x` approaches 1, where a
//! glint is bright.

use crate::Scalar;

/// The largest error of the interpolation `x^f ≈ 1 − f + f·x` for `x ≥ ½` and `f` in
/// [0, 1): `1 − f/2 − 2^−f` at `x = ½`, `f ≈ 0.47`, which is 0.04303, rounded up (the
/// formats' rounding adds a few DELTAs on top).
pub const FRACTION_MAX_ERROR: f64 = 0.0431;

/// The largest error of [`pow_unit`] against the exact power for `x ≥ ½` and any exponent
/// ≥ 1: [`FRACTION_MAX_ERROR`] times `x^⌊e⌋ ≤ ½` at its worst (0.02152), rounded up.
/// Below `x = ½` the glint is at most `½^e` bright.
pub const MAX_ERROR: f64 = 0.0216;

/// `x^e` for x in [0, 1], e ≥ 1 (x is clamped to [0, 1]); `None` when `e` does not fit an
/// `i32` or a step overflows.
pub fn pow_unit<S: Scalar>(x: S, e: S) -> Option<S> {
    let x = x.max(S::ZERO).min(S::ONE);
    let k = e.floor_to_i32()?.max(0);
    let f = e.checked_sub(S::from_i32(k)?)?;
    // x^k by repeated squaring; x ≤ 1, so nothing grows.
    let (mut result, mut base, mut n) = (S::ONE, x, k);
    while n > 0 {
        if n & 1 == 1 {
            result = result.checked_mul(base)?;
        }
        base = base.checked_mul(base)?;
        n >>= 1;
    }
    // x^f ≈ 1 − f + f·x.
    let frac = S::ONE.checked_sub(f)?.checked_add(f.checked_mul(x)?)?;
    result.checked_mul(frac)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I20F12, I32F32};

    /// (x, e, x^e): integer exponents are exact up to rounding.
    const VECTORS: [(f64, f64, f64); 6] = [
        (1.0, 40.0, 1.0),
        (0.5, 1.0, 0.5),
        (0.5, 2.0, 0.25),
        (0.5, 4.0, 0.0625),
        (0.75, 3.0, 0.421_875),
        (0.0, 5.0, 0.0),
    ];

    fn vectors<S: Scalar>(deltas: f64) {
        for (x, e, want) in VECTORS {
            let got = pow_unit(S::from_f64(x).unwrap(), S::from_f64(e).unwrap())
                .unwrap()
                .to_f64();
            assert!(
                (got - want).abs() <= deltas * S::DELTA.to_f64(),
                "{}: {x}^{e} = {got}, not {want}",
                S::NAME
            );
        }
    }

    #[test]
    fn integer_exponents_are_exact_up_to_rounding() {
        vectors::<I16F16>(8.0);
        vectors::<I20F12>(8.0);
        vectors::<I32F32>(8.0);
        vectors::<f64>(8.0);
    }

    /// The largest error over x in [½, 1] and exponents `from + j/16`, j = 0..=64.
    fn worst<S: Scalar>(from: f64) -> f64 {
        let mut worst = 0.0f64;
        for i in 0..=64 {
            for j in 0..=64 {
                let x = 0.5 + f64::from(i) / 128.0;
                let e = from + f64::from(j) / 64.0 * if from < 1.0 { 0.999 } else { 4.0 };
                let got = pow_unit(S::from_f64(x).unwrap(), S::from_f64(e).unwrap())
                    .unwrap()
                    .to_f64();
                worst = worst.max((got - x.powf(e)).abs());
            }
        }
        worst
    }

    /// Both stated bounds hold and are attained (they are the real ones, not loose ones).
    /// The interpolation's bound is 0.0430, attained at x = ½.
    #[test]
    fn the_stated_maximum_errors_hold_and_are_attained() {
        fn check<S: Scalar>() {
            let delta = S::DELTA.to_f64();
            let fraction = worst::<S>(0.0);
            assert!(
                fraction <= FRACTION_MAX_ERROR + 16.0 * delta,
                "{}: {fraction}",
                S::NAME
            );
            assert!(
                fraction > 0.042,
                "{}: {fraction} (attained at x = ½)",
                S::NAME
            );
            let power = worst::<S>(1.0);
            assert!(power <= MAX_ERROR + 16.0 * delta, "{}: {power}", S::NAME);
            assert!(
                power > 0.021,
                "{}: {power} (attained at x = ½, e ≈ 1.47)",
                S::NAME
            );
        }
        check::<f64>();
        check::<I16F16>();
        check::<I20F12>();
        check::<I32F32>();
    }
}

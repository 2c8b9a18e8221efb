//! What a format is, measured rather than named: the per-format tests take their
//! tolerances and their exceptions from these probes, so that a format added to
//! `fixray::num::formats` is classified with no test file edited.

use fixray::Scalar;

/// The largest relative error of `S`'s square root over 64 values in [1, 4): within one
/// `DELTA` for a rounded root (the fixed formats' truncation to nearest below, the
/// floats' ½ ε), 6 % for micromath's approximation (`f32m`).
pub fn sqrt_error<S: Scalar>() -> f64 {
    (0..64)
        .filter_map(|i| S::from_f64(1.0 + f64::from(i) * 3.0 / 64.0))
        .map(|x| {
            let want = x.to_f64().sqrt();
            let got = x.checked_sqrt().map_or(f64::INFINITY, Scalar::to_f64);
            ((got - want) / want).abs()
        })
        .fold(0.0, f64::max)
}

/// Whether `S`'s square root is rounded ([`sqrt_error`] within one `DELTA`): what every
/// bound that assumes unit directions needs (`f32m`'s approximate root leaves a
/// normalised direction up to 6 % off unit length).
pub fn sqrt_is_rounded<S: Scalar>() -> bool {
    sqrt_error::<S>() <= S::DELTA.to_f64()
}

/// Whether `S::dot3` rounds a dot product once (the wide accumulation): the floats always
/// (their bounds count their own per-operation rounding), a fixed format when its dot
/// product of (⅓, ⅓, ⅓) with itself (quantised) lands within ½ `DELTA` of the exact sum
/// of the quantised products. Three products each rounded towards −∞ (`i16f16n`'s narrow
/// dot products) lose 1⅔ `DELTA`s there.
pub fn dot_rounds_once<S: Scalar>() -> bool {
    if S::INT_BITS == 0 {
        return true;
    }
    let third = S::from_f64(1.0 / 3.0).unwrap();
    let exact = 3.0 * third.to_f64() * third.to_f64();
    let got = S::dot3([third; 3], [third; 3]).unwrap().to_f64();
    (got - exact).abs() <= 0.5 * S::DELTA.to_f64()
}

/// Whether `S` divides exactly where the quotient is representable (a fixed format's
/// truncation of the exact quotient, a float's rounding), as exact expected values
/// assume: then the unit normal of an axis-aligned plane is exact too. Not `i16f16r`: its
/// division by reciprocal is within 1 + |q|·2⁻²⁸ `DELTA`s (`fixray::num::variants`), so
/// even (0, 0, 1) normalises to 1 − `DELTA`.
pub fn divides_exactly<S: Scalar>() -> bool {
    let n = |k: i32| S::from_i32(k).unwrap();
    [(n(1), n(1)), (n(12), n(-1)), (n(-12), n(-1)), (n(30), n(3))]
        .iter()
        .all(|&(a, b)| a.checked_div(b).map(Scalar::to_f64) == Some(a.to_f64() / b.to_f64()))
}

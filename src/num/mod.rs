//! Number formats: the [`Scalar`] trait (arithmetic and conversions), its implementations
//! and the one list of formats.
//!
//! Geometry, scene and renderer are generic over `Scalar`. It is implemented for the
//! fixed-point formats [`I16F16`], [`I20F12`] and [`I32F32`] of the [`fixed`](::fixed) crate
//! (`fixed.rs`) and for `f32` and `f64` (`float.rs`); the `f64` instantiation is the
//! reference every other format is measured against. [`variants`] holds formats that differ
//! from a main one in a single choice, [`formats`] the list every tool takes its format
//! names from, and the shading series (`pow_unit`, `cos`) live in their own files under
//! `series/`, each with its test vectors and its stated maximum error.
//!
//! The overflow policy is in the method names, as in `fixed`: every operation that can
//! leave the format's range is `checked_` and returns `None` instead of wrapping or
//! panicking. For `f32`/`f64`, "overflow" means a non-finite result (infinity or NaN), so
//! callers handle both kinds of format the same way.
//!
//! ```
//! use fixray::{Scalar, I16F16};
//!
//! let a = I16F16::from_f64(1.5).unwrap();
//! assert_eq!(a.checked_mul(a).map(Scalar::to_f64), Some(2.25));
//! // 40000 does not fit in I16F16 (range ±32768): an error, never a wrap.
//! assert_eq!(I16F16::from_f64(40000.0), None);
//! assert_eq!(I16F16::MAX.checked_add(I16F16::ONE), None);
//! ```

use core::fmt::Debug;

mod decimal;
mod fixed;
mod float;
pub mod formats;
mod private;
mod recip;
pub mod series;
pub mod variants;
pub(crate) mod wide;

pub use decimal::Decimal;
pub(crate) use private::KernelArith;
pub use series::Series;

/// The fixed-point formats, from the [`fixed`](::fixed) crate, each a [`Scalar`]: `I16F16`
/// (16 integer bits, the sign's included, and 16 fraction bits: range ±32768, resolution
/// 2^−16), `I20F12` (±524288, 2^−12) and `I32F32` (±2^31, 2^−32).
///
/// ```
/// use fixray::{I16F16, I20F12, I32F32, Scalar};
///
/// assert_eq!(I16F16::DELTA.to_f64(), 1.0 / 65536.0);
/// assert_eq!(I20F12::DELTA.to_f64(), 1.0 / 4096.0);
/// assert_eq!(I32F32::DELTA.to_f64(), 2f64.powi(-32));
/// // 40000 fits I20F12 and I32F32, not I16F16.
/// assert_eq!(I16F16::from_f64(40000.0), None);
/// assert_eq!(I20F12::from_f64(40000.0).map(Scalar::to_f64), Some(40000.0));
/// assert_eq!(I32F32::from_f64(40000.0).map(Scalar::to_f64), Some(40000.0));
/// ```
pub use ::fixed::types::{I16F16, I20F12, I32F32};

/// How many of a format's [`Scalar::DELTA`]s make its default precision epsilon.
///
/// The epsilon guards the division by `N·d` in the plane test. `N` and `d` are unit vectors
/// whose components each carry up to 2 `DELTA`s of rounding from normalisation (measured
/// in `vec3`'s tests), and the wide dot product adds half a `DELTA`, so the computed `N·d`
/// is off by at most 2(‖N‖₁ + ‖d‖₁) + ½ ≤ 7.5 `DELTA`s (‖·‖₁ ≤ √3 for unit vectors; see
/// [`crate::geometry`]). With `|N·d| >= 16 DELTA` the sign of `N·d` is always right, with a
/// 2× margin, so a ray that passes the test is never sent to the wrong side of the plane;
/// its relative error is then at most 7.5/16 ≈ 0.47, and falls as 1/|N·d| above that.
/// 16 is the smallest power of two above twice the bound.
pub const EPSILON_DELTAS: i32 = 16;

/// A number format the ray caster can compute in.
///
/// All arithmetic that can overflow is `checked_`: `None` means "the result does not fit",
/// which the geometry turns into a documented miss and the scene parser into an error.
///
/// The shading series ([`Series`]) are a supertrait: every format has them, and they live
/// in their own files.
///
/// The trait is sealed: it is implemented for the formats of this module ([`I16F16`],
/// [`I20F12`], [`I32F32`], `f32`, `f64` and the [`variants`]) and cannot be implemented
/// outside the crate. Its other supertrait, `KernelArith`, is private to the crate: the
/// unrounded sums of products and the quick pixels the kernels step along a scanline,
/// which generic code reaches through `Scalar` and a user never needs.
///
/// ```
/// use fixray::{Scalar, I16F16, I32F32};
///
/// /// The hypotenuse in any format: `None` where it leaves the format's range.
/// fn hypot<S: Scalar>(a: S, b: S) -> Option<S> {
///     a.checked_mul(a)?.checked_add(b.checked_mul(b)?)?.checked_sqrt()
/// }
/// let int = |n| I16F16::from_i32(n).unwrap();
/// assert_eq!(hypot(int(3), int(4)), Some(int(5)));
/// assert_eq!(hypot(3.0_f64, 4.0), Some(5.0));
/// // 300² + 400² = 250000 does not fit I16F16 (±32768); it fits I32F32.
/// assert_eq!(hypot(int(300), int(400)), None);
/// let (a, b) = (I32F32::from_i32(300).unwrap(), I32F32::from_i32(400).unwrap());
/// assert_eq!(hypot(a, b).map(Scalar::to_f64), Some(500.0));
/// ```
pub trait Scalar: Series + KernelArith + Copy + PartialOrd + Debug + Send + Sync + 'static {
    /// Lower-case name as used on command lines: `i16f16`, `f32`, ...
    const NAME: &'static str;
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// The largest finite value.
    const MAX: Self;
    /// The resolution: the step between neighbouring values near 1 (for fixed formats the
    /// step everywhere; for floats the machine epsilon).
    const DELTA: Self;
    /// The default precision epsilon of the intersection tests: [`EPSILON_DELTAS`] × `DELTA`.
    /// A scene's `precision` overrides it.
    const DEFAULT_EPSILON: Self;

    /// Converts an `f64`, rounding to the nearest representable value; `None` when the
    /// value is not finite or outside the format's range.
    fn from_f64(value: f64) -> Option<Self>;
    /// Converts a decimal as written in a scene, rounding its exact value to the nearest
    /// representable one (ties away from zero for fixed formats, to even for floats);
    /// `None` when it is outside the format's range.
    fn from_decimal(value: Decimal) -> Option<Self>;
    /// Converts an integer exactly; `None` when it is outside the format's range.
    fn from_i32(value: i32) -> Option<Self>;
    /// Converts to `f64` (exact for every format here except very large `I32F32` values).
    fn to_f64(self) -> f64;

    /// `self + rhs`, or `None` on overflow.
    fn checked_add(self, rhs: Self) -> Option<Self>;
    /// `self - rhs`, or `None` on overflow.
    fn checked_sub(self, rhs: Self) -> Option<Self>;
    /// `self × rhs`, or `None` on overflow. Fixed formats round towards −∞ (error < 1 `DELTA`).
    fn checked_mul(self, rhs: Self) -> Option<Self>;
    /// `self / rhs`, or `None` on overflow or when `rhs` is zero.
    fn checked_div(self, rhs: Self) -> Option<Self>;
    /// `√self`, or `None` when `self` is negative.
    fn checked_sqrt(self) -> Option<Self>;
    /// `|self|`, saturating at [`Scalar::MAX`] (only the fixed formats' `MIN` saturates).
    fn abs(self) -> Self;

    /// The dot product `a·b` of two 3-vectors.
    ///
    /// Fixed formats multiply into the double-width format (`wide_mul`, exact), add there,
    /// and round once to nearest when narrowing back: error ≤ ½ `DELTA` instead of up to
    /// 3 `DELTA`s for three narrow products. `None` when the sum does not fit.
    fn dot3(a: [Self; 3], b: [Self; 3]) -> Option<Self>;

    /// Compares the products `a·b` and `c·d`: exactly in the fixed formats (double-width
    /// products), to the format's own rounding in floats (exactly where both overflow).
    /// The division-free comparison of two quotients `a/d` and `c/b` with positive
    /// denominators. `None` only for floats, when a product has no value (a NaN operand,
    /// or an infinity times zero), never a silent tie.
    fn cmp_products(a: Self, b: Self, c: Self, d: Self) -> Option<core::cmp::Ordering>;

    /// `c − a·b`, rounded once like [`Scalar::dot3`]: `None` only when the result does not
    /// fit (`a·b` alone may exceed the range, as for `D' − N·b` with a far eye).
    fn sub_dot3(c: Self, a: [Self; 3], b: [Self; 3]) -> Option<Self>;

    /// `self × num / den`, `None` on overflow or when `den` is zero. Fixed formats round
    /// once (a double-width intermediate); floats round the product and the quotient.
    /// Used for pixel → screen coordinates.
    fn mul_ratio(self, num: i32, den: i32) -> Option<Self>;

    /// Rounds to the nearest integer (ties away from zero); `None` when out of `i32` range.
    fn round_to_i32(self) -> Option<i32>;

    /// Rounds towards −∞ to an integer; `None` when out of `i32` range.
    fn floor_to_i32(self) -> Option<i32>;

    /// The spacing of the format at the magnitude of `self`, or at 1 when `|self| < 1`:
    /// `DELTA` everywhere for fixed formats, `EPSILON × max(|self|, 1)` for floats. One
    /// rounding errs by at most this much; error bounds are written in these units.
    fn ulp(self) -> Self;

    /// The integer bits of a fixed format (its range is ±2^(INT_BITS − 1)); 0 for the
    /// floats, whose resolution is relative rather than absolute.
    const INT_BITS: u32;

    /// `self × k` for an integer `k`, exact, or `None` on overflow.
    fn checked_mul_int(self, k: i32) -> Option<Self>;

    /// The larger of two values.
    #[inline]
    fn max(self, other: Self) -> Self {
        if other > self { other } else { self }
    }

    /// The smaller of two values.
    #[inline]
    fn min(self, other: Self) -> Self {
        if other < self { other } else { self }
    }

    /// `-self`, or `None` on overflow.
    #[inline]
    fn checked_neg(self) -> Option<Self> {
        Self::ZERO.checked_sub(self)
    }
}

/// A seeded xorshift64 generator for the unit tests' cases (the same sequence on every
/// machine), with the whole numbers and reals the tests' scenes are drawn from.
#[cfg(test)]
pub(crate) struct Rng(pub(crate) u64);

#[cfg(test)]
impl Rng {
    /// The next value.
    pub(crate) fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A whole number in `0..n`.
    pub(crate) fn below(&mut self, n: u32) -> u32 {
        u32::try_from(self.next() % u64::from(n)).unwrap_or(0)
    }

    /// A real in `[lo, hi)`.
    pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let u = f64::from(self.below(1 << 24)) / f64::from(1u32 << 24);
        lo + (hi - lo) * u
    }
}

/// [`Rng`]'s sequence as a closure.
#[cfg(test)]
pub(crate) fn xorshift(seed: u64) -> impl FnMut() -> u64 {
    let mut rng = Rng(seed);
    move || rng.next()
}

/// [`Rng`]'s sequence as reals in `[0, 1)`, 53 bits each.
#[cfg(test)]
pub(crate) fn unit_reals(seed: u64) -> impl FnMut() -> f64 {
    let mut next = xorshift(seed);
    move || (next() >> 11) as f64 / (1u64 << 53) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every format in one list, so that tests cover them all.
    fn check_basic<S: Scalar>() {
        let two = S::from_i32(2).unwrap();
        let three = S::from_i32(3).unwrap();
        assert_eq!(two.checked_mul(three).unwrap().to_f64(), 6.0, "{}", S::NAME);
        assert_eq!(S::ONE.checked_div(S::ZERO), None, "{}", S::NAME);
        assert_eq!(S::MAX.checked_mul(two), None, "{}", S::NAME);
        assert_eq!(S::from_f64(f64::NAN), None, "{}", S::NAME);
        assert_eq!(S::from_f64(f64::INFINITY), None, "{}", S::NAME);
        assert_eq!(S::from_i32(-4).unwrap().checked_sqrt(), None, "{}", S::NAME);
        assert_eq!(
            S::from_i32(9).unwrap().checked_sqrt().unwrap().to_f64(),
            3.0,
            "{}",
            S::NAME
        );
        assert_eq!(
            S::from_f64(2.5).unwrap().round_to_i32(),
            Some(3),
            "{}",
            S::NAME
        );
        assert_eq!(
            S::from_f64(-2.5).unwrap().round_to_i32(),
            Some(-3),
            "{}",
            S::NAME
        );
        assert!(S::DEFAULT_EPSILON > S::ZERO);
        assert_eq!(
            S::DEFAULT_EPSILON.to_f64(),
            S::DELTA.to_f64() * f64::from(EPSILON_DELTAS)
        );
    }

    #[test]
    fn basic_arithmetic_in_every_format() {
        check_basic::<I16F16>();
        check_basic::<I20F12>();
        check_basic::<I32F32>();
        check_basic::<f32>();
        check_basic::<f64>();
    }

    #[test]
    fn out_of_range_conversion_is_refused() {
        assert_eq!(I16F16::from_f64(32768.0), None);
        assert!(I16F16::from_f64(32767.0).is_some());
        assert_eq!(I20F12::from_f64(524_288.0), None);
        assert_eq!(I32F32::from_f64(3.0e9), None);
        assert_eq!(f32::from_f64(1.0e39), None);
        assert_eq!(I16F16::from_i32(40_000), None);
    }

    #[test]
    fn wide_dot_rounds_once_to_nearest() {
        // (1/3 quantised)² × 3: the exact sum of the quantised products, rounded once.
        let third = I16F16::from_f64(1.0 / 3.0).unwrap();
        let v = [third; 3];
        let wide = I16F16::dot3(v, v).unwrap();
        let exact = 3.0 * third.to_f64() * third.to_f64();
        assert!((wide.to_f64() - exact).abs() <= 0.5 * I16F16::DELTA.to_f64());
        // Overflow of the sum (not of any single product) is refused.
        let big = I16F16::from_i32(30_000).unwrap();
        assert_eq!(I16F16::dot3([big; 3], [I16F16::ONE; 3]), None);
    }

    /// `dot3` is the rounding of the accumulated products, and stepping an accumulator
    /// by a product gives the dot product of the stepped vector, bit for bit in the
    /// fixed formats.
    fn check_acc<S: Scalar>(exact: bool) {
        let v = |x: f64, y: f64, z: f64| [x, y, z].map(|c| S::from_f64(c).unwrap());
        let n = v(0.371, -0.802, 0.468);
        let mut d = v(-3.217, 1.093, -6.0);
        let step = S::from_f64(0.05).unwrap();
        let mut acc = S::acc_dot3(n, d).unwrap();
        let per_step = S::acc_mul(n[0], step).unwrap();
        for _ in 0..200 {
            assert_eq!(S::acc_round(S::acc_dot3(n, d).unwrap()), S::dot3(n, d));
            d[0] = d[0].checked_add(step).unwrap();
            acc = S::acc_add(acc, per_step).unwrap();
            let stepped = S::acc_round(acc).unwrap().to_f64();
            let direct = S::dot3(n, d).unwrap().to_f64();
            if exact {
                assert_eq!(stepped, direct, "{}", S::NAME);
            } else {
                assert!((stepped - direct).abs() < 1e-4, "{}", S::NAME);
            }
        }
    }

    #[test]
    fn accumulated_dot_products_step_exactly_in_fixed_formats() {
        check_acc::<I16F16>(true);
        check_acc::<I20F12>(true);
        check_acc::<I32F32>(true);
        check_acc::<f32>(false);
        check_acc::<f64>(false);
    }

    #[test]
    fn mul_ratio_has_one_rounding() {
        let w = I16F16::from_i32(8).unwrap();
        // 8 × 3 / 320 = 0.075
        let x = w.mul_ratio(3, 320).unwrap();
        assert!((x.to_f64() - 0.075).abs() <= I16F16::DELTA.to_f64());
        assert_eq!(w.mul_ratio(1, 0), None);
        assert_eq!(I16F16::MAX.mul_ratio(3, 1), None);
        assert_eq!(2.0f64.mul_ratio(3, 4), Some(1.5));
    }
}

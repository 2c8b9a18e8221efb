//! The [`Scalar`] trait: one code path, many number formats.
//!
//! Geometry, scene and renderer are generic over `Scalar`. It is implemented for the
//! fixed-point formats [`I16F16`], [`I20F12`] and [`I32F32`] of the [`fixed`] crate and for
//! `f32` and `f64`; the `f64` instantiation is the reference every other format is measured
//! against.
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

use crate::decimal::Decimal;

pub use fixed::types::{I16F16, I20F12, I32F32};

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
pub trait Scalar: Copy + PartialOrd + Debug + Send + Sync + 'static {
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
    /// products), to the format's own rounding in floats. The division-free comparison of
    /// two quotients `a/d` and `c/b` with positive denominators.
    fn cmp_products(a: Self, b: Self, c: Self, d: Self) -> core::cmp::Ordering;

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

    /// `self^exponent` for `self` in [0, 1] and `exponent >= 1` (the specular term).
    /// Floats use `libm`'s `pow`. Fixed formats raise to the integer part by repeated
    /// squaring (exact up to rounding: integer shininess is exact) and take the fraction
    /// f as the interpolation `x^f ≈ 1 − f + f·x` (error below 0.03 for x ≥ ½, which is
    /// where a specular glint is visible; it vanishes for integer exponents).
    fn pow_unit(self, exponent: Self) -> Option<Self>;

    /// The cosine of an angle in radians, |angle| ≤ π (spotlight cones). Floats use
    /// `libm`; fixed formats sum the Taylor series to x¹⁴/14! (truncation error below
    /// 1e-8 on [−π/2, π/2], under one DELTA of every fixed format here).
    fn cos(self) -> Option<Self>;

    /// The spacing of the format at the magnitude of `self`, or at 1 when `|self| < 1`:
    /// `DELTA` everywhere for fixed formats, `EPSILON × max(|self|, 1)` for floats. One
    /// rounding errs by at most this much; error bounds are written in these units.
    fn ulp(self) -> Self;

    /// How many bits [`crate::flat`] scales a ratio of at most 1 up by, so that it keeps the
    /// format's full resolution: half the integer bits of a fixed format (I16F16: 8, so
    /// `2^8/|num|` still fits for planes 1/128 of a unit from the eye), 0 for floats (their
    /// resolution is relative).
    const RATIO_SHIFT: u32;

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

/// The exact product of two `i32`s, from four 16 × 16 → 32 multiplications: what a core
/// without a long multiply (Cortex-M0: no `SMULL`) does far faster than the 64-bit
/// multiply helper (about 15 instructions against 41, `../shared/measurements.md`).
/// Bit-identical to `i64::from(a) * i64::from(b)` (tested on every sign and size).
#[inline(always)]
pub fn mul_wide_halves(a: i32, b: i32) -> i64 {
    // a = ah·2¹⁶ + al with ah signed and al in [0, 2¹⁶); the same for b.
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // |ah·bh| ≤ 2³⁰; |ah·bl|, |al·bh| < 2³¹; al·bl < 2³² (u32).
    let high = i64::from(ah * bh);
    let middle = i64::from(ah * bl) + i64::from(al * bh);
    let low = i64::from(al.cast_unsigned() * bl.cast_unsigned());
    (high << 32) + (middle << 16) + low
}

/// The exact product of two `i32`s: one long multiply where the core has it, otherwise
/// [`mul_wide_halves`] (chosen by the build script for the target, not by the format).
#[inline(always)]
fn mul_wide_i32(a: i32, b: i32) -> i64 {
    #[cfg(no_long_multiply)]
    {
        mul_wide_halves_call(a, b)
    }
    #[cfg(not(no_long_multiply))]
    {
        i64::from(a) * i64::from(b)
    }
}

/// [`mul_wide_halves`] as one function (a call, as the 64-bit helper is, but about a third
/// of its instructions): inlined at every product it would add kilobytes of flash.
#[cfg(no_long_multiply)]
#[inline(never)]
fn mul_wide_halves_call(a: i32, b: i32) -> i64 {
    mul_wide_halves(a, b)
}

/// The exact product of two `u32`s: one long multiply where the core has it, otherwise
/// from 16-bit halves as [`mul_wide_halves`].
#[inline(always)]
pub(crate) fn mul_wide_u32(a: u32, b: u32) -> u64 {
    #[cfg(no_long_multiply)]
    {
        let (ah, al) = (a >> 16, a & 0xFFFF);
        let (bh, bl) = (b >> 16, b & 0xFFFF);
        let middle = u64::from(ah * bl) + u64::from(al * bh);
        (u64::from(ah * bh) << 32) + (middle << 16) + u64::from(al * bl)
    }
    #[cfg(not(no_long_multiply))]
    {
        u64::from(a) * u64::from(b)
    }
}

/// The exact product of two `i64`s (`I32F32`'s double width). One shared function: a
/// 128-bit product inlined at every use would double I32F32's flash on a 32-bit core.
#[inline(never)]
fn mul_wide_i64(a: i64, b: i64) -> i128 {
    i128::from(a) * i128::from(b)
}

/// `bits × num / den` truncated towards zero, as the double-width quotient
/// `(bits·num)/den` would give it, without dividing in double width: with
/// `bits = q·den + r`, the result is `q·num + (r·num)/den`, where `|r·num| < |den·num|`
/// nearly always fits an `i32` (screen coordinates: below 2²⁶), so the division is a
/// 32-bit one (one instruction on the Cortex-M4 instead of the 64-bit helper's ~350).
/// Both parts have the same sign, so truncating the second truncates the sum.
/// `None` on overflow or when `den` is zero.
macro_rules! mul_ratio_bits {
    ($bits:expr, $num:expr, $den:expr, $b:ty, $wide:ty) => {{
        let (bits, num, den): ($b, i32, i32) = ($bits, $num, $den);
        (|| {
            let q = bits.checked_div(<$b>::from(den))?;
            let r = bits.checked_rem(<$b>::from(den))?;
            let whole = q.checked_mul(<$b>::from(num))?;
            let part = <$wide>::from(r) * <$wide>::from(num);
            let frac = match i32::try_from(part) {
                Ok(p) => <$wide>::from(p / den),
                Err(_) => part / <$wide>::from(den),
            };
            whole.checked_add(<$b>::try_from(frac).ok()?)
        })()
    }};
}

macro_rules! impl_fixed {
    ($t:ty, $name:literal, $wide:ty, $bits:ty, $wide_bits:ty, $mul:path) => {
        impl Scalar for $t {
            const NAME: &'static str = $name;
            const ZERO: Self = <$t>::ZERO;
            const ONE: Self = <$t>::ONE;
            const MAX: Self = <$t>::MAX;
            const DELTA: Self = <$t>::DELTA;
            const DEFAULT_EPSILON: Self = <$t>::from_bits(EPSILON_DELTAS as $bits);
            const RATIO_SHIFT: u32 = <$t>::INT_NBITS / 2;

            #[inline]
            fn checked_mul_int(self, k: i32) -> Option<Self> {
                <$t>::checked_mul_int(self, <$bits>::from(k))
            }

            #[inline]
            fn from_f64(value: f64) -> Option<Self> {
                // `checked_from_num` rounds to nearest (ties to even) and returns `None`
                // for NaN, infinities and out-of-range values.
                <$t>::checked_from_num(value)
            }
            fn from_decimal(value: Decimal) -> Option<Self> {
                // Integer arithmetic only: exact, and no float code on a chip.
                let bits = value.to_fixed_bits(<$t>::FRAC_NBITS)?;
                <$bits>::try_from(bits).ok().map(<$t>::from_bits)
            }
            #[inline]
            fn from_i32(value: i32) -> Option<Self> {
                <$t>::checked_from_num(value)
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self.to_num::<f64>()
            }
            #[inline]
            fn checked_add(self, rhs: Self) -> Option<Self> {
                <$t>::checked_add(self, rhs)
            }
            #[inline]
            fn checked_sub(self, rhs: Self) -> Option<Self> {
                <$t>::checked_sub(self, rhs)
            }
            #[inline]
            fn checked_mul(self, rhs: Self) -> Option<Self> {
                // As `fixed`'s `checked_mul` (the exact product, floored), with the
                // product formed by `$mul`.
                let product = $mul(self.to_bits(), rhs.to_bits()) >> <$t>::FRAC_NBITS;
                <$bits>::try_from(product).ok().map(<$t>::from_bits)
            }
            #[inline]
            fn checked_div(self, rhs: Self) -> Option<Self> {
                <$t>::checked_div(self, rhs)
            }
            #[inline]
            fn checked_sqrt(self) -> Option<Self> {
                <$t>::checked_sqrt(self)
            }
            #[inline]
            fn abs(self) -> Self {
                self.saturating_abs()
            }
            #[inline]
            fn dot3(a: [Self; 3], b: [Self; 3]) -> Option<Self> {
                let w = |x: Self, y: Self| <$wide>::from_bits($mul(x.to_bits(), y.to_bits()));
                let sum = w(a[0], b[0])
                    .checked_add(w(a[1], b[1]))?
                    .checked_add(w(a[2], b[2]))?;
                // Round to nearest: add half a narrow DELTA, then narrowing floors.
                let half = <$wide>::from_num(<$t>::DELTA) >> 1u32;
                <$t>::checked_from_num(sum.checked_add(half)?)
            }
            #[inline]
            fn cmp_products(a: Self, b: Self, c: Self, d: Self) -> core::cmp::Ordering {
                $mul(a.to_bits(), b.to_bits()).cmp(&$mul(c.to_bits(), d.to_bits()))
            }
            #[inline]
            fn sub_dot3(c: Self, a: [Self; 3], b: [Self; 3]) -> Option<Self> {
                let w = |x: Self, y: Self| <$wide>::from_bits($mul(x.to_bits(), y.to_bits()));
                let diff = <$wide>::from_num(c)
                    .checked_sub(w(a[0], b[0]))?
                    .checked_sub(w(a[1], b[1]))?
                    .checked_sub(w(a[2], b[2]))?;
                let half = <$wide>::from_num(<$t>::DELTA) >> 1u32;
                <$t>::checked_from_num(diff.checked_add(half)?)
            }
            #[inline]
            fn mul_ratio(self, num: i32, den: i32) -> Option<Self> {
                mul_ratio_bits!(self.to_bits(), num, den, $bits, $wide_bits).map(<$t>::from_bits)
            }
            #[inline]
            fn round_to_i32(self) -> Option<i32> {
                self.checked_round()?.checked_to_num::<i32>()
            }
            #[inline]
            fn ulp(self) -> Self {
                <$t>::DELTA
            }
            #[inline]
            fn floor_to_i32(self) -> Option<i32> {
                self.checked_floor()?.checked_to_num::<i32>()
            }
            fn pow_unit(self, exponent: Self) -> Option<Self> {
                pow_unit_series(self, exponent)
            }
            fn cos(self) -> Option<Self> {
                cos_series(self)
            }
        }
    };
}

impl_fixed!(
    I16F16,
    "i16f16",
    fixed::types::I32F32,
    i32,
    i64,
    mul_wide_i32
);
impl_fixed!(
    I20F12,
    "i20f12",
    fixed::types::I40F24,
    i32,
    i64,
    mul_wide_i32
);
impl_fixed!(
    I32F32,
    "i32f32",
    fixed::types::I64F64,
    i64,
    i128,
    mul_wide_i64
);

macro_rules! impl_float {
    ($t:ty, $name:literal, $sqrt:path, $round:path, $floor:path, $pow:path, $cos:path) => {
        impl Scalar for $t {
            const NAME: &'static str = $name;
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const MAX: Self = <$t>::MAX;
            const DELTA: Self = <$t>::EPSILON;
            // EPSILON_DELTAS is a small integer: exact in both float formats.
            const DEFAULT_EPSILON: Self = <$t>::EPSILON * EPSILON_DELTAS as $t;
            const RATIO_SHIFT: u32 = 0;

            #[inline]
            fn checked_mul_int(self, k: i32) -> Option<Self> {
                Some(self * Self::from_i32(k)?).filter(|v| v.is_finite())
            }

            #[inline]
            fn from_f64(value: f64) -> Option<Self> {
                // Rounds to nearest; out-of-range values become infinite and are refused.
                #[allow(clippy::cast_possible_truncation)]
                let v = value as $t;
                v.is_finite().then_some(v)
            }
            fn from_decimal(value: Decimal) -> Option<Self> {
                // core's parser rounds correctly (straight to this width, no double
                // rounding); the decimal is written back out digit for digit to use it.
                use core::fmt::Write;
                let mut text: heapless::String<40> = heapless::String::new();
                let sign = if value.negative { "-" } else { "" };
                write!(text, "{sign}{}e{}", value.mantissa, value.exponent).ok()?;
                text.parse::<$t>().ok().filter(|v| v.is_finite())
            }
            #[inline]
            fn from_i32(value: i32) -> Option<Self> {
                // Every i32 is within range; f32 rounds above 2^24.
                Self::from_f64(f64::from(value))
            }
            #[inline]
            fn to_f64(self) -> f64 {
                f64::from(self)
            }
            #[inline]
            fn checked_add(self, rhs: Self) -> Option<Self> {
                Some(self + rhs).filter(|v| v.is_finite())
            }
            #[inline]
            fn checked_sub(self, rhs: Self) -> Option<Self> {
                Some(self - rhs).filter(|v| v.is_finite())
            }
            #[inline]
            fn checked_mul(self, rhs: Self) -> Option<Self> {
                Some(self * rhs).filter(|v| v.is_finite())
            }
            #[inline]
            fn checked_div(self, rhs: Self) -> Option<Self> {
                Some(self / rhs).filter(|v| v.is_finite())
            }
            #[inline]
            fn checked_sqrt(self) -> Option<Self> {
                Some($sqrt(self)).filter(|v| v.is_finite())
            }
            #[inline]
            fn abs(self) -> Self {
                if self < 0.0 { -self } else { self }
            }
            #[inline]
            fn dot3(a: [Self; 3], b: [Self; 3]) -> Option<Self> {
                Some(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).filter(|v| v.is_finite())
            }
            #[inline]
            fn sub_dot3(c: Self, a: [Self; 3], b: [Self; 3]) -> Option<Self> {
                Some(c - (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])).filter(|v| v.is_finite())
            }
            #[inline]
            fn cmp_products(a: Self, b: Self, c: Self, d: Self) -> core::cmp::Ordering {
                // In the format itself: each product rounds once (½ ulp). Widening f32 to
                // f64 would be exact but is soft-float on an FPU that has only f32.
                (a * b)
                    .partial_cmp(&(c * d))
                    .unwrap_or(core::cmp::Ordering::Equal)
            }
            #[inline]
            fn mul_ratio(self, num: i32, den: i32) -> Option<Self> {
                let num = Self::from_i32(num)?;
                let den = Self::from_i32(den)?;
                Some(self * num / den).filter(|v| v.is_finite())
            }
            #[inline]
            fn round_to_i32(self) -> Option<i32> {
                let r = $round(self);
                // The range test also refuses NaN.
                if (-2_147_483_648.0..2_147_483_648.0).contains(&r) {
                    #[allow(clippy::cast_possible_truncation)]
                    Some(r as i32)
                } else {
                    None
                }
            }
            fn pow_unit(self, exponent: Self) -> Option<Self> {
                Some($pow(self, exponent)).filter(|v| v.is_finite())
            }
            fn cos(self) -> Option<Self> {
                Some($cos(self)).filter(|v| v.is_finite())
            }
            #[inline]
            fn floor_to_i32(self) -> Option<i32> {
                let r = $floor(self);
                if (-2_147_483_648.0..2_147_483_648.0).contains(&r) {
                    #[allow(clippy::cast_possible_truncation)]
                    Some(r as i32)
                } else {
                    None
                }
            }
            #[inline]
            fn ulp(self) -> Self {
                let m = if self < 0.0 { -self } else { self };
                <$t>::EPSILON * if m > 1.0 { m } else { 1.0 }
            }
        }
    };
}

impl_float!(
    f32,
    "f32",
    libm::sqrtf,
    libm::roundf,
    libm::floorf,
    libm::powf,
    libm::cosf
);
impl_float!(
    f64,
    "f64",
    libm::sqrt,
    libm::round,
    libm::floor,
    libm::pow,
    libm::cos
);

/// `x^e` for x in [0, 1], e ≥ 1, with the formats' own arithmetic (see [`Scalar::pow_unit`]).
pub fn pow_unit_series<S: Scalar>(x: S, e: S) -> Option<S> {
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

/// cos x by its Taylor series to x¹⁴/14! (see [`Scalar::cos`]).
pub fn cos_series<S: Scalar>(x: S) -> Option<S> {
    let x2 = x.checked_mul(x)?;
    // Horner form of Σ (−1)^k x^2k / (2k)!, k = 0..=7, from the inside out:
    // 1 − x²/2 (1 − x²/12 (1 − x²/30 (1 − x²/56 (1 − x²/90 (1 − x²/132 (1 − x²/182))))))
    let mut acc = S::ONE;
    for d in [182, 132, 90, 56, 30, 12, 2] {
        acc = S::ONE.checked_sub(x2.checked_mul(acc)?.checked_div(S::from_i32(d)?)?)?;
    }
    Some(acc)
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

    #[test]
    fn products_from_halves_are_exact() {
        let edges = [
            i32::MIN,
            i32::MIN + 1,
            -65_537,
            -65_536,
            -65_535,
            -1,
            0,
            1,
            0xFFFF,
            0x1_0000,
            0x1_0001,
            i32::MAX - 1,
            i32::MAX,
        ];
        for a in edges {
            for b in edges {
                assert_eq!(
                    mul_wide_halves(a, b),
                    i64::from(a) * i64::from(b),
                    "{a} {b}"
                );
            }
        }
        // A seeded sweep (xorshift) over every size.
        let mut x: u32 = 0x2026_1124;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let a = x.cast_signed() >> (x % 31);
            let b = x.rotate_left(11).cast_signed() >> (x % 29);
            assert_eq!(
                mul_wide_halves(a, b),
                i64::from(a) * i64::from(b),
                "{a} {b}"
            );
        }
    }

    #[test]
    fn checked_mul_matches_fixed() {
        let values = [
            -32768.0, -300.5, -1.0, -0.000_015, 0.0, 0.3, 1.0, 181.0, 32767.99,
        ];
        for a in values {
            for b in values {
                let (x, y) = (I16F16::from_f64(a).unwrap(), I16F16::from_f64(b).unwrap());
                assert_eq!(Scalar::checked_mul(x, y), x.checked_mul(y), "{a} {b}");
                let (x, y) = (I20F12::from_f64(a).unwrap(), I20F12::from_f64(b).unwrap());
                assert_eq!(Scalar::checked_mul(x, y), x.checked_mul(y), "{a} {b}");
            }
        }
    }

    #[test]
    fn mul_ratio_equals_the_double_width_quotient() {
        let wide = |bits: i32, num: i32, den: i32| -> Option<i32> {
            let q = (i64::from(bits) * i64::from(num)).checked_div(i64::from(den))?;
            i32::try_from(q).ok()
        };
        let mut x: u64 = 0x2026_1124_0000_0001;
        for case in 0..300_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let bits = (x as u32).cast_signed() >> (x % 32);
            let num = ((x >> 32) as u32).cast_signed() >> ((x >> 8) % 32);
            let den = ((x >> 16) as u32).cast_signed() >> ((x >> 24) % 32);
            let den = if case % 3 == 0 { den % 8192 } else { den };
            let got = mul_ratio_bits!(bits, num, den, i32, i64);
            let want = if den == 0 { None } else { wide(bits, num, den) };
            // The split form may refuse a result right at the range's edge (q·num alone
            // overflowing while the sum would not): never a different value.
            if got != want {
                assert!(got.is_none(), "{bits} {num} {den}: {got:?} vs {want:?}");
                let exact = i64::from(bits) * i64::from(num) / i64::from(den);
                assert!(exact.unsigned_abs() > (1 << 30), "{bits} {num} {den}");
            }
            let got64 = mul_ratio_bits!(i64::from(bits) << 16, num, den, i64, i128);
            let want64 = (den != 0)
                .then(|| i128::from(i64::from(bits) << 16) * i128::from(num) / i128::from(den))
                .and_then(|q| i64::try_from(q).ok());
            if got64 != want64 {
                assert!(got64.is_none(), "i64 {bits} {num} {den}");
            }
        }
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

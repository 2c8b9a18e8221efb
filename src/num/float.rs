//! [`Scalar`] for `f32` and `f64` (the reference): IEEE arithmetic with `libm`'s correctly
//! rounded square root, "overflow" meaning a non-finite result.

use core::cmp::Ordering;

use super::{Decimal, EPSILON_DELTAS, KernelArith, Scalar};

/// An integral float (already rounded) as an `i32`, in its own width (a wider type would
/// be soft float on an f32-only FPU); `None` outside the range, and for NaN, which the
/// range test refuses.
macro_rules! integral_to_i32 {
    ($r:expr) => {{
        let r = $r;
        if (-2_147_483_648.0..2_147_483_648.0).contains(&r) {
            #[allow(clippy::cast_possible_truncation)]
            Some(r as i32)
        } else {
            None
        }
    }};
}

/// A scene number as an `f32`: correctly rounded by integer arithmetic
/// ([`Decimal::to_f32`], no float-parsing tables in a chip's flash).
fn f32_of_decimal(value: Decimal) -> Option<f32> {
    value.to_f32()
}

/// A scene number as an `f64` (the host's reference): `core`'s correctly rounded parser
/// (straight to this width, no double rounding), the decimal written back out digit for
/// digit to use it.
fn f64_of_decimal(value: Decimal) -> Option<f64> {
    use core::fmt::Write;
    let mut text: heapless::String<40> = heapless::String::new();
    let sign = if value.negative { "-" } else { "" };
    write!(text, "{sign}{}e{}", value.mantissa, value.exponent).ok()?;
    text.parse::<f64>().ok().filter(|v| v.is_finite())
}

macro_rules! impl_float {
    ($t:ty, $name:literal, $sqrt:path, $round:path, $floor:path, $tie:path, $decimal:path) => {
        impl Scalar for $t {
            const NAME: &'static str = $name;
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const MAX: Self = <$t>::MAX;
            const DELTA: Self = <$t>::EPSILON;
            // EPSILON_DELTAS is a small integer: exact in both float formats.
            const DEFAULT_EPSILON: Self = <$t>::EPSILON * EPSILON_DELTAS as $t;
            const INT_BITS: u32 = 0;

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
                $decimal(value)
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
            fn cmp_products(a: Self, b: Self, c: Self, d: Self) -> Option<core::cmp::Ordering> {
                // In the format itself: each product rounds once (½ ulp); a NaN product
                // (an infinity times a zero operand) is `None`. Equal products go out of
                // line (a cold function: they are rare): a
                // finite tie is a tie, but two products overflowing to the same infinity
                // are decided exactly (the finite operands say which is larger).
                let order = (a * b).partial_cmp(&(c * d));
                if order == Some(core::cmp::Ordering::Equal) {
                    $tie(a, b, c, d)
                } else {
                    order
                }
            }
            #[inline]
            fn mul_ratio(self, num: i32, den: i32) -> Option<Self> {
                let num = Self::from_i32(num)?;
                let den = Self::from_i32(den)?;
                Some(self * num / den).filter(|v| v.is_finite())
            }
            #[inline]
            fn round_to_i32(self) -> Option<i32> {
                integral_to_i32!($round(self))
            }
            #[inline]
            fn floor_to_i32(self) -> Option<i32> {
                integral_to_i32!($floor(self))
            }
            #[inline]
            fn ulp(self) -> Self {
                let m = if self < 0.0 { -self } else { self };
                <$t>::EPSILON * if m > 1.0 { m } else { 1.0 }
            }
        }

        impl KernelArith for $t {
            const EXACT_SUMS: bool = false;
            const EXACT_PRODUCTS: bool = false;
            type Acc = $t;
            type QuickTerm = ();
            #[inline]
            fn acc_mul(a: Self, b: Self) -> Option<Self> {
                Some(a * b).filter(|v| v.is_finite())
            }
            #[inline]
            fn acc_add(x: Self, y: Self) -> Option<Self> {
                Some(x + y).filter(|v| v.is_finite())
            }
            #[inline]
            fn acc_round(x: Self) -> Option<Self> {
                Some(x).filter(|v| v.is_finite())
            }
            #[inline]
            fn acc_dot3(a: [Self; 3], b: [Self; 3]) -> Option<Self> {
                Self::dot3(a, b)
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
    tie_f32,
    f32_of_decimal
);
impl_float!(
    f64,
    "f64",
    libm::sqrt,
    libm::round,
    libm::floor,
    tie_f64,
    f64_of_decimal
);

/// `a·b` and `c·d` compared neither less nor greater in `f32`: equal when that is a
/// finite value, otherwise decided exactly.
#[cold]
#[inline(never)]
fn tie_f32(a: f32, b: f32, c: f32, d: f32) -> Option<Ordering> {
    if (a * b).is_finite() && (c * d).is_finite() {
        return Some(Ordering::Equal);
    }
    cmp_products_f32(a, b, c, d)
}

/// As [`tie_f32`] for `f64`.
#[cold]
#[inline(never)]
fn tie_f64(a: f64, b: f64, c: f64, d: f64) -> Option<Ordering> {
    if (a * b).is_finite() && (c * d).is_finite() {
        return Some(Ordering::Equal);
    }
    cmp_products_f64(a, b, c, d)
}

/// `a·b` against `c·d` exactly for `f32` operands: in `f64` a product of two `f32`s is exact
/// (24 + 24 significant bits) and finite. `None` when an operand is NaN or a product is
/// (an infinity times zero).
fn cmp_products_f32(a: f32, b: f32, c: f32, d: f32) -> Option<Ordering> {
    (f64::from(a) * f64::from(b)).partial_cmp(&(f64::from(c) * f64::from(d)))
}

/// `a·b` against `c·d` for `f64` operands whose products overflow: compared as sign,
/// binary exponent and mantissa (`frexp`), which cannot overflow. `None` when an operand
/// is NaN or a product is an infinity times zero.
fn cmp_products_f64(a: f64, b: f64, c: f64, d: f64) -> Option<Ordering> {
    /// The product as (sign, exponent, mantissa in [0.5, 1)); `None` for NaN.
    fn parts(x: f64, y: f64) -> Option<(i8, i64, f64)> {
        if x.is_nan() || y.is_nan() {
            return None;
        }
        let sign = |v: f64| if v < 0.0 { -1i8 } else { 1 };
        if x == 0.0 || y == 0.0 {
            // An infinity times zero has no value.
            return if x.is_infinite() || y.is_infinite() {
                None
            } else {
                Some((0, 0, 0.0))
            };
        }
        let s = sign(x) * sign(y);
        if x.is_infinite() || y.is_infinite() {
            return Some((s, i64::MAX, 1.0));
        }
        let (mx, ex) = libm::frexp(x.abs());
        let (my, ey) = libm::frexp(y.abs());
        let (m, e) = libm::frexp(mx * my);
        Some((s, i64::from(ex) + i64::from(ey) + i64::from(e), m))
    }
    let (sp, ep, mp) = parts(a, b)?;
    let (sq, eq, mq) = parts(c, d)?;
    if sp != sq {
        return Some(sp.cmp(&sq));
    }
    let magnitude = ep.cmp(&eq).then(mp.partial_cmp(&mq)?);
    Some(if sp < 0 {
        magnitude.reverse()
    } else {
        magnitude
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Products that overflow to the same infinity, and NaN products, do not compare
    /// `Equal` (that would be a silent tie).
    #[test]
    fn float_products_beyond_the_range_are_not_ties() {
        use Ordering::{Greater, Less};
        let big32 = f32::MAX / 2.0;
        assert_eq!(f32::cmp_products(big32, 4.0, big32, 3.0), Some(Greater));
        assert_eq!(f32::cmp_products(big32, -4.0, big32, -3.0), Some(Less));
        assert_eq!(f32::cmp_products(f32::INFINITY, 0.0, 1.0, 1.0), None);
        assert_eq!(f32::cmp_products(f32::NAN, 1.0, 1.0, 1.0), None);
        let big64 = f64::MAX / 2.0;
        assert_eq!(f64::cmp_products(big64, 4.0, big64, 3.0), Some(Greater));
        assert_eq!(f64::cmp_products(big64, 3.0, big64, 4.0), Some(Less));
        assert_eq!(f64::cmp_products(big64, -4.0, big64, -3.0), Some(Less));
        assert_eq!(f64::cmp_products(big64, -4.0, 1.0, 1.0), Some(Less));
        assert_eq!(f64::cmp_products(f64::INFINITY, 0.0, 1.0, 1.0), None);
        assert_eq!(f64::cmp_products(f64::NAN, 1.0, 1.0, 1.0), None);
        // Within the range nothing changes.
        assert_eq!(f64::cmp_products(2.0, 3.0, 1.0, 6.0), Some(Ordering::Equal));
        assert_eq!(f32::cmp_products(2.0, 3.0, 1.0, 7.0), Some(Less));
    }
}

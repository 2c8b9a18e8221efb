//! [`Scalar`] for the fixed-point formats of the `fixed` crate: I16F16, I20F12, I32F32.
//! Products are formed exactly in double width ([`super::wide`]) and rounded once.

use super::{Decimal, EPSILON_DELTAS, KernelArith, Scalar, wide};
use ::fixed::FixedI32;
use ::fixed::types::{I16F16, I20F12, I32F32};

/// `bits × num / den` truncated towards zero, as the double-width quotient
/// `(bits·num)/den` would give it, without dividing in double width: with
/// `bits = q·den + r`, the result is `q·num + (r·num)/den`, where `|r·num| < |den·num|`
/// nearly always fits an `i32` (screen coordinates: below 2²⁶), so the division is a
/// 32-bit one (one instruction on the Cortex-M4 instead of the 64-bit helper).
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

/// The truncated quotient `(a·2^frac)/b` of 32-bit bit patterns, as `fixed`'s
/// `checked_div`. The one place the division is chosen: on 32-bit targets (no 64 by
/// 32-bit divide instruction: a software helper, dear on a Cortex-M0) the
/// reciprocal form [`super::recip::exact_div`], bit for bit the same; elsewhere the
/// 64-bit division.
#[inline]
fn div_i32(a: i32, b: i32, frac: u32) -> Option<i32> {
    #[cfg(target_pointer_width = "32")]
    {
        super::recip::exact_div(a, b, frac)
    }
    #[cfg(not(target_pointer_width = "32"))]
    {
        if b == 0 {
            return None;
        }
        i32::try_from((i64::from(a) << frac) / i64::from(b)).ok()
    }
}

/// Whether [`quick_i32`] answers on this target: on cores without a long multiply, and on
/// hosted targets (`target_os` not `none`), so that the host's tests, reports and
/// simulator draw with the Cortex-M0's arithmetic (the pixels are the same either way).
const QUICK_I32: bool = cfg!(any(no_long_multiply, not(target_os = "none")));

/// [`super::recip::quick_pixel_term`] on the bit patterns ([`KernelArith::quick_pixel`] of the
/// 32-bit formats), where it pays: on cores without a long multiply (the
/// Cortex-M0, where the exact division and the colour's three double-width products are
/// built from 16-bit products), and on hosted targets ([`QUICK_I32`]). Elsewhere `None`:
/// on bare-metal cores with `UMULL` or `MULHU` (Cortex-M4F, RISC-V) the exact arithmetic
/// is cheaper than the quick pixel's certification. The one place the choice is made; the
/// pixels are the same either way.
#[inline]
fn quick_i32<F: ::fixed::types::extra::LeEqU32>(
    base: [FixedI32<F>; 3],
    term: &super::recip::QuickTerm,
    b: FixedI32<F>,
) -> Option<[u8; 3]> {
    if QUICK_I32 {
        super::recip::quick_pixel_term(
            base.map(FixedI32::<F>::to_bits),
            term,
            b.to_bits(),
            FixedI32::<F>::FRAC_NBITS,
        )
    } else {
        None
    }
}

/// [`KernelArith::quick_term`] of the 32-bit formats with a quick pixel ([`quick_i32`]).
#[inline]
fn quick_term_i32<F: ::fixed::types::extra::LeEqU32>(
    a: [FixedI32<F>; 3],
    slack: FixedI32<F>,
) -> Option<super::recip::QuickTerm> {
    if QUICK_I32 {
        super::recip::quick_term(a.map(FixedI32::<F>::to_bits), slack.to_bits())
    } else {
        None
    }
}

macro_rules! impl_fixed {
    ($t:ty, $name:literal, $wide:ty, $bits:ty, $wide_bits:ty, $mul:path, $div:expr, $qterm:ty, $quick:expr, $term:expr, $has_quick:expr) => {
        impl Scalar for $t {
            const NAME: &'static str = $name;
            const ZERO: Self = <$t>::ZERO;
            const ONE: Self = <$t>::ONE;
            const MAX: Self = <$t>::MAX;
            const DELTA: Self = <$t>::DELTA;
            const DEFAULT_EPSILON: Self = <$t>::from_bits(EPSILON_DELTAS as $bits);
            const INT_BITS: u32 = <$t>::INT_NBITS;

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
                let div: fn(Self, Self) -> Option<Self> = $div;
                div(self, rhs)
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
                Self::acc_round(Self::acc_dot3(a, b)?)
            }
            #[inline]
            fn cmp_products(a: Self, b: Self, c: Self, d: Self) -> Option<core::cmp::Ordering> {
                Some($mul(a.to_bits(), b.to_bits()).cmp(&$mul(c.to_bits(), d.to_bits())))
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
        }

        impl KernelArith for $t {
            const EXACT_SUMS: bool = true;
            const EXACT_PRODUCTS: bool = true;
            // `fixed`'s division and `recip::exact_div` (bit for bit the same) truncate
            // the exact quotient.
            const EXACT_QUOTIENTS: bool = true;
            const QUICK_PIXEL: bool = $has_quick;
            type QuickTerm = $qterm;
            #[inline]
            fn quick_term(a: [Self; 3], slack: Self) -> Option<$qterm> {
                let term: fn([Self; 3], Self) -> Option<$qterm> = $term;
                term(a, slack)
            }
            #[inline]
            fn quick_pixel(base: [Self; 3], term: &$qterm, b: Self) -> Option<[u8; 3]> {
                let quick: fn([Self; 3], &$qterm, Self) -> Option<[u8; 3]> = $quick;
                quick(base, term, b)
            }
            type Acc = $wide;
            #[inline]
            fn acc_mul(a: Self, b: Self) -> Option<$wide> {
                Some(<$wide>::from_bits($mul(a.to_bits(), b.to_bits())))
            }
            #[inline]
            fn acc_add(x: $wide, y: $wide) -> Option<$wide> {
                x.checked_add(y)
            }
            #[inline]
            fn acc_round(x: $wide) -> Option<Self> {
                // Round to nearest: add half a narrow DELTA, then narrowing floors.
                let half = <$wide>::from_num(<$t>::DELTA) >> 1u32;
                <$t>::checked_from_num(x.checked_add(half)?)
            }
            #[inline]
            fn acc_step_fitting(x: $wide, y: $wide) -> ($wide, Self) {
                // `acc_add` and `acc_round` wrapping: the same values where they fit.
                let sum = x.wrapping_add(y);
                let half = <$wide>::from_num(<$t>::DELTA) >> 1u32;
                (sum, <$t>::wrapping_from_num(sum.wrapping_add(half)))
            }
            #[inline]
            fn products_clearly_greater(a: Self, b: Self, c: Self, d: Self) -> bool {
                // Raw units: the products are in DELTA², `|a| + |c|` in DELTA × DELTA.
                let margin =
                    <$wide_bits>::from(a.to_bits()).abs() + <$wide_bits>::from(c.to_bits()).abs();
                $mul(a.to_bits(), b.to_bits())
                    .checked_sub($mul(c.to_bits(), d.to_bits()))
                    .is_some_and(|g| g > margin)
            }
        }
    };
}

impl_fixed!(
    I16F16,
    "i16f16",
    ::fixed::types::I32F32,
    i32,
    i64,
    wide::mul_wide_i32,
    |a, b| div_i32(a.to_bits(), b.to_bits(), I16F16::FRAC_NBITS).map(I16F16::from_bits),
    super::recip::QuickTerm,
    quick_i32,
    quick_term_i32,
    QUICK_I32
);
impl_fixed!(
    I20F12,
    "i20f12",
    ::fixed::types::I40F24,
    i32,
    i64,
    wide::mul_wide_i32,
    |a, b| div_i32(a.to_bits(), b.to_bits(), I20F12::FRAC_NBITS).map(I20F12::from_bits),
    super::recip::QuickTerm,
    quick_i32,
    quick_term_i32,
    QUICK_I32
);
impl_fixed!(
    I32F32,
    "i32f32",
    ::fixed::types::I64F64,
    i64,
    i128,
    wide::mul_wide_i64,
    I32F32::checked_div,
    // No shortcut: a 64-bit format's terms take its division.
    (),
    |_, _, _| None,
    |_, _| None,
    false
);

#[cfg(test)]
mod tests {
    use super::*;

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

    /// `products_clearly_greater` against the same test in 128-bit integers, on the
    /// edges of both formats and 100,000 seeded cases (I32F32's products need `i128`).
    #[test]
    fn clearly_greater_products_are_the_wide_test() {
        fn wide(a: i64, b: i64, c: i64, d: i64) -> bool {
            let g = i128::from(a) * i128::from(b) - i128::from(c) * i128::from(d);
            g > i128::from(a.abs()) + i128::from(c.abs())
        }
        let edges = [
            i32::MIN + 1,
            -65_536,
            -3,
            -1,
            0,
            1,
            2,
            3,
            65_535,
            65_536,
            i32::MAX,
        ];
        let mut next = crate::num::xorshift(0x0DDB_1A5E_5BAD_5EED);
        let mut cases: std::vec::Vec<[i32; 4]> = std::vec::Vec::new();
        for a in edges {
            for b in edges {
                cases.push([a, b, b, a]);
                cases.push([a, b, a, b.saturating_sub(1)]);
            }
        }
        for _ in 0..100_000 {
            let shift = u32::try_from(next() % 31).unwrap();
            let mut v = || {
                i32::try_from(i64::try_from(next() >> 33).unwrap() - (1 << 30)).unwrap() >> shift
            };
            cases.push([v(), v(), v(), v()]);
        }
        for [a, b, c, d] in cases {
            let (a, b, c, d) = (
                I16F16::from_bits(a),
                I16F16::from_bits(b),
                I16F16::from_bits(c),
                I16F16::from_bits(d),
            );
            let expect = wide(
                i64::from(a.to_bits()),
                i64::from(b.to_bits()),
                i64::from(c.to_bits()),
                i64::from(d.to_bits()),
            );
            assert_eq!(
                KernelArith::products_clearly_greater(a, b, c, d),
                expect,
                "{a} {b} {c} {d}"
            );
            let w = |v: I16F16| I32F32::from_bits(i64::from(v.to_bits()) << 16);
            let expect = wide(
                w(a).to_bits(),
                w(b).to_bits(),
                w(c).to_bits(),
                w(d).to_bits(),
            );
            assert_eq!(
                KernelArith::products_clearly_greater(w(a), w(b), w(c), w(d)),
                expect,
                "{a} {b} {c} {d} in I32F32"
            );
        }
    }

    /// `acc_step_fitting` is `acc_add` then `acc_round` wherever both fit (seeded cases
    /// of every magnitude, in the three fixed formats), and never panics elsewhere.
    #[test]
    fn a_fitting_step_is_the_checked_step() {
        fn check<S: Scalar>(a: S, b: S, c: S) -> bool {
            let (Some(x), Some(y)) = (S::acc_mul(a, b), S::acc_mul(c, b)) else {
                return false;
            };
            let fitting = S::acc_step_fitting(x, y);
            match S::acc_add(x, y).and_then(|sum| Some((sum, S::acc_round(sum)?))) {
                Some((sum, rounded)) => {
                    assert_eq!(fitting.1, rounded, "{} {a:?} {b:?} {c:?}", S::NAME);
                    assert_eq!(S::acc_round(fitting.0), Some(rounded));
                    assert_eq!(S::acc_round(sum), Some(rounded));
                    true
                }
                None => false,
            }
        }
        let mut x: u64 = 0x2026_1205_0000_0007;
        let mut fitted = 0;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let bits = |k: u32| ((x >> k) as u32).cast_signed() >> ((x >> (k + 3)) % 31);
            fitted += usize::from(check(
                I16F16::from_bits(bits(0)),
                I16F16::from_bits(bits(11)),
                I16F16::from_bits(bits(23)),
            ));
            fitted += usize::from(check(
                I20F12::from_bits(bits(5)),
                I20F12::from_bits(bits(17)),
                I20F12::from_bits(bits(29)),
            ));
            fitted += usize::from(check(
                I32F32::from_bits(i64::from(bits(2)) << (x % 24)),
                I32F32::from_bits(i64::from(bits(13))),
                I32F32::from_bits(i64::from(bits(31)) << (x % 17)),
            ));
        }
        assert!(fitted > 300_000, "{fitted}");
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
}

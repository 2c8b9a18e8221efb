//! Variants of the main number formats that differ in one choice, so that the accuracy
//! report can show what that choice costs:
//!
//! - [`F32Micro`]: `f32` with `micromath`'s fast square root (about 45 instructions on a
//!   Cortex-M0 against about 400 for a correctly rounded one, and up to 6.1 % off).
//!   The tempting choice on a chip without an FPU; the report shows what it does to the
//!   picture when it normalises rays.
//! - [`I16F16Narrow`]: I16F16 with narrow dot products (three products, each rounded
//!   towards −∞, summed in I16F16) instead of [`Scalar::dot3`]'s wide accumulation. The
//!   alternative the crate measured and did not keep.
//! - [`I16F16Recip`]: I16F16 whose division multiplies by a reciprocal (a 256-entry table
//!   and two Newton steps in 32-bit arithmetic, [`recip_div`]) instead of dividing
//!   64 by 32 bits: on a core without a divide instruction (the Cortex-M0's division
//!   helper takes ~370 instructions) the cheaper division, at up to a few `DELTA`s of
//!   error.
//!
//! All are complete [`Scalar`]s: any scene renders in them.
//!
//! ```
//! use fixray::variants::{F32Micro, I16F16Narrow, I16F16Recip};
//! use fixray::{Scalar, Scene};
//!
//! let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }";
//! assert!(Scene::<F32Micro>::parse(text).is_ok());
//! assert!(Scene::<I16F16Narrow>::parse(text).is_ok());
//! assert!(Scene::<I16F16Recip>::parse(text).is_ok());
//! assert_eq!(F32Micro::NAME, "f32m");
//! ```

use micromath::F32Ext;

use crate::decimal::Decimal;
use crate::scalar::mul_wide_u32;
use crate::{I16F16, Scalar};

/// `f32` with `micromath`'s approximate square root (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct F32Micro(pub f32);

/// I16F16 with narrow dot products (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct I16F16Narrow(pub I16F16);

/// I16F16 with division by reciprocal (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct I16F16Recip(pub I16F16);

/// `1/d` for `d` in [1, 2) to 9 bits, in Q0.16: entry `i` is `1/(1 + (i + ½)/256)`, the
/// reciprocal of its interval's midpoint, rounded (relative error ≤ 2⁻⁹).
const RECIPROCALS: [u16; 256] = {
    let mut table = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        // 2¹⁶ · 512 / (512 + 2i + 1), rounded to nearest: at most 2²⁵/513 < 2¹⁶, so the
        // narrowing keeps every bit. (`as` because `TryFrom` is not `const`; i < 256.)
        let den = 512 + 2 * i as u32 + 1;
        table[i] = (((1u32 << 25) + den / 2) / den) as u16;
        i += 1;
    }
    table
};

/// `a / b` for I16F16 bit patterns by reciprocal, without a 64-bit division: `|b|` is
/// normalised to `d` in [1, 2) (Q1.31), `1/d` is read from [`RECIPROCALS`] (9 bits) and
/// refined by two Newton steps `x ← x(2 − dx)` (to about 2⁻³⁰: the 32-bit arithmetic's
/// limit), and `|a|·x` is scaled back. It differs from the exact truncated quotient by at
/// most `1 + |q|·2⁻²⁸` DELTAs (about 9 DELTAs at the format's largest quotients, 1 for
/// quotients below 2¹²; the unit test checks the bound on 400,000 seeded cases). `None`
/// when `b` is zero or the quotient does not fit.
pub fn recip_div(a: i32, b: i32) -> Option<i32> {
    if b == 0 {
        return None;
    }
    let negative = (a < 0) != (b < 0);
    let (ua, ub) = (a.unsigned_abs(), b.unsigned_abs());
    let n = ub.leading_zeros();
    let d = ub << n; // Q1.31 in [1, 2)
    let index = usize::try_from((d >> 23) & 0xFF).ok()?;
    // Q0.16 → Q1.31.
    let mut x = u32::from(*RECIPROCALS.get(index)?) << 15;
    for _ in 0..2 {
        // t = d·x ≈ 1 (Q1.31); x ← x·(2 − t).
        let t = u32::try_from(mul_wide_u32(d, x) >> 31).ok()?;
        let e = 0u32.wrapping_sub(t); // 2 − t in Q1.31: 2³² − t (t in (0, 2³²))
        x = u32::try_from(mul_wide_u32(x, e) >> 31).ok()?;
    }
    // a/b = ua · x/2³¹ · 2ⁿ/2³¹ · 2¹⁶/2¹⁶ … in bits: ua · x · 2^(n − 46).
    let q = mul_wide_u32(ua, x) >> (46 - n);
    if negative {
        0i32.checked_sub_unsigned(u32::try_from(q).ok()?)
    } else {
        i32::try_from(q).ok()
    }
}

/// Implements every `Scalar` method but the ones given by delegating to the wrapped type.
macro_rules! delegate {
    ($t:ident, $inner:ty, $name:literal, { $($own:item)* }) => {
        impl Scalar for $t {
            const NAME: &'static str = $name;
            const ZERO: Self = Self(<$inner as Scalar>::ZERO);
            const ONE: Self = Self(<$inner as Scalar>::ONE);
            const MAX: Self = Self(<$inner as Scalar>::MAX);
            const DELTA: Self = Self(<$inner as Scalar>::DELTA);
            const DEFAULT_EPSILON: Self = Self(<$inner as Scalar>::DEFAULT_EPSILON);
            const RATIO_SHIFT: u32 = <$inner as Scalar>::RATIO_SHIFT;

            #[inline]
            fn checked_mul_int(self, k: i32) -> Option<Self> {
                self.0.checked_mul_int(k).map(Self)
            }

            fn from_f64(value: f64) -> Option<Self> {
                <$inner>::from_f64(value).map(Self)
            }
            fn from_decimal(value: Decimal) -> Option<Self> {
                <$inner>::from_decimal(value).map(Self)
            }
            fn from_i32(value: i32) -> Option<Self> {
                <$inner>::from_i32(value).map(Self)
            }
            fn to_f64(self) -> f64 {
                self.0.to_f64()
            }
            #[inline]
            fn checked_add(self, rhs: Self) -> Option<Self> {
                Scalar::checked_add(self.0, rhs.0).map(Self)
            }
            #[inline]
            fn checked_sub(self, rhs: Self) -> Option<Self> {
                Scalar::checked_sub(self.0, rhs.0).map(Self)
            }
            #[inline]
            fn checked_mul(self, rhs: Self) -> Option<Self> {
                Scalar::checked_mul(self.0, rhs.0).map(Self)
            }
            #[inline]
            fn abs(self) -> Self {
                Self(Scalar::abs(self.0))
            }
            #[inline]
            fn mul_ratio(self, num: i32, den: i32) -> Option<Self> {
                self.0.mul_ratio(num, den).map(Self)
            }
            #[inline]
            fn round_to_i32(self) -> Option<i32> {
                self.0.round_to_i32()
            }
            #[inline]
            fn cmp_products(a: Self, b: Self, c: Self, d: Self) -> core::cmp::Ordering {
                <$inner>::cmp_products(a.0, b.0, c.0, d.0)
            }
            #[inline]
            fn ulp(self) -> Self {
                Self(self.0.ulp())
            }
            #[inline]
            fn floor_to_i32(self) -> Option<i32> {
                self.0.floor_to_i32()
            }
            fn pow_unit(self, exponent: Self) -> Option<Self> {
                Scalar::pow_unit(self.0, exponent.0).map(Self)
            }
            fn cos(self) -> Option<Self> {
                Scalar::cos(self.0).map(Self)
            }
            $($own)*
        }
    };
}

delegate!(F32Micro, f32, "f32m", {
    #[inline]
    fn checked_div(self, rhs: Self) -> Option<Self> {
        Scalar::checked_div(self.0, rhs.0).map(Self)
    }
    #[inline]
    fn checked_sqrt(self) -> Option<Self> {
        if self.0 < 0.0 {
            return None;
        }
        // Called through the trait: with std linked, `self.0.sqrt()` would be std's.
        Some(Self(F32Ext::sqrt(self.0))).filter(|v| v.0.is_finite())
    }
    #[inline]
    fn dot3(a: [Self; 3], b: [Self; 3]) -> Option<Self> {
        f32::dot3([a[0].0, a[1].0, a[2].0], [b[0].0, b[1].0, b[2].0]).map(Self)
    }
    #[inline]
    fn sub_dot3(c: Self, a: [Self; 3], b: [Self; 3]) -> Option<Self> {
        f32::sub_dot3(c.0, [a[0].0, a[1].0, a[2].0], [b[0].0, b[1].0, b[2].0]).map(Self)
    }
});

delegate!(I16F16Narrow, I16F16, "i16f16n", {
    #[inline]
    fn checked_div(self, rhs: Self) -> Option<Self> {
        Scalar::checked_div(self.0, rhs.0).map(Self)
    }
    #[inline]
    fn checked_sqrt(self) -> Option<Self> {
        Scalar::checked_sqrt(self.0).map(Self)
    }
    #[inline]
    fn dot3(a: [Self; 3], b: [Self; 3]) -> Option<Self> {
        let p = |i: usize| a[i].0.checked_mul(b[i].0);
        p(0)?.checked_add(p(1)?)?.checked_add(p(2)?).map(Self)
    }
    #[inline]
    fn sub_dot3(c: Self, a: [Self; 3], b: [Self; 3]) -> Option<Self> {
        c.0.checked_sub(Self::dot3(a, b)?.0).map(Self)
    }
});

delegate!(I16F16Recip, I16F16, "i16f16r", {
    #[inline]
    fn checked_div(self, rhs: Self) -> Option<Self> {
        recip_div(self.0.to_bits(), rhs.0.to_bits()).map(|q| Self(I16F16::from_bits(q)))
    }
    #[inline]
    fn checked_sqrt(self) -> Option<Self> {
        Scalar::checked_sqrt(self.0).map(Self)
    }
    #[inline]
    fn dot3(a: [Self; 3], b: [Self; 3]) -> Option<Self> {
        I16F16::dot3([a[0].0, a[1].0, a[2].0], [b[0].0, b[1].0, b[2].0]).map(Self)
    }
    #[inline]
    fn sub_dot3(c: Self, a: [Self; 3], b: [Self; 3]) -> Option<Self> {
        I16F16::sub_dot3(c.0, [a[0].0, a[1].0, a[2].0], [b[0].0, b[1].0, b[2].0]).map(Self)
    }
});

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn micromath_sqrt_is_approximate_and_std_is_not_used() {
        let two = F32Micro(2.0);
        let root = two.checked_sqrt().unwrap().0;
        // micromath's bit trick gives 1.5 for √2 (its worst case, 6.1 % high; the crate
        // documents ~5 % on average). It must not be the exact root: that would mean std's
        // sqrt had been called instead.
        assert_eq!(root, 1.5);
        assert!((root - core::f32::consts::SQRT_2).abs() / core::f32::consts::SQRT_2 < 0.065);
        assert_eq!(F32Micro(-1.0).checked_sqrt(), None);
    }

    /// The reciprocal division against the exact (truncated) one: within
    /// `1 + |q|·2⁻²⁸` DELTAs.
    #[test]
    fn reciprocal_division_is_within_its_bound() {
        let mut x: u64 = 0x0D1F_2026_1124_0001;
        let mut worst = 0.0f64;
        for case in 0..400_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let a = ((x >> 32) as u32).cast_signed() >> ((x >> 3) % 32);
            let b = (x as u32).cast_signed() >> ((x >> 9) % 32);
            let exact = if b == 0 {
                None
            } else {
                i32::try_from((i64::from(a) << 16) / i64::from(b)).ok()
            };
            let got = recip_div(a, b);
            match (got, exact) {
                (Some(q), Some(e)) => {
                    let err = (i64::from(e) - i64::from(q)).abs();
                    let bound = 1.0 + f64::from(e).abs() / f64::from(1u32 << 28);
                    assert!(
                        err as f64 <= bound,
                        "case {case}: {a} / {b}: {q} vs {e} ({err} DELTAs)"
                    );
                    worst = worst.max(err as f64);
                }
                (None, None) => {}
                // Right at the range's edge the two may disagree on fitting.
                (g, e) => assert!(
                    e.is_some_and(|e| e.unsigned_abs() >= (1 << 31) - 16) || g.is_none(),
                    "case {case}: {a} / {b}: {g:?} vs {e:?}"
                ),
            }
        }
        std::println!("reciprocal division: worst {worst} DELTAs");
        assert!(worst >= 1.0, "the bound is exercised");
    }

    #[test]
    fn narrow_dot_rounds_each_product() {
        let third = I16F16Narrow(I16F16::from_f64(1.0 / 3.0).unwrap());
        let narrow = I16F16Narrow::dot3([third; 3], [third; 3]).unwrap().0;
        let wide = I16F16::dot3([third.0; 3], [third.0; 3]).unwrap();
        // Each narrow product is floored: the narrow sum is below the wide one.
        assert!(narrow < wide);
        assert!(wide.to_f64() - narrow.to_f64() <= 3.0 * I16F16::DELTA.to_f64());
    }
}

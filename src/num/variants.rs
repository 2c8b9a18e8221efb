//! Variants of the main number formats that differ in one choice, so that the accuracy
//! report can show what that choice costs:
//!
//! - [`F32Micro`]: `f32` with `micromath`'s fast square root (far cheaper on a Cortex-M0
//!   than a correctly rounded one, and up to 6.1 % off).
//!   The tempting choice on a chip without an FPU; the report shows what it does to the
//!   picture when it normalises rays.
//! - [`I16F16Narrow`]: I16F16 with narrow dot products (three products, each rounded
//!   towards −∞, summed in I16F16) instead of [`Scalar::dot3`]'s wide accumulation. The
//!   alternative the crate measured and did not keep.
//! - [`I16F16Recip`]: I16F16 whose division multiplies by a reciprocal (a 256-entry table
//!   and two Newton steps in 32-bit arithmetic, `recip.rs`) instead of dividing
//!   64 by 32 bits: on a core without a divide instruction (the Cortex-M0: a software
//!   helper) the cheaper division, at up to a few `DELTA`s of
//!   error.
//!
//! All are complete [`Scalar`]s: any scene renders in them.
//!
//! ```
//! use fixray::num::variants::{F32Micro, I16F16Narrow, I16F16Recip};
//! use fixray::{Scalar, Scene};
//!
//! let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }";
//! assert!(Scene::<F32Micro>::parse(text).is_ok());
//! assert!(Scene::<I16F16Narrow>::parse(text).is_ok());
//! assert!(Scene::<I16F16Recip>::parse(text).is_ok());
//! assert_eq!(F32Micro::NAME, "f32m");
//! ```

use micromath::F32Ext;

use super::recip::recip_div;
use super::{Decimal, I16F16, KernelArith, Scalar};

/// `f32` with `micromath`'s approximate square root (see the module documentation).
///
/// ```
/// use fixray::num::variants::F32Micro;
/// use fixray::Scalar;
///
/// // micromath's square root: fast, and up to 6.1 % off (√2 comes out as 1.5).
/// assert_eq!(F32Micro(2.0).checked_sqrt(), Some(F32Micro(1.5)));
/// assert_eq!(F32Micro::NAME, "f32m");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct F32Micro(pub f32);

/// I16F16 with narrow dot products (see the module documentation).
///
/// ```
/// use fixray::num::variants::I16F16Narrow;
/// use fixray::{Scalar, I16F16};
///
/// let third = I16F16::from_f64(1.0 / 3.0).unwrap();
/// let narrow = I16F16Narrow::dot3([I16F16Narrow(third); 3], [I16F16Narrow(third); 3]).unwrap();
/// let wide = I16F16::dot3([third; 3], [third; 3]).unwrap();
/// assert!(narrow.0 < wide); // three products each rounded down, against one rounding
/// ```
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct I16F16Narrow(pub I16F16);

/// I16F16 with division by reciprocal (see the module documentation).
///
/// ```
/// use fixray::num::variants::I16F16Recip;
/// use fixray::{Scalar, I16F16};
///
/// let (a, b) = (I16F16::from_num(7), I16F16::from_num(3));
/// let exact = Scalar::checked_div(a, b).unwrap();
/// let recip = I16F16Recip(a).checked_div(I16F16Recip(b)).unwrap().0;
/// // Through the reciprocal: within a few DELTAs of the exact quotient.
/// assert!((recip - exact).abs() <= I16F16::DELTA * 4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct I16F16Recip(pub I16F16);

/// Implements every `Scalar` and `KernelArith` method but the ones given by delegating to the
/// wrapped type.
macro_rules! delegate {
    (
        $t:ident, $inner:ty, $name:literal, exact_products: $exact:expr,
        { $($own:item)* }, kernel: { $($kernel:item)* }
    ) => {
        impl Scalar for $t {
            const NAME: &'static str = $name;
            const ZERO: Self = Self(<$inner as Scalar>::ZERO);
            const ONE: Self = Self(<$inner as Scalar>::ONE);
            const MAX: Self = Self(<$inner as Scalar>::MAX);
            const DELTA: Self = Self(<$inner as Scalar>::DELTA);
            const DEFAULT_EPSILON: Self = Self(<$inner as Scalar>::DEFAULT_EPSILON);
            const INT_BITS: u32 = <$inner as Scalar>::INT_BITS;

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
            fn cmp_products(a: Self, b: Self, c: Self, d: Self) -> Option<core::cmp::Ordering> {
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
            $($own)*
        }

        impl KernelArith for $t {
            type QuickTerm = ();
            const EXACT_SUMS: bool = <$inner as KernelArith>::EXACT_SUMS;
            const EXACT_PRODUCTS: bool = $exact;
            #[inline]
            fn products_clearly_greater(a: Self, b: Self, c: Self, d: Self) -> bool {
                <$inner>::products_clearly_greater(a.0, b.0, c.0, d.0)
            }
            $($kernel)*
        }
    };
}

delegate!(F32Micro, f32, "f32m", exact_products: false, {
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
}, kernel: {
    type Acc = f32;
    #[inline]
    fn acc_mul(a: Self, b: Self) -> Option<f32> {
        f32::acc_mul(a.0, b.0)
    }
    #[inline]
    fn acc_add(x: f32, y: f32) -> Option<f32> {
        f32::acc_add(x, y)
    }
    #[inline]
    fn acc_round(x: f32) -> Option<Self> {
        f32::acc_round(x).map(Self)
    }
    #[inline]
    fn acc_dot3(a: [Self; 3], b: [Self; 3]) -> Option<f32> {
        Self::dot3(a, b).map(|d| d.0)
    }
});

delegate!(I16F16Narrow, I16F16, "i16f16n", exact_products: false, {
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
}, kernel: {
    // Narrow: every product rounded on its own, as its dot products.
    type Acc = I16F16;
    #[inline]
    fn acc_mul(a: Self, b: Self) -> Option<I16F16> {
        a.0.checked_mul(b.0)
    }
    #[inline]
    fn acc_add(x: I16F16, y: I16F16) -> Option<I16F16> {
        x.checked_add(y)
    }
    #[inline]
    fn acc_round(x: I16F16) -> Option<Self> {
        Some(Self(x))
    }
});

delegate!(I16F16Recip, I16F16, "i16f16r", exact_products: <I16F16 as KernelArith>::EXACT_PRODUCTS, {
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
}, kernel: {
    type Acc = <I16F16 as KernelArith>::Acc;
    #[inline]
    fn acc_mul(a: Self, b: Self) -> Option<Self::Acc> {
        I16F16::acc_mul(a.0, b.0)
    }
    #[inline]
    fn acc_add(x: Self::Acc, y: Self::Acc) -> Option<Self::Acc> {
        I16F16::acc_add(x, y)
    }
    #[inline]
    fn acc_round(x: Self::Acc) -> Option<Self> {
        I16F16::acc_round(x).map(Self)
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

//! The series the shading needs, one file each with its test vectors and stated maximum
//! error: [`pow_unit`] (the specular exponent) and [`cos`] (spotlight cones). The floats
//! take them from `libm`; the fixed formats sum them in their own arithmetic.
//!
//! ```
//! use fixray::num::Series;
//! use fixray::{I16F16, Scalar};
//!
//! let half = I16F16::from_f64(0.5).unwrap();
//! let two = I16F16::from_i32(2).unwrap();
//! assert_eq!(half.pow_unit(two).map(Scalar::to_f64), Some(0.25));
//! ```

pub mod cos;
pub mod pow_unit;

use ::fixed::types::{I16F16, I20F12, I32F32};

use super::variants::{F32Micro, I16F16Narrow, I16F16Recip};

/// The shading series of a number format (a supertrait of [`super::Scalar`]).
///
/// ```
/// use fixray::num::Series;
/// use fixray::{Scalar, I16F16};
///
/// // A spotlight's cone of 60°: cos(π/3) = ½, within the series' stated error.
/// let third_pi = I16F16::from_f64(core::f64::consts::FRAC_PI_3).unwrap();
/// assert!((third_pi.cos().unwrap().to_f64() - 0.5).abs() < 1e-4);
/// // A glint of shininess 8 at N·H = 0.9: 0.9⁸ ≈ 0.430.
/// let nh = I16F16::from_f64(0.9).unwrap();
/// assert!((nh.pow_unit(I16F16::from_i32(8).unwrap()).unwrap().to_f64() - 0.4305).abs() < 1e-3);
/// ```
pub trait Series: Sized {
    /// `self^exponent` for `self` in [0, 1] and `exponent >= 1` (the specular term).
    /// Floats use `libm`'s `pow`; fixed formats [`pow_unit::pow_unit`] (error at most
    /// [`pow_unit::MAX_ERROR`] for `self ≥ ½`, none for integer exponents beyond rounding).
    fn pow_unit(self, exponent: Self) -> Option<Self>;

    /// The cosine of an angle in radians, |angle| ≤ π (spotlight cones). Floats use `libm`;
    /// fixed formats [`cos::cos`] (truncation error below [`cos::MAX_ERROR`] on
    /// [−π/2, π/2], under one DELTA of every fixed format here).
    fn cos(self) -> Option<Self>;
}

macro_rules! fixed_series {
    ($($t:ty),*) => {$(
        impl Series for $t {
            fn pow_unit(self, exponent: Self) -> Option<Self> {
                pow_unit::pow_unit(self, exponent)
            }
            fn cos(self) -> Option<Self> {
                cos::cos(self)
            }
        }
    )*};
}
fixed_series!(I16F16, I20F12, I32F32);

impl Series for f32 {
    fn pow_unit(self, exponent: Self) -> Option<Self> {
        Some(libm::powf(self, exponent)).filter(|v| v.is_finite())
    }
    fn cos(self) -> Option<Self> {
        Some(libm::cosf(self)).filter(|v| v.is_finite())
    }
}

impl Series for f64 {
    fn pow_unit(self, exponent: Self) -> Option<Self> {
        Some(libm::pow(self, exponent)).filter(|v| v.is_finite())
    }
    fn cos(self) -> Option<Self> {
        Some(libm::cos(self)).filter(|v| v.is_finite())
    }
}

/// The variants compute their series as the format they wrap.
macro_rules! delegate_series {
    ($($t:ident),*) => {$(
        impl Series for $t {
            fn pow_unit(self, exponent: Self) -> Option<Self> {
                Series::pow_unit(self.0, exponent.0).map(Self)
            }
            fn cos(self) -> Option<Self> {
                Series::cos(self.0).map(Self)
            }
        }
    )*};
}
delegate_series!(F32Micro, I16F16Narrow, I16F16Recip);

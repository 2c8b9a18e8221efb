//! [`Vec3`]: the vector operations of the course notes (`dot`, `scale`, `sum`, `diff`,
//! `length`, `unit`), every one checked: `None` means the result does not fit the format.

use crate::Scalar;

/// A 3-vector in number format `S`.
///
/// ```
/// use fixray::{Scalar, I16F16};
/// use fixray::geometry::Vec3;
///
/// let v = Vec3::<I16F16>::from_f64([3.0, 0.0, -4.0]).unwrap();
/// assert_eq!(v.length().unwrap().to_f64(), 5.0);
/// let u = v.unit().unwrap();
/// assert!((u.z.to_f64() + 0.8).abs() <= I16F16::DELTA.to_f64());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vec3<S> {
    /// x component.
    pub x: S,
    /// y component.
    pub y: S,
    /// z component.
    pub z: S,
}

impl<S: Scalar> Vec3<S> {
    /// The zero vector.
    pub const ZERO: Self = Self::new(S::ZERO, S::ZERO, S::ZERO);

    /// A vector from its components.
    pub const fn new(x: S, y: S, z: S) -> Self {
        Self { x, y, z }
    }

    /// Converts `f64` components (rounded to nearest); `None` if one does not fit.
    pub fn from_f64(v: [f64; 3]) -> Option<Self> {
        Some(Self::new(
            S::from_f64(v[0])?,
            S::from_f64(v[1])?,
            S::from_f64(v[2])?,
        ))
    }

    /// The components as `f64`.
    pub fn to_f64(self) -> [f64; 3] {
        [self.x.to_f64(), self.y.to_f64(), self.z.to_f64()]
    }

    /// The components as an array.
    pub fn to_array(self) -> [S; 3] {
        [self.x, self.y, self.z]
    }

    /// The dot product (see [`Scalar::dot3`] for how each format rounds it).
    #[inline]
    pub fn dot(self, other: Self) -> Option<S> {
        S::dot3(self.to_array(), other.to_array())
    }

    /// `self·axis`, without products when `axis` lies along a world axis (`±1` on one
    /// coordinate, `0` on the others: the normals of floors and walls, the axes of their
    /// tiles). The dot product is then `±` that coordinate of `self` exactly in every
    /// format (the wide sum of exact products, rounded once; in the float formats
    /// `x·1 + y·0 + z·0 = x` up to the sign of a zero, which no caller tells apart), so
    /// the result is [`Vec3::dot`]'s bit for bit, without its three double-width
    /// products. Other axes: [`Vec3::dot`].
    #[inline(always)]
    pub(crate) fn dot_axis(self, axis: Self) -> Option<S> {
        match axis.world_axis() {
            Some(along) => self.along(along),
            None => self.dot(axis),
        }
    }

    /// The world axis `self` lies along, if it does: `±1` on one coordinate (its index,
    /// and whether `−1`) and `0` on the others ([`Vec3::dot_axis`]).
    #[inline(always)]
    pub(crate) fn world_axis(self) -> Option<(u8, bool)> {
        let zero = S::ZERO;
        let signed = |k: u8, c: S| {
            if c == S::ONE {
                Some((k, false))
            } else if c.checked_neg() == Some(S::ONE) {
                Some((k, true))
            } else {
                None
            }
        };
        if self.y == zero && self.z == zero {
            signed(0, self.x)
        } else if self.x == zero && self.z == zero {
            signed(1, self.y)
        } else if self.x == zero && self.y == zero {
            signed(2, self.z)
        } else {
            None
        }
    }

    /// `self·axis` for an `axis` along the world axis `(k, negative)`
    /// ([`Vec3::world_axis`]): `±self[k]`, exactly.
    #[inline(always)]
    pub(crate) fn along(self, (k, negative): (u8, bool)) -> Option<S> {
        let value = match k {
            0 => self.x,
            1 => self.y,
            _ => self.z,
        };
        if negative {
            value.checked_neg()
        } else {
            Some(value)
        }
    }

    /// `k × self`.
    #[inline]
    pub fn scale(self, k: S) -> Option<Self> {
        Some(Self::new(
            k.checked_mul(self.x)?,
            k.checked_mul(self.y)?,
            k.checked_mul(self.z)?,
        ))
    }

    /// `self + other`.
    #[inline]
    pub fn sum(self, other: Self) -> Option<Self> {
        Some(Self::new(
            self.x.checked_add(other.x)?,
            self.y.checked_add(other.y)?,
            self.z.checked_add(other.z)?,
        ))
    }

    /// `self − other`.
    #[inline]
    pub fn diff(self, other: Self) -> Option<Self> {
        Some(Self::new(
            self.x.checked_sub(other.x)?,
            self.y.checked_sub(other.y)?,
            self.z.checked_sub(other.z)?,
        ))
    }

    /// The cross product `self × other`.
    #[inline]
    pub fn cross(self, other: Self) -> Option<Self> {
        let term = |a: S, b: S, c: S, d: S| a.checked_mul(b)?.checked_sub(c.checked_mul(d)?);
        Some(Self::new(
            term(self.y, other.z, self.z, other.y)?,
            term(self.z, other.x, self.x, other.z)?,
            term(self.x, other.y, self.y, other.x)?,
        ))
    }

    /// `−self`.
    #[inline]
    pub fn checked_neg(self) -> Option<Self> {
        Vec3::ZERO.diff(self)
    }

    /// The largest absolute component (the ∞-norm).
    #[inline]
    pub fn max_abs(self) -> S {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }

    /// Divides by the largest absolute component, so that every component lies in
    /// [−1, 1] and one of them is ±1. `None` for the zero vector.
    ///
    /// Squaring a fixed-point vector overflows early (in I16F16 a component of 182 already
    /// squares past the range); the scaled vector's squared length lies in [1, 3] in every
    /// format, so `length` and `unit` work for every representable vector.
    #[inline]
    fn scaled(self) -> Option<(Self, S)> {
        let m = self.max_abs();
        if m <= S::ZERO {
            return None;
        }
        let w = Self::new(
            self.x.checked_div(m)?,
            self.y.checked_div(m)?,
            self.z.checked_div(m)?,
        );
        Some((w, m))
    }

    /// The direction and the length of `self`, the length split as `scale × scaled_length`
    /// so that neither part overflows even when the length itself would: a vector with a
    /// component of at least 1 whose squared length fits is taken as it is (`scale` 1),
    /// any other is divided by its largest absolute component first (`scale`), so that
    /// the scaled length lies in [1, √3].
    /// `None` for the zero vector (or one too short for the format to give a direction).
    ///
    /// Unit components are clamped to [−1, 1], so multiplying anything by a component of
    /// a unit vector can never overflow.
    pub fn normalize(self) -> Option<Normalized<S>> {
        let m = self.max_abs();
        // Nearly every vector of a scene (rays, normals, directions to lights) has a
        // component of at least 1 and squares within the format: it needs no scaling,
        // and three divisions fewer (on a Cortex-M0 a division costs many products:
        // `docs/performance.md`). Unscaled, its squared length keeps every bit of `self`.
        let ((w, scale), squared) = match self.dot(self) {
            Some(d) if m >= S::ONE => ((self, S::ONE), d),
            _ => {
                let (w, scale) = self.scaled()?;
                ((w, scale), w.dot(w)?)
            }
        };
        let scaled_length = squared.checked_sqrt()?;
        if scaled_length <= S::ZERO {
            return None;
        }
        let one = S::ONE;
        let minus_one = one.checked_neg()?;
        let clamp =
            |c: S| -> Option<S> { Some(c.checked_div(scaled_length)?.min(one).max(minus_one)) };
        Some(Normalized {
            unit: Self::new(clamp(w.x)?, clamp(w.y)?, clamp(w.z)?),
            scale,
            scaled_length,
        })
    }

    /// The Euclidean length, `None` when it does not fit the format. The zero vector has
    /// length zero.
    pub fn length(self) -> Option<S> {
        match self.normalize() {
            Some(n) => n.length(),
            None if self.max_abs() == S::ZERO => Some(S::ZERO),
            None => None,
        }
    }

    /// The unit vector along `self`; `None` for the zero vector (or a vector too short
    /// for the format to give a direction). See [`Vec3::normalize`].
    pub fn unit(self) -> Option<Self> {
        self.normalize().map(|n| n.unit)
    }
}

/// A vector split into its direction and its length (see [`Vec3::normalize`]).
///
/// ```
/// use fixray::geometry::Vec3;
/// use fixray::{Scalar, I16F16};
///
/// // |(30000, 40000, 0)| = 50000 does not fit I16F16 (range ±32768); split, it does.
/// let big = Vec3::<I16F16>::new(I16F16::from_num(30_000), I16F16::from_num(20_000), I16F16::ZERO);
/// let n = big.normalize().unwrap();
/// assert_eq!(n.scale, I16F16::from_num(30_000));
/// assert!((n.unit.x.to_f64() - 0.832).abs() < 0.001);
/// assert_eq!(n.length(), None); // 36055.5: beyond the format, but the direction is known
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normalized<S> {
    /// The unit vector, components in [−1, 1].
    pub unit: Vec3<S>,
    /// What the vector was divided by before its length was taken: 1 for a vector with a
    /// component of at least 1 whose squared length fits the format, otherwise its
    /// largest absolute component.
    pub scale: S,
    /// The length of `vector / scale`: in [1, √3] for a scaled vector.
    pub scaled_length: S,
}

impl<S: Scalar> Normalized<S> {
    /// The length, `scale × scaled_length`; `None` when it does not fit the format.
    pub fn length(&self) -> Option<S> {
        self.scale.checked_mul(self.scaled_length)
    }

    /// `k / length`, computed as `k / scale / scaled_length` so that a length beyond the
    /// format's range still gives a (small) result. `None` when the quotient overflows.
    pub fn divide(&self, k: S) -> Option<S> {
        if self.scale == S::ONE {
            return k.checked_div(self.scaled_length);
        }
        k.checked_div(self.scale)?.checked_div(self.scaled_length)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I20F12, I32F32};

    /// Unit vectors of random-ish directions have length 1 within a few DELTAs.
    fn unit_table<S: Scalar>(max_error_deltas: f64) {
        let cases = [
            [3.0, 0.0, -4.0],
            [1.0, 1.0, 1.0],
            [-0.001, 0.002, 0.0005],
            [1000.0, -2000.0, 30.0],
            [0.0, 0.0, -1.0],
            [7.3, -2.1, 5.5],
            [150.0, 90.0, -20.0],
            [1.0, 0.0001, -0.0002],
        ];
        for c in cases {
            let q = Vec3::<S>::from_f64(c).unwrap();
            let u = q.unit().unwrap().to_f64();
            // Against the exact unit vector of the quantised input.
            let c = q.to_f64();
            let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
            for i in 0..3 {
                let err = (u[i] - c[i] / len).abs() / S::DELTA.to_f64();
                assert!(err <= max_error_deltas, "{} {:?}: {err} DELTAs", S::NAME, c);
            }
        }
    }

    #[test]
    fn unit_error_is_within_two_deltas() {
        unit_table::<I16F16>(2.0);
        unit_table::<I20F12>(2.0);
        unit_table::<I32F32>(2.0);
        unit_table::<f32>(2.0);
        unit_table::<f64>(2.0);
    }

    #[test]
    fn zero_vector_has_no_direction() {
        assert_eq!(Vec3::<I16F16>::ZERO.unit(), None);
        assert_eq!(Vec3::<f64>::ZERO.unit(), None);
        assert_eq!(Vec3::<I20F12>::ZERO.length(), Some(I20F12::ZERO));
    }

    #[test]
    fn long_vectors_do_not_overflow_length() {
        // 20000² overflows I16F16, the scaled length does not.
        let v = Vec3::<I16F16>::from_f64([20000.0, 0.0, 0.0]).unwrap();
        assert_eq!(v.length().unwrap().to_f64(), 20000.0);
        let v = Vec3::<I16F16>::from_f64([30000.0, 30000.0, 0.0]).unwrap();
        assert_eq!(v.length(), None, "42426 does not fit I16F16");
        assert!(v.unit().is_some());
    }

    #[test]
    fn sum_and_scale_refuse_overflow() {
        let v = Vec3::<I16F16>::from_f64([30000.0, 1.0, 1.0]).unwrap();
        assert_eq!(v.sum(v), None);
        assert_eq!(v.scale(I16F16::from_i32(2).unwrap()), None);
        assert!(v.diff(v).is_some());
    }
}

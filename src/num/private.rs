//! The kernel-only part of [`Scalar`]: the unrounded sums of products a kernel steps along
//! a scanline, what a format's arithmetic guarantees about them, and the quick pixel.
//!
//! [`KernelArith`] is a supertrait of [`Scalar`], so generic code with `S: Scalar` calls these
//! items as before (`S::acc_mul`), while `Scalar`'s documentation shows arithmetic and
//! conversions only. The trait is public in a private module: no other crate can name it,
//! so none can implement it, and through it none can implement [`Scalar`] (the sealed-trait
//! pattern). Every format here implements both, beside each other (`fixed.rs`, `float.rs`,
//! `variants.rs`).

use core::fmt::Debug;

use super::Scalar;

/// The kernels' operations of a number format (see the module documentation): sealed, and
/// reached through [`Scalar`].
pub trait KernelArith: Copy {
    /// A sum of products before its rounding: double width and exact in the fixed
    /// formats (what [`Scalar::dot3`] adds in), the format itself for floats. A kernel
    /// that steps a dot product along a scanline adds a per-frame product to it instead
    /// of forming three products per pixel: in the fixed formats bit for bit the
    /// [`Scalar::dot3`] of the stepped vector.
    type Acc: Copy + Debug + Send + Sync + PartialOrd + Default;

    /// Whether sums of [`KernelArith::Acc`] are exact (the fixed formats: integers), so that a
    /// kernel may add a dot product's terms in any order, e.g. a per-row `y² + z²` and a
    /// per-pixel `x²`, and round to [`Scalar::dot3`]'s value bit for bit. `false` for
    /// floats (their sums round at each step).
    const EXACT_SUMS: bool;

    /// Whether [`KernelArith::acc_mul`] is exact as well (the fixed formats' double-width
    /// products; not `i16f16n`, whose products round one by one): a dot product is
    /// then linear in [`KernelArith::Acc`], so one stepped along a scanline by a per-frame
    /// product equals, bit for bit, the one formed afresh from the stepped vector, and a
    /// kernel may skip its steps and form it again where it needs it.
    const EXACT_PRODUCTS: bool;

    /// The exact product `a·b` as an [`KernelArith::Acc`] (fixed formats; floats round it);
    /// `None` only for floats, when it is not finite.
    fn acc_mul(a: Self, b: Self) -> Option<Self::Acc>;

    /// `x + y`, or `None` on overflow.
    fn acc_add(x: Self::Acc, y: Self::Acc) -> Option<Self::Acc>;

    /// Rounds a sum to the format as [`Scalar::dot3`] does (to nearest in the fixed
    /// formats): `dot3(a, b)` is `acc_round` of the sum of the three `acc_mul`s.
    fn acc_round(x: Self::Acc) -> Option<Self>;

    /// Whether a sum is below zero (its default is zero): the exact sign of `a·b − c·d`
    /// from `acc_mul(a, b)` and `acc_mul(c, −d)` where products are exact
    /// ([`KernelArith::EXACT_PRODUCTS`]), as [`Scalar::cmp_products`] compares them.
    #[inline]
    fn acc_negative(x: Self::Acc) -> bool {
        x < Self::Acc::default()
    }

    /// `x + y` and its [`KernelArith::acc_round`], for a caller that knows both fit (a
    /// scanline stepping `N·D` between two values it checked once): the same values,
    /// without the overflow tests where the format can leave them out (the fixed
    /// formats, whose sums are integers); where they do not fit, some value (never a
    /// panic).
    #[inline]
    fn acc_step_fitting(x: Self::Acc, y: Self::Acc) -> (Self::Acc, Self)
    where
        Self: Scalar,
    {
        match Self::acc_add(x, y) {
            Some(sum) => (sum, Self::acc_round(sum).unwrap_or(Self::ZERO)),
            None => (x, Self::ZERO),
        }
    }

    /// The unrounded `a·b` of two 3-vectors (see [`KernelArith::Acc`]).
    #[inline]
    fn acc_dot3(a: [Self; 3], b: [Self; 3]) -> Option<Self::Acc> {
        let sum = Self::acc_add(Self::acc_mul(a[0], b[0])?, Self::acc_mul(a[1], b[1])?)?;
        Self::acc_add(sum, Self::acc_mul(a[2], b[2])?)
    }

    /// Whether `a·b − c·d` exceeds `|a| + |c|` in units of `DELTA²`: far enough that `b` and `d`
    /// each moving by a `DELTA` cannot bring `a·b` down to `c·d` (twice what two roundings to
    /// nearest can move them). Exact in the fixed formats; `false` where the format cannot say (the
    /// default: floats and the variants), so that a caller only ever skips work.
    #[inline]
    fn products_clearly_greater(a: Self, b: Self, c: Self, d: Self) -> bool {
        let _ = (a, b, c, d);
        false
    }

    /// Whether [`Scalar::checked_div`]'s quotient is always within one `DELTA` of the
    /// exact one (the fixed formats' division, truncated; not a division through an
    /// approximate reciprocal, nor a float's): a kernel may then bound what its hits' own
    /// planes' sides can be.
    const EXACT_QUOTIENTS: bool = false;

    /// Whether [`KernelArith::quick_pixel`] can answer on this target (a kernel leaves its
    /// shortcut out entirely where it cannot).
    const QUICK_PIXEL: bool = false;

    /// A colour term prepared once for many [`KernelArith::quick_pixel`]s (a row's pixels):
    /// its numerators and the caller's slack ([`KernelArith::quick_term`]). `()` in the formats
    /// without a quick pixel (no room is taken for it there).
    type QuickTerm: Copy + Debug + Send + Sync;

    /// The [`KernelArith::QuickTerm`] of the numerators `aᵢ` (not negative, not all zero) of a
    /// colour term `aᵢ/b` and the caller's `slack` ([`KernelArith::quick_pixel`]). `None` (the
    /// default) where the format has no quick pixel or an argument is outside that
    /// domain.
    #[inline]
    fn quick_term(a: [Self; 3], slack: Self) -> Option<Self::QuickTerm> {
        let _ = (a, slack);
        None
    }

    /// The pixel of a colour term over a base colour, `round(clamp(baseᵢ + aᵢ/b, 0,
    /// 255))` per channel (the `fixray` rules' mapping, `shade::color::to_rgb888`), for
    /// the term's non-negative `aᵢ` (prepared by [`KernelArith::quick_term`]) and a positive
    /// `b`, when one approximate reciprocal settles it: the quotients are known to within
    /// a bound `e` (about `q·2⁻¹⁷`), and the pixel is returned only where every colour
    /// within `e + slack` of the base plus them rounds to it. A caller whose own term
    /// (the format's truncated division and products) is within `slack` of the real
    /// quotients `aᵢ/b` thus gets its own pixel, bit for bit, without the division (the
    /// level-plane kernel's lean pixels). `None` (the default) where the format has no
    /// such shortcut (I16F16 and I20F12 have one, `num/recip.rs`, on cores without a long
    /// multiply, where it pays, and on hosted targets: `num/fixed.rs`), `b` is outside
    /// that domain, a quotient may not fit, or the interval straddles two pixel values.
    #[inline]
    fn quick_pixel(base: [Self; 3], term: &Self::QuickTerm, b: Self) -> Option<[u8; 3]> {
        let _ = (base, term, b);
        None
    }
}

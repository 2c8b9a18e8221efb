//! Division by reciprocal for 32-bit fixed-point bit patterns: a 256-entry table and two
//! Newton steps in 32-bit arithmetic instead of a 64 by 32-bit division (about 370
//! instructions on a Cortex-M0, 120 on a Cortex-M4, whose `UDIV` takes only 32 bits).
//!
//! - [`recip_div`] is the approximate quotient of the `i16f16r` variant
//!   ([`super::variants::I16F16Recip`]): within `1 + |q|·2⁻²⁸` DELTAs.
//! - [`exact_div`] corrects that estimate by its remainder: bit for bit the truncated
//!   quotient of `fixed`'s `checked_div`, which I16F16 and I20F12 use on 32-bit targets
//!   (`num/fixed.rs`).

use super::wide::mul_wide_u32;

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
pub(crate) fn recip_div(a: i32, b: i32) -> Option<i32> {
    if b == 0 {
        return None;
    }
    let (ua, ub) = (a.unsigned_abs(), b.unsigned_abs());
    let (x, n) = reciprocal(ub)?;
    // a/b = ua · x/2³¹ · 2ⁿ/2³¹ · 2¹⁶/2¹⁶ … in bits: ua · x · 2^(n − 46).
    let q = mul_wide_u32(ua, x) >> (46 - n);
    with_sign(q, (a < 0) != (b < 0))
}

/// `1/ub` as `(x, n)`: `ub·2ⁿ = d` in [1, 2) (Q1.31) and `x ≈ 1/d` in Q1.31, from the
/// table and two Newton steps `x ← x(2 − dx)` (relative error below 2⁻²⁹, 2⁻²⁹·⁵ at
/// most over the unit test's 2,000,000 seeded divisors). `ub ≠ 0`.
///
/// The first step needs only 16 bits: it takes `d`'s top half (`dh`, Q1.15) and the
/// table's `x₀` (Q0.16), whose product `t` is one 32-bit multiply, and its correction
/// `x₀·(2³¹ − t)` fits 32 bits too (`|2³¹ − t| ≤ 2³¹·(2⁻⁹ + 2⁻¹⁵)`: the table's error and
/// `dh`'s truncation). That gives `1/d` to about 2⁻¹⁵ (the truncation's error); the second
/// step, on the whole of `d` with double-width products, squares it to about 2⁻³⁰. On a
/// Cortex-M0 the first step is two `MULS` instead of two double-width products (about
/// 40 instructions fewer per division).
#[inline(always)]
fn reciprocal(ub: u32) -> Option<(u32, u32)> {
    let n = leading_zeros(ub);
    let d = ub << n; // Q1.31 in [1, 2)
    let index = usize::try_from((d >> 23) & 0xFF).ok()?;
    let x0 = u32::from(*RECIPROCALS.get(index)?); // Q0.16, in (2¹⁵, 2¹⁶)
    // First step, 16-bit: t = dh·x₀ ≈ 2³¹ (Q1.31, below 2³²: both factors below 2¹⁶).
    let t = (d >> 16) * x0;
    // (2³¹ − t)/2, signed and small (|·| < 2²¹·¹): t/2 < 2³¹ fits an i32.
    let half_err = (1i32 << 30) - i32::try_from(t >> 1).ok()?;
    // x₁ = x₀ + x₀·(2³¹ − t)/2³¹, in Q1.31: x₀·2¹⁵ + x₀·half_err/2¹⁵ (|product| < 2³¹).
    let x0 = i32::try_from(x0).ok()?;
    let x1 = (x0 << 15) + ((x0 * (half_err >> 7)) >> 8);
    let mut x = u32::try_from(x1).ok()?;
    // Second step, on all of d: t = d·x ≈ 1 (Q1.31); x ← x·(2 − t).
    let t = u32::try_from(mul_wide_u32(d, x) >> 31).ok()?;
    let e = 0u32.wrapping_sub(t); // 2 − t in Q1.31: 2³² − t (t in (0, 2³²))
    x = u32::try_from(mul_wide_u32(x, e) >> 31).ok()?;
    Some((x, n))
}

/// `x.leading_zeros()`: inline on cores without `CLZ` (ARMv6-M, the cores without a long
/// multiply too), where the compiler calls a helper.
#[inline(always)]
fn leading_zeros(x: u32) -> u32 {
    #[cfg(no_long_multiply)]
    {
        leading_zeros_soft(x)
    }
    #[cfg(not(no_long_multiply))]
    {
        x.leading_zeros()
    }
}

/// [`leading_zeros`] by binary search (five steps).
#[inline(always)]
#[cfg_attr(not(no_long_multiply), allow(dead_code))]
fn leading_zeros_soft(x: u32) -> u32 {
    let (mut x, mut n) = (x, 0);
    for bits in [16, 8, 4, 2, 1] {
        if x >> (32 - bits) == 0 {
            n += bits;
            x <<= bits;
        }
    }
    n + u32::from(x == 0)
}

/// `x >> s` for `s < 64`, on 32-bit halves (a 64-bit shift by a variable amount is a
/// helper call on 32-bit cores).
#[inline(always)]
#[cfg_attr(not(target_pointer_width = "32"), allow(dead_code))]
fn shr(x: u64, s: u32) -> u64 {
    // The two halves: truncation is the split itself.
    let (hi, lo) = ((x >> 32) as u32, x as u32);
    if s >= 32 {
        u64::from(hi >> (s - 32))
    } else if s == 0 {
        x
    } else {
        (u64::from(hi >> s) << 32) | u64::from((lo >> s) | (hi << (32 - s)))
    }
}

/// `±q` as an `i32`, or `None` when it does not fit.
#[inline(always)]
fn with_sign(q: u64, negative: bool) -> Option<i32> {
    if negative {
        0i32.checked_sub_unsigned(u32::try_from(q).ok()?)
    } else {
        i32::try_from(q).ok()
    }
}

/// `(a·2^frac) / b` truncated towards zero, as `fixed`'s `checked_div` of bit patterns
/// with `frac` fraction bits (`frac` ≤ 16) computes it, bit for bit, without a 64-bit
/// division: [`recip_div`]'s estimate `q̂` (within `1 + q·2⁻²⁸` of the quotient) is
/// corrected by the remainder `|a|·2^frac − q̂·|b|` until it lies in `[0, |b|)`, which
/// makes `q̂` the exact floor of `|a|·2^frac / |b|`. `None` when `b` is zero or the
/// quotient does not fit an `i32` (as `fixed`).
///
/// About 90 instructions on a Cortex-M0 (six 32 × 32 → 64 products from 16-bit halves)
/// and 30 on a Cortex-M4; the unit tests compare it with the 64-bit division on every
/// sign, size and edge.
#[inline(never)]
#[cfg_attr(not(target_pointer_width = "32"), allow(dead_code))]
pub(crate) fn exact_div(a: i32, b: i32, frac: u32) -> Option<i32> {
    if b == 0 || frac > 16 {
        return None;
    }
    let (ua, ub) = (a.unsigned_abs(), b.unsigned_abs());
    let (x, n) = reciprocal(ub)?;
    // The estimate, in bits: ua · x · 2^(n + frac − 62); n + frac ≤ 47.
    let mut q = shr(mul_wide_u32(ua, x), 62 - frac - n);
    let negative = (a < 0) != (b < 0);
    if ub < SMALL_DIVISOR {
        // An estimate beyond 2³¹ + 64 means a quotient beyond 2³¹ (the estimate is within
        // 1 + q·2⁻²⁷ of it): no i32 holds it, whatever its sign.
        let mut q = u32::try_from(q).ok().filter(|q| *q < (1 << 31) + 64)?;
        // The remainder in 32 bits: q̂ is within 1 + q·2⁻²⁷ < 18 of the quotient, so
        // |rem| < 19·|b| < 2³¹: its low 32 bits, wrapped, are all of it.
        let mut rem = (ua << frac).wrapping_sub(q.wrapping_mul(ub)).cast_signed();
        let den = ub.cast_signed();
        while rem < 0 {
            q = q.checked_sub(1)?;
            rem += den;
        }
        while rem >= den {
            q = q.checked_add(1)?;
            rem -= den;
        }
        return with_sign(u64::from(q), negative);
    }
    // |a|·2^frac < 2⁴⁸ and q̂·|b| ≤ (q + 33)·|b| < 2⁴⁹: both fit an i64 exactly.
    let num = i64::from(ua) << frac;
    let den = i64::from(ub);
    let mut rem = num - i64::try_from(mul_wide_u32_u64(q, ub)?).ok()?;
    // A few steps either way (the estimate's bound), one or none nearly always.
    while rem < 0 {
        q = q.checked_sub(1)?;
        rem += den;
    }
    while rem >= den {
        q += 1;
        rem -= den;
    }
    with_sign(q, negative)
}

/// Divisors below this (2²⁵: 512.0 in I16F16, nearly every divisor of a frame) take
/// [`exact_div`]'s remainder in 32-bit arithmetic: one `MULS` instead of a double-width
/// product and a 64-bit subtraction.
const SMALL_DIVISOR: u32 = 1 << 25;

/// `q·b` for a quotient estimate `q` below 2³³ (the largest is `2⁴⁸/1`, far beyond the
/// range, refused here: `None` when `q` has more than 32 bits).
#[inline(always)]
#[cfg_attr(not(target_pointer_width = "32"), allow(dead_code))]
fn mul_wide_u32_u64(q: u64, b: u32) -> Option<u64> {
    Some(mul_wide_u32(u32::try_from(q).ok()?, b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use fixed::types::{I16F16, I20F12};

    /// The reciprocal division against the exact (truncated) one: within
    /// `1 + |q|·2⁻²⁸` DELTAs.
    #[test]
    fn reciprocal_division_is_within_its_bound_and_refuses_only_at_the_edge() {
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
                // Right at the range's edge the two may disagree on fitting, nowhere else.
                (None, Some(e)) => assert!(
                    e.unsigned_abs() >= (1 << 31) - 16,
                    "case {case}: {a} / {b}: refused, exact {e}"
                ),
                (Some(q), None) => assert!(
                    b != 0 && q.unsigned_abs() >= (1 << 31) - 16,
                    "case {case}: {a} / {b}: {q}, exact does not fit"
                ),
            }
        }
        std::println!("reciprocal division: worst {worst} DELTAs");
        assert!(worst >= 1.0, "the bound is exercised");
    }

    /// The reciprocal's relative error, `|x·d − 1|`, over seeded divisors of every size:
    /// below 2⁻²⁹ (the bound [`exact_div`]'s 32-bit remainder and its few correction
    /// steps rest on), and the first, 16-bit Newton step does not lose it.
    #[test]
    fn the_reciprocal_is_within_two_to_the_minus_29() {
        let mut x: u64 = 0x0D1F_2026_1203_0001;
        let mut worst = 0.0f64;
        for case in 0..2_000_000u32 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let ub = ((x as u32) >> ((x >> 40) % 32)).max(1);
            let (r, n) = reciprocal(ub).unwrap();
            let d = f64::from(ub << n) / f64::from(1u32 << 31);
            let err = (f64::from(r) / f64::from(1u32 << 31) * d - 1.0).abs();
            assert!(err < 2f64.powi(-29), "case {case}: 1/{ub}: {err:e}");
            worst = worst.max(err);
        }
        std::println!("reciprocal: worst relative error 2^{:.2}", worst.log2());
    }

    /// The exact division against the 64-bit one, bit for bit, for both fraction sizes
    /// the 32-bit formats use: edges and a seeded sweep over every sign and size.
    #[test]
    fn leading_zeros_and_shifts_on_halves() {
        for x in [
            0u32,
            1,
            2,
            3,
            0xFF,
            0x100,
            0xFFFF,
            0x1_0000,
            1 << 31,
            u32::MAX,
        ] {
            assert_eq!(leading_zeros_soft(x), x.leading_zeros(), "{x}");
        }
        let v = 0x8123_4567_89AB_CDEFu64;
        for s in 0..64 {
            assert_eq!(shr(v, s), v >> s, "{s}");
        }
    }

    #[test]
    fn exact_division_is_the_truncated_quotient() {
        let want = |a: i32, b: i32, frac: u32| -> Option<i32> {
            (b != 0)
                .then(|| (i64::from(a) << frac) / i64::from(b))
                .and_then(|q| i32::try_from(q).ok())
        };
        let edges = [
            i32::MIN,
            i32::MIN + 1,
            -(1 << 16),
            -65_535,
            -3,
            -1,
            0,
            1,
            2,
            3,
            0xFFFF,
            1 << 16,
            0x1_0001,
            1 << 30,
            i32::MAX - 1,
            i32::MAX,
        ];
        for frac in [12, 16] {
            for a in edges {
                for b in edges {
                    assert_eq!(exact_div(a, b, frac), want(a, b, frac), "{a} {b} {frac}");
                }
            }
        }
        let mut x: u64 = 0x0D1F_2026_1202_0001;
        for case in 0..1_000_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let a = ((x >> 32) as u32).cast_signed() >> ((x >> 3) % 32);
            let b = (x as u32).cast_signed() >> ((x >> 9) % 32);
            let frac = if case % 2 == 0 { 16 } else { 12 };
            assert_eq!(exact_div(a, b, frac), want(a, b, frac), "{a} {b} {frac}");
            // `want` is `fixed`'s own division.
            let fixed = if frac == 16 {
                I16F16::from_bits(a)
                    .checked_div(I16F16::from_bits(b))
                    .map(I16F16::to_bits)
            } else {
                I20F12::from_bits(a)
                    .checked_div(I20F12::from_bits(b))
                    .map(I20F12::to_bits)
            };
            assert_eq!(fixed, want(a, b, frac), "fixed: {a} {b} {frac}");
            // Quotients right at the range's edge: b·2^31/2^frac ± a little.
            let b = b.unsigned_abs().max(1 << frac).min(1 << 30).cast_signed();
            let edge = (i64::from(b) << (31 - frac)) + i64::from((x >> 40) as u8) - 128;
            if let Ok(a) = i32::try_from(edge) {
                for a in [a, -a] {
                    assert_eq!(exact_div(a, b, frac), want(a, b, frac), "{a} {b} {frac}");
                }
            }
        }
    }

    /// Regression: the bound test let any refused quotient pass. Quotients well inside
    /// the range, and the zero divisor, are decided exactly here.
    #[test]
    fn reciprocal_division_refuses_zero_and_nothing_inside_the_range() {
        assert_eq!(recip_div(1 << 16, 0), None);
        assert_eq!(recip_div(0, 0), None);
        for (a, b) in [
            (1 << 16, 1 << 16),
            (-(3 << 16), 1 << 15),
            (i32::MAX, 1 << 17),
            (7, -3),
        ] {
            let exact = i32::try_from((i64::from(a) << 16) / i64::from(b)).unwrap();
            let q = recip_div(a, b).unwrap();
            assert!(
                (i64::from(q) - i64::from(exact)).abs() <= 1,
                "{a} / {b}: {q} vs {exact}"
            );
        }
        // 2¹⁴ / 2⁻¹⁶ = 2³⁰ does not fit the format: refused, never wrapped.
        assert_eq!(recip_div(1 << 30, 1), None);
    }
}

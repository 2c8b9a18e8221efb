//! Division by reciprocal for 32-bit fixed-point bit patterns: a 256-entry table and two
//! Newton steps in 32-bit arithmetic instead of a 64 by 32-bit division (a software
//! helper on a Cortex-M0, and on a Cortex-M4, whose `UDIV` takes only 32 bits; costs:
//! `docs/performance.md`).
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
/// Cortex-M0 the first step is two `MULS` instead of two double-width products.
#[inline(always)]
fn reciprocal(ub: u32) -> Option<(u32, u32)> {
    let n = leading_zeros(ub);
    let d = ub << n; // Q1.31 in [1, 2)
    let x0 = table_reciprocal(d)?;
    // First step, 16-bit: t = dh·x₀ ≈ 2³¹ (Q1.31, below 2³²: both factors below 2¹⁶).
    let mut x = newton_16(x0, (d >> 16) * x0)?;
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

/// [`leading_zeros`] by two halving steps and a table of the top byte's.
#[inline(always)]
#[cfg_attr(not(no_long_multiply), allow(dead_code))]
fn leading_zeros_soft(x: u32) -> u32 {
    let (mut x, mut n) = (x, 0);
    if x >> 16 == 0 {
        n = 16;
        x <<= 16;
    }
    if x >> 24 == 0 {
        n += 8;
        x <<= 8;
    }
    // x >> 24 < 256: the table's index.
    n + u32::from(CLZ8[(x >> 24) as usize])
}

/// The leading zeros of a byte (8 for zero).
#[cfg_attr(not(no_long_multiply), allow(dead_code))]
const CLZ8: [u8; 256] = {
    let mut table = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        let mut n = 0;
        while n < 8 && (i << n) & 0x80 == 0 {
            n += 1;
        }
        // n ≤ 8 (`as` because `TryFrom` is not `const`).
        table[i] = n as u8;
        i += 1;
    }
    table
};

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
/// Six 32 × 32 → 64 products (from 16-bit halves on a Cortex-M0) instead of the 64-bit
/// division helper (per-operation costs: `docs/performance.md`); the unit tests compare
/// it with the 64-bit division on every sign, size and edge.
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

/// `1/d` for `d` in [1, 2) (Q1.31, top bit set) to about 2⁻¹⁸, in Q1.31, without a
/// double-width product: the table's `x₀` and one Newton step `x₀(2 − d·x₀)` whose
/// `d·x₀` takes all of `d` (two 32-bit multiplies: `dh·x₀ + dl·x₀/2¹⁶`). Its error is the
/// table's squared (2⁻¹⁸) plus the step's truncations (about 2⁻²³): below 2⁻¹⁷·⁸ either
/// way (the unit test checks it over 2,000,000 divisors and every table interval's
/// ends). Cheaper than [`reciprocal`] (which adds a second, double-width step for
/// 2⁻²⁹) for [`quick_quotients`].
#[inline(always)]
fn reciprocal_fine(d: u32) -> Option<u32> {
    let x0 = table_reciprocal(d)?;
    // t = d·x₀/2¹⁶ ≈ 2³¹ (Q1.31): the high half's product and the low half's, which
    // both fit 32 bits (each factor below 2¹⁶), the low one truncated.
    newton_16(x0, (d >> 16) * x0 + (((d & 0xFFFF) * x0) >> 16))
}

/// The table's `x₀ ≈ 1/d` (Q0.16, in (2¹⁵, 2¹⁶)) for `d` in [1, 2) (Q1.31).
#[inline(always)]
fn table_reciprocal(d: u32) -> Option<u32> {
    let index = usize::try_from((d >> 23) & 0xFF).ok()?;
    Some(u32::from(*RECIPROCALS.get(index)?))
}

/// One Newton step `x₁ = x₀(2 − d·x₀)` in 32-bit arithmetic, from the table's `x₀` (Q0.16)
/// and `t ≈ d·x₀` (Q1.31, near 2³¹): `x₁ = x₀·2¹⁵ + x₀·(2³¹ − t)/2¹⁶` in Q1.31. Both
/// reciprocals take it ([`reciprocal`] with `d`'s top half, [`reciprocal_fine`] with all
/// of it).
#[inline(always)]
fn newton_16(x0: u32, t: u32) -> Option<u32> {
    // (2³¹ − t)/2, signed and small (|·| < 2²¹·¹): t/2 < 2³¹ fits an i32.
    let half_err = (1i32 << 30) - i32::try_from(t >> 1).ok()?;
    // x₀·half_err/2¹⁵ with |product| < 2³¹.
    let x0 = i32::try_from(x0).ok()?;
    u32::try_from((x0 << 15) + ((x0 * (half_err >> 7)) >> 8)).ok()
}

/// `x·y/2³²` from 16-bit halves with three 32-bit multiplies (the low halves' product
/// is dropped): between the exact value's floor minus 2 and the exact value.
#[inline(always)]
fn mul_high_approx(x: u32, y: u32) -> u32 {
    let (xh, xl) = (x >> 16, x & 0xFFFF);
    let (yh, yl) = (y >> 16, y & 0xFFFF);
    // xh·yh ≤ (2¹⁶ − 1)² and each cross term shifted is below 2¹⁶: the sum fits.
    xh * yh + ((xh * yl) >> 16) + ((xl * yh) >> 16)
}

/// Three non-negative numerators scaled for [`quick_quotients_scaled`] (once for many
/// divisors: a row's pixels, [`QuickTerm`]): `(aᵢ·2^(s−1), s)` where `s` is the
/// largest's leading zeros (at least 1: the largest then has its top bit at 30). `None`
/// when an `aᵢ` is negative or all are zero.
#[inline]
fn quick_scale(a: [i32; 3]) -> Option<([i32; 3], u32)> {
    if a.iter().any(|v| *v < 0) {
        return None;
    }
    let top = a[0].max(a[1]).max(a[2]).cast_unsigned();
    if top == 0 {
        return None;
    }
    // top < 2³¹: s ≥ 1, and aᵢ·2^(s−1) < 2³¹.
    let s = leading_zeros(top);
    Some((a.map(|v| v << (s - 1)), s))
}

/// `(aᵢ·2^frac)/b` for three non-negative 32-bit bit patterns `aᵢ` and a positive `b`,
/// by one shared reciprocal ([`reciprocal_fine`]) and three products of 16-bit halves:
/// `(q, e)` with `|qᵢ − aᵢ·2^frac/b| ≤ e` for each `i` (the real quotient, not the
/// truncated one), where `e = ⌊q_max/2¹⁷⌋ + 4` (the reciprocal's 2⁻¹⁷·⁸ and the
/// products' and the final shift's truncations, at most 2.5 DELTAs; the unit test checks
/// it on 1,000,000 seeded cases). No double-width product and no remainder: for colour
/// terms whose pixels [`quick_pixel`] certifies from the bound. `None` when an `aᵢ` is
/// negative, `b` is not positive, `frac > 16`, or a quotient may not fit 31 bits.
#[cfg(test)]
pub(crate) fn quick_quotients(a: [i32; 3], b: i32, frac: u32) -> Option<([i32; 3], i32)> {
    if a == [0; 3] && b > 0 && frac <= 16 {
        return Some(([0; 3], 0));
    }
    let (scaled, s) = quick_scale(a)?;
    quick_quotients_scaled(scaled, s, b, frac)
}

/// [`quick_quotients`] of numerators scaled once by [`quick_scale`] (`scaled`, `s`), bit
/// for bit: the per-divisor part.
#[inline(always)]
fn quick_quotients_scaled(scaled: [i32; 3], s: u32, b: i32, frac: u32) -> Option<([i32; 3], i32)> {
    if b <= 0 || frac > 16 || !(1..=31).contains(&s) {
        return None;
    }
    let ub = b.cast_unsigned();
    let n = leading_zeros(ub);
    let x = reciprocal_fine(ub << n)?; // ≈ 2⁶²/(ub·2ⁿ)
    // qᵢ = aᵢ·2^frac/b = (aᵢ·2ˢ)·x/2³² · 2^(frac + n − 30 − s), with `aᵢ·2ˢ` the scaled
    // numerator doubled (the largest has its top bit at 31: its product keeps 30 bits).
    // The product is below 2³¹ (x < 2³¹), so the quotients fit; a right shift of at
    // least one halves the products' truncation (the bound's 2.5 DELTAs), and refuses
    // only quotients of at least 2²⁹ (the largest product is at least 2²⁹).
    let shift = (30 + s).checked_sub(frac + n).filter(|k| *k >= 1)?;
    let q = |v: i32| -> i32 {
        let p = mul_high_approx(v.cast_unsigned() << 1, x);
        // shift ≥ 1: the result is below 2³¹ (and zero beyond 31 places).
        p.checked_shr(shift).unwrap_or(0).cast_signed()
    };
    let q = [q(scaled[0]), q(scaled[1]), q(scaled[2])];
    let e = (q[0].max(q[1]).max(q[2]) >> 17) + 4;
    Some((q, e))
}

/// The pixel channels `round(clamp(bᵢ + aᵢ·2^frac/d, 0, 255))` (ties away from zero,
/// as the crate's rules map colours to pixels) of bit patterns with `frac` fraction
/// bits, for one colour term `aᵢ/d` over a base colour `bᵢ`, when [`quick_quotients`]
/// settles them: each channel's interval `bᵢ + qᵢ ± (e + slack)` (in plain 32-bit
/// arithmetic, within the ranges [`settle`] checks) must round to one pixel value.
/// Whatever lies in those intervals, the colour the exact arithmetic computes among it
/// (the caller states how far its terms can be from the real quotients in `slack`),
/// maps to the same pixel, the mapping being monotonic. `None` when it does not settle or
/// [`quick_quotients`] refuses.
#[cfg(test)]
pub(crate) fn quick_pixel(
    base: [i32; 3],
    a: [i32; 3],
    d: i32,
    slack: i32,
    frac: u32,
) -> Option<[u8; 3]> {
    let (q, e) = quick_quotients(a, d, frac)?;
    let pixel = settle(base, q, e, slack, frac);
    // The prepared form is the same function of its arguments.
    #[cfg(test)]
    if let Some(term) = quick_term(a, slack) {
        assert_eq!(pixel, quick_pixel_term(base, &term, d, frac));
    }
    pixel
}

/// A colour term's numerators and slack prepared once for many [`quick_pixel_term`]s
/// (a row's pixels): the numerators scaled by [`quick_scale`], and the caller's slack
/// ([`quick_pixel`]). The I16F16 and I20F12 formats' `KernelArith::QuickTerm`.
#[derive(Debug, Clone, Copy)]
pub struct QuickTerm {
    scaled: [i32; 3],
    shift: u32,
    slack: i32,
}

/// The [`QuickTerm`] of non-negative numerators `a` (not all zero) with the caller's
/// `slack` (not negative); `None` outside that domain.
#[inline]
pub(crate) fn quick_term(a: [i32; 3], slack: i32) -> Option<QuickTerm> {
    let (scaled, shift) = quick_scale(a)?;
    (slack >= 0).then_some(QuickTerm {
        scaled,
        shift,
        slack,
    })
}

/// [`quick_pixel`] of a prepared term, bit for bit (the per-divisor part).
#[inline(always)]
pub(crate) fn quick_pixel_term(
    base: [i32; 3],
    term: &QuickTerm,
    d: i32,
    frac: u32,
) -> Option<[u8; 3]> {
    let (q, e) = quick_quotients_scaled(term.scaled, term.shift, d, frac)?;
    settle(base, q, e, term.slack, frac)
}

/// The pixel of `base + q` where every colour within `e + slack` of it rounds to one
/// value per channel ([`quick_pixel`]). In plain 32-bit arithmetic: with `|base| ≤ 2²⁹`,
/// `0 ≤ q < 2³⁰` ([`quick_quotients_scaled`]) and `e + slack < 2²⁹` (else `None`) no sum
/// can overflow.
#[inline(always)]
fn settle(base: [i32; 3], q: [i32; 3], e: i32, slack: i32, frac: u32) -> Option<[u8; 3]> {
    const LIMIT: i32 = 1 << 29;
    let e = e.checked_add(slack).filter(|e| *e < LIMIT)?;
    let (one, half) = (1i32 << frac, 1i32 << frac >> 1);
    let top = 255 * one;
    // round(clamp(v, 0, 255)) in bits: 0 ≤ v ≤ 255·2^frac after the clamp, so v + ½ fits.
    let pixel = |v: i32| -> i32 { (v.clamp(0, top) + half) >> frac };
    let mut out = [0u8; 3];
    for ((o, b), q) in out.iter_mut().zip(base).zip(q) {
        if !(-LIMIT..=LIMIT).contains(&b) || !(0..2 * LIMIT).contains(&q) {
            return None;
        }
        // Both ends of the channel's interval (the real term is not negative, so the
        // low end could be `b`; `b + q − e` is below it or equal: a wider interval, as
        // sure).
        let mid = b + q;
        let p = pixel(mid - e);
        if pixel(mid + e) != p {
            return None;
        }
        *o = u8::try_from(p).ok()?;
    }
    Some(out)
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

    /// The one-step reciprocal ([`reciprocal_fine`]): within 2⁻¹⁷·⁸ of `1/d` (relative),
    /// over seeded divisors and both ends of every table interval (where the table's
    /// error is largest).
    #[test]
    fn the_fine_reciprocal_is_within_two_to_the_minus_17_8() {
        let mut worst = 0.0f64;
        let mut check = |d: u32| {
            let x = reciprocal_fine(d).unwrap();
            let prod =
                f64::from(x) / f64::from(1u32 << 31) * (f64::from(d) / f64::from(1u32 << 31));
            let err = (1.0 - prod).abs();
            assert!(err < 2f64.powf(-17.8), "1/{d:#x}: {err:e}");
            worst = worst.max(err);
        };
        for i in 0u32..256 {
            let lo = (1 << 31) | (i << 23);
            for d in [
                lo,
                lo + 1,
                lo | 0x7F_FFFF,
                (lo | 0x7F_FFFF) - 1,
                lo | 0x40_0000,
            ] {
                check(d);
            }
        }
        let mut x: u64 = 0x0D1F_2026_1204_0001;
        for _ in 0..2_000_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            check((x as u32) | (1 << 31));
        }
        std::println!(
            "fine reciprocal: worst relative error 2^{:.2}",
            worst.log2()
        );
    }

    /// [`quick_quotients`] within its stated error `e` of the real quotients, for both
    /// fraction sizes, over seeded triples of every size (equal, spread, zero) and
    /// divisors of every size; refused only where its contract says.
    #[test]
    fn quick_quotients_are_within_their_bound() {
        let mut x: u64 = 0x0D1F_2026_1204_0002;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let (mut answered, mut worst) = (0u32, 0.0f64);
        for case in 0..1_000_000u32 {
            let r = next();
            let frac = if case % 2 == 0 { 16 } else { 12 };
            let big = ((r >> 32) as u32 >> 1) >> ((r >> 3) % 31);
            let mut spread = |k: u64| -> i32 {
                let v = (next() as u32 >> 1) >> (k % 31);
                match k % 5 {
                    0 => 0,
                    1 => big.cast_signed(),
                    _ => v.min(big).cast_signed(),
                }
            };
            let a = [big.cast_signed(), spread(r >> 8), spread(r >> 16)];
            let b = ((r as u32) >> 1 >> ((r >> 24) % 31)).max(1).cast_signed();
            let Some((q, e)) = quick_quotients(a, b, frac) else {
                // Refused: only where a quotient might not fit 31 bits.
                let exact = (f64::from(big) * f64::from(1u32 << frac)) / f64::from(b);
                assert!(
                    exact >= 2f64.powi(28),
                    "case {case}: {a:?}/{b} refused, {exact}"
                );
                continue;
            };
            answered += 1;
            for (qi, ai) in q.iter().zip(a) {
                let exact = (f64::from(ai) * f64::from(1u32 << frac)) / f64::from(b);
                let err = (f64::from(*qi) - exact).abs();
                assert!(
                    err <= f64::from(e),
                    "case {case}: {ai}/{b} (frac {frac}): {qi} vs {exact} (e {e})"
                );
                if exact >= 2f64.powi(20) {
                    worst = worst.max(err / exact);
                }
            }
        }
        assert!(answered > 800_000, "{answered} answered");
        std::println!(
            "quick quotients: worst relative error 2^{:.2}",
            worst.log2()
        );
        assert_eq!(quick_quotients([1, 2, 3], 0, 16), None);
        assert_eq!(quick_quotients([1, -2, 3], 7, 16), None);
        assert_eq!(quick_quotients([0; 3], 7, 16), Some(([0; 3], 0)));
        // 2³⁰ / 2⁻¹⁶ does not fit: refused, never wrapped.
        assert_eq!(quick_quotients([1 << 30, 0, 0], 1, 16), None);
    }

    /// [`quick_pixel`] where it answers is the pixel of the exact arithmetic it stands
    /// in for (the lean pixel's: `b + ⌊w·⌊knl·2¹⁶/ll⌋/2¹⁶⌋`, rounded and clamped) when the
    /// caller's slack is `(⌊w⌋ + 3)` DELTAs, over seeded bases, weights (up to 12),
    /// numerators and divisors of I16F16 and I20F12; and it answers nearly always.
    #[test]
    fn quick_pixels_are_the_exact_arithmetics_pixels() {
        let mut x: u64 = 0x0D1F_2026_1204_0003;
        let mut next = |n: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % n
        };
        let (mut tried, mut answered) = (0u32, 0u32);
        for case in 0..400_000u32 {
            let frac: u32 = if case % 2 == 0 { 16 } else { 12 };
            let one = 1i64 << frac;
            // |L|² ≥ 1, 255·N·L > 0, weights in [0, 12], bases around the pixel range.
            let ll = one + i64::try_from(next(400 << frac)).unwrap();
            let knl = 1 + i64::try_from(next(2000 << frac)).unwrap();
            let w: [i64; 3] = [0, 1, 2].map(|_| i64::try_from(next(12 << frac)).unwrap());
            let b: [i64; 3] =
                [0, 1, 2].map(|_| i64::try_from(next(300 << frac)).unwrap() - (20 << frac));
            let wk = w.map(|w| (w * knl) >> frac);
            let Ok(wk) = wk
                .map(i32::try_from)
                .into_iter()
                .collect::<Result<Vec<_>, _>>()
            else {
                continue;
            };
            let top = w.iter().max().unwrap() >> frac;
            // One DELTA is 1 in bits.
            let slack = i32::try_from(top + 3).unwrap();
            let exact = |c: usize| -> u8 {
                let f = (knl << frac) / ll;
                let t = (w[c] * f) >> frac;
                let v = (b[c] + t).clamp(0, 255 * one);
                u8::try_from((v + one / 2) >> frac).unwrap()
            };
            tried += 1;
            let base = b.map(|v| i32::try_from(v).unwrap());
            let d = i32::try_from(ll).unwrap();
            if let Some(p) = quick_pixel(base, [wk[0], wk[1], wk[2]], d, slack, frac) {
                answered += 1;
                assert_eq!(
                    p,
                    [exact(0), exact(1), exact(2)],
                    "case {case}: {b:?} {w:?} {knl} {ll}"
                );
            }
        }
        std::println!("quick pixels: {answered} of {tried} answered");
        assert!(
            f64::from(answered) > 0.95 * f64::from(tried),
            "{answered} of {tried}"
        );
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
        for shift in 0..32 {
            for low in [0u32, 1, 0x5A5A_5A5A, u32::MAX] {
                let x = (1u32 << shift) | (low & ((1u32 << shift) - 1));
                assert_eq!(leading_zeros_soft(x), x.leading_zeros(), "{x:#x}");
            }
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

    /// A refused quotient does not pass as within the bound: quotients well inside the
    /// range, and the zero divisor, are decided exactly here.
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

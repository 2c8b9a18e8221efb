//! Division by reciprocal for I16F16 bit patterns ([`super::variants::I16F16Recip`]): a
//! 256-entry table and two Newton steps in 32-bit arithmetic instead of a 64 by 32-bit
//! division (about 370 instructions on a Cortex-M0).

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

#[cfg(test)]
mod tests {
    use super::*;

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

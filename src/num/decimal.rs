//! [`Decimal`]: a scene number exactly as written, `±mantissa × 10^exponent`.
//!
//! The parser keeps numbers in this form and converts each one once, straight into the
//! chosen format ([`crate::Scalar::from_decimal`]): fixed formats round the exact decimal
//! value to nearest with integer arithmetic (no `f64` on the way, so no double rounding
//! and, on a chip, no soft-float code or float-parsing tables in flash); float formats
//! use `core`'s correctly rounded parser. Domain checks (`> 0`, `in [0, 1]`, ...) are
//! exact comparisons on the decimal.
//!
//! ```
//! use fixray::num::Decimal;
//! use core::cmp::Ordering;
//!
//! let d = Decimal::parse("-2.50e1").unwrap();
//! assert_eq!((d.negative, d.mantissa, d.exponent), (true, 250, -1));
//! assert_eq!(d.cmp_int(-25), Ordering::Equal);
//! assert!(Decimal::parse("1e").is_none());
//! ```

use core::cmp::Ordering;

/// `(−1)^negative × mantissa × 10^exponent`.
///
/// At least 19 significant digits are kept exactly; further digits are dropped (truncation,
/// a relative change below 1e-18, far under every format's resolution).
///
/// ```
/// use fixray::num::Decimal;
/// use fixray::{Scalar, I16F16};
///
/// let d = Decimal::parse("0.1").unwrap();
/// assert_eq!((d.mantissa, d.exponent), (1, -1));
/// // Converted once, straight into the format: the nearest I16F16 to one tenth.
/// assert_eq!(I16F16::from_decimal(d), Some(I16F16::from_num(0.1)));
/// assert_eq!(d.times(30).to_integer(), Some(3));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Decimal {
    /// Sign (`-0` is negative zero, which compares equal to zero).
    pub negative: bool,
    /// The significant digits.
    pub mantissa: u64,
    /// The power of ten.
    pub exponent: i32,
}

/// Exponents beyond this are saturated: every format's range ends long before.
const EXPONENT_LIMIT: i32 = 100_000;

impl Decimal {
    /// Parses the scene format's number syntax: optional sign, digits, optional fraction,
    /// optional exponent (`-7`, `0.5`, `.25`, `1e-3`). `None` for anything else (`inf`,
    /// `NaN`, `0x10`, `1,5`, ...).
    pub fn parse(text: &str) -> Option<Self> {
        let b = text.as_bytes();
        let mut i = 0;
        let mut d = Self::default();
        if let Some(&sign @ (b'+' | b'-')) = b.first() {
            d.negative = sign == b'-';
            i = 1;
        }
        let mut any_digit = false;
        let mut fraction = false;
        // Set at the first digit that no longer fits: every later digit is dropped too.
        let mut truncated = false;
        while let Some(&c) = b.get(i) {
            match c {
                b'0'..=b'9' => {
                    any_digit = true;
                    let value = u64::from(c - b'0');
                    let next = d
                        .mantissa
                        .checked_mul(10)
                        .and_then(|m| m.checked_add(value));
                    match next.filter(|_| !truncated) {
                        Some(m) => {
                            d.mantissa = m;
                            if fraction {
                                d.exponent = d.exponent.saturating_sub(1).max(-EXPONENT_LIMIT);
                            }
                        }
                        None => {
                            truncated = true;
                            // A dropped integer digit still scales the value.
                            if !fraction {
                                d.exponent = d.exponent.saturating_add(1).min(EXPONENT_LIMIT);
                            }
                        }
                    }
                }
                b'.' if !fraction => fraction = true,
                _ => break,
            }
            i += 1;
        }
        if !any_digit {
            return None;
        }
        if let Some(b'e' | b'E') = b.get(i) {
            i += 1;
            let negative = match b.get(i) {
                Some(b'-') => {
                    i += 1;
                    true
                }
                Some(b'+') => {
                    i += 1;
                    false
                }
                _ => false,
            };
            let start = i;
            let mut e: i32 = 0;
            while let Some(&c @ b'0'..=b'9') = b.get(i) {
                e = e
                    .saturating_mul(10)
                    .saturating_add(i32::from(c - b'0'))
                    .min(EXPONENT_LIMIT);
                i += 1;
            }
            if i == start {
                return None;
            }
            d.exponent = d
                .exponent
                .saturating_add(if negative { -e } else { e })
                .clamp(-EXPONENT_LIMIT, EXPONENT_LIMIT);
        }
        (i == b.len()).then_some(d.normalized())
    }

    /// Zero gets exponent 0, so that `0e39` is simply zero.
    fn normalized(self) -> Self {
        if self.mantissa == 0 {
            Self {
                exponent: 0,
                ..self
            }
        } else {
            self
        }
    }

    /// Whether the value is zero (of either sign).
    pub fn is_zero(&self) -> bool {
        self.mantissa == 0
    }

    /// Compares the value with an integer, exactly.
    pub fn cmp_int(&self, n: i64) -> Ordering {
        let self_negative = self.negative && !self.is_zero();
        match (self_negative, n < 0) {
            (false, true) => return Ordering::Greater,
            (true, false) => return Ordering::Less,
            _ => {}
        }
        let magnitude = self.cmp_magnitude(n.unsigned_abs());
        if self_negative {
            magnitude.reverse()
        } else {
            magnitude
        }
    }

    /// Compares |value| with `n` (u64 arithmetic: small code on a 32-bit chip).
    fn cmp_magnitude(&self, n: u64) -> Ordering {
        let m = self.mantissa;
        if m == 0 {
            return 0.cmp(&n);
        }
        if self.exponent >= 0 {
            // m × 10^e against n: overflow means far larger.
            match pow10_u64(self.exponent).and_then(|p| m.checked_mul(p)) {
                Some(lhs) => lhs.cmp(&n),
                None => Ordering::Greater,
            }
        } else {
            // m against n × 10^−e: overflow means far smaller.
            match pow10_u64(self.exponent).and_then(|p| n.checked_mul(p)) {
                Some(rhs) => m.cmp(&rhs),
                None => Ordering::Less,
            }
        }
    }

    /// The value as an integer, when it is one and fits an `i64`.
    pub fn to_integer(&self) -> Option<i64> {
        let m = self.mantissa;
        let magnitude = if m == 0 {
            0
        } else if self.exponent >= 0 {
            m.checked_mul(pow10_u64(self.exponent)?)?
        } else {
            let p = pow10_u64(self.exponent)?;
            if !m.is_multiple_of(p) {
                return None;
            }
            m / p
        };
        let magnitude = i64::try_from(magnitude).ok()?;
        Some(if self.negative { -magnitude } else { magnitude })
    }

    /// The value times `k`, exactly when the digits allow, else with the least significant
    /// digits dropped (see the type's documentation).
    pub fn times(self, k: u64) -> Self {
        let mut d = self;
        loop {
            if let Some(m) = d.mantissa.checked_mul(k) {
                return Self { mantissa: m, ..d }.normalized();
            }
            d.mantissa /= 10;
            d.exponent = d.exponent.saturating_add(1);
        }
    }

    /// `round(value × 2^frac_bits)`, ties away from zero: the bits of the nearest
    /// fixed-point number with `frac_bits` fraction bits. `None` when `mantissa·2^frac_bits`
    /// or the result exceeds `i128` (the formats take at most 32 fraction bits: a
    /// mantissa below 2^64 always fits).
    pub fn to_fixed_bits(&self, frac_bits: u32) -> Option<i128> {
        // `i128::MAX`, unsigned. Shifts, adds and 16-bit divisions only: 128-bit products
        // and quotients call helpers of kilobytes on a 32-bit core.
        const MAX: u128 = u128::MAX >> 1;
        let m = u128::from(self.mantissa);
        let scaled = m
            .checked_shl(frac_bits)
            .filter(|s| s >> frac_bits == m && *s <= MAX)?;
        let magnitude = if scaled == 0 {
            0
        } else if self.exponent >= 0 {
            // Ten times at a time: beyond `i128` within 39 steps.
            let mut x = scaled;
            for _ in 0..self.exponent {
                if x > MAX / 10 {
                    return None;
                }
                x = (x << 3) + (x << 1);
            }
            x
        } else {
            round_div_pow10(scaled, self.exponent.unsigned_abs())
        };
        let magnitude = i128::try_from(magnitude).ok()?;
        Some(if self.negative { -magnitude } else { magnitude })
    }
}

/// `round(n / 10^k)`, ties up, for `n < 2^127`: `y = ⌊2n / 10^k⌋` by `k` divisions by ten
/// of 16-bit limbs (each an exact floor, so their chain is `⌊2n / 10^k⌋`), then
/// `⌊(y + 1) / 2⌋`, which is `⌊(2n + 10^k) / (2·10^k)⌋`. No 128-bit division: its
/// helper would be inlined at every fixed format's `from_decimal`, a large copy in flash
/// per format on the Cortex-M0.
fn round_div_pow10(n: u128, k: u32) -> u128 {
    const LIMBS: usize = 8;
    let two_n = n << 1;
    // Most significant first.
    let mut limbs = [0u32; LIMBS];
    for (i, limb) in limbs.iter_mut().enumerate() {
        let shift = 16 * (LIMBS - 1 - i);
        *limb = u32::try_from((two_n >> shift) & 0xFFFF).unwrap_or(0);
    }
    for _ in 0..k {
        if limbs == [0; LIMBS] {
            break;
        }
        let mut rem = 0u32;
        for limb in &mut limbs {
            // rem < 10: cur < 10·2^16, its quotient < 2^16.
            let cur = (rem << 16) | *limb;
            *limb = cur / 10;
            rem = cur % 10;
        }
    }
    let y = limbs
        .iter()
        .fold(0u128, |acc, &limb| (acc << 16) | u128::from(limb));
    // k ≥ 1: y ≤ 2n/10 < 2^125, so `y + 1` does not overflow.
    (y + 1) >> 1
}

impl Decimal {
    /// The nearest `f32` (ties to even), `None` when it is infinite: the decimal's exact
    /// value divided out bit by bit in integer arithmetic (a 256-bit quotient, its
    /// remainder as the sticky bit) and rounded once, subnormals included. What `core`'s
    /// parser gives, without its tables and code in flash; a
    /// scene's numbers are converted once, at parse time.
    ///
    /// ```
    /// use fixray::num::Decimal;
    ///
    /// let d = Decimal::parse("0.1").unwrap();
    /// assert_eq!(d.to_f32(), Some(0.1f32));
    /// assert_eq!(Decimal::parse("1e39").unwrap().to_f32(), None);
    /// ```
    pub fn to_f32(&self) -> Option<f32> {
        let magnitude = if self.mantissa == 0 {
            0.0
        } else {
            f32_of_ratio(self.mantissa, self.exponent)?
        };
        Some(if self.negative { -magnitude } else { magnitude })
    }
}

/// `m × 10^e` (`m > 0`) rounded to the nearest `f32`: `n/d` with `n = m·10^max(e,0)`,
/// `d = 10^max(−e,0)`, aligned so that `1 ≤ n/d < 2`, then 63 more quotient bits.
fn f32_of_ratio(m: u64, e: i32) -> Option<f32> {
    // 10^39 > f32::MAX; m·10^e < 2^64·10^−65 < 2^−150 rounds to zero.
    if e > 38 {
        return None;
    }
    if e < -64 {
        return Some(0.0);
    }
    let mut n = Big::from(m);
    let mut d = Big::from(1);
    for _ in 0..e.unsigned_abs() {
        if e > 0 {
            n.times10();
        } else {
            d.times10();
        }
    }
    // n < 2^192, d < 2^213: aligned and doubled, both stay below 2^256.
    let a = i32::try_from(n.bits()).ok()? - i32::try_from(d.bits()).ok()?;
    if a >= 0 {
        d.shl(a.unsigned_abs());
    } else {
        n.shl(a.unsigned_abs());
    }
    let mut exp = a;
    if !n.at_least(&d) {
        n.shl(1);
        exp -= 1;
    }
    n.sub(&d);
    let mut q: u64 = 1;
    for _ in 0..63 {
        n.shl(1);
        q <<= 1;
        if n.at_least(&d) {
            n.sub(&d);
            q |= 1;
        }
    }
    round_f32(q, exp - 63, !n.is_zero())
}

/// `q·2^e2` (`q`'s top bit set), `sticky` when the exact value is a little more: the
/// nearest `f32`, ties to even, `None` when infinite.
fn round_f32(q: u64, e2: i32, sticky: bool) -> Option<f32> {
    // The exponent of the top bit, and of the result's last bit (subnormals: 2^−149).
    let top = 63 + e2;
    if top > 127 {
        return None;
    }
    let last = (top - 23).max(-149);
    let shift = (last - e2).unsigned_abs();
    let wide = u128::from(q);
    let (kept, rest, half) = if shift >= 128 {
        (0, wide, u128::MAX)
    } else {
        (
            wide >> shift,
            wide & ((1u128 << shift) - 1),
            1u128 << (shift - 1),
        )
    };
    let up = rest > half || (rest == half && (sticky || kept & 1 == 1));
    let r = u32::try_from(kept + u128::from(up)).ok()?;
    let v = if top < -126 {
        // Subnormal: the bits are the value in units of 2^−149 (2^23 is the least normal).
        f32::from_bits(r)
    } else {
        #[allow(clippy::cast_precision_loss)] // r ≤ 2^24: exact.
        let r = r as f32;
        let scale = if last >= -126 {
            f32::from_bits(((last + 127).unsigned_abs()) << 23)
        } else {
            f32::from_bits(1 << (last + 149).unsigned_abs())
        };
        // Exact: r·2^last is an f32 (or infinite at the top).
        r * scale
    };
    v.is_finite().then_some(v)
}

/// A 256-bit unsigned integer (eight 32-bit limbs, least significant first): what
/// [`f32_of_ratio`] divides with.
#[derive(Clone, Copy)]
struct Big([u32; 8]);

impl Big {
    fn from(v: u64) -> Self {
        let mut b = [0u32; 8];
        b[0] = v as u32;
        b[1] = (v >> 32) as u32;
        Self(b)
    }

    fn times10(&mut self) {
        let mut carry = 0u64;
        for limb in &mut self.0 {
            let v = u64::from(*limb) * 10 + carry;
            *limb = v as u32;
            carry = v >> 32;
        }
    }

    fn bits(&self) -> u32 {
        let mut bits = 0;
        for (i, &limb) in self.0.iter().enumerate() {
            if limb != 0 {
                bits = 32 * (i as u32) + (32 - limb.leading_zeros());
            }
        }
        bits
    }

    fn shl(&mut self, by: u32) {
        let (words, bits) = ((by / 32) as usize, by % 32);
        for i in (0..8usize).rev() {
            let lo = i.checked_sub(words).map_or(0, |j| self.0[j]);
            let below = i.checked_sub(words + 1).map_or(0, |j| self.0[j]);
            self.0[i] = if bits == 0 {
                lo
            } else {
                (lo << bits) | (below >> (32 - bits))
            };
        }
    }

    fn at_least(&self, other: &Self) -> bool {
        for (a, b) in self.0.iter().zip(&other.0).rev() {
            if a != b {
                return a > b;
            }
        }
        true
    }

    fn sub(&mut self, other: &Self) {
        let mut borrow = false;
        for (a, &b) in self.0.iter_mut().zip(&other.0) {
            let (v, b1) = a.overflowing_sub(b);
            let (v, b2) = v.overflowing_sub(u32::from(borrow));
            *a = v;
            borrow = b1 || b2;
        }
    }

    fn is_zero(&self) -> bool {
        self.0.iter().all(|&l| l == 0)
    }
}

/// 10^|e| for |e| ≤ 19 (the powers that fit a `u64`); callers pick the direction.
fn pow10_u64(e: i32) -> Option<u64> {
    10u64.checked_pow(e.unsigned_abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_table() {
        type Parts = Option<(bool, u64, i32)>;
        let cases: [(&str, Parts); 18] = [
            ("-7", Some((true, 7, 0))),
            ("0.5", Some((false, 5, -1))),
            (".25", Some((false, 25, -2))),
            ("1e-3", Some((false, 1, -3))),
            ("+2", Some((false, 2, 0))),
            ("5.", Some((false, 5, 0))),
            ("1E+4", Some((false, 1, 4))),
            ("-0.0", Some((true, 0, 0))),
            (
                "123456789012345678901",
                Some((false, 12_345_678_901_234_567_890, 1)),
            ),
            (
                "0.12345678901234567890123",
                Some((false, 12_345_678_901_234_567_890, -20)),
            ),
            ("", None),
            ("-", None),
            (".", None),
            ("e5", None),
            ("1e", None),
            ("1.2.3", None),
            ("inf", None),
            ("0x10", None),
        ];
        for (text, expected) in cases {
            let got = Decimal::parse(text).map(|d| (d.negative, d.mantissa, d.exponent));
            assert_eq!(got, expected, "{text}");
        }
        for bad in ["NaN", "1,5", "--1", "1e+-2", "é"] {
            assert_eq!(Decimal::parse(bad), None, "{bad}");
        }
        // Huge exponents saturate instead of overflowing.
        assert_eq!(
            Decimal::parse("1e99999999999").unwrap().exponent,
            EXPONENT_LIMIT
        );
        // Zero is zero whatever its exponent.
        assert_eq!(Decimal::parse("0e39").unwrap().exponent, 0);
        // Once a digit is dropped, later ones are too (no digit is shifted into its place).
        let d = Decimal::parse("184467440737095516160").unwrap();
        assert_eq!((d.mantissa, d.exponent), (1_844_674_407_370_955_161, 2));
        let d = Decimal::parse("1844674407370955161.61").unwrap();
        assert_eq!((d.mantissa, d.exponent), (1_844_674_407_370_955_161, 0));
    }

    /// `to_f32` is `core`'s correctly rounded parser, on seeded random decimals across
    /// the whole range (overflow, subnormals, zero), on halfway cases and on long
    /// mantissas.
    #[test]
    fn to_f32_rounds_as_core_does() {
        let check = |m: u64, e: i32, negative: bool| {
            let d = Decimal {
                negative,
                mantissa: m,
                exponent: e,
            };
            let sign = if negative { "-" } else { "" };
            let want: f32 = format!("{sign}{m}e{e}").parse().unwrap();
            let want = want.is_finite().then_some(want);
            assert_eq!(
                d.to_f32().map(f32::to_bits),
                want.map(f32::to_bits),
                "{sign}{m}e{e}"
            );
        };
        let mut next = crate::num::xorshift(0x2545_f491_4f6c_dd1d);
        for i in 0..40_000u32 {
            let digits = next() % 20 + 1;
            let m = next() % 10u64.pow(u32::try_from(digits.min(19)).unwrap()) + 1;
            let e = i32::try_from(next() % 120).unwrap() - 80;
            check(m, e, i % 2 == 0);
        }
        // Halfway between two f32s (ties to even both ways), a hair above and below, the
        // extremes, and the last values before zero.
        for (m, e) in [
            (16_777_217, 0),
            (16_777_219, 0),
            (33_554_434, 0),
            (33_554_438, 0),
            (1_000_000_059_604_644_775, -18),
            (1_000_000_059_604_644_776, -18),
            (3_402_823_567_797_336_616, 20),
            (3_402_823_466, 29),
            (3_402_823_467, 29),
            (u64::MAX, 19),
            (u64::MAX, -64),
            (701, -48),
            (700_649_232_162_408_535, -63),
            (1_401_298_464_324_817, -60),
            (1, -38),
            (11_754_942, -45),
            (1, 38),
            (1, -64),
        ] {
            check(m, e, false);
        }
        assert_eq!(
            Decimal::parse("-0").unwrap().to_f32().map(f32::to_bits),
            Some((-0.0f32).to_bits())
        );
    }

    /// The fields are public: extreme values must not overflow any method.
    #[test]
    fn extreme_fields_do_not_overflow() {
        for exponent in [i32::MIN, i32::MAX, -39, 39] {
            for mantissa in [0, 1, u64::MAX] {
                for negative in [false, true] {
                    let d = Decimal {
                        negative,
                        mantissa,
                        exponent,
                    };
                    let _ = (
                        d.cmp_int(0),
                        d.cmp_int(i64::MIN),
                        d.to_integer(),
                        d.to_f32(),
                    );
                    let _ = (d.to_fixed_bits(16), d.to_fixed_bits(64), d.times(255));
                }
            }
        }
        let zero_big = Decimal {
            negative: false,
            mantissa: 0,
            exponent: 50,
        };
        assert_eq!(zero_big.cmp_int(0), Ordering::Equal);
        assert_eq!(zero_big.to_fixed_bits(16), Some(0));
        assert_eq!(zero_big.to_integer(), Some(0));
    }

    #[test]
    fn comparisons_are_exact() {
        let d = |s| Decimal::parse(s).unwrap();
        assert_eq!(d("90").cmp_int(90), Ordering::Equal);
        assert_eq!(d("90.0000000001").cmp_int(90), Ordering::Greater);
        assert_eq!(d("-0").cmp_int(0), Ordering::Equal);
        assert_eq!(d("-1e-300").cmp_int(0), Ordering::Less);
        assert_eq!(d("1e300").cmp_int(i64::MAX), Ordering::Greater);
        assert_eq!(d("-1e300").cmp_int(i64::MIN), Ordering::Less);
        assert_eq!(d("4.096e3").to_integer(), Some(4096));
        assert_eq!(d("6.5").to_integer(), None);
        assert_eq!(d("1e30").to_integer(), None);
    }

    /// The 16-bit-limb rounding division against the 128-bit one it avoids, on the
    /// edges (ties, zero, the largest numerators, 10^k beyond 2^128) and 200,000 seeded
    /// cases.
    #[test]
    fn rounded_division_by_powers_of_ten_is_the_wide_ones() {
        // The 128-bit formula, in `u128` (its `i128` form overflowed `2·(n mod p)` for
        // `n ≥ 2^126`, which needs 62 or more fraction bits; no format has them).
        fn wide(n: u128, k: u32) -> u128 {
            match 10u128.checked_pow(k) {
                Some(p) => n / p + u128::from(2 * (n % p) >= p),
                None => 0,
            }
        }
        let top = (1u128 << 127) - 1;
        let mut cases = vec![
            (0, 1),
            (5, 1),
            (4, 1),
            (15, 1),
            (25, 1),
            (50, 2),
            (49, 2),
            (top, 1),
            (top, 20),
            (top, 38),
            (top, 39),
            (top, 60),
            (1, 40),
            (u128::from(u64::MAX) << 32, 19),
        ];
        let mut next = crate::num::xorshift(0x9E37_79B9_7F4A_7C15);
        for _ in 0..200_000 {
            let n = (u128::from(next()) << 64 | u128::from(next())) >> (next() % 127 + 1);
            let k = u32::try_from(next() % 42).unwrap() + 1;
            cases.push((n, k));
        }
        for (n, k) in cases {
            assert_eq!(round_div_pow10(n, k), wide(n, k), "{n} / 10^{k}");
        }
    }

    /// `to_fixed_bits` against the 128-bit formula it had (products and a quotient; its
    /// remainder test in `u128`, where the `i128` one overflowed at 62 fraction bits),
    /// over seeded decimals of every size and the fixed formats' fraction bits.
    #[test]
    fn fixed_bits_are_the_wide_formulas() {
        fn wide(d: &Decimal, frac_bits: u32) -> Option<i128> {
            let scaled = i128::from(d.mantissa).checked_mul(1i128.checked_shl(frac_bits)?)?;
            let magnitude = if scaled == 0 {
                0
            } else if d.exponent >= 0 {
                let p = 10u128.checked_pow(d.exponent.unsigned_abs())?;
                scaled.checked_mul(i128::try_from(p).ok()?)?
            } else {
                let n = scaled.unsigned_abs();
                let q = match 10u128.checked_pow(d.exponent.unsigned_abs()) {
                    Some(p) => n / p + u128::from(2 * (n % p) >= p),
                    None => 0,
                };
                i128::try_from(q).ok()?
            };
            Some(if d.negative { -magnitude } else { magnitude })
        }
        let mut next = crate::num::xorshift(0x2545_F491_4F6C_DD1D);
        for _ in 0..100_000 {
            let d = Decimal {
                negative: next().is_multiple_of(2),
                mantissa: next() >> (next() % 64),
                exponent: i32::try_from(next() % 91).unwrap() - 45,
            };
            for frac_bits in [0, 12, 16, 32, 63] {
                assert_eq!(
                    d.to_fixed_bits(frac_bits),
                    wide(&d, frac_bits),
                    "{d:?} {frac_bits}"
                );
            }
        }
    }

    #[test]
    fn fixed_bits_round_to_nearest() {
        let d = |s| Decimal::parse(s).unwrap();
        // 0.7 × 2^16 = 45875.2 → 45875; 0.7 × 255 = 178.5 exactly.
        assert_eq!(d("0.7").to_fixed_bits(16), Some(45875));
        assert_eq!(
            d("0.7").times(255).to_fixed_bits(16),
            Some(178 * 65536 + 32768)
        );
        // Ties away from zero: 2^-17 = 0.00000762939453125 is half a DELTA of I16F16.
        assert_eq!(d("0.00000762939453125").to_fixed_bits(16), Some(1));
        assert_eq!(d("-0.00000762939453125").to_fixed_bits(16), Some(-1));
        assert_eq!(d("1e-60").to_fixed_bits(32), Some(0));
        assert_eq!(d("-7").to_fixed_bits(16), Some(-7 * 65536));
        assert_eq!(d("1e40").to_fixed_bits(16), None);
    }
}

//! The hints of the parser's messages, which a chip's build leaves out ([`HINTS`]): the
//! name a misspelt word most likely meant, a number format's range and the formats of
//! [`MAIN`] that hold a number or resolve a length the scene derives (from each format's
//! constants, no code of its arithmetic), and a derived value written short.

use core::fmt;

use super::error::Quantity;
use crate::num::Decimal;
use crate::num::formats::MAIN;
#[cfg(not(target_os = "none"))]
use crate::scene::{MIN_RADIUS_SQ_DELTAS, MIN_SCALE_DELTAS};

/// Whether the parser looks for hints and its messages carry them: the entity's attributes
/// and the nearest one, a format's range, the value of a derived length and the formats
/// that hold or resolve it, invisible characters escaped, an example camera, and where a
/// block that is not closed ends
/// ([`SceneErrorKind::Unclosed`](super::SceneErrorKind::Unclosed)). Everywhere but on bare
/// metal (`target_os = "none"`: a chip's firmware), where their code, some 8 KB, is more
/// flash than a 64 KB chip has to spare. There a block that is not closed is reported at
/// its next statement's first word, or at the end of the input,
/// [`SceneErrorKind::nearest`](super::SceneErrorKind::nearest) is `None`, a scale error
/// keeps no number nor formats (it returns at once: on a host the parse reads on, for the
/// formats that resolve the whole scene), and every other error is the same kind at the
/// same position, its message without the hint.
pub(super) const HINTS: bool = cfg!(not(target_os = "none"));

/// ` (range ±…); {holders} hold it`: the hint of a number beyond the range of `format`
/// (the holders when the number is known).
pub(super) fn beyond_range(
    f: &mut fmt::Formatter<'_>,
    format: &str,
    number: Option<Decimal>,
) -> fmt::Result {
    f.write_str(" (range ±")?;
    match Shape::of(format) {
        Some(Shape::Fixed { int, .. }) => write!(f, "{}", 1u32 << int.saturating_sub(1).min(31))?,
        Some(Shape::Float { max, .. }) => f.write_str(max)?,
        None => f.write_str("?")?,
    }
    f.write_str(")")?;
    match number {
        Some(n) => {
            f.write_str("; ")?;
            holders(f, format, |_, s| s.holds(&n), "and", ("holds", "hold"))
        }
        None => Ok(()),
    }
}

/// The value of a derived quantity from the number it is derived from, as written (a
/// pitch's `worlddim`, over `pixels`; a radius): to 18 significant digits, a square to 9.
/// `None` without [`HINTS`], or when the number was cut to be quoted.
pub(super) fn derived(quantity: Quantity, number: &str, pixels: u16) -> Option<Decimal> {
    if !HINTS {
        return None;
    }
    Some(derive(quantity, Decimal::parse(number)?, pixels))
}

/// The value of a derived quantity from the number `d` it is derived from ([`derived`]).
fn derive(quantity: Quantity, mut d: Decimal, pixels: u16) -> Decimal {
    match quantity {
        Quantity::PixelPitch => {
            while let Some(m) = d.mantissa.checked_mul(10).filter(|m| *m < u64::MAX / 10) {
                d.mantissa = m;
                d.exponent = d.exponent.saturating_sub(1);
            }
            d.mantissa /= u64::from(pixels.max(1));
        }
        Quantity::Radius => {}
        Quantity::RadiusSq => {
            while d.mantissa > u64::from(u32::MAX) {
                d.mantissa /= 10;
                d.exponent = d.exponent.saturating_add(1);
            }
            d.mantissa *= d.mantissa;
            d.exponent = d.exponent.saturating_mul(2);
        }
    }
    d
}

/// The formats of [`MAIN`] (bit `i`: `MAIN[i]`) that resolve a length the scene derives
/// from `number` among coordinates below 2^`order`, as the parser's scale rule asks of
/// each ([`Shape::resolves`]): a pixel pitch (`quantity`; `number` a `worlddim` over
/// `pixels`), or a sphere's radius (either of the other quantities: `number` the radius,
/// held to its square in a fixed format). Only where [`HINTS`] holds (the parser keeps
/// the formats there).
#[cfg(not(target_os = "none"))]
pub(super) fn resolvers(quantity: Quantity, number: &Decimal, pixels: u16, order: u8) -> u8 {
    let mut bits = 0;
    for (i, name) in MAIN.iter().enumerate() {
        if Shape::of(name).is_some_and(|s| s.resolves(quantity, number, pixels, order)) {
            bits |= 1 << i;
        }
    }
    bits
}

/// Lists the formats of [`MAIN`] other than `format` for which `ok` holds (given a
/// format's index in [`MAIN`] and its shape): `a, b and c hold it` (`last` joins the last
/// two; `verb` is the singular and plural verb), or `no number format holds it`.
pub(super) fn holders(
    f: &mut fmt::Formatter<'_>,
    format: &str,
    ok: impl Fn(usize, Shape) -> bool,
    last: &str,
    (one, many): (&str, &str),
) -> fmt::Result {
    let mut names = heapless::Vec::<&str, { MAIN.len() }>::new();
    for (i, name) in MAIN.into_iter().enumerate() {
        if name != format && Shape::of(name).is_some_and(|s| ok(i, s)) {
            let _ = names.push(name);
        }
    }
    let count = names.len();
    if count == 0 {
        return write!(f, "no number format {one} it");
    }
    for (i, name) in names.iter().enumerate() {
        let sep = match i {
            0 => "",
            _ if i + 1 == count => last,
            _ => ",",
        };
        if i > 0 && i + 1 == count {
            write!(f, " {sep} ")?;
        } else if i > 0 {
            write!(f, "{sep} ")?;
        }
        f.write_str(name)?;
    }
    write!(f, " {} it", if count == 1 { one } else { many })
}

/// A number format's range and resolution, as the messages need them: its constants
/// ([`crate::Scalar::INT_BITS`] and its size), so that naming a format costs no code of
/// its arithmetic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Shape {
    /// A fixed format: `int` integer bits (the sign's included) and `frac` fraction bits.
    Fixed { int: u32, frac: u32 },
    /// A float with `mantissa` fraction bits (`DELTA` = 2^−mantissa), holding every value
    /// below 10^`order` (a power of ten below its largest), its largest `max` written
    /// short.
    Float {
        mantissa: u32,
        order: i32,
        max: &'static str,
    },
}

impl Shape {
    /// The shape of the format named `name` ([`crate::num::formats::FORMATS`]).
    fn of(name: &str) -> Option<Self> {
        crate::with_format!(name, shape()).ok()
    }

    /// Whether the format holds `number` (floats: a conservative test, below 10^order).
    fn holds(self, number: &Decimal) -> bool {
        match self {
            Shape::Fixed { int, frac } => {
                let limit = 1i128 << (int + frac).saturating_sub(1).min(126);
                number
                    .to_fixed_bits(frac)
                    .is_some_and(|b| -limit <= b && b < limit)
            }
            Shape::Float { order, .. } => {
                let mut digits = 0i32;
                let mut m = number.mantissa;
                while m > 0 {
                    m /= 10;
                    digits += 1;
                }
                number.mantissa == 0 || number.exponent.saturating_add(digits) <= order
            }
        }
    }

    /// Whether the format resolves the length `quantity` derived from `number` (a pitch
    /// over `pixels`; a sphere's radius for either other quantity) among coordinates below
    /// 2^`order` as the parser's scale rule asks: a pitch of [`MIN_SCALE_DELTAS`] ulps
    /// (`DELTA`; a float's times 2^`order`); a radius, in a fixed format, whose square
    /// it holds, of [`MIN_RADIUS_SQ_DELTAS`] `DELTA`s, in a float of [`MIN_SCALE_DELTAS`]
    /// ulps. A fixed format must hold 2^`order` too.
    #[cfg(not(target_os = "none"))]
    fn resolves(self, quantity: Quantity, number: &Decimal, pixels: u16, order: u8) -> bool {
        let order = u32::from(order);
        let pitch = quantity == Quantity::PixelPitch;
        let (value, bits, min) = match self {
            Shape::Fixed { int, .. } if order >= int => return false,
            Shape::Fixed { frac, .. } if pitch => {
                (derive(quantity, *number, pixels), frac, MIN_SCALE_DELTAS)
            }
            Shape::Fixed { frac, .. } => {
                let square = derive(Quantity::RadiusSq, *number, 1);
                if !self.holds(&square) {
                    return false;
                }
                (square, frac, MIN_RADIUS_SQ_DELTAS)
            }
            Shape::Float { mantissa, .. } => {
                let length = if pitch { quantity } else { Quantity::Radius };
                (
                    derive(length, *number, pixels),
                    mantissa.saturating_sub(order),
                    MIN_SCALE_DELTAS,
                )
            }
        };
        // `None`: beyond i128 after the shift, far above the limit.
        value
            .to_fixed_bits(bits)
            .is_none_or(|v| v >= i128::from(min))
    }
}

/// The [`Shape`] of format `S`.
fn shape<S: crate::Scalar>() -> Shape {
    let bits = u32::try_from(8 * core::mem::size_of::<S>()).unwrap_or(u32::MAX);
    if S::INT_BITS > 0 {
        Shape::Fixed {
            int: S::INT_BITS,
            frac: bits.saturating_sub(S::INT_BITS),
        }
    } else if bits <= 32 {
        // IEEE binary32.
        Shape::Float {
            mantissa: 23,
            order: 38,
            max: "3.4e38",
        }
    } else {
        // IEEE binary64.
        Shape::Float {
            mantissa: 52,
            order: 308,
            max: "1.8e308",
        }
    }
}

/// Writes a decimal with up to four significant digits (the rest truncated): plainly
/// from 0.0001 to below 10^7, else as `6.25e-6`.
pub(super) fn write_decimal(f: &mut fmt::Formatter<'_>, d: &Decimal) -> fmt::Result {
    let (mut m, mut e) = (d.mantissa, d.exponent);
    while m >= 10_000 || (m != 0 && m % 10 == 0) {
        m /= 10;
        e = e.saturating_add(1);
    }
    // Below 10^4: `digits` digits (1 to 4).
    let m = u32::try_from(m).unwrap_or(0);
    let digits = match m {
        0..=9 => 1,
        10..=99 => 2,
        100..=999 => 3,
        _ => 4,
    };
    if d.negative && m != 0 {
        f.write_str("-")?;
    }
    // The value is 0.m × 10^point.
    let point = e.saturating_add(digits);
    if m == 0 || (e >= 0 && point <= 7) {
        // An integer: its digits, then zeros.
        write!(f, "{m}")?;
        (0..e).try_for_each(|_| f.write_str("0"))
    } else if (-3..=0).contains(&point) {
        f.write_str("0.")?;
        (point..0).try_for_each(|_| f.write_str("0"))?;
        write!(f, "{m}")
    } else {
        // `m` with a point before its last `after` digits, then the exponent if any.
        let plain = (1..=7).contains(&point);
        let after = if plain { -e } else { digits - 1 };
        let p = 10u32.pow(u32::try_from(after).unwrap_or(0).min(3));
        write!(f, "{}", m / p)?;
        if after > 0 {
            let w = usize::try_from(after).unwrap_or(0);
            write!(f, ".{:0w$}", m % p)?;
        }
        if plain {
            return Ok(());
        }
        let x = point.saturating_sub(1);
        let sign = if x < 0 { "-" } else { "" };
        write!(f, "e{sign}{}", x.unsigned_abs())
    }
}

/// The name of `names` nearest to `word`: at most a third of its letters (at least one)
/// added, dropped, changed or swapped with a neighbour; the first of the nearest. Without
/// an allocator: three rows of the distance table on the stack.
pub(super) fn nearest(
    word: &str,
    names: impl Iterator<Item = &'static str>,
) -> Option<&'static str> {
    let mut best: Option<(&'static str, u8)> = None;
    for name in names {
        let limit = u8::try_from(name.len() / 3).unwrap_or(u8::MAX).max(1);
        if let Some(d) = distance(word, name, limit)
            && best.is_none_or(|(_, b)| d < b)
        {
            best = Some((name, d));
        }
    }
    best.map(|(name, _)| name)
}

/// Longest name [`distance`] measures, in bytes (the schema's longest is 12).
const MAX_EDIT_NAME: usize = 16;

/// The optimal-string-alignment distance (Levenshtein's, with a swap of two neighbours
/// as one edit) between `word`'s characters and the ASCII `name`'s, when it is at most
/// `limit`; `None` beyond, or for a name longer than [`MAX_EDIT_NAME`].
fn distance(word: &str, name: &str, limit: u8) -> Option<u8> {
    let name = name.as_bytes();
    let n = name.len();
    if n >= MAX_EDIT_NAME {
        return None;
    }
    // Rows i − 2, i − 1 and i of d[i][j], the distance between the word's first i
    // characters and the name's first j bytes.
    let (mut older, mut prev, mut cur) = (
        [0u8; MAX_EDIT_NAME],
        [0u8; MAX_EDIT_NAME],
        [0u8; MAX_EDIT_NAME],
    );
    for (j, d) in prev.iter_mut().enumerate() {
        *d = u8::try_from(j).unwrap_or(u8::MAX);
    }
    let mut before = '\0';
    for (i, c) in word.chars().enumerate() {
        cur[0] = u8::try_from(i + 1).unwrap_or(u8::MAX);
        let mut least = cur[0];
        for j in 1..=n {
            let b = char::from(name[j - 1]);
            let mut d = (prev[j].min(cur[j - 1]).saturating_add(1))
                .min(prev[j - 1].saturating_add(u8::from(c != b)));
            if i > 0 && j > 1 && c == char::from(name[j - 2]) && before == b {
                d = d.min(older[j - 2].saturating_add(1));
            }
            cur[j] = d;
            least = least.min(d);
        }
        // No later row is below this one's least: past the limit for good.
        if least > limit {
            return None;
        }
        (older, prev) = (prev, cur);
        before = c;
    }
    let d = prev[n];
    (d <= limit).then_some(d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::ToString;

    /// The distance counts a letter changed, added, dropped, or two neighbours swapped,
    /// as one edit each; beyond the limit there is none.
    #[test]
    fn distances_count_edits() {
        for (word, name, d) in [
            ("center", "center", Some(0)),
            ("centre", "center", Some(1)),
            ("cenrte", "center", Some(2)),
            ("cetner", "center", Some(1)),
            ("cnter", "center", Some(1)),
            ("centerr", "center", Some(1)),
            ("Center", "center", Some(1)),
            ("", "v0", Some(2)),
            ("ambient\u{200b}", "ambient", Some(1)),
            ("middle", "center", None),
            ("x", "dimensions_of_it_all", None),
        ] {
            assert_eq!(distance(word, name, 2), d, "{word} {name}");
        }
        let names = || ["material", "center", "radius"].into_iter();
        assert_eq!(nearest("radious", names()), Some("radius"));
        assert_eq!(nearest("colour", names()), None);
        // At most a third of the name's letters: `v3` is one from `v0`.
        assert_eq!(nearest("v3", ["v0", "v1"].into_iter()), Some("v0"));
        assert_eq!(nearest("xy", ["v0"].into_iter()), None);
    }

    struct Shown(Decimal);
    impl fmt::Display for Shown {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write_decimal(f, &self.0)
        }
    }

    /// Decimals are written with up to four significant digits, plainly from 0.0001 to
    /// below 10^7.
    #[test]
    fn decimals_are_written_short() {
        for (text, shown) in [
            ("40000", "40000"),
            ("0.00000625", "6.25e-6"),
            ("0.0005", "0.0005"),
            ("0.00006062", "6.062e-5"),
            ("0.000016", "1.6e-5"),
            ("1.05", "1.05"),
            ("123.456", "123.4"),
            ("0.05", "0.05"),
            ("1e999", "1e999"),
            ("12345678", "1.234e7"),
            ("-2.5", "-2.5"),
            ("0", "0"),
        ] {
            let d = Decimal::parse(text).unwrap();
            assert_eq!(Shown(d).to_string(), shown, "{text}");
        }
    }

    /// The shapes of the formats, from their constants.
    #[test]
    fn formats_have_their_shapes() {
        assert_eq!(
            Shape::of("i16f16"),
            Some(Shape::Fixed { int: 16, frac: 16 })
        );
        assert_eq!(
            Shape::of("i16f16r"),
            Some(Shape::Fixed { int: 16, frac: 16 })
        );
        assert_eq!(
            Shape::of("i20f12"),
            Some(Shape::Fixed { int: 20, frac: 12 })
        );
        assert_eq!(
            Shape::of("i32f32"),
            Some(Shape::Fixed { int: 32, frac: 32 })
        );
        assert!(matches!(
            Shape::of("f32m"),
            Some(Shape::Float { mantissa: 23, .. })
        ));
        assert!(matches!(
            Shape::of("f64"),
            Some(Shape::Float { mantissa: 52, .. })
        ));
        assert_eq!(Shape::of("q15"), None);
    }
}

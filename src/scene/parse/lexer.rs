//! The lexer: `{`, `}` and runs of other non-space characters, with positions; `#`
//! comments run to the end of the line. A byte order mark is a character of its token,
//! shown escaped in messages ([`quote`]); the parser skips one at the very start of a
//! text (`Scene::read_with`).

use super::error::{MAX_NUMBER, MAX_QUOTED, Pos, Quoted, QuotedNumber};

#[derive(Debug, Clone, Copy)]
pub(super) struct Token<'a> {
    pub(super) text: &'a str,
    pub(super) pos: Pos,
}

/// Splits the text into tokens: `{`, `}` and runs of other non-space characters; `#`
/// comments run to the end of the line.
#[derive(Clone)]
pub(super) struct Lexer<'a> {
    rest: &'a str,
    pub(super) pos: Pos,
}

impl<'a> Lexer<'a> {
    pub(super) fn new(text: &'a str) -> Self {
        Self {
            rest: text,
            pos: Pos { line: 1, column: 1 },
        }
    }

    /// Moves the position over byte `c` of the text: a new line at `\n`, a column at the
    /// first byte of every other character (columns count characters).
    fn step(&mut self, c: u8) {
        if c == b'\n' {
            self.pos.line = self.pos.line.saturating_add(1);
            self.pos.column = 1;
        } else if c & 0xC0 != 0x80 {
            self.pos.column = self.pos.column.saturating_add(1);
        }
    }

    /// The next token. Byte by byte: every separator is ASCII, so a token starts and ends
    /// on a character boundary (`get` keeps the impossible panic path, and its formatting
    /// code, out of the firmware).
    pub(super) fn next_token(&mut self) -> Option<Token<'a>> {
        let b = self.rest.as_bytes();
        let mut i = 0;
        // Skip white space and comments.
        loop {
            let Some(&c) = b.get(i) else {
                // At the end: nothing left to skip again (the position stays).
                self.rest = "";
                return None;
            };
            if c == b'#' {
                while let Some(&c) = b.get(i).filter(|&&c| c != b'\n') {
                    self.step(c);
                    i += 1;
                }
            } else if is_space(c) {
                self.step(c);
                i += 1;
            } else {
                break;
            }
        }
        let (start, pos) = (i, self.pos);
        // A brace is a token of its own.
        let brace = matches!(b.get(start), Some(b'{' | b'}'));
        while let Some(&c) = b.get(i) {
            if i > start && (brace || is_space(c) || matches!(c, b'{' | b'}' | b'#')) {
                break;
            }
            self.step(c);
            i += 1;
        }
        let text = self.rest.get(start..i).unwrap_or("");
        self.rest = self.rest.get(i..).unwrap_or("");
        Some(Token { text, pos })
    }
}

/// Whether `c` separates tokens: the white space of the course's C reader (`scanf`'s
/// `%s`, `isspace` in the C locale), ASCII only. A no-break space or another Unicode space
/// is part of a token there, and here. (Unicode's table would also cost a chip flash.)
fn is_space(c: u8) -> bool {
    matches!(c, b' ' | b'\t' | b'\n' | 0x0B | 0x0C | b'\r')
}

/// A token as an error message quotes it: control and invisible characters escaped as
/// Rust writes them (`\u{feff}` for a byte order mark, `\u{0}` for NUL, `\u{a0}` for a
/// no-break space), so that a token that looks right but is not can be told apart; cut
/// to [`MAX_QUOTED`] bytes, ending in `…`.
pub(super) fn quote(text: &str) -> Quoted {
    let mut q = Quoted::new();
    for c in text.chars() {
        // The character, or its escape: `\u{` and at most six hex digits.
        let mut one = heapless::String::<10>::new();
        if super::hints::HINTS && is_invisible(c) {
            let code = u32::from(c);
            let _ = one.push_str("\\u{");
            for shift in (0..6).rev() {
                let digit = (code >> (4 * shift)) & 0xF;
                if digit != 0 || shift == 0 || one.len() > 3 {
                    let _ = one.push(char::from_digit(digit, 16).unwrap_or('?'));
                }
            }
            let _ = one.push('}');
        } else {
            let _ = one.push(c);
        }
        if q.len() + one.len() > MAX_QUOTED - '…'.len_utf8() {
            // Room for the ellipsis is kept above, so this push cannot fail.
            let _ = q.push('…');
            break;
        }
        let _ = q.push_str(&one);
    }
    q
}

/// A number as a scale error keeps it: cut to [`MAX_NUMBER`] bytes, ending in `…` (a
/// number is ASCII: every byte is a character).
#[inline(never)]
pub(super) fn quote_number(text: &str) -> QuotedNumber {
    let mut q = QuotedNumber::new();
    if q.push_str(text).is_err() {
        let cut = MAX_NUMBER - '…'.len_utf8();
        let _ = q.push_str(text.get(..cut).unwrap_or(""));
        let _ = q.push('…');
    }
    q
}

/// Whether `c` is a control character or one that shows as nothing or as a plain space:
/// the C0 and C1 controls and DEL, the no-break, figure and other Unicode spaces, the soft
/// hyphen, the zero-width characters and direction marks, the line and paragraph
/// separators, the word joiner and the byte order mark. (A table of ranges, not
/// Unicode's: a chip keeps it in a few bytes of flash.)
fn is_invisible(c: char) -> bool {
    matches!(
        u32::from(c),
        0..=0x1F
            | 0x7F..=0xA0
            | 0xAD
            | 0x1680
            | 0x180E
            | 0x2000..=0x200F
            | 0x2028..=0x202F
            | 0x205F..=0x2064
            | 0x3000
            | 0xFEFF
    )
}

/// Whether a token can be a name ([`crate::scene::language`], "Names"): any token that is
/// not a brace, a keyword or a number. Real course files write `Sphere.060` and
/// `seg-your-fault.115`.
pub(super) fn is_name(s: &str) -> bool {
    !s.is_empty()
        && s != "{"
        && s != "}"
        && !super::schema::is_keyword(s)
        && crate::num::Decimal::parse(s).is_none()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_format_syntax() {
        // Names as real course files write them (Blender exports), and ours.
        for ok in [
            "a",
            "_x",
            "floor_2",
            "Z9",
            "Sphere.060",
            "seg-your-fault.115",
            "2a",
            "é",
        ] {
            assert!(is_name(ok), "{ok}");
        }
        // Braces, keywords and numbers are not names.
        for bad in [
            "",
            "{",
            "}",
            "plane",
            "camera",
            "background",
            "7",
            "-0.5",
            ".25",
            "1e3",
        ] {
            assert!(!is_name(bad), "{bad}");
        }
    }

    #[test]
    fn braces_split_from_words_and_comments_end_at_newline() {
        let mut lx = Lexer::new("plane floor{ # note {\n x}");
        let toks: [&str; 5] = core::array::from_fn(|_| lx.next_token().map_or("", |t| t.text));
        assert_eq!(toks, ["plane", "floor", "{", "x", "}"]);
        let mut lx = Lexer::new("a\n  bb");
        lx.next_token();
        assert_eq!(
            lx.next_token().map(|t| t.pos),
            Some(Pos { line: 2, column: 3 })
        );
    }

    /// The separators are C's `isspace` (the course's reader): the six ASCII ones, vertical
    /// tab and form feed among them; a no-break space is part of a word, as in C.
    #[test]
    fn tokens_are_separated_by_the_c_white_space() {
        let mut lx = Lexer::new("a\tb\x0Bc\x0Cd\re\u{a0}f g");
        let toks: [&str; 6] = core::array::from_fn(|_| lx.next_token().map_or("", |t| t.text));
        assert_eq!(toks, ["a", "b", "c", "d", "e\u{a0}f", "g"]);
        assert!(lx.next_token().is_none());
    }

    /// Columns count characters, not bytes; the end of the text is the end for good.
    #[test]
    fn columns_count_characters_and_the_end_stays_put() {
        let mut lx = Lexer::new("é x\na\u{a0}b c # note\n  ");
        let toks: [(&str, u32, u32); 3] = core::array::from_fn(|_| {
            lx.next_token()
                .map_or(("", 0, 0), |t| (t.text, t.pos.line, t.pos.column))
        });
        assert_eq!(toks, [("é", 1, 1), ("x", 1, 3), ("a\u{a0}b", 2, 1)]);
        assert_eq!(
            lx.next_token().map(|t| (t.text, t.pos.column)),
            Some(("c", 5))
        );
        assert!(lx.next_token().is_none());
        let end = lx.pos;
        assert_eq!(end, Pos { line: 3, column: 3 });
        assert!(lx.next_token().is_none());
        assert_eq!(lx.pos, end);
    }

    #[test]
    fn long_tokens_are_cut_in_messages() {
        let q = quote("abcdefghijklmnopqrstuvwxyz0123456789");
        assert!(q.ends_with('…'));
        assert!(q.len() <= MAX_QUOTED);
        // An escape is never cut in half: it is quoted whole or not at all.
        let q = quote("abcdefghijklmnopq\u{feff}xyz");
        assert_eq!(q.as_str(), "abcdefghijklmnopq…");
    }

    /// Control and invisible characters are quoted escaped; visible ones as they are.
    #[test]
    fn invisible_characters_are_quoted_escaped() {
        for (token, quoted) in [
            ("\u{feff}camera", "\\u{feff}camera"),
            ("a\0b", "a\\u{0}b"),
            ("x\u{a0}y", "x\\u{a0}y"),
            ("\u{7f}\u{85}\u{200b}", "\\u{7f}\\u{85}\\u{200b}"),
            ("\u{2028}", "\\u{2028}"),
            ("é→Ω", "é→Ω"),
            ("\u{1}", "\\u{1}"),
        ] {
            assert_eq!(quote(token).as_str(), quoted);
        }
    }

    /// A byte order mark is a character of its token, which starts a column.
    #[test]
    fn a_byte_order_mark_is_part_of_its_token() {
        let mut lx = Lexer::new("camera c\n\u{feff}x");
        assert_eq!(lx.next_token().map(|t| t.text), Some("camera"));
        assert_eq!(lx.next_token().map(|t| t.text), Some("c"));
        let t = lx.next_token().unwrap();
        assert_eq!((t.text, t.pos), ("\u{feff}x", Pos { line: 2, column: 1 }));
    }
}

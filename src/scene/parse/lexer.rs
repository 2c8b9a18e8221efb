//! The lexer: `{`, `}` and runs of other non-space characters, with positions; `#`
//! comments run to the end of the line.

use super::error::{MAX_QUOTED, Pos, Quoted};

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

    fn advance(&mut self, c: char) {
        // `c` is the first char of `rest`: the cut is on a char boundary (`get` keeps the
        // impossible panic path, and its formatting code, out of the firmware).
        self.rest = self.rest.get(c.len_utf8()..).unwrap_or("");
        if c == '\n' {
            self.pos.line = self.pos.line.saturating_add(1);
            self.pos.column = 1;
        } else {
            self.pos.column = self.pos.column.saturating_add(1);
        }
    }

    pub(super) fn next_token(&mut self) -> Option<Token<'a>> {
        // Skip white space and comments.
        loop {
            let c = self.rest.chars().next()?;
            if c == '#' {
                while let Some(c) = self.rest.chars().next() {
                    if c == '\n' {
                        break;
                    }
                    self.advance(c);
                }
            } else if c.is_whitespace() {
                self.advance(c);
            } else {
                break;
            }
        }
        let start = self.rest;
        let pos = self.pos;
        let first = start.chars().next()?;
        self.advance(first);
        if first != '{' && first != '}' {
            while let Some(c) = self.rest.chars().next() {
                if c.is_whitespace() || c == '{' || c == '}' || c == '#' {
                    break;
                }
                self.advance(c);
            }
        }
        let len = start.len() - self.rest.len();
        Some(Token {
            text: start.get(..len).unwrap_or(""),
            pos,
        })
    }
}

pub(super) fn quote(text: &str) -> Quoted {
    let mut q = Quoted::new();
    for c in text.chars() {
        if q.len() + c.len_utf8() > MAX_QUOTED - '…'.len_utf8() {
            // Room for the ellipsis is kept above, so this push cannot fail.
            let _ = q.push('…');
            break;
        }
        let _ = q.push(c);
    }
    q
}

/// Whether a token can be a name (`scene-format.md`, "Lexical rules"): any token that is
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

    #[test]
    fn long_tokens_are_cut_in_messages() {
        let q = quote("abcdefghijklmnopqrstuvwxyz0123456789");
        assert!(q.ends_with('…'));
        assert!(q.len() <= MAX_QUOTED);
    }
}

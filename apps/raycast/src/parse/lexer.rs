//! The tokenizer: scene text to tokens, each with its 1-based line and column.
//!
//! ```text
//! token   = "{" | "}" | "[" | "]" | number | word
//! number  = [+-]? ( digits [ "." digits? ] | "." digits ) ( [eE] [+-]? digits )?
//! word    = any other run of characters up to white space, a bracket or "#"
//! comment = "#" … end of line
//! ```
//!
//! Brackets are tokens of their own even without surrounding white space, so
//! `[-1 0 0]` and `Sphere{` read as expected. A number that overflows (`1e999`)
//! is still a number token; the parser rejects it as not finite.

/// A 1-based position in the scene text (columns count characters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Pos {
    pub(super) line: usize,
    pub(super) column: usize,
}

impl std::fmt::Display for Pos {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// What a token is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Kind {
    /// `{`
    Open,
    /// `}`
    Close,
    /// `[`
    OpenBracket,
    /// `]`
    CloseBracket,
    /// A decimal number (possibly infinite after overflow).
    Number(f64),
    /// Anything else: keywords, values such as `true`, file paths.
    Word,
}

/// One token: its kind, its text in the source and where it starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Token<'a> {
    pub(super) kind: Kind,
    pub(super) text: &'a str,
    pub(super) pos: Pos,
}

/// The tokens of `text` and the position just after its last character (where
/// a premature end of file is reported).
pub(super) fn tokenize(text: &str) -> (Vec<Token<'_>>, Pos) {
    let mut tokens = Vec::new();
    let mut pos = Pos { line: 1, column: 1 };
    let mut chars = text.char_indices().peekable();
    while let Some(&(start, c)) = chars.peek() {
        let here = pos;
        if c == '\n' {
            chars.next();
            pos = Pos {
                line: pos.line + 1,
                column: 1,
            };
        } else if c.is_whitespace() {
            chars.next();
            pos.column += 1;
        } else if c == '#' {
            while chars.next_if(|&(_, c)| c != '\n').is_some() {
                pos.column += 1;
            }
        } else if let Some(kind) = bracket(c) {
            chars.next();
            pos.column += 1;
            tokens.push(Token {
                kind,
                text: &text[start..start + c.len_utf8()],
                pos: here,
            });
        } else {
            let mut end = start;
            while let Some((i, c)) =
                chars.next_if(|&(_, c)| !c.is_whitespace() && c != '#' && bracket(c).is_none())
            {
                end = i + c.len_utf8();
                pos.column += 1;
            }
            let word = &text[start..end];
            let kind = if is_number(word) {
                word.parse().map_or(Kind::Word, Kind::Number)
            } else {
                Kind::Word
            };
            tokens.push(Token {
                kind,
                text: word,
                pos: here,
            });
        }
    }
    (tokens, pos)
}

/// The token kind of a bracket character.
fn bracket(c: char) -> Option<Kind> {
    match c {
        '{' => Some(Kind::Open),
        '}' => Some(Kind::Close),
        '[' => Some(Kind::OpenBracket),
        ']' => Some(Kind::CloseBracket),
        _ => None,
    }
}

/// Whether `word` is a decimal number of the grammar above (no `inf`, `nan`,
/// hexadecimal or digit separators, which `f64::from_str` would partly accept).
pub(super) fn is_number(word: &str) -> bool {
    let b = word.as_bytes();
    let mut i = 0;
    if matches!(b.first(), Some(b'+' | b'-')) {
        i += 1;
    }
    let digits = |i: &mut usize| {
        let start = *i;
        while b.get(*i).is_some_and(u8::is_ascii_digit) {
            *i += 1;
        }
        *i - start
    };
    let mut mantissa = digits(&mut i);
    if b.get(i) == Some(&b'.') {
        i += 1;
        mantissa += digits(&mut i);
    }
    if mantissa == 0 {
        return false;
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        i += 1;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        if digits(&mut i) == 0 {
            return false;
        }
    }
    i == b.len()
}

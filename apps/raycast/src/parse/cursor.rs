//! The token cursor: walks the tokens, reads typed values and builds the
//! errors that point at the offending token.
//!
//! Every block of the format has the same shape, `Name { key value… key value… }`;
//! [`Cursor::open`], [`Cursor::key`] and [`Cursor::field`] read it, and the
//! value readers ([`Cursor::number`], [`Cursor::vector`], [`Cursor::color`],
//! [`Cursor::reflectance`],
//! [`Cursor::whole`], …) say which key they were reading when they fail.

use std::path::Path;

use revolve::nalgebra::{Point3, Vector3};

use super::keywords::{BLOCK_KEYWORDS, OBJECTS};
use super::lexer::{Kind, Pos, Token, tokenize};
use super::suggest::did_you_mean;
use super::{ParseError, ParseWarning};

/// Results of the parser.
pub(super) type Result<T> = std::result::Result<T, ParseError>;

/// The largest colour component of a light, an emission or the background.
/// With reflectances at most 1, every radiance the renderer computes stays
/// finite: it sums at most a few thousand terms, each this bound times
/// factors whose product stays under 2¹⁰⁰ (an upper bound on the whole ray tree).
pub(super) const MAX_RADIANCE: f64 = 1e100;

/// `x` for a message: plain decimals, or the exponent form for magnitudes
/// that would print as a long run of zeros (below 1e-4 or from 1e16 on).
pub(super) fn shown(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && !(1e-4..1e16).contains(&a) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The tokens of one scene file and the position of the next one.
pub(super) struct Cursor<'a> {
    tokens: Vec<Token<'a>>,
    next: usize,
    end: Pos,
    file: &'a Path,
    /// The warnings raised so far, in file order.
    warnings: Vec<ParseWarning>,
}

impl<'a> Cursor<'a> {
    /// A cursor at the first token of `text`, which `file` names in errors.
    pub(super) fn new(text: &'a str, file: &'a Path) -> Self {
        let (tokens, end) = tokenize(text);
        Cursor {
            tokens,
            next: 0,
            end,
            file,
            warnings: Vec::new(),
        }
    }

    /// Records a warning at `pos` in this file.
    pub(super) fn warn(&mut self, pos: Pos, message: impl Into<String>) {
        self.warnings.push(ParseWarning {
            file: self.file.to_path_buf(),
            line: pos.line,
            column: pos.column,
            message: message.into(),
        });
    }

    /// The warnings raised so far, in file order, leaving none.
    pub(super) fn take_warnings(&mut self) -> Vec<ParseWarning> {
        std::mem::take(&mut self.warnings)
    }

    /// An error at `pos` in this file.
    pub(super) fn error(&self, pos: Pos, message: impl Into<String>) -> ParseError {
        ParseError {
            file: self.file.to_path_buf(),
            line: pos.line,
            column: pos.column,
            message: message.into(),
        }
    }

    /// The next token, without consuming it.
    pub(super) fn peek(&self) -> Option<Token<'a>> {
        self.tokens.get(self.next).copied()
    }

    /// Consumes and returns the next token.
    pub(super) fn bump(&mut self) -> Option<Token<'a>> {
        let token = self.peek();
        if token.is_some() {
            self.next += 1;
        }
        token
    }

    /// Where the next token starts (the end of the file after the last one).
    pub(super) fn here(&self) -> Pos {
        self.peek().map_or(self.end, |t| t.pos)
    }

    /// Where the last consumed token starts.
    pub(super) fn previous(&self) -> Pos {
        self.next
            .checked_sub(1)
            .and_then(|i| self.tokens.get(i))
            .map_or(self.end, |t| t.pos)
    }

    /// `'text'` of a token, or `end of file`.
    pub(super) fn describe(token: Option<Token<'_>>) -> String {
        token.map_or_else(|| "end of file".to_string(), |t| format!("'{}'", t.text))
    }

    /// "expected `what`, found …" at the next token, without consuming it.
    pub(super) fn expected(&self, what: &str) -> ParseError {
        self.error(
            self.here(),
            format!("expected {what}, found {}", Self::describe(self.peek())),
        )
    }

    /// Reads the `{` that opens the block `name`; returns its position.
    pub(super) fn open(&mut self, name: &str) -> Result<Pos> {
        match self.peek() {
            Some(t) if t.kind == Kind::Open => {
                self.next += 1;
                Ok(t.pos)
            }
            _ => Err(self.expected(&format!("'{{' after {name}"))),
        }
    }

    /// The error for a block opened at `open` that the file never closes.
    pub(super) fn unclosed(&self, open: Pos) -> ParseError {
        self.error(
            self.end,
            format!("missing '}}' (the block opened at {open})"),
        )
    }

    /// The next key of the block `block` opened at `open`: a word, or `None`
    /// after consuming the closing `}`.
    pub(super) fn key(&mut self, block: &str, open: Pos) -> Result<Option<Token<'a>>> {
        match self.peek() {
            None => Err(self.unclosed(open)),
            Some(t) if t.kind == Kind::Close => {
                self.next += 1;
                Ok(None)
            }
            Some(t) if t.kind == Kind::Word => {
                self.next += 1;
                Ok(Some(t))
            }
            Some(_) => Err(self.expected(&format!("a keyword or '}}' in {block}"))),
        }
    }

    /// Reads the `}` closing the block `block` opened at `open`.
    pub(super) fn close(&mut self, block: &str, open: Pos) -> Result<()> {
        match self.peek() {
            None => Err(self.unclosed(open)),
            Some(t) if t.kind == Kind::Close => {
                self.next += 1;
                Ok(())
            }
            Some(_) => Err(self.expected(&format!("'}}' closing {block}"))),
        }
    }

    /// The error for a keyword `key` that `context` does not know; suggests a
    /// near spelling from `known`, or a missing `}` when `key` opens a block
    /// that belongs elsewhere.
    pub(super) fn unknown(&self, key: Token<'_>, context: &str, known: &[&str]) -> ParseError {
        let mut message = format!("unknown keyword '{}' in {context}", key.text);
        if let Some(near) = did_you_mean(key.text, known) {
            message += &format!(" (did you mean '{near}'?)");
        } else if (BLOCK_KEYWORDS.contains(&key.text) || OBJECTS.contains(&key.text))
            && self.peek().is_some_and(|t| t.kind == Kind::Open)
        {
            message += &format!(" ({} does not belong here; is a '}}' missing?)", key.text);
        } else {
            message += &format!("; expected one of {}", known.join(", "));
        }
        self.error(key.pos, message)
    }

    /// Reads the value of `key` into `slot` with `read`; a key given twice in
    /// `block` is an error.
    pub(super) fn field<T>(
        &mut self,
        slot: &mut Option<T>,
        key: Token<'a>,
        block: &str,
        read: impl FnOnce(&mut Self, &str) -> Result<T>,
    ) -> Result<()> {
        if slot.is_some() {
            return Err(self.error(key.pos, format!("duplicate '{}' in {block}", key.text)));
        }
        *slot = Some(read(self, key.text)?);
        Ok(())
    }

    /// The value of a required key, or an error at the block's closing `}`.
    pub(super) fn required<T>(&self, slot: Option<T>, key: &str, block: &str) -> Result<T> {
        slot.ok_or_else(|| self.error(self.previous(), format!("{block} needs '{key}'")))
    }

    /// A finite number, the value of `what`.
    pub(super) fn number(&mut self, what: &str) -> Result<f64> {
        Ok(self.number_at(what)?.0)
    }

    /// A finite number, the value of `what`, and where it is.
    pub(super) fn number_at(&mut self, what: &str) -> Result<(f64, Pos)> {
        match self.peek() {
            Some(Token {
                kind: Kind::Number(x),
                text,
                pos,
            }) => {
                if !x.is_finite() {
                    return Err(self.error(
                        pos,
                        format!("the number '{text}' for '{what}' is not finite"),
                    ));
                }
                self.next += 1;
                Ok((x, pos))
            }
            _ => Err(self.expected(&format!("a number for '{what}'"))),
        }
    }

    /// A number `> 0`.
    pub(super) fn positive(&mut self, what: &str) -> Result<f64> {
        let (x, pos) = self.number_at(what)?;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(self.error(
                pos,
                format!("'{what}' must be positive, found {}", shown(x)),
            ))
        }
    }

    /// A number `≥ 0`.
    pub(super) fn non_negative(&mut self, what: &str) -> Result<f64> {
        let (x, pos) = self.number_at(what)?;
        if x >= 0.0 {
            Ok(x)
        } else {
            Err(self.error(
                pos,
                format!("'{what}' must not be negative, found {}", shown(x)),
            ))
        }
    }

    /// Three numbers.
    pub(super) fn vector(&mut self, what: &str) -> Result<Vector3<f64>> {
        Ok(Vector3::new(
            self.number(what)?,
            self.number(what)?,
            self.number(what)?,
        ))
    }

    /// Three numbers that are not all zero (a direction or a normal).
    pub(super) fn direction(&mut self, what: &str) -> Result<Vector3<f64>> {
        let pos = self.here();
        let v = self.vector(what)?;
        if v == Vector3::zeros() {
            return Err(self.error(pos, format!("'{what}' must not be the zero vector")));
        }
        Ok(v)
    }

    /// Three numbers as a point.
    pub(super) fn point(&mut self, what: &str) -> Result<Point3<f64>> {
        Ok(Point3::from(self.vector(what)?))
    }

    /// A number in `[0, max]`; `kind` names what `max` bounds in the error.
    fn bounded(&mut self, what: &str, max: f64, kind: &str) -> Result<f64> {
        let at = self.here();
        let x = self.non_negative(what)?;
        if x > max {
            return Err(self.error(
                at,
                format!(
                    "'{what}' is {kind}, at most {}, found {}",
                    shown(max),
                    shown(x)
                ),
            ));
        }
        Ok(x)
    }

    /// Three numbers in `[0, MAX_RADIANCE]`: the colour of a light, an
    /// emission or the background.
    pub(super) fn color(&mut self, what: &str) -> Result<Vector3<f64>> {
        let kind = "a radiance";
        Ok(Vector3::new(
            self.bounded(what, MAX_RADIANCE, kind)?,
            self.bounded(what, MAX_RADIANCE, kind)?,
            self.bounded(what, MAX_RADIANCE, kind)?,
        ))
    }

    /// Three numbers in `[0, 1]`: the fraction of light a surface reflects
    /// or lets through.
    pub(super) fn reflectance(&mut self, what: &str) -> Result<Vector3<f64>> {
        let kind = "a fraction of the light";
        Ok(Vector3::new(
            self.bounded(what, 1.0, kind)?,
            self.bounded(what, 1.0, kind)?,
            self.bounded(what, 1.0, kind)?,
        ))
    }

    /// Three numbers `≥ 0` (absorption coefficients per unit length).
    pub(super) fn rates(&mut self, what: &str) -> Result<Vector3<f64>> {
        Ok(Vector3::new(
            self.non_negative(what)?,
            self.non_negative(what)?,
            self.non_negative(what)?,
        ))
    }

    /// A whole number `≥ min` that fits a `u32`, and where it is.
    pub(super) fn whole(&mut self, what: &str, min: u32) -> Result<(u32, Pos)> {
        let kind = if min == 0 {
            "a whole number"
        } else {
            "a positive whole number"
        };
        match self.peek() {
            Some(Token {
                kind: Kind::Number(x),
                pos,
                ..
            }) if x.fract() == 0.0 && x >= f64::from(min) && x <= f64::from(u32::MAX) => {
                self.next += 1;
                Ok((x as u32, pos))
            }
            _ => Err(self.expected(&format!("{kind} for '{what}'"))),
        }
    }

    /// Any non-bracket token (a file path or a named value).
    pub(super) fn word(&mut self, what: &str) -> Result<Token<'a>> {
        match self.peek() {
            Some(t) if matches!(t.kind, Kind::Word | Kind::Number(_)) => {
                self.next += 1;
                Ok(t)
            }
            _ => Err(self.expected(&format!("a value for '{what}'"))),
        }
    }

    /// One of the named values `choices` for `what`.
    pub(super) fn choice<T: Copy>(&mut self, what: &str, choices: &[(&str, T)]) -> Result<T> {
        let found = self
            .peek()
            .filter(|t| t.kind == Kind::Word)
            .and_then(|t| choices.iter().find(|(name, _)| *name == t.text));
        match found {
            Some(&(_, value)) => {
                self.next += 1;
                Ok(value)
            }
            None => {
                let listed = choices
                    .iter()
                    .map(|(name, _)| format!("'{name}'"))
                    .collect::<Vec<_>>()
                    .join(" or ");
                Err(self.expected(&format!("{listed} for '{what}'")))
            }
        }
    }

    /// Reads `[`, or returns false (consuming nothing) when the next token is
    /// not one.
    pub(super) fn open_bracket(&mut self) -> bool {
        if self.peek().is_some_and(|t| t.kind == Kind::OpenBracket) {
            self.next += 1;
            true
        } else {
            false
        }
    }

    /// Reads the `]` closing a bracket opened at `open`.
    pub(super) fn close_bracket(&mut self, open: Pos) -> Result<()> {
        match self.peek() {
            Some(t) if t.kind == Kind::CloseBracket => {
                self.next += 1;
                Ok(())
            }
            _ => Err(self.expected(&format!("']' closing the '[' at {open}"))),
        }
    }
}

//! The counts that open a list block (`numObjects`, `numLights`,
//! `numMaterials`): optional, but when given they must match the entries.

use super::cursor::{Cursor, Result};
use super::lexer::{Pos, Token};

/// A list block's declared count, checked against what the block holds.
pub(super) struct Counter {
    /// The count's keyword, e.g. `numObjects`.
    key: &'static str,
    /// What holds the entries, e.g. `the group`.
    holder: &'static str,
    /// One entry, e.g. `object`.
    noun: &'static str,
    /// The declared count and where its value is.
    given: Option<(u32, Pos)>,
}

impl Counter {
    /// A counter for `key` in `holder`, whose entries are `noun`s.
    pub(super) fn new(key: &'static str, holder: &'static str, noun: &'static str) -> Self {
        Counter {
            key,
            holder,
            noun,
            given: None,
        }
    }

    /// Reads the count's value after its keyword `key`.
    pub(super) fn read(&mut self, c: &mut Cursor<'_>, key: Token<'_>) -> Result<()> {
        if self.given.is_some() {
            return Err(c.error(key.pos, format!("duplicate '{}'", self.key)));
        }
        self.given = Some(c.whole(self.key, 0)?);
        Ok(())
    }

    /// Checks the declared count (if any) against the `found` entries; the
    /// error points at the count's value.
    pub(super) fn check(&self, c: &Cursor<'_>, found: usize) -> Result<()> {
        match self.given {
            Some((n, pos)) if n as usize != found => Err(c.error(
                pos,
                format!(
                    "{} is {n} but {} holds {found} {}{}",
                    self.key,
                    self.holder,
                    self.noun,
                    if found == 1 { "" } else { "s" }
                ),
            )),
            _ => Ok(()),
        }
    }
}

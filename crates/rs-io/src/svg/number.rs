//! The SVG number grammar, one tokenizer for every attribute that holds numbers: path data,
//! transform lists, `points` and lengths.
//!
//! A number is `[+-]? (digits ("." digits?)? | "." digits) ([eE] [+-]? digits)?`. A number ends
//! where the grammar stops, so no separator is needed before a sign or before a second point:
//! `0-5` is `0, -5` and `.5.5` is `0.5, 0.5`. An `e` not followed by exponent digits is not
//! part of the number (`1em` is `1` then `em`). Between numbers: white space with at most one
//! comma (`comma-wsp`).

/// A malformed token: its byte position in the scanned text and what is wrong there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LexError {
    /// Byte offset of the token in the scanned text.
    pub(crate) position: usize,
    /// What is wrong.
    pub(crate) kind: LexErrorKind,
}

/// What is wrong with a token.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LexErrorKind {
    /// No number where one is expected (or the text ends there).
    NotANumber,
    /// A number beyond the `f64` range.
    OutOfRange,
    /// A comma at the end of a list.
    DanglingComma,
}

impl LexErrorKind {
    /// The kind as a short phrase, for messages that give the position apart.
    pub(crate) fn message(self) -> &'static str {
        match self {
            Self::NotANumber => "expected a number",
            Self::OutOfRange => "number out of range",
            Self::DanglingComma => "a comma with no number after it",
        }
    }
}

/// A cursor over the bytes of an attribute value. Every method leaves the cursor on a byte
/// boundary of the original `&str` (it only steps over ASCII bytes).
pub(crate) struct Lexer<'a> {
    text: &'a str,
    pos: usize,
}

impl<'a> Lexer<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        Self { text, pos: 0 }
    }

    /// The byte offset of the cursor.
    pub(crate) fn position(&self) -> usize {
        self.pos
    }

    /// The byte under the cursor, if any.
    pub(crate) fn peek(&self) -> Option<u8> {
        self.text.as_bytes().get(self.pos).copied()
    }

    /// Steps over one byte; the caller has seen it is ASCII with [`Lexer::peek`].
    pub(crate) fn bump(&mut self) {
        debug_assert!(self.peek().is_some_and(|b| b.is_ascii()));
        self.pos += 1;
    }

    /// The text from the cursor on.
    pub(crate) fn rest(&self) -> &'a str {
        self.text.get(self.pos..).unwrap_or("")
    }

    /// True once every byte is consumed.
    pub(crate) fn at_end(&self) -> bool {
        self.pos >= self.text.len()
    }

    /// Skips SVG white space (space, tab, line feed, carriage return, form feed).
    pub(crate) fn skip_whitespace(&mut self) {
        while self
            .peek()
            .is_some_and(|b| matches!(b, b' ' | b'\t' | b'\n' | b'\r' | b'\x0c'))
        {
            self.pos += 1;
        }
    }

    /// Skips white space with at most one comma (`comma-wsp`, or nothing); true if a comma
    /// was skipped.
    pub(crate) fn skip_separators(&mut self) -> bool {
        self.skip_whitespace();
        let comma = self.peek() == Some(b',');
        if comma {
            self.pos += 1;
            self.skip_whitespace();
        }
        comma
    }

    /// The token under the cursor, for messages: up to the next separator or parenthesis,
    /// and at least one character unless the text ends at the cursor.
    pub(crate) fn token(&self) -> &'a str {
        let rest = self.rest();
        let ends = |c: char| c.is_whitespace() || matches!(c, ',' | '(' | ')');
        let end = match rest.chars().next() {
            None => 0,
            Some(c) if ends(c) => c.len_utf8(),
            Some(_) => rest.find(ends).unwrap_or(rest.len()),
        };
        &rest[..end]
    }

    /// A number at the cursor (no separators skipped), finite.
    ///
    /// # Errors
    /// At the cursor's position: no number there, or one beyond the `f64` range.
    pub(crate) fn number(&mut self) -> Result<f64, LexError> {
        let b = self.text.as_bytes();
        let start = self.pos;
        let digits_from = |mut i: usize| {
            while b.get(i).is_some_and(u8::is_ascii_digit) {
                i += 1;
            }
            i
        };
        let mut i = start;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let int_end = digits_from(i);
        let mut has_digits = int_end > i;
        i = int_end;
        if b.get(i) == Some(&b'.') {
            let frac_end = digits_from(i + 1);
            has_digits |= frac_end > i + 1;
            i = frac_end;
        }
        if !has_digits {
            return Err(LexError {
                position: start,
                kind: LexErrorKind::NotANumber,
            });
        }
        if matches!(b.get(i), Some(b'e' | b'E')) {
            let mut j = i + 1;
            if matches!(b.get(j), Some(b'+' | b'-')) {
                j += 1;
            }
            let exp_end = digits_from(j);
            if exp_end > j {
                i = exp_end;
            }
        }
        // `start..i` holds ASCII bytes only, so it is a valid `&str` slice of the grammar
        // above, which Rust's float syntax includes.
        let value = self
            .text
            .get(start..i)
            .and_then(|s| s.parse::<f64>().ok())
            .ok_or(LexError {
                position: start,
                kind: LexErrorKind::NotANumber,
            })?;
        if !value.is_finite() {
            return Err(LexError {
                position: start,
                kind: LexErrorKind::OutOfRange,
            });
        }
        self.pos = i;
        Ok(value)
    }

    /// Numbers separated by `comma-wsp` or by nothing where the grammar allows (`1-2`),
    /// up to the end of the text or a byte for which `stop` is true (not consumed). White
    /// space around the list is skipped; a comma must sit between two numbers, and a letter
    /// right after a number makes the whole token an error (`2px` is not a number).
    ///
    /// # Errors
    /// The first token that is not a number, or a comma with no number after it.
    pub(crate) fn number_list(&mut self, stop: impl Fn(u8) -> bool) -> Result<Vec<f64>, LexError> {
        let mut values = Vec::new();
        self.skip_whitespace();
        let ended = |l: &Self| l.peek().is_none_or(&stop);
        if ended(self) {
            return Ok(values);
        }
        loop {
            let start = self.pos;
            values.push(self.number()?);
            // A letter right after a number (a unit, say) makes the whole token garbage.
            if self.peek().is_some_and(|b| b.is_ascii_alphabetic()) {
                return Err(LexError {
                    position: start,
                    kind: LexErrorKind::NotANumber,
                });
            }
            let comma = self.skip_separators();
            if ended(self) {
                if comma {
                    return Err(LexError {
                        position: self.pos,
                        kind: LexErrorKind::DanglingComma,
                    });
                }
                return Ok(values);
            }
        }
    }
}

/// The numbers of a whole attribute value (`points`, say); `what` names it in errors.
///
/// # Errors
/// `what: "token" is not a number` (one line).
pub(crate) fn number_list(text: &str, what: &str) -> Result<Vec<f64>, String> {
    let mut lexer = Lexer::new(text);
    lexer
        .number_list(|_| false)
        .map_err(|e| describe(text, what, e))
}

/// A lexer on `text` with its cursor at `position` (for quoting the token there).
fn lexer_at(text: &str, position: usize) -> Lexer<'_> {
    Lexer {
        text,
        pos: position.min(text.len()),
    }
}

/// The one-line message of `e` in `text`, quoting the token at its position.
pub(crate) fn describe(text: &str, what: &str, e: LexError) -> String {
    let token = lexer_at(text, e.position).token();
    match e.kind {
        LexErrorKind::NotANumber if token.is_empty() => {
            format!("{what}: the text ends where a number is expected")
        }
        LexErrorKind::NotANumber => format!("{what}: {token:?} is not a number"),
        LexErrorKind::OutOfRange => format!("{what}: {token:?} is out of range"),
        LexErrorKind::DanglingComma => {
            format!("{what}: {} (byte {})", e.kind.message(), e.position)
        }
    }
}

/// A length in user units: one number, optionally followed by `px`, with white space around;
/// `None` for anything else (other units, percentages, garbage).
pub(crate) fn user_length(text: &str) -> Option<f64> {
    let mut lexer = Lexer::new(text);
    lexer.skip_whitespace();
    let value = lexer.number().ok()?;
    let rest = lexer.rest().trim_end_matches(is_whitespace);
    (rest.is_empty() || rest == "px").then_some(value)
}

fn is_whitespace(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\n' | '\r' | '\x0c')
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbers(text: &str) -> Vec<f64> {
        number_list(text, "test").unwrap()
    }

    #[test]
    fn numbers_end_where_the_grammar_stops() {
        assert_eq!(numbers("0-1036.36"), [0.0, -1036.36]);
        assert_eq!(numbers("1-1"), [1.0, -1.0]);
        assert_eq!(numbers(".5.5"), [0.5, 0.5]);
        assert_eq!(numbers("90 .5.5"), [90.0, 0.5, 0.5]);
        assert_eq!(numbers("1 0 0 1 0-5"), [1.0, 0.0, 0.0, 1.0, 0.0, -5.0]);
        assert_eq!(numbers("1e-3,1E+2 2e3"), [1e-3, 100.0, 2000.0]);
        assert_eq!(numbers("+.5-.5e1 5."), [0.5, -5.0, 5.0]);
        assert_eq!(numbers(" 1 ,\t2\n"), [1.0, 2.0]);
        assert_eq!(numbers("1+2"), [1.0, 2.0]);
        assert!(numbers("  ").is_empty());
    }

    #[test]
    fn garbage_is_refused_with_one_line() {
        for (text, message) in [
            ("1 x", r#"test: "x" is not a number"#),
            ("1,,2", r#"test: "," is not a number"#),
            ("1 2,", "test: a comma with no number after it (byte 4)"),
            (", 1", r#"test: "," is not a number"#),
            ("1e", r#"test: "1e" is not a number"#),
            ("1 2px", r#"test: "2px" is not a number"#),
            ("- 1", r#"test: "-" is not a number"#),
            ("1..", r#"test: "." is not a number"#),
            ("1e999", r#"test: "1e999" is out of range"#),
            ("NaN", r#"test: "NaN" is not a number"#),
            ("inf", r#"test: "inf" is not a number"#),
        ] {
            let e = number_list(text, "test").unwrap_err();
            assert_eq!(e, message, "{text}");
        }
    }

    #[test]
    fn lengths_are_numbers_in_user_units() {
        assert_eq!(user_length("16"), Some(16.0));
        assert_eq!(user_length(" 16px "), Some(16.0));
        assert_eq!(user_length("1e1"), Some(10.0));
        assert_eq!(user_length(".5"), Some(0.5));
        for bad in ["", "px", "1em", "10%", "1mm", "1 2", "1e", "x"] {
            assert_eq!(user_length(bad), None, "{bad}");
        }
    }
}

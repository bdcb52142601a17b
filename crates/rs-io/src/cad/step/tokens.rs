//! The ISO 10303-21 lexer: bytes to tokens, each with its 1-based line.
//!
//! Every token is produced in time linear in its length; comments and strings must be closed
//! before the end of the file; numbers must be finite. The lexer never looks back, so the whole
//! scan is one pass over the bytes.

/// One Part 21 token.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Token {
    /// `#123`: an entity instance name (a definition on the left of `=`, a reference elsewhere).
    Instance(u64),
    /// A standard (`CIRCLE`) or user-defined (`!MY_TYPE`) keyword, also `ISO-10303-21`,
    /// `END-ISO-10303-21`, `HEADER`, `DATA`, `ENDSEC`.
    Keyword(String),
    /// An integer or real number, always finite.
    Number(f64),
    /// `'text'` with `''` unescaped (other control directives are kept as written).
    Str(String),
    /// `.T.`, `.UNSPECIFIED.`: the name between the dots.
    Enum(String),
    /// `"0A1"`: a binary; its contents are not needed.
    Binary,
    /// `(`
    Open,
    /// `)`
    Close,
    /// `,`
    Comma,
    /// `;`
    Semicolon,
    /// `=`
    Equals,
    /// `$`: the value is not given.
    Dollar,
    /// `*`: the value is derived from the supertype.
    Star,
}

/// A lexer over the bytes of a file.
pub(crate) struct Lexer<'a> {
    text: &'a [u8],
    at: usize,
    line: u32,
}

/// A lexical error: the line and what is wrong.
pub(crate) type LexError = (u32, String);

impl<'a> Lexer<'a> {
    /// A lexer at the start of `text`.
    pub(crate) fn new(text: &'a [u8]) -> Self {
        Self {
            text,
            at: 0,
            line: 1,
        }
    }

    /// The line of the next unread byte.
    pub(crate) fn line(&self) -> u32 {
        self.line
    }

    fn peek(&self) -> Option<u8> {
        self.text.get(self.at).copied()
    }

    fn bump(&mut self) -> Option<u8> {
        let c = self.peek()?;
        self.at += 1;
        if c == b'\n' {
            self.line = self.line.saturating_add(1);
        }
        Some(c)
    }

    /// Skips white space and comments; an unclosed comment is an error.
    fn skip_blank(&mut self) -> Result<(), LexError> {
        loop {
            match self.peek() {
                Some(c) if c.is_ascii_whitespace() => {
                    self.bump();
                }
                Some(b'/') if self.text.get(self.at + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.at += 2;
                    loop {
                        match self.bump() {
                            None => return Err((start, "unterminated comment".into())),
                            Some(b'*') if self.peek() == Some(b'/') => {
                                self.at += 1;
                                break;
                            }
                            Some(_) => {}
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    /// The next token with its line, `None` at the end of the bytes.
    pub(crate) fn next_token(&mut self) -> Result<Option<(Token, u32)>, LexError> {
        self.skip_blank()?;
        let line = self.line;
        let Some(c) = self.peek() else {
            return Ok(None);
        };
        let token = match c {
            b'(' => self.single(Token::Open),
            b')' => self.single(Token::Close),
            b',' => self.single(Token::Comma),
            b';' => self.single(Token::Semicolon),
            b'=' => self.single(Token::Equals),
            b'$' => self.single(Token::Dollar),
            b'*' => self.single(Token::Star),
            b'#' => self.instance()?,
            b'\'' => self.string()?,
            b'"' => self.binary()?,
            b'.' if self
                .text
                .get(self.at + 1)
                .is_some_and(u8::is_ascii_alphabetic) =>
            {
                self.enumeration()?
            }
            b'0'..=b'9' | b'+' | b'-' | b'.' => self.number()?,
            b'!' | b'A'..=b'Z' | b'a'..=b'z' | b'_' => self.keyword(),
            _ => {
                return Err((
                    line,
                    format!(
                        "unexpected character {:?}",
                        char::from(c).escape_default().to_string()
                    ),
                ));
            }
        };
        Ok(Some((token, line)))
    }

    fn single(&mut self, t: Token) -> Token {
        self.at += 1;
        t
    }

    fn take_while(&mut self, f: impl Fn(u8) -> bool) -> &'a [u8] {
        let start = self.at;
        while self.peek().is_some_and(&f) {
            self.at += 1;
        }
        &self.text[start..self.at]
    }

    fn instance(&mut self) -> Result<Token, LexError> {
        self.at += 1;
        let digits = self.take_while(|c| c.is_ascii_digit());
        let n = std::str::from_utf8(digits)
            .ok()
            .and_then(|s| s.parse::<u64>().ok())
            .ok_or_else(|| {
                (
                    self.line,
                    "'#' not followed by an instance number".to_string(),
                )
            })?;
        Ok(Token::Instance(n))
    }

    fn keyword(&mut self) -> Token {
        let start = self.at;
        self.at += 1;
        // '-' only occurs inside the keywords ISO-10303-21 and END-ISO-10303-21.
        self.take_while(|c| c.is_ascii_alphanumeric() || c == b'_' || c == b'-');
        Token::Keyword(String::from_utf8_lossy(&self.text[start..self.at]).to_ascii_uppercase())
    }

    fn string(&mut self) -> Result<Token, LexError> {
        let start = self.line;
        self.at += 1;
        let mut out = Vec::new();
        loop {
            match self.bump() {
                None => return Err((start, "unterminated string".into())),
                Some(b'\'') if self.peek() == Some(b'\'') => {
                    self.at += 1;
                    out.push(b'\'');
                }
                Some(b'\'') => break,
                // Part 21 strings are printable; a line break inside one is the writer's
                // wrapping, not content.
                Some(b'\n' | b'\r') => {}
                Some(c) => out.push(c),
            }
        }
        Ok(Token::Str(String::from_utf8_lossy(&out).into_owned()))
    }

    fn binary(&mut self) -> Result<Token, LexError> {
        let start = self.line;
        self.at += 1;
        self.take_while(|c| c.is_ascii_hexdigit());
        if self.bump() != Some(b'"') {
            return Err((start, "unterminated binary".into()));
        }
        Ok(Token::Binary)
    }

    fn enumeration(&mut self) -> Result<Token, LexError> {
        self.at += 1;
        let name = self.take_while(|c| c.is_ascii_alphanumeric() || c == b'_');
        let name = String::from_utf8_lossy(name).to_ascii_uppercase();
        if self.bump() != Some(b'.') {
            return Err((self.line, format!("enumeration .{name} has no closing '.'")));
        }
        Ok(Token::Enum(name))
    }

    fn number(&mut self) -> Result<Token, LexError> {
        let start = self.at;
        if matches!(self.peek(), Some(b'+' | b'-')) {
            self.at += 1;
        }
        self.take_while(|c| c.is_ascii_digit());
        if self.peek() == Some(b'.') {
            self.at += 1;
            self.take_while(|c| c.is_ascii_digit());
        }
        if matches!(self.peek(), Some(b'e' | b'E')) {
            self.at += 1;
            if matches!(self.peek(), Some(b'+' | b'-')) {
                self.at += 1;
            }
            self.take_while(|c| c.is_ascii_digit());
        }
        let text = String::from_utf8_lossy(&self.text[start..self.at]);
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Token::Number(v)),
            Ok(_) => Err((self.line, format!("number {text} is not finite"))),
            Err(_) => Err((self.line, format!("malformed number {text:?}"))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all(text: &str) -> Result<Vec<Token>, LexError> {
        let mut lx = Lexer::new(text.as_bytes());
        let mut out = Vec::new();
        while let Some((t, _)) = lx.next_token()? {
            out.push(t);
        }
        Ok(out)
    }

    #[test]
    fn tokens_of_an_instance() {
        let t = all("#12 = CIRCLE('it''s',#3,1.E-7) /* c */ ;").unwrap();
        assert_eq!(
            t,
            vec![
                Token::Instance(12),
                Token::Equals,
                Token::Keyword("CIRCLE".into()),
                Token::Open,
                Token::Str("it's".into()),
                Token::Comma,
                Token::Instance(3),
                Token::Comma,
                Token::Number(1e-7),
                Token::Close,
                Token::Semicolon,
            ]
        );
        assert_eq!(
            all(".T. $ * -2 \"0F\" ISO-10303-21").unwrap(),
            vec![
                Token::Enum("T".into()),
                Token::Dollar,
                Token::Star,
                Token::Number(-2.0),
                Token::Binary,
                Token::Keyword("ISO-10303-21".into()),
            ]
        );
    }

    #[test]
    fn errors_name_the_line() {
        assert_eq!(all("\n\n'abc").unwrap_err().0, 3);
        assert!(all("/* open").unwrap_err().1.contains("comment"));
        assert!(all("1E400").unwrap_err().1.contains("not finite"));
        assert!(all("#x").is_err());
        assert!(all(".T").is_err());
        assert!(all("@").is_err());
    }
}

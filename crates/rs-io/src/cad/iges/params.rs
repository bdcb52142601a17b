//! Free-format parameter records (IGES 5.3, section 2.2.3): fields separated by the parameter
//! delimiter and ended by the record delimiter. A field is empty (its default), a number
//! (integer, or real with an `E` or `D` exponent) or a Hollerith string `nH...` whose `n`
//! characters may include delimiters.
//!
//! [`Params`] is a cursor: entity readers take the fields in order, so no list of fields is
//! ever built, and [`Params::max_remaining`] bounds any count read from the file before
//! anything is allocated for it.

use std::borrow::Cow;

use super::error::{FieldProblem, IgesError};

/// One field of a parameter record.
#[derive(Debug, PartialEq)]
pub(super) enum Field<'a> {
    /// An empty field (the parameter's default).
    Empty,
    /// A number or other unquoted text, trimmed of blanks.
    Text(&'a [u8]),
    /// A Hollerith string's characters.
    String(&'a [u8]),
}

/// A cursor over one free-format record.
#[derive(Debug)]
pub(super) struct Params<'a> {
    text: Cow<'a, [u8]>,
    pos: usize,
    /// 1-based index of the next field.
    index: usize,
    delim: u8,
    end: u8,
    ended: bool,
    /// Where the record is, for messages (`DE 57 (126 rational B-spline curve)`).
    who: String,
}

impl<'a> Params<'a> {
    /// A cursor over `text` with the parameter and record delimiters `delim` and `end`.
    pub(super) fn new(text: Cow<'a, [u8]>, delim: u8, end: u8, who: String) -> Self {
        Self {
            text,
            pos: 0,
            index: 1,
            delim,
            end,
            ended: false,
            who,
        }
    }

    /// The error about the parameter just read (or about to be read, before the first).
    pub(super) fn err(&self, name: &'static str, problem: FieldProblem) -> IgesError {
        IgesError::Field {
            who: self.who.clone(),
            index: self.index.saturating_sub(1).max(1),
            name,
            problem,
        }
    }

    /// An upper bound on the number of fields left: each takes at least one delimiter byte.
    pub(super) fn max_remaining(&self) -> usize {
        if self.ended {
            0
        } else {
            self.text.len() - self.pos + 1
        }
    }

    /// Checks that `count` items of `fields_each` fields can still be in the record, before
    /// anything is allocated for them.
    pub(super) fn check_count(
        &self,
        name: &'static str,
        count: usize,
        fields_each: usize,
    ) -> Result<(), IgesError> {
        let need = count.checked_mul(fields_each);
        match need {
            Some(n) if n <= self.max_remaining() => Ok(()),
            _ => Err(self.err(
                name,
                FieldProblem::CountTooLarge {
                    count,
                    left: self.max_remaining() / fields_each.max(1),
                },
            )),
        }
    }

    /// The next field, or `None` after the record delimiter.
    pub(super) fn next_field(&mut self) -> Result<Option<Field<'_>>, IgesError> {
        if self.ended {
            return Ok(None);
        }
        let index = self.index;
        self.index += 1;
        let text: &[u8] = &self.text;
        let mut i = self.pos;
        while i < text.len() && text[i] == b' ' {
            i += 1;
        }
        // A Hollerith string: digits, `H`, then exactly that many characters.
        let digits = text[i..].iter().take_while(|b| b.is_ascii_digit()).count();
        if digits > 0 && matches!(text.get(i + digits), Some(b'H' | b'h')) {
            let count: usize = std::str::from_utf8(&text[i..i + digits])
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(usize::MAX);
            let start = i + digits + 1;
            if count > text.len() - start {
                return Err(IgesError::Field {
                    who: self.who.clone(),
                    index,
                    name: "",
                    problem: FieldProblem::HollerithPastEnd(count),
                });
            }
            let mut j = start + count;
            while j < text.len() && text[j] == b' ' {
                j += 1;
            }
            match text.get(j) {
                Some(&c) if c == self.delim || c == self.end => {
                    self.ended = c == self.end;
                    self.pos = j + 1;
                }
                None => {
                    self.ended = true;
                    self.pos = j;
                }
                Some(&c) => {
                    return Err(IgesError::Field {
                        who: self.who.clone(),
                        index,
                        name: "",
                        problem: FieldProblem::AfterHollerith(char::from(c)),
                    });
                }
            }
            return Ok(Some(Field::String(&self.text[start..start + count])));
        }
        let stop = memchr::memchr2(self.delim, self.end, &text[i..]).map(|k| i + k);
        let (mut a, mut b, next, ended) = match stop {
            Some(k) => (i, k, k + 1, text[k] == self.end),
            // A record without its delimiter ends at the end of its data.
            None => (i, text.len(), text.len(), true),
        };
        while a < b && text[a] == b' ' {
            a += 1;
        }
        while b > a && text[b - 1] == b' ' {
            b -= 1;
        }
        self.pos = next;
        self.ended = ended;
        Ok(Some(if a == b {
            Field::Empty
        } else {
            Field::Text(&self.text[a..b])
        }))
    }

    /// The next field, an error naming `name` if the record has ended.
    fn required(&mut self, name: &'static str) -> Result<Field<'_>, IgesError> {
        if self.ended {
            return Err(IgesError::Field {
                who: self.who.clone(),
                index: self.index,
                name,
                problem: FieldProblem::Missing,
            });
        }
        // Not ended, so there is a field.
        Ok(self.next_field()?.unwrap_or(Field::Empty))
    }

    /// A real number (empty: 0, the IGES default).
    pub(super) fn real(&mut self, name: &'static str) -> Result<f64, IgesError> {
        let value = match self.required(name)? {
            Field::Empty => Ok(0.0),
            Field::Text(t) => parse_real(t),
            Field::String(_) => Err(FieldProblem::StringForNumber),
        };
        value.map_err(|m| self.err(name, m))
    }

    /// An integer (empty: 0, the IGES default).
    pub(super) fn int(&mut self, name: &'static str) -> Result<i64, IgesError> {
        let value = match self.required(name)? {
            Field::Empty => Ok(0),
            Field::Text(t) => parse_int(t),
            Field::String(_) => Err(FieldProblem::StringForInteger),
        };
        value.map_err(|m| self.err(name, m))
    }

    /// A count: a non-negative integer.
    pub(super) fn count(&mut self, name: &'static str) -> Result<usize, IgesError> {
        let n = self.int(name)?;
        usize::try_from(n).map_err(|_| self.err(name, FieldProblem::NegativeCount(n)))
    }

    /// A pointer to a directory entry (its odd sequence number; 0 for none). The sign is
    /// dropped: IGES negates some pointers to mark them, the entry is the same.
    pub(super) fn pointer(&mut self, name: &'static str) -> Result<usize, IgesError> {
        let n = self.int(name)?;
        usize::try_from(n.unsigned_abs())
            .map_err(|_| self.err(name, FieldProblem::PointerOutOfRange))
    }

    /// `count` pointer fields named `name`, after checking that the record can hold them (the
    /// count read as field `count_name`).
    pub(super) fn pointers(
        &mut self,
        count_name: &'static str,
        count: usize,
        name: &'static str,
    ) -> Result<Vec<usize>, IgesError> {
        self.check_count(count_name, count, 1)?;
        (0..count).map(|_| self.pointer(name)).collect()
    }

    /// Skips one field (any kind).
    pub(super) fn skip(&mut self, name: &'static str) -> Result<(), IgesError> {
        self.required(name).map(|_| ())
    }
}

/// Parses an IGES real: digits, sign, point, and an exponent with `E` or `D`; finite only.
pub(super) fn parse_real(t: &[u8]) -> Result<f64, FieldProblem> {
    let shown = || String::from_utf8_lossy(t).into_owned();
    let ok = !t.is_empty()
        && t.len() <= 64
        && t.iter().all(|b| {
            b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b'E' | b'e' | b'D' | b'd')
        })
        && t.iter().any(u8::is_ascii_digit);
    if !ok {
        return Err(FieldProblem::NotANumber(shown()));
    }
    let s: String = t
        .iter()
        .map(|&b| match b {
            b'D' | b'd' => 'E',
            _ => char::from(b),
        })
        .collect();
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(FieldProblem::NotFinite(shown())),
        Err(_) => Err(FieldProblem::NotANumber(shown())),
    }
}

/// Parses an IGES integer (optional sign, digits).
fn parse_int(t: &[u8]) -> Result<i64, FieldProblem> {
    let shown = || String::from_utf8_lossy(t).into_owned();
    let digits = match t {
        [b'+' | b'-', rest @ ..] => rest,
        _ => t,
    };
    if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
        return Err(FieldProblem::NotAnInteger(shown()));
    }
    std::str::from_utf8(t)
        .ok()
        .and_then(|s| s.parse::<i64>().ok())
        .ok_or_else(|| FieldProblem::IntegerOutOfRange(shown()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Params<'_> {
        Params::new(
            Cow::Borrowed(s.as_bytes()),
            b',',
            b';',
            "DE 1 (test)".into(),
        )
    }

    #[test]
    fn fields_numbers_and_strings() {
        let mut c = p("126, 3 ,, 1.5D2,-2.E-1,4H;,ab,.5;trailing comment");
        assert_eq!(c.int("type").unwrap(), 126);
        assert_eq!(c.count("K").unwrap(), 3);
        assert_eq!(c.real("empty").unwrap(), 0.0);
        assert_eq!(c.real("x").unwrap(), 150.0);
        assert_eq!(c.real("y").unwrap(), -0.2);
        assert_eq!(c.next_field().unwrap(), Some(Field::String(b";,ab")));
        assert_eq!(c.real("z").unwrap(), 0.5);
        assert_eq!(c.next_field().unwrap(), None);
        assert!(
            c.real("more")
                .unwrap_err()
                .to_string()
                .contains("ends before")
        );
    }

    #[test]
    fn bad_fields_are_one_line_errors() {
        for (text, want) in [
            ("abc;", "not a number"),
            ("1e400;", "not a finite number"),
            ("NaN;", "not a number"),
            ("inf;", "not a number"),
            ("99H abc;", "past the end"),
            ("3Habcd;", "after a Hollerith"),
        ] {
            let e = p(text).real("x").unwrap_err().to_string();
            assert!(e.contains(want), "{text}: {e}");
            assert!(!e.contains('\n'));
        }
        let msg = |e: IgesError| e.to_string();
        assert!(msg(p("1.5;").int("n").unwrap_err()).contains("not an integer"));
        assert!(msg(p("-3;").count("n").unwrap_err()).contains("negative"));
        assert!(msg(p("99999999999999999999;").int("n").unwrap_err()).contains("out of range"));
        let c = p("1,2,3;");
        assert!(c.check_count("K", 1_000_000_000_000, 4).is_err());
        assert!(c.check_count("K", 1, 4).is_ok());
        assert!(c.check_count("K", usize::MAX, 4).is_err());
    }
}

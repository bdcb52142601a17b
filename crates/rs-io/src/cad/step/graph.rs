//! The instance table of a Part 21 file and typed access to the attributes of its instances.
//!
//! The parser keeps every instance of the DATA sections as written (simple `#1=A(...)` or
//! complex `#1=(A(...)B(...))`); references stay labels, resolved on access, so a missing or
//! cyclic reference is found where it is followed. Nested parameter lists are limited to
//! [`MAX_NESTING`] levels so the recursive descent has bounded depth.

use std::collections::HashMap;

use super::error::{Result, StepError};
use super::tokens::{Lexer, Token};

/// The deepest nesting of parameter lists and typed parameters accepted. STEP geometry needs
/// three (a B-spline surface's rows of points inside the instance's own list).
pub(crate) const MAX_NESTING: usize = 32;

/// One parameter value.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Value {
    /// `#12`
    Ref(u64),
    /// A finite number.
    Num(f64),
    /// A string.
    Str(String),
    /// `.NAME.`
    Enum(String),
    /// `TYPE(value)`, e.g. `LENGTH_MEASURE(1.E-7)`.
    Typed(String, Box<Value>),
    /// `(a, b, ...)`
    List(Vec<Value>),
    /// `$`
    Unset,
    /// `*`
    Derived,
    /// A binary (ignored).
    Binary,
}

/// One record of an instance: its entity type name and parameters.
#[derive(Clone, Debug)]
pub(crate) struct Part {
    pub(crate) name: String,
    pub(crate) params: Vec<Value>,
}

/// One entity instance.
#[derive(Clone, Debug)]
pub(crate) struct Instance {
    /// `#label`
    pub(crate) label: u64,
    /// One part for a simple instance; the partial records of a complex one.
    pub(crate) parts: Vec<Part>,
}

impl Instance {
    /// Whether this is a complex instance (`#1=(A()B())`).
    pub(crate) fn is_complex(&self) -> bool {
        self.parts.len() != 1
    }

    /// The simple instance's type name, or for a complex one its most specific record
    /// (a `RATIONAL_*` record first, then the record names that are not generic supertypes),
    /// joined by `+` if several remain.
    pub(crate) fn type_name(&self) -> String {
        if let [p] = self.parts.as_slice() {
            return p.name.clone();
        }
        if let Some(p) = self.parts.iter().find(|p| p.name.starts_with("RATIONAL_")) {
            return p.name.clone();
        }
        const GENERIC: [&str; 10] = [
            "REPRESENTATION_ITEM",
            "GEOMETRIC_REPRESENTATION_ITEM",
            "CURVE",
            "BOUNDED_CURVE",
            "B_SPLINE_CURVE",
            "SURFACE",
            "BOUNDED_SURFACE",
            "B_SPLINE_SURFACE",
            "TOPOLOGICAL_REPRESENTATION_ITEM",
            "REPRESENTATION_CONTEXT",
        ];
        let names: Vec<&str> = self
            .parts
            .iter()
            .map(|p| p.name.as_str())
            .filter(|n| !GENERIC.contains(n))
            .collect();
        if names.is_empty() {
            self.parts
                .iter()
                .map(|p| p.name.as_str())
                .collect::<Vec<_>>()
                .join("+")
        } else {
            names.join("+")
        }
    }

    /// The name of its first record (a simple instance's type), or `""`.
    pub(crate) fn first_name(&self) -> &str {
        self.parts
            .first()
            .map(|p| p.name.as_str())
            .unwrap_or_default()
    }

    /// Whether the instance is of type `name` (a simple instance of it, or a complex one with
    /// that record).
    pub(crate) fn is(&self, name: &str) -> bool {
        self.parts.iter().any(|p| p.name == name)
    }

    /// `#12 CIRCLE`, for messages.
    pub(crate) fn what(&self) -> String {
        format!("#{} {}", self.label, self.type_name())
    }

    /// The attributes of the record `name` (for a simple instance: the instance's own list,
    /// which starts with its supertypes' attributes).
    pub(crate) fn record(&self, name: &str) -> Result<Attrs<'_>> {
        self.parts
            .iter()
            .find(|p| p.name == name)
            .map(|p| Attrs {
                inst: self,
                part: p,
            })
            .ok_or_else(|| StepError::WrongType {
                what: self.what(),
                expected: name.to_string(),
            })
    }

    /// The attributes of a simple instance, or `Err` for a complex one.
    pub(crate) fn simple(&self) -> Result<Attrs<'_>> {
        match self.parts.as_slice() {
            [p] => Ok(Attrs {
                inst: self,
                part: p,
            }),
            _ => Err(StepError::Complex { what: self.what() }),
        }
    }
}

/// Typed access to the parameters of one record; errors name the instance and attribute.
#[derive(Clone, Copy)]
pub(crate) struct Attrs<'a> {
    pub(crate) inst: &'a Instance,
    pub(crate) part: &'a Part,
}

impl<'a> Attrs<'a> {
    fn err(&self, i: usize, name: &'static str, problem: &str) -> StepError {
        StepError::Attribute {
            what: self.inst.what(),
            index: i,
            name,
            problem: problem.to_string(),
        }
    }

    /// Parameter `i` (0-based) as written.
    pub(crate) fn get(&self, i: usize, name: &'static str) -> Result<&'a Value> {
        self.part
            .params
            .get(i)
            .ok_or_else(|| self.err(i, name, "is missing"))
    }

    /// A number (a typed measure `LENGTH_MEASURE(2.)` is accepted too).
    pub(crate) fn real(&self, i: usize, name: &'static str) -> Result<f64> {
        value_real(self.get(i, name)?).ok_or_else(|| self.err(i, name, "is not a number"))
    }

    /// A whole number in `0..=max`.
    pub(crate) fn count(&self, i: usize, name: &'static str, max: usize) -> Result<usize> {
        let v = self.real(i, name)?;
        value_count(v, max)
            .ok_or_else(|| self.err(i, name, &format!("is not a whole number in 0..={max}")))
    }

    /// A reference.
    pub(crate) fn reference(&self, i: usize, name: &'static str) -> Result<u64> {
        match self.get(i, name)? {
            Value::Ref(r) => Ok(*r),
            _ => Err(self.err(i, name, "is not a reference")),
        }
    }

    /// A list.
    pub(crate) fn list(&self, i: usize, name: &'static str) -> Result<&'a [Value]> {
        match self.get(i, name)? {
            Value::List(v) => Ok(v),
            _ => Err(self.err(i, name, "is not a list")),
        }
    }

    /// A list of references.
    pub(crate) fn refs(&self, i: usize, name: &'static str) -> Result<Vec<u64>> {
        self.list(i, name)?
            .iter()
            .map(|v| match v {
                Value::Ref(r) => Ok(*r),
                _ => Err(self.err(i, name, "holds something other than a reference")),
            })
            .collect()
    }

    /// A list of numbers.
    pub(crate) fn reals(&self, i: usize, name: &'static str) -> Result<Vec<f64>> {
        self.list(i, name)?
            .iter()
            .map(|v| value_real(v).ok_or_else(|| self.err(i, name, "holds a non-number")))
            .collect()
    }

    /// A boolean or logical `.T.`/`.F.` (`.U.` is an error).
    pub(crate) fn boolean(&self, i: usize, name: &'static str) -> Result<bool> {
        match self.get(i, name)? {
            Value::Enum(e) if e == "T" => Ok(true),
            Value::Enum(e) if e == "F" => Ok(false),
            _ => Err(self.err(i, name, "is not .T. or .F.")),
        }
    }
}

/// A number, looking through one level of typed parameter (`LENGTH_MEASURE(2.)`).
pub(crate) fn value_real(v: &Value) -> Option<f64> {
    match v {
        Value::Num(x) => Some(*x),
        Value::Typed(_, inner) => match inner.as_ref() {
            Value::Num(x) => Some(*x),
            _ => None,
        },
        _ => None,
    }
}

/// A whole number in `0..=max`.
pub(crate) fn value_count(v: f64, max: usize) -> Option<usize> {
    (v >= 0.0 && v.fract() == 0.0 && v <= max as f64).then_some(v as usize)
}

/// The instances of a file, in file order, with an index by label.
pub(crate) struct Graph {
    instances: Vec<Instance>,
    by_label: HashMap<u64, usize>,
}

impl Graph {
    /// Parses a whole Part 21 file: the `ISO-10303-21;` line, the HEADER section (read and
    /// skipped), the DATA sections and `END-ISO-10303-21;`.
    ///
    /// # Errors
    /// A one-line message naming the line: syntax, duplicate instance names, nesting deeper
    /// than [`MAX_NESTING`], a file that ends early.
    pub(crate) fn parse(text: &[u8]) -> Result<Graph> {
        Self::parse_text(text).map_err(StepError::Syntax)
    }

    fn parse_text(text: &[u8]) -> Result<Graph, String> {
        let mut p = Parser {
            lx: Lexer::new(text),
            peeked: None,
        };
        p.expect_keyword("ISO-10303-21")?;
        p.expect(&Token::Semicolon)?;
        p.expect_keyword("HEADER")?;
        p.expect(&Token::Semicolon)?;
        // Header entities: KEYWORD(params); until ENDSEC;
        loop {
            match p.next()? {
                (Token::Keyword(k), _) if k == "ENDSEC" => {
                    p.expect(&Token::Semicolon)?;
                    break;
                }
                (Token::Keyword(_), _) => {
                    p.params()?;
                    p.expect(&Token::Semicolon)?;
                }
                (t, line) => return Err(format!("line {line}: unexpected {t:?} in the header")),
            }
        }
        let mut g = Graph {
            instances: Vec::new(),
            by_label: HashMap::new(),
        };
        loop {
            match p.next()? {
                (Token::Keyword(k), _) if k == "DATA" => {
                    // DATA or DATA(parameters) in edition 3.
                    if p.peek()? == Some(&Token::Open) {
                        p.params()?;
                    }
                    p.expect(&Token::Semicolon)?;
                    g.data_section(&mut p)?;
                }
                (Token::Keyword(k), _) if k == "END-ISO-10303-21" => {
                    p.expect(&Token::Semicolon)?;
                    return Ok(g);
                }
                // ANCHOR, REFERENCE and SIGNATURE sections (edition 3) are not needed.
                (Token::Keyword(k), line) => {
                    return Err(format!("line {line}: unsupported section {k}"));
                }
                (t, line) => return Err(format!("line {line}: unexpected {t:?} between sections")),
            }
        }
    }

    fn data_section(&mut self, p: &mut Parser<'_>) -> Result<(), String> {
        loop {
            match p.next()? {
                (Token::Keyword(k), _) if k == "ENDSEC" => {
                    p.expect(&Token::Semicolon)?;
                    return Ok(());
                }
                (Token::Instance(label), line) => {
                    p.expect(&Token::Equals)?;
                    let parts = if p.peek()? == Some(&Token::Open) {
                        p.next()?;
                        let mut parts = Vec::new();
                        loop {
                            match p.next()? {
                                (Token::Close, _) => break,
                                (Token::Keyword(name), _) => {
                                    let params = p.params()?;
                                    parts.push(Part { name, params });
                                }
                                (t, l) => {
                                    return Err(format!(
                                        "line {l}: #{label}: unexpected {t:?} in a complex instance"
                                    ));
                                }
                            }
                        }
                        if parts.is_empty() {
                            return Err(format!("line {line}: #{label}: empty complex instance"));
                        }
                        parts
                    } else {
                        match p.next()? {
                            (Token::Keyword(name), _) => vec![Part {
                                name,
                                params: p.params()?,
                            }],
                            (t, l) => {
                                return Err(format!(
                                    "line {l}: #{label}: expected an entity type, found {t:?}"
                                ));
                            }
                        }
                    };
                    p.expect(&Token::Semicolon)?;
                    if self.by_label.insert(label, self.instances.len()).is_some() {
                        return Err(format!("line {line}: instance #{label} is defined twice"));
                    }
                    self.instances.push(Instance { label, parts });
                }
                (t, line) => {
                    return Err(format!("line {line}: expected an instance, found {t:?}"));
                }
            }
        }
    }

    /// The instances in file order.
    pub(crate) fn instances(&self) -> &[Instance] {
        &self.instances
    }

    /// The instance `#label`, or an error saying who referred to it.
    pub(crate) fn get(&self, label: u64, from: &str) -> Result<&Instance> {
        self.by_label
            .get(&label)
            .and_then(|&i| self.instances.get(i))
            .ok_or_else(|| StepError::MissingInstance {
                from: from.to_string(),
                label,
            })
    }
}

struct Parser<'a> {
    lx: Lexer<'a>,
    peeked: Option<(Token, u32)>,
}

impl Parser<'_> {
    fn fill(&mut self) -> Result<(), String> {
        if self.peeked.is_none() {
            self.peeked = self
                .lx
                .next_token()
                .map_err(|(line, m)| format!("line {line}: {m}"))?;
        }
        Ok(())
    }

    fn peek(&mut self) -> Result<Option<&Token>, String> {
        self.fill()?;
        Ok(self.peeked.as_ref().map(|(t, _)| t))
    }

    fn next(&mut self) -> Result<(Token, u32), String> {
        self.fill()?;
        self.peeked
            .take()
            .ok_or_else(|| format!("line {}: the file ends early (truncated?)", self.lx.line()))
    }

    fn expect(&mut self, want: &Token) -> Result<(), String> {
        match self.next()? {
            (t, _) if &t == want => Ok(()),
            (t, line) => Err(format!("line {line}: expected {want:?}, found {t:?}")),
        }
    }

    fn expect_keyword(&mut self, want: &str) -> Result<(), String> {
        match self.next()? {
            (Token::Keyword(k), _) if k == want => Ok(()),
            (t, line) => Err(format!("line {line}: expected {want}, found {t:?}")),
        }
    }

    /// `( value, value, ... )`, the list of a record.
    fn params(&mut self) -> Result<Vec<Value>, String> {
        self.expect(&Token::Open)?;
        self.list_rest(1)
    }

    /// The rest of a list after its `(`, at nesting `depth`.
    fn list_rest(&mut self, depth: usize) -> Result<Vec<Value>, String> {
        let mut out = Vec::new();
        if self.peek()? == Some(&Token::Close) {
            self.next()?;
            return Ok(out);
        }
        loop {
            out.push(self.value(depth)?);
            match self.next()? {
                (Token::Comma, _) => {}
                (Token::Close, _) => return Ok(out),
                (t, line) => return Err(format!("line {line}: expected ',' or ')', found {t:?}")),
            }
        }
    }

    fn value(&mut self, depth: usize) -> Result<Value, String> {
        let (t, line) = self.next()?;
        Ok(match t {
            Token::Instance(r) => Value::Ref(r),
            Token::Number(x) => Value::Num(x),
            Token::Str(s) => Value::Str(s),
            Token::Enum(e) => Value::Enum(e),
            Token::Binary => Value::Binary,
            Token::Dollar => Value::Unset,
            Token::Star => Value::Derived,
            Token::Open | Token::Keyword(_) if depth >= MAX_NESTING => {
                return Err(format!(
                    "line {line}: parameters nested deeper than {MAX_NESTING} levels"
                ));
            }
            Token::Open => Value::List(self.list_rest(depth + 1)?),
            Token::Keyword(k) => {
                self.expect(&Token::Open)?;
                let v = self.value(depth + 1)?;
                self.expect(&Token::Close)?;
                Value::Typed(k, Box::new(v))
            }
            t => return Err(format!("line {line}: unexpected {t:?} in a parameter list")),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(data: &str) -> String {
        format!(
            "ISO-10303-21;\nHEADER;\nFILE_NAME('a',(''));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
        )
    }

    #[test]
    fn simple_and_complex_instances() {
        let g = Graph::parse(
            file("#1=CIRCLE('c',#2,LENGTH_MEASURE(2.));\n#2=(A(1)B((1,2),$,*)C());").as_bytes(),
        )
        .unwrap();
        let c = g.get(1, "test").unwrap();
        assert_eq!(c.type_name(), "CIRCLE");
        let a = c.simple().unwrap();
        assert_eq!(a.reference(1, "position").unwrap(), 2);
        assert_eq!(a.real(2, "radius").unwrap(), 2.0);
        assert!(
            a.real(1, "position")
                .map(|_| ())
                .unwrap_err()
                .to_string()
                .contains("#1 CIRCLE: attribute 2 (position)")
        );
        let x = g.get(2, "test").unwrap();
        assert!(x.is_complex() && x.is("B") && !x.is("D"));
        assert_eq!(
            x.record("B").unwrap().reals(0, "l").unwrap(),
            vec![1.0, 2.0]
        );
        assert!(
            g.get(3, "#2 X")
                .map(|_| ())
                .unwrap_err()
                .to_string()
                .contains("#3")
        );
    }

    #[test]
    fn syntax_errors() {
        assert!(
            Graph::parse(file("#1=A(1);#1=B(2);").as_bytes())
                .map(|_| ())
                .unwrap_err()
                .to_string()
                .contains("twice")
        );
        let deep = format!("#1=A({}{});", "(".repeat(100), ")".repeat(100));
        assert!(
            Graph::parse(file(&deep).as_bytes())
                .map(|_| ())
                .unwrap_err()
                .to_string()
                .contains("nested")
        );
        assert!(
            Graph::parse(b"ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=A(")
                .map(|_| ())
                .unwrap_err()
                .to_string()
                .contains("ends early")
        );
        assert!(Graph::parse(file("#1=A(1,,2);").as_bytes()).is_err());
    }
}

//! Formulas in `x` and `y`, as users write them for `inrs fit --function`, `inrs integrate
//! --function` and the Python package: one grammar, parsed once into a program evaluated at
//! many points.
//!
//! # Grammar
//! ```text
//! formula := sum
//! sum     := product (("+" | "-") product)*          left to right
//! product := unary (("*" | "/") unary)*              left to right
//! unary   := ("-" | "+") unary | power
//! power   := atom (("^" | "**") unary)?              right to left: 2^3^2 = 2^9
//! atom    := number | name | name "(" sum ("," sum)* ")" | "(" sum ")"
//! number  := digits ["." digits] | "." digits, then optionally ("e" | "E") ["+" | "-"] digits
//! ```
//! So `-x^2` is `-(x^2)`, `2^-1` is `0.5`, `x*y/3` is `(x*y)/3`, and `1e-3`, `2.5E+4` and
//! `x*1e-3` are numbers as in Rust, Python or C. White space is ignored between tokens.
//!
//! Names: the variables `x` and `y` (and `z` in a formula over a surface in space,
//! [`Formula::parse_xyz`]); the constants `pi`, `e`, `tau` (also `PI`, `E`, `TAU`,
//! `π`, `τ`); the functions of one argument `abs`, `signum`, `sqrt`, `cbrt`, `exp`, `ln`,
//! `log` (natural), `log2`, `log10`, `sin`, `cos`, `tan`, `asin`, `acos`, `atan`, `sinh`,
//! `cosh`, `tanh`, `asinh`, `acosh`, `atanh`, `floor`, `ceil`, `round`, `trunc`, `fract`, and
//! of two `atan2(y, x)`, `min(a, b)`, `max(a, b)`, `hypot(a, b)`. Every operation is the
//! `f64` one of Rust's standard library (`^` is `powf`).
//!
//! Errors are one line: the formula, the column (1-based, in characters) and what was
//! expected there, in these words.

use rs_spline::Point;
use thiserror::Error;

/// The longest formula accepted, in bytes.
pub const MAX_FORMULA_BYTES: usize = 4096;

/// The deepest nesting of parentheses, unary signs and powers accepted (the parser recurses).
const MAX_NESTING: usize = 256;

/// Why a formula could not be read: its text, the column (1-based, in characters) and what is
/// wrong there.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("formula {text:?}: {}", describe(*.column, .text, .message))]
pub struct FormulaError {
    /// The formula as given.
    pub text: String,
    /// The 1-based column (in characters) where it goes wrong; 0 for the whole formula.
    pub column: usize,
    /// What was expected there, or what is wrong.
    pub message: String,
}

fn describe(column: usize, text: &str, message: &str) -> String {
    match column {
        0 => message.to_string(),
        c if c > text.chars().count() => format!("at its end: {message}"),
        c => format!("column {c}: {message}"),
    }
}

/// One step of a parsed formula's program (postfix: operands first).
#[derive(Clone, Copy, Debug)]
enum Op {
    Number(f64),
    X,
    Y,
    Z,
    Neg,
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Unary(fn(f64) -> f64),
    Binary(fn(f64, f64) -> f64),
}

/// A formula in `x` and `y`, parsed once ([`Formula::parse`]) and evaluated at any number of
/// points ([`Formula::at`]).
///
/// # Examples
///
/// ```
/// use rs_io::formula::Formula;
/// use rs_spline::Point;
/// let f = Formula::parse("-x^2 + 2.5E+1 * y - 1e-3").unwrap();
/// assert_eq!(f.at(Point::new(3.0, 2.0)), -9.0 + 50.0 - 0.001);
/// let e = Formula::parse("foo(x)").unwrap_err();
/// assert_eq!(
///     e.to_string(),
///     "formula \"foo(x)\": column 1: unknown function \"foo\" (see the functions in `inrs fit --help`)"
/// );
/// ```
#[derive(Clone, Debug)]
pub struct Formula {
    text: String,
    program: Vec<Op>,
    /// The most values the program holds at once.
    depth: usize,
}

impl Formula {
    /// Parses `text` (see the module's grammar).
    ///
    /// # Errors
    /// A [`FormulaError`] naming the column and what was expected there: an unknown name or
    /// function, a function with the wrong number of arguments, a missing operand, operator or
    /// parenthesis, a number out of range, a formula longer than [`MAX_FORMULA_BYTES`] or
    /// nested more than 256 deep, an empty formula.
    pub fn parse(text: &str) -> Result<Self, FormulaError> {
        Self::parse_with(text, false)
    }

    /// Parses `text` as a formula in `x`, `y` and `z` (over a surface in space, such as
    /// `inrs integrate --over surface`); evaluate it with [`Formula::at_xyz`].
    ///
    /// # Errors
    /// As [`Formula::parse`].
    pub fn parse_xyz(text: &str) -> Result<Self, FormulaError> {
        Self::parse_with(text, true)
    }

    fn parse_with(text: &str, space: bool) -> Result<Self, FormulaError> {
        let whole = |message: String| FormulaError {
            text: text.to_string(),
            column: 0,
            message,
        };
        if text.len() > MAX_FORMULA_BYTES {
            return Err(FormulaError {
                text: format!("{}...", truncate(text, 40)),
                column: 0,
                message: format!("longer than {MAX_FORMULA_BYTES} bytes"),
            });
        }
        if text.trim().is_empty() {
            return Err(whole(
                "empty: write a formula in x and y, such as x^2 + y".into(),
            ));
        }
        let mut parser = Parser {
            text,
            space,
            pos: 0,
            nesting: 0,
            program: Vec::new(),
        };
        parser.sum()?;
        parser.skip_space();
        if let Some(c) = parser.peek() {
            let hint = if c.is_alphanumeric() || c == '(' || c == '.' {
                " (write * between factors: 2*x)"
            } else {
                ""
            };
            return Err(parser.error(format!(
                "expected an operator (+ - * / ^) or the end, found {:?}{hint}",
                parser.token()
            )));
        }
        let depth = stack_depth(&parser.program);
        Ok(Self {
            text: text.to_string(),
            program: parser.program,
            depth,
        })
    }

    /// The formula as written.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The value at `p` (NaN, infinite or finite as the `f64` operations give it).
    pub fn at(&self, p: Point) -> f64 {
        self.at_xyz(p.x, p.y, f64::NAN)
    }

    /// The value at `(x, y, z)` (`z` is a variable only in a formula read by
    /// [`Formula::parse_xyz`]).
    pub fn at_xyz(&self, x: f64, y: f64, z: f64) -> f64 {
        let mut stack: Vec<f64> = Vec::with_capacity(self.depth);
        for op in &self.program {
            let v = match *op {
                Op::Number(v) => v,
                Op::X => x,
                Op::Y => y,
                Op::Z => z,
                Op::Neg => {
                    let a = stack.pop().unwrap_or(f64::NAN);
                    -a
                }
                Op::Unary(f) => {
                    let a = stack.pop().unwrap_or(f64::NAN);
                    f(a)
                }
                _ => {
                    let b = stack.pop().unwrap_or(f64::NAN);
                    let a = stack.pop().unwrap_or(f64::NAN);
                    match *op {
                        Op::Add => a + b,
                        Op::Sub => a - b,
                        Op::Mul => a * b,
                        Op::Div => a / b,
                        Op::Pow => a.powf(b),
                        Op::Binary(f) => f(a, b),
                        _ => f64::NAN,
                    }
                }
            };
            stack.push(v);
        }
        stack.pop().unwrap_or(f64::NAN)
    }
}

impl std::str::FromStr for Formula {
    type Err = FormulaError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::parse(s)
    }
}

/// The first `n` characters of `s`.
fn truncate(s: &str, n: usize) -> &str {
    s.char_indices().nth(n).map_or(s, |(i, _)| &s[..i])
}

/// The most values `program` holds on its stack at once.
fn stack_depth(program: &[Op]) -> usize {
    let (mut now, mut most) = (0usize, 0usize);
    for op in program {
        match op {
            Op::Number(_) | Op::X | Op::Y | Op::Z => now += 1,
            Op::Neg | Op::Unary(_) => {}
            _ => now = now.saturating_sub(1),
        }
        most = most.max(now);
    }
    most
}

/// The constants by name.
fn constant(name: &str) -> Option<f64> {
    use std::f64::consts::{E, PI, TAU};
    Some(match name {
        "pi" | "PI" | "π" => PI,
        "e" | "E" => E,
        "tau" | "TAU" | "τ" => TAU,
        _ => return None,
    })
}

/// The functions of one argument by name.
fn unary(name: &str) -> Option<fn(f64) -> f64> {
    Some(match name {
        "abs" => f64::abs,
        "signum" => f64::signum,
        "sqrt" => f64::sqrt,
        "cbrt" => f64::cbrt,
        "exp" => f64::exp,
        "ln" | "log" => f64::ln,
        "log2" => f64::log2,
        "log10" => f64::log10,
        "sin" => f64::sin,
        "cos" => f64::cos,
        "tan" => f64::tan,
        "asin" => f64::asin,
        "acos" => f64::acos,
        "atan" => f64::atan,
        "sinh" => f64::sinh,
        "cosh" => f64::cosh,
        "tanh" => f64::tanh,
        "asinh" => f64::asinh,
        "acosh" => f64::acosh,
        "atanh" => f64::atanh,
        "floor" => f64::floor,
        "ceil" => f64::ceil,
        "round" => f64::round,
        "trunc" => f64::trunc,
        "fract" => f64::fract,
        _ => return None,
    })
}

/// The functions of two arguments by name.
fn binary(name: &str) -> Option<fn(f64, f64) -> f64> {
    Some(match name {
        "atan2" => f64::atan2,
        "min" => f64::min,
        "max" => f64::max,
        "hypot" => f64::hypot,
        _ => return None,
    })
}

/// The recursive-descent parser of the module's grammar, writing the program as it goes.
struct Parser<'a> {
    text: &'a str,
    /// Whether `z` is a variable (formulas over a surface in space).
    space: bool,
    /// Byte offset of the next character.
    pos: usize,
    nesting: usize,
    program: Vec<Op>,
}

impl Parser<'_> {
    fn peek(&self) -> Option<char> {
        self.text[self.pos..].chars().next()
    }

    fn skip_space(&mut self) {
        while let Some(c) = self.peek().filter(|c| c.is_whitespace()) {
            self.pos += c.len_utf8();
        }
    }

    /// Consumes `s` (after white space) if it comes next.
    fn eat(&mut self, s: &str) -> bool {
        self.skip_space();
        if self.text[self.pos..].starts_with(s) {
            self.pos += s.len();
            true
        } else {
            false
        }
    }

    /// The token at the cursor, for messages: a name or number, else one character.
    fn token(&self) -> String {
        let rest = &self.text[self.pos..];
        let word: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '.')
            .collect();
        if word.is_empty() {
            rest.chars().next().map(String::from).unwrap_or_default()
        } else {
            word
        }
    }

    /// An error at byte offset `at`.
    fn error_at(&self, at: usize, message: String) -> FormulaError {
        FormulaError {
            text: self.text.to_string(),
            column: self.text[..at].chars().count() + 1,
            message,
        }
    }

    /// An error at the cursor.
    fn error(&self, message: String) -> FormulaError {
        self.error_at(self.pos, message)
    }

    fn enter(&mut self) -> Result<(), FormulaError> {
        self.nesting += 1;
        if self.nesting > MAX_NESTING {
            return Err(self.error(format!("nested more than {MAX_NESTING} deep")));
        }
        Ok(())
    }

    fn sum(&mut self) -> Result<(), FormulaError> {
        self.product()?;
        loop {
            if self.eat("+") {
                self.product()?;
                self.program.push(Op::Add);
            } else if self.eat("-") {
                self.product()?;
                self.program.push(Op::Sub);
            } else {
                return Ok(());
            }
        }
    }

    fn product(&mut self) -> Result<(), FormulaError> {
        self.unary()?;
        loop {
            self.skip_space();
            if self.text[self.pos..].starts_with("**") {
                return Ok(()); // a power, read by `power`
            }
            if self.eat("*") {
                self.unary()?;
                self.program.push(Op::Mul);
            } else if self.eat("/") {
                self.unary()?;
                self.program.push(Op::Div);
            } else {
                return Ok(());
            }
        }
    }

    fn unary(&mut self) -> Result<(), FormulaError> {
        self.enter()?;
        if self.eat("-") {
            self.unary()?;
            self.program.push(Op::Neg);
        } else if self.eat("+") {
            self.unary()?;
        } else {
            self.power()?;
        }
        self.nesting -= 1;
        Ok(())
    }

    fn power(&mut self) -> Result<(), FormulaError> {
        self.atom()?;
        if self.eat("^") || self.eat("**") {
            self.unary()?;
            self.program.push(Op::Pow);
        }
        Ok(())
    }

    fn atom(&mut self) -> Result<(), FormulaError> {
        self.skip_space();
        let start = self.pos;
        match self.peek() {
            Some(c) if c.is_ascii_digit() || c == '.' => self.number(),
            Some(c) if c.is_alphabetic() || c == '_' => self.name(),
            Some('(') => {
                self.pos += 1;
                self.enter()?;
                self.sum()?;
                self.nesting -= 1;
                if !self.eat(")") {
                    self.skip_space();
                    return Err(self.closing(start));
                }
                Ok(())
            }
            None => Err(self.error("expected a number, a name or \"(\"".into())),
            Some(_) => Err(self.error(format!(
                "expected a number, a name or \"(\", found {:?}",
                self.token()
            ))),
        }
    }

    /// The error of a missing `)` for the `(` at byte `open`.
    fn closing(&self, open: usize) -> FormulaError {
        let column = self.text[..open].chars().count() + 1;
        match self.peek() {
            None => self.error(format!(
                "expected \")\" to close the \"(\" of column {column}"
            )),
            Some(_) => self.error(format!(
                "expected \")\" to close the \"(\" of column {column}, found {:?}",
                self.token()
            )),
        }
    }

    /// `digits ["." digits] | "." digits`, then an optional exponent (an `e` without digits
    /// after it is an error: `2e` is no number).
    fn number(&mut self) -> Result<(), FormulaError> {
        let bytes = self.text.as_bytes();
        let start = self.pos;
        let digits = |mut i: usize| {
            while bytes.get(i).is_some_and(u8::is_ascii_digit) {
                i += 1;
            }
            i
        };
        let mut i = digits(start);
        let mut any = i > start;
        if bytes.get(i) == Some(&b'.') {
            let j = digits(i + 1);
            any |= j > i + 1;
            i = j;
        }
        if !any {
            return Err(self.error("expected digits before or after \".\"".into()));
        }
        if matches!(bytes.get(i), Some(b'e' | b'E')) {
            let mut j = i + 1;
            if matches!(bytes.get(j), Some(b'+' | b'-')) {
                j += 1;
            }
            let k = digits(j);
            if k == j {
                return Err(self.error_at(j, "expected the digits of the exponent".into()));
            }
            i = k;
        }
        let value: f64 = self.text[start..i]
            .parse()
            .map_err(|_| self.error("not a number".into()))?;
        if !value.is_finite() {
            return Err(self.error(format!("{} is out of range", &self.text[start..i])));
        }
        self.pos = i;
        self.program.push(Op::Number(value));
        Ok(())
    }

    /// A variable, a constant or a function call.
    fn name(&mut self) -> Result<(), FormulaError> {
        let start = self.pos;
        let len: usize = self.text[start..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .map(char::len_utf8)
            .sum();
        let name = &self.text[start..start + len];
        self.pos += len;
        self.skip_space();
        if self.peek() == Some('(') {
            return self.call(name, start);
        }
        if let Some(v) = constant(name) {
            self.program.push(Op::Number(v));
        } else if name == "x" {
            self.program.push(Op::X);
        } else if name == "y" {
            self.program.push(Op::Y);
        } else if name == "z" && self.space {
            self.program.push(Op::Z);
        } else if unary(name).is_some() || binary(name).is_some() {
            return Err(self.error(format!("expected \"(\" after the function {name:?}")));
        } else {
            return Err(self.error_at(
                start,
                if self.space {
                    format!(
                        "unknown name {name:?} (the variables are x, y and z; constants pi, e, tau)"
                    )
                } else if name == "z" {
                    "unknown name \"z\" (the variables are x and y; z only over a surface in space)"
                        .to_string()
                } else {
                    format!(
                        "unknown name {name:?} (the variables are x and y; constants pi, e, tau)"
                    )
                },
            ));
        }
        Ok(())
    }

    /// The call of function `name` (at byte `start`), the cursor on its `(`.
    fn call(&mut self, name: &str, start: usize) -> Result<(), FormulaError> {
        let arity = if unary(name).is_some() {
            1
        } else if binary(name).is_some() {
            2
        } else {
            return Err(self.error_at(
                start,
                format!("unknown function {name:?} (see the functions in `inrs fit --help`)"),
            ));
        };
        let open = self.pos;
        self.pos += 1;
        self.enter()?;
        let mut args = 0;
        loop {
            self.sum()?;
            args += 1;
            if !self.eat(",") {
                break;
            }
        }
        self.nesting -= 1;
        if !self.eat(")") {
            self.skip_space();
            return Err(self.closing(open));
        }
        if args != arity {
            let wanted = if arity == 1 {
                "one argument"
            } else {
                "two arguments"
            };
            return Err(self.error_at(start, format!("{name} takes {wanted}, not {args}")));
        }
        self.program.push(match (unary(name), binary(name)) {
            (Some(f), _) => Op::Unary(f),
            (_, Some(f)) => Op::Binary(f),
            _ => unreachable!("the arity was found above"),
        });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{E, PI};

    fn at(text: &str, x: f64, y: f64) -> f64 {
        Formula::parse(text)
            .unwrap_or_else(|e| panic!("{e}"))
            .at(Point::new(x, y))
    }

    #[test]
    fn float_literals_as_in_rust() {
        for (text, want) in [
            ("1e-3", 1e-3),
            ("2.5E+4", 2.5e4),
            ("1E3", 1e3),
            (".5", 0.5),
            ("5.", 5.0),
            ("0.125e1", 1.25),
            ("3e0", 3.0),
        ] {
            assert_eq!(at(text, 0.0, 0.0), want, "{text}");
        }
        assert_eq!(at("x*1e-3", 2.0, 0.0), 2e-3);
        assert_eq!(at("x*1e-3 - y", 2.0, 1.0), 2e-3 - 1.0);
    }

    #[test]
    fn the_usual_precedence_and_associativity() {
        assert_eq!(at("-x^2", 3.0, 0.0), -9.0);
        assert_eq!(at("-2^2", 0.0, 0.0), -4.0);
        assert_eq!(at("2^3^2", 0.0, 0.0), 512.0);
        assert_eq!(at("2^-1", 0.0, 0.0), 0.5);
        assert_eq!(at("x**2", 3.0, 0.0), 9.0);
        assert_eq!(at("1 - x - y", 0.25, 0.5), (1.0 - 0.25) - 0.5);
        assert_eq!(at("x*y/3", 0.1, 0.7), (0.1 * 0.7) / 3.0);
        assert_eq!(at("8/4/2", 0.0, 0.0), 1.0);
        assert_eq!(at("(1 + x) * y", 1.0, 3.0), 6.0);
        assert_eq!(at("+x", 2.0, 0.0), 2.0);
        assert_eq!(at("--x", 2.0, 0.0), 2.0);
        assert_eq!(at("pi + e + tau - PI - E - TAU", 0.0, 0.0), 0.0);
        assert_eq!(at("π", 0.0, 0.0), PI);
        assert_eq!(at("log(e)", 0.0, 0.0), E.ln());
        assert_eq!(at("atan2(y, x)", 1.0, 1.0), 1.0f64.atan2(1.0));
        assert_eq!(at("min(x, y) + max(x, y)", 1.0, 2.0), 3.0);
        assert_eq!(at("hypot(3, 4)", 0.0, 0.0), 5.0);
        let g = at("sqrt(abs(x)) * e + pi - log(y) + x^2 / tan(y)", -4.0, 0.5);
        let want = 2.0 * E + PI - 0.5f64.ln() + 16.0f64 / 0.5f64.tan();
        assert_eq!(g, want);
        assert_eq!(
            at("sin(10*x) + sin(10*y)", 0.3, -0.2),
            3f64.sin() + (-2f64).sin()
        );
        assert!(at("1/0 - 1/0", 0.0, 0.0).is_nan());
    }

    #[test]
    fn errors_name_the_column_and_what_was_expected() {
        for (text, want) in [
            (
                "foo(x)",
                "column 1: unknown function \"foo\" (see the functions in `inrs fit --help`)",
            ),
            (
                "z + 1",
                "column 1: unknown name \"z\" (the variables are x and y; z only over a surface in space)",
            ),
            ("sin(", "at its end: expected a number, a name or \"(\""),
            (
                "sin(x",
                "at its end: expected \")\" to close the \"(\" of column 4",
            ),
            (
                "(x + 1",
                "at its end: expected \")\" to close the \"(\" of column 1",
            ),
            (
                "x +* y",
                "column 4: expected a number, a name or \"(\", found \"*\"",
            ),
            (
                "2x",
                "column 2: expected an operator (+ - * / ^) or the end, found \"x\" (write * between factors: 2*x)",
            ),
            (
                "x)",
                "column 2: expected an operator (+ - * / ^) or the end, found \")\"",
            ),
            ("1e", "at its end: expected the digits of the exponent"),
            ("1e+x", "column 4: expected the digits of the exponent"),
            ("1e999", "column 1: 1e999 is out of range"),
            (".", "column 1: expected digits before or after \".\""),
            (
                "sin",
                "at its end: expected \"(\" after the function \"sin\"",
            ),
            ("atan2(y)", "column 1: atan2 takes two arguments, not 1"),
            ("sin(x, y)", "column 1: sin takes one argument, not 2"),
            (
                "x # y",
                "column 3: expected an operator (+ - * / ^) or the end, found \"#\"",
            ),
            ("", "empty: write a formula in x and y, such as x^2 + y"),
        ] {
            let e = Formula::parse(text).unwrap_err();
            assert_eq!(e.to_string(), format!("formula {text:?}: {want}"), "{text}");
            assert!(!e.to_string().contains('\n'));
        }
        let long = "1+".repeat(3000) + "1";
        let e = Formula::parse(&long).unwrap_err().to_string();
        assert!(e.ends_with(": longer than 4096 bytes"), "{e}");
        let deep = "(".repeat(300) + "x" + &")".repeat(300);
        let e = Formula::parse(&deep).unwrap_err().to_string();
        assert!(e.contains("nested more than 256 deep"), "{e}");
        let e = Formula::parse(&"-".repeat(1000)).unwrap_err().to_string();
        assert!(e.contains("nested more than 256 deep"), "{e}");
    }

    #[test]
    fn z_is_a_variable_only_over_a_surface() {
        let f = Formula::parse_xyz("x*z + y^2 - z").unwrap();
        assert_eq!(f.at_xyz(2.0, 3.0, 4.0), 8.0 + 9.0 - 4.0);
        let e = Formula::parse("x*z").unwrap_err().to_string();
        assert!(e.contains("z only over a surface in space"), "{e}");
        let e = Formula::parse_xyz("w").unwrap_err().to_string();
        assert!(e.contains("the variables are x, y and z"), "{e}");
    }
}

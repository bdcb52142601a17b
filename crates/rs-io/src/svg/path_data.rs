//! The SVG path data grammar (`d` attribute): every command, absolute and relative, with the
//! shorthand (`S`, `T`, `H`, `V`) and implicit-repeat forms.

use rs_spline::{Point, SplineError};

use super::arc::{ArcSegment, endpoint_arc};
use crate::IoError;
use crate::builder::LoopBuilder;

/// Reads path data into `builder` (subpaths become loops).
///
/// Path data is read on its own, whatever `builder` drew before: the pen starts at the origin
/// (so a leading relative `m` is absolute, as the SVG specification says), `S` and `T` have no
/// previous control point to reflect, and `z` returns to a subpath this data opened.
pub(crate) fn read_path_data(d: &str, builder: &mut LoopBuilder) -> Result<(), IoError> {
    builder.end_path();
    let mut reader = PathReader {
        lexer: Lexer {
            bytes: d.as_bytes(),
            pos: 0,
        },
        command: None,
        last_cubic: None,
        last_quad: None,
    };
    while let Some((cmd, start)) = reader.next_command()? {
        reader.segment(cmd, start, builder)?;
    }
    Ok(())
}

/// The state of the path-data grammar between segments.
struct PathReader<'a> {
    lexer: Lexer<'a>,
    /// The command in force (repeated implicitly when numbers follow).
    command: Option<u8>,
    /// Second control point of the last cubic, reflected by `S`.
    last_cubic: Option<Point>,
    /// Control point of the last quadratic, reflected by `T`.
    last_quad: Option<Point>,
}

impl PathReader<'_> {
    /// The next segment's command letter and its byte position: an explicit letter, or the
    /// command in force repeated (pairs after a moveto are implicit linetos). `None` at the end.
    fn next_command(&mut self) -> Result<Option<(u8, usize)>, IoError> {
        let lexer = &mut self.lexer;
        lexer.skip_separators();
        let Some(&b) = lexer.bytes.get(lexer.pos) else {
            return Ok(None);
        };
        let start = lexer.pos;
        let cmd = if b.is_ascii_alphabetic() {
            lexer.pos += 1;
            b
        } else {
            match self.command {
                Some(b'M') => b'L',
                Some(b'm') => b'l',
                Some(b'Z' | b'z') | None => {
                    return Err(lexer.error(start, "expected a command letter"));
                }
                Some(c) => c,
            }
        };
        if self.command.is_none() && !matches!(cmd, b'M' | b'm') {
            return Err(lexer.error(start, "path data must start with a moveto (M or m)"));
        }
        self.command = Some(cmd);
        Ok(Some((cmd, start)))
    }

    /// Reads the arguments of one segment of command `cmd` (at byte `start`) and adds it to
    /// `builder`, keeping the control points that `S` and `T` reflect.
    fn segment(&mut self, cmd: u8, start: usize, builder: &mut LoopBuilder) -> Result<(), IoError> {
        let rel = cmd.is_ascii_lowercase();
        let pen = builder.pen();
        let origin = if rel { pen } else { Point::new(0.0, 0.0) };
        let at = |p: Point| p + origin;
        let curve_err = |e: SplineError| IoError::PathData {
            position: start,
            message: e.to_string(),
        };
        let lexer = &mut self.lexer;
        let (mut new_cubic, mut new_quad) = (None, None);
        match cmd.to_ascii_uppercase() {
            b'M' => builder.move_to(at(lexer.point()?)),
            b'L' => builder.line_to(at(lexer.point()?)).map_err(curve_err)?,
            b'H' => {
                let x = lexer.number()? + origin.x;
                builder.line_to(Point::new(x, pen.y)).map_err(curve_err)?;
            }
            b'V' => {
                let y = lexer.number()? + origin.y;
                builder.line_to(Point::new(pen.x, y)).map_err(curve_err)?;
            }
            b'C' => {
                let (c1, c2, p) = (at(lexer.point()?), at(lexer.point()?), at(lexer.point()?));
                builder.bezier_to(&[c1, c2, p]).map_err(curve_err)?;
                new_cubic = Some(c2);
            }
            b'S' => {
                let c1 = self.last_cubic.map_or(pen, |c| pen * 2.0 - c);
                let (c2, p) = (at(lexer.point()?), at(lexer.point()?));
                builder.bezier_to(&[c1, c2, p]).map_err(curve_err)?;
                new_cubic = Some(c2);
            }
            b'Q' => {
                let (c, p) = (at(lexer.point()?), at(lexer.point()?));
                builder.bezier_to(&[c, p]).map_err(curve_err)?;
                new_quad = Some(c);
            }
            b'T' => {
                let c = self.last_quad.map_or(pen, |c| pen * 2.0 - c);
                let p = at(lexer.point()?);
                builder.bezier_to(&[c, p]).map_err(curve_err)?;
                new_quad = Some(c);
            }
            b'A' => {
                let (rx, ry, phi) = (lexer.number()?, lexer.number()?, lexer.number()?);
                let (large, sweep) = (lexer.flag()?, lexer.flag()?);
                let p = at(lexer.point()?);
                match endpoint_arc(pen, rx, ry, phi, large, sweep, p).map_err(curve_err)? {
                    ArcSegment::Nothing => {}
                    ArcSegment::Line => builder.line_to(p).map_err(curve_err)?,
                    ArcSegment::Curve(c) => builder.curve(c),
                }
            }
            b'Z' => builder.close(),
            _ => {
                return Err(lexer.error(start, &format!("unknown command {:?}", char::from(cmd))));
            }
        }
        self.last_cubic = new_cubic;
        self.last_quad = new_quad;
        Ok(())
    }
}

struct Lexer<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl Lexer<'_> {
    fn error(&self, position: usize, message: &str) -> IoError {
        IoError::PathData {
            position,
            message: message.to_string(),
        }
    }

    fn skip_whitespace(&mut self) {
        while self
            .bytes
            .get(self.pos)
            .is_some_and(|b| matches!(b, b' ' | b'\t' | b'\n' | b'\r' | b'\x0c'))
        {
            self.pos += 1;
        }
    }

    /// Whitespace with at most one comma.
    fn skip_separators(&mut self) {
        self.skip_whitespace();
        if self.bytes.get(self.pos) == Some(&b',') {
            self.pos += 1;
            self.skip_whitespace();
        }
    }

    fn point(&mut self) -> Result<Point, IoError> {
        let x = self.number()?;
        let y = self.number()?;
        Ok(Point::new(x, y))
    }

    /// A number per the SVG grammar: sign, digits, optional fraction, optional exponent
    /// (`.5.5` is two numbers, `1-2` too).
    fn number(&mut self) -> Result<f64, IoError> {
        self.skip_separators();
        let start = self.pos;
        let b = self.bytes;
        let mut i = self.pos;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let int_start = i;
        while b.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        let mut digits = i > int_start;
        if b.get(i) == Some(&b'.') {
            i += 1;
            let frac_start = i;
            while b.get(i).is_some_and(u8::is_ascii_digit) {
                i += 1;
            }
            digits |= i > frac_start;
        }
        if !digits {
            return Err(self.error(
                start,
                match b.get(start) {
                    None => "path data ends where a number is expected",
                    Some(_) => "expected a number",
                },
            ));
        }
        if matches!(b.get(i), Some(b'e' | b'E')) {
            let mut j = i + 1;
            if matches!(b.get(j), Some(b'+' | b'-')) {
                j += 1;
            }
            let exp_start = j;
            while b.get(j).is_some_and(u8::is_ascii_digit) {
                j += 1;
            }
            if j > exp_start {
                i = j;
            }
        }
        // The slice is ASCII by construction.
        let text = std::str::from_utf8(&b[start..i]).unwrap_or("");
        let value: f64 = text
            .parse()
            .map_err(|_| self.error(start, "expected a number"))?;
        if !value.is_finite() {
            return Err(self.error(start, "number out of range"));
        }
        self.pos = i;
        Ok(value)
    }

    /// An arc flag: a single `0` or `1` (no separator needed after it).
    fn flag(&mut self) -> Result<bool, IoError> {
        self.skip_separators();
        let start = self.pos;
        match self.bytes.get(self.pos) {
            Some(b'0') => {
                self.pos += 1;
                Ok(false)
            }
            Some(b'1') => {
                self.pos += 1;
                Ok(true)
            }
            None => Err(self.error(start, "path data ends where an arc flag is expected")),
            Some(_) => Err(self.error(start, "an arc flag must be 0 or 1")),
        }
    }
}

//! The SVG path data grammar (`d` attribute): every command, absolute and relative, with the
//! shorthand (`S`, `T`, `H`, `V`) and implicit-repeat forms.

use rs_spline::{Point, SplineError};

use super::arc::{ArcSegment, endpoint_arc};
use super::number::{LexError, LexErrorKind, Lexer};
use crate::IoError;
use crate::builder::LoopBuilder;

/// Reads path data into `builder` (subpaths become loops).
///
/// Path data is read on its own, whatever `builder` drew before: the pen starts at the origin
/// (so a leading relative `m` is absolute, as the SVG specification says), `S` and `T` have no
/// previous control point to reflect, and `z` returns to a subpath this data opened.
///
/// An error of the grammar (a token that is not a command or a number, a command without all
/// its arguments) stops the reading there, the segments before it drawn: `Ok(Some(error))`,
/// the specification's error handling ("render up to the command containing the first
/// error", which renderers apply segment by segment). A segment whose curve cannot be made
/// (an arc's radii beyond the limits, say) is an error (`Err`).
pub(crate) fn read_path_data(
    d: &str,
    builder: &mut LoopBuilder,
) -> Result<Option<IoError>, IoError> {
    builder.end_path();
    let mut reader = PathReader {
        lexer: Lexer::new(d),
        command: None,
        last_cubic: None,
        last_quad: None,
    };
    loop {
        let (cmd, start) = match reader.next_command() {
            Ok(Some(next)) => next,
            Ok(None) => return Ok(None),
            Err(e) => return Ok(Some(e)),
        };
        match reader.segment(cmd, start, builder)? {
            None => {}
            Some(grammar) => return Ok(Some(grammar)),
        }
    }
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
        let Some(b) = lexer.peek() else {
            return Ok(None);
        };
        let start = lexer.position();
        let cmd = if b.is_ascii_alphabetic() {
            lexer.bump();
            b
        } else {
            match self.command {
                Some(b'M') => b'L',
                Some(b'm') => b'l',
                Some(b'Z' | b'z') | None => {
                    return Err(error(start, "expected a command letter"));
                }
                Some(c) => c,
            }
        };
        if self.command.is_none() && !matches!(cmd, b'M' | b'm') {
            return Err(error(start, "path data must start with a moveto (M or m)"));
        }
        self.command = Some(cmd);
        Ok(Some((cmd, start)))
    }

    /// Reads the arguments of one segment of command `cmd` (at byte `start`) and adds it to
    /// `builder`, keeping the control points that `S` and `T` reflect. An error of the grammar
    /// (its arguments) is `Ok(Some(error))`, the segment not drawn; a curve that cannot be made
    /// is `Err`.
    fn segment(
        &mut self,
        cmd: u8,
        start: usize,
        builder: &mut LoopBuilder,
    ) -> Result<Option<IoError>, IoError> {
        match self.arguments(cmd, start) {
            Ok(args) => self.draw(cmd, start, args, builder).map(|()| None),
            Err(grammar) => Ok(Some(grammar)),
        }
    }

    /// The numbers of one segment of command `cmd` (at byte `start`; flags as 0 and 1), all
    /// read before any is drawn.
    fn arguments(&mut self, cmd: u8, start: usize) -> Result<[f64; 7], IoError> {
        let mut args = Arguments(&mut self.lexer);
        let mut v = [0.0; 7];
        match cmd.to_ascii_uppercase() {
            b'M' | b'L' | b'T' => [v[0], v[1]] = [args.number()?, args.number()?],
            b'H' | b'V' => v[0] = args.number()?,
            b'C' => {
                for x in &mut v[..6] {
                    *x = args.number()?;
                }
            }
            b'S' | b'Q' => {
                for x in &mut v[..4] {
                    *x = args.number()?;
                }
            }
            b'A' => {
                for x in &mut v[..3] {
                    *x = args.number()?;
                }
                v[3] = f64::from(u8::from(args.flag()?));
                v[4] = f64::from(u8::from(args.flag()?));
                [v[5], v[6]] = [args.number()?, args.number()?];
            }
            b'Z' => {}
            _ => {
                return Err(error(
                    start,
                    &format!("unknown command {:?}", char::from(cmd)),
                ));
            }
        }
        Ok(v)
    }

    /// Draws one segment of command `cmd` (at byte `start`) with its numbers `v`.
    fn draw(
        &mut self,
        cmd: u8,
        start: usize,
        v: [f64; 7],
        builder: &mut LoopBuilder,
    ) -> Result<(), IoError> {
        let rel = cmd.is_ascii_lowercase();
        let pen = builder.pen();
        let origin = if rel { pen } else { Point::new(0.0, 0.0) };
        let at = |p: Point| p + origin;
        let curve_err = |e: SplineError| IoError::PathData {
            position: start,
            message: e.to_string(),
        };
        let point = |i: usize| at(Point::new(v[i], v[i + 1]));
        let (mut new_cubic, mut new_quad) = (None, None);
        match cmd.to_ascii_uppercase() {
            b'M' => builder.move_to(point(0)),
            b'L' => builder.line_to(point(0)).map_err(curve_err)?,
            b'H' => {
                let x = v[0] + origin.x;
                builder.line_to(Point::new(x, pen.y)).map_err(curve_err)?;
            }
            b'V' => {
                let y = v[0] + origin.y;
                builder.line_to(Point::new(pen.x, y)).map_err(curve_err)?;
            }
            b'C' => {
                let (c1, c2, p) = (point(0), point(2), point(4));
                builder.bezier_to(&[c1, c2, p]).map_err(curve_err)?;
                new_cubic = Some(c2);
            }
            b'S' => {
                let c1 = self.last_cubic.map_or(pen, |c| pen * 2.0 - c);
                let (c2, p) = (point(0), point(2));
                builder.bezier_to(&[c1, c2, p]).map_err(curve_err)?;
                new_cubic = Some(c2);
            }
            b'Q' => {
                let (c, p) = (point(0), point(2));
                builder.bezier_to(&[c, p]).map_err(curve_err)?;
                new_quad = Some(c);
            }
            b'T' => {
                let c = self.last_quad.map_or(pen, |c| pen * 2.0 - c);
                let p = point(0);
                builder.bezier_to(&[c, p]).map_err(curve_err)?;
                new_quad = Some(c);
            }
            b'A' => {
                let (rx, ry, phi) = (v[0], v[1], v[2]);
                let (large, sweep) = (v[3] == 1.0, v[4] == 1.0);
                let p = point(5);
                match endpoint_arc(pen, rx, ry, phi, large, sweep, p).map_err(curve_err)? {
                    ArcSegment::Nothing => {}
                    ArcSegment::Line => builder.line_to(p).map_err(curve_err)?,
                    ArcSegment::Curve(c) => builder.curve(c),
                }
            }
            _ => builder.close(),
        }
        self.last_cubic = new_cubic;
        self.last_quad = new_quad;
        Ok(())
    }
}

fn error(position: usize, message: &str) -> IoError {
    IoError::PathData {
        position,
        message: message.to_string(),
    }
}

/// The arguments of a path command: numbers and arc flags, each after an optional `comma-wsp`.
struct Arguments<'l, 'a>(&'l mut Lexer<'a>);

impl Arguments<'_, '_> {
    /// A number of the SVG grammar (see [`Lexer::number`]).
    fn number(&mut self) -> Result<f64, IoError> {
        self.0.skip_separators();
        self.0.number().map_err(|LexError { position, kind }| {
            let message = match kind {
                LexErrorKind::NotANumber if self.0.at_end() => {
                    "path data ends where a number is expected"
                }
                other => other.message(),
            };
            error(position, message)
        })
    }

    /// An arc flag: a single `0` or `1` (no separator needed after it).
    fn flag(&mut self) -> Result<bool, IoError> {
        self.0.skip_separators();
        let start = self.0.position();
        let flag = match self.0.peek() {
            Some(b'0') => false,
            Some(b'1') => true,
            None => return Err(error(start, "path data ends where an arc flag is expected")),
            Some(_) => return Err(error(start, "an arc flag must be 0 or 1")),
        };
        self.0.bump();
        Ok(flag)
    }
}

//! The SVG `transform` attribute: a list of `matrix`, `translate`, `scale`, `rotate`, `skewX`
//! and `skewY`, applied right to left.

use rs_spline::Affine;

use super::number::{Lexer, describe};

/// Parses a transform list; the result maps element coordinates to parent coordinates.
///
/// The grammar is SVG 2's: functions separated by white space and at most one comma (or by
/// nothing), white space allowed before `(`, arguments numbers of the one SVG number grammar
/// ([`Lexer::number_list`]), so `translate(0-5)` is `translate(0, -5)`.
///
/// # Errors
/// A one-line message naming the offending function or argument.
pub(crate) fn parse_transform(text: &str) -> Result<Affine, String> {
    let mut total = Affine::IDENTITY;
    let mut lexer = Lexer::new(text);
    lexer.skip_whitespace();
    while !lexer.at_end() {
        let name_start = lexer.position();
        while lexer.peek().is_some_and(|b| b.is_ascii_alphabetic()) {
            lexer.bump();
        }
        let name = &text[name_start..lexer.position()];
        if name.is_empty() {
            return Err(format!(
                "expected a transform function at {:?}",
                lexer.token()
            ));
        }
        lexer.skip_whitespace();
        if lexer.peek() != Some(b'(') {
            return Err(format!("expected '(' after {name}"));
        }
        lexer.bump();
        let args = lexer
            .number_list(|b| b == b')')
            .map_err(|e| describe(text, name, e))?;
        if lexer.peek() != Some(b')') {
            return Err(format!("missing ')' after {name}("));
        }
        lexer.bump();
        total = total.then_apply_to(function(name, &args)?);
        lexer.skip_separators();
    }
    Ok(total)
}

/// The map of one transform function `name` with arguments `args`.
fn function(name: &str, args: &[f64]) -> Result<Affine, String> {
    let arity = |allowed: &[usize]| {
        if allowed.contains(&args.len()) {
            Ok(())
        } else {
            Err(format!(
                "{name} takes {allowed:?} arguments, got {}",
                args.len()
            ))
        }
    };
    Ok(match name {
        "matrix" => {
            arity(&[6])?;
            Affine {
                m: [args[0], args[1], args[2], args[3], args[4], args[5]],
            }
        }
        "translate" => {
            arity(&[1, 2])?;
            Affine::translate(args[0], args.get(1).copied().unwrap_or(0.0))
        }
        "scale" => {
            arity(&[1, 2])?;
            Affine::scale(args[0], args.get(1).copied().unwrap_or(args[0]))
        }
        "rotate" => {
            arity(&[1, 3])?;
            let r = Affine::rotate(args[0].to_radians());
            if args.len() == 3 {
                let (cx, cy) = (args[1], args[2]);
                Affine::translate(cx, cy)
                    .then_apply_to(r)
                    .then_apply_to(Affine::translate(-cx, -cy))
            } else {
                r
            }
        }
        "skewX" => {
            arity(&[1])?;
            Affine {
                m: [1.0, 0.0, args[0].to_radians().tan(), 1.0, 0.0, 0.0],
            }
        }
        "skewY" => {
            arity(&[1])?;
            Affine {
                m: [1.0, args[0].to_radians().tan(), 0.0, 1.0, 0.0, 0.0],
            }
        }
        other => return Err(format!("unknown transform function {other:?}")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::Point;

    #[test]
    fn list_applies_right_to_left() {
        let t = parse_transform("translate(10, 20) scale(2)").unwrap();
        assert_eq!(t.apply(Point::new(1.0, 1.0)), Point::new(12.0, 22.0));
        let r = parse_transform(" rotate(90 1 1) ").unwrap();
        let q = r.apply(Point::new(2.0, 1.0));
        assert!(q.distance(Point::new(1.0, 2.0)) < 1e-15);
        let m = parse_transform("matrix(1 0 0 -1 0 16)").unwrap();
        assert_eq!(m.apply(Point::new(3.0, 4.0)), Point::new(3.0, 12.0));
        let k = parse_transform("skewX(45)").unwrap();
        assert!(k.apply(Point::new(0.0, 1.0)).distance(Point::new(1.0, 1.0)) < 1e-15);
        assert!(parse_transform("").unwrap().is_identity());
    }

    #[test]
    fn errors_name_the_problem() {
        assert!(
            parse_transform("scale(1 2 3)")
                .unwrap_err()
                .contains("scale")
        );
        assert!(parse_transform("shear(1)").unwrap_err().contains("shear"));
        assert!(parse_transform("translate(1").unwrap_err().contains("')'"));
        assert!(parse_transform("rotate(x)").unwrap_err().contains("\"x\""));
    }

    /// Separators are optional where the number grammar ends a number by itself.
    #[test]
    fn arguments_follow_the_svg_number_grammar() {
        let p = Point::new(3.0, 4.0);
        for (text, want) in [
            ("translate(0-1036.36)", Point::new(3.0, 4.0 - 1036.36)),
            ("scale(1-1)", Point::new(3.0, -4.0)),
            ("matrix(1 0 0 1 0-5)", Point::new(3.0, -1.0)),
            ("matrix(1,0,0,1,0,-5)", Point::new(3.0, -1.0)),
            ("translate(1e-3 1E+2)", Point::new(3.001, 104.0)),
            ("translate(.5.5)", Point::new(3.5, 4.5)),
            ("translate (1)scale(2),scale(1 1)", Point::new(7.0, 8.0)),
            ("\n translate( 1 , 2 ) \t", Point::new(4.0, 6.0)),
        ] {
            let q = parse_transform(text).unwrap().apply(p);
            assert!(q.distance(want) < 1e-12, "{text}: {q:?}");
        }
        // About (0.5, 0.5): (1.5, 0.5) goes to (0.5, 1.5).
        let r = parse_transform("rotate(90 .5.5)").unwrap();
        assert!(r.apply(Point::new(1.5, 0.5)).distance(Point::new(0.5, 1.5)) < 1e-15);
    }

    #[test]
    fn garbage_is_refused_with_one_line() {
        for (text, want) in [
            ("translate(1 x)", r#"translate: "x" is not a number"#),
            (
                "translate(1,)",
                "translate: a comma with no number after it (byte 12)",
            ),
            ("translate(1,,2)", r#"translate: "," is not a number"#),
            ("scale(1e999)", r#"scale: "1e999" is out of range"#),
            ("translate(1 2", "missing ')' after translate("),
            ("translate", "expected '(' after translate"),
            ("(1 2)", r#"expected a transform function at "(""#),
            ("translate(1) 3", r#"expected a transform function at "3""#),
            ("rotate(1 2)", "rotate takes [1, 3] arguments, got 2"),
        ] {
            assert_eq!(parse_transform(text).unwrap_err(), want, "{text}");
        }
    }
}

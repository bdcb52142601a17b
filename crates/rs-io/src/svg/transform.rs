//! The SVG `transform` attribute: a list of `matrix`, `translate`, `scale`, `rotate`, `skewX`
//! and `skewY`, applied right to left.

use rs_spline::Affine;

/// Parses a transform list; the result maps element coordinates to parent coordinates.
///
/// # Errors
/// A message naming the offending function or argument.
pub(crate) fn parse_transform(text: &str) -> Result<Affine, String> {
    let mut total = Affine::IDENTITY;
    let mut rest = text.trim_start_matches(is_separator);
    while !rest.is_empty() {
        let open = rest
            .find('(')
            .ok_or_else(|| format!("expected '(' after {:?}", rest.trim()))?;
        let name = rest[..open].trim();
        let close = rest[open..]
            .find(')')
            .map(|i| i + open)
            .ok_or_else(|| format!("missing ')' after {name}("))?;
        let args = number_list(&rest[open + 1..close], name)?;
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
        let m = match name {
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
        };
        total = total.then_apply_to(m);
        rest = rest[close + 1..].trim_start_matches(is_separator);
    }
    Ok(total)
}

/// Numbers separated by commas and/or white space; `what` names the list in errors.
pub(crate) fn number_list(text: &str, what: &str) -> Result<Vec<f64>, String> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("{what}: {s:?} is not a number"))
        })
        .collect()
}

fn is_separator(c: char) -> bool {
    c == ',' || c.is_whitespace()
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
}

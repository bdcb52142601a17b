//! `--function EXPR`: a formula in `x` and `y`, parsed once by `exmex` and evaluated many
//! times (`+ - * / ^`, parentheses, `pi`, `e`, and `sin cos tan exp log sqrt abs` among
//! others).

use exmex::prelude::*;
use inrs::Point;

/// The longest formula accepted.
const MAX_FORMULA_BYTES: usize = 4096;

/// What each of the formula's variables stands for.
#[derive(Clone, Copy, Debug)]
enum Variable {
    X,
    Y,
    Pi,
}

/// A parsed formula of the plane.
#[derive(Debug)]
pub(crate) struct Function {
    expr: FlatEx<f64>,
    variables: Vec<Variable>,
}

impl Function {
    /// Parses `text`; its only variables may be `x` and `y` (and `pi`, the constant).
    pub(crate) fn parse(text: &str) -> Result<Self, String> {
        if text.len() > MAX_FORMULA_BYTES {
            return Err(format!("formula longer than {MAX_FORMULA_BYTES} bytes"));
        }
        let expr = exmex::parse::<f64>(text).map_err(|e| format!("formula {text:?}: {e}"))?;
        let variables = expr
            .var_names()
            .iter()
            .map(|v| match v.as_str() {
                "x" => Ok(Variable::X),
                "y" => Ok(Variable::Y),
                "pi" => Ok(Variable::Pi),
                other => Err(format!(
                    "formula {text:?}: unknown name {other:?} (the variables are x and y)"
                )),
            })
            .collect::<Result<_, _>>()?;
        Ok(Self { expr, variables })
    }

    /// The value at `p` (NaN where the formula fails).
    pub(crate) fn at(&self, p: Point) -> f64 {
        let values: Vec<f64> = self
            .variables
            .iter()
            .map(|v| match v {
                Variable::X => p.x,
                Variable::Y => p.y,
                Variable::Pi => std::f64::consts::PI,
            })
            .collect();
        self.expr.eval(&values).unwrap_or(f64::NAN)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formulas_in_x_and_y() {
        let f = Function::parse("sin(10*x) + sin(10*y)").unwrap();
        let p = Point::new(0.3, -0.2);
        assert!((f.at(p) - ((3.0f64).sin() + (-2.0f64).sin())).abs() < 1e-15);
        let g = Function::parse("sqrt(abs(x)) * e + pi - log(y) + x^2 / tan(y)").unwrap();
        let q = Point::new(-4.0, 0.5);
        let want =
            2.0 * std::f64::consts::E + std::f64::consts::PI - 0.5f64.ln() + 16.0 / 0.5f64.tan();
        assert!((g.at(q) - want).abs() < 1e-12);
        assert_eq!(Function::parse("y").unwrap().at(q), 0.5);
        assert!(Function::parse("2 + 3").unwrap().at(q) == 5.0);
        for bad in ["sin(", "z + 1", "x +* y", &"1+".repeat(5000)] {
            assert!(Function::parse(bad).is_err(), "{bad}");
        }
    }
}

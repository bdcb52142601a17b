//! The kinds of conics, each with its parameterisation.

use std::fmt;

/// The kind of a [`Conic`](crate::Conic), which fixes its parameterisation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConicKind {
    /// `(cos t, sin t)`: ellipses and circles, period `2 pi`.
    Ellipse,
    /// `(cosh t, sinh t)`: one branch of a hyperbola.
    Hyperbola,
    /// `(t^2, 2 t)`: a parabola.
    Parabola,
}

impl ConicKind {
    /// `(f, f', f'')` and `(g, g', g'')` at `t`.
    pub(crate) fn basis(self, t: f64) -> ([f64; 3], [f64; 3]) {
        match self {
            ConicKind::Ellipse => {
                let (s, c) = t.sin_cos();
                ([c, -s, -c], [s, c, -s])
            }
            ConicKind::Hyperbola => {
                let (s, c) = (t.sinh(), t.cosh());
                ([c, s, c], [s, c, s])
            }
            ConicKind::Parabola => ([t * t, 2.0 * t, 2.0], [2.0 * t, 2.0, 0.0]),
        }
    }
}

impl fmt::Display for ConicKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ConicKind::Ellipse => "ellipse",
            ConicKind::Hyperbola => "hyperbola",
            ConicKind::Parabola => "parabola",
        })
    }
}

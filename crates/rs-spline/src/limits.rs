//! Documented limits on curve data.
//!
//! Every limit is checked where the data enters ([`crate::NurbsCurve::new`],
//! [`crate::RationalBezier::new`], the primitives) and reported as
//! [`crate::SplineError::LimitExceeded`] (or a more specific error) instead of letting a
//! computation overflow, lose every digit or allocate without bound.

/// The largest curve degree accepted. Crossing solves and tight boxes work with derivative
/// numerators of degree `2p - 2`; beyond this, binomial weights and power-basis coefficients
/// lose the digits the root finders need.
pub const MAX_DEGREE: usize = 32;

/// The largest absolute value of a control-point coordinate. Areas, cross products and
/// squared distances multiply two coordinates, so `1e150` keeps every such product finite
/// (below `1e300`) with room for the quadrature's sums.
pub const MAX_COORDINATE: f64 = 1e150;

/// The largest ratio `max w_i / min w_i` of the weights of one curve. Weights are homogeneous
/// (scaling them all changes nothing), but their spread skews the parametrisation: with a
/// spread `r` a piece of degree `p` is traversed in a parameter interval of width about
/// `r^(-1/p)`, and beyond `1e12` the tangency roots and crossing solves no longer resolve it
/// in double precision. Uniformly huge or tiny weights (all near `1e50`, or `1e-300`) are
/// fine: they are rescaled exactly by a power of two.
pub const MAX_WEIGHT_RATIO: f64 = 1e12;

/// The most quarter-turn pieces a circular or elliptic arc may have (`|sweep| <= 1024 * 2 pi`,
/// 4096 rational quadratic pieces).
pub const MAX_ARC_PIECES: usize = 4096;

/// The largest input file read (domain files, SVG, DXF, fonts, curve files): 256 MiB. Points
/// files are streamed and have no size limit.
pub const MAX_FILE_BYTES: u64 = 256 << 20;

/// Reads a whole file of at most [`MAX_FILE_BYTES`].
///
/// # Errors
/// The I/O error, or one of kind [`std::io::ErrorKind::FileTooLarge`] naming the limit.
pub fn read_file(path: &std::path::Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let file = std::fs::File::open(path)?;
    let mut data = Vec::new();
    file.take(MAX_FILE_BYTES + 1).read_to_end(&mut data)?;
    if data.len() as u64 > MAX_FILE_BYTES {
        return Err(std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            format!("larger than {} MiB (the limit)", MAX_FILE_BYTES >> 20),
        ));
    }
    Ok(data)
}

/// Reads a whole UTF-8 text file of at most [`MAX_FILE_BYTES`].
///
/// # Errors
/// As [`read_file`], or [`std::io::ErrorKind::InvalidData`] for text that is not UTF-8.
pub fn read_text_file(path: &std::path::Path) -> std::io::Result<String> {
    String::from_utf8(read_file(path)?).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to() + 1),
        )
    })
}

/// A number that is finite and `>= 0`: every tolerance, relative tolerance and size a user
/// gives, checked once where it enters ([`NonNegative::new`]) so that code holding one needs
/// no second check.
///
/// ```
/// use rs_spline::limits::NonNegative;
/// assert_eq!(NonNegative::new(1e-9).map(NonNegative::get), Ok(1e-9));
/// assert!(NonNegative::new(-1.0).is_err());
/// assert!(NonNegative::new(f64::NAN).is_err());
/// assert_eq!(NonNegative::new(f64::INFINITY).unwrap_err().to_string(), "inf must be finite and >= 0");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct NonNegative(f64);

/// A number that should have been finite and `>= 0` (its value is kept for the message).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("{0} must be finite and >= 0")]
pub struct NotNonNegative(pub f64);

impl NonNegative {
    /// Zero.
    pub const ZERO: NonNegative = NonNegative(0.0);

    /// `value` if it is finite and `>= 0`.
    ///
    /// # Errors
    /// [`NotNonNegative`] with the value for a negative, NaN or infinite one.
    pub fn new(value: f64) -> Result<NonNegative, NotNonNegative> {
        if value.is_finite() && value >= 0.0 {
            Ok(NonNegative(value))
        } else {
            Err(NotNonNegative(value))
        }
    }

    /// The number.
    pub fn get(self) -> f64 {
        self.0
    }
}

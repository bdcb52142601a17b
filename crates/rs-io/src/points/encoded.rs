//! Points as a `.npy` array stores them ([`EncodedPoints`], of an [`NpyType`]): what a
//! `.npy` run of points holds, read by index without a copy.

use rs_spline::Point;

use super::PointsError;

/// The element types read and written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NpyType {
    /// `<f8`: little-endian float64.
    F64,
    /// `<f4`: little-endian float32 (read only; converted exactly to float64).
    F32,
    /// `|i1`: int8.
    I8,
}

impl NpyType {
    /// The `descr` string.
    pub fn descr(self) -> &'static str {
        match self {
            NpyType::F64 => "<f8",
            NpyType::F32 => "<f4",
            NpyType::I8 => "|i1",
        }
    }

    /// Bytes per element.
    pub fn size(self) -> usize {
        match self {
            NpyType::F64 => 8,
            NpyType::F32 => 4,
            NpyType::I8 => 1,
        }
    }
}

/// Points as a `.npy` array stores them: pairs of `f64` or `f32`, little-endian, every
/// coordinate checked finite. Read one at a time by [`EncodedPoints::point`] (for instance by a
/// locator's indexed query), so that they need not be copied into a `Vec<Point>` first.
///
/// # Examples
///
/// ```
/// use rs_io::points::{NpyReader, NpyType, PointRun, PointsReader, RunPoints, RunSizes, npy_header};
/// let mut bytes = npy_header(NpyType::F32, &[2, 2]);
/// for v in [0.5f32, 1.0, -2.0, 3.25] {
///     bytes.extend_from_slice(&v.to_le_bytes());
/// }
/// let reader = NpyReader::new(&bytes[..], "mem", RunSizes::default()).unwrap();
/// let mut run = PointRun::default();
/// reader.next_run(&mut run).unwrap().1.unwrap();
/// let RunPoints::Npy(pts) = run.points() else { panic!("a .npy run") };
/// assert_eq!(pts.len(), 2);
/// assert_eq!(pts.point(1), rs_spline::Point::new(-2.0, 3.25));
/// ```
#[derive(Clone, Copy, Debug)]
pub struct EncodedPoints<'a> {
    ty: NpyType,
    bytes: &'a [u8],
}

/// Whether every little-endian `ty` number in `bytes` is finite: no exponent field all ones,
/// tested for all of them without a branch or a comparison (the compiler vectorises it with
/// the baseline instructions; the search for the first bad point runs only if there is one).
/// The exponent field masked out and its lowest bit added carries into the sign bit exactly
/// when the field is all ones; the sums' bits are or-ed together and the sign bit read once.
fn all_finite(ty: NpyType, bytes: &[u8]) -> bool {
    fn none_all_ones<const N: usize>(
        bytes: &[u8],
        exponent: u64,
        bits: impl Fn([u8; N]) -> u64,
    ) -> bool {
        // The lowest bit of the field, and the sign bit the carry reaches.
        let (low, sign) = (exponent & exponent.wrapping_neg(), 1u64 << (8 * N - 1));
        let mut carries = 0u64;
        for c in bytes.chunks_exact(N) {
            let mut a = [0u8; N];
            a.copy_from_slice(c);
            carries |= (bits(a) & exponent) + low;
        }
        carries & sign == 0
    }
    if ty == NpyType::F32 {
        none_all_ones::<4>(bytes, 0x7f80_0000, |b| u64::from(u32::from_le_bytes(b)))
    } else {
        none_all_ones::<8>(bytes, 0x7ff0_0000_0000_0000, u64::from_le_bytes)
    }
}

impl<'a> EncodedPoints<'a> {
    /// The points encoded in `bytes` (pairs of `ty`, a whole number of them), the first being
    /// point `first` of the file `path` (for the error naming a non-finite coordinate).
    pub(super) fn checked(
        ty: NpyType,
        bytes: &'a [u8],
        first: usize,
        path: &str,
    ) -> Result<Self, PointsError> {
        let points = Self { ty, bytes };
        if all_finite(ty, bytes) {
            return Ok(points);
        }
        if let Some(i) = (0..points.len()).find(|&i| {
            let p = points.point(i);
            !(p.x.is_finite() && p.y.is_finite())
        }) {
            return Err(PointsError::Npy {
                path: path.to_string(),
                message: format!("point {} is not finite: {:?}", first + i, points.point(i)),
            });
        }
        Ok(points)
    }

    /// The points encoded in `bytes` (pairs of `ty`, a whole number of them), already checked
    /// finite by [`EncodedPoints::checked`].
    pub(super) fn from_checked(ty: NpyType, bytes: &'a [u8]) -> Self {
        Self { ty, bytes }
    }

    /// The number of points.
    #[inline]
    pub fn len(&self) -> usize {
        self.bytes.len() / (2 * self.ty.size())
    }

    /// True if there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Point `i` (`float32` coordinates converted exactly).
    ///
    /// # Panics
    /// If `i >= self.len()`.
    #[inline]
    pub fn point(&self, i: usize) -> Point {
        if self.ty == NpyType::F32 {
            f32_pair(&self.bytes[8 * i..8 * i + 8])
        } else {
            f64_pair(&self.bytes[16 * i..16 * i + 16])
        }
    }
}

/// The point of 8 bytes `c`: two little-endian float32 coordinates, converted exactly.
#[inline(always)]
fn f32_pair(c: &[u8]) -> Point {
    let v = |b: &[u8]| f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]));
    Point::new(v(&c[..4]), v(&c[4..8]))
}

/// The point of 16 bytes `c`: two little-endian float64 coordinates.
#[inline(always)]
fn f64_pair(c: &[u8]) -> Point {
    let v = |b: &[u8]| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]);
    Point::new(v(&c[..8]), v(&c[8..16]))
}

/// Queries read the points by index straight from the bytes.
impl rs_spline::PointSource for EncodedPoints<'_> {
    #[inline]
    fn len(&self) -> usize {
        EncodedPoints::len(self)
    }
    #[inline]
    fn point(&self, i: usize) -> Point {
        EncodedPoints::point(self, i)
    }

    /// The block's element type decided once, its points decoded in one loop.
    #[inline]
    fn points_into(&self, first: usize, out: &mut [Point]) {
        let size = 2 * self.ty.size();
        let bytes = &self.bytes[first * size..(first + out.len()) * size];
        if self.ty == NpyType::F32 {
            for (q, c) in out.iter_mut().zip(bytes.chunks_exact(8)) {
                *q = f32_pair(c);
            }
        } else {
            for (q, c) in out.iter_mut().zip(bytes.chunks_exact(16)) {
                *q = f64_pair(c);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The branch-free scan says what `is_finite` says of every number, wherever the bad one
    /// stands, for both widths (including the largest, the smallest normal and subnormal
    /// values, and NaN of either sign).
    #[test]
    fn the_finiteness_scan_agrees_with_is_finite() {
        let specials = [
            0.0,
            -0.0,
            1.5,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            3.4e38,
            f64::NAN,
            -f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for v in specials {
            for at in 0..7 {
                let mut xs = [1.0f64; 7];
                xs[at] = v;
                let wide: Vec<u8> = xs.iter().flat_map(|x| x.to_le_bytes()).collect();
                assert_eq!(
                    all_finite(NpyType::F64, &wide),
                    v.is_finite(),
                    "{v} at {at}"
                );
                let narrow: Vec<u8> = xs.iter().flat_map(|&x| (x as f32).to_le_bytes()).collect();
                let v32 = v as f32;
                assert_eq!(
                    all_finite(NpyType::F32, &narrow),
                    v32.is_finite(),
                    "{v32} at {at}"
                );
            }
        }
    }

    /// A block decoded at once is the points one by one, for both widths, from any first
    /// point (a float32 block converted exactly).
    #[test]
    fn a_block_of_points_is_its_points_one_by_one() {
        use rs_spline::PointSource;
        let coords: Vec<f64> = (0..22).map(|i| (i as f64 - 7.5) * 0.37e-3).collect();
        let wide: Vec<u8> = coords.iter().flat_map(|x| x.to_le_bytes()).collect();
        let narrow: Vec<u8> = coords
            .iter()
            .flat_map(|&x| (x as f32).to_le_bytes())
            .collect();
        for (ty, bytes) in [(NpyType::F64, &wide), (NpyType::F32, &narrow)] {
            let points = EncodedPoints::from_checked(ty, bytes);
            assert_eq!(points.len(), 11);
            for first in 0..points.len() {
                let mut block = vec![Point::default(); points.len() - first];
                points.points_into(first, &mut block);
                for (k, q) in block.iter().enumerate() {
                    assert_eq!(*q, points.point(first + k), "{ty:?} from {first}");
                }
            }
        }
        let mut block = [Point::default(); 2];
        EncodedPoints::from_checked(NpyType::F32, &narrow).points_into(3, &mut block);
        assert_eq!(
            block[1],
            Point::new(f64::from(coords[8] as f32), f64::from(coords[9] as f32))
        );
    }
}

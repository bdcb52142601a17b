//! Covered lengths along one grid line, from its sorted crossings with the boundary.

use std::ops::Range;

/// Per column of a line: the covered length and, when asked for, its first and second
/// moments about the column's start, `int (s - edges[c]) ds` and `int (s - edges[c])^2 ds`
/// over the covered part.
pub(crate) struct LineSums<'a> {
    pub(crate) len: &'a mut [f64],
    pub(crate) first: Option<&'a mut [f64]>,
    pub(crate) second: Option<&'a mut [f64]>,
    /// The moments of the columns an interval covers from edge to edge are added too; if
    /// not, they are left alone and their reader takes `w^2 / 2` and `w^3 / 3` wherever the
    /// length is the width `w` ([`full_column_moments`]).
    pub(crate) full_columns: bool,
}

/// The moments `(w^2 / 2, w^3 / 3)` of a column of width `w` covered from edge to edge: what
/// [`LineSums`] adds for such a column (or leaves to its reader).
#[inline]
pub(crate) fn full_column_moments(w: f64) -> (f64, f64) {
    (0.5 * (w * w), w * w * w / 3.0)
}

/// The first and second moments of column `i` (width `w`, covered length `len`) of a line
/// summed into `first` and `second` (empty when not summed: 0) by [`add_covered`], with
/// `full_columns` as it was there: without, a column covered from edge to edge takes
/// [`full_column_moments`].
#[inline]
pub(crate) fn column_moments(
    (first, second): (&[f64], &[f64]),
    i: usize,
    (len, w): (f64, f64),
    full_columns: bool,
) -> (f64, f64) {
    if !full_columns && len == w {
        return full_column_moments(w);
    }
    (
        first.get(i).copied().unwrap_or(0.0),
        second.get(i).copied().unwrap_or(0.0),
    )
}

/// The covered fraction of an annulus face swept about an axis by an interval of length
/// `width` starting at the radius `r0`, from its covered length `len` and that part's first
/// moment `first` about `r0`: `int r dr` over the covered part over the interval's.
#[inline]
pub(crate) fn annulus_fraction(r0: f64, width: f64, len: f64, first: f64) -> f64 {
    (r0 * len + first) / (width * (r0 + 0.5 * width))
}

/// Adds to `sums.len[c]` the length of the covered part of `[edges[c], edges[c + 1]]` on a
/// line whose status is `inside` before its first crossing and flips at each crossing
/// (`crossings` sorted ascending; an odd count leaves the line covered to `+inf`), and to
/// `first` and `second` that part's moments ([`LineSums`]).
///
/// A column covered from edge to edge gets exactly `edges[c + 1] - edges[c]`. The columns
/// each covered interval meets are pushed to `touched` as a range (ascending; consecutive
/// ranges may share a column); the others are left alone. The work is one binary search per
/// covered interval plus one step per column it meets.
pub(crate) fn add_covered(
    edges: &[f64],
    crossings: &[f64],
    mut inside: bool,
    sums: &mut LineSums<'_>,
    touched: &mut Vec<Range<usize>>,
) {
    let mut start = f64::NEG_INFINITY;
    for &c in crossings {
        if inside {
            add_interval(edges, (start, c), sums, touched);
        } else {
            start = c;
        }
        inside = !inside;
    }
    if inside {
        add_interval(edges, (start, f64::INFINITY), sums, touched);
    }
}

/// Adds the covered interval `[a, b]` to the columns it meets (see [`add_covered`]).
fn add_interval(
    edges: &[f64],
    (a, b): (f64, f64),
    sums: &mut LineSums<'_>,
    touched: &mut Vec<Range<usize>>,
) {
    let LineSums {
        len,
        first,
        second,
        full_columns,
    } = sums;
    let last = edges.len() - 1;
    if b <= a || b.is_nan() || b <= edges[0] || a >= edges[last] {
        return;
    }
    // The columns meeting the interval: from the one holding `a` (or the first when `a` is
    // left of the grid) to the last whose left edge is below `b`.
    let c_first = edges.partition_point(|&e| e <= a).saturating_sub(1);
    let c_end = edges.partition_point(|&e| e < b).min(last);
    let mut add = |c: usize| {
        let (e0, e1) = (edges[c], edges[c + 1]);
        let (lo, hi) = (a.max(e0), b.min(e1));
        if hi > lo {
            len[c] += hi - lo;
            let (u0, u1) = (lo - e0, hi - e0);
            if let Some(f) = first.as_deref_mut() {
                f[c] += 0.5 * (u1 * u1 - u0 * u0);
            }
            if let Some(s) = second.as_deref_mut() {
                s[c] += (u1 * u1 * u1 - u0 * u0 * u0) / 3.0;
            }
        }
    };
    add(c_first);
    if c_end > c_first + 1 {
        add(c_end - 1);
        // The columns between are covered from edge to edge (`lo = e0`, `hi = e1` above).
        let (lo, hi) = (c_first + 1, c_end - 1);
        let widths = || {
            edges[lo + 1..=hi]
                .iter()
                .zip(&edges[lo..hi])
                .map(|(e1, e0)| e1 - e0)
        };
        for (l, w) in len[lo..hi].iter_mut().zip(widths()) {
            *l += w;
        }
        if !*full_columns {
            touched.push(c_first..c_end);
            return;
        }
        if let Some(f) = first.as_deref_mut() {
            for (f, w) in f[lo..hi].iter_mut().zip(widths()) {
                *f += full_column_moments(w).0;
            }
        }
        if let Some(s) = second.as_deref_mut() {
            for (s, w) in s[lo..hi].iter_mut().zip(widths()) {
                *s += full_column_moments(w).1;
            }
        }
    }
    touched.push(c_first..c_end);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intervals_are_split_over_columns() {
        let edges = [0.0, 1.0, 2.0, 4.0];
        let mut len = [0.0; 3];
        let mut first = [0.0; 3];
        let mut second = [0.0; 3];
        // Covered on [-1, 0.5] and [1.5, 3] and from 3.5 on.
        let mut touched = Vec::new();
        let mut sums = LineSums {
            len: &mut len,
            first: Some(&mut first),
            second: Some(&mut second),
            full_columns: true,
        };
        add_covered(
            &edges,
            &[-1.0, 0.5, 1.5, 3.0, 3.5],
            false,
            &mut sums,
            &mut touched,
        );
        assert_eq!(len, [0.5, 0.5, 1.5]);
        // int s^2 ds from the column's start: [0, 0.5]; [0.5, 1]; [0, 1] and [1.5, 2].
        let cube = |a: f64, b: f64| (b * b * b - a * a * a) / 3.0;
        assert_eq!(
            second,
            [
                cube(0.0, 0.5),
                cube(0.5, 1.0),
                cube(0.0, 1.0) + cube(1.5, 2.0)
            ]
        );
        // [-1, 0.5] meets column 0, [1.5, 3] columns 1 and 2, [3.5, inf) column 2.
        assert_eq!(touched, [0..1, 1..3, 2..3]);
        assert_eq!(first, [0.125, 0.5 * (1.0 - 0.25), 0.5 * (1.0 + 4.0 - 2.25)]);
        // Inside before the first crossing: covered up to 0.25, then from 3 on.
        fn plain(len: &mut [f64; 3]) -> LineSums<'_> {
            LineSums {
                len,
                first: None,
                second: None,
                full_columns: true,
            }
        }
        let mut len = [0.0; 3];
        add_covered(
            &edges,
            &[0.25, 3.0],
            true,
            &mut plain(&mut len),
            &mut Vec::new(),
        );
        assert_eq!(len, [0.25, 0.0, 1.0]);
        // Two crossings at one point (a tangency) change nothing.
        let mut len = [0.0; 3];
        add_covered(
            &edges,
            &[1.5, 1.5],
            true,
            &mut plain(&mut len),
            &mut Vec::new(),
        );
        assert_eq!(len, [1.0, 1.0, 2.0]);
        // Nothing when the line is outside throughout.
        let (mut len, mut touched) = ([0.0; 3], Vec::new());
        add_covered(&edges, &[], false, &mut plain(&mut len), &mut touched);
        assert_eq!(len, [0.0; 3]);
        assert!(touched.is_empty());
    }
}

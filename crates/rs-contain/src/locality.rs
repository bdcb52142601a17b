//! A locality order for a batch of query points: the points cell by cell along a Z-order
//! (Morton) curve over a grid on the queried set's box, so that points answered one after the
//! other lie near each other. Their queries then read the same parts of an index (still in
//! the cache) and take the same branches (which the processor has learnt). Answering in this
//! order and writing each answer to its point's place changes no answer, only the time (see
//! the winding-number field's batches, its first user).

use rs_spline::Point;

/// Points per cell the grid aims at (its cells per side a power of two).
const POINTS_PER_CELL: usize = 4;

/// Most cells per side: `2^6`. (Measured on the GWN paper's shapes with 10^5 points in
/// blocks of `2^15`: `2^5` to `2^7` cells a side within a few percent; the cells' counts then
/// stay in the first-level cache.) At most 8, so a cell's Z-order index fits 16 bits.
const MAX_SIDE_BITS: u32 = 6;

/// The first points of a batch that tell whether it comes in an order of its own.
const SAMPLE: usize = 128;

/// Fewer points than this are taken in their own order: the grid would cost more than it
/// saves.
pub(crate) const MIN_ORDERED: usize = 64;

/// `order` <- the indices `0..n` of the points `point(i)`, cell by cell along the Z-order
/// curve of a grid of `2^b x 2^b` cells over the box `[lo, hi]` (about [`POINTS_PER_CELL`]
/// points a cell, at most `2^`[`MAX_SIDE_BITS`] cells a side), in input order within a cell;
/// in input order for fewer than [`MIN_ORDERED`] points, and for points whose first
/// [`SAMPLE`] change cell at most a quarter of the time (they come in an order of their own:
/// a grid row by row was 20-30% slower reordered). A point outside the box counts in
/// the nearest border cell, a NaN coordinate as the lowest; a box of no width (or height) has
/// one column (row). Two passes over the points and one over the cells (a counting sort):
/// about 5 ns a point.
pub(crate) fn locality_order(
    n: usize,
    point: impl Fn(usize) -> Point,
    lo: Point,
    hi: Point,
    order: &mut Vec<u32>,
) {
    order.clear();
    if n < MIN_ORDERED {
        order.extend(0..n as u32);
        return;
    }
    let bits = side_bits(n);
    let side = 1usize << bits;
    let last = (side - 1) as f64;
    let per_unit = |lo: f64, hi: f64| {
        let s = side as f64 / (hi - lo);
        if s.is_finite() && s > 0.0 { s } else { 0.0 }
    };
    let (sx, sy) = (per_unit(lo.x, hi.x), per_unit(lo.y, hi.y));
    // `max` then `min` take NaN to 0 (`f64::max` returns the number), then the cast floors.
    let coordinate = |v: f64, lo: f64, s: f64| ((v - lo) * s).max(0.0).min(last) as u32 as usize;
    let cell = |p: Point| {
        INTERLEAVED[coordinate(p.x, lo.x, sx)] | INTERLEAVED[coordinate(p.y, lo.y, sy)] << 1
    };
    // Points that come in an order of their own (a grid row by row, a curve's samples along
    // it) are taken as they come: their first ones seldom change cell.
    let mut previous = cell(point(0));
    let changes = (1..SAMPLE.min(n))
        .filter(|&i| {
            let c = cell(point(i));
            std::mem::replace(&mut previous, c) != c
        })
        .count();
    if changes <= SAMPLE / 4 {
        order.extend(0..n as u32);
        return;
    }
    let mut starts = vec![0u32; side * side + 1];
    let cells: Vec<u16> = (0..n)
        .map(|i| {
            let c = cell(point(i));
            starts[usize::from(c) + 1] += 1;
            c
        })
        .collect();
    for c in 0..side * side {
        starts[c + 1] += starts[c];
    }
    order.resize(n, 0);
    for (i, &c) in cells.iter().enumerate() {
        let slot = &mut starts[usize::from(c)];
        order[*slot as usize] = i as u32;
        *slot += 1;
    }
}

/// `b` of the `2^b x 2^b` grid for `n` points: the least with at most [`POINTS_PER_CELL`]
/// points a cell, at most [`MAX_SIDE_BITS`].
fn side_bits(n: usize) -> u32 {
    let cells = n.div_ceil(POINTS_PER_CELL).max(1);
    // 4^b >= cells.
    let b = cells.next_power_of_two().trailing_zeros().div_ceil(2);
    b.min(MAX_SIDE_BITS)
}

/// The bits of `v` (below `2^8`) spread to the even positions: `b7 0 b6 0 ... b0`.
const fn interleave(v: usize) -> u16 {
    let mut v = v & 0xff;
    v = (v | v << 4) & 0x0f0f;
    v = (v | v << 2) & 0x3333;
    ((v | v << 1) & 0x5555) as u16
}

/// [`interleave`] of every cell coordinate.
const INTERLEAVED: [u16; 1 << MAX_SIDE_BITS] = {
    let mut t = [0; 1 << MAX_SIDE_BITS];
    let mut v = 0;
    while v < t.len() {
        t[v] = interleave(v);
        v += 1;
    }
    t
};

#[cfg(test)]
mod tests {
    use super::*;

    fn random_points(count: usize, seed: u64) -> Vec<Point> {
        let mut rng = rs_testkit::XorShift64::new(seed);
        (0..count)
            .map(|_| Point::new(rng.next_f64(), rng.next_f64()))
            .collect()
    }

    /// Every index comes once, for batches of every kind: random points with some outside the
    /// box, on its border and not numbers; fewer than the order takes are in input order.
    #[test]
    fn every_index_comes_once() {
        let (lo, hi) = (Point::new(-1.0, -2.0), Point::new(3.0, 2.0));
        for n in [0, 1, 63, 64, 65, 1000, 70_000] {
            let mut points = random_points(n, n as u64 + 1);
            for (i, p) in points.iter_mut().enumerate() {
                *p = match i % 7 {
                    0 => Point::new(f64::NAN, p.y),
                    1 => Point::new(10.0 * p.x, -5.0),
                    2 => Point::new(hi.x, lo.y),
                    _ => Point::new(lo.x + 4.0 * p.x, lo.y + 4.0 * p.y),
                };
            }
            let mut order = Vec::new();
            locality_order(n, |i| points[i], lo, hi, &mut order);
            assert_eq!(order.len(), n);
            let mut seen = vec![false; n];
            for &i in &order {
                assert!(!seen[i as usize], "{n}: {i} twice");
                seen[i as usize] = true;
            }
            if n < MIN_ORDERED {
                assert!(order.iter().enumerate().all(|(k, &i)| k == i as usize));
            }
        }
    }

    /// Random points come cell by cell along the Z-order curve, so consecutive ones lie close
    /// (the mean step a small fraction of the input order's); a grid row by row, whose first
    /// points seldom change cell, comes as it is.
    #[test]
    fn random_points_come_by_cells_and_a_grid_as_it_is() {
        let points = random_points(20_000, 12345);
        let (lo, hi) = (Point::new(0.0, 0.0), Point::new(1.0, 1.0));
        let mut order = Vec::new();
        locality_order(points.len(), |i| points[i], lo, hi, &mut order);
        let mean_step = |v: &[Point]| {
            v.windows(2).map(|w| (w[1] - w[0]).length()).sum::<f64>() / (v.len() - 1) as f64
        };
        let ordered: Vec<Point> = order.iter().map(|&i| points[i as usize]).collect();
        let (before, after) = (mean_step(&points), mean_step(&ordered));
        assert!(after < before / 20.0, "{after} vs {before}");
        let side = 1usize << side_bits(points.len());
        let cell = |p: Point| {
            let c = |v: f64| ((v * side as f64) as usize).min(side - 1);
            INTERLEAVED[c(p.x)] | INTERLEAVED[c(p.y)] << 1
        };
        assert!(ordered.windows(2).all(|w| cell(w[0]) <= cell(w[1])));
        let grid: Vec<Point> = (0..300 * 300)
            .map(|k| Point::new((k % 300) as f64 / 299.0, (k / 300) as f64 / 299.0))
            .collect();
        locality_order(grid.len(), |i| grid[i], lo, hi, &mut order);
        assert!(order.iter().enumerate().all(|(k, &i)| k == i as usize));
    }

    #[test]
    fn grid_sides_and_interleaving() {
        assert_eq!(side_bits(64), 2); // 16 cells of 4 points.
        assert_eq!(side_bits(65), 3);
        assert_eq!(side_bits(16_384), 6);
        assert_eq!(side_bits(usize::MAX / 2), MAX_SIDE_BITS);
        assert_eq!(interleave(0b1011), 0b100_0101);
        assert_eq!(interleave(0xff), 0x5555);
        assert!((0..1 << MAX_SIDE_BITS).all(|v| INTERLEAVED[v] == interleave(v)));
    }
}

//! One band of rows: the boundary's crossings with the band's grid lines, its parts in the
//! band's cells, and from them the cells' fractions, centroids and the faces' apertures.
//!
//! For row `j` (height `h`) and column `i` (width `w`), Green's theorem on the strip of column
//! `i` with `g(y) = min(y, y_{j+1}) - min(y, y_j)` gives the covered area of the cell as
//! `h L - sum b`, where `L` is the covered length of the cell's top face (the line
//! `y = y_{j+1}` just above it, where `-int dx` over the boundary above the line adds up to
//! the covered length) and `b = int (y - y_j) dx` over the boundary's parts inside the cell,
//! each oriented with the region on its left. So only the parts inside the band's cells and
//! the crossings with the band's horizontal lines are needed: the work is that of the band.

use std::ops::Range;

use rs_boxes::Monotonicity;
use rs_spline::Point;

use crate::arc::{Arc, PartIntegrals, Rules};
use crate::lines::add_covered;

/// Where a band writes its results: row-major slices of the caller's arrays, the fractions
/// and centroids zeroed.
pub(crate) struct BandOut<'a> {
    /// `(rows, nx)`; holds the sum of the parts' `b` until the end.
    pub(crate) fractions: &'a mut [f64],
    /// `(rows, nx)`; holds the sums of the parts' moments until the end.
    pub(crate) centroids: Option<&'a mut [[f64; 2]]>,
    /// `(rows, nx + 1)`.
    pub(crate) x_apertures: Option<&'a mut [f64]>,
    /// `(rows, nx)`: the horizontal faces at the bottom of each row (lines `j0 .. j1`).
    pub(crate) y_apertures: Option<&'a mut [f64]>,
    /// `(nx)`: the faces of the band's top line `j1`, when this band writes them.
    pub(crate) y_top: Option<&'a mut [f64]>,
}

/// A band of rows of a grid and what to compute there.
pub(crate) struct Band<'a> {
    pub(crate) xs: &'a [f64],
    pub(crate) ys: &'a [f64],
    pub(crate) rows: Range<usize>,
    pub(crate) moments: bool,
    pub(crate) apertures: bool,
    pub(crate) rules: &'a Rules,
}

/// What the walk over the pieces collects, and its per-piece scratch.
#[derive(Default)]
struct Crossings {
    /// `(line - j0, x)`: every piece's crossing with the lines `y_j0 ..= y_j1`, under the
    /// half-open rule (a piece crosses `y = c` when `ymin <= c < ymax`: the line `c + 0`), so
    /// the status of `(x, c + 0)` is the parity of the crossings left of `x`. Pieces left of
    /// the grid count with `x = -inf`, without a solve; pieces right of it are left out.
    horizontal: Vec<(u32, f64)>,
    /// `(i, y)`: crossings of the vertical lines `x_i + 0` (half-open in `x`) with the
    /// boundary inside the band (apertures only). A crossing belongs to the band when the
    /// piece's part above the band's bottom line holds it, which is decided from the same
    /// crossing with that line as the horizontal list, so the two lists agree at grid
    /// vertices.
    vertical: Vec<(u32, f64)>,
    /// The current piece's crossings with the band's lines: `(line, t, x)`, ascending lines.
    local: Vec<(usize, f64, f64)>,
    /// Its crossings with vertical lines strictly inside its band part: `(t, i)`, by `t`.
    v_events: Vec<(f64, usize)>,
    /// Its crossings with horizontal lines strictly inside its band part: `(t, x)`, by `t`.
    h_events: Vec<(f64, f64)>,
}

impl Band<'_> {
    /// Computes the band's results into `out`, from every piece of the boundary. The
    /// fractions and centroids must be zero on entry (they accumulate the parts' integrals).
    pub(crate) fn cover(&self, arcs: &[Arc], out: BandOut<'_>) {
        let BandOut {
            fractions,
            mut centroids,
            x_apertures,
            y_apertures,
            y_top,
        } = out;
        let mut c = Crossings::default();
        for arc in arcs {
            self.visit(arc, &mut c, fractions, centroids.as_deref_mut());
        }
        let (hx, starts) = self.group_horizontal(&mut c.horizontal);
        self.finish_rows(&hx, &starts, fractions, centroids, y_apertures, y_top);
        if let Some(xa) = x_apertures {
            self.finish_x_apertures(&hx[starts[0]..starts[1]], &mut c.vertical, xa);
        }
    }

    /// Collects one piece's crossings and integrates its parts in the band's cells.
    fn visit(
        &self,
        arc: &Arc,
        c: &mut Crossings,
        acc: &mut [f64],
        mut mom: Option<&mut [[f64; 2]]>,
    ) {
        let (xs, ys) = (self.xs, self.ys);
        let (j0, j1) = (self.rows.start, self.rows.end);
        let b = &arc.piece.band;
        let (x_first, x_last) = (xs[0], xs[xs.len() - 1]);
        if b.ymax < ys[j0] || b.ymin > ys[j1] || b.xmin > x_last {
            return;
        }
        let (x_dir, y_dir) = (arc.piece.x_dir, arc.piece.y_dir);
        let left_of_grid = b.xmax < x_first;
        c.local.clear();
        if y_dir != Monotonicity::Constant {
            let k_start = j0.max(ys.partition_point(|&y| y < b.ymin));
            let k_end = (j1 + 1).min(ys.partition_point(|&y| y < b.ymax));
            for (k, &y) in ys.iter().enumerate().take(k_end).skip(k_start) {
                let line = (k - j0) as u32;
                if left_of_grid {
                    c.horizontal.push((line, f64::NEG_INFINITY));
                    continue;
                }
                let (t, x) = arc.at_y(y);
                c.horizontal.push((line, x));
                c.local.push((k, t, x));
            }
        }
        // A vertical piece has `dx = 0` (no area, no moment) and no crossing with `x_i + 0`.
        if left_of_grid || x_dir == Monotonicity::Constant {
            return;
        }
        let Some(((ta, pa), (tb, pb))) = self.band_part(arc, &c.local) else {
            return;
        };
        let (bx0, bx1) = (pa.x.min(pb.x), pa.x.max(pb.x));
        let (ylow, yhigh) = (pa.y.min(pb.y), pa.y.max(pb.y));
        // Vertical lines with x_i in [bx0, bx1) cross the part (half-open, as the lines
        // `x_i + 0`); those strictly inside split it.
        c.v_events.clear();
        let (i_lo, i_hi) = (
            xs.partition_point(|&x| x < bx0),
            xs.partition_point(|&x| x < bx1),
        );
        for (i, &x) in xs.iter().enumerate().take(i_hi).skip(i_lo) {
            let y = if x == bx0 {
                if pa.x == bx0 { pa.y } else { pb.y }
            } else {
                let (t, y) = arc.at_x(x);
                c.v_events.push((t.clamp(ta, tb), i));
                y.clamp(ylow, yhigh)
            };
            if self.apertures {
                c.vertical.push((i as u32, y));
            }
        }
        if x_dir == Monotonicity::Decreasing {
            c.v_events.reverse();
        }
        c.h_events.clear();
        c.h_events.extend(
            c.local
                .iter()
                .filter(|l| ylow < ys[l.0] && ys[l.0] < yhigh)
                .map(|l| (l.1.clamp(ta, tb), l.2)),
        );
        if y_dir == Monotonicity::Decreasing {
            c.h_events.reverse();
        }
        // Separate solves may disagree in the last bit near a grid vertex: keep each list in
        // order along the piece.
        let mut last = ta;
        for e in &mut c.v_events {
            e.0 = e.0.max(last);
            last = e.0;
        }
        let mut last = ta;
        for e in &mut c.h_events {
            e.0 = e.0.max(last);
            last = e.0;
        }
        if bx1 <= x_first || bx0 >= x_last {
            return;
        }
        // Walk the part from `pa`, one cell to the next at each crossing.
        let below = |v: &[f64], p: f64, inclusive: bool| {
            let n = if inclusive {
                v.partition_point(|&e| e <= p)
            } else {
                v.partition_point(|&e| e < p)
            };
            n as isize - 1
        };
        let increasing = |d: Monotonicity| d == Monotonicity::Increasing;
        let mut col = below(xs, pa.x, increasing(x_dir));
        let mut row = below(ys, pa.y, increasing(y_dir));
        let dcol = if increasing(x_dir) { 1 } else { -1 };
        let drow = match y_dir {
            Monotonicity::Increasing => 1,
            Monotonicity::Decreasing => -1,
            Monotonicity::Constant => 0,
        };
        let (mut t_prev, mut x_prev) = (ta, pa.x);
        let (mut hi, mut vi) = (0, 0);
        loop {
            let vertical = match (c.h_events.get(hi), c.v_events.get(vi)) {
                (None, None) => break,
                (Some(h), Some(v)) => v.0 <= h.0,
                (None, Some(_)) => true,
                (Some(_), None) => false,
            };
            let (t, x) = if vertical {
                let (t, i) = c.v_events[vi];
                (t, xs[i])
            } else {
                c.h_events[hi]
            };
            self.add_part(
                arc,
                (col, row),
                (t_prev, t),
                (x_prev, x),
                acc,
                mom.as_deref_mut(),
            );
            if vertical {
                col += dcol;
                vi += 1;
            } else {
                row += drow;
                hi += 1;
            }
            (t_prev, x_prev) = (t, x);
        }
        self.add_part(arc, (col, row), (t_prev, tb), (x_prev, pb.x), acc, mom);
    }

    /// The piece's part in the band, `((ta, pa), (tb, pb))` in the piece's order: clipped at
    /// the band's bottom and top lines by the crossings in `local`. A horizontal piece
    /// belongs to the band when `y_j0 < y <= y_j1` (one on the line `y_j1` is part of the
    /// row below it, as the half-open crossing rule leaves it out of that line's covered
    /// length). `None` when the piece has no part of positive length in the band.
    #[allow(clippy::type_complexity)]
    fn band_part(
        &self,
        arc: &Arc,
        local: &[(usize, f64, f64)],
    ) -> Option<((f64, Point), (f64, Point))> {
        let (j0, j1) = (self.rows.start, self.rows.end);
        let (ya, yb) = (self.ys[j0], self.ys[j1]);
        let b = &arc.piece.band;
        let (start, end) = ((0.0, b.start), (1.0, b.end));
        let y_dir = arc.piece.y_dir;
        if y_dir == Monotonicity::Constant {
            return (ya < b.start.y && b.start.y <= yb).then_some((start, end));
        }
        if !(b.ymin < yb && b.ymax > ya) {
            return None;
        }
        let at = |c: Option<&(usize, f64, f64)>, k: usize| {
            c.filter(|c| c.0 == k)
                .map(|&(_, t, x)| (t, Point::new(x, self.ys[k])))
        };
        let bottom = if b.ymin < ya {
            at(local.first(), j0)
        } else {
            None
        };
        let top = if b.ymax > yb {
            at(local.last(), j1)
        } else {
            None
        };
        Some(if y_dir == Monotonicity::Increasing {
            (bottom.unwrap_or(start), top.unwrap_or(end))
        } else {
            (top.unwrap_or(start), bottom.unwrap_or(end))
        })
    }

    /// Adds the integrals of the piece's part over `[t0, t1]` (abscissas `x0`, `x1`) to the
    /// cell `(col, row)` when that cell is one of the band's.
    fn add_part(
        &self,
        arc: &Arc,
        (col, row): (isize, isize),
        (t0, t1): (f64, f64),
        (x0, x1): (f64, f64),
        acc: &mut [f64],
        mom: Option<&mut [[f64; 2]]>,
    ) {
        let nx = self.xs.len() - 1;
        let (j0, j1) = (self.rows.start, self.rows.end);
        if col < 0 || col as usize >= nx || row < j0 as isize || row as usize >= j1 || t1 <= t0 {
            return;
        }
        let (i, j) = (col as usize, row as usize);
        let corner = Point::new(self.xs[i], self.ys[j]);
        let part = if arc.piece.y_dir == Monotonicity::Constant {
            // A horizontal part: closed forms on its exact end abscissas.
            let v = arc.piece.band.start.y - corner.y;
            let (u0, u1) = (x0 - corner.x, x1 - corner.x);
            PartIntegrals {
                b: v * (x1 - x0),
                mx: 0.5 * v * (u1 * u1 - u0 * u0),
                my: 0.5 * v * v * (x1 - x0),
            }
        } else {
            let size = (self.xs[i + 1] - self.xs[i], self.ys[j + 1] - self.ys[j]);
            arc.integrals((t0, t1), corner, size, self.moments, self.rules)
        };
        let idx = (j - j0) * nx + i;
        acc[idx] += arc.sign * part.b;
        if let Some(m) = mom {
            m[idx][0] += arc.sign * part.mx;
            m[idx][1] += arc.sign * part.my;
        }
    }

    /// Sorts the horizontal crossings by line and abscissa: their abscissas, and where each
    /// line's start (`starts[k] .. starts[k + 1]` for line `j0 + k`).
    fn group_horizontal(&self, horizontal: &mut [(u32, f64)]) -> (Vec<f64>, Vec<usize>) {
        horizontal.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        let lines = self.rows.len() + 1;
        let mut starts = vec![0usize; lines + 1];
        for &(k, _) in horizontal.iter() {
            starts[k as usize + 1] += 1;
        }
        for k in 0..lines {
            starts[k + 1] += starts[k];
        }
        (horizontal.iter().map(|h| h.1).collect(), starts)
    }

    /// The fractions and centroids of every row, from the covered lengths of its top line,
    /// and the horizontal apertures.
    fn finish_rows(
        &self,
        hx: &[f64],
        starts: &[usize],
        fractions: &mut [f64],
        centroids: Option<&mut [[f64; 2]]>,
        mut y_apertures: Option<&mut [f64]>,
        mut y_top: Option<&mut [f64]>,
    ) {
        let (xs, ys) = (self.xs, self.ys);
        let nx = xs.len() - 1;
        let (j0, rows) = (self.rows.start, self.rows.len());
        let mut len = vec![0.0; nx];
        let mut first = vec![0.0; if centroids.is_some() { nx } else { 0 }];
        let mut centroids = centroids;
        for k in 0..=rows {
            let faces = if k < rows {
                y_apertures
                    .as_deref_mut()
                    .map(|y| &mut y[k * nx..(k + 1) * nx])
            } else {
                y_top.as_deref_mut()
            };
            // The bottom line's lengths only give its own faces.
            if k == 0 && faces.is_none() {
                continue;
            }
            len.fill(0.0);
            first.fill(0.0);
            let moments = centroids.is_some().then_some(&mut first[..]);
            add_covered(xs, &hx[starts[k]..starts[k + 1]], false, &mut len, moments);
            if let Some(faces) = faces {
                for (i, f) in faces.iter_mut().enumerate() {
                    *f = (len[i] / (xs[i + 1] - xs[i])).clamp(0.0, 1.0);
                }
            }
            if k == 0 {
                continue;
            }
            let (r, j) = (k - 1, j0 + k - 1);
            let h = ys[j + 1] - ys[j];
            for i in 0..nx {
                let idx = r * nx + i;
                let w = xs[i + 1] - xs[i];
                let area = h * len[i] - fractions[idx];
                let fraction = (area / (h * w)).clamp(0.0, 1.0);
                fractions[idx] = fraction;
                if let Some(m) = centroids.as_deref_mut() {
                    m[idx] = if fraction == 0.0 {
                        [f64::NAN; 2]
                    } else {
                        let mx = h * first[i] - m[idx][0];
                        let my = 0.5 * h * h * len[i] - m[idx][1];
                        [
                            (xs[i] + mx / area).clamp(xs[i], xs[i + 1]),
                            (ys[j] + my / area).clamp(ys[j], ys[j + 1]),
                        ]
                    };
                }
            }
        }
    }

    /// The vertical apertures: each line `x_i + 0` starts the band with the status the
    /// bottom line's crossings give it (the parity of those at or left of `x_i`) and flips
    /// at its crossings inside the band. Rows are written one after the other (each row's
    /// faces are contiguous), every line keeping its place in its crossings.
    fn finish_x_apertures(&self, bottom: &[f64], vertical: &mut [(u32, f64)], out: &mut [f64]) {
        let xs = self.xs;
        let lines = xs.len();
        let edges = &self.ys[self.rows.start..=self.rows.end];
        vertical.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        // Per line: the next crossing, one past its last, and whether it is inside.
        let mut next = vec![0usize; lines];
        let mut end = vec![0usize; lines];
        let mut inside = vec![false; lines];
        let (mut v, mut left) = (0, 0);
        for (i, &x) in xs.iter().enumerate() {
            while left < bottom.len() && bottom[left] <= x {
                left += 1;
            }
            inside[i] = left % 2 == 1;
            next[i] = v;
            while v < vertical.len() && vertical[v].0 as usize == i {
                v += 1;
            }
            end[i] = v;
        }
        for (r, row) in out.chunks_exact_mut(lines).enumerate() {
            let (e0, e1) = (edges[r], edges[r + 1]);
            for (i, face) in row.iter_mut().enumerate() {
                let (mut at, mut len, mut ins) = (e0, 0.0, inside[i]);
                while next[i] < end[i] && vertical[next[i]].1 < e1 {
                    let y = vertical[next[i]].1.clamp(e0, e1);
                    if ins {
                        len += y - at;
                    }
                    (at, ins) = (y, !ins);
                    next[i] += 1;
                }
                if ins {
                    len += e1 - at;
                }
                inside[i] = ins;
                *face = (len / (e1 - e0)).clamp(0.0, 1.0);
            }
        }
    }
}

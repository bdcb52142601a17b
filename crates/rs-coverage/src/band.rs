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
use rs_spline::{Axis, Point};

use crate::arc::{Arc, Moments, PartIntegrals};
use crate::lines::{LineSums, add_covered, annulus_fraction, column_moments};

/// Where a band writes its results: row-major slices of the caller's arrays, whose entry
/// values are zeros (fractions, apertures, boundary lengths) and `NaN` (centroids). Fresh
/// arrays hold them already, and only the cells the covered set reaches are written (a zeroed
/// page the band never writes is never touched); otherwise the band sets them itself: each
/// row's fractions and centroids just before the row is written (while it is in cache), the
/// other arrays first.
pub(crate) struct BandOut<'a> {
    /// `(rows, nx)`.
    pub(crate) fractions: &'a mut [f64],
    /// `(rows, nx)`.
    pub(crate) centroids: Option<&'a mut [[f64; 2]]>,
    /// `(rows, nx + 1)`.
    pub(crate) x_apertures: Option<&'a mut [f64]>,
    /// `(rows, nx)`: the horizontal faces at the bottom of each row (lines `j0 .. j1`).
    pub(crate) y_apertures: Option<&'a mut [f64]>,
    /// `(nx)`: the faces of the band's top line `j1`, when this band writes them.
    pub(crate) y_top: Option<&'a mut [f64]>,
    /// `(rows, nx)` each: the boundary's length, centroid and unit normal in each cell (0,
    /// `NaN`, `NaN` on entry).
    pub(crate) boundary: Option<BoundaryOut<'a>>,
    /// `(rows, nx + 1)`: the centroid `y` of each vertical face's covered part (`NaN` on
    /// entry).
    pub(crate) x_face_centroids: Option<&'a mut [f64]>,
    /// `(rows, nx)` and the top line's `(nx)`, as the horizontal apertures: the centroid `x`
    /// of each horizontal face's covered part (`NaN` on entry).
    pub(crate) y_face_centroids: Option<&'a mut [f64]>,
    /// The top line's, when this band writes them.
    pub(crate) y_top_centroids: Option<&'a mut [f64]>,
    /// Whether the arrays hold the entry values already.
    pub(crate) fresh: bool,
}

impl BandOut<'_> {
    /// Sets the entry values of the arrays the band writes outside its rows' loop (all but
    /// the fractions and centroids).
    fn reset_faces_and_boundary(&mut self) {
        for zeros in [
            &mut self.x_apertures,
            &mut self.y_apertures,
            &mut self.y_top,
        ]
        .into_iter()
        .flatten()
        {
            zeros.fill(0.0);
        }
        for nan in [
            &mut self.x_face_centroids,
            &mut self.y_face_centroids,
            &mut self.y_top_centroids,
        ]
        .into_iter()
        .flatten()
        {
            nan.fill(f64::NAN);
        }
        if let Some(b) = &mut self.boundary {
            b.lengths.fill(0.0);
            b.centroids.fill([f64::NAN; 2]);
            b.normals.fill([f64::NAN; 2]);
        }
    }
}

/// Where a band writes the boundary's geometry in its cells.
pub(crate) struct BoundaryOut<'a> {
    pub(crate) lengths: &'a mut [f64],
    pub(crate) centroids: &'a mut [[f64; 2]],
    pub(crate) normals: &'a mut [[f64; 2]],
}

/// A band of rows of a grid and what to compute there.
pub(crate) struct Band<'a> {
    pub(crate) xs: &'a [f64],
    pub(crate) ys: &'a [f64],
    pub(crate) rows: Range<usize>,
    /// The area moments the cells need: first ones for centroids or a revolved volume,
    /// second ones for a revolved volume's centroid.
    pub(crate) moments: Moments,
    /// The vertical lines' crossings are collected (apertures or face centroids).
    pub(crate) vertical_faces: bool,
    /// The boundary's length, centroid and normal in each cell.
    pub(crate) boundary: bool,
    /// The axis the domain revolves about, if any: fractions, centroids and the faces across
    /// the axis are then weighted by the distance to it.
    pub(crate) axis: Option<Axis>,
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
    /// Its crossings with vertical lines strictly inside its band part: `(t, i, y, m)`, by
    /// `t`, `m` the first of `anchors` at or beyond it along the piece.
    v_events: Vec<(f64, usize, f64, usize)>,
    /// Its crossings with horizontal lines strictly inside its band part: `(t, x, y)`, by `t`.
    h_events: Vec<(f64, f64, f64)>,
    /// Its band part's start, `h_events` and end: `(t, x, y)` in the piece's order.
    anchors: Vec<(f64, f64, f64)>,
    /// `(cell, integrals)`: the signed integrals of every part, by the cell's index in the
    /// band, in the order the walk found them (summed per cell in that order).
    parts: Vec<(usize, PartIntegrals)>,
    /// `(cell, [length, int u ds, int v ds, n_x, n_y])`: the boundary's parts (with
    /// [`Band::boundary`]), `n` the integral of the outward normal, `(dy, -dx)` signed.
    boundary: Vec<(usize, [f64; 5])>,
}

impl Band<'_> {
    /// Computes the band's results into `out` (see [`BandOut`] for its values on entry), from
    /// every piece of the boundary.
    pub(crate) fn cover(&self, arcs: &[Arc], mut out: BandOut<'_>) {
        if !out.fresh {
            out.reset_faces_and_boundary();
        }
        let BandOut {
            fractions,
            centroids,
            x_apertures,
            y_apertures,
            y_top,
            boundary,
            x_face_centroids,
            y_face_centroids,
            y_top_centroids,
            fresh,
        } = out;
        let mut c = Crossings::default();
        for arc in arcs {
            self.visit(arc, &mut c);
        }
        let cells = sum_by_cell(&mut c.parts);
        let (hx, starts) = self.group_horizontal(&mut c.horizontal);
        self.finish_rows(
            (&hx, &starts),
            &cells,
            (fractions, centroids, fresh),
            YFaces {
                apertures: y_apertures,
                top: y_top,
                centroids: y_face_centroids,
                top_centroids: y_top_centroids,
            },
        );
        if x_apertures.is_some() || x_face_centroids.is_some() {
            self.finish_x_faces(
                &hx[starts[0]..starts[1]],
                &mut c.vertical,
                (x_apertures, x_face_centroids),
            );
        }
        if let Some(out) = boundary {
            finish_boundary(self.xs, &self.ys[self.rows.start..], &mut c.boundary, out);
        }
    }

    /// Collects one piece's crossings and integrates its parts in the band's cells.
    fn visit(&self, arc: &Arc, c: &mut Crossings) {
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
        // A vertical piece has `dx = 0` (no area, no moment) and no crossing with `x_i + 0`;
        // it is boundary, though.
        if left_of_grid {
            return;
        }
        if x_dir == Monotonicity::Constant {
            if self.boundary {
                self.vertical_boundary(arc, &mut c.boundary);
            }
            return;
        }
        let Some(((ta, pa), (tb, pb))) = self.band_part(arc, &c.local) else {
            return;
        };
        let (bx0, bx1) = (pa.x.min(pb.x), pa.x.max(pb.x));
        let (ylow, yhigh) = (pa.y.min(pb.y), pa.y.max(pb.y));
        c.h_events.clear();
        c.h_events.extend(
            c.local
                .iter()
                .filter(|l| ylow < ys[l.0] && ys[l.0] < yhigh)
                .map(|l| (l.1.clamp(ta, tb), l.2, ys[l.0])),
        );
        if y_dir == Monotonicity::Decreasing {
            c.h_events.reverse();
        }
        // The part's crossings with horizontal lines and its ends, in its order: what a
        // vertical line's crossing is held between, so that it falls in the same place
        // whether a horizontal line is one of the band's own or its first or last (the
        // values of a cell do not depend on the band it is computed in).
        c.anchors.clear();
        c.anchors.push((ta, pa.x, pa.y));
        c.anchors.extend(c.h_events.iter().copied());
        c.anchors.push((tb, pb.x, pb.y));
        let forward = x_dir == Monotonicity::Increasing;
        // Vertical lines with x_i in [bx0, bx1) cross the part (half-open, as the lines
        // `x_i + 0`: consecutive band parts share their clip's abscissa, so each line falls
        // in one of them); those strictly inside split it. Each crossing is placed by the
        // anchors: the anchor's own point where one has the line's abscissa (a grid vertex,
        // or the part's end), else the solve held between the two anchors about it; so its
        // point does not depend on the band.
        c.v_events.clear();
        let (i_lo, i_hi) = (
            xs.partition_point(|&x| x < bx0),
            xs.partition_point(|&x| x < bx1),
        );
        for (i, &x) in xs.iter().enumerate().take(i_hi).skip(i_lo) {
            // The first anchor at or beyond `x` along the part.
            let m = if forward {
                c.anchors.partition_point(|a| a.1 < x)
            } else {
                c.anchors.partition_point(|a| a.1 > x)
            }
            .min(c.anchors.len() - 1);
            let after = c.anchors[m];
            let (t, y) = if after.1 == x {
                (after.0, after.2)
            } else {
                let before = c.anchors[m.saturating_sub(1)];
                let (t, y) = arc.at_x(x);
                (
                    t.clamp(before.0, after.0.max(before.0)),
                    y.clamp(before.2.min(after.2), before.2.max(after.2)),
                )
            };
            if x != bx0 {
                c.v_events.push((t, i, y, m.max(1)));
            }
            if self.vertical_faces {
                c.vertical.push((i as u32, y));
            }
        }
        if x_dir == Monotonicity::Decreasing {
            c.v_events.reverse();
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
        // Within the columns the piece spans (from the one right of its least abscissa to
        // the one left of its greatest): a crossing solved a rounding beyond the piece's end
        // (a vertical tangent at a grid vertex) must not start the part in a column the
        // piece never enters, which the walk from the piece's start would not.
        let mut col = below(xs, pa.x, increasing(x_dir)).clamp(
            below(xs, b.xmin, true),
            below(xs, b.xmax, false).max(below(xs, b.xmin, true)),
        );
        let mut row = below(ys, pa.y, increasing(y_dir));
        let dcol = if increasing(x_dir) { 1 } else { -1 };
        let drow = match y_dir {
            Monotonicity::Increasing => 1,
            Monotonicity::Decreasing => -1,
            Monotonicity::Constant => 0,
        };
        let (mut t_prev, mut p_prev) = (ta, pa);
        let (mut hi, mut vi) = (0, 0);
        loop {
            // In the order of the anchors (`h_events[hi]` is `anchors[hi + 1]`), so that a
            // crossing's place does not hang on the last bits of two solves.
            let vertical = match (c.h_events.get(hi), c.v_events.get(vi)) {
                (None, None) => break,
                (Some(_), Some(v)) => v.3 <= hi + 1,
                (None, Some(_)) => true,
                (Some(_), None) => false,
            };
            let (t, p) = if vertical {
                let (t, i, y, _) = c.v_events[vi];
                (t, Point::new(xs[i], y))
            } else {
                let (t, x, y) = c.h_events[hi];
                (t, Point::new(x, y))
            };
            self.add_part(arc, (col, row), (t_prev, t), (p_prev, p), c);
            if vertical {
                col += dcol;
                vi += 1;
            } else {
                row += drow;
                hi += 1;
            }
            (t_prev, p_prev) = (t, p);
        }
        self.add_part(arc, (col, row), (t_prev, tb), (p_prev, pb), c);
    }

    /// Revolved fractions without centroids: each part's integrals are the one volume
    /// integral (`Arc::volume_integral`).
    fn volume_only(&self) -> bool {
        self.axis.is_some() && self.moments == Moments::Area
    }

    /// The boundary's parts of a vertical piece, cut at the band's horizontal lines: each
    /// belongs to the column whose right edge it may lie on (`x_i < x <= x_{i+1}`, as a face
    /// the boundary runs on takes the value just to its right) and to the row it spans.
    fn vertical_boundary(&self, arc: &Arc, boundary: &mut Vec<(usize, [f64; 5])>) {
        let (xs, ys) = (self.xs, self.ys);
        let nx = xs.len() - 1;
        let b = &arc.piece.band;
        let x = b.start.x;
        let Some(i) = xs.partition_point(|&e| e < x).checked_sub(1) else {
            return;
        };
        if i >= nx {
            return;
        }
        let (j0, j1) = (self.rows.start, self.rows.end);
        let up = if arc.piece.y_dir == Monotonicity::Decreasing {
            -1.0
        } else {
            1.0
        };
        let first = j0.max(ys.partition_point(|&y| y <= b.ymin).saturating_sub(1));
        for j in first..j1 {
            let (lo, hi) = (b.ymin.max(ys[j]), b.ymax.min(ys[j + 1]));
            if ys[j] >= b.ymax {
                break;
            }
            if hi <= lo {
                continue;
            }
            let len = hi - lo;
            let (u, v) = (x - xs[i], 0.5 * (lo + hi) - ys[j]);
            let idx = (j - j0) * nx + i;
            boundary.push((idx, [len, len * u, len * v, arc.sign * up * len, 0.0]));
        }
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

    /// Records the integrals of the piece's part over `[t0, t1]` (from `p0` to `p1`) for
    /// the cell `(col, row)` when that cell is one of the band's: its area integrals, and
    /// with [`Band::boundary`] its arc-length integrals and the integral of its outward
    /// normal, `sign (y1 - y0, x0 - x1)` (the filled set on the part's left).
    fn add_part(
        &self,
        arc: &Arc,
        (col, row): (isize, isize),
        (t0, t1): (f64, f64),
        (p0, p1): (Point, Point),
        c: &mut Crossings,
    ) {
        let (x0, x1) = (p0.x, p1.x);
        let nx = self.xs.len() - 1;
        let (j0, j1) = (self.rows.start, self.rows.end);
        if col < 0 || col as usize >= nx || row < j0 as isize || row as usize >= j1 || t1 <= t0 {
            return;
        }
        let (i, j) = (col as usize, row as usize);
        let corner = Point::new(self.xs[i], self.ys[j]);
        let size = (self.xs[i + 1] - self.xs[i], self.ys[j + 1] - self.ys[j]);
        let horizontal = arc.piece.y_dir == Monotonicity::Constant;
        let part = if let (true, Some(axis)) = (self.volume_only(), self.axis) {
            // Revolved fractions alone: the volume integral (closed form on a horizontal part).
            let volume = if horizontal {
                let v = arc.piece.band.start.y - corner.y;
                let (u0, u1) = (x0 - corner.x, x1 - corner.x);
                match axis {
                    Axis::Y => v * (corner.x * (u1 - u0) + 0.5 * (u1 * u1 - u0 * u0)),
                    Axis::X => (corner.y + 0.5 * v) * v * (x1 - x0),
                }
            } else {
                arc.volume_integral((t0, t1), corner, size, axis)
            };
            [volume, 0.0, 0.0, 0.0, 0.0, 0.0]
        } else if horizontal {
            // A horizontal part: closed forms on its exact end abscissas.
            let v = arc.piece.band.start.y - corner.y;
            let (u0, u1) = (x0 - corner.x, x1 - corner.x);
            let dx = x1 - x0;
            [
                v * dx,
                0.5 * v * (u1 * u1 - u0 * u0),
                0.5 * v * v * dx,
                v * (u1 * u1 * u1 - u0 * u0 * u0) / 3.0,
                0.25 * v * v * (u1 * u1 - u0 * u0),
                v * v * v * dx / 3.0,
            ]
        } else {
            arc.integrals((t0, t1), corner, size, self.moments)
        };
        let idx = (j - j0) * nx + i;
        c.parts.push((idx, part.map(|p| arc.sign * p)));
        if self.boundary {
            let [len, lu, lv] = if horizontal {
                let len = (x1 - x0).abs();
                let v = arc.piece.band.start.y - corner.y;
                [len, len * (0.5 * (x0 + x1) - corner.x), len * v]
            } else {
                arc.arc_length_integrals((t0, t1), corner, size)
            };
            let normal = [arc.sign * (p1.y - p0.y), arc.sign * (x0 - x1)];
            c.boundary.push((idx, [len, lu, lv, normal[0], normal[1]]));
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

    /// The fractions and centroids of every row, from the covered lengths of its top line and
    /// the parts' integrals `cells` (by cell, ascending), and the horizontal faces. Only
    /// the cells of the line's covered intervals and those the boundary passes through are
    /// written; a cell covered from side to side that the boundary misses is exactly 1
    /// (`h w / (h w)`, which [`CellGrid`](crate::CellGrid) keeps finite and nonzero) without a
    /// division.
    fn finish_rows(
        &self,
        (hx, starts): (&[f64], &[usize]),
        cells: &[(usize, PartIntegrals)],
        (fractions, mut centroids, fresh): (&mut [f64], Option<&mut [[f64; 2]]>, bool),
        mut faces: YFaces<'_>,
    ) {
        let (xs, ys) = (self.xs, self.ys);
        let nx = xs.len() - 1;
        let (j0, rows) = (self.rows.start, self.rows.len());
        let with_first = self.moments >= Moments::First
            || faces.centroids.is_some()
            || self.axis == Some(Axis::Y);
        let with_second = self.moments == Moments::Second && self.axis == Some(Axis::Y);
        let mut len = vec![0.0; nx];
        let mut first = vec![0.0; if with_first { nx } else { 0 }];
        let mut second = vec![0.0; if with_second { nx } else { 0 }];
        let mut touched: Vec<Range<usize>> = Vec::new();
        let mut next_cell = 0;
        for k in 0..=rows {
            let (line_faces, line_centroids) = faces.line(k, rows, nx);
            // The bottom line's lengths only give its own faces.
            if k == 0 && line_faces.is_none() && line_centroids.is_none() {
                continue;
            }
            for r in touched.drain(..) {
                len[r.clone()].fill(0.0);
                if let Some(f) = first.get_mut(r.clone()) {
                    f.fill(0.0);
                }
                if let Some(s) = second.get_mut(r) {
                    s.fill(0.0);
                }
            }
            // Revolved, a full column's moments are read as such (the planar centroids keep
            // the sums they always had).
            let full_columns = self.axis.is_none();
            let mut sums = LineSums {
                len: &mut len,
                first: with_first.then_some(&mut first[..]),
                second: with_second.then_some(&mut second[..]),
                full_columns,
            };
            add_covered(
                xs,
                &hx[starts[k]..starts[k + 1]],
                false,
                &mut sums,
                &mut touched,
            );
            if let Some(line_faces) = line_faces {
                for (i, f) in line_faces.iter_mut().enumerate() {
                    let w = xs[i + 1] - xs[i];
                    *f = match self.axis {
                        // An annulus about the y axis: weighted by the radius |x|.
                        Some(Axis::Y) => {
                            let (f, _) =
                                column_moments((&first, &[]), i, (len[i], w), full_columns);
                            annulus_fraction(xs[i], w, len[i], f)
                        }
                        _ => len[i] / w,
                    }
                    .clamp(0.0, 1.0);
                }
            }
            // (Face centroids are planar only: `first` holds every column's moments.)
            if let Some(line_centroids) = line_centroids {
                for (i, c) in line_centroids.iter_mut().enumerate() {
                    if len[i] > 0.0 {
                        *c = (xs[i] + first[i] / len[i]).clamp(xs[i], xs[i + 1]);
                    }
                }
            }
            if k == 0 {
                continue;
            }
            let (r, j) = (k - 1, j0 + k - 1);
            let row = Row {
                xs,
                y: (ys[j], ys[j + 1]),
                len: &len,
                first: &first,
                second: &second,
                full_columns,
                axis: self.axis,
                volume_only: self.volume_only(),
            };
            let fractions = &mut fractions[r * nx..(r + 1) * nx];
            let mut centroids = centroids
                .as_deref_mut()
                .map(|m| &mut m[r * nx..(r + 1) * nx]);
            if !fresh {
                fractions.fill(0.0);
                if let Some(m) = centroids.as_deref_mut() {
                    m.fill([f64::NAN; 2]);
                }
            }
            // This row's cells the boundary passes through, as columns.
            let row_cells = cells[next_cell..].partition_point(|c| c.0 < (r + 1) * nx);
            let mut cuts = cells[next_cell..next_cell + row_cells]
                .iter()
                .map(|&(idx, acc)| (idx - r * nx, acc))
                .peekable();
            next_cell += row_cells;
            // The covered intervals' columns (ascending; an interval's last column may be the
            // next one's first) merged with the cut cells.
            let mut done = 0;
            for range in &touched {
                let mut i = range.start.max(done);
                while i < range.end {
                    let cut = cuts.next_if(|c| c.0 < range.end);
                    let run_end = cut.map_or(range.end, |c| c.0);
                    if run_end < i {
                        // A cut cell left of the interval.
                        if let Some((c, acc)) = cut {
                            row.set(c, acc, fractions, centroids.as_deref_mut());
                        }
                        continue;
                    }
                    // Columns without parts: whole ones are 1 (no moments asked) or take
                    // the general formula with no parts. The interval's inner columns are
                    // whole (`add_covered` gives each exactly its width): one fill.
                    match centroids.as_deref_mut() {
                        None => {
                            let inner_start = (range.start + 1).clamp(i, run_end);
                            let inner_end = range.end.saturating_sub(1).clamp(inner_start, run_end);
                            for c in (i..inner_start).chain(inner_end..run_end) {
                                if len[c] == xs[c + 1] - xs[c] {
                                    fractions[c] = 1.0;
                                } else {
                                    row.set(c, [0.0; 6], fractions, None);
                                }
                            }
                            debug_assert!(
                                (inner_start..inner_end).all(|c| len[c] == xs[c + 1] - xs[c])
                            );
                            fractions[inner_start..inner_end].fill(1.0);
                        }
                        Some(m) => {
                            for c in i..run_end {
                                row.set(c, [0.0; 6], fractions, Some(&mut *m));
                            }
                        }
                    }
                    if let Some((c, acc)) = cut {
                        row.set(c, acc, fractions, centroids.as_deref_mut());
                    }
                    i = run_end + 1;
                }
                done = done.max(range.end);
            }
            for (c, acc) in cuts {
                row.set(c, acc, fractions, centroids.as_deref_mut());
            }
        }
    }

    /// The vertical faces' apertures and centroids: each line `x_i + 0` starts the band with
    /// the status the bottom line's crossings give it (the parity of those at or left of
    /// `x_i`) and flips at its crossings inside the band. Rows are written one after the
    /// other (each row's faces are contiguous), every line keeping its place in its
    /// crossings. About the x axis a face is an annulus: its aperture is weighted by `|y|`.
    fn finish_x_faces(
        &self,
        bottom: &[f64],
        vertical: &mut [(u32, f64)],
        (mut apertures, mut centroids): (Option<&mut [f64]>, Option<&mut [f64]>),
    ) {
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
        let rows = edges.len() - 1;
        for r in 0..rows {
            let (e0, e1) = (edges[r], edges[r + 1]);
            let h = e1 - e0;
            for i in 0..lines {
                // The covered length and its first moment about `e0`.
                let (mut at, mut len, mut first, mut ins) = (e0, 0.0, 0.0, inside[i]);
                let mut add = |a: f64, b: f64| {
                    len += b - a;
                    let (v0, v1) = (a - e0, b - e0);
                    first += 0.5 * (v1 * v1 - v0 * v0);
                };
                while next[i] < end[i] && vertical[next[i]].1 < e1 {
                    let y = vertical[next[i]].1.clamp(e0, e1);
                    if ins {
                        add(at, y);
                    }
                    (at, ins) = (y, !ins);
                    next[i] += 1;
                }
                if ins {
                    add(at, e1);
                }
                inside[i] = ins;
                if let Some(a) = apertures.as_deref_mut() {
                    a[r * lines + i] = match self.axis {
                        Some(Axis::X) => annulus_fraction(e0, h, len, first),
                        _ => len / h,
                    }
                    .clamp(0.0, 1.0);
                }
                if let Some(c) = centroids.as_deref_mut()
                    && len > 0.0
                {
                    c[r * lines + i] = (e0 + first / len).clamp(e0, e1);
                }
            }
        }
    }
}

/// Sums the parts' integrals per cell, in the order they were found (so each cell's sums are
/// those of adding its parts one by one from zero), ascending by cell.
fn sum_by_cell<const N: usize>(parts: &mut [(usize, [f64; N])]) -> Vec<(usize, [f64; N])> {
    // Stable: the parts of one cell keep their order.
    parts.sort_by_key(|p| p.0);
    let mut cells: Vec<(usize, [f64; N])> = Vec::with_capacity(parts.len());
    for &(idx, v) in parts.iter() {
        match cells.last_mut() {
            Some((last, acc)) if *last == idx => {
                for (a, v) in acc.iter_mut().zip(v) {
                    *a += v;
                }
            }
            _ => cells.push((idx, v.map(|v| 0.0 + v))),
        }
    }
    cells
}

/// The boundary's length, centroid and unit normal in each cell of a band from its parts
/// (`edges`: the band's row edges from its first row on): the sums of the parts' lengths,
/// arc-length moments and normal integrals per cell, in the order found. A cell without
/// boundary keeps 0 and `NaN`; a normal integral of zero (the boundary leaves the cell
/// where it entered, in equal and opposite measure) is `NaN`.
fn finish_boundary(
    xs: &[f64],
    edges: &[f64],
    parts: &mut [(usize, [f64; 5])],
    out: BoundaryOut<'_>,
) {
    let nx = xs.len() - 1;
    for (idx, [len, lu, lv, n_x, n_y]) in sum_by_cell(parts) {
        let (i, r) = (idx % nx, idx / nx);
        if len <= 0.0 {
            continue;
        }
        out.lengths[idx] = len;
        let (x0, y0) = (xs[i], edges[r]);
        out.centroids[idx] = [
            (x0 + lu / len).clamp(x0, xs[i + 1]),
            (y0 + lv / len).clamp(y0, edges[r + 1]),
        ];
        let norm = n_x.hypot(n_y);
        if norm > 0.0 {
            out.normals[idx] = [n_x / norm, n_y / norm];
        }
    }
}

/// The horizontal faces' outputs of a band: the lines `j0 .. j1` and the top line `j1`
/// (written by the last band only).
struct YFaces<'a> {
    apertures: Option<&'a mut [f64]>,
    top: Option<&'a mut [f64]>,
    centroids: Option<&'a mut [f64]>,
    top_centroids: Option<&'a mut [f64]>,
}

impl YFaces<'_> {
    /// The apertures and centroids of line `k` of a band of `rows` rows (`k = rows`: the top
    /// line), each `nx` faces.
    #[allow(clippy::type_complexity)]
    fn line(
        &mut self,
        k: usize,
        rows: usize,
        nx: usize,
    ) -> (Option<&mut [f64]>, Option<&mut [f64]>) {
        if k < rows {
            let at = k * nx..(k + 1) * nx;
            (
                self.apertures.as_deref_mut().map(|a| &mut a[at.clone()]),
                self.centroids.as_deref_mut().map(|c| &mut c[at]),
            )
        } else {
            (self.top.as_deref_mut(), self.top_centroids.as_deref_mut())
        }
    }
}

/// One row of cells: its top line's covered lengths (and their first moments, with
/// centroids) by column, from which, with the parts' integrals, a cell's values follow.
struct Row<'a> {
    xs: &'a [f64],
    /// The row's bottom and top edges.
    y: (f64, f64),
    len: &'a [f64],
    first: &'a [f64],
    /// The top line's covered second moments (a revolved volume's centroid about `y`).
    second: &'a [f64],
    /// Whether `first` and `second` hold full columns' moments (see `LineSums`).
    full_columns: bool,
    /// The axis of revolution, if any.
    axis: Option<Axis>,
    /// The parts' integrals are the volume integral alone (revolved fractions without
    /// centroids): `acc[0]` is `int x v dx` (about y) or `int (y0 + v / 2) v dx` (about x).
    volume_only: bool,
}

impl Row<'_> {
    /// Writes the fraction (and centroid) of column `i` from the sums `acc` of its parts
    /// ([`PartIntegrals`]): the covered area is `A = h L - b`, its first moments about the
    /// cell's corner `Mu = h F - mx` and `Mv = h^2 L / 2 - my` (`L`, `F`: the top line's
    /// covered length in the column and its first moment). Revolved about the y axis the
    /// volume fraction is `int int x dA / int int_cell x dA = (x0 A + Mu) / (h w (x0 + w / 2))`
    /// and the centroid `(x0 + (x0 Mu + Muu) / V, y0 + (x0 Mv + Muv) / V)`, `V = x0 A + Mu`,
    /// with `Muu = h S - muu`, `Muv = h^2 F / 2 - muv` (`S`: the line's second moment);
    /// about the x axis likewise with the roles of `x` and `y` exchanged
    /// (`Mvv = h^3 L / 3 - mvv`).
    #[inline]
    fn set(
        &self,
        i: usize,
        acc: PartIntegrals,
        fractions: &mut [f64],
        centroids: Option<&mut [[f64; 2]]>,
    ) {
        let (xs, (y0, y1)) = (self.xs, self.y);
        let (h, w) = (y1 - y0, xs[i + 1] - xs[i]);
        let x0 = xs[i];
        let len = self.len[i];
        let area = h * len - acc[0];
        let (line_first, line_second) =
            column_moments((self.first, self.second), i, (len, w), self.full_columns);
        let first_u = || h * line_first - acc[1];
        let first_v = || 0.5 * h * h * len - acc[2];
        let (volume, fraction) = match (self.axis, self.volume_only) {
            (None, _) => (area, area / (h * w)),
            (Some(Axis::Y), only) => {
                let v = if only {
                    h * (x0 * len + line_first) - acc[0]
                } else {
                    x0 * area + first_u()
                };
                (v, v / (h * w * (x0 + 0.5 * w)))
            }
            (Some(Axis::X), only) => {
                let v = if only {
                    h * len * (y0 + 0.5 * h) - acc[0]
                } else {
                    y0 * area + first_v()
                };
                (v, v / (w * h * (y0 + 0.5 * h)))
            }
        };
        let fraction = fraction.clamp(0.0, 1.0);
        fractions[i] = fraction;
        if let Some(m) = centroids {
            m[i] = if fraction == 0.0 {
                [f64::NAN; 2]
            } else {
                let (mu, mv) = match self.axis {
                    None => (first_u(), first_v()),
                    Some(Axis::Y) => {
                        let muu = h * line_second - acc[3];
                        let muv = 0.5 * h * h * line_first - acc[4];
                        (x0 * first_u() + muu, x0 * first_v() + muv)
                    }
                    Some(Axis::X) => {
                        let muv = 0.5 * h * h * line_first - acc[4];
                        let mvv = h * h * h * len / 3.0 - acc[5];
                        (y0 * first_u() + muv, y0 * first_v() + mvv)
                    }
                };
                [
                    (x0 + mu / volume).clamp(x0, xs[i + 1]),
                    (y0 + mv / volume).clamp(y0, y1),
                ]
            };
        }
    }
}

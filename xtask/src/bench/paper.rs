//! The inRS paper's Tables 1-2 and the fast-path table: every method on N Halton points of
//! each domain's box, the inside counts checked against inRS2.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use inrs::contain::baselines::{FlattenedPolygon, halton_points};
use inrs::contain::{Locate, LocatorOptions, PointLocator};
use inrs::{Classifier, ContainOptions, Domain, Method};

use super::{BenchOptions, count_inside, median_time};

/// The paths timed for the tables.
const PATHS: [&str; 6] = [
    "inrs1",
    "inrs2",
    "polygon",
    "locator",
    "locator-parallel",
    "gwn",
];

/// inRS1 (O(MN)) and the reference GWN (every curve per point) stop at this size unless
/// `--full` is given.
const SLOW_PATH_MAX: usize = 100_000;

/// One timing: median seconds and the inside count it produced.
pub(super) struct Row {
    pub(super) seconds: f64,
    pub(super) inside: usize,
}

/// Timings by (domain, N, path), and the polygon baseline's number of sides per domain.
pub(super) struct PaperTimings {
    pub(super) rows: BTreeMap<(String, usize, &'static str), Row>,
    sides: BTreeMap<String, usize>,
}

/// Times every path on every domain and size; fails if a path's inside count differs from
/// inRS2's.
pub(super) fn measure(
    domains: &[(String, Domain)],
    o: &BenchOptions,
) -> Result<PaperTimings, String> {
    let mut rows = BTreeMap::new();
    let mut sides = BTreeMap::new();
    for (name, d) in domains {
        let c = Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
        let poly = FlattenedPolygon::new(d, 1e-10);
        sides.insert(name.clone(), poly.edge_count());
        for &n in &o.sizes {
            let pts = halton_points(n, d.bounding_box());
            for path in PATHS {
                if (path == "inrs1" || path == "gwn") && n > SLOW_PATH_MAX && !o.full {
                    continue;
                }
                let mut inside = 0;
                let seconds = median_time(o.reps, || {
                    inside = match path {
                        "inrs1" => count_inside(&c.locate_all_with(Method::InRS1, &pts)),
                        "inrs2" => count_inside(&c.locate_all_with(Method::InRS2, &pts)),
                        "polygon" => poly.classify(&pts).iter().filter(|&&b| b).count(),
                        "locator" => count_inside(
                            &PointLocator::new(&c, LocatorOptions::default()).locate_all(&pts),
                        ),
                        "locator-parallel" => count_inside(
                            &PointLocator::new(&c, LocatorOptions::default())
                                .locate_all_parallel(&pts),
                        ),
                        _ => count_inside(&c.locate_all_with(Method::Gwn, &pts)),
                    }
                });
                rows.insert((name.clone(), n, path), Row { seconds, inside });
            }
            let reference = rows[&(name.clone(), n, "inrs2")].inside;
            for path in PATHS {
                if let Some(r) = rows.get(&(name.clone(), n, path))
                    && r.inside != reference
                {
                    return Err(format!(
                        "{name} N={n}: {path} counts {} inside, inRS2 {reference}",
                        r.inside
                    ));
                }
            }
        }
    }
    Ok(PaperTimings { rows, sides })
}

impl PaperTimings {
    /// Timings from rows alone (for tests of what is drawn from them).
    #[cfg(test)]
    pub(super) fn from_rows(rows: BTreeMap<(String, usize, &'static str), Row>) -> Self {
        Self {
            rows,
            sides: BTreeMap::new(),
        }
    }

    /// The rows as CSV (`domain,n,method,seconds,inside`).
    pub(super) fn csv(&self) -> String {
        let mut csv = String::from("domain,n,method,seconds,inside\n");
        for ((d, n, path), r) in &self.rows {
            let _ = writeln!(csv, "{d},{n},{path},{},{}", r.seconds, r.inside);
        }
        csv
    }

    /// Tables 1, 2 and 3 in Markdown.
    pub(super) fn tables(&self, md: &mut String, names: &[&str], sizes: &[usize]) {
        let table = Table { t: self, names };
        let _ = writeln!(md, "### Table 1: inRS1 and inRS2 (paper Table 1)\n");
        let _ = writeln!(
            md,
            "CPU time for N Halton points of each domain's bounding box; speed-up = inRS1 / inRS2.\n"
        );
        table.versus(md, sizes, ("inRS1", "inrs1"), ("inRS2", "inrs2"));
        let _ = writeln!(
            md,
            "\n### Table 2: inRS2 and a polygon within 1e-10 (paper Table 2)\n"
        );
        let sides: Vec<String> = names.iter().map(|d| self.sides[*d].to_string()).collect();
        let _ = writeln!(
            md,
            "The polygon baseline flattens the boundary to within 1e-10 ({} sides) and \
             classifies with sorted points and a binary search per edge (the INPOLY2 strategy); \
             speed-up = polygon / inRS2.\n",
            sides.join(", ")
        );
        table.versus(md, sizes, ("polygon", "polygon"), ("inRS2", "inrs2"));
        let _ = writeln!(
            md,
            "\n### Table 3: fast paths and generalized winding numbers\n"
        );
        let _ = writeln!(
            md,
            "Grid point locator ({0} x {0} cells) including its build, on one thread and on all \
             threads; GWN = rounded generalized winding number (reference field, up to N = \
             {SLOW_PATH_MAX}); speed-ups over inRS2.\n",
            inrs::contain::DEFAULT_GRID_CELLS
        );
        table.header(md);
        for &n in sizes {
            table.time_row(md, n, "inRS2", "inrs2");
            table.time_row(md, n, "locator", "locator");
            table.time_row(md, n, "locator parallel", "locator-parallel");
            table.time_row(md, n, "GWN", "gwn");
            table.ratio_row(md, n, "locator speed-up", "inrs2", "locator");
            table.ratio_row(md, n, "parallel speed-up", "inrs2", "locator-parallel");
        }
    }
}

/// A Markdown table with one column per domain.
struct Table<'a> {
    t: &'a PaperTimings,
    names: &'a [&'a str],
}

impl Table<'_> {
    /// A table of the times of two algorithms `(label, path)` at every size, each size's rows
    /// followed by the speed-up of `b` over `a` (time of `a` / time of `b`).
    fn versus(
        &self,
        md: &mut String,
        sizes: &[usize],
        (a_label, a): (&str, &'static str),
        (b_label, b): (&str, &'static str),
    ) {
        self.header(md);
        for &n in sizes {
            self.time_row(md, n, a_label, a);
            self.time_row(md, n, b_label, b);
            self.ratio_row(md, n, "speed-up", a, b);
        }
    }

    fn header(&self, md: &mut String) {
        let _ = writeln!(md, "| N | algorithm | {} |", self.names.join(" | "));
        let _ = writeln!(md, "| ---: | --- |{}", " ---: |".repeat(self.names.len()));
    }

    /// One cell per domain, `-` where there is no value.
    fn cells(&self, cell: impl Fn(&str) -> Option<String>) -> String {
        let cells: Vec<String> = self
            .names
            .iter()
            .map(|d| cell(d).unwrap_or_else(|| "-".into()))
            .collect();
        cells.join(" | ")
    }

    fn row(&self, d: &str, n: usize, path: &'static str) -> Option<&Row> {
        self.t.rows.get(&(d.to_string(), n, path))
    }

    fn time_row(&self, md: &mut String, n: usize, label: &str, path: &'static str) {
        let cells = self.cells(|d| self.row(d, n, path).map(|r| format!("{:.1e} s", r.seconds)));
        let _ = writeln!(md, "| {n} | {label} | {cells} |");
    }

    fn ratio_row(
        &self,
        md: &mut String,
        n: usize,
        label: &str,
        slow: &'static str,
        fast: &'static str,
    ) {
        let cells = self.cells(|d| {
            let (s, f) = (self.row(d, n, slow)?, self.row(d, n, fast)?);
            Some(format!("{:.2}", s.seconds / f.seconds))
        });
        let _ = writeln!(md, "| | {label} | {cells} |");
    }
}

//! Option parsers that state their limits, and the help text listing every limit.

/// Printed after `--help`: the boundary tolerance and every documented limit.
pub(crate) const AFTER_HELP: &str = "\
Boundary tolerance: with T = tol x (diagonal of the domain's bounding box), a point is 'boundary'
when its vertical or horizontal distance to the boundary curve is at most T. Every point within
Euclidean distance T/sqrt(2) of the boundary is 'boundary', none farther than T is; all other
points are 'inside' or 'outside' exactly (up to floating-point rounding, far below T). Default
tol = 1e-12 (relative).

Limits (inputs beyond them are errors, never a crash or a hang):
  input files (domain, SVG, DXF, font, curve)   256 MiB; points files are streamed (any size,
                                                lines up to 64 KiB), with several --domain too
  curve degree                                  32
  |control point coordinate|                    1e150 (meshing: 3.2e60, nonzero >= 1.8e-43)
  weight ratio max/min within one curve         1e12 (uniform scaling of weights is free)
  arc sweep                                     1024 turns
  SVG group nesting / XML nodes                 256 / 10^7
  --subdivisions                                1..4096, reduced so a domain has at most about
                                                131072 boxes (544 bytes a box)
  sample --count / points from sample           10^7
  mesh vertices                                 2 x 10^6 (memory about 1 KB a vertex;
                                                fit: 1.8 KB at degree 2, 3.8 KB at degree 5)
  boundary pieces for mesh, fit, sample --ny    10^4 Bezier pieces (a piece costs about 0.25 ms)
  fit --degree / formula length                 12 / 4096 bytes; spline files 1 GiB
  convex-domain --box coordinates / --max-level 1e100 / 20
  fractions --grid, --x-edges / --y-edges       nx, ny 1..67108863 (edges files: 2..2^26
                                                float64 values); nx x ny <= 2^32 cells,
                                                computed and written in bands of 8 MiB
  cubature / integrate --degree                 0..40 (at most 861 nodes; the work grows
                                                like degree^6: seconds at 40)";

/// The default `--tol` of classify as shown by `--help` (the value is
/// [`inrs::contain::DEFAULT_RELATIVE_TOLERANCE`], checked by a test).
pub(crate) const DEFAULT_TOL: &str = "1e-12";

/// The default `--tol` of convex-domain (the value of `ConvexDomainOptions::default()`).
pub(crate) const DEFAULT_CONVEX_TOL: &str = "1e-3";

fn whole(s: &str) -> Result<u64, String> {
    s.parse::<u64>()
        .map_err(|_| format!("{s:?} is not a whole number >= 0"))
}

fn in_range(s: &str, lo: u64, hi: u64) -> Result<u64, String> {
    let v = whole(s).map_err(|_| format!("{s:?}: expected a whole number from {lo} to {hi}"))?;
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} is out of range: expected {lo} to {hi}"))
    }
}

/// `--tol` (of classify and convex-domain): a finite number >= 0.
pub(crate) fn parse_tolerance(s: &str) -> Result<f64, String> {
    let v = s
        .parse::<f64>()
        .map_err(|_| format!("{s:?} is not a number"))?;
    inrs::spline::limits::NonNegative::new(v)
        .map(|v| v.get())
        .map_err(|e| e.to_string())
}

/// `--subdivisions`: 1 to [`inrs::boxes::MAX_SUBDIVISIONS`].
pub(crate) fn parse_subdivisions(s: &str) -> Result<usize, String> {
    in_range(s, 1, inrs::boxes::MAX_SUBDIVISIONS as u64).map(|v| v as usize)
}

/// `--degree`: 1 to [`inrs::trispline::bb::MAX_DEGREE`].
pub(crate) fn parse_degree(s: &str) -> Result<usize, String> {
    in_range(s, 1, inrs::trispline::bb::MAX_DEGREE as u64).map(|v| v as usize)
}

/// `cubature --degree`, `integrate --degree`: 0 to [`inrs::cubature::MAX_DEGREE`].
pub(crate) fn parse_cubature_degree(s: &str) -> Result<usize, String> {
    in_range(s, 0, inrs::cubature::MAX_DEGREE as u64).map(|v| v as usize)
}

/// `--ny`: 2 to [`inrs::mesh::MAX_LINES`].
pub(crate) fn parse_ny(s: &str) -> Result<usize, String> {
    in_range(s, 2, inrs::mesh::MAX_LINES as u64).map(|v| v as usize)
}

/// `--count`: 1 to [`inrs::mesh::MAX_SAMPLE_POINTS`].
pub(crate) fn parse_count(s: &str) -> Result<usize, String> {
    in_range(s, 1, inrs::mesh::MAX_SAMPLE_POINTS as u64).map(|v| v as usize)
}

/// `--max-level`: 0 to [`inrs::convex::MAX_LEVEL`].
pub(crate) fn parse_level(s: &str) -> Result<u32, String> {
    in_range(s, 0, u64::from(inrs::convex::MAX_LEVEL)).map(|v| v as u32)
}

/// `--free-index`, `--curve-index`: a whole number (checked against the curve later).
pub(crate) fn parse_free_index(s: &str) -> Result<usize, String> {
    in_range(s, 0, u32::MAX as u64).map(|v| v as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_are_checked_with_messages() {
        assert_eq!(
            parse_tolerance("-1").unwrap_err(),
            "-1 must be finite and >= 0"
        );
        assert!(parse_tolerance("inf").is_err());
        assert_eq!(parse_tolerance("1e-9"), Ok(1e-9));
        assert!(parse_subdivisions("0").unwrap_err().contains("1 to 4096"));
        assert!(
            parse_subdivisions("10000000")
                .unwrap_err()
                .contains("out of range")
        );
        assert!(parse_ny("-5").unwrap_err().contains("from 2 to 100000"));
        assert!(parse_count("1000000000").is_err());
        assert_eq!(parse_count("10"), Ok(10));
        assert!(parse_level("21").is_err());
        assert_eq!(parse_cubature_degree("0"), Ok(0));
        assert!(
            parse_cubature_degree("41")
                .unwrap_err()
                .contains("expected 0 to 40")
        );
    }

    #[test]
    fn defaults_and_help_agree_with_the_libraries() {
        assert_eq!(
            parse_tolerance(DEFAULT_TOL),
            Ok(inrs::contain::DEFAULT_RELATIVE_TOLERANCE)
        );
        assert_eq!(
            parse_tolerance(DEFAULT_CONVEX_TOL),
            Ok(inrs::convex::ConvexDomainOptions::default().relative_tolerance)
        );
        let limits = [
            format!("{}", inrs::spline::limits::MAX_DEGREE),
            format!("{:e}", inrs::spline::limits::MAX_COORDINATE),
            format!("{:e}", inrs::spline::limits::MAX_WEIGHT_RATIO),
            format!("{} turns", inrs::spline::limits::MAX_ARC_PIECES / 4),
            format!("{} MiB", inrs::spline::limits::MAX_FILE_BYTES >> 20),
            format!("{} KiB", inrs::MAX_LINE_BYTES >> 10),
            format!("{} / 10^7", inrs::io::svg::MAX_SVG_DEPTH),
            format!("1..{}", inrs::boxes::MAX_SUBDIVISIONS),
            format!(
                "{} boxes ({} bytes",
                inrs::boxes::BOX_BUDGET,
                inrs::boxes::BYTES_PER_BOX
            ),
            format!("{:e}", inrs::convex::MAX_BOX_COORDINATE),
            format!("/ {}", inrs::convex::MAX_LEVEL),
            format!("--degree                 0..{}", inrs::cubature::MAX_DEGREE),
            format!(
                "{} nodes",
                inrs::cubature::dim_polynomials(inrs::cubature::MAX_DEGREE)
            ),
            format!(
                "nx, ny 1..{}",
                crate::commands::fractions::MAX_CELLS_PER_AXIS
            ),
        ];
        for l in limits {
            assert!(AFTER_HELP.contains(&l), "--help does not state {l}");
        }
        assert_eq!(inrs::io::svg::MAX_SVG_NODES, 10_000_000);
        assert_eq!(inrs::mesh::MAX_SAMPLE_POINTS, 10_000_000);
        assert_eq!(inrs::mesh::MAX_MESH_VERTICES, 2_000_000);
        assert_eq!(inrs::mesh::MAX_MESH_PIECES, 10_000);
        assert_eq!(crate::commands::fractions::MAX_GRID_CELLS, 1 << 32);
    }
}

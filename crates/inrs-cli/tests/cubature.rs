//! `inrs cubature` and `inrs integrate`: the rule's CSV against the unit disc's area and
//! moments in closed form (an independent formula: the Beta function of half-integers), the
//! integral of polynomials on a disc and a square and of `exp(x + y)` on the unit square, and
//! one-line errors that leave no file behind.

#[allow(dead_code)]
mod common;
use common::{fixture, inrs, stdout_of_success, temp_file};

use std::path::PathBuf;

/// `Gamma(k / 2)` for `k >= 1`, from `Gamma(1 / 2) = sqrt(pi)`, `Gamma(1) = 1` and
/// `Gamma(s + 1) = s Gamma(s)`.
fn gamma_half(k: usize) -> f64 {
    let mut s = if k % 2 == 1 { 0.5 } else { 1.0 };
    let mut g = if k % 2 == 1 {
        std::f64::consts::PI.sqrt()
    } else {
        1.0
    };
    while 2.0 * s < k as f64 {
        g *= s;
        s += 1.0;
    }
    g
}

/// `integral over the unit disc of x^p y^q`: in polar coordinates `1 / (p + q + 2)` times
/// `integral_0^{2 pi} cos^p sin^q = 2 B((p + 1) / 2, (q + 1) / 2)` for even `p` and `q`, 0
/// otherwise.
fn unit_disc_moment(p: usize, q: usize) -> f64 {
    if p % 2 == 1 || q % 2 == 1 {
        return 0.0;
    }
    let beta = gamma_half(p + 1) * gamma_half(q + 1) / gamma_half(p + q + 2);
    2.0 * beta / (p + q + 2) as f64
}

/// The rows of a rule's CSV, after checking its header.
fn rule_rows(text: &str) -> Vec<[f64; 3]> {
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,w"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|f| f.parse().unwrap()).collect();
            assert_eq!(v.len(), 3, "{l}");
            [v[0], v[1], v[2]]
        })
        .collect()
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    common::scratch("cubature", name)
}

/// The unit square `[0, 1]^2` as a JSON domain file.
fn unit_square() -> String {
    temp_file(
        "unit_square.json",
        r#"{"curves": [{"polyline": [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]}]}"#,
    )
}

/// `inrs integrate` on `domain`, parsed.
fn integrate(domain: &str, function: &str, degree: Option<&str>) -> f64 {
    let mut args = vec!["integrate", "--domain", domain, "--function", function];
    if let Some(n) = degree {
        args.extend(["--degree", n]);
    }
    let text = stdout_of_success(inrs(&args));
    assert_eq!(text.lines().count(), 1, "{text}");
    text.trim().parse().unwrap()
}

#[test]
fn unit_disc_rule_is_positive_interior_and_integrates_every_monomial() {
    let disc = fixture("inrs-paper/circle.json");
    let dir = scratch("disc");
    let out = dir.join("rule.csv");
    let n = 10;
    let run = inrs(&[
        "cubature",
        "--domain",
        &disc,
        "--degree",
        "10",
        "--output",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{stderr}");
    // The data go to the file, the summary line to standard error.
    assert!(run.stdout.is_empty());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("degree 10, ") && stderr.contains(" nodes (at most 66), residual "),
        "{stderr}"
    );
    let text = std::fs::read_to_string(&out).unwrap();
    // Without --output: the same bytes on standard output.
    assert_eq!(
        stdout_of_success(inrs(&["cubature", "--domain", &disc, "--degree", "10"])),
        text
    );
    let rows = rule_rows(&text);
    assert!(!rows.is_empty() && rows.len() <= (n + 1) * (n + 2) / 2);
    for [x, y, w] in &rows {
        assert!(*w > 0.0, "weight {w}");
        // Strictly inside the disc, farther than the boundary tolerance (1e-12 of the box's
        // diagonal, 2 sqrt(2)) from the circle.
        assert!(x.hypot(*y) < 1.0 - 2e-12, "node ({x}, {y})");
    }
    let area: f64 = rows.iter().map(|r| r[2]).sum();
    assert!((area - std::f64::consts::PI).abs() < 1e-12, "{area}");
    let mut worst = 0.0f64;
    for total in 0..=n {
        for q in 0..=total {
            let p = total - q;
            let got: f64 = rows
                .iter()
                .map(|[x, y, w]| w * x.powi(p as i32) * y.powi(q as i32))
                .sum();
            let err = (got - unit_disc_moment(p, q)).abs();
            worst = worst.max(err);
            assert!(
                err < 1e-12,
                "x^{p} y^{q}: {got} vs {}",
                unit_disc_moment(p, q)
            );
        }
    }
    eprintln!(
        "unit disc, degree {n}: {} nodes, worst monomial error {worst:e}",
        rows.len()
    );
    // The closed forms themselves, against the values every calculus book has.
    assert!((unit_disc_moment(2, 0) - std::f64::consts::PI / 4.0).abs() < 1e-15);
    assert!((unit_disc_moment(2, 2) - std::f64::consts::PI / 24.0).abs() < 1e-15);
    assert!((unit_disc_moment(0, 0) - std::f64::consts::PI).abs() < 1e-15);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn integrate_polynomials_and_exp_against_closed_forms() {
    let disc = fixture("inrs-paper/circle.json");
    let pi = std::f64::consts::PI;
    let cases = [
        ("x^2", pi / 4.0),
        ("x^2 * y^2", pi / 24.0),
        // x y and x^3 y^5 are odd: 0.
        ("x^4 + 3*x*y - 2 + x^3*y^5", pi / 8.0 - 2.0 * pi),
    ];
    for (f, want) in cases {
        let got = integrate(&disc, f, Some("10"));
        assert!((got - want).abs() < 1e-12, "{f}: {got} vs {want}");
    }
    let square = unit_square();
    // Default degree (20): x^3 y^7 integrates to 1/4 x 1/8, exp(x + y) to (e - 1)^2.
    let got = integrate(&square, "x^3 * y^7 - 5*x", None);
    assert!((got - (1.0 / 32.0 - 2.5)).abs() < 1e-13, "{got}");
    let e = std::f64::consts::E;
    let got = integrate(&square, "exp(x + y)", None);
    assert!((got - (e - 1.0).powi(2)).abs() < 1e-10, "{got}");
    assert_eq!(integrate(&square, "exp(x + y)", Some("20")), got);
    // A low degree integrates exp less well: the degree is used.
    let coarse = integrate(&square, "exp(x + y)", Some("2"));
    assert!((coarse - (e - 1.0).powi(2)).abs() > 1e-6, "{coarse}");
}

/// Degrees out of range, an open boundary, a domain too thin for its candidates, a formula
/// that is not finite at a node or names an unknown variable: one line on standard error each,
/// the usual exit status (2 for the command line, 1 for the input), no file written and an
/// existing output left as it was.
#[test]
fn bad_input_gets_one_line_and_leaves_no_file() {
    let dir = scratch("errors");
    let out = dir.join("rule.csv");
    std::fs::write(&out, "old").unwrap();
    let disc = fixture("inrs-paper/circle.json");
    let open = fixture("bad/open_loop.json");
    let thin = temp_file(
        "thin_annulus.json",
        r#"{"curves": [{"circle": {"center": [0, 0], "radius": 1.000001}},
                       {"circle": {"center": [0, 0], "radius": 1}}]}"#,
    );
    let check = |args: &[String], message: &str, code: i32| -> String {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = inrs(&args);
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("inrs: "), "{err}");
        assert!(err.contains(message), "{args:?}: {err}");
        assert_eq!(o.status.code(), Some(code), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?}");
        assert_eq!(common::entries(&dir), ["rule.csv"], "{args:?}");
        assert_eq!(std::fs::read(&out).unwrap(), b"old");
        err
    };
    let output = out.to_str().unwrap();
    let words = |w: &[&str]| -> Vec<String> { w.iter().map(|s| s.to_string()).collect() };
    let cubature = |domain: &str, degree: &str| {
        words(&[
            "cubature", "--domain", domain, "--degree", degree, "--output", output,
        ])
    };
    let max = inrs::cubature::MAX_DEGREE;
    check(
        &cubature(&disc, &(max + 1).to_string()),
        &format!("out of range: expected 0 to {max}"),
        2,
    );
    check(&cubature(&disc, "-1"), "expected a whole number", 2);
    check(&cubature(&open, "4"), "open boundary", 1);
    check(&cubature(&thin, "2"), "too thin or too small", 1);
    let integrate = |domain: &str, f: &str| {
        words(&[
            "integrate",
            "--domain",
            domain,
            "--function",
            f,
            "--degree",
            "6",
        ])
    };
    check(
        &words(&[
            "integrate",
            "--domain",
            &disc,
            "--function",
            "x",
            "--degree",
            "41",
        ]),
        "out of range",
        2,
    );
    check(&integrate(&open, "x"), "open boundary", 1);
    check(&integrate(&disc, "z + 1"), "unknown name \"z\"", 1);
    check(&integrate(&disc, "sin("), "formula \"sin(\"", 1);
    // 1 / 0 at every node: the first one is named.
    check(
        &integrate(&disc, "1/(x-x)"),
        "integrand value inf at node 0 (",
        1,
    );
    // sqrt(x) is NaN where x < 0: the node named is one of those.
    let err = check(&integrate(&disc, "sqrt(x)"), "is not finite", 1);
    let at = err.split(" (").nth(1).and_then(|t| t.split(')').next());
    let x: f64 = at.unwrap().split(',').next().unwrap().parse().unwrap();
    assert!(x < 0.0, "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

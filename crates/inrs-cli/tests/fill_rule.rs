//! `--fill-rule` on the command line: on nested, overlapping and self-crossing loops
//! (`fixtures/fill-rule/`), `classify` with every method, one domain and several, gives what
//! the rule makes of a dense polygon's winding numbers, as `winding`'s numbers say too;
//! `fractions`, `cubature`, `integrate` and `info` give the rule's filled area where the loops
//! do not cross, and a one-line error naming the crossing where they do.

mod common;

use common::{fixture, inrs, inrs_ok, last_column, read_npy, scratch, temp_file};
use rs_testkit::{DensePolygon, NearBoundary};

const RULES: [&str; 2] = ["even-odd", "nonzero"];

/// The filled areas of the fixtures whose loops do not cross (closed forms).
fn area(name: &str, rule: &str) -> f64 {
    let pi = std::f64::consts::PI;
    match (name, rule) {
        ("nested_same", "even-odd") => 3.0 * pi,
        ("nested_same", "nonzero") => 4.0 * pi,
        ("nested_opposite", _) => 3.0 * pi,
        ("three_nested", "even-odd") => 6.0 * pi - 0.09 * pi,
        ("three_nested", "nonzero") => 6.0 * pi,
        _ => unreachable!("{name}"),
    }
}

/// A grid of points over the domain's box grown by a tenth, off round coordinates.
fn grid(d: &inrs::Domain, n: usize) -> Vec<(f64, f64)> {
    let b = d.bounding_box();
    let (x0, y0) = (b.min.x - 0.1 * b.width(), b.min.y - 0.1 * b.height());
    let (w, h) = (1.2 * b.width(), 1.2 * b.height());
    (0..n * n)
        .map(|k| {
            let (i, j) = ((k % n) as f64 + 0.37, (k / n) as f64 + 0.61);
            (x0 + w * i / n as f64, y0 + h * j / n as f64)
        })
        .collect()
}

#[test]
fn classify_and_winding_follow_the_rule_with_every_method() {
    for (case, _) in rs_testkit::fill_rule_fixtures() {
        let domain = fixture(&format!("fill-rule/{}.json", case.name));
        let d = &case.domain;
        let poly = DensePolygon::new(d, 1e-7);
        let near = NearBoundary::new(&poly, 1e-5 * d.bounding_box().diagonal());
        let pts = grid(d, 40);
        let csv: String = std::iter::once("x,y\n".to_string())
            .chain(pts.iter().map(|(x, y)| format!("{x},{y}\n")))
            .collect();
        let points = temp_file(&format!("{}.csv", case.name), &csv);
        let truth: Vec<Option<i64>> = pts
            .iter()
            .map(|&(x, y)| {
                let p = inrs::Point::new(x, y);
                (!near.is_near(p)).then(|| poly.winding_number(p).round() as i64)
            })
            .collect();
        let windings = last_column(&inrs_ok(&[
            "winding", "--domain", &domain, "--points", &points,
        ]));
        for (w, t) in windings.iter().zip(&truth) {
            if let Some(t) = t {
                assert_eq!(
                    w.parse::<f64>().unwrap().round() as i64,
                    *t,
                    "{}",
                    case.name
                );
            }
        }
        for rule in RULES {
            let fills = |w: i64| {
                if rule == "even-odd" {
                    w.rem_euclid(2) == 1
                } else {
                    w != 0
                }
            };
            for method in ["fast", "inrs1", "inrs2", "gwn"] {
                let args = ["classify", "--domain", &domain, "--points", &points];
                let out =
                    inrs_ok(&[&args[..], &["--method", method, "--fill-rule", rule]].concat());
                for (got, t) in last_column(&out).iter().zip(&truth) {
                    if let Some(t) = t {
                        let want = if fills(*t) { "inside" } else { "outside" };
                        assert_eq!(got, want, "{} {rule} {method}", case.name);
                    }
                }
            }
            // Several domains: one column each, the one domain's answers.
            let many = inrs_ok(&[
                "classify",
                "--domain",
                &domain,
                "--domain",
                &domain,
                "--points",
                &points,
                "--fill-rule",
                rule,
            ]);
            let one = inrs_ok(&[
                "classify",
                "--domain",
                &domain,
                "--points",
                &points,
                "--fill-rule",
                rule,
            ]);
            for (m, o) in many.lines().skip(1).zip(last_column(&one)) {
                assert!(
                    m.ends_with(&format!(",{o},{o}")),
                    "{} {rule}: {m}",
                    case.name
                );
            }
        }
    }
}

#[test]
fn green_capabilities_give_the_rules_area_or_name_the_crossing() {
    let dir = scratch("fill-rule", "green");
    for (case, crossing) in rs_testkit::fill_rule_fixtures() {
        let name = case.name.as_str();
        let domain = fixture(&format!("fill-rule/{name}.json"));
        let b = case.domain.bounding_box();
        let (x0, x1, y0, y1) = (b.min.x - 0.5, b.max.x + 0.5, b.min.y - 0.5, b.max.y + 0.5);
        let spec = format!("--grid={x0},{x1},40,{y0},{y1},30");
        let cell = (x1 - x0) / 40.0 * (y1 - y0) / 30.0;
        for rule in RULES {
            let out = dir.join(format!("{name}-{rule}.npy"));
            let runs: [Vec<&str>; 4] = [
                vec![
                    "fractions",
                    "--domain",
                    &domain,
                    &spec,
                    "--output",
                    out.to_str().unwrap(),
                ],
                vec!["cubature", "--domain", &domain, "--degree", "4"],
                vec![
                    "integrate",
                    "--domain",
                    &domain,
                    "--function",
                    "1",
                    "--degree",
                    "4",
                ],
                vec!["info", "--domain", &domain],
            ];
            for run in runs {
                let result = inrs(&[&run[..], &["--fill-rule", rule]].concat());
                let (stdout, stderr) = (
                    String::from_utf8_lossy(&result.stdout).into_owned(),
                    String::from_utf8_lossy(&result.stderr).into_owned(),
                );
                let tag = format!("{name} {rule} {}", run[0]);
                if crossing && run[0] != "info" {
                    assert!(!result.status.success(), "{tag}");
                    assert_eq!(stderr.lines().count(), 1, "{tag}: {stderr}");
                    assert!(stderr.contains("loops cross"), "{tag}: {stderr}");
                    continue;
                }
                assert!(result.status.success(), "{tag}: {stderr}");
                let got = match run[0] {
                    "fractions" => read_npy(&out).1.iter().sum::<f64>() * cell,
                    "cubature" => stdout
                        .lines()
                        .skip(1)
                        .map(|l| l.rsplit(',').next().unwrap().parse::<f64>().unwrap())
                        .sum(),
                    "integrate" => stdout.trim().parse().unwrap(),
                    _ => {
                        let line = stdout.lines().nth(1).unwrap();
                        assert!(
                            line.starts_with(&format!("  filled area ({rule}): ")),
                            "{tag}: {line}"
                        );
                        if crossing {
                            assert!(line.contains("loops cross"), "{tag}: {line}");
                            continue;
                        }
                        line.rsplit(' ').next().unwrap().parse().unwrap()
                    }
                };
                let want = area(name, rule);
                assert!((got - want).abs() < 1e-10 * want, "{tag}: {got} vs {want}");
            }
        }
    }
}

//! `--function` of `fit` and `integrate`: one grammar (`inrs::io::formula`), standard float
//! literals, one-line errors naming the column and what was expected, and a leading minus read
//! as the formula (`--function -x^2`) as well as after `=`.

mod common;

use common::{inrs, inrs_ok, temp_file};

const UNIT_SQUARE: &str = r#"{"curves": [{"polyline": [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]}]}"#;

/// `inrs integrate` of `args` (the function given as the caller writes it) over the unit square.
fn integral(square: &str, args: &[&str]) -> f64 {
    let base = ["integrate", "--domain", square, "--degree", "4"];
    inrs_ok(&[&base[..], args].concat()).trim().parse().unwrap()
}

#[test]
fn float_literals_and_a_leading_minus_are_read() {
    let square = temp_file("formula-square.json", UNIT_SQUARE);
    for (function, want) in [
        ("1e-3", 1e-3),
        ("2.5E+4", 2.5e4),
        ("x*1e-3", 0.5e-3),
        ("-x^2", -1.0 / 3.0),
        ("2^-1 + x**2", 0.5 + 1.0 / 3.0),
        ("1 - x - y", 0.0),
    ] {
        let joined = format!("--function={function}");
        for args in [vec!["--function", function], vec![joined.as_str()]] {
            let got = integral(&square, &args);
            assert!(
                (got - want).abs() < 1e-14 * want.abs().max(1.0),
                "{args:?}: {got} vs {want}"
            );
        }
    }
    // fit reads the same grammar, a leading minus included.
    let spline = inrs_ok(&[
        "fit",
        "--domain",
        &square,
        "--ny",
        "4",
        "--degree",
        "2",
        "--function",
        "-x^2",
    ]);
    assert!(spline.starts_with('{'));
}

#[test]
fn bad_formulas_are_one_line_naming_the_column_and_what_was_expected() {
    let square = temp_file("formula-square-bad.json", UNIT_SQUARE);
    for (function, message) in [
        (
            "foo(x)",
            "formula \"foo(x)\": column 1: unknown function \"foo\"",
        ),
        (
            "1e",
            "formula \"1e\": at its end: expected the digits of the exponent",
        ),
        (
            "sin(x",
            "formula \"sin(x\": at its end: expected \")\" to close the \"(\" of column 4",
        ),
        (
            "x +* y",
            "formula \"x +* y\": column 4: expected a number, a name or \"(\", found \"*\"",
        ),
        ("2x", "formula \"2x\": column 2: expected an operator"),
        ("z", "formula \"z\": column 1: unknown name \"z\""),
    ] {
        for command in [
            vec!["integrate", "--domain", &square, "--function", function],
            vec![
                "fit",
                "--domain",
                &square,
                "--ny",
                "4",
                "--function",
                function,
            ],
        ] {
            let out = inrs(&command);
            assert!(!out.status.success(), "{command:?}");
            let err = String::from_utf8(out.stderr).unwrap();
            assert_eq!(err.lines().count(), 1, "{command:?}: {err}");
            assert!(
                err.starts_with(&format!("inrs: {message}")),
                "{command:?}: {err}"
            );
        }
    }
}

"""Formulas in Python: ``inrs.Formula``, and the text of a formula given to :func:`inrs.fit`
and :meth:`Domain.integrate`, read by the command line's one grammar: standard float
literals, the usual precedence, one-line ``ValueError``s naming the column, and the same
numbers as ``inrs integrate --function`` and ``inrs fit --function``."""

import json
import subprocess

import numpy as np
import pytest

import inrs

from conftest import FIXTURES

UNIT_SQUARE = '{"curves": [{"polyline": [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]}]}'


def test_literals_and_precedence():
    f = inrs.Formula("x*1e-3 + 2.5E+4 - y**2")
    x, y = np.array([1.0, 2.0]), np.array([[3.0], [0.5]])
    assert np.array_equal(f(x, y), x * 1e-3 + 2.5e4 - y**2)
    assert f(x, y).shape == (2, 2)
    assert inrs.Formula("-x^2")(3.0, 0.0) == -9.0
    assert inrs.Formula("2^3^2")(0.0, 0.0) == 512.0
    assert inrs.Formula("atan2(y, x)")(1.0, 1.0) == np.arctan2(1.0, 1.0)
    assert repr(inrs.Formula("1e-3")) == "Formula('1e-3')"


@pytest.mark.parametrize(
    "text, message",
    [
        ("foo(x)", 'formula "foo(x)": column 1: unknown function "foo"'),
        ("1e", 'formula "1e": at its end: expected the digits of the exponent'),
        ("sin(x", 'formula "sin(x": at its end: expected ")" to close the "(" of column 4'),
        ("x +* y", 'formula "x +* y": column 4: expected a number, a name or "(", found "*"'),
    ],
)
def test_errors_name_the_column(text, message):
    for call in (
        lambda: inrs.Formula(text),
        lambda: inrs.Domain.from_json(UNIT_SQUARE).integrate(text, 4),
        lambda: inrs.fit(inrs.Domain.from_json(UNIT_SQUARE), text, ny=4, degree=2),
    ):
        with pytest.raises(ValueError) as e:
            call()
        assert str(e.value).startswith(message) and "\n" not in str(e.value)


def test_fit_and_integrate_take_the_text_and_equal_the_cli(cli, tmp_path):
    d = inrs.Domain.load(str(FIXTURES / "inrs-paper" / "circle.json"))
    text = "-x^2 + exp(y) * 1e-1"
    got = d.integrate(text, 10)
    assert got == d.integrate(lambda x, y: -(x**2) + np.exp(y) * 1e-1, 10)
    out = subprocess.run(
        [cli, "integrate", "--domain", FIXTURES / "inrs-paper" / "circle.json", "--function", text, "--degree", "10"],
        check=True,
        capture_output=True,
        text=True,
    )
    assert float(out.stdout) == got
    s = inrs.fit(d, text, ny=5, degree=3)
    spline = tmp_path / "s.json"
    subprocess.run(
        [cli, "fit", "--domain", FIXTURES / "inrs-paper" / "circle.json", "--ny", "5", "--degree", "3", "--function", text, "--output", spline],
        check=True,
        capture_output=True,
    )
    # The same coefficients, bit for bit, from the same text.
    assert json.loads(s.to_json())["coefficients"] == json.loads(spline.read_text())["coefficients"]

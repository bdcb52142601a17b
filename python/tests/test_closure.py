"""The closure tolerance: the error names the two curves that miss, ``closure_tol=`` joins
them for every domain source (a file, ``from_curves``), and bad values are refused."""

import numpy as np
import pytest

import inrs
from conftest import FIXTURES

THIN = FIXTURES / "bad" / "thin_gap.json"
POINTS = np.array([[0.05, 0.001], [0.05, -0.001]])


def test_the_error_names_the_two_curves_that_miss():
    with pytest.raises(ValueError, match=r"curve 0 ends 2e-10 away from the start of curve 1"):
        inrs.Domain.load(THIN).classify(POINTS)


def test_closure_tol_joins_them_from_a_file_and_from_curves():
    d = inrs.Domain.load(THIN, closure_tol=1e-8)
    assert d.classify(POINTS).tolist() == [inrs.INSIDE, inrs.OUTSIDE]
    curves = [
        {"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0], [0.1, 0]]},
        {
            "degree": 2,
            "knots": [0, 0, 0, 1, 1, 1],
            "control_points": [[0.1, 2e-10], [0.05, 0.004], [0, 0]],
        },
    ]
    with pytest.raises(ValueError, match="curve 0 ends"):
        inrs.Domain.from_curves(curves).classify(POINTS)
    joined = inrs.Domain.from_curves(curves, closure_tol=1e-8)
    assert joined.classify(POINTS).tolist() == [inrs.INSIDE, inrs.OUTSIDE]
    assert len(joined.loops) == 1


@pytest.mark.parametrize("bad", [-1.0, float("nan"), float("inf")])
def test_bad_closure_tolerances_are_refused(bad):
    with pytest.raises(ValueError, match="closure_tol"):
        inrs.Domain.load(THIN, closure_tol=bad)

"""inrs.convex_domain: the same table as ``inrs convex-domain`` for the same inputs, and one-line
errors for bad input."""

import json
import subprocess

import numpy as np
import pytest

import inrs

from conftest import FIXTURES

CUBIC = FIXTURES / "convex" / "cubic.json"
SPACE = FIXTURES / "convex" / "quintic_space.json"


def number(text):
    return None if text == "-" else float(text)


def cli_table(cli, curve, free, box, *extra):
    """The levels ``[level, inequalities, measure, abs, rel]`` as printed (numbers; ``None`` for
    ``-``), the vertex (face) count of the last level, the outer bound's measure and the
    outcome, parsed from ``inrs convex-domain``'s output."""
    out = subprocess.run(
        [cli, "convex-domain", "--curve", curve, "--free-index", str(free), "--box=" + ",".join(map(str, box)), *extra],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    lines = out.splitlines()
    sign = lines[0].split()[2].rstrip(",")
    rows = [l.split() for l in lines[2:] if l.split() and l.split()[0].isdigit()]
    table = [[int(r[0]), int(r[1]), float(r[3]), number(r[4]), number(r[5])] for r in rows]
    outer = [l for l in lines if l.startswith("outer bound")][0]
    outer_measure = float(outer.split(": ")[1].split()[1].rstrip(","))
    outcome = lines[-1].split(": ")[1]
    return sign, table, int(rows[-1][2]), outer_measure, outcome


def as_printed(k):
    """The result of :func:`inrs.convex_domain` rounded as the command line prints it (9
    significant digits for measures, 6 for the errors)."""
    r = lambda v, digits: None if v is None else float(f"{v:.{digits}e}")
    rows = [[l["level"], l["inequalities"], r(l["measure"], 8), r(l["abs_error"], 5), r(l["rel_error"], 5)] for l in k["levels"]]
    return k["sign"], rows, r(k["outer_measure"], 8), k["outcome"]


@pytest.mark.parametrize(
    "curve, free, box, kwargs, extra",
    [
        (CUBIC, 2, (-10, 10, -11, 9), {"tol": 1e-4}, ["--tol", "1e-4"]),
        (CUBIC, 2, (-10, 10, -11, 9), {}, []),
        (CUBIC, 1, (-8, 2, -6, 4), {"sign": "negative", "max_level": 4}, ["--sign", "negative", "--max-level", "4"]),
        (SPACE, 2, (-100, 100, -100, 100, -100, 100), {"max_level": 3}, ["--max-level", "3"]),
    ],
)
def test_levels_equal_the_cli_table(cli, curve, free, box, kwargs, extra):
    sign, table, last_count, outer, outcome = cli_table(cli, curve, free, box, *extra)
    k = inrs.convex_domain(curve, free, box, **kwargs)
    assert as_printed(k) == (sign, table, outer, outcome)
    assert len(table) >= 2 or outcome == "Empty"
    assert k["dimension"] == len(box) // 2
    if k["dimension"] == 2:
        poly = k["polygon"]
        assert poly.shape == (last_count, 2) and poly.dtype == np.float64
        # The shoelace area of the vertices is the last level's area.
        x, y = poly[:, 0], poly[:, 1]
        area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
        assert area == pytest.approx(k["levels"][-1]["measure"], rel=1e-12)
    else:
        assert k["polygon"] is None


def test_json_text_and_path_like_give_the_same_result():
    a = inrs.convex_domain(str(CUBIC), 2, [-10, 10, -11, 9])
    b = inrs.convex_domain(CUBIC.read_text(), 2, [-10, 10, -11, 9])
    assert a["levels"] == b["levels"] and a["outcome"] == "Converged"
    assert inrs.DEFAULT_CONVEX_TOLERANCE == 1e-3


def test_quadratic_bezier_domain_is_the_half_plane_below_the_chord():
    # Positive curvature of (0,0), d, (2,0) exactly when d is below the chord: the lower half
    # of the box, area 8, at level 0.
    curve = json.dumps({"degree": 2, "control_points": [[0, 0], [1, -1], [2, 0]]})
    k = inrs.convex_domain(curve, 1, (-1, 3, -2, 2), sign="positive")
    assert k["levels"][0]["measure"] == pytest.approx(8.0, abs=1e-12)
    assert k["outer_measure"] == pytest.approx(8.0, abs=1e-12)


@pytest.mark.parametrize(
    "args, kwargs, error, message",
    [
        ((CUBIC, 2, (-1, 1, -1)), {}, ValueError, "invalid box"),
        ((CUBIC, 2, (-1, 1, -1, 1, -1, 1)), {}, ValueError, "2-D but the box is 3-D"),
        ((CUBIC, 9, (-1, 1, -1, 1)), {}, ValueError, None),
        ((CUBIC, -1, (-1, 1, -1, 1)), {}, ValueError, "free_index must be non-negative"),
        ((CUBIC, 2, (-1, 1, -1, 1)), {"sign": "up"}, ValueError, 'unknown sign "up"'),
        ((CUBIC, 2, (-1, 1, -1, 1)), {"tol": -1.0}, ValueError, "invalid tolerance"),
        ((CUBIC, 2, (-1, 1, -1, 1)), {"max_level": 21}, ValueError, "max level 21"),
        ((CUBIC, 2, (-1, 1, -1, 1)), {"curve_index": 3}, ValueError, "a single-curve file has no curve 3"),
        ((FIXTURES / "convex" / "missing.json", 2, (-1, 1, -1, 1)), {}, OSError, "missing.json"),
        (('{"degree": 2}', 1, (-1, 1, -1, 1)), {}, ValueError, None),
    ],
)
def test_bad_input_raises_one_line_errors(args, kwargs, error, message):
    with pytest.raises(error, match=message) as e:
        inrs.convex_domain(*args, **kwargs)
    assert "\n" not in str(e.value) and str(e.value)
    if error is ValueError:
        assert not isinstance(e.value, OSError)

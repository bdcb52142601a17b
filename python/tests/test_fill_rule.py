"""The fill rule in Python: on nested, overlapping and self-crossing loops
(``fixtures/fill-rule``), ``classify`` (every method, one domain and many), ``winding``,
``cell_fractions``, ``cubature``/``integrate`` and ``filled_area`` give what the rule makes of
the winding numbers of a polygon drawn here from the files' own curves (NumPy, not the
package), or a one-line ``ValueError`` naming the crossing where the loops cross."""

import json
import math

import numpy as np
import pytest

import inrs

from conftest import FIXTURES

DIR = FIXTURES / "fill-rule"
NAMES = sorted(p.stem for p in DIR.glob("*.json"))
CROSSING = {"overlapping", "overlapping_opposite", "pentagram", "figure_eight"}
RULES = ["even-odd", "nonzero"]
METHODS = ["fast", "inrs1", "inrs2", "gwn"]

#: Closed forms of the filled areas of the fixtures whose loops do not cross.
AREAS = {
    ("nested_same", "even-odd"): 3 * math.pi,
    ("nested_same", "nonzero"): 4 * math.pi,
    ("nested_opposite", "even-odd"): 3 * math.pi,
    ("nested_opposite", "nonzero"): 3 * math.pi,
    ("three_nested", "even-odd"): 6 * math.pi - 0.09 * math.pi,
    ("three_nested", "nonzero"): 6 * math.pi,
}


def polygon(name: str) -> np.ndarray:
    """The fixture's boundary as one closed polyline per curve, from its JSON: circles and
    arcs by their angles, polylines as given, Bezier curves by Bernstein sums."""
    curves = json.loads((DIR / f"{name}.json").read_text())["curves"]
    t = np.linspace(0.0, 1.0, 4001)
    rings = []
    for c in curves:
        if "circle" in c:
            (cx, cy), r = c["circle"]["center"], c["circle"]["radius"]
            a = 2 * math.pi * t
        elif "arc" in c:
            (cx, cy), r = c["arc"]["center"], c["arc"]["radius"]
            a = c["arc"]["start_angle"] + c["arc"]["sweep"] * t
        if "circle" in c or "arc" in c:
            rings.append(np.column_stack([cx + r * np.cos(a), cy + r * np.sin(a)]))
        elif "polyline" in c:
            rings.append(np.array(c["polyline"], dtype=float))
        else:
            p = np.array(c["control_points"], dtype=float)
            n = len(p) - 1
            b = np.stack([math.comb(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)])
            rings.append(b.T @ p)
    return rings


def winding(rings, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Signed crossings of the downward ray from each point with the polylines (the curves'
    winding numbers away from them)."""
    w = np.zeros(len(x), dtype=np.int64)
    for ring in rings:
        a, b = ring[:-1], ring[1:]
        for (ax, ay), (bx, by) in zip(a, b):
            straddles = (ax <= x) != (bx <= x)
            if not straddles.any():
                continue
            with np.errstate(divide="ignore", invalid="ignore"):
                yc = ay + (x - ax) * (by - ay) / (bx - ax)
            hit = straddles & (yc < y)
            w += np.where(hit, 1 if ax < bx else -1, 0)
    return w


def points(d: inrs.Domain, n: int = 60):
    x0, y0, x1, y1 = d.bounds
    gx = np.linspace(x0 - 0.1, x1 + 0.1, n) + 0.0037
    gy = np.linspace(y0 - 0.1, y1 + 0.1, n) + 0.0053
    x, y = np.meshgrid(gx, gy)
    return x.ravel(), y.ravel()


def filled(w: np.ndarray, rule: str) -> np.ndarray:
    return (w % 2 == 1) if rule == "even-odd" else (w != 0)


@pytest.mark.parametrize("name", NAMES)
def test_classify_and_winding_follow_the_rule(name):
    d = inrs.Domain.load(str(DIR / f"{name}.json"))
    x, y = points(d)
    w = winding(polygon(name), x, y)
    codes_any = {}
    for rule in RULES:
        want = np.where(filled(w, rule), inrs.INSIDE, inrs.OUTSIDE)
        for method in METHODS:
            got = d.classify(x, y, method=method, fill_rule=rule)
            away = got != inrs.BOUNDARY
            assert away.mean() > 0.95
            assert np.array_equal(got[away], want[away]), (name, rule, method)
            codes_any[(rule, method)] = got
        many = inrs.classify_many([d, d], np.column_stack([x, y]), fill_rule=rule)
        assert np.array_equal(many[1], codes_any[(rule, "fast")])
    away = codes_any[("even-odd", "fast")] != inrs.BOUNDARY
    assert np.array_equal(np.round(d.winding(x, y))[away], w[away])


@pytest.mark.parametrize("name", NAMES)
def test_green_capabilities_follow_the_rule_or_name_the_crossing(name):
    d = inrs.Domain.load(str(DIR / f"{name}.json"))
    x0, y0, x1, y1 = d.bounds
    xe, ye = np.linspace(x0 - 0.5, x1 + 0.5, 41), np.linspace(y0 - 0.5, y1 + 0.5, 37)
    cell = (xe[1] - xe[0]) * (ye[1] - ye[0])
    for rule in RULES:
        if name in CROSSING:
            for call in (
                lambda: d.filled_area(rule),
                lambda: d.cell_fractions(xe, ye, fill_rule=rule),
                lambda: inrs.cubature(d, 4, fill_rule=rule),
                lambda: d.integrate(lambda x, y: x * 0 + 1, 4, fill_rule=rule),
            ):
                with pytest.raises(ValueError, match="cross") as e:
                    call()
                assert "\n" not in str(e.value)
            assert d.summary().filled_area is None
            continue
        area = AREAS[(name, rule)]
        assert d.filled_area(rule) == pytest.approx(area, rel=1e-12)
        fractions = d.cell_fractions(xe, ye, fill_rule=rule)
        assert fractions.sum() * cell == pytest.approx(area, rel=1e-11)
        nodes, weights = inrs.cubature(d, 6, fill_rule=rule)
        assert weights.sum() == pytest.approx(area, rel=1e-12)
        codes = d.classify(nodes, fill_rule=rule)
        assert (codes == inrs.INSIDE).all()
        assert d.integrate(lambda x, y: np.ones_like(x), 6, fill_rule=rule) == pytest.approx(area, rel=1e-12)
    if name not in CROSSING:
        assert d.summary().filled_area == pytest.approx(AREAS[(name, "even-odd")], rel=1e-12)
        assert d.area == d.summary().filled_area


def test_the_rules_differ_where_windings_are_even_and_not_zero():
    d = inrs.Domain.load(str(DIR / "nested_same.json"))
    centre = np.array([[0.1, 0.05]])
    assert d.classify(centre)[0] == inrs.OUTSIDE
    for method in METHODS:
        assert d.classify(centre, method=method, fill_rule="nonzero")[0] == inrs.INSIDE, method
    with pytest.raises(ValueError, match="fill rule"):
        d.classify(centre, fill_rule="winding")
    crossing = inrs.Domain.load(str(DIR / "overlapping.json"))
    with pytest.raises(ValueError, match="cross"):
        crossing.area

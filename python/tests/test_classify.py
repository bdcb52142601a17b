"""Classification on NumPy arrays against the command-line tool, the inRS paper's reference
counts, and independent truth; array handling; errors; pickling."""

import io
import pickle
import subprocess

import numpy as np
import pytest

import inrs
from conftest import FIXTURES, PAPER, fixture_meta, halton

METHODS = ["fast", "inrs1", "inrs2", "gwn"]
CODES = {"outside": inrs.OUTSIDE, "inside": inrs.INSIDE, "boundary": inrs.BOUNDARY}


@pytest.mark.parametrize("name", PAPER)
def test_every_method_equals_the_cli(name, cli, tmp_path):
    path = FIXTURES / "inrs-paper" / f"{name}.json"
    d = inrs.Domain.load(path)
    b = d.bounds
    pts = halton(60_000, (b[0], b[2], b[1], b[3]))
    # Points on the boundary and near it too: the curves' sample points nudged.
    csv = tmp_path / "p.csv"
    np.savetxt(csv, pts, delimiter=",", fmt="%.17g")
    for method in METHODS:
        out = subprocess.run(
            [cli, "classify", "--domain", path, "--points", csv, "--method", method],
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        want = np.array([CODES[l.rsplit(",", 1)[1]] for l in out.splitlines()[1:]], dtype=np.int8)
        got = d.classify(pts, method=method)
        assert got.dtype == np.int8
        assert np.array_equal(got, want), f"{name} {method}: {np.sum(got != want)} differ"


@pytest.mark.parametrize("name", PAPER)
def test_reference_inside_counts(name):
    meta = fixture_meta(name)
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / f"{name}.json")
    refs = meta["reference_inside_counts_halton"]
    # Two shapes of record: the paper's protocol (several N) or one N = 10^4 check.
    cases = [(int(n), r["inRS_nbox200_safe1_in"]) for n, r in refs.get("paper_protocol", {}).items()]
    if "N10000_check" in refs:
        r = refs["N10000_check"]
        cases.append((int(r["N"]), r["inRS_nbox100_safe1_in"]))
    assert cases, f"{name}: no reference counts"
    for n, want in cases:
        pts = halton(n, meta["bbox_xmin_xmax_ymin_ymax"])
        for method in ["fast", "inrs2"]:
            assert np.sum(d.classify(pts, method=method) == inrs.INSIDE) == want, (name, n, method)


def test_contains_covers_and_winding_on_a_circle():
    d = inrs.Domain.from_json('{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}')
    x = np.array([0.0, 0.5, 1.0, 1.5, -0.999999])
    y = np.zeros_like(x)
    assert d.classify(x, y).tolist() == [1, 1, 2, 0, 1]
    assert d.contains_xy(x, y).tolist() == [True, True, False, False, True]
    assert d.covers_xy(x, y).tolist() == [True, True, True, False, True]
    w = d.winding(x, y)
    assert w.dtype == np.float64
    assert np.allclose(w, [1, 1, 0.5, 0, 1], atol=1e-12)
    # Independent truth: inside the unit disc exactly when x^2 + y^2 < 1, away from the circle.
    rng = np.random.default_rng(7)
    pts = rng.uniform(-1.5, 1.5, size=(200_000, 2))
    r = np.hypot(pts[:, 0], pts[:, 1])
    far = np.abs(r - 1) > 1e-9
    assert np.array_equal(d.contains_xy(pts)[far], (r < 1)[far])


def test_any_layout_and_float32():
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "s4_disk_ellipse_segment.json")
    pts = halton(5000, (-0.5, 1.0, -1.0, 1.0))
    want = d.classify(pts)
    fortran = np.asfortranarray(pts)
    strided = np.column_stack([pts[:, 0], np.zeros(len(pts)), pts[:, 1]])[:, ::2]
    assert not strided.flags.c_contiguous
    assert np.array_equal(d.classify(fortran), want)
    assert np.array_equal(d.classify(strided), want)
    assert np.array_equal(d.classify(pts[::-1]), want[::-1])  # negative strides
    assert np.array_equal(d.classify(fortran[:, 0], fortran[:, 1]), want)  # column views
    assert np.array_equal(d.classify(strided[::3, 0], strided[::3, 1]), want[::3])
    big = halton(120_000, (-0.5, 1.0, -1.0, 1.0))  # the grid locator's path
    want_big = d.classify(big)
    assert np.array_equal(d.classify(np.asfortranarray(big)), want_big)
    assert np.array_equal(d.classify(big[::-1]), want_big[::-1])
    assert np.array_equal(d.classify(big[:, 0], big[:, 1], method="inrs2"), want_big)
    assert np.array_equal(d.classify(np.asfortranarray(big), method="gwn"), want_big)
    assert np.array_equal(d.classify(pts[:, 0], pts[:, 1]), want)
    assert np.array_equal(d.classify(pts[:, 0].tolist(), pts[:, 1].tolist()), want)
    # float32: converted exactly, so it equals float64 classification of the rounded points.
    p32 = pts.astype(np.float32)
    assert np.array_equal(d.classify(p32), d.classify(p32.astype(np.float64)))
    # Two arrays of any shape give that shape.
    grid_x, grid_y = np.meshgrid(np.linspace(-0.5, 1, 7), np.linspace(-1, 1, 5))
    assert d.classify(grid_x, grid_y).shape == (5, 7)
    assert np.array_equal(d.classify(pts, threads=1), want)
    assert d.classify(np.empty((0, 2))).shape == (0,)


def test_bad_input_raises_with_the_rust_message():
    with pytest.raises(OSError, match="nonexistent"):
        inrs.Domain.load("/nonexistent/domain.json")
    with pytest.raises(ValueError, match="invalid JSON"):
        inrs.Domain.from_json("{not json")
    with pytest.raises(ValueError, match="curve 0"):
        inrs.Domain.from_json('{"curves": [{"degree": 2, "control_points": [[0, 0]]}]}')
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "circle.json")
    with pytest.raises(ValueError, match=r"shape \(N, 2\)"):
        d.classify(np.zeros((4, 3)))
    with pytest.raises(ValueError, match="same shape"):
        d.classify(np.zeros(3), np.zeros(4))
    with pytest.raises(ValueError, match="unknown method"):
        d.classify(np.zeros((1, 2)), method="magic")
    with pytest.raises(ValueError, match="tolerance"):
        d.classify(np.zeros((1, 2)), tol=-1.0)
    with pytest.raises(ValueError, match=r"fill rule .*\(expected even-odd or nonzero\)"):
        d.classify(np.zeros((1, 2)), method="gwn", fill_rule="sideways")
    with pytest.raises(ValueError, match="threads"):
        d.classify(np.zeros((1, 2)), threads=0)
    # An open boundary: the crossing methods refuse it, gwn accepts it.
    arc = inrs.Domain.from_json(
        '{"curves": [{"arc": {"center": [0, 0], "radius": 1, "start_angle": 0, "sweep": 5.5}}]}'
    )
    with pytest.raises(ValueError, match="open boundary"):
        arc.classify(np.zeros((1, 2)))
    assert arc.classify(np.zeros((1, 2)), method="gwn").tolist() == [inrs.INSIDE]


def test_pickle_round_trip():
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "leaf_cubic.json")
    back = pickle.loads(pickle.dumps(d))
    assert back.to_json() == d.to_json()
    pts = halton(20_000, (d.bounds[0], d.bounds[2], d.bounds[1], d.bounds[3]))
    assert np.array_equal(back.classify(pts), d.classify(pts))
    assert "Domain(" in repr(d) and d.area > 0 and len(d.loops) == 1


def test_summary_has_named_read_only_attributes():
    # A disc of radius 2 with a hole of radius 1 (clockwise): two loops of one curve each.
    d = inrs.Domain.from_json(
        '{"curves": [{"circle": {"center": [0, 0], "radius": 2}},'
        ' {"arc": {"center": [0, 0], "radius": 1, "start_angle": 0, "sweep": -6.283185307179586}}]}'
    )
    s = d.summary()
    assert isinstance(s, inrs.DomainSummary)
    assert s.curves == 2 and s.max_degree == 2 and s.rational and s.bezier_pieces >= 8
    assert abs(s.filled_area - 3 * np.pi) < 1e-12 and abs(s.signed_area - 3 * np.pi) < 1e-12
    assert s.areas_converged
    assert np.allclose(s.bounds, (-2, -2, 2, 2), atol=1e-15)
    outer, hole = s.loops
    assert isinstance(outer, inrs.LoopSummary)
    assert (outer.first_curve, outer.last_curve, outer.closed) == (0, 0, True)
    assert (hole.first_curve, hole.last_curve, hole.closed) == (1, 1, True)
    assert abs(outer.signed_area - 4 * np.pi) < 1e-12 and abs(hole.signed_area + np.pi) < 1e-12
    assert hole.gap < 1e-12
    assert d.loops[1].signed_area == hole.signed_area and d.bounds == s.bounds
    assert d.area == s.filled_area and d.summary() is s  # computed once
    with pytest.raises(AttributeError):
        s.curves = 3
    with pytest.raises(AttributeError):
        hole.closed = False
    assert repr(s).startswith("DomainSummary(curves=2, loops=2, filled_area=9.42")
    assert repr(hole).startswith("LoopSummary(first_curve=1, last_curve=1, closed=True")
    # An open loop: no filled area; the area falls back to the signed area's size.
    arc = inrs.Domain.from_json(
        '{"curves": [{"arc": {"center": [0, 0], "radius": 1, "start_angle": 0, "sweep": 3.0}}]}'
    )
    assert arc.summary().filled_area is None and not arc.loops[0].closed
    assert arc.area == abs(arc.summary().signed_area) > 0


def test_other_formats_load():
    d = inrs.Domain.load(FIXTURES / "io" / "gear.svg")
    assert d.area > 0
    assert inrs.Domain.load(FIXTURES / "io" / "plate.dxf").area > 0


def test_fill_rules_by_any_of_their_names():
    # Two counter-clockwise circles, one inside the other: winding number 2 at the centre.
    d = inrs.Domain.from_json(
        '{"curves": [{"circle": {"center": [0, 0], "radius": 2}},'
        ' {"circle": {"center": [0, 0], "radius": 1}}]}'
    )
    pts = np.array([[0.0, 0.0], [1.5, 0.0], [3.0, 0.0]])
    for name in ["even-odd", "evenodd", "EvenOdd"]:
        assert d.classify(pts, method="gwn", fill_rule=name).tolist() == [0, 1, 0], name
    for name in ["nonzero", "non-zero", "NonZero"]:
        assert d.classify(pts, method="gwn", fill_rule=name).tolist() == [1, 1, 0], name


def test_winding_on_curves_is_the_average_across_the_jump():
    # The cubic (0,0), (0,1), (-1,1), (-1,0) evaluated in float64 at non-dyadic parameters: its
    # points lie on it only up to rounding, inside the boundary band.
    ctrl = np.array([[0.0, 0.0], [0.0, 1.0], [-1.0, 1.0], [-1.0, 0.0]])
    t = np.array([0.1, 0.4, 0.7])[:, None]
    pts = (
        (1 - t) ** 3 * ctrl[0]
        + 3 * t * (1 - t) ** 2 * ctrl[1]
        + 3 * t**2 * (1 - t) * ctrl[2]
        + t**3 * ctrl[3]
    )
    cubic = '{"degree": 3, "control_points": [[0, 0], [0, 1], [-1, 1], [-1, 0]]}'
    open_cubic = inrs.Domain.from_json('{"curves": [%s]}' % cubic)
    # LLNL Axom's values for these points (its primal_winding_number tests).
    axom = [0.276676361896, 0.310998033871, 0.305165888012]
    assert np.allclose(open_cubic.winding(pts), axom, atol=1e-9)
    closed = inrs.Domain.from_json(
        '{"curves": [%s, {"segment": {"from": [-1, 0], "to": [0, 0]}}]}' % cubic
    )
    assert np.allclose(closed.winding(pts), 0.5, atol=1e-12)
    assert closed.classify(pts).tolist() == [inrs.BOUNDARY] * 3
    assert closed.classify(pts, method="gwn").tolist() == [inrs.BOUNDARY] * 3
    # 1e-13 above the closing segment: in the default band, inside at tol=0.
    near = np.array([[-0.5, 1e-13]])
    # (The other pieces' angles are exact at the point itself, 1e-13 off the segment.)
    assert abs(closed.winding(near)[0] - 0.5) < 1e-12
    assert abs(closed.winding(near, tol=0.0)[0] - 1.0) < 1e-12


S = np.sqrt(0.5)
#: The unit circle as the standard rational quadratic NURBS (nine control points).
CIRCLE = {
    "degree": 2,
    "knots": [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
    "control_points": [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]],
    "weights": [1, S, 1, S, 1, S, 1, S, 1],
}


def test_a_domain_from_curves_is_the_json_one():
    d = inrs.Domain.from_curves([CIRCLE], name="unit circle")
    s = d.summary()
    assert s.curves == 1 and len(s.loops) == 1 and s.loops[0].closed and s.rational
    assert abs(s.filled_area - np.pi) < 1e-12 and abs(d.area - np.pi) < 1e-12
    assert d.name == "unit circle"
    fixture = inrs.Domain.load(FIXTURES / "inrs-paper" / "circle.json")
    pts = np.vstack([
        inrs.halton_points(20_000, (-1.5, -1.5, 1.5, 1.5)),
        np.column_stack([np.cos(np.linspace(0, 6, 50)), np.sin(np.linspace(0, 6, 50))]),
    ])
    for method in METHODS:
        assert np.array_equal(d.classify(pts, method=method), fixture.classify(pts, method=method))
    assert (d.classify(pts[-50:]) == inrs.BOUNDARY).all()
    # Arrays, a tuple, no weights: the same curves; the JSON round trip is exact.
    arrays = (2, np.array(CIRCLE["knots"], dtype=np.float32), np.array(CIRCLE["control_points"]),
              np.array(CIRCLE["weights"]))
    assert inrs.Domain.from_curves([arrays]).to_json() == inrs.Domain.from_curves([CIRCLE]).to_json()
    back = inrs.Domain.from_json(d.to_json())
    assert back.to_json() == d.to_json() and back.name == "unit circle"
    square = [
        (1, [0, 0, 1, 1], [a, b])
        for a, b in [((0, 0), (1, 0)), ((1, 0), (1, 1)), ((1, 1), (0, 1)), ((0, 1), (0, 0))]
    ]
    q = inrs.Domain.from_curves(square)
    assert abs(q.area - 1) < 1e-15 and q.bounds == (0.0, 0.0, 1.0, 1.0) and len(q.loops) == 1
    assert q.classify(np.array([[0.5, 0.5], [1.0, 0.5], [2.0, 0.5]])).tolist() == [1, 2, 0]


def test_from_curves_bad_input_names_the_curve():
    good = (1, [0, 0, 1, 1], [[0, 0], [1, 0]])
    cases = [
        ([good, (2, [0, 0, 0, 1, 1], [[0, 0], [1, 0], [1, 1]])], r"^curve 1: .*knot"),
        ([dict(CIRCLE, weights=[1, S, 1, S, 1, S, 1, S])], r"^curve 0: .*weights"),
        ([dict(CIRCLE, weights=[1, S, 1, -S, 1, S, 1, S, 1])], r"^curve 0: .*weight"),
        ([good, dict(CIRCLE, control_points=np.zeros((9, 3)))], r"^curve 1: control points must have shape \(M, 2\), got \(9, 3\)$"),
        ([good, good, (1, [0, 0, 1, 1], [[0, np.nan], [1, 0]])], r"^curve 2: .*not finite"),
        ([(1, [[0, 0, 1, 1]], [[0, 0], [1, 0]])], r"^curve 0: knots must have shape \(M,\), got \(1, 4\)$"),
        ([(1.5, [0, 0, 1, 1], [[0, 0], [1, 0]])], r"^curve 0: degree must be an integer, got 1.5$"),
        ([(-1, [0, 0, 1, 1], [[0, 0], [1, 0]])], r"^curve 0: degree must be an integer >= 0, got -1$"),
        ([(0, [0, 1], [[0, 0]])], r"^curve 0: "),
        ([(40, [0] * 41 + [1] * 41, [[0, 0]] * 41)], r"^curve 0: .*degree"),
        ([(1, ["a", 0, 1, 1], [[0, 0], [1, 0]])], r"^curve 0: knots must be numbers"),
        ([good, {"degree": 1, "knots": [0, 0, 1, 1]}], r"^curve 1: expected the keys degree, knots, control_points"),
        ([good, (1, [0, 0, 1, 1])], r"^curve 1: expected a dict or a tuple"),
        ([], r"^the domain has no curves$"),
        (CIRCLE, r"^curves must be a list"),
    ]
    for curves, message in cases:
        with pytest.raises(ValueError, match=message) as e:
            inrs.Domain.from_curves(curves)
        assert "\n" not in str(e.value)
    # The JSON reader says the same of the same curve.
    with pytest.raises(ValueError) as e:
        inrs.Domain.from_json('{"curves": [{"degree": 2, "knots": [0, 0, 0, 1, 1], "control_points": [[0, 0], [1, 0], [1, 1]]}]}')
    with pytest.raises(ValueError) as f:
        inrs.Domain.from_curves([(2, [0, 0, 0, 1, 1], [[0, 0], [1, 0], [1, 1]])])
    assert str(e.value) == str(f.value)


@pytest.mark.parametrize("algorithm", ["adaptive", "binary-search", "bezier-clipping"])
def test_winding_algorithms_equal_the_cli(algorithm, cli, tmp_path):
    # A closed rational boundary and an open cubic (fractional winding numbers).
    open_cubic = tmp_path / "open.json"
    open_cubic.write_text('{"curves": [{"degree": 3, "control_points": [[0, 0], [0, 1], [-1, 1], [-1, 0]]}]}')
    for path in [FIXTURES / "inrs-paper" / "leaf_cubic.json", open_cubic]:
        d = inrs.Domain.load(path)
        b = d.bounds
        pts = np.vstack([halton(3000, (b[0] - 0.1, b[2] + 0.1, b[1] - 0.1, b[3] + 0.1)), d.flatten(1e-3)[0][::7]])
        csv = tmp_path / "p.csv"
        np.savetxt(csv, pts, delimiter=",", fmt="%.17g")
        out = subprocess.run(
            [cli, "winding", "--domain", path, "--points", csv, "--algorithm", algorithm],
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        want = np.array([float(l.rsplit(",", 1)[1]) for l in out.splitlines()[1:]])
        got = d.winding(pts, algorithm=algorithm)
        assert np.array_equal(got, want), f"{path.name} {algorithm}: {np.sum(got != want)} differ"
        assert np.array_equal(d.winding(pts[:, 0], pts[:, 1], algorithm=algorithm, threads=1), got)
        # Every algorithm gives the same values up to rounding; the default is the adaptive one.
        assert np.allclose(got, d.winding(pts), atol=1e-9)
        if algorithm == "adaptive":
            assert np.array_equal(got, d.winding(pts))


def test_unknown_winding_algorithm():
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "circle.json")
    with pytest.raises(ValueError, match=r'^unknown winding algorithm "raycast" \(expected adaptive, binary-search or bezier-clipping\)$'):
        d.winding(np.zeros((1, 2)), algorithm="raycast")


def test_svg_path_data_errors_are_drawn_up_to_them_with_a_warning(tmp_path):
    f = tmp_path / "icon.svg"
    f.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg"><path id="tri" d="M 13,9 3,19 h 11 v -3 l"/></svg>'
    )
    with pytest.warns(UserWarning, match='path id="tri".*drawn up to its last complete segment'):
        d = inrs.Domain.load(f)
    # The quadrilateral drawn before the error: (13, 9), (3, 19), (14, 19), (14, 16).
    assert len(d.loops) == 1 and d.area == pytest.approx(56.5, rel=1e-12)

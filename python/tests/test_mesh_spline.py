"""Sampling, meshing and splines from Python."""

import json
import pickle
import subprocess
import warnings

import numpy as np
import pytest

import inrs
from conftest import FIXTURES


def test_sample_and_mesh():
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "s4_disk_ellipse_segment.json")
    pts, on_boundary = inrs.sample(d, 12)
    assert pts.shape[1] == 2 and on_boundary.dtype == bool and on_boundary.any()
    assert np.all(d.covers_xy(pts))
    assert np.all(d.classify(pts[~on_boundary]) == inrs.INSIDE)
    m = inrs.mesh(d, 8)
    v, t = m["vertices"], m["triangles"]
    assert v.shape[1] == 2 and t.shape[1] == 3
    a, b = v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]
    area = 0.5 * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    assert np.all(area > 0)
    e = m["curved_edges"]
    assert len(e["triangle"]) == len(e["u0"]) > 0
    for how, factor in [("ct", 3), ("ps", 6), ("clough-tocher", 3), ("PS", 6)]:
        r = inrs.mesh(d, 8, refine=how)
        assert len(r["triangles"]) % factor == 0
    assert len(inrs.mesh(d, 8, refine="none")["triangles"]) == len(t)
    with pytest.raises(ValueError, match=r'^unknown refinement "cubic" \(expected none, ct or ps\)$'):
        inrs.mesh(d, 8, refine="cubic")


def test_fit_reproduces_polynomials_and_pickles():
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "s4_disk_ellipse_segment.json")
    calls = []

    def f(x, y):
        calls.append(len(x))
        return 1 + x - 2 * y**2 + x * y**3

    s = inrs.fit(d, f, ny=6, degree=4)
    assert len(calls) == 1  # one vectorised call
    pts, _ = inrs.sample(d, 20)
    assert np.allclose(s(pts), f(pts[:, 0], pts[:, 1]), atol=1e-10)
    jet = s.evaluate(pts, derivatives=True)
    assert jet.shape == (len(pts), 3)
    assert np.allclose(jet[:, 1], 1 + pts[:, 1] ** 3, atol=1e-8)
    assert np.isnan(s.evaluate(np.array([[5.0, 5.0]]))).all()
    back = pickle.loads(pickle.dumps(s))
    assert np.array_equal(back(pts), s(pts))
    assert s.degree == 4 and s.triangles > 0 and s.dimension > s.triangles and s.space == "s0"
    with pytest.raises(ValueError, match="not finite"), np.errstate(invalid="ignore"):
        inrs.fit(d, lambda x, y: np.log(x - 100), ny=4, degree=2)


def _scattered(d, interior):
    """The boundary points of ``sample(d, 9)`` and ``interior`` Halton points strictly inside,
    shuffled: scattered data with the boundary covered."""
    pts, on_boundary = inrs.sample(d, 9)
    h = inrs.halton_points(400, d.bounds, start=7)
    h = h[d.classify(h) == inrs.INSIDE][:interior]
    xy = np.vstack([pts[on_boundary], h])
    return xy[np.random.default_rng(3).permutation(len(xy))]


def _polynomial(degree):
    """A polynomial of total degree ``degree`` whose coefficients do not cancel."""

    def f(x, y):
        v = np.zeros_like(x)
        for a in range(degree + 1):
            for b in range(degree + 1 - a):
                v += (((a * 7 + b * 3) % 5) - 1.7) * x**a * y**b
        return v

    return f


@pytest.mark.filterwarnings("ignore:.*between a boundary arc and its chord")
@pytest.mark.parametrize("name", ["s3_m_shape", "s4_disk_ellipse_segment", "s5_lune"])
@pytest.mark.parametrize("space, degree", [("ct", 3), ("ps", 2), ("s512", 3), ("min-energy", 1)])
def test_interpolate_reproduces_the_polynomials_of_its_space(name, space, degree):
    # ct and ps reproduce the polynomials of their degree; s512 those of its cubic local fits,
    # minimal energy the linear ones.
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / f"{name}.json")
    f = _polynomial(degree)
    xy = _scattered(d, 60)
    s = inrs.interpolate(d, xy, f(xy[:, 0], xy[:, 1]), space=space)
    assert s.space == space and s.degree == {"ct": 3, "ps": 2, "s512": 5, "min-energy": 2}[space]
    q = inrs.halton_points(5000, d.bounds, start=1000)
    q = np.vstack([q[d.covers_xy(q)], inrs.sample(d, 31)[0]])
    v = s(q)
    assert not np.isnan(v).any()
    assert np.max(np.abs(v - f(q[:, 0], q[:, 1]))) < 1e-10
    # One degree more is not reproduced (the test can fail).
    g = _polynomial(degree + 1)
    t = inrs.interpolate(d, xy, g(xy[:, 0], xy[:, 1]), space=space)
    assert np.max(np.abs(t(q) - g(q[:, 0], q[:, 1]))) > 1e-6


def test_interpolate_is_the_cli_fit_with_data(cli, tmp_path):
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "s4_disk_ellipse_segment.json")
    xy = _scattered(d, 40)
    z = np.sin(3 * xy[:, 0]) + xy[:, 1] ** 2
    data = tmp_path / "data.csv"
    np.savetxt(data, np.column_stack([xy, z]), delimiter=",", fmt="%.17g", header="x,y,z", comments="")
    path = FIXTURES / "inrs-paper" / "s4_disk_ellipse_segment.json"
    for space in ["ct", "ps", "s512", "min-energy"]:
        out = subprocess.run(
            [cli, "fit", "--domain", path, "--data", data, "--space", space],
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            s = inrs.interpolate(d, xy, z, space=space)
        assert json.loads(s.to_json()) == json.loads(out), space
        back = pickle.loads(pickle.dumps(s))
        assert back.space == space and np.array_equal(back(xy), s(xy))
        # Through the data, but for the points the warning names (not vertices).
        left_out = int(str(w[0].message).split()[0]) if w else 0
        assert np.sum(np.abs(s(xy) - z) > 1e-12) <= left_out < 3


def test_interpolate_warns_of_points_it_leaves_out():
    # Interior points only: the boundary's vertices are the curves' start points, and points
    # between the long chords and their arcs cannot be vertices.
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "s4_disk_ellipse_segment.json")
    h = inrs.halton_points(400, d.bounds)
    h = h[d.classify(h) == inrs.INSIDE][:120]
    with pytest.warns(UserWarning, match=r"^\d+ data points lie between a boundary arc .* \(xy\[\d+\]"):
        inrs.interpolate(d, h, h[:, 0])


def test_interpolate_bad_input_is_a_one_line_value_error():
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "s4_disk_ellipse_segment.json")
    xy = _scattered(d, 20)
    z = xy[:, 0] + 1
    nan_xy, inf_z = xy.copy(), z.copy()
    nan_xy[3, 1] = np.nan
    inf_z[4] = np.inf
    cases = [
        ((xy[:, :1], z), r"^xy must have shape \(N, 2\), got \(\d+, 1\)$"),
        ((xy.ravel(), z), r"^xy must have shape \(N, 2\)"),
        ((xy, z[:, None]), r"^z must have shape \(N,\), got \(\d+, 1\)$"),
        ((xy, z[:-1]), r"^data: \d+ points and \d+ values$"),
        ((nan_xy, z), r"^the point xy\[3\] = \(.*NaN\) is not finite$"),
        ((xy, inf_z), r"^the point xy\[4\] = .* has a value that is not finite$"),
        ((np.vstack([xy, [[9.0, 9.0]]]), np.append(z, 0.0)), r"^the point xy\[\d+\] = \(9, 9\) lies outside the domain$"),
        ((np.vstack([xy, xy[2:3]]), np.append(z, 0.0)), r"^the point xy\[\d+\] = .* repeats an earlier point$"),
    ]
    for args, message in cases:
        with pytest.raises(ValueError, match=message) as e:
            inrs.interpolate(d, *args)
        assert "\n" not in str(e.value)
    with pytest.raises(ValueError, match=r'^unknown space "s0" \(expected s512, ct, ps or min-energy\)$'):
        inrs.interpolate(d, xy, z, space="s0")

"""Sampling, meshing and splines from Python."""

import pickle

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
    assert s.degree == 4 and s.triangles > 0 and s.dimension > s.triangles
    with pytest.raises(ValueError, match="not finite"), np.errstate(invalid="ignore"):
        inrs.fit(d, lambda x, y: np.log(x - 100), ny=4, degree=2)

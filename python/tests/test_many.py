"""``inrs.classify_many``: many domains at once, each answer equal to ``Domain.classify``
(and to the command line's several-domain run); analytic answers; errors."""

import subprocess

import numpy as np
import pytest

import inrs
from conftest import FIXTURES, PAPER, halton

METHODS = ["fast", "inrs1", "inrs2", "gwn"]
CODES = {"outside": inrs.OUTSIDE, "inside": inrs.INSIDE, "boundary": inrs.BOUNDARY}


def disc(cx, r):
    return inrs.Domain.from_json(f'{{"curves": [{{"circle": {{"center": [{cx}, 0], "radius": {r}}}}}]}}')


def annulus(r0, r1):
    return inrs.Domain.from_json(
        '{"curves": [{"circle": {"center": [0, 0], "radius": %r}}, '
        '{"circle": {"center": [0, 0], "radius": %r}}]}' % (r1, r0)
    )


def paper_domains():
    return [inrs.Domain.load(FIXTURES / "inrs-paper" / f"{n}.json") for n in PAPER]


def boundary_points(domains):
    """Points on and very near every domain's curves (flattened boundaries, nudged)."""
    pts = []
    for d in domains:
        for ring in d.flatten(1e-3):
            pts.append(ring)
            pts.append(ring + 1e-12)
    return np.concatenate(pts)


@pytest.mark.parametrize("method", METHODS)
def test_shared_points_equal_one_classify_per_domain(method):
    domains = paper_domains()
    pts = np.concatenate([halton(3000, (-1.3, 1.3, -1.3, 1.3)), boundary_points(domains)])
    got = inrs.classify_many(domains, pts, method=method)
    assert len(got) == len(domains)
    for d, g in zip(domains, got):
        want = d.classify(pts, method=method)
        assert g.dtype == np.int8 and g.shape == (len(pts),)
        assert np.array_equal(g, want), f"{d.name} {method}: {np.sum(g != want)} differ"
    assert any((g == inrs.BOUNDARY).any() for g in got)


def test_one_array_per_domain_and_large_batches():
    domains = paper_domains()
    rng = np.random.default_rng(3)
    # Small batches, an empty one, and one large enough for the grid locator (split over the
    # cores); any layout (a Fortran-ordered array too).
    sizes = [10, 0, 400, inrs._inrs.FAST_METHOD_MIN_POINTS + 1000, 7, 1]
    arrays = [rng.uniform(-1.3, 1.3, size=(n, 2)) for n in sizes]
    arrays[2] = np.asfortranarray(arrays[2])
    got = inrs.classify_many(domains, arrays)
    for d, a, g in zip(domains, arrays, got):
        assert np.array_equal(g, d.classify(a))
    with pytest.raises(ValueError, match="one array per domain"):
        inrs.classify_many(domains, arrays[:2])


def test_discs_and_annuli_answer_analytically():
    domains = [disc(0, 1.0), annulus(1.0, 3.0), disc(0, 2.0)]
    pts = halton(5000, (-4, 4, -4, 4))
    r = np.hypot(pts[:, 0], pts[:, 1])
    keep = np.min(np.abs(r[:, None] - np.array([1.0, 2.0, 3.0])), axis=1) > 1e-6
    pts, r = pts[keep], r[keep]
    for (r0, r1), g in zip([(-1, 1), (1, 3), (-1, 2)], inrs.classify_many(domains, pts)):
        want = np.where((r > r0) & (r < r1), inrs.INSIDE, inrs.OUTSIDE).astype(np.int8)
        assert np.array_equal(g, want)
    # A list of pairs is one array of points.
    assert [g.tolist() for g in inrs.classify_many(domains, [[0.0, 0.0], [1.5, 0.0]])] == [
        [inrs.INSIDE, inrs.OUTSIDE],
        [inrs.OUTSIDE, inrs.INSIDE],
        [inrs.INSIDE, inrs.INSIDE],
    ]


def test_an_open_domain_raises_or_is_none_while_the_others_answer():
    open_arc = inrs.Domain.from_json(
        '{"curves": [{"arc": {"center": [0, 0], "radius": 1, "start_angle": 0, "sweep": 5.5}}]}'
    )
    domains = [disc(0, 1.0), open_arc, disc(0, 2.0)]
    pts = np.array([[0.0, 0.0], [1.5, 0.0]])
    with pytest.raises(ValueError, match="domain 1: "):
        inrs.classify_many(domains, pts)
    got = inrs.classify_many(domains, pts, errors="none")
    assert got[1] is None
    assert got[0].tolist() == [inrs.INSIDE, inrs.OUTSIDE]
    assert got[2].tolist() == [inrs.INSIDE, inrs.INSIDE]
    # The winding-number method accepts open boundaries, with its fill rule.
    got = inrs.classify_many(domains, pts, method="gwn", fill_rule="nonzero")
    assert [g.tolist() for g in got] == [
        d.classify(pts, method="gwn", fill_rule="nonzero").tolist() for d in domains
    ]


def test_bad_arguments_raise():
    d = disc(0, 1.0)
    pts = np.zeros((3, 2))
    with pytest.raises(ValueError, match="unknown method"):
        inrs.classify_many([d], pts, method="nope")
    with pytest.raises(ValueError, match="tolerance"):
        inrs.classify_many([d], pts, tol=-1.0)
    with pytest.raises(ValueError, match=r"shape \(N, 2\)"):
        inrs.classify_many([d], np.zeros((3, 3)))
    with pytest.raises(ValueError, match=r"points\[1\] must have shape"):
        inrs.classify_many([d, d], [pts, np.zeros(3)])
    with pytest.raises(ValueError, match="errors must be"):
        inrs.classify_many([d], pts, errors="ignore")
    with pytest.raises(TypeError, match="not an inrs.Domain"):
        inrs.classify_many(["circle.json"], pts)
    with pytest.raises(ValueError, match="threads"):
        inrs.classify_many([d], pts, threads=0)
    assert inrs.classify_many([], pts) == []
    assert [g.tolist() for g in inrs.classify_many([d, d], np.empty((0, 2)), threads=1)] == [[], []]


def test_every_face_equals_the_cli_several_domain_run(cli, tmp_path):
    plate = FIXTURES / "cad" / "plate.step"
    faces = inrs.cad_faces(plate)
    domains = [f.domain for f in faces] + paper_domains()
    pts = np.concatenate([halton(2000, (-1.5, 11.5, -1.5, 11.5)), halton(500, (-1.3, 1.3, -1.3, 1.3))])
    csv = tmp_path / "p.csv"
    np.savetxt(csv, pts, delimiter=",", fmt="%.17g")
    args = [cli, "classify", "--points", csv, "--domain", f"{plate}#face:*"]
    for n in PAPER:
        args += ["--domain", FIXTURES / "inrs-paper" / f"{n}.json"]
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout.splitlines()
    header = out[0].split(",")
    assert header[2:] == [f"plate.step#face:{f.index}" for f in faces] + [f"{n}.json" for n in PAPER]
    cols = np.array([[CODES[w] for w in line.split(",")[2:]] for line in out[1:]], dtype=np.int8)
    got = inrs.classify_many(domains, pts)
    assert np.array_equal(np.stack(got, axis=1), cols)

"""Python cells of docs/FRONTENDS.md not exercised elsewhere: the domain in JSON
(``Domain.to_json``) is what ``inrs convert`` writes, and ``Domain.summary`` states what
``inrs info`` prints, and ``sample(d, count=n)`` gives the Halton points of ``inrs sample
--count``."""

import re
import subprocess

import numpy as np
import pytest

import inrs

from conftest import FIXTURES, PAPER

DOMAINS = [FIXTURES / "inrs-paper" / f"{n}.json" for n in PAPER] + sorted((FIXTURES / "axom-contours").glob("*.svg"))[:2]


@pytest.mark.parametrize("path", DOMAINS, ids=lambda p: p.name)
def test_to_json_is_the_cli_convert(cli, path):
    out = subprocess.run([cli, "convert", "--domain", path], check=True, capture_output=True, text=True).stdout
    d = inrs.Domain.load(path)
    assert d.to_json() + "\n" == out
    assert inrs.Domain.from_json(out).to_json() == d.to_json()


@pytest.mark.parametrize("path", DOMAINS, ids=lambda p: p.name)
def test_summary_is_what_cli_info_prints(cli, path):
    out = subprocess.run([cli, "info", "--domain", path], check=True, capture_output=True, text=True).stdout
    s = inrs.Domain.load(path).summary()
    m = re.search(r"curves: (\d+)  Bezier pieces: (\d+)  max degree: (\d+)", out)
    assert m, out
    assert (s.curves, s.bezier_pieces, s.max_degree) == tuple(int(g) for g in m.groups())
    loops = re.findall(r"^\s*loop (\d+): curves (\d+)\.\.=(\d+)", out, re.M)
    assert loops and [(l.first_curve, l.last_curve) for l in s.loops] == [(int(a), int(b)) for _, a, b in loops]
    filled = re.search(r"filled area \(even-odd\): (\S+)", out)
    if s.filled_area is not None:
        assert filled and float(filled.group(1)) == pytest.approx(s.filled_area, rel=1e-11)


def test_sample_with_count_is_the_cli_halton_sample(cli):
    path = FIXTURES / "inrs-paper" / "s4_disk_ellipse_segment.json"
    out = subprocess.run([cli, "sample", "--domain", path, "--count", "77"], check=True, capture_output=True, text=True).stdout
    rows = [l.split(",") for l in out.splitlines()[1:]]
    d = inrs.Domain.load(path)
    pts, on_boundary = inrs.sample(d, count=77)
    assert pts.shape == (77, 2) and not on_boundary.any()
    assert [[float(x), float(y)] for x, y, kind in rows] == pts.tolist()
    assert all(kind == "interior" for *_, kind in rows)
    assert (d.classify(pts) == inrs.INSIDE).all()
    # Without count: the well-spaced points of --ny, 20 by default.
    assert np.array_equal(inrs.sample(d)[0], inrs.sample(d, 20)[0])
    for kwargs, message in [({"count": 0}, None), ({"count": -1}, "count must be positive"), ({"ny": 5, "count": 5}, "not both")]:
        with pytest.raises(ValueError, match=message):
            inrs.sample(d, **kwargs)


PLATE = FIXTURES / "cad" / "plate.step"


def test_cad_faces_are_what_cli_info_lists_and_load_reads_them(cli):
    out = subprocess.run([cli, "info", "--domain", PLATE], check=True, capture_output=True, text=True).stdout
    faces = inrs.cad_faces(PLATE)
    rows = re.findall(r"^face (\d+)\s+(\S+)\s+(\S+)\s+loops (\d+)  curves (\d+)", out, re.M)
    assert [(f.index, f.entity, f.surface, f.loops, f.curves) for f in faces] == [
        (int(k), e, s, int(l), int(c)) for k, e, s, l, c in rows
    ]
    assert faces[0].error is None and faces[0].area == pytest.approx(100 - 4 * np.pi, rel=1e-13)
    d = inrs.Domain.load(f"{PLATE}#face:0")
    assert d.to_json() == faces[0].domain.to_json()
    uv = np.array([[1.0, 1.0], [5.0, 5.0], [11.0, 5.0]])
    assert d.classify(uv).tolist() == [inrs.INSIDE, inrs.OUTSIDE, inrs.OUTSIDE]
    with pytest.raises(ValueError, match="face 3 does not exist"):
        inrs.Domain.load(f"{PLATE}#face:3")

"""``inrs.cad_model``: faces with their surfaces, outward normals and 3-D edges, shells and
solids, against OpenCASCADE on the test parts of ``cad_parts`` (written by OCC to STEP, IGES
faces mode and IGES B-rep mode) and on real files; the API's shapes and errors.

The surfaces and the classification of every face are checked in test_cad_occ.py; here: the
normals (our ``S_u x S_v`` oriented by the face's sense, against OCC's face normal at the same
3-D point), the edges (their samples on OCC's surface of the face, consecutive edges meeting),
and the solids' faces. Skips (or fails under ``INRS_REQUIRE_SYSTEM_FILES=1``) without OCP.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import inrs

import cad_files
import cad_parts

try:
    cad_files.load_ocp()
    OCP_ERROR = None
except ImportError as e:
    OCP_ERROR = f"OCP is not installed (pip install cadquery-ocp-novtk): {e}"

KINDS = ("step", "iges", "iges_brep")


def need_ocp() -> None:
    if OCP_ERROR is not None:
        if cad_files.require_system_files():
            pytest.fail(f"{OCP_ERROR} (INRS_REQUIRE_SYSTEM_FILES=1)", pytrace=False)
        pytest.skip(OCP_ERROR)


@pytest.fixture(scope="module")
def parts(tmp_path_factory):
    """Every part written once: ``{(part, kind): path}``."""
    if OCP_ERROR is not None:
        return None
    directory = tmp_path_factory.mktemp("model-parts")
    out = {}
    for name, part in cad_parts.write_parts(directory).items():
        for kind, path in part.files().items():
            out[(name, kind)] = path
    return out


def occ_normals(face, uv: np.ndarray) -> np.ndarray:
    """OCC's outward unit normals of ``face`` (its orientation applied) at OCC's ``(u, v)``."""
    from OCP.BRepGProp import BRepGProp_Face
    from OCP.gp import gp_Pnt, gp_Vec

    g = BRepGProp_Face(face)
    out = np.full((len(uv), 3), np.nan)
    for i, (u, v) in enumerate(uv):
        p, n = gp_Pnt(), gp_Vec()
        g.Normal(float(u), float(v), p, n)
        length = n.Magnitude()
        if length > 0:
            out[i] = (n.X() / length, n.Y() / length, n.Z() / length)
    return out


def inside_points(face, n: int, seed: int) -> np.ndarray:
    """Up to ``n`` random ``(u, v)`` points inside the face (by its own domain)."""
    u0, v0, u1, v1 = face.bbox
    rng = np.random.default_rng(seed)
    uv = np.column_stack([rng.uniform(u0, u1, 8 * n), rng.uniform(v0, v1, 8 * n)])
    return uv[face.domain.classify(uv) == inrs.INSIDE][:n]


@pytest.mark.parametrize("part", list(cad_parts.PARTS))
@pytest.mark.parametrize("kind", KINDS)
def test_normals_point_as_occs_face_normals(part, kind, parts):
    need_ocp()
    path = parts[(part, kind)]
    model = inrs.cad_model(path)
    shape = cad_parts.read_shape(path)
    occ = cad_parts.faces(shape)
    assert len(occ) == len(model.faces)
    checked = 0
    for k, face in enumerate(model.faces):
        uv = inside_points(face, 12, k)
        if len(uv) == 0:
            continue
        xyz = face.points(uv)
        ours = face.normals(uv)
        occ_uv, distance = cad_parts.project_points(occ[k], xyz)
        assert (distance <= 1e-9 * max(1.0, float(np.abs(xyz).max()))).all(), f"face {k}: {distance.max()}"
        theirs = occ_normals(occ[k], occ_uv)
        ok = np.isfinite(ours).all(axis=1) & np.isfinite(theirs).all(axis=1)
        # Away from singular points every normal exists on both sides, and they agree.
        assert ok.sum() >= len(uv) - 1, f"{part}.{kind} face {k}: {ours[~ok]}, {theirs[~ok]}"
        dots = np.einsum("ij,ij->i", ours[ok], theirs[ok])
        assert (dots > 1 - 1e-9).all(), f"{part}.{kind} face {k} ({face.surface}): {dots.min()}"
        assert np.allclose(np.linalg.norm(ours[ok], axis=1), 1.0, atol=1e-14)
        checked += int(ok.sum())
    assert checked > 0


@pytest.mark.parametrize("part", list(cad_parts.PARTS))
@pytest.mark.parametrize("kind", ("step", "iges_brep"))
def test_edges_lie_on_their_faces_and_chain(part, kind, parts):
    need_ocp()
    path = parts[(part, kind)]
    model = inrs.cad_model(path)
    occ = cad_parts.faces(cad_parts.read_shape(path))
    tolerance = max(model.tolerance or 0.0, 1e-9)
    for k, face in enumerate(model.faces):
        loops = face.edges
        assert face.natural_bounds or loops, f"{part}.{kind} face {k}: no edges"
        for l, loop in enumerate(loops):
            ends = []
            for e in loop:
                samples = e.sample(9)
                assert samples.shape == (9, 3)
                _uv, distance = cad_parts.project_points(occ[k], samples)
                assert (distance <= 10 * tolerance).all(), f"{part}.{kind} face {k} loop {l} {e}: {distance.max()}"
                ends.append((samples[0], samples[-1]))
                # points(t) at the window's ends are the sample's ends, in loop order.
                a, b = e.points([e.t0, e.t1])
                first, last = (b, a) if e.reversed else (a, b)
                assert np.allclose(first, samples[0], atol=1e-12) and np.allclose(last, samples[-1], atol=1e-12)
            # Consecutive edges meet (a degenerate edge at a pole is not written: the loop
            # may jump along a pole, which is one point in space anyway).
            for (_, end), (start, _) in zip(ends, ends[1:] + ends[:1]):
                assert math.dist(end, start) <= 10 * tolerance, f"{part}.{kind} face {k} loop {l}"


def test_solids_shells_and_faces_of_a_part_with_a_void(parts):
    need_ocp()
    model = inrs.cad_model(parts[("box_void", "step")])
    assert (model.format, len(model.solids), len(model.shells), len(model.faces)) == ("STEP", 1, 2, 7)
    assert model.tolerance == 1e-7 and model.length_unit[1] == 1.0
    (solid,) = model.solids
    outer, void = solid.shells
    assert outer.closed and void.closed
    assert (len(outer.faces), len(void.faces)) == (6, 1)
    assert solid.faces == outer.faces + void.faces
    sphere = model.faces[void.faces[0]]
    assert sphere.surface_kind == "sphere" and sphere.natural_bounds
    # The void's face is reversed: its outward normal (out of the solid) points to the centre.
    uv = inside_points(sphere, 5, 0)
    centre = np.array(cad_parts.VOID_CENTER)
    toward = centre - sphere.points(uv)
    assert (np.einsum("ij,ij->i", sphere.normals(uv), toward) > 0).all()
    assert "1 solids" in repr(model) and "7 faces" in repr(model)


def test_the_api_refuses_what_it_cannot_do(parts):
    need_ocp()
    path = parts[("sphere", "step")]
    (face,) = inrs.cad_faces(path)
    with pytest.raises(ValueError, match="cad_model"):
        face.points(np.zeros((1, 2)))
    (face,) = inrs.cad_model(path).faces
    with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
        face.points(np.zeros((3, 3)))
    assert face.points(np.zeros((0, 2))).shape == (0, 3)
    with pytest.raises(OSError):
        inrs.cad_model(path.parent / "missing.step")
    with pytest.raises(ValueError):
        inrs.cad_model(path, closure_tol=-1.0)


def test_a_real_assembly_is_placed_as_occ_places_it():
    need_ocp()
    source = dict(cad_files.all_files())["as1-tu-203.stp"]
    if not source.exists():
        if cad_files.require_system_files():
            pytest.fail(cad_files.missing_message(source), pytrace=False)
        pytest.skip(cad_files.missing_message(source))
    import tempfile, pathlib

    with tempfile.TemporaryDirectory() as scratch:
        path = cad_files.materialize(source, pathlib.Path(scratch))
        model = inrs.cad_model(path)
        occ = cad_parts.faces(cad_parts.read_shape(path))
        assert len(model.solids) == 18
        mm = 1.0  # the file is in millimetres
        for k in range(0, len(model.faces), 7):
            face = model.faces[k]
            uv = inside_points(face, 4, k)
            if len(uv):
                _uv, distance = cad_parts.project_points(occ[k], mm * face.points(uv))
                assert distance.max() <= 1e-9 * 500, f"face {k}: {distance.max()}"

"""Point in a B-rep solid (``CadSolid.classify``) against OpenCASCADE's
``BRepClass3d_SolidClassifier``, against constructions whose answer is known, and against closed
forms.

1. **Random points.** Every solid of every real file of ``cad_files`` (freecad-common's IDF
   library, gmsh-doc's demos) and of the test parts of ``cad_parts`` (STEP and IGES B-rep): random
   points (fixed seed) in OCC's box of the solid, ours against OCC's classifier built once per
   solid. No point may be IN for one and OUT for the other, except the ones listed in
   :data:`OCC_WRONG`, each of which is checked to be OCC's error (OCC contradicts itself inside a
   ball free of faces around it, ours does not). Ours ``boundary`` and OCC's ``ON`` are counted;
   ours is rare (under 1%, :data:`BOUNDARY_HEAVY` excepted) and every point ours puts on the
   boundary lies within twice the tolerance ``T`` of OCC's faces. A solid ours refuses
   (``ValueError``) must be listed in :data:`EXPECTED_REFUSALS` (none is).
2. **Near the boundary.** Points of our faces (inside their ``(u, v)`` domains) moved along our
   outward normals by 1e-2, 1e-4, 1e-6 and 1e-8 of the solid's size, both ways: the side is known
   by construction where the ball of the largest offset is free of faces (OCC's distance,
   ``BRepExtrema_DistShapeShape``). Ours is on that side or on the boundary, never on the other
   side; never on the boundary at 1e-2 and 1e-4, nor anywhere farther than ``2 T``. Points near
   edges and vertices: moved from OCC's edge points (and vertices) along the bisector of the
   adjacent faces' outward normals (out) and against it (in), where OCC confirms that side at
   1e-2 of the size and at the offset itself; ours never on the other side farther than ``2 T``
   from every face, and never on the boundary farther than that. The points once on the wrong
   side (:data:`ONCE_WRONG`) are asserted one by one.
3. **Degenerate rays on purpose.** Grids whose coordinates are the parts' face planes, vertex
   coordinates, axes and poles (the sphere's polar axis and seam plane, the torus's axis, both
   axes of the fused cylinders and lines grazing them, the cube with its spherical void, the
   B-spline block with its hole, the filleted plate), against exact distances in closed form:
   farther than ``2 T`` ours is exact, within ``T / 2`` (on the surface) it is ``boundary``.
4. **Hostile input and the API.** An open shell (STEP: no solid as OCC; an open void shell: a
   ``ValueError`` naming the free edges), a face reversed (``ValueError`` about the
   orientation), points of the wrong shape, pickling, threads.

Without OCP or the files the OCC tests skip with a message, and fail instead under
``INRS_REQUIRE_SYSTEM_FILES=1`` (``.ci/run`` sets it). ``pytest -s`` prints the counts.
"""

from __future__ import annotations

import math
import pathlib
import pickle
import threading
import time
import zlib
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

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

FIXTURES = pathlib.Path(__file__).resolve().parents[2] / "fixtures" / "cad"

unavailable = cad_files.unavailable

OUT, IN, ON = 0, 1, 2

#: Random points per solid (test 1); fewer where OCC is slow (up to 5 ms a point).
POINTS = 2000
FEWER_POINTS = {"as1-tu-203.stp": 300, "component8.step": 600, "t20_data.step": 600, "2225_SMD.stp": 1000}
#: OCC's classifier tolerance (absolute, millimetres), as cad_parts.
OCC_TOL = cad_parts.CLASSIFY_TOL
#: Ours ``boundary`` must be rarer than this among the random points.
BOUNDARY_RATE = 0.01

#: The offsets of test 2, relative to the solid's size (the diagonal of OCC's box).
OFFSETS = (1e-2, 1e-4, 1e-6, 1e-8)
#: The offsets at which ours must never answer ``boundary`` (test 2).
FAR_OFFSETS = (1e-2, 1e-4)

#: The solid parts of cad_parts (bspline_two_holes is a face) and the files tested of each.
SOLID_PARTS = [p for p in cad_parts.PARTS if cad_parts.VOLUMES.get(p) is not None]
PART_KINDS = ("step", "iges_brep")

#: Solids ours refuses (``ValueError``), ``{(file, solid): part of the message}``: none. Every
#: solid of the real files and the test parts classifies; a new refusal fails.
EXPECTED_REFUSALS: Dict[Tuple[str, int], str] = {}

#: Random points of test 1 where OCC is wrong, measured: ``{(file, solid): (points, why)}``. Each
#: listed point must still disagree (IN against OUT) and be shown OCC's error again: it lies
#: farther than ``2 T`` from every face (OCC's distance), so a ball around it holds no face and
#: one answer is right in all of it, and there ours answers as at the point while OCC answers
#: ours somewhere in it. A disagreement not listed fails, and so does a listed one that agrees.
OCC_WRONG: Dict[Tuple[str, int], Tuple[List[Tuple[float, float, float]], str]] = {
    ("component8.step", 0): (
        [(-7.402602620383837, 183.09151581175684, 14.212129194951242)],
        "1.79 mm from every face, ours IN; OCC answers OUT there and IN at 61 of 64 points of the "
        "ball of radius 1.6 mm around it (OUT at 11 of 200 points within 0.18 mm)",
    ),
    ("bspline_box_hole.step", 0): (
        [(2.0134981889514245, 2.99651982224964, 1.4893386751849735)],
        "in the hole (0.99660 from its axis, radius 1: OUT in closed form, 3.4e-3 from the "
        "hole's rational B-spline face), ours OUT; OCC answers IN at all 200 points within 3.4e-4 "
        "of it",
    ),
}

#: Files whose stated tolerance makes the band of ``T`` round the faces a larger share of the
#: box: ``{file: (largest boundary rate, why)}``.
BOUNDARY_HEAVY = {
    "component8.step": (
        0.03,
        "the file states a tolerance of 0.074 mm (T, 1.1e-3 of the solid's size): 9 of 600 points (1.5%) measured",
    ),
    "t20_data.step": (0.03, "the same part as component8.step"),
}


def need_ocp() -> None:
    if OCP_ERROR is not None:
        unavailable(OCP_ERROR)


# --- OCC's side ----------------------------------------------------------------------------------


def occ_solids(shape) -> list:
    """The solids of ``shape`` in ``TopExp_Explorer(shape, TopAbs_SOLID)`` order (inrs's)."""
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopoDS import TopoDS

    return [TopoDS.Solid(s) for s in cad_parts._explore(shape, TopAbs_SOLID)]


def occ_box(solid) -> Tuple[np.ndarray, np.ndarray]:
    """OCC's box of ``solid`` (``BRepBndLib.Add``, exact geometry): corners, millimetres."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    box = Bnd_Box()
    BRepBndLib.Add_s(solid, box, False)
    return np.array(box.CornerMin().Coord()), np.array(box.CornerMax().Coord())


class Faces:
    """OCC's distance from points to the faces of a solid (its boundary), millimetres."""

    def __init__(self, solid):
        from OCP.BRep import BRep_Builder
        from OCP.TopoDS import TopoDS_Compound

        self.compound = TopoDS_Compound()
        builder = BRep_Builder()
        builder.MakeCompound(self.compound)
        for face in cad_parts.faces(solid):
            builder.Add(self.compound, face)

    def distance(self, points) -> np.ndarray:
        from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
        from OCP.BRepExtrema import BRepExtrema_DistShapeShape
        from OCP.gp import gp_Pnt

        points = np.asarray(points, float).reshape(-1, 3)
        out = np.empty(len(points))
        for i, p in enumerate(points):
            vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, p))).Vertex()
            d = BRepExtrema_DistShapeShape(vertex, self.compound)
            out[i] = d.Value() if d.IsDone() else math.nan
        return out


@dataclass
class Case:
    """One solid, ours and OCC's. Lengths: ours in the file's unit, OCC's in millimetres
    (``mm`` per unit); ``size`` and ``tol`` (``T``) in the file's unit."""

    name: str
    index: int
    ours: "inrs.CadSolid"
    model: "inrs.CadModel"
    occ: object  # TopoDS_Solid
    mm: float
    lo: np.ndarray  # OCC's box, the file's unit
    hi: np.ndarray
    size: float
    tol: float
    _faces: Optional[Faces] = None

    def occ_codes(self, points) -> np.ndarray:
        return cad_parts.classify_solid(self.occ, np.asarray(points) * self.mm, OCC_TOL)

    def distance(self, points) -> np.ndarray:
        """OCC's distance from ``points`` to the solid's faces, the file's unit."""
        if self._faces is None:
            self._faces = Faces(self.occ)
        return self._faces.distance(np.asarray(points) * self.mm) / self.mm

    def where(self) -> str:
        return f"{self.name} solid {self.index}"


def cases(path: pathlib.Path, name: str) -> Tuple["inrs.CadModel", List[Case]]:
    """Our model of ``path`` and its solids paired with OCC's (the counts must agree)."""
    model = inrs.cad_model(path)
    solids = occ_solids(cad_parts.read_shape(path))
    if len(model.solids) != len(solids):
        pytest.fail(f"{name}: {len(model.solids)} solids, OCC {len(solids)}")
    mm = model.length_unit[1] if model.length_unit else 1.0
    out = []
    for k, (ours, occ) in enumerate(zip(model.solids, solids)):
        lo, hi = occ_box(occ)
        size = float(np.linalg.norm(hi - lo)) / mm
        tol = max(model.tolerance or 0.0, 1e-8 * size)
        out.append(Case(name, k, ours, model, occ, mm, lo / mm, hi / mm, size, tol))
    return model, out


def seed(name: str, k: int, what: str) -> np.random.Generator:
    return np.random.default_rng([zlib.crc32(name.encode()), k, zlib.crc32(what.encode())])


# --- files ----------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    return tmp_path_factory.mktemp("real")


@pytest.fixture(scope="module")
def parts(tmp_path_factory):
    """Every solid part of cad_parts, written once: ``{name: cad_parts.Part}``."""
    need_ocp()
    cad_parts.quiet()
    return cad_parts.write_parts(tmp_path_factory.mktemp("parts"), SOLID_PARTS)


def real_file(name: str, scratch) -> pathlib.Path:
    """The real file ``name`` (decompressed into ``scratch``), or skip / fail."""
    need_ocp()
    source = dict(cad_files.all_files())[name]
    if not source.exists():
        unavailable(cad_files.missing_message(source))
    return cad_files.materialize(source, scratch)


REAL = [n for n, _ in cad_files.all_files()]
PART_FILES = [f"{p}.{k}" for p in SOLID_PARTS for k in PART_KINDS]


def any_file(name: str, scratch, parts) -> pathlib.Path:
    """A real file by name, or a part as ``part.step`` / ``part.iges_brep``."""
    if name in dict(cad_files.all_files()):
        return real_file(name, scratch)
    part, kind = name.rsplit(".", 1)
    return parts[part].files()[kind]


# --- 1. random points against OCC ----------------------------------------------------------------


def arbitrate(case: Case, p: np.ndarray, ours_code: int) -> Tuple[bool, str]:
    """Whether the disagreement at ``p`` is OCC's error: ``p`` lies farther than ``2 T`` from
    every face (OCC's distance ``d``), so one answer holds in the whole ball of radius ``0.9 d``;
    ours answers ``ours_code`` at 64 random points of it, and OCC answers ``ours_code`` at some."""
    d = float(case.distance(p[None])[0])
    if not d > 2 * case.tol:
        return False, f"{d:.3g} from the faces (T {case.tol:.3g})"
    rng = np.random.default_rng(0)
    v = rng.normal(size=(64, 3))
    q = p + v / np.linalg.norm(v, axis=1)[:, None] * (0.9 * d * rng.uniform(0, 1, (64, 1)) ** (1 / 3))
    ours, occ = case.ours.classify(q), case.occ_codes(q)
    counts = [np.bincount(c, minlength=3).tolist() for c in (ours, occ)]
    text = f"{d:.3g} from the faces; in the ball (OUT, IN, ON) ours {counts[0]}, OCC {counts[1]}"
    return bool((ours == ours_code).all() and (occ == ours_code).any()), text


def compare_random(case: Case, n: int) -> dict:
    """Test 1 for one solid: ``n`` random points in OCC's box grown by 2%."""
    grow = 0.02 * (case.hi - case.lo)
    pts = seed(case.name, case.index, "random").uniform(case.lo - grow, case.hi + grow, (n, 3))
    start = time.perf_counter()
    ours = case.ours.classify(pts)
    t_ours = time.perf_counter() - start
    start = time.perf_counter()
    occ = case.occ_codes(pts)
    t_occ = time.perf_counter() - start
    bad = np.where(((ours == IN) & (occ == OUT)) | ((ours == OUT) & (occ == IN)))[0]
    boundary = np.where(ours == ON)[0]
    far = []
    if len(boundary):
        d = case.distance(pts[boundary])
        far = [(pts[i].tolist(), float(x)) for i, x in zip(boundary, d) if not x <= 2 * case.tol]
    return {
        "points": pts,
        "ours": ours,
        "occ": occ,
        "disagree": [(pts[i], int(ours[i]), int(occ[i])) for i in bad],
        "boundary": len(boundary),
        "on": int((occ == ON).sum()),
        "far_boundary": far,
        "times": (t_ours, t_occ),
    }


@pytest.mark.parametrize("name", REAL + PART_FILES)
def test_random_points_agree_with_occ(name, scratch, parts):
    path = any_file(name, scratch, parts)
    _, solids = cases(path, name)
    problems, lines = [], []
    for case in solids:
        where = case.where()
        try:
            case.ours.classify(np.zeros((0, 3)))
        except ValueError as e:
            expected = EXPECTED_REFUSALS.get((name, case.index))
            if expected is None or expected not in str(e):
                problems.append(f"{where}: refused: {e}")
            lines.append(f"{where}: refused as expected: {e}")
            continue
        if (name, case.index) in EXPECTED_REFUSALS:
            problems.append(f"{where}: listed as refused, but classifies")
        n = FEWER_POINTS.get(name, POINTS)
        r = compare_random(case, n)
        t_ours, t_occ = r["times"]
        lines.append(
            f"{where}: {n} points, {int((r['ours'] == IN).sum())} in; ours boundary {r['boundary']}, "
            f"OCC ON {r['on']}; {len(r['disagree'])} IN/OUT disagreements; ours {1e6 * t_ours / n:.0f} us, "
            f"OCC {1e6 * t_occ / n:.0f} us a point; T {case.tol:.3g}, size {case.size:.4g}"
        )
        listed, why = OCC_WRONG.get((name, case.index), ([], ""))
        found = {tuple(map(float, p)) for p, _, _ in r["disagree"]}
        for p, ours_code, occ_code in r["disagree"]:
            key = tuple(map(float, p))
            if key not in listed:
                problems.append(f"{where}: at {list(key)} ours {ours_code}, OCC {occ_code}")
                continue
            is_occs, text = arbitrate(case, p, ours_code)
            if not is_occs:
                problems.append(
                    f"{where}: at {list(key)} ours {ours_code}, OCC {occ_code}, listed as OCC's error but not "
                    f"shown so: {text}"
                )
            else:
                lines.append(f"  OCC wrong at {list(key)} (ours {ours_code}, OCC {occ_code}): {text}")
        for key in listed:
            if key not in found:
                problems.append(f"{where}: {list(key)} is listed in OCC_WRONG ({why}) but ours and OCC agree there now")
        limit, _ = BOUNDARY_HEAVY.get(name, (BOUNDARY_RATE, ""))
        if not r["boundary"] <= limit * n:
            problems.append(f"{where}: {r['boundary']} of {n} points on the boundary (more than {limit:.0%})")
        for p, d in r["far_boundary"]:
            problems.append(f"{where}: {p} is boundary for ours but {d:.3g} from OCC's faces (T {case.tol:.3g})")
    print(f"\n[random] {name}: {len(solids)} solids" + "".join("\n  " + l for l in lines))
    assert not problems, "\n".join(problems)


# --- 2. near the boundary ------------------------------------------------------------------------

#: The real files of test 2 (the parts are all tested, in STEP).
NEAR_FILES = ["1210_SMD.stp", "0603_SMD.stp", "EPL22_6_16.stp", "SOT404.stp", "CAP_50SGV_8_10.stp", "as1-tu-203.stp"]
#: The solids of a file tested in test 2 (all where not listed).
NEAR_SOLIDS = {"as1-tu-203.stp": [3, 4, 9, 10]}
NEAR_CASES = [f"{p}.step" for p in SOLID_PARTS] + ["revolved_bspline.iges_brep"] + NEAR_FILES
#: Points per face (test 2), at most so many per solid.
FACE_POINTS = 4
SOLID_FACE_POINTS = 160


def near_file(name: str, scratch, parts) -> pathlib.Path:
    if name.endswith(".step") and name[: -len(".step")] in cad_parts.PARTS:
        return parts[name[: -len(".step")]].step
    return any_file(name, scratch, parts)


def near_cases(name, scratch, parts) -> List[Case]:
    _, solids = cases(near_file(name, scratch, parts), name)
    keep = NEAR_SOLIDS.get(name)
    return [c for c in solids if keep is None or c.index in keep]


def face_samples(case: Case) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points of the solid's faces inside their ``(u, v)`` domains (ours), our outward
    normals there, and the radius ``r`` (the file's unit) such that the balls of radius ``r``
    about ``p + r n`` and ``p - r n`` hold no face (OCC's distance): 1e-2 of the size, or 1e-4
    where the first is not free; points free at neither are left out."""
    rng = seed(case.name, case.index, "faces")
    model = case.model
    points, normals = [], []
    for f in case.ours.faces:
        face = model.faces[f]
        if face.domain is None:
            continue
        u0, v0, u1, v1 = face.bbox
        uv = np.column_stack([rng.uniform(u0, u1, 16 * FACE_POINTS), rng.uniform(v0, v1, 16 * FACE_POINTS)])
        uv = uv[face.domain.classify(uv) == IN][:FACE_POINTS]
        if len(uv):
            points.append(face.points(uv))
            normals.append(face.normals(uv))
    p, n = np.concatenate(points), np.concatenate(normals)
    ok = np.isfinite(n).all(axis=1) & np.isfinite(p).all(axis=1)
    p, n = p[ok], n[ok]
    if len(p) > SOLID_FACE_POINTS:
        pick = np.sort(rng.choice(len(p), SOLID_FACE_POINTS, replace=False))
        p, n = p[pick], n[pick]
    radius = np.zeros(len(p))
    for rel in (1e-2, 1e-4):
        r = rel * case.size
        todo = np.where(radius == 0)[0]
        if not len(todo):
            break
        d_out = case.distance(p[todo] + r * n[todo])
        d_in = case.distance(p[todo] - r * n[todo])
        free = (d_out >= r * (1 - 1e-6)) & (d_in >= r * (1 - 1e-6))
        radius[todo[free]] = r
    keep = radius > 0
    return p[keep], n[keep], radius[keep]


def _xfail_near(names: List[str], known: Dict[str, str]) -> list:
    def mark(n):
        return pytest.mark.xfail(strict=True, raises=AssertionError, reason=known[n])

    return [pytest.param(n, marks=mark(n)) if n in known else n for n in names]


@pytest.mark.parametrize("name", NEAR_CASES)
def test_points_off_faces_are_on_their_side(name, scratch, parts):
    problems, lines = [], []
    for case in near_cases(name, scratch, parts):
        where = case.where()
        p, n, radius = face_samples(case)
        if len(p) == 0:
            lines.append(f"{where}: no face point with a free ball (thinner than 2e-4 of its size)")
            continue
        counts = {}
        for rel in OFFSETS:
            delta = rel * case.size
            use = radius >= delta
            q_out, q_in = p[use] + delta * n[use], p[use] - delta * n[use]
            out, inn = case.ours.classify(q_out), case.ours.classify(q_in)
            counts[rel] = (int(use.sum()), int((out == ON).sum() + (inn == ON).sum()))
            for q, codes, want in ((q_out, out, OUT), (q_in, inn, IN)):
                for i in np.where(codes == 1 - want)[0]:
                    problems.append(f"{where}: offset {rel:g}: {q[i].tolist()} is {codes[i]}, should be {want}")
                if rel in FAR_OFFSETS or delta > 2 * case.tol:
                    for i in np.where(codes == ON)[0]:
                        problems.append(
                            f"{where}: offset {rel:g} ({delta:.3g}, T {case.tol:.3g}): {q[i].tolist()} is boundary"
                        )
            if rel == OFFSETS[0]:
                # OCC agrees where the construction is sure (a check of our normals).
                occ_out, occ_in = case.occ_codes(q_out), case.occ_codes(q_in)
                for q, codes, want in ((q_out, occ_out, OUT), (q_in, occ_in, IN)):
                    for i in np.where(codes == 1 - want)[0]:
                        problems.append(
                            f"{where}: offset {rel:g}: OCC says {codes[i]} at {q[i].tolist()}, should be {want}"
                        )
        # The far offsets are farther than 2 T here, so "not boundary" is the contract's.
        assert all(rel * case.size > 2 * case.tol for rel in FAR_OFFSETS), (where, case.tol)
        lines.append(f"{where}: {len(p)} face points; (points, ours boundary) per offset {counts}")
    print(f"\n[faces] {name}" + "".join("\n  " + l for l in lines))
    assert not problems, "\n".join(problems[:40]) + f"\n({len(problems)} problems)"


def _normal(face, u: float, v: float) -> Optional[np.ndarray]:
    """OCC's outward unit normal of ``face`` (as oriented in its solid) at ``(u, v)``."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepLProp import BRepLProp_SLProps
    from OCP.TopAbs import TopAbs_REVERSED

    props = BRepLProp_SLProps(BRepAdaptor_Surface(face), u, v, 1, 1e-9)
    if not props.IsNormalDefined():
        return None
    n = np.array(props.Normal().Coord())
    return -n if face.Orientation() == TopAbs_REVERSED else n


def _shared(solid, kind) -> list:
    """``[(sub-shape, [faces])]``: each edge or vertex of ``solid`` with the faces (oriented as
    in the solid) that hold it."""
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopoDS import TopoDS

    groups: Dict[int, list] = {}
    for face in cad_parts._explore(solid, TopAbs_FACE):
        face = TopoDS.Face(face)
        for sub in cad_parts._explore(face, kind):
            bucket = groups.setdefault(hash(sub), [])
            for key, faces in bucket:
                if key.IsSame(sub):
                    if not any(f.IsSame(face) for f in faces):
                        faces.append(face)
                    break
            else:
                bucket.append((sub, [face]))
    return [entry for bucket in groups.values() for entry in bucket]


def edge_samples(solid, fractions=(0.31, 0.77)) -> List[Tuple[np.ndarray, np.ndarray]]:
    """``(point, direction)``: points of each edge between two different faces (no seams, no
    degenerate edges) and the bisector of the two faces' outward normals there (millimetres)."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopoDS import TopoDS

    out = []
    for edge, faces in _shared(solid, TopAbs_EDGE):
        edge = TopoDS.Edge(edge)
        if BRep_Tool.Degenerated_s(edge) or len(faces) != 2:
            continue
        curve = BRepAdaptor_Curve(edge)
        t0, t1 = curve.FirstParameter(), curve.LastParameter()
        for fraction in fractions:
            t = t0 + fraction * (t1 - t0)
            normals = []
            for face in faces:
                uv = BRepAdaptor_Curve2d(edge, face).Value(t)
                normals.append(_normal(face, uv.X(), uv.Y()))
            if any(n is None for n in normals):
                continue
            b = normals[0] + normals[1]
            if np.linalg.norm(b) < 0.1:  # a knife edge: no side to move to
                continue
            out.append((np.array(curve.Value(t).Coord()), b / np.linalg.norm(b)))
    return out


def vertex_samples(solid) -> List[Tuple[np.ndarray, np.ndarray]]:
    """``(vertex, direction)``: each vertex and the normalised sum of its faces' outward
    normals there (millimetres)."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_VERTEX
    from OCP.TopoDS import TopoDS

    out = []
    for vertex, faces in _shared(solid, TopAbs_VERTEX):
        vertex = TopoDS.Vertex(vertex)
        total = np.zeros(3)
        for face in faces:
            uv = BRep_Tool.Parameters_s(vertex, face)
            n = _normal(face, uv.X(), uv.Y())
            if n is not None:
                total += n
        if np.linalg.norm(total) < 0.1:
            continue
        out.append((np.array(BRep_Tool.Pnt_s(vertex).Coord()), total / np.linalg.norm(total)))
    return out


#: Test 2 near edges and vertices, measured wrong: ``{case: why}``; xfail, strict, so that a
#: fix fails the mark until it is removed. None today: the wrong sides found on 2026-12-05 (see
#: :data:`ONCE_WRONG`) were crossings near the end of a bounded surface's parameter range,
#: where Newton's iterate left the range and stalled; fixed, and those points are now asserted.
EDGE_BUGS: Dict[str, str] = {}


def check_edges_and_vertices(case: Case) -> Tuple[List[str], str]:
    """Test 2 near the edges and vertices of one solid: ``(problems, summary)``."""
    where = case.where()
    problems = []
    summary = []
    for what, samples in (("edge", edge_samples(case.occ)), ("vertex", vertex_samples(case.occ))):
        if not samples:
            continue
        p = np.array([s[0] for s in samples]) / case.mm
        b = np.array([s[1] for s in samples])
        # The construction holds at the largest offset where OCC agrees with it on both sides.
        big = OFFSETS[0] * case.size
        sure = (case.occ_codes(p + big * b) == OUT) & (case.occ_codes(p - big * b) == IN)
        p, b = p[sure], b[sure]
        counts = dict(samples=len(samples), sure=int(sure.sum()), unconfirmed=0, wrong_within_2T=0, boundary=0)
        for rel in OFFSETS:
            delta = rel * case.size
            for sign, want in ((1, OUT), (-1, IN)):
                q = p + sign * delta * b
                ours = case.ours.classify(q)
                suspicious = np.where(ours != want)[0]
                if not len(suspicious):
                    continue
                occ = case.occ_codes(q[suspicious])
                d = case.distance(q[suspicious])
                for i, o, dist in zip(suspicious, occ, d):
                    if ours[i] == ON:
                        counts["boundary"] += 1
                        if dist > 2 * case.tol:
                            problems.append(
                                f"{where}: {what} offset {rel:g}: {q[i].tolist()} is boundary, {dist:.3g} from the "
                                f"faces (T {case.tol:.3g})"
                            )
                        continue
                    if o != want:
                        counts["unconfirmed"] += 1  # OCC does not confirm the side here
                        continue
                    if dist <= 2 * case.tol:
                        counts["wrong_within_2T"] += 1
                        continue
                    problems.append(
                        f"{where}: {what} offset {rel:g}: {q[i].tolist()} is {ours[i]}, should be {want} "
                        f"(OCC {o}), {dist:.3g} from the faces (T {case.tol:.3g})"
                    )
        summary.append(f"{dict(edge='edges', vertex='vertices')[what]} {counts}")
    return problems, f"{where}: " + "; ".join(summary)


@pytest.mark.parametrize("name", _xfail_near(NEAR_CASES, EDGE_BUGS))
def test_points_near_edges_and_vertices_are_on_their_side(name, scratch, parts):
    problems, lines = [], []
    for case in near_cases(name, scratch, parts):
        p, s = check_edges_and_vertices(case)
        problems += p
        lines.append(s)
    print(f"\n[edges] {name}" + "".join("\n  " + l for l in lines))
    assert not problems, "\n".join(problems[:40]) + f"\n({len(problems)} problems)"


#: Points ours once classified wrongly (found 2026-12-05 off edges and vertices, fixed the same
#: day: a crossing near the end of a bounded surface's parameter range was missed when Newton's
#: iterate left the range): ``{file: [(solid, point, answer)]}``. Each answer is shown again by
#: the test (OCC gives it and the point lies farther than ``2 T`` from every face, OCC's
#: distance), and ours must give it.
ONCE_WRONG: Dict[str, List[Tuple[int, Tuple[float, float, float], int]]] = {
    "revolved_bspline.step": [
        (0, (1.0001, 0.0, -1e-4), OUT),  # below the base's rim, 1.3e-4 from the faces
        (0, (-0.36816600037748437, 0.9298811708104731, 3.000693820038853), OUT),  # above the top rim
    ],
    "revolved_bspline.iges_brep": [
        (0, (1.0001, 0.0, -1e-4), OUT),
        (0, (-0.36816600037750313, 0.9298811708104656, 3.000693820038853), OUT),
    ],
    "0603_SMD.stp": [
        (0, (-0.03544327679126471, 0.06717270266329747, 0.302001282810407), OUT),  # 1.8e-6 off
        (0, (0.04368598762819634, 0.06603207225883977, 0.301998717189593), IN),  # 1.3e-6 off
    ],
    "0805_SMD.stp": [(0, (-0.08346598419268957, 0.4033789952282059, 0.7820017569897002), OUT)],  # 2.5e-6
    "1206_SMD.stp": [(0, (-0.2135306100056504, 0.23683739293577882, 1.0020026271663747), OUT)],  # 3.7e-6
    "1812_SMD.stp": [(0, (0.7745739323054018, 0.8630006100366527, 1.6020040654893755), OUT)],  # 5.8e-6
    "2225_SMD.stp": [(0, (-0.6456465365646243, 0.5145820940011817, 1.4500061331600915), OUT)],  # 8.7e-6
    "2512_SMD.stp": [(0, (-0.4497060823110865, -0.5131780684435211, 1.60138), OUT)],  # 7.2e-6
    "VC0603_SMD.stp": [(0, (-0.06717270266329747, -0.03544327679126471, 0.302001282810407), OUT)],  # 1.8e-6
    "as1-tu-203.stp": [
        (2, (190.0000900000001, 75.0, 54.999819999999794), OUT),  # 2.0e-4 off (100 T)
        (3, (25.0, 67.49553323380258, 33.00223338309871), OUT),  # 5.0e-3 off (10^4 T)
        (4, (28.32053065821535, 78.7382184620616, -2.9999798878144253), IN),  # 2.0e-5 off (71 T)
        (10, (50.820627730687086, 58.27129119777155, 19.999833717108306), IN),  # 1.7e-4 off (71 T)
    ],
}


@pytest.mark.parametrize("name", list(ONCE_WRONG))
def test_once_wrong_points(name, scratch, parts):
    if name.startswith("revolved_bspline."):
        path = parts["revolved_bspline"].files()[name.rsplit(".", 1)[1]]
    else:
        path = real_file(name, scratch)
    _, solids = cases(path, name)
    wrong = []
    for k, point, answer in ONCE_WRONG[name]:
        case = solids[k]
        p = np.array([point])
        # The answer, shown: OCC's, farther than 2 T from every face.
        if case.occ_codes(p)[0] != answer:
            pytest.fail(f"{name} solid {k} {point}: OCC no longer answers {answer}")
        d = case.distance(p)[0]
        if not d > 2 * case.tol:
            pytest.fail(f"{name} solid {k} {point}: {d:.3g} from the faces, T {case.tol:.3g}")
        ours = int(case.ours.classify(p)[0])
        if ours != answer:
            wrong.append(
                f"solid {k} {list(point)}: ours {ours}, should be {answer} ({d:.3g} from the faces, T {case.tol:.3g})"
            )
    assert not wrong, f"{name}: " + "; ".join(wrong)


# --- 3. degenerate rays on purpose: closed forms ------------------------------------------------


def _capped_cylinder(radial: np.ndarray, axial: np.ndarray, r: float, h: float) -> np.ndarray:
    """Exact signed distance (negative inside) to the cylinder of radius ``r``, ``|axial| <= h``."""
    a, b = radial - r, np.abs(axial) - h
    outside = np.hypot(np.maximum(a, 0), np.maximum(b, 0))
    return np.where((a > 0) | (b > 0), outside, np.maximum(a, b))


def _box_sdf(p: np.ndarray, lo, hi) -> np.ndarray:
    """Exact signed distance to the box ``[lo, hi]`` (any dimension)."""
    centre, half = (np.asarray(lo) + hi) / 2, (np.asarray(hi) - lo) / 2
    q = np.abs(p - centre) - half
    return np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)


def _rounded_rect_sdf(p2: np.ndarray, lo, hi, radius: float) -> np.ndarray:
    """Exact signed distance to the rectangle ``[lo, hi]`` with corners rounded by ``radius``."""
    centre, half = (np.asarray(lo) + hi) / 2, (np.asarray(hi) - lo) / 2 - radius
    q = np.abs(p2 - centre) - half
    return np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0) - radius


def _prism(d2: np.ndarray, z: np.ndarray, z0: float, z1: float) -> np.ndarray:
    """Exact signed distance to the prism ``R x [z0, z1]`` from the exact signed 2-D distance
    ``d2`` to ``R``."""
    dz = np.maximum(z0 - z, z - z1)
    outside = np.hypot(np.maximum(d2, 0), np.maximum(dz, 0))
    return np.where((d2 > 0) | (dz > 0), outside, np.maximum(d2, dz))


def _holed(outer: np.ndarray, rho: np.ndarray, radius: float) -> np.ndarray:
    """Signed 2-D distance to a region less a disc of ``radius`` (``rho`` from its centre) that
    lies well inside it (``outer`` the region's exact signed distance): exact."""
    hole = rho - radius
    return np.where(outer > 0, outer, np.where(hole < 0, -hole, -np.minimum(-outer, hole)))


def _axis(n: int, lo: float, hi: float) -> np.ndarray:
    return np.linspace(lo, hi, n)


def _grid(*axes) -> np.ndarray:
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(axes))


def _line(fixed: dict, along: int, values) -> np.ndarray:
    """Points with the coordinates of ``fixed`` ({axis: value}) and ``values`` along ``along``."""
    pts = np.zeros((len(values), 3))
    pts[:, along] = values
    for k, v in fixed.items():
        pts[:, k] = v
    return pts


def sphere_points():
    cx, cy, cz = cad_parts.SPHERE_CENTER
    r = cad_parts.SPHERE_RADIUS
    q = _axis(49, -3.0, 3.0)  # steps of 1/8: the poles, the centre, the equator
    pts = [
        _line({0: cx, 1: cy}, 2, cz + q),  # the polar axis, through both poles
        *[_line({0: cx + dx, 1: cy}, 2, cz + q) for dx in (1e-9, 1e-6, 1e-3, 0.5, r)],  # beside it
        _grid(cx + q[::2], [cy], cz + q[::2]),  # the seam's plane (y = cy) and the meridian
        _grid(cx + q[::2], cy + q[::2], [cz]),  # the equator's plane
        np.array([[cx, cy, cz - r], [cx, cy, cz + r], [cx + r, cy, cz], [cx, cy + r, cz]]),
    ]
    pts = np.concatenate(pts)
    rho = np.linalg.norm(pts - cad_parts.SPHERE_CENTER, axis=1)
    return pts, rho - r


def torus_points():
    c = np.array(cad_parts.TORUS_CENTER)
    a = np.array(cad_parts.TORUS_AXIS) / np.linalg.norm(cad_parts.TORUS_AXIS)
    big, small = cad_parts.TORUS_RADII
    u = np.cross(a, [1.0, 0.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(a, u)
    s = _axis(81, -5.0, 5.0)  # steps of 1/8 through the tube's surface (2, 4) and centre (3)
    theta = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    pts = np.concatenate(
        [
            c + np.outer(_axis(33, -4.0, 4.0), a),  # the axis: outside, 2 or more from the tube
            c + np.outer(s, u),
            c + np.outer(s, v),
            c + np.outer(s, (u + v) / math.sqrt(2)) + 0.5 * a,
            c + big * (np.outer(np.cos(theta), u) + np.outer(np.sin(theta), v)),  # the tube's core
        ]
    )
    d = pts - c
    h = d @ a
    rho = np.linalg.norm(d - np.outer(h, a), axis=1)
    return pts, np.hypot(rho - big, h) - small


def fused_cylinders_points():
    (rz, hz), (rx, hx) = cad_parts.CYLINDER_Z, cad_parts.CYLINDER_X
    g = _axis(29, -3.5, 3.5)  # steps of 1/4: the end caps (3) and the z cylinder (1) on the grid
    lines = [
        _line({0: 0.0, 1: 0.0}, 2, g),  # the z axis, through both x-cylinder sides (z = +-0.8)
        _line({1: 0.0, 2: 0.0}, 0, g),  # the x axis, through the z cylinder (x = +-1)
        _line({0: 0.0, 2: 0.0}, 1, g),  # the y axis
        _line({1: 0.0, 2: rx}, 0, g),  # grazing the top line of the x cylinder
        _line({1: rx, 2: 0.0}, 0, g),  # grazing its side line
        _line({0: rz, 1: 0.0}, 2, g),  # grazing the z cylinder
        _line({0: 0.0, 1: rz}, 2, g),
        _line({0: hx, 1: 0.0}, 2, g),  # in the plane of the x cylinder's end cap
        _line({2: hz, 1: 0.0}, 0, g),  # in the plane of the z cylinder's end cap
    ]
    pts = np.concatenate(lines + [_grid(g, g, g)])  # the lines first (OCC_SUBSET)
    x, y, z = pts.T
    sa = _capped_cylinder(np.hypot(x, y), z, rz, hz)
    sb = _capped_cylinder(np.hypot(y, z), x, rx, hx)
    # Outside both: the nearer (exact). Inside one: at least as deep as in that one (the
    # union's faces are the cylinders' faces outside the other).
    signed = np.where(np.minimum(sa, sb) > 0, np.minimum(sa, sb), -np.maximum(np.maximum(-sa, -sb), 0))
    return pts, signed


def box_void_points():
    (x0, y0, z0), edge = cad_parts.VOID_BOX
    g = _axis(21, -2.5, 2.5)  # steps of 1/4: the faces' planes, edges, vertices, the void's poles
    pts = _grid(g, g, g)
    cube = _box_sdf(pts, (x0, y0, z0), (x0 + edge, y0 + edge, z0 + edge))
    ball = np.linalg.norm(pts - cad_parts.VOID_CENTER, axis=1) - cad_parts.VOID_RADIUS
    signed = np.where(cube >= 0, cube, np.where(ball < 0, -ball, -np.minimum(-cube, ball)))
    return pts, signed


def bspline_box_hole_points():
    lx, ly, lz = cad_parts.HOLED_BOX
    hx, hy, hr = cad_parts.HOLED_BOX_HOLE
    pts = _grid(_axis(21, -0.5, 4.5), _axis(21, -0.5, 4.5), _axis(13, -0.5, 2.5))  # steps of 1/4
    d2 = _holed(_box_sdf(pts[:, :2], (0, 0), (lx, ly)), np.hypot(pts[:, 0] - hx, pts[:, 1] - hy), hr)
    return pts, _prism(d2, pts[:, 2], 0.0, lz)


def filleted_plate_points():
    lx, ly, lz = cad_parts.PLATE
    hx, hy, hr = cad_parts.PLATE_HOLE
    f = cad_parts.PLATE_FILLET
    xs = [-0.5, 0.0, f / 2, f, 1.0, hx - hr, hx, hx + hr, 7.0, lx - f, lx - f / 2, lx, lx + 0.5]
    ys = [-0.5, 0.0, f / 2, f, hy - hr, hy, hy + hr, ly - f, ly - f / 2, ly, ly + 0.5]
    pts = _grid(xs, ys, [-0.5, 0.0, 0.25, lz / 2, lz, lz + 0.5])
    d2 = _holed(_rounded_rect_sdf(pts[:, :2], (0, 0), (lx, ly), f), np.hypot(pts[:, 0] - hx, pts[:, 1] - hy), hr)
    return pts, _prism(d2, pts[:, 2], 0.0, lz)


def cone_minus_sphere_points():
    r0, _r1, h = cad_parts.CONE
    centre_z, rs = cad_parts.CONE_SPHERE_CENTER[2], cad_parts.CONE_SPHERE_RADIUS
    z = _axis(33, -1.0, 3.0)  # steps of 1/8
    axis = _line({0: 0.0, 1: 0.0}, 2, z)  # the axis, through the sphere's south pole (z = 1.8)
    pole = centre_z - rs
    # Below the base: to the base; inside: to the base or the pole; in the ball: to the pole.
    axial = np.where(z < 0, -z, np.where(z <= pole, -np.minimum(z, pole - z), z - pole))
    # In the plane of the base: on it within the base's radius, else as far as its rim.
    g = _axis(17, -3.0, 3.0)
    plane = _grid(g, g, [0.0])
    rho = np.hypot(plane[:, 0], plane[:, 1])
    base = np.maximum(rho - r0, 0.0)
    return np.concatenate([axis, plane]), np.concatenate([axial, base])


#: Closed forms: ``{part: points() -> (points, signed distance)}`` (negative inside; exact, or
#: for the fused cylinders' insides a lower bound of the depth).
CLOSED_FORMS = {
    "sphere": sphere_points,
    "torus": torus_points,
    "fused_cylinders": fused_cylinders_points,
    "box_void": box_void_points,
    "bspline_box_hole": bspline_box_hole_points,
    "filleted_plate": filleted_plate_points,
    "cone_minus_sphere": cone_minus_sphere_points,
}
#: The points compared with OCC as well, where not all: the first so many (OCC takes 0.2 ms a
#: point on the fused cylinders; their 261 points on the lines).
OCC_SUBSET = {"fused_cylinders": 261}
CLOSED_CASES = [(p, k) for p in CLOSED_FORMS for k in PART_KINDS]


@pytest.mark.parametrize("part,kind", CLOSED_CASES, ids=[f"{p}.{k}" for p, k in CLOSED_CASES])
def test_degenerate_rays_against_closed_forms(part, kind, parts):
    path = parts[part].files()[kind]
    _, (case,) = cases(path, f"{part}.{kind}")
    pts, signed = CLOSED_FORMS[part]()
    ours = case.ours.classify(pts)
    truth = np.where(signed < 0, IN, OUT)
    far = np.abs(signed) > 2 * case.tol
    on = np.abs(signed) <= case.tol / 2
    problems = []
    for i in np.where(far & (ours != truth))[0]:
        problems.append(f"{pts[i].tolist()}: ours {ours[i]}, closed form {truth[i]} ({signed[i]:+.3g} from the faces)")
    for i in np.where(on & (ours != ON))[0]:
        problems.append(f"{pts[i].tolist()}: ours {ours[i]}, on a face ({signed[i]:+.3g})")
    for i in np.where(~far & ~on & (ours != truth) & (ours != ON))[0]:
        problems.append(f"{pts[i].tolist()}: ours {ours[i]}, closed form {truth[i]} ({signed[i]:+.3g}, within 2 T)")
    # OCC on the same points (its ON within its tolerance), for the record: its mistakes are
    # printed, ours fail.
    sub = np.arange(OCC_SUBSET.get(part, len(pts)))
    occ = case.occ_codes(pts[sub])
    occ_wrong = [
        (pts[i].tolist(), int(o), int(truth[i])) for i, o in zip(sub, occ) if far[i] and o != ON and o != truth[i]
    ]
    print(
        f"\n[closed form] {part}.{kind}: {len(pts)} points ({int(on.sum())} on a face, {int(far.sum())} "
        f"farther than 2 T {2 * case.tol:.2g}); ours boundary {int((ours == ON).sum())}; OCC on {len(sub)} "
        f"points: {len(occ_wrong)} wrong {occ_wrong[:3]}"
    )
    assert not problems, f"{part}.{kind}: " + "\n".join(problems[:30]) + f"\n({len(problems)} problems)"


# --- 4. hostile input and the API ------------------------------------------------------------------


def _box_faces(corner, size):
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    from OCP.gp import gp_Pnt

    return cad_parts.faces(BRepPrimAPI_MakeBox(gp_Pnt(*corner), *size).Shape())


def _shell(faces):
    from OCP.BRep import BRep_Builder
    from OCP.TopoDS import TopoDS_Shell

    shell = TopoDS_Shell()
    builder = BRep_Builder()
    builder.MakeShell(shell)
    for face in faces:
        builder.Add(shell, face)
    return shell


def _solid(*shells):
    from OCP.BRep import BRep_Builder
    from OCP.TopoDS import TopoDS_Solid

    solid = TopoDS_Solid()
    builder = BRep_Builder()
    builder.MakeSolid(solid)
    for shell in shells:
        builder.Add(solid, shell)
    return solid


def _sewed_open_box():
    """A 2 x 3 x 4 box without its last face, sewed into one open shell."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing

    sewing = BRepBuilderAPI_Sewing(1e-6)
    for face in _box_faces((0, 0, 0), (2.0, 3.0, 4.0))[:-1]:
        sewing.Add(face)
    sewing.Perform()
    return sewing.SewedShape()


def test_an_open_outer_shell_is_no_solid(tmp_path):
    """A box without a face, written as a solid (a MANIFOLD_SOLID_BREP of a CLOSED_SHELL that is
    open) and as a shell: neither is a solid, for OCC as for us: a free open shell."""
    need_ocp()
    cad_parts.quiet()
    shell = _sewed_open_box()
    for what, shape in (("solid", _solid(shell)), ("shell", shell)):
        path = cad_parts.write_step(shape, tmp_path / f"open_{what}.step")
        model = inrs.cad_model(path)
        topo = cad_parts.topology(path)
        assert model.solids == [] and topo.solids == [], (what, topo.summary())
        assert [(s.closed, list(s.faces)) for s in model.shells] == [(False, [0, 1, 2, 3, 4])], what
        assert [s.closed for s in topo.free_shells] == [False], what


def test_an_open_void_shell_is_refused_naming_its_free_edges(tmp_path):
    """A cube with a box-shaped void whose shell lacks a face (STEP ``BREP_WITH_VOIDS``): ours
    keeps the solid (its outer shell is closed) and refuses to classify, naming the void's
    four free edges."""
    need_ocp()
    cad_parts.quiet()
    void = _box_faces((-1, -1, -1), (2.0, 2.0, 2.0))[:-1]
    shape = _solid(_shell(_box_faces((-2, -2, -2), (4.0, 4.0, 4.0))), _shell(void).Reversed())
    path = cad_parts.write_step(shape, tmp_path / "open_void.step")
    model = inrs.cad_model(path)
    (solid,) = model.solids
    assert [(s.closed, len(s.faces)) for s in solid.shells] == [(True, 6), (False, 5)]
    # OCC reads the solid with its outer shell alone and the open void as a free shell (so
    # its classifier answers for the cube without the void); ours keeps the void and refuses.
    topo = cad_parts.topology(path)
    assert [[len(s.faces) for s in so.shells] for so in topo.solids] == [[6]], topo.summary()
    assert [(s.closed, len(s.faces)) for s in topo.free_shells] == [(False, 5)], topo.summary()
    with pytest.raises(ValueError) as e:
        solid.classify(np.array([[1.5, 1.5, 1.5]]))
    message = str(e.value)
    assert "\n" not in message
    assert "shell 1" in message and "is open" in message and "free edges" in message, message
    assert len(message.split("free edges:")[1].split(",")) == 4, message
    with pytest.raises(ValueError, match="is open"):
        solid.contains_xyz(np.array([[0.0, 0.0, 0.0]]))


def _iges_open_voids(tmp_path) -> Dict[str, pathlib.Path]:
    """IGES B-rep files (514 shells written with form 1, closed, by OCC) of a cube with an open
    void: a box void without its top (a large hole) and a thin slab void without one end (a
    hole of 2e-4 of the area)."""
    big = _box_faces((-1, -1, -1), (2.0, 2.0, 2.0))[:-1]
    slab = _box_faces((-1, -1, -0.005), (2.0, 2.0, 0.01))[1:]
    out = {}
    for name, void in (("box", big), ("slab", slab)):
        shape = _solid(_shell(_box_faces((-2, -2, -2), (4.0, 4.0, 4.0))), _shell(void).Reversed())
        out[name] = cad_parts.write_iges(shape, tmp_path / f"open_{name}_void_brep.igs", brep=True)
    return out


@pytest.mark.parametrize("void", ["box", "slab"])
def test_an_open_iges_void_shell_is_refused_naming_its_free_edges(void, tmp_path):
    need_ocp()
    cad_parts.quiet()
    path = _iges_open_voids(tmp_path)[void]
    (solid,) = inrs.cad_model(path).solids
    try:
        solid.classify(np.array([[1.5, 1.5, 1.5]]))
        message = None
    except ValueError as e:
        message = str(e)
    assert message is not None and "is open, so its volume is not defined; free edges: " in message, message


def test_a_reversed_face_is_refused_for_its_orientation(tmp_path):
    need_ocp()
    cad_parts.quiet()
    from OCP.TopoDS import TopoDS

    faces = _box_faces((0, 0, 0), (2.0, 3.0, 4.0))
    faces[-1] = TopoDS.Face(faces[-1].Reversed())
    path = cad_parts.write_step(_solid(_shell(faces)), tmp_path / "reversed_face.step")
    (solid,) = inrs.cad_model(path).solids
    with pytest.raises(ValueError) as e:
        solid.classify(np.array([[1.0, 1.0, 1.0]]))
    message = str(e.value)
    assert "\n" not in message
    assert message.startswith("solid 0: its faces are not consistently oriented"), message
    assert "outward normals" in message
    # The face reversed (the top, 2 x 3) leaves a net area vector of twice its area.
    assert "net area vector 1.200e1 of area 5.200000e1" in message, message


def _box_void_solid() -> "inrs.CadSolid":
    return inrs.cad_model(FIXTURES / "box_void.step").solids[0]


def _probe_points(n: int = 4000) -> np.ndarray:
    """Random points in and around the fixture's cube [-2, 2]^3 with its unit spherical void,
    and some on its faces."""
    rng = np.random.default_rng(11)
    pts = rng.uniform(-2.5, 2.5, (n, 3))
    pts[: n // 10, 0] = 2.0  # on the face x = 2, or in its plane outside
    return pts


def test_codes_shapes_and_wrong_shapes():
    s = _box_void_solid()
    pts = _probe_points()
    codes = s.classify(pts)
    assert codes.dtype == np.int8 and codes.shape == (len(pts),)
    # Far from the faces (1e-6, T being 1e-8 x 6.9), exactly the closed form.
    r = np.linalg.norm(pts, axis=1)
    cube = np.abs(pts).max(axis=1)
    far = (np.abs(cube - 2.0) > 1e-6) & (np.abs(r - 1.0) > 1e-6)
    truth = np.where((cube < 2.0) & (r > 1.0), IN, OUT)
    assert np.array_equal(codes[far], truth[far])
    on = (cube == 2.0)
    assert (codes[on] == ON).all()
    assert np.array_equal(s.contains_xyz(pts), codes == IN)
    # One point gives one code; a list works; no points give no codes.
    assert s.classify([0.0, 0.0, 1.5]) == IN and s.classify((0.0, 0.0, 0.5)) == OUT
    assert s.classify([[0.0, 0.0, 1.5], [3.0, 0.0, 0.0]]).tolist() == [IN, OUT]
    assert s.classify(np.zeros((0, 3))).shape == (0,)
    # Non-contiguous and integer arrays.
    assert np.array_equal(s.classify(np.asfortranarray(pts)), codes)
    assert np.array_equal(s.classify(pts[::2]), codes[::2])
    assert s.classify(np.array([[0, 0, 1]], dtype=np.int64)).tolist() == [ON]
    # A coordinate that is not finite: outside.
    assert s.classify(np.array([[np.nan, 0.0, 1.5], [0.0, np.inf, 0.0]])).tolist() == [OUT, OUT]
    for bad in (np.zeros((5, 2)), np.zeros((5, 4)), np.zeros((2, 2, 3)), np.zeros(2), np.zeros((0, 2))):
        with pytest.raises(ValueError, match=r"shape \(n, 3\)") as e:
            s.classify(bad)
        assert "\n" not in str(e.value)
        with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
            s.contains_xyz(bad)


def test_pickled_solids_classify_the_same():
    s = _box_void_solid()
    pts = _probe_points()
    codes = s.classify(pts)
    t = pickle.loads(pickle.dumps(s))
    assert t == s and t.index == 0
    assert np.array_equal(t.classify(pts), codes)
    # A solid of a model read with a closure tolerance comes back read with it.
    u = pickle.loads(pickle.dumps(inrs.cad_model(FIXTURES / "box_void.step", closure_tol=1e-6).solids[0]))
    assert u == s
    assert np.array_equal(u.classify(pts), codes)
    # A solid made by hand has no model.
    with pytest.raises(ValueError, match="no model"):
        inrs.CadSolid(*tuple(s)).classify(pts)


def test_threads_classify_alike():
    """Four threads classify at once against a fresh model (the first calls race to build the
    classifier): the same codes as one thread afterwards."""
    s = _box_void_solid()
    pts = np.concatenate([_probe_points(20000), np.random.default_rng(3).uniform(-1.01, 1.01, (20000, 3))])
    results: List[Optional[np.ndarray]] = [None] * 4
    errors = []
    barrier = threading.Barrier(4)

    def work(k):
        try:
            barrier.wait()
            results[k] = s.classify(pts)
        except Exception as e:  # pragma: no cover
            errors.append(e)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    alone = s.classify(pts)
    for r in results:
        assert r is not None and np.array_equal(r, alone)


def test_sod523_point_where_the_files_pcurves_and_occ_differ(scratch):
    """SOD_523.stp solid 0 at (-0.47144, -0.4000000009, 0.7099985): OCC's faces are 1.5e-6
    (15 T) away, but the file's own face 14 (a plane, trimmed by the file's pcurves) passes
    5.3e-8 from it with the foot 1.5e-6 inside the trim: OCC's face 14 ends at its 3-D edge
    (z = 0.71) instead. Ours answers ``boundary`` (within T of the face as the file writes it),
    never the other side (OCC: inside)."""
    path = real_file("SOD_523.stp", scratch)
    m = inrs.cad_model(path)
    p = np.array([[-0.4714438452882808, -0.4000000009052708, 0.7099984620717887]])
    assert m.solids[0].classify(p)[0] == ON
    face = m.faces[14]
    foot = face.points(np.array([[1.537022940367065e-6, 0.17855615471171915]]))[0]
    assert np.linalg.norm(foot - p[0]) < 1e-7
    assert face.domain.classify(np.array([[1.537022940367065e-6, 0.17855615471171915]]))[0] == IN

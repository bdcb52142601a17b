"""The OpenCASCADE oracle: faces of real STEP and IGES files classified by OCC and by inrs.

Part a (``inrs.occ``): for every face OCC reads, ``inrs.occ.face_domain`` (its pcurves,
converted exactly) classifies random ``(u, v)`` points as OCC's ``BRepClass_FaceClassifier``
does, away from the boundary. Part b (``inrs.cad_model``, the Rust readers and geometry): the
same face count as OCC, STEP faces in OCC's order (checked by their instance labels), every
face read, its surface on OCC's (random points within 1e-9 of the part's size), and its
domain classifying as OCC does, each through an exact map between the file's ``(u, v)`` and
OCC's, checked in space with our surface (``cad_files``); the same for the test parts of
``cad_parts`` (written by OCC to STEP, IGES faces and IGES B-rep), with their solids and shells
as OCC's explorers list them; IGES 108 planes, absent from the real files, on hand-written
files.

Also the conversion itself on shapes built with OCC (analytic areas, holes, orientation, the
errors). Without OCP or the files the tests skip with a message, and fail instead under
``INRS_REQUIRE_SYSTEM_FILES=1`` (``.ci/run`` installs both). ``pytest -s`` prints the
per-file counts.
"""

from __future__ import annotations

import math
import subprocess
import sys
import time

import numpy as np
import pytest

import inrs

import cad_files
import cad_parts
from cad_files import OccFile

try:
    cad_files.load_ocp()
    OCP_ERROR = None
except ImportError as e:
    OCP_ERROR = f"OCP is not installed (pip install cadquery-ocp-novtk): {e}"

FILES = cad_files.all_files()


unavailable = cad_files.unavailable


def need_ocp() -> None:
    if OCP_ERROR is not None:
        unavailable(OCP_ERROR)


@pytest.fixture(scope="module")
def occ_files(tmp_path_factory):
    """Reads each real file with OCC once: ``get(name) -> (path, OccFile)``."""
    cache = {}
    scratch = tmp_path_factory.mktemp("cad")

    def get(name: str):
        need_ocp()
        source = dict(FILES)[name]
        if not source.exists():
            unavailable(cad_files.missing_message(source))
        if name not in cache:
            path = cad_files.materialize(source, scratch)
            cache[name] = (path, OccFile.read(path))
        return cache[name]

    return get


# --- Part a: inrs.occ.face_domain against OCC's classifier, every face of every file ---------


@pytest.mark.parametrize("name", [n for n, _ in FILES])
def test_occ_face_domains_classify_as_occ(name, occ_files):
    _path, occ = occ_files(name)
    start = time.perf_counter()
    r = cad_files.check_occ_faces(occ)
    print(
        f"\n[occ] {name}: {r.faces} faces, {r.built} built, {len(r.open)} open (gaps over "
        f"{r.closure_tol:g}), {len(r.degenerate)} degenerate; {r.compared} points compared, "
        f"{r.excluded} excluded, {len(r.disagreements)} disagree ({time.perf_counter() - start:.1f} s)"
    )
    assert not r.problems, f"{name}: {r.problems[:5]}"
    assert not r.disagreements, f"{name}: (face, surface, (u, v), OCC, inrs): {r.disagreements[:5]}"
    # Every face is built or refused for a gap measured over the tolerance, and the faces
    # built are compared unless degenerate.
    assert r.built + len(r.open) == r.faces
    assert r.compared > 0 or r.built == len(r.degenerate)
    # Gaps are rare: at most half the faces miss the default 1e-9, and with the closure
    # tolerance of cad_files at most 2 per file (SMB/SMC_DO_214: a pcurve 2.5e-3 off). Loops
    # broken by a wrong edge direction would show here.
    assert len(r.open) <= r.faces // 2
    assert len(r.open) <= 2 or r.closure_tol < cad_files.CLOSURE_TOL


# --- Part b: the Rust readers (inrs.cad_model) against OCC ----------------------------------

#: Faces of the real files refused on purpose, with the reason: none. (Every face OCC reads
#: must read; a refusal would need a malformed file that OCC refuses too, listed in docs/CAD.md.)
KNOWN_REFUSALS: dict = {}


def check_model_against_occ(name: str, path, occ) -> "cad_files.ReadersReport":
    """``cad_files.check_readers`` with its printout and the assertions every file shares."""
    start = time.perf_counter()
    r = cad_files.check_readers(path, occ)
    print(
        f"\n[cad_model] {name}: {r.faces} faces (OCC {r.occ_faces}; {r.labels_checked} STEP labels "
        f"checked, {r.iges_same_de} IGES faces with OCC's DE), {r.read} read, "
        f"{sum(map(len, r.refused.values()))} refused {sorted(r.refused.items())[:4]}; surfaces of "
        f"{r.surfaces_checked} faces on OCC's within {r.surface_deviation:.2g} of the part's size "
        f"({r.surface_points} points); {r.fitted} faces with fitted pcurves (largest bound "
        f"{r.largest_fit_bound:.2g}); {r.compared} points compared, {r.excluded} excluded; {r.mapped} "
        f"faces mapped through space ({r.unmapped_points} points without image), scale maps checked "
        f"on {r.scale_checked} faces, {r.degenerate} degenerate, {len(r.disagreements)} disagree "
        f"({time.perf_counter() - start:.1f} s)"
    )
    # The same faces in the same order (STEP: OCC's face K is our face K's instance), each
    # listed consistently with its domain, its surface on OCC's.
    assert not r.problems, f"{name}: {r.problems[:5]}"
    # Every face read classifies as OCC does, each compared through an exact map from its
    # (u, v) in the file to OCC's, checked in space (our surface evaluated).
    assert not r.disagreements, f"{name}: (face, entity, surface, (u, v), OCC, inrs): {r.disagreements[:5]}"
    assert r.other_parameterisation == 0
    assert r.read == r.degenerate + r.mapped + r.scale_checked
    refused = sorted(k for ks in r.refused.values() for k in ks)
    assert refused == KNOWN_REFUSALS.get(name, []), f"{name}: refused {r.refused}"
    # Solids and shells as OCC's explorers give them, each with the same faces: a solid's
    # shells (the outer one first), then the shells in no solid.
    import inrs

    model = inrs.cad_model(path)
    topo = cad_parts.topology(path)
    in_solids = {s.index for solid in model.solids for s in solid.shells}
    ours = [[list(s.faces) for s in solid.shells] for solid in model.solids]
    theirs = [[list(shell.faces) for shell in solid.shells] for solid in topo.solids]
    assert ours == theirs, f"{name}: solids {ours}, OCC {theirs}"
    free = [list(s.faces) for s in model.shells if s.index not in in_solids]
    assert free == [list(s.faces) for s in topo.free_shells], f"{name}: free shells"
    return r


@pytest.mark.parametrize("name", [n for n, _ in FILES])
def test_cad_model_matches_occ(name, occ_files):
    path, occ = occ_files(name)
    check_model_against_occ(name, path, occ)


# --- The test parts of cad_parts.py, written by OCC to STEP and IGES, against OCC ------------

PART_FILES = [(part, kind) for part in cad_parts.PARTS for kind in ("step", "iges", "iges_brep")]


@pytest.fixture(scope="module")
def part_files(tmp_path_factory):
    """Writes every part once: ``get(part, kind) -> (path, OccFile)``."""
    cache = {}
    scratch = tmp_path_factory.mktemp("parts")

    def get(part: str, kind: str):
        need_ocp()
        if part not in cache:
            cache[part] = cad_parts.write_part(part, scratch).files()
        path = cache[part][kind]
        return path, OccFile.read(path)

    return get


@pytest.mark.parametrize("part,kind", PART_FILES, ids=[f"{p}.{k}" for p, k in PART_FILES])
def test_parts_match_occ(part, kind, part_files):
    path, occ = part_files(part, kind)
    r = check_model_against_occ(f"{part}.{kind}", path, occ)
    assert r.read == r.faces > 0


# --- The IGES 108 plane (none in the real files): hand-written files against OCC ------------


def iges_text(entities) -> str:
    """A fixed-form IGES 5.3 file (millimetres) of ``entities``: ``(type, parameters ending in
    ';', transformation matrix DE, status)`` each; entity ``k`` (from 0) is ``DE 2k+1``."""

    def line(text: str, section: str, seq: int) -> str:
        return f"{text:<72}{section}{seq:07d}\n"

    out = line("hand-written by python/tests/test_cad_occ.py", "S", 1)
    glob = (
        ",,4Htest,8Htest.igs,4Htest,4Htest,32,308,15,308,15,,1.,2,2HMM,1,0.01,"
        "15H20240101.000000,1.E-09,100.,4Htest,,11,0,15H20240101.000000;"
    )
    g = [glob[i : i + 72] for i in range(0, len(glob), 72)]
    out += "".join(line(t, "G", i + 1) for i, t in enumerate(g))
    d, p, seq = "", "", 1
    for i, (kind, params, transform, status) in enumerate(entities):
        de = 2 * i + 1
        lines = [""]  # parameter lines of at most 64 columns, split after delimiters
        for piece in params.replace(",", ",\0").split("\0"):
            if len(lines[-1]) + len(piece) > 64:
                lines.append("")
            lines[-1] += piece
        d += f"{kind:>8}{seq:>8}{0:>8}{0:>8}{0:>8}{0:>8}{transform:>8}{0:>8}{status:>8}D{de:07d}\n"
        d += f"{kind:>8}{0:>8}{0:>8}{len(lines):>8}{0:>8}{'':>8}{'':>8}{'':>8}{0:>8}D{de + 1:07d}\n"
        for text in lines:
            p += f"{text:<64} {de:>7}P{seq:07d}\n"
            seq += 1
    out += d + p
    return out + f"S{1:07d}G{len(g):07d}D{2 * len(entities):07d}P{seq - 1:07d}{'':40}T{1:07d}\n"


def plane_face_file(placed: bool, hole_clockwise: bool) -> str:
    """One 144 face on the plane x + 2y + 2z = 6 bounded by model-space curves (142s with no
    parameter-space curve): in the plane's frame (o; a, b), o = (2, 4, 4) / 3 its point nearest
    the origin, a = (2, -1, 0) / sqrt 5, b = n x a, the triangle with corners (-3, -2),
    (3, -2), (0, 3) less the unit disk around o. The disk's circle is a 100 placed by a 124
    frame (a, b, n) or, for a clockwise hole, (a, -b, -n). The plane is the 108
    ``x + 2y + 2z = 6``, or (``placed``) the 108 ``z = 0`` placed by the frame (a, b, n)."""
    n = np.array([1.0, 2.0, 2.0]) / 3
    o = 2 * n
    a = np.array([2.0, -1.0, 0.0]) / math.sqrt(5)
    b = np.cross(n, a)
    corners = [o + s * a + t * b for s, t in ((-3, -2), (3, -2), (0, 3))]

    def numbers(*arrays) -> str:
        return ",".join(repr(float(c)) for x in arrays for c in np.ravel(x))

    dep = "00010000"  # physically dependent: only the 144 is a root
    return iges_text(
        [
            (144, "144,3,1,1,5,15;", 0, "00000000"),  # DE 1
            (108, "108,0.,0.,1.,0.;" if placed else "108,1.,2.,2.,6.;", 19 if placed else 0, dep),  # DE 3
            (142, "142,0,3,0,7,2;", 0, dep),  # DE 5: the outer boundary
            (102, "102,3,9,11,13;", 0, dep),  # DE 7
            (110, f"110,{numbers(corners[0], corners[1])};", 0, dep),  # DE 9
            (110, f"110,{numbers(corners[1], corners[2])};", 0, dep),  # DE 11
            (110, f"110,{numbers(corners[2], corners[0])};", 0, dep),  # DE 13
            (142, "142,0,3,0,17,2;", 0, dep),  # DE 15: the hole
            (100, "100,0.,0.,0.,1.,0.,1.,0.;", 21 if hole_clockwise else 19, dep),  # DE 17
            (124, f"124,{numbers(np.column_stack([a, b, n, o]))};", 0, dep),  # DE 19
            (124, f"124,{numbers(np.column_stack([a, -b, -n, o]))};", 0, dep),  # DE 21
        ]
    )


@pytest.mark.parametrize("placed", [False, True], ids=["tilted 108", "108 placed by a 124"])
def test_an_iges_plane_in_the_readers_axes_classifies_as_occ(placed, tmp_path):
    need_ocp()
    if not hasattr(inrs, "cad_faces"):
        pytest.skip("this build of inrs has no cad_faces (the CAD readers)")
    path = tmp_path / "plane.igs"
    path.write_text(plane_face_file(placed, hole_clockwise=True))
    (face,) = inrs.cad_faces(path)
    assert face.surface == "108 (plane)" and face.error is None and face.loops == 2
    # (u, v) are lengths in the plane, so the domain is the triangle (area 15) less the disk.
    assert face.domain.area == pytest.approx(15 - math.pi, rel=1e-12)
    assert face.area == pytest.approx(15 - math.pi, rel=1e-12)
    # The reader's axes put (0, 0) at o, the centre of the hole; the ring around it is in.
    theta = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    ring = np.column_stack([1.25 * np.cos(theta), 1.25 * np.sin(theta)])
    assert face.domain.classify(np.array([[0.0, 0.0], [0.5, 0.1]])).tolist() == [0, 0]
    assert (face.domain.classify(ring) == 1).all()
    # Against OCC through the map (the reader's axes evaluated in space, projected on OCC's
    # plane): the triangle's orientation in (u, v) pins the axes, not only the area.
    r = cad_files.check_readers(path, OccFile.read(path))
    assert (r.faces, r.occ_faces, r.read, r.mapped) == (1, 1, 1, 1)
    assert not r.problems and not r.disagreements
    assert r.compared >= cad_files.POINTS_PER_FACE - 4


# --- inrs.occ on shapes built with OCC: analytic answers and errors --------------------------


def faces_of(shape) -> list:
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
    out, explorer = [], TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        out.append(as_face(explorer.Current()))
        explorer.Next()
    return out


def test_primitives_have_their_analytic_uv_areas():
    need_ocp()
    import inrs.occ
    from OCP.BRepPrimAPI import (
        BRepPrimAPI_MakeBox,
        BRepPrimAPI_MakeCone,
        BRepPrimAPI_MakeCylinder,
        BRepPrimAPI_MakeSphere,
        BRepPrimAPI_MakeTorus,
    )

    pi = math.pi
    cases = [
        # Planar faces of a 2 x 3 x 4 box: (u, v) are lengths.
        (BRepPrimAPI_MakeBox(2.0, 3.0, 4.0).Shape(), [12, 12, 8, 8, 6, 6]),
        # Cylinder r = 1, h = 5: the side is [0, 2 pi] x [0, 5]; the caps are unit disks.
        (BRepPrimAPI_MakeCylinder(1.0, 5.0).Shape(), [10 * pi, pi, pi]),
        # Sphere: [0, 2 pi] x [-pi/2, pi/2], with degenerated edges at the poles.
        (BRepPrimAPI_MakeSphere(1.0).Shape(), [2 * pi * pi]),
        # Cone r = 1 to apex, h = 2: v runs along the generatrix, of length sqrt(5).
        (BRepPrimAPI_MakeCone(1.0, 0.0, 2.0).Shape(), [2 * pi * math.sqrt(5), pi]),
        (BRepPrimAPI_MakeTorus(3.0, 1.0).Shape(), [4 * pi * pi]),
    ]
    for shape, areas in cases:
        faces = faces_of(shape)
        assert len(faces) == len(areas)
        for face, area in zip(faces, areas):
            d = inrs.occ.face_domain(face)
            assert d.area == pytest.approx(area, rel=1e-12)
            # Outer loops counter-clockwise: positive signed area, every loop closed.
            assert all(loop.closed for loop in d.loops)
            assert d.summary().signed_area == pytest.approx(area, rel=1e-12)


def test_circles_are_exact_rational_quadratics_and_lines_degree_one():
    need_ocp()
    import inrs.occ
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder

    side, top, _bottom = faces_of(BRepPrimAPI_MakeCylinder(2.0, 1.0).Shape())
    for degree, knots, points, weights in inrs.occ.face_loops(side)[0]:
        assert degree == 1 and weights is None and len(points) == 2 and len(knots) == 4
    (loop,) = inrs.occ.face_loops(top)
    (circle,) = loop
    degree, knots, points, weights = circle
    assert degree == 2 and weights is not None and len(knots) == len(points) + 3
    # A rational quadratic of a circle: end points and the even-index control points on the
    # circle, the middle weights cos(half the arc) below 1.
    assert np.allclose(np.hypot(points[::2, 0], points[::2, 1]), 2.0, rtol=0, atol=1e-12)
    assert (weights[1::2] < 1).all() and np.allclose(weights[::2], 1.0)
    d = inrs.occ.face_domain(top)
    theta = np.linspace(0, 2 * np.pi, 50, endpoint=False)
    inside = np.column_stack([1.999 * np.cos(theta), 1.999 * np.sin(theta)])
    outside = np.column_stack([2.001 * np.cos(theta), 2.001 * np.sin(theta)])
    assert (d.classify(inside) == inrs.INSIDE).all() and (d.classify(outside) == inrs.OUTSIDE).all()


def test_a_hole_is_a_clockwise_loop_after_the_outer_one():
    need_ocp()
    import inrs.occ
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    plate = BRepPrimAPI_MakeBox(10.0, 6.0, 1.0).Shape()
    drill = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(4.0, 3.0, -1.0), gp_Dir(0, 0, 1)), 1.5, 3.0).Shape()
    cut = BRepAlgoAPI_Cut(plate, drill).Shape()
    holed = [f for f in faces_of(cut) if len(inrs.occ.face_loops(f)) == 2]
    assert len(holed) == 2  # top and bottom
    for face in holed:
        d = inrs.occ.face_domain(face)
        outer, hole = d.loops
        assert outer.signed_area == pytest.approx(60.0, rel=1e-12)
        assert hole.signed_area == pytest.approx(-math.pi * 1.5**2, rel=1e-12)
        assert d.area == pytest.approx(60.0 - math.pi * 1.5**2, rel=1e-12)
        # OCC and inrs agree at the hole's centre and in the solid part, in the face's (u, v).
        from OCP.BRepClass import BRepClass_FaceClassifier
        from OCP.BRepTools import BRepTools
        from OCP.gp import gp_Pnt2d
        from OCP.TopAbs import TopAbs_IN, TopAbs_OUT

        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        pts = np.array([[u0 + 0.5, v0 + 0.5], [u1 - 0.5, v1 - 0.5], [u0 - 1, v0]])
        # The hole's centre in (u, v): the middle of the inner loop's box.
        hole_pts = np.concatenate([c[2] for c in inrs.occ.face_loops(face)[1]])
        centre = (hole_pts.min(axis=0) + hole_pts.max(axis=0)) / 2
        pts = np.vstack([pts, centre])
        occ = [BRepClass_FaceClassifier(face, gp_Pnt2d(*map(float, p)), 1e-7).State() for p in pts]
        assert occ == [TopAbs_IN, TopAbs_IN, TopAbs_OUT, TopAbs_OUT]
        assert d.classify(pts).tolist() == [1, 1, 0, 0]


def test_a_reversed_face_covers_the_same_region():
    need_ocp()
    import inrs.occ
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder

    rng = np.random.default_rng(7)
    for face in faces_of(BRepPrimAPI_MakeCylinder(1.0, 5.0).Shape()):
        forward, backward = inrs.occ.face_domain(face), inrs.occ.face_domain(face.Reversed())
        assert forward.to_json() == backward.to_json()
        pts = rng.uniform(-7, 7, (200, 2))
        assert (forward.classify(pts) == backward.classify(pts)).all()


def test_reversed_edges_run_their_pcurves_backwards_exactly():
    need_ocp()
    import inrs.occ
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder

    side = faces_of(BRepPrimAPI_MakeCylinder(1.0, 5.0).Shape())[0]
    (loop,) = inrs.occ.face_loops(side)
    # Watertight to the last bit: each curve starts where the previous one ends.
    for c, d in zip(loop, loop[1:] + loop[:1]):
        assert np.array_equal(c[2][-1], d[2][0])
    # The seam appears twice, at u = 0 and u = 2 pi, run in opposite directions.
    seams = [c for c in loop if c[2][0, 0] == c[2][-1, 0]]
    assert sorted(float(s[2][0, 0]) for s in seams) == pytest.approx([0.0, 2 * math.pi])
    assert {float(s[2][-1, 1] - s[2][0, 1]) for s in seams} == {5.0, -5.0}
    for _degree, knots, _points, _weights in loop:
        assert (np.diff(knots) >= 0).all()


def test_an_offset_pcurve_is_refused_not_approximated():
    need_ocp()
    import inrs.occ
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
    from OCP.BRepLib import BRepLib
    from OCP.Geom import Geom_Plane
    from OCP.Geom2d import Geom2d_Circle, Geom2d_OffsetCurve
    from OCP.gp import gp_Ax2d, gp_Dir2d, gp_Pln, gp_Pnt2d

    plane = Geom_Plane(gp_Pln())
    offset = Geom2d_OffsetCurve(Geom2d_Circle(gp_Ax2d(gp_Pnt2d(0, 0), gp_Dir2d(1, 0)), 1.0), 0.5)
    edge = BRepBuilderAPI_MakeEdge(offset, plane).Edge()
    BRepLib.BuildCurves3d_s(edge)
    face = BRepBuilderAPI_MakeFace(plane, BRepBuilderAPI_MakeWire(edge).Wire()).Face()
    with pytest.raises(ValueError, match=r"wire 0, edge 0: an offset pcurve has no exact B-spline form"):
        inrs.occ.face_domain(face)


def test_an_edge_without_pcurve_is_named():
    need_ocp()
    import inrs.occ
    from OCP.BRep import BRep_Builder
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax2, gp_Ax3, gp_Circ, gp_Dir, gp_Pnt
    from OCP.TopoDS import TopoDS_Face

    # A face on a cylinder bounded by a 3-D circle that has no curve in the cylinder's (u, v)
    # (OCC computes missing pcurves on planes only).
    surface = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 1.0)
    edge = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 1.0)).Edge()
    face = TopoDS_Face()
    builder = BRep_Builder()
    builder.MakeFace(face, surface, 1e-7)
    builder.Add(face, BRepBuilderAPI_MakeWire(edge).Wire())
    with pytest.raises(ValueError, match=r"^wire 0, edge 0: no pcurve on the face"):
        inrs.occ.face_domain(face)


def test_closure_tol_is_handed_on_or_warned_about(monkeypatch):
    need_ocp()
    import inrs.occ
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox

    face = faces_of(BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape())[0]
    seen = {}

    def with_tol(curves, name=None, closure_tol=None):
        seen.update(name=name, closure_tol=closure_tol, curves=len(curves))
        return "domain"

    monkeypatch.setattr(inrs.Domain, "from_curves", staticmethod(with_tol))
    assert inrs.occ.face_domain(face, 1e-6, name="f0") == "domain"
    assert seen == {"name": "f0", "closure_tol": 1e-6, "curves": 4}

    def without_tol(curves, name=None):
        seen.update(name=name, curves=len(curves), closure_tol="absent")
        return "old"

    monkeypatch.setattr(inrs.Domain, "from_curves", staticmethod(without_tol))
    with pytest.warns(UserWarning, match="no closure_tol"):
        assert inrs.occ.face_domain(face, 1e-6) == "old"
    assert seen["closure_tol"] == "absent"


def test_docstring_examples_run():
    need_ocp()
    import doctest

    import inrs.occ

    failed, tried = doctest.testmod(inrs.occ, report=True)
    assert tried > 0 and failed == 0


def test_import_inrs_does_not_import_ocp_and_inrs_occ_names_the_package(tmp_path):
    # A fresh interpreter each: OCP must not be loaded by `import inrs`, and without OCP the
    # error of `import inrs.occ` says what to install.
    code = "import sys, inrs; assert 'OCP' not in sys.modules, 'OCP imported'; print('ok')"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr
    code = (
        "import sys; sys.modules['OCP'] = None\n"
        "try:\n    import inrs.occ\nexcept ImportError as e:\n    print(e)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert "pip install cadquery-ocp-novtk" in out.stdout, (out.stdout, out.stderr)


def test_an_iges_hole_run_like_its_outer_loop_is_a_hole(tmp_path):
    need_ocp()
    if not hasattr(inrs, "cad_faces"):
        pytest.skip("this build of inrs has no cad_faces (the CAD readers)")
    path = tmp_path / "plane.igs"
    path.write_text(plane_face_file(False, hole_clockwise=False))
    (face,) = inrs.cad_faces(path)
    # IGES does not orient a 144's inner boundaries: the hole is one by its nesting.
    assert face.domain.area == pytest.approx(15 - math.pi, rel=1e-12)
    assert face.domain.classify(np.array([[0.0, 0.0], [1.25, 0.0]])).tolist() == [0, 1]
    r = cad_files.check_readers(path, OccFile.read(path))
    assert (r.read, r.mapped) == (1, 1) and not r.disagreements
    assert r.compared >= cad_files.POINTS_PER_FACE - 4
    # The loops are oriented by nesting: the hole runs clockwise, so the face's signed area
    # is its area.
    assert face.area == pytest.approx(15 - math.pi, rel=1e-12)
    assert face.domain.summary().signed_area == pytest.approx(15 - math.pi, rel=1e-12)
    assert not r.problems

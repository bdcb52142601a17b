"""Mass properties of CAD faces and solids (``CadModel.properties``) against closed forms and
against OpenCASCADE's ``BRepGProp``.

(a) Parts OCC makes (sphere, tilted torus, tilted cylinder, cone frustum, box with a
cylindrical hole, a revolved polygon, box with a spherical void), written to STEP: volume, area,
centroid and inertia within 1e-12 of their closed forms. (b) Every face and solid of the test
parts of ``cad_parts`` (STEP, IGES faces mode, IGES B-rep mode) and of the real files of
``test_cad_occ`` (freecad-common's IDF library, gmsh-doc's demos): area, volume, centroid and
inertia within 1e-7 of ``BRepGProp`` at ``eps = 1e-9`` (relative to the quantity; centroids to
the part's size; tensors to their largest component; quantities below 1e-9 of the part's size
to their power against that), except where measured and explained, face by face: a solid
whose faces leave gaps (within what its leak area leaves open, ``LEAKY``), ``BRepGProp`` off
a closed form (``OCC_WRONG``), a file that contradicts itself beyond 1e-7
(``FILE_INCONSISTENT``); a difference anywhere else, or agreement where one is listed, fails.
(c) Where a closed form exists, ours is no farther from it than ``BRepGProp``'s at
``eps = 1e-9`` (or within 1e-15 of it).

Also the Python API: the native call made once, errors as ``ValueError``, threads, pickling.
Without OCP or the files the OCC tests skip with a message, and fail instead under
``INRS_REQUIRE_SYSTEM_FILES=1``. ``pytest -s`` prints the worst differences seen.
"""

from __future__ import annotations

import math
import pathlib
import pickle
import re
import threading
import time

import numpy as np
import pytest

import inrs

import cad_files

try:
    cad_files.load_ocp()
    OCP_ERROR = None
except ImportError as e:
    OCP_ERROR = f"OCP is not installed (pip install cadquery-ocp-novtk): {e}"

FIXTURES = pathlib.Path(__file__).resolve().parents[2] / "fixtures" / "cad"

#: ``BRepGProp``'s relative accuracy in (b) and (c).
OCC_EPS = 1e-9
#: Agreement with ``BRepGProp`` (b).
OCC_REL = 1e-7
#: Agreement with the closed forms (a).
CLOSED_REL = 1e-12
#: Below this relative difference (c) calls ours and OCC's equal.
EQUAL_REL = 1e-15

#: The worst relative differences from OCC seen, per quantity: ``(value, where)``.
WORST: dict = {}


unavailable = cad_files.unavailable


def need_ocp() -> None:
    if OCP_ERROR is not None:
        unavailable(OCP_ERROR)


@pytest.fixture(scope="module", autouse=True)
def report_worst():
    yield
    if WORST:
        print("\nWorst relative differences from BRepGProp (eps %g):" % OCC_EPS)
        for what, (value, where) in sorted(WORST.items()):
            print(f"  {what:>22}: {value:.2e}  ({where})")


# --- the API (no OCP) ------------------------------------------------------------------------


def box_void() -> inrs.CadModel:
    return inrs.cad_model(FIXTURES / "box_void.step")


def test_properties_of_a_solid_with_a_void():
    m = box_void()
    p = m.properties()
    assert isinstance(p, inrs.CadProperties)
    assert len(p.faces) == len(m.faces) and len(p.solids) == len(m.solids) == 1
    assert p.face_errors == [None] * len(m.faces) and p.solid_errors == [None]
    s = m.solids[0]
    volume = 64 - 4 / 3 * math.pi
    assert s.volume == pytest.approx(volume, rel=1e-13)
    assert s.area == pytest.approx(96 + 4 * math.pi, rel=1e-13)
    assert s.centroid.shape == (3,) and np.abs(s.centroid).max() < 1e-13
    inertia = 64 * 32 / 12 - 2 / 5 * (4 / 3 * math.pi)
    assert s.inertia.shape == (3, 3)
    np.testing.assert_allclose(s.inertia, inertia * np.eye(3), rtol=0, atol=1e-12 * inertia)
    np.testing.assert_allclose(s.principal_moments, [inertia] * 3, rtol=1e-12)
    axes = s.principal_axes
    np.testing.assert_allclose(axes @ axes.T, np.eye(3), atol=1e-12)
    # Watertight: the net area vector is rounding.
    assert 0.0 <= s.leak_area < 1e-12 * s.area and s.properties.leak_area == s.leak_area
    # The attributes read the cached properties: one native call, the same objects.
    assert m.properties() is p and s.properties is p.solids[0]
    assert m.faces[3].properties is p.faces[3] and m.faces[3].centroid is p.faces[3].centroid
    assert sum(f.surface_area for f in m.faces) == pytest.approx(s.area, rel=1e-14)
    # The arrays are shared, so read-only.
    with pytest.raises(ValueError):
        s.centroid[0] = 1.0
    # A face's second moments: the sphere's (the void, face 6), r^2 A / 3 I about its centre.
    sphere = m.faces[6]
    assert sphere.surface_area == pytest.approx(4 * math.pi, rel=1e-13)
    np.testing.assert_allclose(sphere.second_moments, 4 * math.pi / 3 * np.eye(3), atol=1e-12)


def test_properties_pickle_and_solids_without_their_model():
    m = box_void()
    p = m.properties()
    q = pickle.loads(pickle.dumps(p))
    assert q.solids[0].volume == p.solids[0].volume
    np.testing.assert_array_equal(q.solids[0].inertia, p.solids[0].inertia)
    # A solid pickles as its file and index: it comes back with its model.
    s = pickle.loads(pickle.dumps(m.solids[0]))
    assert s == m.solids[0] and tuple(s) == tuple(m.solids[0]) and len(s) == 3
    assert s.volume == m.solids[0].volume
    # Read with a closure tolerance, it comes back read with it.
    t = pickle.loads(pickle.dumps(inrs.cad_model(FIXTURES / "box_void.step", closure_tol=1e-9).solids[0]))
    assert tuple(t) == tuple(m.solids[0]) and t.volume == m.solids[0].volume
    # A solid made by hand has no model.
    with pytest.raises(ValueError, match="no model"):
        inrs.CadSolid(*tuple(m.solids[0])).volume


def test_faces_without_a_model_have_no_properties():
    face = inrs.cad_faces(FIXTURES / "box_void.step")[0]
    with pytest.raises(ValueError, match="cad_model"):
        face.centroid


def test_threads_share_one_computation():
    m = box_void()
    results, barrier = [], threading.Barrier(8)

    def work():
        barrier.wait()
        results.append(m.properties())

    threads = [threading.Thread(target=work) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(results) == 8 and all(r is results[0] for r in results)


# --- OCC's properties --------------------------------------------------------------------------


def occ_props(shape, volume: bool, eps: float = OCC_EPS):
    """``BRepGProp``'s volume (``volume``) or surface properties of ``shape`` at ``eps``:
    ``(mass, centroid, inertia about the centroid)``."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    if volume:
        BRepGProp.VolumeProperties_s(shape, props, eps)
    else:
        BRepGProp.SurfaceProperties_s(shape, props, eps)
    c = props.CentreOfMass()
    m = props.MatrixOfInertia()
    inertia = np.array([[m.Value(i, j) for j in (1, 2, 3)] for i in (1, 2, 3)])
    return props.Mass(), np.array([c.X(), c.Y(), c.Z()]), inertia


def face_inertia(second_moments: np.ndarray) -> np.ndarray:
    """A face's inertia tensor (OCC's ``MatrixOfInertia`` of an area) from its second moments
    about its centroid: ``tr(S) I - S``."""
    return np.trace(second_moments) * np.eye(3) - second_moments


def note(what: str, value: float, where: str) -> None:
    if value > WORST.get(what, (-1.0, ""))[0]:
        WORST[what] = (value, where)


def compare(what: str, where: str, ours, theirs, size: float, power: int, problems: list, allow=(0.0, 0.0, 0.0)) -> None:
    """Records and checks ``ours`` against OCC's ``(mass, centroid, inertia)``: the mass
    relative to itself, the centroid to ``size``, the inertia to its largest component
    (``power``: the mass's dimension, for the zero-mass case). ``allow``: absolute
    differences of the mass, the centroid and the inertia that the file itself leaves open
    (see :func:`leak_allowance`); a difference within it is not a problem."""
    mass, centroid, inertia = ours
    m, c, i = theirs
    # A degenerate face (a sliver of zero area: OCC's 0, ours rounding) is compared against
    # ``DEGENERATE`` of the part's size to the power instead of its own near-zero size.
    degenerate = abs(m) < size**power * DEGENERATE
    d_mass = abs(mass - m) / max(abs(m), size**power * DEGENERATE)
    d_centroid = np.abs(centroid - c).max() / size
    floor = size ** (power + 2) * DEGENERATE if degenerate else 1e-300
    d_inertia = np.abs(inertia - i).max() / max(np.abs(i).max(), floor)
    absolute = (abs(mass - m), np.abs(centroid - c).max(), np.abs(inertia - i).max())
    checks = list(zip((what, f"{what} centroid", f"{what} inertia"), (d_mass, d_centroid, d_inertia), absolute, allow))
    # A degenerate face has no centroid (its moments over a zero area): its mass alone.
    for q, d, a, limit in checks[:1] if degenerate else checks:
        note(q, d, where)
        if not (d <= OCC_REL or a <= limit):
            problems.append(f"{where}: {q} differs by {d:.2e} (ours {mass!r}, OCC {m!r})")


#: Masses (and inertias) below this fraction of the part's size to their power are compared
#: against it: zero-area slivers (OCC's area 0, ours rounding) are not divided by zero.
DEGENERATE = 1e-9

#: A solid whose leak leaves more than this fraction of its volume open (its leak area times
#: the square root of its boundary's area over 3, as ``inrs properties`` warns) leaves gaps
#: between its faces (a watertight one's leak is rounding, ~1e-16 of its area).
LEAK = 1e-9


def leak_allowance(solid, size: float):
    """What a leaky boundary leaves open: the divergence theorem's volume changes by
    ``(p1 - p0) . N / 3`` between reference points ``p0`` and ``p1`` (``N`` the net area
    vector, ``|N|`` the leak area), its first moments by up to ``|N| R^2`` and its second by
    ``|N| R^3``, ``R`` the farthest the reference points are apart: ours is the centre of the
    model's box, OCC's the origin, so ``R <= |centroid| + size``. The allowances of the
    volume, the centroid (first moments over the volume) and the inertia."""
    r = float(np.linalg.norm(solid.centroid)) + size
    leak = solid.leak_area
    return leak * r, 2.0 * leak * r**2 / abs(solid.volume), 2.0 * leak * r**3


def check_against_occ(path: pathlib.Path, name: str) -> None:
    """Every face (area, centroid, inertia of the area) and solid (volume, centroid, inertia,
    and boundary area) of ``path`` against ``BRepGProp``, faces in OCC's explorer order."""
    from OCP.TopAbs import TopAbs_SOLID

    import cad_parts

    occ = cad_files.OccFile.read(path)
    shape = cad_parts.read_shape(path)
    model = inrs.cad_model(path, **cad_files.closure_kwargs())
    props = model.properties()
    assert len(props.faces) == len(occ.faces), f"{name}: {len(props.faces)} faces, OCC {len(occ.faces)}"
    mm = occ.mm_per_unit  # OCC's lengths are millimetres, ours the file's unit
    size = occ.size / mm
    problems = [f"{name}: face {k}: {e}" for k, e in enumerate(props.face_errors) if e is not None]
    for k, (ours, face) in enumerate(zip(props.faces, occ.faces)):
        if ours is None:
            continue
        m, c, i = occ_props(face, volume=False)
        theirs = (m / mm**2, c / mm, i / mm**4)
        mine = (ours.area, ours.centroid, face_inertia(ours.second_moments))
        compare("face area", f"{name} face {k}", mine, theirs, size, 2, problems)
    solids = cad_parts._explore(shape, TopAbs_SOLID)
    assert len(props.solids) == len(solids), f"{name}: {len(props.solids)} solids, OCC {len(solids)}"
    for k, (ours, solid) in enumerate(zip(props.solids, solids)):
        if ours is None:
            problems.append(f"{name}: solid {k}: {props.solid_errors[k]}")
            continue
        m, c, i = occ_props(solid, volume=True)
        theirs = (m / mm**3, c / mm, i / mm**5)
        leaky = ours.leak_area * math.sqrt(ours.area) / 3.0 > LEAK * abs(ours.volume)
        assert leaky == (name in LEAKY), f"{name} solid {k}: leak area {ours.leak_area:.2e} of boundary area {ours.area:.4g}"
        allow = leak_allowance(ours, size) if leaky else (0.0, 0.0, 0.0)
        compare("volume", f"{name} solid {k}", (ours.volume, ours.centroid, ours.inertia), theirs, size, 3, problems, allow)
        a = occ_props(solid, volume=False)[0] / mm**2
        d = abs(ours.area - a) / a
        note("solid area", d, f"{name} solid {k}")
        if not d <= OCC_REL:
            problems.append(f"{name}: solid {k}: boundary area differs by {d:.2e}")
    where = sorted({re.search(r"(face|solid) \d+", p).group(0) for p in problems})
    if name in OCC_WRONG or name in FILE_INCONSISTENT:
        reason, expected = OCC_WRONG.get(name) or FILE_INCONSISTENT[name]
        # Exactly the faces and solids measured: one more, or one fewer, fails; and no
        # difference grows past three times the largest measured.
        assert where == sorted(expected), f"{name}: differs from OCC at {where}, measured at {sorted(expected)}: " + "; ".join(problems)
        largest = max(float(d) for d in re.findall(r"differs by ([0-9.e+-]+)", " ".join(problems)))
        print(f"\n{name}: largest difference {largest:.2e}")
        assert largest <= 3.0 * LARGEST[name], f"{name}: a difference of {largest:.2e}, measured at most {LARGEST[name]:.2e}"
        pytest.xfail(f"{name}: {reason}: " + "; ".join(problems))
    assert not problems, "\n".join(problems)


#: Real files whose solids' faces leave gaps (leaving more than ``LEAK`` of the volume open),
#: measured: their volumes and moments are defined only up to ``leak_allowance``, and
#: ours and OCC's differ within it (each takes another reference point). SMB_DO_214AA and
#: SMC_DO_214AB: five plane faces bounded by straight pcurves where their neighbours follow
#: 3-D edges that bow off the planes by up to 5e-3 mm (25 times the file's uncertainty), leak
#: 5.2e-4 mm^2 (volumes 1.9e-6 and 7.2e-7 apart). CAP_50SGV_8_10: leak 2.0e-4 mm^2.
#: component8.step and t20_data.step (one part): no pcurves, edges up to 1e-3 mm off their
#: surfaces, leak 5.1e-2 mm^2.
LEAKY = {
    "RLF_7030.stp",  # leak 7.7e-8 mm^2, 2.8e-9 of its volume open
    "SMB_DO_214AA.stp",
    "SMC_DO_214AB.stp",
    "CAP_50SGV_8_10.stp",
    "component8.step",
    "t20_data.step",
}

_IGES_REVOLUTION = (
    "BRepGProp at eps 1e-9 integrates the faces that IGES faces mode writes as surfaces of "
    "revolution (sphere, torus, cylinder and cone pieces) coarsely: the sphere's centroid off "
    "by 9.4e-7 and its inertia by 7.1e-4 of the closed form (ours 4.5e-11, 4.3e-11, the file's "
    "rounding); at eps 1e-12 OCC's inertia comes within 1.9e-6 of ours"
)
_TORUS = "BRepGProp's inertia of the torus is 1.1e-7 off its closed form (ours 1.4e-13)"
_REVOLVED = (
    "BRepGProp at eps 1e-9 is off on the surface of revolution: volume 2.2e-7 from the closed "
    "form (cad_parts), centroid 3.6e-4 off the axis, I_xx != I_yy by 1%; at eps 1e-12 3.3e-11, "
    "9.4e-7; ours 2.8e-14, 5.5e-14, I_xx = I_yy"
)
_BSPLINE_HOLE = (
    "BRepGProp at eps 1e-9 is off on the rational B-spline hole: area 2.1e-7 from 4 pi (1.1e-9 "
    "at eps 1e-12), the solid's inertia 3.0e-7 from the closed form; ours 1.4e-13, 2.3e-14"
)
#: Files where BRepGProp at eps 1e-9 is wrong, not us (closed forms, and OCC converging to our
#: values at eps 1e-12; measured, see the reasons), with the faces and solids where it is: a
#: difference anywhere else fails, and so does agreement there.
OCC_WRONG = {
    "sphere.igs": (_IGES_REVOLUTION, {"face 0"}),
    "torus.igs": (_IGES_REVOLUTION, {"face 0"}),
    "cone_minus_sphere.igs": (_IGES_REVOLUTION, {"face 0", "face 1"}),
    "fused_cylinders.igs": (_IGES_REVOLUTION, {"face 0", "face 1", "face 4"}),
    "filleted_plate.igs": (_IGES_REVOLUTION, {"face 10"}),
    "box_void.igs": (_IGES_REVOLUTION, {"face 6"}),
    "torus.step": (_TORUS, {"solid 0"}),
    "torus_brep.igs": (_TORUS, {"solid 0"}),
    "revolved_bspline.step": (_REVOLVED, {"face 1", "solid 0"}),
    "revolved_bspline.igs": (_REVOLVED, {"face 1"}),
    "revolved_bspline_brep.igs": (_REVOLVED, {"face 1", "solid 0"}),
    "bspline_box_hole.step": (_BSPLINE_HOLE, {"face 6", "solid 0"}),
    "bspline_box_hole.igs": (_BSPLINE_HOLE, {"face 6"}),
    "bspline_box_hole_brep.igs": (_BSPLINE_HOLE, {"face 6", "solid 0"}),
    "SOT23.stp": (
        "faces 23, 26, 31 are spherical triangles (a surface of revolution of a circle about an "
        "axis through its centre) with the closed-form area r^2 x spherical excess = "
        "2.290968477e-4: ours 9.2e-10 from it (the file's pcurves leave the great circles by "
        "7.4e-10 mm), BRepGProp 2.5e-7 at eps 1e-9 and 1e-12 alike (ShapeFix's degenerate edge "
        "at the pole spans u in [2.49e-5, pi/2] and bends the meridian's pcurve, cutting a wedge)",
        {"face 23", "face 26", "face 31"},
    ),
    "CAP_50SGV_8_10.stp": (
        "face 23, a quarter of a torus's tube over a full turn: ours within 3e-14 (area) and "
        "1.3e-13 (second moments) of the closed form, BRepGProp's second moments 1.5e-7 off at "
        "eps 1e-9 (2.2e-11 at 1e-12), as on torus.step",
        {"face 23"},
    ),
    "SOT404.stp": (
        "solid 1, a disc (cylinder of radius 0.5, height 0.01, two planar caps): ours within "
        "1.9e-13 (volume) and 2.3e-11 (inertia) of the closed form, BRepGProp's inertia 1.2e-7 "
        "off at eps 1e-9 (1.8e-11 at 1e-12)",
        {"solid 1"},
    ),
    "SOT404.igs": (
        "face 55, an IGES surface of revolution that is a cylinder band (radius 0.5, height "
        "0.01): ours 3.3e-11 from the closed form's second moments, BRepGProp 7.1e-4 at eps "
        "1e-9 (I_xx - I_yy = 1.4e-3, centroid 3e-7 off the axis; 1.9e-6 at 1e-12); the areas "
        "agree to 3e-11 (" + _IGES_REVOLUTION + ")",
        {"face 55"},
    ),
}

#: Real files where ours and BRepGProp read different faces out of a file that contradicts
#: itself beyond 1e-7 (measured, per face; both answers lie within what the file defines), with
#: where they differ.
_SOD_323 = (
    "planar faces written as degree-(1, 1) B-spline surfaces whose vertices lie up to 3.8e-7 mm "
    "off their own lines (1.4 to 1.9 times the faces' stated uncertainties, 1e-7 and 2e-7). "
    "Ours is the area of the file's loops as written, checked by an independent strip rule on "
    "faces 20, 29 and 62 (within 4e-11); where a loop's gap is closed (faces 4, 9, 11) moving a "
    "line's end shears it, changing the area by half its length times the gap (face 9: 7.7e-7 "
    "of its area, faces 4 and 11: 3.1e-7; face 8, a 0.002-wide sliver: 1.8e-4), the band the "
    "file leaves. OCC re-makes the faces (ShapeFix merges vertices and re-projects pcurves; "
    "its STEP reader shifts line #1060 through its vertices, OCCT #25415, its IGES reader does "
    "not, and its two readings of face 8 differ by 1.8e-4): on faces 29 to 74 (traced on 29 "
    "and 62) it is 2.2e-7 to "
    "6.9e-7 from the file's loops. Faces 20, 21 and 27 (and 14 and 17 in IGES) are slivers "
    "narrower than the closure tolerance, areas 6.8e-8 to 2.6e-6 mm^2 (ours and OCC's at most "
    "2.5e-8 mm^2 apart, up to 0.38 of the sliver's area; IGES face 14: OCC's re-made pcurves "
    "leave 1.7e-11 gaps, ours is the file's loop to 4e-11); faces 15 and 26 have no area "
    "(both agree)"
)
_SOD_323_FACES = [4, 8, 9, 11, 20, 21, 27, 29, 31, 34, 41, 44, 45, 48, 49, 52, 53, 54, 55, 58, 62, 71, 74]
_COMPONENT8 = (
    "no pcurves, and 3-D edges up to 1.03e-3 mm off their surfaces (face 1; the stated "
    "uncertainty is 0.074 mm): a face's area is defined only to about its perimeter times its "
    "edges' distance from its surface. Our pcurves are fitted to 1e-7 of the part's size (the "
    "areas agree with the converged projection of the edges to about 1e-8), OCC's are its own "
    "projections: faces 0, 2 to 4, 9 to 13 and 20 differ by 2.3e-7 to 7.5e-7, face 1 (a "
    "rational B-spline face whose two curved edges are 1.03e-3 mm off it) by 1.0e-4, where "
    "the projected 3-D edges bound an area 4.1e-6 from ours; the solid leaks 5.1e-2 mm^2"
)
_COMPONENT8_WHERE = {f"face {k}" for k in [0, 1, 2, 3, 4, 9, 10, 11, 12, 13, 20]} | {"solid 0"}
FILE_INCONSISTENT = {
    "SOD_323.stp": (_SOD_323, {f"face {k}" for k in _SOD_323_FACES}),
    "SOD_323.igs": (_SOD_323, {f"face {k}" for k in [14, 17] + [k for k in _SOD_323_FACES if k not in (4, 11)]}),
    "component8.step": (_COMPONENT8, _COMPONENT8_WHERE),
    "t20_data.step": (_COMPONENT8, _COMPONENT8_WHERE),
}


#: The largest relative difference measured (2026-12-05) on each file of ``OCC_WRONG`` and
#: ``FILE_INCONSISTENT``; one more than three times it fails.
LARGEST = {
    "CAP_50SGV_8_10.stp": 1.50e-07,
    "SOD_323.igs": 3.77e-01,
    "SOD_323.stp": 3.77e-01,
    "SOT23.stp": 6.89e-07,
    "SOT404.igs": 7.11e-04,
    "SOT404.stp": 1.19e-07,
    "box_void.igs": 7.11e-04,
    "bspline_box_hole.igs": 2.13e-07,
    "bspline_box_hole.step": 2.96e-07,
    "bspline_box_hole_brep.igs": 2.96e-07,
    "component8.step": 9.21e-04,
    "cone_minus_sphere.igs": 7.11e-04,
    "filleted_plate.igs": 7.11e-04,
    "fused_cylinders.igs": 5.81e-04,
    "revolved_bspline.igs": 7.11e-04,
    "revolved_bspline.step": 8.39e-03,
    "revolved_bspline_brep.igs": 8.39e-03,
    "sphere.igs": 7.11e-04,
    "t20_data.step": 9.21e-04,
    "torus.igs": 6.79e-04,
    "torus.step": 1.10e-07,
    "torus_brep.igs": 1.10e-07,
}

# --- (b) the test parts and the real files against BRepGProp ---------------------------------


@pytest.fixture(scope="module")
def parts(tmp_path_factory):
    need_ocp()
    import cad_parts

    cad_parts.quiet()
    return cad_parts.write_parts(tmp_path_factory.mktemp("parts"))


def _part_names():
    try:
        import cad_parts

        return list(cad_parts.PARTS)
    except ImportError:  # pragma: no cover
        return []


@pytest.mark.parametrize("kind", ["step", "iges", "iges_brep"])
@pytest.mark.parametrize("name", _part_names())
def test_parts_agree_with_occ(name, kind, parts):
    path = parts[name].files()[kind]
    check_against_occ(path, path.name)


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    return tmp_path_factory.mktemp("real")


def _real_file(name: str) -> pathlib.Path:
    need_ocp()
    source = dict(cad_files.all_files())[name]
    if not source.exists():
        unavailable(cad_files.missing_message(source))
    return source


@pytest.mark.parametrize("name", [n for n, _ in cad_files.all_files()])
def test_real_files_agree_with_occ(name, scratch):
    check_against_occ(cad_files.materialize(_real_file(name), scratch), name)


def test_parts_volumes_against_closed_forms_and_occ_default(parts):
    """Every solid test part with a closed-form volume (``cad_parts.VOLUMES``), STEP and IGES
    B-rep: ours within 1e-10 of it; and where ``BRepGProp``'s default rule (what OCC users get
    without an ``eps``) is off by more than 1e-9, ours is at least 1000 times closer (measured
    2026-12-05: fused cylinders 4.5e-6, the revolved B-spline 4.8e-6, the rational B-spline hole
    1.6e-3 against ours 1.4e-11, 2.8e-14 and 6.9e-14 in STEP). ``pytest -s`` prints the table."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    import cad_parts

    compared = 0
    for name, part in parts.items():
        truth = cad_parts.VOLUMES.get(name)
        if truth is None:
            continue
        for kind, path in part.files().items():
            solids = inrs.cad_model(path).solids
            if not solids:
                continue  # IGES faces mode: no solids
            ours = abs(sum(s.volume for s in solids) - truth) / truth
            props = GProp_GProps()
            BRepGProp.VolumeProperties_s(cad_parts.read_shape(path), props)
            theirs = abs(props.Mass() - truth) / truth
            print(f"{name:18s} {kind:9s} ours {ours:.1e}  BRepGProp default {theirs:.1e}")
            assert ours <= 1e-10, (name, kind, ours)
            if theirs > 1e-9:
                assert 1000.0 * ours <= theirs, (name, kind, ours, theirs)
            compared += 1
    assert compared >= 16, compared


def test_sot23_spherical_triangles_against_their_closed_form():
    """SOT23.stp faces 23, 26 and 31: a surface of revolution of a circle (radius r) about an
    axis through its centre, a sphere, cut to the spherical triangle of the south pole and two
    vertices: area r^2 times the spherical excess (face 23's vertices from the file). Ours
    within the file's pcurves' 7.4e-10 mm from the great circles; BRepGProp's 2.5e-7 off."""
    path = _real_file("SOT23.stp")
    centre = np.array([1.433463764766, -0.623463764754, 0.102500000003])
    corners = [
        np.array([1.445946633952, -0.623463764754, 0.101845800551]),
        np.array([1.433463764766, -0.635946633939, 0.101845800551]),
        np.array([1.433463764766, -0.623463764754, 9.000000000271e-2]),
    ]
    a, b, c = (p - centre for p in corners)
    a, b, c = (v / np.linalg.norm(v) for v in (a, b, c))
    excess = 2.0 * math.atan2(abs(a @ np.cross(b, c)), 1.0 + a @ b + b @ c + c @ a)
    area = 1.250000000122e-2**2 * excess
    props = inrs.cad_model(path).properties()
    occ = cad_files.OccFile.read(path)
    for k in (23, 26, 31):
        ours = props.faces[k].area
        theirs = occ_props(occ.faces[k], volume=False)[0]
        assert abs(ours - area) <= 2e-9 * area, (k, ours, area)
        assert abs(theirs - area) >= 1e-7 * area, (k, theirs, area)


def test_cap_torus_quarter_against_its_closed_form():
    """CAP_50SGV_8_10.stp face 23: the quarter of a torus's tube (R = 3.25, r = 1, about an
    axis along z) from the outer equator to the top, over a full turn: area
    2 pi r (R pi / 2 + r) and second moments from 1-D integrals over the tube's angle (Gauss,
    exact to rounding). Ours within 1e-12; BRepGProp's second moments 1.5e-7 off at eps 1e-9."""
    path = _real_file("CAP_50SGV_8_10.stp")
    big, r = 3.25, 1.0
    x, w = np.polynomial.legendre.leggauss(60)
    v = np.pi / 4 * (x + 1.0)
    w = w * np.pi / 4
    d_area = r * (big + r * np.cos(v))
    area = 2 * np.pi * r * (big * np.pi / 2 + r)
    assert abs(2 * np.pi * (w @ d_area) - area) <= 1e-14 * area
    zc = 2 * np.pi * (w @ (r * np.sin(v) * d_area)) / area
    sxx = np.pi * (w @ ((big + r * np.cos(v)) ** 2 * d_area))
    szz = 2 * np.pi * (w @ ((r * np.sin(v)) ** 2 * d_area)) - area * zc**2
    second = np.diag([sxx, sxx, szz])
    ours = inrs.cad_model(path).properties().faces[23]
    assert abs(ours.area - area) <= 1e-12 * area
    assert np.abs(ours.second_moments - second).max() <= 1e-12 * np.abs(second).max()
    occ = cad_files.OccFile.read(path)
    _, _, inertia = occ_props(occ.faces[23], volume=False)
    want = np.trace(second) * np.eye(3) - second
    assert np.abs(inertia - want).max() >= 1e-8 * np.abs(want).max()


# --- (a), (c) closed forms -------------------------------------------------------------------


def _ax2(origin, axis):
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    return gp_Ax2(gp_Pnt(*origin), gp_Dir(*axis))


def _about_axis(axial: float, transverse: float, axis) -> np.ndarray:
    """The inertia tensor with moment ``axial`` about the unit direction of ``axis`` and
    ``transverse`` about every perpendicular one."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    return axial * np.outer(a, a) + transverse * (np.eye(3) - np.outer(a, a))


def _box(lo, size):
    """Volume, centroid and inertia (about the centroid) of the box at ``lo`` of ``size``."""
    a, b, c = size
    v = a * b * c
    return v, np.asarray(lo, float) + np.asarray(size) / 2, np.diag([b * b + c * c, a * a + c * c, a * a + b * b]) * v / 12


def _shifted(v, centroid, inertia, to) -> np.ndarray:
    """Parallel axes: ``inertia`` (about ``centroid``) about the point ``to``."""
    d = np.asarray(centroid, float) - np.asarray(to, float)
    return inertia + v * (d @ d * np.eye(3) - np.outer(d, d))


def sphere_part():
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeSphere
    from OCP.gp import gp_Pnt

    c, r = (1.0, 2.0, 3.0), 2.0
    v = 4 / 3 * math.pi * r**3
    return BRepPrimAPI_MakeSphere(gp_Pnt(*c), r).Shape(), (v, 4 * math.pi * r * r, c, 2 / 5 * v * r * r * np.eye(3))


def torus_part():
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeTorus

    c, axis, big, small = (0.5, -1.0, 2.0), (1.0, 1.0, 1.0), 3.0, 1.0
    v = 2 * math.pi**2 * big * small**2
    inertia = _about_axis(v * (big**2 + 3 / 4 * small**2), v * (big**2 / 2 + 5 / 8 * small**2), axis)
    return BRepPrimAPI_MakeTorus(_ax2(c, axis), big, small).Shape(), (v, 4 * math.pi**2 * big * small, c, inertia)


def cylinder_part():
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder

    base, axis, r, h = (1.0, -2.0, 0.5), (1.0, 2.0, -2.0), 1.5, 4.0
    a = np.asarray(axis) / 3.0
    v = math.pi * r * r * h
    inertia = _about_axis(v * r * r / 2, v * (3 * r * r + h * h) / 12, axis)
    area = 2 * math.pi * r * h + 2 * math.pi * r * r
    return BRepPrimAPI_MakeCylinder(_ax2(base, axis), r, h).Shape(), (v, area, np.asarray(base) + h / 2 * a, inertia)


def frustum_part():
    """A cone frustum of radii 2 (base) and 0.5 (top), height 3, tilted: its properties from
    the discs' integrals (polynomials in z, exact)."""
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCone

    base, axis, r1, r2, h = (0.0, 1.0, -1.0), (0.0, 3.0, 4.0), 2.0, 0.5, 3.0
    a = np.asarray(axis) / 5.0
    radius = np.polynomial.Polynomial([r1, (r2 - r1) / h])
    z = np.polynomial.Polynomial([0.0, 1.0])

    def integral(p):
        q = p.integ()
        return q(h) - q(0)

    v = integral(math.pi * radius**2)
    zc = integral(math.pi * radius**2 * z) / v
    axial = integral(math.pi * radius**4 / 2)
    transverse = integral(math.pi * radius**4 / 4 + math.pi * radius**2 * z**2) - v * zc * zc
    area = math.pi * (r1 + r2) * math.hypot(r1 - r2, h) + math.pi * (r1 * r1 + r2 * r2)
    inertia = _about_axis(axial, transverse, axis)
    return BRepPrimAPI_MakeCone(_ax2(base, axis), r1, r2, h).Shape(), (v, area, np.asarray(base) + zc * a, inertia)


def holed_box_part():
    """The box [0, 5] x [0, 4] x [0, 2] less a vertical cylinder of radius 1 about (3, 1.5)."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder

    size, (hx, hy, r) = (5.0, 4.0, 2.0), (3.0, 1.5, 1.0)
    box = BRepPrimAPI_MakeBox(*size).Shape()
    drill = BRepPrimAPI_MakeCylinder(_ax2((hx, hy, -1.0), (0, 0, 1)), r, size[2] + 2).Shape()
    cut = BRepAlgoAPI_Cut(box, drill)
    cut.Build()
    vb, cb, ib = _box((0, 0, 0), size)
    h = size[2]
    vh, ch = math.pi * r * r * h, np.array([hx, hy, h / 2])
    ih = _about_axis(vh * r * r / 2, vh * (3 * r * r + h * h) / 12, (0, 0, 1))
    v = vb - vh
    c = (vb * cb - vh * ch) / v
    inertia = _shifted(vb, cb, ib, c) - _shifted(vh, ch, ih, c)
    area = 2 * (size[0] * size[1] + size[1] * size[2] + size[0] * size[2]) - 2 * math.pi * r * r + 2 * math.pi * r * h
    return cut.Shape(), (v, area, c, inertia)


#: The revolved polygon, in the (x, z) half plane: (radius, height) corners.
PROFILE = [(1.0, 0.0), (3.0, 0.5), (2.5, 2.0), (1.5, 1.5)]


def revolved_part():
    """The polygon :data:`PROFILE` revolved a full turn about z: Pappus's volume (2 pi times
    its area times its centroid's radius) and area (2 pi times each edge's length times its
    midpoint's radius); the centroid on the axis at ``int z x dA / int x dA``."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeRevol
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt

    poly = BRepBuilderAPI_MakePolygon()
    for x, z in PROFILE:
        poly.Add(gp_Pnt(x, 0.0, z))
    poly.Close()
    face = BRepBuilderAPI_MakeFace(poly.Wire()).Face()
    shape = BRepPrimAPI_MakeRevol(face, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2 * math.pi).Shape()
    pts = PROFILE + PROFILE[:1]
    volume = 2 * math.pi * _polygon_integral(lambda x, z: x * x / 2)  # 2 pi int x dA
    surface = sum(2 * math.pi * math.dist(p, q) * (p[0] + q[0]) / 2 for p, q in zip(pts, pts[1:]))
    zc = 2 * math.pi * _polygon_integral(lambda x, z: x * x * z / 2) / volume  # int x z dA
    # About z: int r^2 dV = 2 pi int x^3 dA; about a transverse axis through the centroid:
    # int y^2 dV = pi int x^3 dA, int z^2 dV = 2 pi int z^2 x dA.
    x3 = _polygon_integral(lambda x, z: x**4 / 4)
    z2x = _polygon_integral(lambda x, z: z * z * x * x / 2)
    axial = 2 * math.pi * x3
    transverse = math.pi * x3 + 2 * math.pi * z2x - volume * zc * zc
    return shape, (volume, surface, (0.0, 0.0, zc), _about_axis(axial, transverse, (0, 0, 1)))


def _polygon_integral(antiderivative) -> float:
    """``int f dA`` over :data:`PROFILE` (counter-clockwise in (x, z)) by Green's theorem,
    ``oint F dz`` with ``F`` the antiderivative of ``f`` in ``x``: a polynomial of degree <= 7
    along each edge, which 4-point Gauss-Legendre integrates exactly."""
    t, w = np.polynomial.legendre.leggauss(4)
    t, w = (t + 1) / 2, w / 2
    pts = PROFILE + PROFILE[:1]
    total = 0.0
    for (x0, z0), (x1, z1) in zip(pts, pts[1:]):
        x, z = x0 + t * (x1 - x0), z0 + t * (z1 - z0)
        total += math.fsum(w * antiderivative(x, z)) * (z1 - z0)
    return total


def void_part():
    import cad_parts

    v = 64 - 4 / 3 * math.pi
    inertia = (64 * 32 / 12 - 2 / 5 * 4 / 3 * math.pi) * np.eye(3)
    return cad_parts.box_with_void(), (v, 96 + 4 * math.pi, (0.0, 0.0, 0.0), inertia)


CLOSED_FORMS = {
    "sphere": sphere_part,
    "torus": torus_part,
    "cylinder": cylinder_part,
    "frustum": frustum_part,
    "holed_box": holed_box_part,
    "revolved": revolved_part,
    "box_void": void_part,
}


def relative_errors(volume, area, centroid, inertia, truth, size):
    v, a, c, i = truth
    return {
        "volume": abs(volume - v) / v,
        "area": abs(area - a) / a,
        "centroid": np.abs(np.asarray(centroid) - c).max() / size,
        "inertia": np.abs(np.asarray(inertia) - i).max() / np.abs(i).max(),
    }


@pytest.mark.parametrize("name", list(CLOSED_FORMS))
def test_closed_forms(name, tmp_path):
    need_ocp()
    import cad_parts

    cad_parts.quiet()
    shape, truth = CLOSED_FORMS[name]()
    path = cad_parts.write_step(shape, tmp_path / f"{name}.step")
    m = inrs.cad_model(path)
    assert len(m.solids) == 1
    s = m.solids[0]
    size = cad_files.OccFile.read(path).size
    ours = relative_errors(s.volume, s.area, s.centroid, s.inertia, truth, size)
    shape = cad_parts.read_shape(path)
    v, c, i = occ_props(shape, volume=True)
    a = occ_props(shape, volume=False)[0]
    theirs = relative_errors(v, a, c, i, truth, size)
    print(f"\n{name}: ours {ours}\n{' ' * len(name)}  OCC  {theirs}")
    for what, d in ours.items():
        # (a) the closed form
        assert d <= CLOSED_REL, f"{name}: {what} off its closed form by {d:.2e}"
    # (c) no farther from it than OCC at eps 1e-9, or within 1e-15 of it
    worse = {what for what, d in ours.items() if not d <= max(theirs[what], EQUAL_REL)}
    detail = ", ".join(f"{w} {ours[w]:.1e} (OCC {theirs[w]:.1e})" for w in sorted(worse))
    assert worse == OCC_CLOSER.get(name, set()), f"{name}: farther from the closed form than OCC: {detail or 'none'}"
    if worse:
        pytest.xfail(f"{name}: OCC closer to the closed form than inrs: {detail}")


#: Where (c) does not hold, measured: OCC's ``BRepGProp`` at eps 1e-9 is closer to the closed
#: form than we are (its volumes and areas of analytic faces to ~1e-16; ours stop at ~1e-13 on
#: the torus, ~5e-15 on planes and cylinders). Ours are still within 1e-12 (a), and OCC's
#: inertia is the worse by 1e-9 to 1e-7 on every part but ``box_void`` (where both are within
#: 1e-15). Listed so that a change
#: either way fails the test.
OCC_CLOSER = {
    "torus": {"volume", "area", "centroid"},  # ours 1.5e-13, 7.7e-14, 1.5e-14; OCC 6e-16, 0, 1e-16
    "cylinder": {"centroid"},  # ours 1.0e-13, OCC 8.9e-14 (both: the STEP file's rounding?)
    "holed_box": {"volume", "area", "centroid"},  # ours 5.7e-15, 5.5e-15, 2.2e-15; OCC ~2e-16
}


def test_largest_file_timing(scratch):
    """``properties()`` on the largest real file, timed (printed with ``-s``)."""
    need_ocp()
    sources = [p for _, p in cad_files.all_files() if p.exists()]
    if not sources:
        unavailable(cad_files.missing_message(cad_files.all_files()[0][1]))
    path = max((cad_files.materialize(p, scratch) for p in sources), key=lambda p: p.stat().st_size)
    m = inrs.cad_model(path, **cad_files.closure_kwargs())
    start = time.perf_counter()
    p = m.properties()
    elapsed = time.perf_counter() - start
    print(f"\nproperties() of {path.name} ({len(m.faces)} faces, {len(m.solids)} solids): {elapsed:.3f} s")
    assert len(p.faces) == len(m.faces)

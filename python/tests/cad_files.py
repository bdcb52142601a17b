"""The real CAD files and the OpenCASCADE oracle, shared by test_cad_occ.py and cad_table.py.

The files come from Debian packages (``.ci/run`` installs them): ``freecad-common``'s IDF
library (28 STEP and 4 IGES parts written by OpenCASCADE, with pcurves) and ``gmsh-doc``'s
gzipped demos (STEP from other writers). OpenCASCADE (OCP, PyPI ``cadquery-ocp-novtk``) reads
each file as ``STEPControl_Reader`` / ``IGESControl_Reader`` do it (``TransferRoots``,
``OneShape``) and lists the faces with ``TopExp_Explorer(shape, TopAbs_FACE)``: that order is
the order ``inrs.cad_faces`` promises.

Per face, random ``(u, v)`` points in the face's ``BRepTools.UVBounds`` box enlarged by 5% on
each side are classified by ``BRepClass_FaceClassifier`` (the oracle) and by an inrs domain;
points that either side puts on the boundary, or that lie within a margin of the loops, are
left out of the comparison (there the answer depends on tolerances, not on the loops).

``inrs.cad_model`` reads each face in the file's own ``(u, v)``, OCC in its own. Where OCC's is
the file's scaled to millimetres and radians (:func:`uv_scale`), the points are scaled, and the
scale is checked in space: our surface (``CadFace.points``, the Rust geometry layer) meets OCC's
surface at the scaled point (:func:`scale_map_error`). Elsewhere (surfaces of revolution, whose
curve OCC re-frames and whose ``u``, ``v`` IGES and OCC swap; IGES planes and the IGES analytic
surfaces in degrees) the points are drawn in the file's box and carried to OCC's ``(u, v)``
through space (:class:`ProjectionMap`): our surface's point, found on OCC's surface. Every face
read also has its surface checked against OCC's: random points of our surface inside the face
lie on OCC's surface within :data:`SURFACE_TOL` of the part's size (:func:`surface_deviation`).

This module imports OCP only inside :func:`load_ocp` and the functions that need it, so that
the test module can skip (or fail) with a message when OCP is missing.
"""

from __future__ import annotations

import gzip
import math
import os
import pathlib
import re
import shutil
import zlib
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import numpy as np

IDF = pathlib.Path("/usr/share/freecad/Mod/Idf/Idflibs")
GMSH = pathlib.Path("/usr/share/doc/gmsh-doc/doc/gmsh")

#: The 28 STEP and 4 IGES parts of freecad-common's IDF library (Debian 0.19-0.21).
IDF_FILES = [
    "0603_SMD.stp", "0805_SMD.stp", "1206_SMD.stp", "1210_SMD.stp", "1812_SMD.stp",
    "2225_SMD.stp", "2512_SMD.stp", "CAP_50SGV_8_10.stp", "EPL22_6_16.stp",
    "I22_2_5_16.stp", "I22_2_5_16withEPL22_6_16.stp", "MSOP_10.stp", "RLF_12545.stp",
    "RLF_7030.stp", "SMB_DO_214AA.stp", "SMC_DO_214AB.stp", "SOD_323.stp", "SOD_523.stp",
    "SOT23.stp", "SOT404.stp", "SOT428_DPAK.stp", "SOT_323_3.stp", "SOT_96.stp",
    "TCMT1107_4.stp", "TSM_103_01_L_DV_A.stp", "TSM_104_01_L_DV_A.stp", "TSS0P_8.stp",
    "VC0603_SMD.stp",
    "RLF_12545.igs", "SOD_323.igs", "SOT23.igs", "SOT404.igs",
]  # fmt: skip

#: gmsh-doc's gzipped STEP demos.
GMSH_FILES = [
    "demos/api/as1-tu-203.stp.gz",
    "demos/api/step_boundary_colors.stp.gz",
    "demos/boolean/component8.step.gz",
    "tutorial/t20_data.step.gz",
]

#: The Debian package of each directory, for the messages about missing files.
PACKAGES = {IDF: "freecad-common", GMSH: "gmsh-doc"}

#: Points per face: 3327 faces in all, so the two comparisons stay well under two minutes.
POINTS_PER_FACE = 64
#: Relative closure tolerance given to inrs when it takes one (OCC writes pcurves whose ends
#: miss by up to ~2e-6 of the face's (u, v) diagonal; the default 1e-9 would refuse those).
CLOSURE_TOL = 1e-5
#: OCC's classifier tolerance, relative to the (u, v) box diagonal.
OCC_TOL = 1e-7
#: Points closer than this (relative to the diagonal) to the loops are left out: it covers the
#: closure gaps and the classifiers' tolerances.
MARGIN = 1e-5
#: A face whose (u, v) box is thinner than this fraction of its length is degenerate (a sliver
#: of zero area: OCC's classifier answers IN far from it); it is reported, not compared.
DEGENERATE = 1e-6


def require_system_files() -> bool:
    """True where missing files or a missing OCP must fail the tests (``.ci/run`` sets it)."""
    return os.environ.get("INRS_REQUIRE_SYSTEM_FILES") == "1"


def unavailable(message: str) -> None:
    """Skips the calling test with ``message``, or fails it where the system files are required
    (``INRS_REQUIRE_SYSTEM_FILES=1``, as CI sets)."""
    import pytest

    if require_system_files():
        pytest.fail(f"{message} (INRS_REQUIRE_SYSTEM_FILES=1)", pytrace=False)
    pytest.skip(message)


def all_files() -> List[Tuple[str, pathlib.Path]]:
    """``(name, path)`` of every real file, present or not (the name is the test id)."""
    return [(n, IDF / n) for n in IDF_FILES] + [(pathlib.Path(g).name[: -len(".gz")], GMSH / g) for g in GMSH_FILES]


def missing_message(path: pathlib.Path) -> str:
    """Why ``path`` is absent and how to get it."""
    package = next((p for d, p in PACKAGES.items() if d in path.parents), None)
    return f"{path} is missing" + (f" (Debian package {package})" if package else "")


def materialize(path: pathlib.Path, scratch: pathlib.Path) -> pathlib.Path:
    """``path`` itself, or for ``x.stp.gz`` the decompressed ``scratch/x.stp``."""
    if path.suffix != ".gz":
        return path
    out = scratch / path.name[: -len(".gz")]
    if not out.exists():
        scratch.mkdir(parents=True, exist_ok=True)
        with gzip.open(path, "rb") as src, open(out, "wb") as dst:
            shutil.copyfileobj(src, dst)
    return out


def load_ocp():
    """Imports OCP, quiets OpenCASCADE's messages, and returns the module (``ImportError``
    when it is not installed)."""
    import OCP  # noqa: F401
    from OCP.Message import Message, Message_Gravity

    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)
    return OCP


@dataclass
class OccFile:
    """A CAD file as OpenCASCADE reads it."""

    path: pathlib.Path
    format: str  # "STEP" or "IGES"
    faces: list  # TopoDS_Face, in TopExp_Explorer order
    #: The entity of each face as the file names it (``#123``, ``DE 57``), None where OCC's
    #: transfer keeps no link.
    entities: List[Optional[str]]
    #: Millimetres per length unit of the file (OCC converts lengths to millimetres).
    mm_per_unit: float
    #: Radians per plane-angle unit of the file (OCC converts angles to radians).
    rad_per_angle_unit: float
    #: Lazily computed per face: points, OCC codes, diagonal (see :meth:`face_sample`).
    samples: Dict[int, "FaceSample"] = field(default_factory=dict)
    #: The diagonal of OCC's bounding box of the whole shape (millimetres).
    size: float = 0.0

    @staticmethod
    def read(path: pathlib.Path) -> "OccFile":
        """Reads ``path`` (``.stp``/``.step`` or ``.igs``/``.iges``) with OCC."""
        from OCP.IFSelect import IFSelect_RetDone
        from OCP.IGESControl import IGESControl_Reader
        from OCP.STEPControl import STEPControl_Reader
        from OCP.TopAbs import TopAbs_FACE
        from OCP.TopExp import TopExp_Explorer
        from OCP.TopLoc import TopLoc_Location
        from OCP.TopoDS import TopoDS

        as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
        step = path.suffix.lower() in (".stp", ".step")
        reader = STEPControl_Reader() if step else IGESControl_Reader()
        if reader.ReadFile(str(path)) != IFSelect_RetDone:
            raise OSError(f"OpenCASCADE cannot read {path}")
        reader.TransferRoots()
        shape = reader.OneShape()
        faces = []
        explorer = TopExp_Explorer(shape, TopAbs_FACE)
        while explorer.More():
            faces.append(as_face(explorer.Current()))
            explorer.Next()
        ws = reader.WS()
        model, transfer = ws.Model(), ws.TransferReader()
        text = path.read_text(errors="replace")
        if step:
            names = _step_face_labels(model, text)
            mm = float(reader.StepModel().LocalLengthUnit())
            rad = math.pi / 180 if re.search(r"CONVERSION_BASED_UNIT\s*\(\s*'DEGREES?'", text, re.I) else 1.0
        else:
            # IGES: the directory entry of entity number i (from 1) is line 2 i - 1.
            names = {model.Value(i): f"DE {2 * i - 1}" for i in range(1, model.NbEntities() + 1)}
            section = reader.IGESModel().GlobalSection()
            mm = float(section.UnitValue()) / float(section.CascadeUnit())
            rad = 1.0  # IGES angles are radians
        entities = []
        for face in faces:
            # The transfer binds the part's faces without the assembly's placement: look the
            # face up without its location (IsSame compares the location too).
            entity = transfer.EntityFromShapeResult(face.Located(TopLoc_Location()), 1)
            entities.append(None if entity is None else names.get(entity))
        from OCP.Bnd import Bnd_Box
        from OCP.BRepBndLib import BRepBndLib

        box = Bnd_Box()
        BRepBndLib.Add_s(shape, box)
        lo, hi = box.CornerMin(), box.CornerMax()
        size = lo.Distance(hi)
        return OccFile(path, "STEP" if step else "IGES", faces, entities, mm, rad, size=size)

    def face_sample(self, k: int, n: int = POINTS_PER_FACE) -> "FaceSample":
        """The random points of face ``k`` and OCC's codes for them (computed once)."""
        if k not in self.samples:
            self.samples[k] = FaceSample.of(self.faces[k], seed=(zlib.crc32(self.path.name.encode()), k), n=n)
        return self.samples[k]


def _step_face_labels(model, text: str) -> dict:
    """``{entity object: "#123"}`` for the file's ADVANCED_FACE instances. (The binding's
    ``IdentLabel`` and ``Number`` answer 0 for every entity; ``NextNumberForLabel`` works, and
    OCP hands out one Python object per live entity, so the objects are the keys.)"""
    labels = {}
    for m in re.finditer(r"#(\d+)\s*=\s*ADVANCED_FACE\b", text):
        number = model.NextNumberForLabel(f"#{m.group(1)}", 0, True)
        if number > 0:
            labels[model.Value(number)] = f"#{m.group(1)}"
    return labels


@dataclass
class FaceSample:
    """Random ``(u, v)`` points of one face and what OCC says of them."""

    points: np.ndarray  # (n, 2), in OCC's (u, v)
    codes: np.ndarray  # int8: 0 OUT, 1 IN, 2 ON (OCC's classifier)
    diagonal: float  # of the UVBounds box
    size: Tuple[float, float]  # width and height of the UVBounds box
    #: Why the face is not compared (degenerate), or None.
    skip: Optional[str]

    @staticmethod
    def of(face, seed, n: int) -> "FaceSample":
        from OCP.BRepTools import BRepTools

        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        du, dv = u1 - u0, v1 - v0
        diagonal = math.hypot(du, dv)
        skip = box_skip(du, dv)
        if skip:
            return FaceSample(np.zeros((0, 2)), np.zeros(0, np.int8), diagonal, (du, dv), skip)
        points = random_points((u0, v0, u1, v1), seed, n)
        return FaceSample(points, occ_codes(face, points, OCC_TOL * diagonal), diagonal, (du, dv), None)


def occ_box(face) -> Tuple[float, float, float, float]:
    """``(u0, v0, du, dv)``: OCC's ``BRepTools.UVBounds`` of ``face``, corner and size."""
    from OCP.BRepTools import BRepTools

    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    return u0, v0, u1 - u0, v1 - v0


def box_skip(du: float, dv: float) -> Optional[str]:
    """Why a face whose ``(u, v)`` box is ``du`` by ``dv`` is not compared, or None."""
    diagonal = math.hypot(du, dv)
    if not (math.isfinite(diagonal) and diagonal > 0):
        return f"UV box {du} x {dv}"
    if min(du, dv) <= DEGENERATE * max(du, dv):
        return f"degenerate: UV box {du:.3g} x {dv:.3g}"
    return None


def random_points(box: Tuple[float, float, float, float], seed, n: int) -> np.ndarray:
    """``n`` random points in ``box = (u0, v0, u1, v1)`` grown by 5% on each side."""
    u0, v0, u1, v1 = box
    du, dv = u1 - u0, v1 - v0
    rng = np.random.default_rng(list(seed))
    return np.column_stack(
        [rng.uniform(u0 - 0.05 * du, u1 + 0.05 * du, n), rng.uniform(v0 - 0.05 * dv, v1 + 0.05 * dv, n)]
    )


def occ_codes(face, points: np.ndarray, tol: float) -> np.ndarray:
    """OCC's classification of ``points`` (in OCC's ``(u, v)`` of ``face``): int8 codes 0
    OUT, 1 IN, 2 ON; NaN points get 2 (left out)."""
    from OCP.BRepClass import BRepClass_FaceClassifier
    from OCP.gp import gp_Pnt2d
    from OCP.TopAbs import TopAbs_IN, TopAbs_OUT

    codes = np.full(len(points), 2, np.int8)
    for i, (u, v) in enumerate(points):
        if math.isfinite(u) and math.isfinite(v):
            state = BRepClass_FaceClassifier(face, gp_Pnt2d(float(u), float(v)), tol).State()
            codes[i] = 1 if state == TopAbs_IN else 0 if state == TopAbs_OUT else 2
    return codes


@dataclass
class Comparison:
    """The points of one face compared: how many, how many left out, which disagree."""

    compared: int
    excluded: int
    #: ``(point, OCC code, inrs code)`` of each disagreement.
    disagreements: List[Tuple[Tuple[float, float], int, int]]


def compare(domain, points: np.ndarray, occ_codes: np.ndarray, diagonal: float) -> Comparison:
    """Classifies ``points`` by ``domain`` (in the domain's coordinates) and compares with
    ``occ_codes``, leaving out the points either side puts on the boundary and those within
    ``MARGIN * diagonal`` of the domain's loops."""
    ours = domain.classify(points)
    accuracy = 0.1 * MARGIN * diagonal
    near = near_loops(domain.flatten(accuracy), points, MARGIN * diagonal + accuracy)
    keep = (occ_codes != 2) & (ours != 2) & ~near
    bad = np.flatnonzero(keep & (ours != occ_codes))
    return Comparison(
        int(keep.sum()),
        int(len(points) - keep.sum()),
        [((float(points[i, 0]), float(points[i, 1])), int(occ_codes[i]), int(ours[i])) for i in bad],
    )


def near_loops(rings: List[np.ndarray], points: np.ndarray, distance: float) -> np.ndarray:
    """True for each point within ``distance`` of one of the closed polylines ``rings``."""
    near = np.zeros(len(points), bool)
    for ring in rings:
        if len(ring) == 0:
            continue
        a, b = ring, np.roll(ring, -1, axis=0)
        # Blocks of points keep the (points, segments) arrays small on long polylines.
        step = max(1, 2_000_000 // max(1, len(a)))
        for s in range(0, len(points), step):
            p = points[s : s + step, None, :]
            ab = b - a
            t = np.clip(np.einsum("psk,sk->ps", p - a, ab) / np.maximum(np.einsum("sk,sk->s", ab, ab), 1e-300), 0, 1)
            d2 = np.sum((a + t[..., None] * ab - p) ** 2, axis=-1)
            near[s : s + step] |= d2.min(axis=1) <= distance * distance
    return near


def filled_area(domain) -> Optional[float]:
    """The domain's filled area, or None where its loops lie on each other (a sliver face's
    two sides written as one curve each way: the fill is not decided, ``Domain.area`` says
    so with a ``ValueError``)."""
    try:
        return domain.area
    except ValueError as e:
        if "lies on another loop" in str(e):
            return None
        raise


def max_relative_gap(loops) -> float:
    """The largest distance from one curve's end to the next one's start (the last to the
    first) over the loops of :func:`inrs.occ.face_loops`, relative to their box diagonal."""
    points = [c[2] for loop in loops for c in loop]
    if not points:
        return math.inf
    allp = np.concatenate(points)
    diagonal = float(np.hypot(*(allp.max(axis=0) - allp.min(axis=0))))
    gap = 0.0
    for loop in loops:
        for c, d in zip(loop, loop[1:] + loop[:1]):
            gap = max(gap, float(np.hypot(*(c[2][-1] - d[2][0]))))
    return gap / diagonal if diagonal > 0 else math.inf


def uv_scale(face, occ_file: OccFile) -> Optional[Tuple[float, float]]:
    """``(su, sv)`` such that the file's own ``(u, v)`` (what ``inrs.cad_faces`` reads) is
    OCC's ``(u / su, v / sv)``, or None where the two parameterisations differ by more than
    a scale.

    OCC converts lengths to millimetres and angles to radians, so a length parameter scales
    by ``mm_per_unit`` and an angle by ``rad_per_angle_unit``: planes (both lengths),
    cylinders (angle, length), spheres and tori (angles), B-spline and Bezier surfaces (their
    own knots: unscaled). A cone's ``v`` is the height along the axis in STEP (ISO 10303-42)
    but the length along the generatrix in OCC: ``sv = mm / cos(semi-angle)``. IGES
    surfaces other than B-splines are parameterised otherwise than OCC's (lines on [0, 1],
    revolution angle second; a 108 plane's axes chosen by the reader), as are surfaces of
    revolution: None (:class:`ProjectionMap` maps those). :func:`scale_map_error` checks the
    scale where it is given.
    """
    from OCP.BRep import BRep_Tool
    from OCP.Geom import (
        Geom_BezierSurface,
        Geom_BSplineSurface,
        Geom_ConicalSurface,
        Geom_CylindricalSurface,
        Geom_Plane,
        Geom_RectangularTrimmedSurface,
        Geom_SphericalSurface,
        Geom_ToroidalSurface,
    )

    surface = BRep_Tool.Surface_s(face)
    for _ in range(8):
        if not isinstance(surface, Geom_RectangularTrimmedSurface):
            break
        surface = surface.BasisSurface()
    mm, rad = occ_file.mm_per_unit, occ_file.rad_per_angle_unit
    if isinstance(surface, (Geom_BSplineSurface, Geom_BezierSurface)):
        return (1.0, 1.0)
    if occ_file.format != "STEP":
        return None
    if isinstance(surface, Geom_Plane):
        return (mm, mm)
    if isinstance(surface, Geom_CylindricalSurface):
        return (rad, mm)
    if isinstance(surface, Geom_ConicalSurface):
        return (rad, mm / math.cos(surface.SemiAngle()))
    if isinstance(surface, (Geom_SphericalSurface, Geom_ToroidalSurface)):
        return (rad, rad)
    return None


#: Largest distance, relative to the face's extent in space, between the file's surface at a
#: point and OCC's surface at the point's mapped ``(u, v)``. Both are the same surface, its
#: numbers written with 10 or more significant digits; the real files give under 1e-11.
MAP_TOL = 1e-7


#: How well a mapped point's OCC ``(u, v)`` must be known, relative to OCC's box diagonal (the
#: distance left in space over the surface's stretch), to be compared: far below MARGIN, so
#: that the points kept are on the same side of the loops for OCC as for inrs.
UV_TOL = 1e-8


class MapError(ValueError):
    """No map between a face's ``(u, v)`` in the file and in OCC."""


def occ_surfaces(face) -> list:
    """OCC's surface of ``face`` in the frames the file's points may be in: without the
    face's location (a STEP part's own frame, when an assembly places the part) and with it
    (IGES: model space, where OCC may have moved a transformation matrix into the location)."""
    from OCP.BRep import BRep_Tool
    from OCP.TopLoc import TopLoc_Location

    return [BRep_Tool.Surface_s(face, TopLoc_Location()), BRep_Tool.Surface_s(face)]


def _extent(evaluate, box) -> float:
    """The diagonal of the 3-D box of the file's surface on a 3 x 3 grid of ``box``."""
    u0, v0, u1, v1 = box
    g = np.array([(u, v) for u in (u0, (u0 + u1) / 2, u1) for v in (v0, (v0 + v1) / 2, v1)])
    p = evaluate(g)
    return float(np.linalg.norm(p.max(axis=0) - p.min(axis=0)))


def _value(surface, u: float, v: float) -> np.ndarray:
    p = surface.Value(float(u), float(v))
    return np.array([p.X(), p.Y(), p.Z()])


def newton(surface, target: np.ndarray, uv: np.ndarray, eps: float) -> Tuple[Optional[np.ndarray], float]:
    """``(uv, error)``: the ``(u, v)`` near ``uv`` where OCC's ``surface`` meets the 3-D point
    ``target`` (Gauss-Newton on the distance, until a step is below ``eps``) and a bound on
    how far it may be from the exact one: the distance left in space divided by the
    surface's smallest stretch there (near an axis or a pole ``u`` is ill-conditioned and
    the steps stop shrinking at the rounding level; that bound says how much it matters).
    ``(None, inf)`` where the surface is singular."""
    from OCP.gp import gp_Pnt, gp_Vec

    p, su, sv = gp_Pnt(), gp_Vec(), gp_Vec()
    u, v = float(uv[0]), float(uv[1])
    best: Tuple[Optional[np.ndarray], float] = (None, math.inf)
    for _ in range(12):
        surface.D1(u, v, p, su, sv)
        r = target - np.array([p.X(), p.Y(), p.Z()])
        eu, ev = np.array([su.X(), su.Y(), su.Z()]), np.array([sv.X(), sv.Y(), sv.Z()])
        aa, ab, bb = eu @ eu, eu @ ev, ev @ ev
        det = aa * bb - ab * ab
        if not (det > 1e-20 * aa * bb):
            break
        # The smallest singular value of the Jacobian [eu ev]: the square root of the Gram
        # matrix's smallest eigenvalue.
        stretch = math.sqrt(max(0.0, (aa + bb) / 2 - math.sqrt(((aa - bb) / 2) ** 2 + ab * ab)))
        error = float(np.linalg.norm(r)) / stretch if stretch > 0 else math.inf
        if error < best[1]:
            best = (np.array([u, v]), error)
        ra, rb = eu @ r, ev @ r
        du, dv = (bb * ra - ab * rb) / det, (aa * rb - ab * ra) / det
        if not (math.isfinite(du) and math.isfinite(dv)) or math.hypot(du, dv) <= eps:
            break
        u, v = u + du, v + dv
    return best


@dataclass
class ProjectionMap:
    """The map from the file's ``(u, v)`` of a face to OCC's, through space: a point's image
    on our surface (``CadFace.points``) is found on OCC's surface by Newton's method, started from the map's linear approximation at the face's
    centre. Where OCC's parameterisation is periodic, that start picks the representative:
    the centre's image is taken in OCC's face box, and the others follow continuously (a
    point outside the file's box goes outside OCC's, as it should)."""

    surface: object  # OCC's Geom_Surface, in the file's frame
    evaluate: object  # our surface, (n, 2) -> (n, 3) millimetres
    centre: np.ndarray  # the file's (u, v)
    image: np.ndarray  # its OCC (u, v)
    jacobian: np.ndarray  # d(OCC's u, v) / d(the file's u, v) at the centre
    diagonal: float  # of OCC's (u, v) box of the face
    eps: float  # Newton's last step in OCC's (u, v)

    @staticmethod
    def of(face, evaluate, box: Tuple[float, float, float, float]) -> "ProjectionMap":
        """The map of ``face`` whose file surface is ``evaluate``, the file's domain in
        ``box = (u0, v0, u1, v1)``."""
        from OCP.BRepTools import BRepTools
        from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
        from OCP.gp import gp_Pnt

        u0, v0, u1, v1 = map(float, box)
        ou0, ou1, ov0, ov1 = BRepTools.UVBounds_s(face)
        tol = MAP_TOL * _extent(evaluate, box)
        box_diagonal = math.hypot(ou1 - ou0, ov1 - ov0)
        eps = 1e-13 * box_diagonal
        if not (tol > 0 and eps > 0):
            raise MapError(f"empty box {box} or OCC box {(ou0, ou1, ov0, ov1)}")
        h = np.array([1e-3 * (u1 - u0), 1e-3 * (v1 - v0)])
        # The centre, or a point near it where the surface is regular (not an apex or pole).
        for fu, fv in ((0.5, 0.5), (0.4, 0.6), (0.6, 0.35)):
            centre = np.array([u0 + fu * (u1 - u0), v0 + fv * (v1 - v0)])
            target = evaluate(centre[None])[0]
            best = None
            for surface in occ_surfaces(face):
                proj = GeomAPI_ProjectPointOnSurf(gp_Pnt(*map(float, target)), surface)
                if proj.NbPoints() > 0 and (best is None or proj.LowerDistance() < best[0]):
                    best = (proj.LowerDistance(), surface, np.array(proj.LowerDistanceParameters()))
            if best is None or not best[0] <= tol:
                dist = "nowhere" if best is None else f"{best[0]:.3g} mm away"
                raise MapError(f"the file's surface at {tuple(centre)} is {dist} from OCC's (tolerance {tol:.3g} mm)")
            _, surface, image = best
            # The representative of a periodic parameter nearest the middle of OCC's box.
            if surface.IsUPeriodic():
                image[0] += surface.UPeriod() * round(((ou0 + ou1) / 2 - image[0]) / surface.UPeriod())
            if surface.IsVPeriodic():
                image[1] += surface.VPeriod() * round(((ov0 + ov1) / 2 - image[1]) / surface.VPeriod())
            image, error = newton(surface, target, image, eps)
            if not error <= UV_TOL * box_diagonal:
                continue
            columns = []
            for d in (np.array([h[0], 0.0]), np.array([0.0, h[1]])):
                q, error = newton(surface, evaluate((centre + d)[None])[0], image, eps)
                if not error <= UV_TOL * box_diagonal:
                    break
                columns.append((q - image) / d[d != 0][0])
            if len(columns) == 2:
                return ProjectionMap(surface, evaluate, centre, image, np.column_stack(columns), box_diagonal, eps)
        raise MapError("OCC's surface is singular at the centre of the face and near it")

    def __call__(self, points: np.ndarray) -> np.ndarray:
        """OCC's ``(u, v)`` of ``points`` (n, 2) in the file's; NaN rows where Newton's method
        fails or its result is not known within ``UV_TOL`` of the box diagonal (at and near
        a singular point of the surface): those are left out of the comparison."""
        targets = self.evaluate(points)
        starts = self.image + (points - self.centre) @ self.jacobian.T
        out = np.full(points.shape, np.nan)
        for i, (target, start) in enumerate(zip(targets, starts)):
            q, error = newton(self.surface, target, start, self.eps)
            if error <= UV_TOL * self.diagonal:
                out[i] = q
        return out


def scale_map_error(face, evaluate, scale: Tuple[float, float], box) -> float:
    """How far (relative to the face's extent) OCC's surface at ``(su u, sv v)`` is from the
    file's surface at ``(u, v)``, the largest over five points of ``box``: ~0 where
    :func:`uv_scale` gives the exact map."""
    u0, v0, u1, v1 = box
    fractions = np.array([(0.5, 0.5), (0.2, 0.3), (0.8, 0.7), (0.3, 0.9), (0.9, 0.1)])
    uv = np.array([u0, v0]) + fractions * np.array([u1 - u0, v1 - v0])
    targets = evaluate(uv)
    extent = _extent(evaluate, box)
    best = math.inf  # over the frames of occ_surfaces: the one the file's points are in
    for surface in occ_surfaces(face):
        d = max(float(np.linalg.norm(_value(surface, scale[0] * u, scale[1] * v) - t)) for (u, v), t in zip(uv, targets))
        best = min(best, d)
    return best / extent if extent > 0 else math.inf


def reason(error: str) -> str:
    """A refusal message without its numbers and entity names, so that the faces refused for
    one reason group together."""
    text = re.sub(r"(#|DE )\d+", "#N", error)
    return re.sub(r"[-+]?\d+(\.\d+)?([eE][-+]?\d+)?", "N", text)


def surface_name(face) -> str:
    """OCC's surface type of ``face`` without the ``Geom_`` prefix."""
    from OCP.BRep import BRep_Tool

    return type(BRep_Tool.Surface_s(face)).__name__.replace("Geom_", "")


def closure_kwargs() -> dict:
    """``closure_tol=CLOSURE_TOL`` where this build's ``Domain.from_curves`` takes it, else
    nothing (the default 1e-9 is in force)."""
    import inrs.occ

    return {"closure_tol": CLOSURE_TOL} if inrs.occ._from_curves_takes_closure_tol() else {}


@dataclass
class OccReport:
    """Part a for one file: ``inrs.occ.face_domain`` of every OCC face against OCC."""

    faces: int
    built: int = 0
    #: Faces refused as open, their pcurves missing by more than the closure tolerance.
    open: List[int] = field(default_factory=list)
    degenerate: List[int] = field(default_factory=list)
    compared: int = 0
    excluded: int = 0
    #: ``(face, surface, (u, v), OCC code, inrs code)``.
    disagreements: list = field(default_factory=list)
    #: Anything else that is wrong, one line each (a refusal the gaps do not explain, ...).
    problems: List[str] = field(default_factory=list)
    closure_tol: float = 1e-9


def check_occ_faces(occ: OccFile) -> OccReport:
    """Builds ``inrs.occ.face_domain`` of every face of ``occ`` and compares it with OCC on
    the face's random points."""
    import inrs.occ

    kwargs = closure_kwargs()
    report = OccReport(faces=len(occ.faces), closure_tol=kwargs.get("closure_tol", 1e-9))
    for k, face in enumerate(occ.faces):
        try:
            loops = inrs.occ.face_loops(face)
        except ValueError as e:
            report.problems.append(f"face {k}: {e}")
            continue
        if not loops or not all(loops):
            report.problems.append(f"face {k}: no loops")
            continue
        gap = max_relative_gap(loops)
        try:
            domain = inrs.occ.face_domain(face, **kwargs)
            domain.classify(np.zeros((1, 2)))  # open loops refuse to classify
        except ValueError as e:
            # Refused only as open, and only when the pcurves do miss by more than the
            # tolerance in force (the relative gap measured here on the same curves).
            if "open boundary" in str(e) and gap > 0.99 * report.closure_tol:
                report.open.append(k)
            else:
                report.problems.append(f"face {k}: {e} (largest gap {gap:.3g} of the diagonal)")
            continue
        report.built += 1
        sample = occ.face_sample(k)
        if sample.skip:
            report.degenerate.append(k)
            continue
        area = filled_area(domain)
        if area is None:
            # Loops lying on each other (a sliver's two sides): no fill to compare.
            report.degenerate.append(k)
            continue
        if not area > 0:
            report.problems.append(f"face {k}: area {area}")
        c = compare(domain, sample.points, sample.codes, sample.diagonal)
        report.compared += c.compared
        report.excluded += c.excluded
        report.disagreements += [(k, surface_name(face), *d) for d in c.disagreements]
    return report


#: The largest distance, relative to the part's size (the diagonal of OCC's box of the whole
#: shape), between a point of our surface inside a face and OCC's surface (the issue's 1e-9).
SURFACE_TOL = 1e-9
#: Points of our surface checked per face (inside the face, by our classifier).
SURFACE_POINTS = 16


def surface_deviation(face, evaluate, domain, box, seed) -> Tuple[float, int]:
    """``(largest distance, points)``: random points of our surface inside the face (drawn in
    ``box``, kept where our ``domain`` says inside), projected on OCC's surface of ``face``
    (located; the part's frame too, as :func:`occ_surfaces`): the largest distance in
    millimetres over those points (``inf`` if OCC cannot project one)."""
    from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
    from OCP.gp import gp_Pnt

    points = random_points(box, seed, 4 * SURFACE_POINTS)
    inside = points[domain.classify(points) == 1][:SURFACE_POINTS]
    if len(inside) == 0:
        return 0.0, 0
    worst = 0.0
    surfaces = occ_surfaces(face)
    for target in evaluate(inside):
        best = math.inf
        for surface in surfaces:
            proj = GeomAPI_ProjectPointOnSurf(gp_Pnt(*map(float, target)), surface)
            if proj.NbPoints() > 0:
                best = min(best, proj.LowerDistance())
        worst = max(worst, best)
    return worst, len(inside)


@dataclass
class ReadersReport:
    """Part b for one file: ``inrs.cad_model`` (the Rust readers and geometry) against OCC."""

    faces: int  # ours
    occ_faces: int
    read: int = 0
    #: ``{reason without numbers: [face, ...]}`` of the faces refused.
    refused: Dict[str, List[int]] = field(default_factory=dict)
    #: STEP faces whose label was checked against OCC's (all of them, when OCC links them).
    labels_checked: int = 0
    #: IGES faces whose DE is the one OCC links the face to (told, not required).
    iges_same_de: int = 0
    #: Faces compared through a :class:`ProjectionMap` (their parameterisation in OCC is not
    #: a scaling of the file's: see uv_scale).
    mapped: int = 0
    #: Points of those faces left out because the map has no image there (a singular point).
    unmapped_points: int = 0
    #: Faces compared through uv_scale whose scale was checked in space.
    scale_checked: int = 0
    #: Faces with neither map (each also a problem): not compared.
    other_parameterisation: int = 0
    degenerate: int = 0
    compared: int = 0
    excluded: int = 0
    #: Faces whose surface was checked against OCC's, the points checked, and the largest
    #: distance relative to the part's size.
    surfaces_checked: int = 0
    surface_points: int = 0
    surface_deviation: float = 0.0
    #: Faces with pcurves fitted to their 3-D edges, and their largest bound (model units).
    fitted: int = 0
    largest_fit_bound: float = 0.0
    #: ``(face, entity, surface, (u, v), OCC code, inrs code)``, (u, v) in the file's units.
    disagreements: list = field(default_factory=list)
    problems: List[str] = field(default_factory=list)


def check_readers(path: pathlib.Path, occ: OccFile) -> ReadersReport:
    """Reads ``path`` with ``inrs.cad_model`` (and its first face again with
    ``Domain.load("path#face:K")``) and compares each face with OCC's: its surface (points of
    ours on OCC's), and its domain on the same random points: OCC's scaled to the file's
    ``(u, v)`` (the scale checked in space), or, where the parameterisations differ otherwise,
    the file's carried to OCC's through space."""
    import inrs

    model = inrs.cad_model(path)
    faces = model.faces
    report = ReadersReport(faces=len(faces), occ_faces=len(occ.faces))
    if len(faces) != len(occ.faces):
        report.problems.append(f"{len(faces)} faces, OCC reads {len(occ.faces)}")
    for k, (ours, face) in enumerate(zip(faces, occ.faces)):
        where = f"face {k} ({ours.entity})"
        if ours.index != k:
            report.problems.append(f"{where}: index {ours.index}")
        if occ.format == "STEP":
            if occ.entities[k] is None:
                report.problems.append(f"{where}: OCC links the face to no ADVANCED_FACE")
            elif ours.entity != occ.entities[k]:
                report.problems.append(f"{where}: OCC's face {k} is {occ.entities[k]}")
            else:
                report.labels_checked += 1
        else:
            report.iges_same_de += ours.entity == occ.entities[k]
        if ours.error is not None:
            if not ours.error or "\n" in ours.error or ours.loops != 0 or ours.bbox is not None:
                report.problems.append(f"{where}: refused as {ours.error!r} with loops {ours.loops}, bbox {ours.bbox}")
            report.refused.setdefault(reason(ours.error), []).append(k)
            continue
        report.read += 1
        domain = ours.domain
        if domain is None:
            report.problems.append(f"{where}: listed as read, but has no domain")
            continue
        if ours.pcurve_deviation is not None:
            report.fitted += 1
            report.largest_fit_bound = max(report.largest_fit_bound, ours.pcurve_deviation)
        if report.read == 1:
            # The `#face:K` path reads the same face (once per file: it reads the file again).
            try:
                loaded = inrs.Domain.load(f"{path}#face:{k}")
            except (OSError, ValueError) as e:
                report.problems.append(f"{where}: listed as read, but Domain.load fails: {e}")
                continue
            if loaded.to_json() != domain.to_json():
                report.problems.append(f"{where}: Domain.load gives another domain than cad_model")
        if not (ours.loops == len(domain.loops) > 0 and ours.curves == domain.summary().curves):
            loaded = (len(domain.loops), domain.summary().curves)
            report.problems.append(f"{where}: {ours.loops} loops, {ours.curves} curves; loaded {loaded}")
        # A zero-area sliver's signed area is rounding (1e-19 either side of 0): compare with
        # an absolute floor at the scale of the face's parameter box.
        x0, y0, x1, y1 = ours.bbox
        signed = domain.summary().signed_area
        if not math.isclose(ours.area, signed, rel_tol=1e-9, abs_tol=1e-12 * ((x1 - x0) ** 2 + (y1 - y0) ** 2)):
            report.problems.append(f"{where}: area {ours.area}, loaded {signed}")
        if ours.surface_kind is None:
            report.problems.append(f"{where}: {ours.surface}: the surface was not read: {ours.surface_error}")
            continue
        mm = occ.mm_per_unit

        def evaluate(uv, ours=ours, mm=mm):
            return mm * ours.points(np.asarray(uv, float))

        seed = (zlib.crc32(occ.path.name.encode()), k)
        deviation, checked = surface_deviation(face, evaluate, domain, ours.bbox, seed)
        report.surfaces_checked += checked > 0
        report.surface_points += checked
        relative = deviation / occ.size if occ.size > 0 else math.inf
        report.surface_deviation = max(report.surface_deviation, relative)
        if not relative <= SURFACE_TOL:
            report.problems.append(f"{where}: {ours.surface}: our surface is {relative:.3g} of the part's size off OCC's")
        scale = uv_scale(face, occ)
        # Faces mapped through space are sampled in the file's (u, v) box, the others in
        # OCC's (shared with check_occ_faces); a thin box in either is degenerate.
        u0, v0, u1, v1 = ours.bbox
        sample = occ.face_sample(k) if scale is not None else None
        skip = sample.skip if sample is not None else box_skip(*occ_box(face)[2:]) or box_skip(u1 - u0, v1 - v0)
        if skip:
            report.degenerate += 1
            continue
        area = filled_area(domain)
        if area is None:
            report.degenerate += 1
            continue
        if not area > 0:
            report.problems.append(f"{where}: area {area}")
        if sample is not None:
            error = scale_map_error(face, evaluate, scale, ours.bbox)
            report.scale_checked += 1
            if not error <= MAP_TOL:
                report.problems.append(f"{where}: OCC's (u, v) is not the file's scaled by {scale}: {error:.3g}")
            points = sample.points / np.array(scale)
            diagonal = math.hypot(sample.size[0] / scale[0], sample.size[1] / scale[1])
            c = compare(domain, points, sample.codes, diagonal)
        else:
            try:
                to_occ = ProjectionMap.of(face, evaluate, ours.bbox)
            except MapError as e:
                report.other_parameterisation += 1
                report.problems.append(f"{where}: {ours.surface}: no map from the file's (u, v) to OCC's: {e}")
                continue
            points = random_points(ours.bbox, seed, POINTS_PER_FACE)
            mapped = to_occ(points)
            report.mapped += 1
            unmapped = int(np.isnan(mapped[:, 0]).sum())
            report.unmapped_points += unmapped
            if unmapped > len(points) // 8:
                report.problems.append(f"{where}: {unmapped} of {len(points)} points have no image in OCC's (u, v)")
            codes = occ_codes(face, mapped, OCC_TOL * math.hypot(*occ_box(face)[2:]))
            c = compare(domain, points, codes, math.hypot(u1 - u0, v1 - v0))
        report.compared += c.compared
        report.excluded += c.excluded
        report.disagreements += [(k, ours.entity, ours.surface, *d) for d in c.disagreements]
    return report

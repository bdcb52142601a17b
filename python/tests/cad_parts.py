"""Test parts built with OpenCASCADE, written to STEP and IGES, and OCC's view of them.

The parts of issue 47 (each a function returning OCC's shape, deterministic, with a closed-form
volume where it is a solid, see :data:`VOLUMES`):

- :func:`sphere`: a full sphere (one face on natural bounds: STEP writes it with a
  ``VERTEX_LOOP``),
- :func:`tilted_torus`: a torus whose axis is (1, 1, 1),
- :func:`cone_minus_sphere`: a frustum with a spherical dimple (a sphere face through the seam
  and the pole),
- :func:`fused_cylinders`: two perpendicular cylinders of different radii fused,
- :func:`filleted_plate`: a plate with rounded corners and a drilled hole,
- :func:`revolved_bspline`: a solid of revolution whose profile is a cubic B-spline,
- :func:`bspline_face_two_holes`: one B-spline face with two round holes (a face, not a solid),
- :func:`box_with_void`: a cube with a spherical void (STEP ``BREP_WITH_VOIDS``),
- :func:`bspline_box_with_hole`: a block with a through hole whose faces are all B-spline
  patches (``BRepBuilderAPI_NurbsConvert``; the hole is rational).

:func:`write_part` / :func:`write_parts` write a part to ``<name>.step``, ``<name>.igs`` (IGES
faces mode, ``write.iges.brep.mode`` 0: trimmed surfaces 144) and ``<name>_brep.igs`` (B-rep
mode 1: 186/514/510/508/504/502), with fixed header dates and author so that the bytes do not
depend on the day or the user.

OCC's view of a file or shape: :func:`read_shape` (``STEPControl_Reader`` /
``IGESControl_Reader``, ``TransferRoots``, ``OneShape``), :func:`faces` (``TopExp_Explorer``
face order: ``#face:K`` of inrs; :func:`face_at` picks one), :func:`topology` (solids, their
shells, each shell's faces as indices into that order, and per face the surface type,
orientation and ``(u, v)`` bounds),
:func:`face_wires` (each wire's edges with OCC's pcurves), :func:`surface_points` (OCC's
surface of face K, located, at ``(u, v)`` arrays), :func:`project_points` (OCC's ``(u, v)`` of
3-D points), :func:`classify_uv` (``BRepClass_FaceClassifier``) and :func:`classify_solid`
(``BRepClass3d_SolidClassifier``).

OCP is imported inside the functions only, so that importing this module never fails; the
functions raise ``ImportError`` without OCP. inrs itself is not used.
"""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

#: The date written into the STEP header's time stamp and the IGES global section (dates of
#: generation and last change), so that a part's files are the same bytes on every run.
FIXED_STEP_TIME_STAMP = "2026-01-01T00:00:00"
FIXED_IGES_DATE = "20260101.000000"
#: The author written into both headers (OCC writes the login name into IGES otherwise).
FIXED_AUTHOR = "inrs cad_parts"

#: Tolerance of the face and solid classifiers (absolute, model units): far below every
#: feature of the parts, far above the 1e-7 of their geometry.
CLASSIFY_TOL = 1e-7


# --- the parts ---------------------------------------------------------------------------------

#: ``sphere``: centre and radius.
SPHERE_CENTER = (1.0, 2.0, 3.0)
SPHERE_RADIUS = 2.0


def sphere():
    """A full sphere of radius 2 about (1, 2, 3), axis z: one face, natural bounds."""
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeSphere
    from OCP.gp import gp_Pnt

    return BRepPrimAPI_MakeSphere(gp_Pnt(*SPHERE_CENTER), SPHERE_RADIUS).Shape()


#: ``tilted_torus``: centre, axis (not unit), major and minor radius.
TORUS_CENTER = (0.5, -1.0, 2.0)
TORUS_AXIS = (1.0, 1.0, 1.0)
TORUS_RADII = (3.0, 1.0)


def tilted_torus():
    """A torus (R = 3, r = 1) about (0.5, -1, 2) on the axis (1, 1, 1): one face."""
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeTorus
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    axes = gp_Ax2(gp_Pnt(*TORUS_CENTER), gp_Dir(*TORUS_AXIS))
    return BRepPrimAPI_MakeTorus(axes, *TORUS_RADII).Shape()


#: ``cone_minus_sphere``: frustum radii at z = 0 and z = h, height h; the sphere's centre
#: (on the axis) and radius.
CONE = (2.0, 0.5, 3.0)
CONE_SPHERE_CENTER = (0.0, 0.0, 3.0)
CONE_SPHERE_RADIUS = 1.2


def cone_minus_sphere():
    """The frustum of radii 2 (z = 0) and 0.5 (z = 3) minus the ball of radius 1.2 about
    (0, 0, 3): the top disc is cut away, and a spherical face holding the sphere's south pole
    remains (3 faces: cone, sphere, bottom plane)."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCone, BRepPrimAPI_MakeSphere
    from OCP.gp import gp_Pnt

    cone = BRepPrimAPI_MakeCone(*CONE).Shape()
    ball = BRepPrimAPI_MakeSphere(gp_Pnt(*CONE_SPHERE_CENTER), CONE_SPHERE_RADIUS).Shape()
    return _boolean(BRepAlgoAPI_Cut(cone, ball), "cone_minus_sphere")


#: ``fused_cylinders``: radius and half length of the cylinder on z, then of the one on x.
CYLINDER_Z = (1.0, 3.0)
CYLINDER_X = (0.8, 3.0)


def fused_cylinders():
    """The cylinder of radius 1 on the z axis (z in [-3, 3]) fused with the one of radius 0.8
    on the x axis (x in [-3, 3]); the axes cross at the origin."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Fuse
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    (rz, hz), (rx, hx) = CYLINDER_Z, CYLINDER_X
    a = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -hz), gp_Dir(0, 0, 1)), rz, 2 * hz).Shape()
    b = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-hx, 0, 0), gp_Dir(1, 0, 0)), rx, 2 * hx).Shape()
    return _boolean(BRepAlgoAPI_Fuse(a, b), "fused_cylinders")


#: ``filleted_plate``: plate size, hole centre (x, y) and radius, corner fillet radius.
PLATE = (10.0, 6.0, 1.0)
PLATE_HOLE = (4.0, 3.0, 1.5)
PLATE_FILLET = 0.8


def filleted_plate():
    """The plate [0, 10] x [0, 6] x [0, 1] with a hole of radius 1.5 at (4, 3), its four
    vertical edges filleted with radius 0.8."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepFilletAPI import BRepFilletAPI_MakeFillet
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopoDS import TopoDS

    lx, ly, lz = PLATE
    hx, hy, hr = PLATE_HOLE
    plate = BRepPrimAPI_MakeBox(lx, ly, lz).Shape()
    drill = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(hx, hy, -1.0), gp_Dir(0, 0, 1)), hr, lz + 2.0).Shape()
    cut = _boolean(BRepAlgoAPI_Cut(plate, drill), "filleted_plate (hole)")
    fillet = BRepFilletAPI_MakeFillet(cut)
    corners = {(x, y) for x in (0.0, lx) for y in (0.0, ly)}
    chosen = []
    for shape in _explore(cut, TopAbs_EDGE):  # each edge once per face it bounds
        edge = TopoDS.Edge(shape)
        curve = BRepAdaptor_Curve(edge)
        p, q = curve.Value(curve.FirstParameter()), curve.Value(curve.LastParameter())
        if (p.X(), p.Y()) == (q.X(), q.Y()) and (p.X(), p.Y()) in corners:
            if _ShapeIndex(chosen).find(edge) < 0:
                chosen.append(edge)
    if len(chosen) != 4:
        raise RuntimeError(f"filleted_plate: {len(chosen)} corner edges, expected 4")
    for edge in chosen:
        fillet.Add(PLATE_FILLET, edge)
    fillet.Build()
    if not fillet.IsDone():
        raise RuntimeError("filleted_plate: the fillet failed")
    return fillet.Shape()


#: ``revolved_bspline``: the profile, a clamped cubic B-spline in the (x, z) half plane
#: (x > 0), revolved a full turn about the z axis; the solid is closed by two discs.
PROFILE_POLES = ((1.0, 0.0), (2.0, 0.5), (1.5, 1.5), (2.5, 2.5), (1.0, 3.0))
PROFILE_KNOTS = (0.0, 0.5, 1.0)
PROFILE_MULTS = (4, 1, 4)
PROFILE_DEGREE = 3


def revolved_bspline():
    """The solid bounded by the cubic B-spline profile :data:`PROFILE_POLES` (x, z) revolved
    about the z axis, and the discs z = 0 (radius 1) and z = 3 (radius 1): 3 faces (plane,
    surface of revolution, plane)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeRevol
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt

    curve = profile_curve()
    (x0, z0), (x1, z1) = PROFILE_POLES[0], PROFILE_POLES[-1]
    p0, p1 = gp_Pnt(x0, 0, z0), gp_Pnt(x1, 0, z1)
    a0, a1 = gp_Pnt(0, 0, z0), gp_Pnt(0, 0, z1)
    wire = BRepBuilderAPI_MakeWire(
        BRepBuilderAPI_MakeEdge(a0, p0).Edge(),
        BRepBuilderAPI_MakeEdge(curve).Edge(),
        BRepBuilderAPI_MakeEdge(p1, a1).Edge(),
        BRepBuilderAPI_MakeEdge(a1, a0).Edge(),
    ).Wire()
    profile = BRepBuilderAPI_MakeFace(wire, True).Face()
    revol = BRepPrimAPI_MakeRevol(profile, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2 * math.pi)
    return _single_solid(revol.Shape(), "revolved_bspline")


def profile_curve():
    """The profile of :func:`revolved_bspline` as an OCC ``Geom_BSplineCurve`` in the plane
    y = 0."""
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt
    from OCP.OCP.collections import Array1_gp_Pnt

    poles = Array1_gp_Pnt(1, len(PROFILE_POLES))
    for i, (x, z) in enumerate(PROFILE_POLES):
        poles.SetValue(i + 1, gp_Pnt(x, 0, z))
    knots = _real_array(PROFILE_KNOTS)
    mults = _int_array(PROFILE_MULTS)
    return Geom_BSplineCurve(poles, knots, mults, PROFILE_DEGREE)


#: ``bspline_face_two_holes``: a bicubic B-spline patch over [0, 8] x [0, 8] (z a smooth bump),
#: and its two holes (x, y, radius).
PATCH_SIZE = 5
PATCH_HOLES = ((2.5, 3.0, 1.0), (5.5, 5.0, 1.3))


def patch_surface():
    """The surface of :func:`bspline_face_two_holes`: bicubic, clamped, 5 x 5 poles at
    (2 i, 2 j, 0.6 sin i cos j), knots (0, 0.5, 1) with multiplicities (4, 1, 4) both ways."""
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt
    from OCP.OCP.collections import Array2_gp_Pnt

    n = PATCH_SIZE
    poles = Array2_gp_Pnt(1, n, 1, n)
    for i in range(n):
        for j in range(n):
            poles.SetValue(i + 1, j + 1, gp_Pnt(2.0 * i, 2.0 * j, 0.6 * math.sin(i) * math.cos(j)))
    knots, mults = _real_array((0.0, 0.5, 1.0)), _int_array((4, 1, 4))
    return Geom_BSplineSurface(poles, knots, knots, mults, mults, 3, 3)


def bspline_face_two_holes():
    """One face on :func:`patch_surface` with two round holes (cut by vertical cylinders at
    :data:`PATCH_HOLES`): 3 wires."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    shape = BRepBuilderAPI_MakeFace(patch_surface(), 1e-7).Face()
    for x, y, r in PATCH_HOLES:
        drill = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, -5.0), gp_Dir(0, 0, 1)), r, 10.0).Shape()
        shape = _boolean(BRepAlgoAPI_Cut(shape, drill), "bspline_face_two_holes")
    found = faces(shape)
    if len(found) != 1:
        raise RuntimeError(f"bspline_face_two_holes: {len(found)} faces, expected 1")
    return found[0]


#: ``box_with_void``: the cube's corner and edge, the void's centre and radius.
VOID_BOX = ((-2.0, -2.0, -2.0), 4.0)
VOID_CENTER = (0.0, 0.0, 0.0)
VOID_RADIUS = 1.0


def box_with_void():
    """The cube [-2, 2]^3 with a spherical void of radius 1 about the origin: one solid of two
    closed shells (the cube's 6 faces, then the sphere's face, reversed: its normals point into
    the void). Built as a solid of two shells with ``BRep_Builder`` (not a boolean), so that the
    structure is explicit; STEP writes ``BREP_WITH_VOIDS`` with an ``ORIENTED_CLOSED_SHELL``
    (.F.)."""
    from OCP.BRep import BRep_Builder
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeSphere
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS, TopoDS_Solid

    corner, edge = VOID_BOX
    box = BRepPrimAPI_MakeBox(gp_Pnt(*corner), edge, edge, edge).Solid()
    ball = BRepPrimAPI_MakeSphere(gp_Pnt(*VOID_CENTER), VOID_RADIUS).Solid()
    outer = TopoDS.Shell(TopExp_Explorer(box, TopAbs_SHELL).Current())
    inner = TopoDS.Shell(TopExp_Explorer(ball, TopAbs_SHELL).Current())
    solid = TopoDS_Solid()
    builder = BRep_Builder()
    builder.MakeSolid(solid)
    builder.Add(solid, outer)
    builder.Add(solid, inner.Reversed())
    return solid


#: ``bspline_box_with_hole``: the block's size and the hole's centre (x, y) and radius.
HOLED_BOX = (4.0, 4.0, 2.0)
HOLED_BOX_HOLE = (2.0, 2.0, 1.0)


def bspline_box_with_hole():
    """The block [0, 4] x [0, 4] x [0, 2] with a vertical through hole of radius 1 at (2, 2),
    every face converted to a B-spline surface (``BRepBuilderAPI_NurbsConvert``): planes become
    bilinear patches, the hole a rational patch (circles are exact rational quadratics)."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepBuilderAPI import BRepBuilderAPI_NurbsConvert
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    lx, ly, lz = HOLED_BOX
    hx, hy, hr = HOLED_BOX_HOLE
    block = BRepPrimAPI_MakeBox(lx, ly, lz).Shape()
    drill = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(hx, hy, -1.0), gp_Dir(0, 0, 1)), hr, lz + 2.0).Shape()
    cut = _boolean(BRepAlgoAPI_Cut(block, drill), "bspline_box_with_hole")
    convert = BRepBuilderAPI_NurbsConvert(cut, True)
    return _single_solid(convert.Shape(), "bspline_box_with_hole")


#: The parts by name, in a fixed order.
PARTS: Dict[str, Callable[[], object]] = {
    "sphere": sphere,
    "torus": tilted_torus,
    "cone_minus_sphere": cone_minus_sphere,
    "fused_cylinders": fused_cylinders,
    "filleted_plate": filleted_plate,
    "revolved_bspline": revolved_bspline,
    "bspline_two_holes": bspline_face_two_holes,
    "box_void": box_with_void,
    "bspline_box_hole": bspline_box_with_hole,
}


# --- closed forms --------------------------------------------------------------------------------


def _gauss(n: int) -> Tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


def _cone_minus_sphere_volume() -> float:
    r0, r1, h = CONE
    rs = CONE_SPHERE_RADIUS
    # Depth t below the top (z = h - t): the frustum's radius is r1 + (r0 - r1) t / h, the
    # ball's squared radius rs^2 - t^2 (centre on the top disc). Near the top the ball covers
    # the frustum's whole section, below the crossing depth t* the ball's section lies inside.
    k = (r0 - r1) / h
    # (r1 + k t)^2 = rs^2 - t^2  <=>  (1 + k^2) t^2 + 2 r1 k t + r1^2 - rs^2 = 0
    a, b, c = 1.0 + k * k, 2.0 * r1 * k, r1 * r1 - rs * rs
    t = (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)
    removed_top = math.pi * ((r1 + k * t) ** 3 - r1**3) / (3 * k)
    removed_cap = math.pi * (rs * rs * (rs - t) - (rs**3 - t**3) / 3)
    frustum = math.pi * h * (r0 * r0 + r0 * r1 + r1 * r1) / 3
    return frustum - removed_top - removed_cap


def _fused_cylinders_volume() -> float:
    (a, ha), (b, hb) = CYLINDER_Z, CYLINDER_X
    # Intersection of perpendicular cylinders radii a >= b (axes crossing): 8 int_0^b
    # sqrt(b^2 - x^2) sqrt(a^2 - x^2) dx; with x = b sin s the integrand is smooth (analytic)
    # on [0, pi/2], and Gauss-Legendre with 40 nodes is exact to rounding.
    s, w = _gauss(40)
    s = s * math.pi / 2
    common = 8 * (math.pi / 2) * float(np.sum(w * b * b * np.cos(s) ** 2 * np.sqrt(a * a - (b * np.sin(s)) ** 2)))
    return math.pi * a * a * 2 * ha + math.pi * b * b * 2 * hb - common


def _revolved_bspline_volume() -> float:
    # Pappus: V = pi int x(t)^2 z'(t) dt over the profile, from z = 0 up to z = 3; x^2 z' is a
    # polynomial of degree 8 on each knot span, integrated exactly by 5 Gauss nodes.
    nodes, weights = _gauss(5)
    total = 0.0
    for lo, hi in zip(PROFILE_KNOTS[:-1], PROFILE_KNOTS[1:]):
        t = lo + (hi - lo) * nodes
        (x, _z), (_dx, dz) = _bspline_point_and_derivative(t)
        total += (hi - lo) * float(np.sum(weights * x * x * dz))
    return math.pi * total


def _bspline_point_and_derivative(t: np.ndarray):
    """The profile's (x, z) and (dx/dt, dz/dt) at ``t``, by de Boor's recursion written here
    (independent of OCC's evaluation)."""
    p = PROFILE_DEGREE
    knots = np.repeat(PROFILE_KNOTS, PROFILE_MULTS)
    poles = np.asarray(PROFILE_POLES, float)

    def evaluate(ts, ctrl, deg, kn):
        out = []
        for tt in ts:
            span = int(np.searchsorted(kn, tt, side="right") - 1)
            span = min(max(span, deg), len(kn) - deg - 2)
            d = [ctrl[j + span - deg].copy() for j in range(deg + 1)]
            for r in range(1, deg + 1):
                for j in range(deg, r - 1, -1):
                    i = j + span - deg
                    alpha = (tt - kn[i]) / (kn[i + deg + 1 - r] - kn[i])
                    d[j] = (1 - alpha) * d[j - 1] + alpha * d[j]
            out.append(d[deg])
        return np.array(out)

    points = evaluate(t, poles, p, knots)
    # Derivative: a degree p - 1 B-spline with poles p (P_{i+1} - P_i) / (t_{i+p+1} - t_{i+1}).
    dpoles = np.array(
        [p * (poles[i + 1] - poles[i]) / (knots[i + p + 1] - knots[i + 1]) for i in range(len(poles) - 1)]
    )
    derivative = evaluate(t, dpoles, p - 1, knots[1:-1])
    return (points[:, 0], points[:, 1]), (derivative[:, 0], derivative[:, 1])


#: The volume of each solid part in closed form (or exact quadrature of a closed-form
#: integrand); None for the face.
VOLUMES: Dict[str, Optional[float]] = {
    "sphere": 4.0 / 3.0 * math.pi * SPHERE_RADIUS**3,
    "torus": 2.0 * math.pi**2 * TORUS_RADII[0] * TORUS_RADII[1] ** 2,
    "cone_minus_sphere": _cone_minus_sphere_volume(),
    "fused_cylinders": _fused_cylinders_volume(),
    "filleted_plate": (
        PLATE[0] * PLATE[1] - 4 * (1 - math.pi / 4) * PLATE_FILLET**2 - math.pi * PLATE_HOLE[2] ** 2
    )
    * PLATE[2],
    "revolved_bspline": _revolved_bspline_volume(),
    "bspline_two_holes": None,
    "box_void": VOID_BOX[1] ** 3 - 4.0 / 3.0 * math.pi * VOID_RADIUS**3,
    "bspline_box_hole": HOLED_BOX[0] * HOLED_BOX[1] * HOLED_BOX[2] - math.pi * HOLED_BOX_HOLE[2] ** 2 * HOLED_BOX[2],
}


# --- writing -------------------------------------------------------------------------------------


@dataclass
class Part:
    """A part written to files."""

    name: str
    shape: object  # TopoDS_Shape
    step: pathlib.Path
    iges: pathlib.Path  # faces mode (write.iges.brep.mode 0)
    iges_brep: pathlib.Path  # B-rep mode (write.iges.brep.mode 1)

    def files(self) -> Dict[str, pathlib.Path]:
        """``{"step": ..., "iges": ..., "iges_brep": ...}``."""
        return {"step": self.step, "iges": self.iges, "iges_brep": self.iges_brep}


def write_step(shape, path: pathlib.Path) -> pathlib.Path:
    """Writes ``shape`` to STEP (AP214, OCC's default schema, ``STEPControl_AsIs``, millimetres)
    with a fixed header time stamp and author."""
    from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
    from OCP.TCollection import TCollection_HAsciiString

    writer = STEPControl_Writer()  # (defines the write.step parameters)
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    if writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone:
        raise RuntimeError(f"STEP transfer failed for {path}")
    # OCC names the product after itself with a per-process counter: name it after the file.
    model = writer.Model()
    for i in range(1, model.NbEntities() + 1):
        entity = model.Value(i)
        if entity.DynamicType().Name() == "StepBasic_Product":
            entity.SetId(TCollection_HAsciiString(pathlib.Path(path).stem))
            entity.SetName(TCollection_HAsciiString(pathlib.Path(path).stem))
    header = APIHeaderSection_MakeHeader(model)
    header.SetTimeStamp(TCollection_HAsciiString(FIXED_STEP_TIME_STAMP))
    header.SetAuthorValue(1, TCollection_HAsciiString(FIXED_AUTHOR))
    if writer.Write(str(path)) != IFSelect_RetDone:
        raise OSError(f"cannot write {path}")
    return path


def write_iges(shape, path: pathlib.Path, brep: bool) -> pathlib.Path:
    """Writes ``shape`` to IGES 5.3 in millimetres: faces mode (``brep`` False:
    ``write.iges.brep.mode`` 0, trimmed surfaces 144 grouped by 402) or B-rep mode (True: 1,
    entities 186/514/510/508/504/502), with fixed dates and author."""
    from OCP.IGESControl import IGESControl_Writer
    from OCP.Interface import Interface_Static
    from OCP.TCollection import TCollection_HAsciiString

    mode = 1 if brep else 0
    Interface_Static.SetIVal_s("write.iges.brep.mode", mode)
    writer = IGESControl_Writer("MM", mode)
    if not writer.AddShape(shape):
        raise RuntimeError(f"IGES transfer failed for {path}")
    writer.ComputeModel()
    model = writer.Model()
    section = model.GlobalSection()
    section.SetDate(TCollection_HAsciiString(FIXED_IGES_DATE))
    section.SetLastChangeDate(TCollection_HAsciiString(FIXED_IGES_DATE))
    section.SetAuthorName(TCollection_HAsciiString(FIXED_AUTHOR))
    section.SetFileName(TCollection_HAsciiString(path.name))
    model.SetGlobalSection(section)
    if not writer.Write(str(path)):
        raise OSError(f"cannot write {path}")
    return path


def write_part(name: str, directory) -> Part:
    """Builds part ``name`` (a key of :data:`PARTS`) and writes ``name.step``, ``name.igs``
    (faces mode) and ``name_brep.igs`` (B-rep mode) into ``directory`` (created if needed)."""
    directory = pathlib.Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    shape = PARTS[name]()
    step = write_step(shape, directory / f"{name}.step")
    iges = write_iges(shape, directory / f"{name}.igs", brep=False)
    iges_brep = write_iges(shape, directory / f"{name}_brep.igs", brep=True)
    return Part(name, shape, step, iges, iges_brep)


def write_parts(directory, names: Optional[Sequence[str]] = None) -> Dict[str, Part]:
    """:func:`write_part` for each of ``names`` (default: all of :data:`PARTS`)."""
    return {name: write_part(name, directory) for name in (names or list(PARTS))}


# --- reading and OCC's view ------------------------------------------------------------------------


def quiet():
    """Silences OpenCASCADE's messages below failures (its readers and writers print)."""
    from OCP.Message import Message, Message_Gravity

    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)


def read_shape(path) -> object:
    """The shape OCC reads from ``path`` (``.stp``/``.step`` or ``.igs``/``.iges``):
    ``TransferRoots`` then ``OneShape``."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.IGESControl import IGESControl_Reader
    from OCP.STEPControl import STEPControl_Reader

    path = pathlib.Path(path)
    reader = STEPControl_Reader() if path.suffix.lower() in (".stp", ".step") else IGESControl_Reader()
    if reader.ReadFile(str(path)) != IFSelect_RetDone:
        raise OSError(f"OpenCASCADE cannot read {path}")
    reader.TransferRoots()
    return reader.OneShape()


def _explore(shape, kind) -> list:
    from OCP.TopExp import TopExp_Explorer

    out = []
    explorer = TopExp_Explorer(shape, kind)
    while explorer.More():
        out.append(explorer.Current())
        explorer.Next()
    return out


def faces(shape) -> list:
    """The faces of ``shape`` (``TopoDS_Face``) in ``TopExp_Explorer(shape, TopAbs_FACE)`` order:
    face K here is inrs's ``#face:K``."""
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopoDS import TopoDS

    return [TopoDS.Face(f) for f in _explore(shape, TopAbs_FACE)]


def face_at(shape_or_path, k: int):
    """Face ``k`` (explorer order, inrs's ``#face:K``) of a shape or of a file read by
    :func:`read_shape`."""
    shape = read_shape(shape_or_path) if isinstance(shape_or_path, (str, pathlib.Path)) else shape_or_path
    found = faces(shape)
    if not 0 <= k < len(found):
        raise IndexError(f"face {k} of {len(found)}")
    return found[k]


class _ShapeIndex:
    """Position of a sub-shape (``IsSame``: same TShape and location, any orientation) in a
    list, first occurrence."""

    def __init__(self, shapes: list):
        self.buckets: Dict[int, List[Tuple[object, int]]] = {}
        for i, s in enumerate(shapes):
            self.buckets.setdefault(hash(s), []).append((s, i))

    def find(self, shape) -> int:
        for s, i in self.buckets.get(hash(shape), []):
            if s.IsSame(shape):
                return i
        return -1


def _name(enum_value, prefix: str) -> str:
    name = enum_value.name
    return name[len(prefix) :] if name.startswith(prefix) else name


@dataclass
class FaceInfo:
    """One face as OCC sees it."""

    index: int  # in face-explorer order
    surface: str  # GeomAbs surface type without the prefix: Plane, Cylinder, Cone, Sphere, Torus,
    #               BezierSurface, BSplineSurface, SurfaceOfRevolution, SurfaceOfExtrusion, ...
    orientation: str  # FORWARD or REVERSED (the face in the shape, as explored)
    uv_bounds: Tuple[float, float, float, float]  # BRepTools.UVBounds: (u0, u1, v0, v1)
    wires: int
    natural_restriction: bool  # BRep_Tool.NaturalRestriction


@dataclass
class ShellInfo:
    """A shell: its faces as indices into the face-explorer order of the whole shape."""

    faces: List[int]
    orientation: str
    closed: bool  # BRep_Tool.IsClosed: every edge shared by two faces of the shell


@dataclass
class SolidInfo:
    """A solid: its shells in explorer order."""

    shells: List[ShellInfo]


@dataclass
class Topology:
    """Solids (``TopAbs_SOLID`` explorer order), shells outside every solid, faces outside
    every shell, and every face."""

    solids: List[SolidInfo]
    free_shells: List[ShellInfo]
    free_faces: List[int]
    faces: List[FaceInfo] = field(default_factory=list)

    def summary(self) -> str:
        """One line: ``2 solids [shells (faces, closed)] ...``."""
        def shell(s):
            return f"{len(s.faces)}{'c' if s.closed else 'o'}{'' if s.orientation == 'FORWARD' else '-'}"

        solids = " ".join("[" + " ".join(shell(s) for s in so.shells) + "]" for so in self.solids)
        return (
            f"{len(self.faces)} faces; {len(self.solids)} solids {solids}; {len(self.free_shells)} free shells "
            f"{[shell(s) for s in self.free_shells]}; {len(self.free_faces)} free faces"
        )


def face_info(face, index: int = -1) -> FaceInfo:
    """Surface type, orientation, UV bounds, wire count and natural restriction of ``face``."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepTools import BRepTools
    from OCP.TopAbs import TopAbs_WIRE

    kind = _name(BRepAdaptor_Surface(face, True).GetType(), "GeomAbs_")
    return FaceInfo(
        index,
        kind,
        _name(face.Orientation(), "TopAbs_"),
        tuple(BRepTools.UVBounds_s(face)),
        len(_explore(face, TopAbs_WIRE)),
        bool(BRep_Tool.NaturalRestriction_s(face)),
    )


def topology(shape_or_path) -> Topology:
    """OCC's solids, shells and faces of a shape or of a file read by :func:`read_shape`."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID
    from OCP.TopoDS import TopoDS

    shape = shape_or_path
    if isinstance(shape_or_path, (str, pathlib.Path)):
        shape = read_shape(shape_or_path)
    all_faces = faces(shape)
    index = _ShapeIndex(all_faces)

    def shell_info(sh) -> ShellInfo:
        return ShellInfo(
            [index.find(f) for f in _explore(sh, TopAbs_FACE)],
            _name(sh.Orientation(), "TopAbs_"),
            bool(BRep_Tool.IsClosed_s(TopoDS.Shell(sh))),
        )

    solids = [SolidInfo([shell_info(sh) for sh in _explore(so, TopAbs_SHELL)]) for so in _explore(shape, TopAbs_SOLID)]
    in_solids = _ShapeIndex([sh for so in _explore(shape, TopAbs_SOLID) for sh in _explore(so, TopAbs_SHELL)])
    free_shells = [shell_info(sh) for sh in _explore(shape, TopAbs_SHELL) if in_solids.find(sh) < 0]
    in_shells = {i for so in solids for sh in so.shells for i in sh.faces} | {i for sh in free_shells for i in sh.faces}
    free = [i for i in range(len(all_faces)) if i not in in_shells]
    return Topology(solids, free_shells, free, [face_info(f, i) for i, f in enumerate(all_faces)])


@dataclass
class EdgeUse:
    """One edge of a wire as the face uses it, with OCC's pcurve on that face."""

    orientation: str  # FORWARD / REVERSED in the wire
    degenerate: bool  # BRep_Tool.Degenerated (a pole: no 3-D curve)
    seam: bool  # BRep_Tool.IsClosed(edge, face): the edge has two pcurves on this face
    curve3d: Optional[str]  # GeomAbs curve type of the 3-D curve, None if there is none
    pcurve: str  # GeomAbs curve type of the pcurve (Line, Circle, BSplineCurve, ...)
    degree: Optional[int]  # of a B-spline or Bezier pcurve
    range: Tuple[float, float]  # the pcurve's parameter range
    #: Points of the pcurve along the edge's use (reversed edges from last to first), (n, 2).
    uv: np.ndarray


def face_wires(face, samples: int = 9) -> List[List[EdgeUse]]:
    """Each wire of ``face`` (outer wire first, as ``BRepTools.OuterWire``, then the others in
    explorer order), its edges in order (``BRepTools_WireExplorer``) with OCC's pcurves."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d
    from OCP.BRepTools import BRepTools, BRepTools_WireExplorer
    from OCP.TopAbs import TopAbs_REVERSED, TopAbs_WIRE
    from OCP.TopoDS import TopoDS

    outer = BRepTools.OuterWire_s(face)
    wires = [TopoDS.Wire(w) for w in _explore(face, TopAbs_WIRE)]
    wires.sort(key=lambda w: 0 if (not outer.IsNull() and w.IsSame(outer)) else 1)
    out = []
    for wire in wires:
        uses = []
        explorer = BRepTools_WireExplorer(wire, face)
        while explorer.More():
            edge = explorer.Current()
            degenerate = bool(BRep_Tool.Degenerated_s(edge))
            curve2d = BRepAdaptor_Curve2d(edge, face)
            kind = curve2d.GetType()
            kind_name = _name(kind, "GeomAbs_")
            degree = curve2d.Degree() if kind_name in ("BSplineCurve", "BezierCurve") else None
            t0, t1 = curve2d.FirstParameter(), curve2d.LastParameter()
            ts = np.linspace(t0, t1, samples)
            if edge.Orientation() == TopAbs_REVERSED:
                ts = ts[::-1]
            uv = np.array([[curve2d.Value(t).X(), curve2d.Value(t).Y()] for t in ts])
            curve3d = None if degenerate else _name(BRepAdaptor_Curve(edge).GetType(), "GeomAbs_")
            uses.append(
                EdgeUse(
                    _name(edge.Orientation(), "TopAbs_"),
                    degenerate,
                    bool(BRep_Tool.IsClosed_s(edge, face)),
                    curve3d,
                    kind_name,
                    degree,
                    (t0, t1),
                    uv,
                )
            )
            explorer.Next()
        out.append(uses)
    return out


def face_surface(face):
    """OCC's surface of ``face`` with the face's location applied (``BRep_Tool.Surface``:
    a ``Geom_Surface`` in model coordinates)."""
    from OCP.BRep import BRep_Tool

    return BRep_Tool.Surface_s(face)


def surface_points(face, u, v) -> np.ndarray:
    """OCC's surface of ``face`` (located) at the parameters ``u``, ``v`` (arrays of one shape,
    OCC's ``(u, v)``): points of shape ``u.shape + (3,)``."""
    surface = face_surface(face)
    u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
    out = np.empty(u.shape + (3,))
    for idx in np.ndindex(u.shape):
        p = surface.Value(float(u[idx]), float(v[idx]))
        out[idx] = (p.X(), p.Y(), p.Z())
    return out


def project_points(face, points, tol: float = 1e-9) -> Tuple[np.ndarray, np.ndarray]:
    """OCC's ``(u, v)`` on the surface of ``face`` (located) of 3-D ``points`` (n, 3), by
    ``ShapeAnalysis_Surface.ValueOfUV`` (the closest point; robust at poles and seams), and the
    distance from each point to its image. A periodic parameter is shifted by whole periods
    to the copy nearest the middle of the face's ``UVBounds``, so that points of the face get
    the parameters of OCC's pcurves. Returns ``(uv (n, 2), distance (n,))``."""
    from OCP.BRepTools import BRepTools
    from OCP.gp import gp_Pnt
    from OCP.ShapeAnalysis import ShapeAnalysis_Surface

    surface = face_surface(face)
    analysis = ShapeAnalysis_Surface(surface)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    mid = ((u0 + u1) / 2, (v0 + v1) / 2)
    periods = [
        surface.UPeriod() if surface.IsUPeriodic() else None,
        surface.VPeriod() if surface.IsVPeriodic() else None,
    ]
    points = np.asarray(points, float).reshape(-1, 3)
    uv = np.empty((len(points), 2))
    distance = np.empty(len(points))
    for i, (x, y, z) in enumerate(points):
        p = analysis.ValueOfUV(gp_Pnt(x, y, z), tol)
        w = [p.X(), p.Y()]
        for k in range(2):
            if periods[k]:
                w[k] += periods[k] * round((mid[k] - w[k]) / periods[k])
        uv[i] = w
        q = surface.Value(w[0], w[1])
        distance[i] = math.dist((x, y, z), (q.X(), q.Y(), q.Z()))
    return uv, distance


#: Codes of the classifiers (as in cad_files.occ_codes).
OUT, IN, ON = 0, 1, 2


def _code(state) -> int:
    from OCP.TopAbs import TopAbs_IN, TopAbs_OUT

    return IN if state == TopAbs_IN else OUT if state == TopAbs_OUT else ON


def classify_uv(face, uv, tol: float = CLASSIFY_TOL) -> np.ndarray:
    """``BRepClass_FaceClassifier`` of the ``(u, v)`` points ``uv`` (n, 2) on ``face``, in OCC's
    parameters: int8 codes :data:`OUT`, :data:`IN`, :data:`ON`."""
    from OCP.BRepClass import BRepClass_FaceClassifier
    from OCP.gp import gp_Pnt2d

    uv = np.asarray(uv, float).reshape(-1, 2)
    return np.array(
        [_code(BRepClass_FaceClassifier(face, gp_Pnt2d(float(u), float(v)), tol).State()) for u, v in uv], np.int8
    )


def classify_solid(solid, points, tol: float = CLASSIFY_TOL) -> np.ndarray:
    """``BRepClass3d_SolidClassifier`` of the 3-D ``points`` (n, 3) against ``solid`` (a
    solid, or a shape holding solids): int8 codes :data:`OUT`, :data:`IN`, :data:`ON`. The
    classifier is built once and ``Perform`` called per point."""
    from OCP.BRepClass3d import BRepClass3d_SolidClassifier
    from OCP.gp import gp_Pnt

    classifier = BRepClass3d_SolidClassifier(solid)
    points = np.asarray(points, float).reshape(-1, 3)
    out = np.empty(len(points), np.int8)
    for i, (x, y, z) in enumerate(points):
        classifier.Perform(gp_Pnt(x, y, z), tol)
        out[i] = _code(classifier.State())
    return out


#: Relative accuracy asked of ``BRepGProp.VolumeProperties``: its default Gauss rule is off by
#: 1e-4 on the surface of revolution and 4e-2 on the B-spline block (measured); with 1e-12 every
#: part is within 5e-9 of its closed form.
VOLUME_EPS = 1e-12


def volume(shape, eps: float = VOLUME_EPS) -> float:
    """OCC's volume of ``shape`` (``BRepGProp.VolumeProperties`` with the adaptive rule to the
    relative accuracy ``eps``)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, eps, True)
    return props.Mass()


def area(shape) -> float:
    """OCC's surface area of ``shape`` (``BRepGProp.SurfaceProperties``)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, props)
    return props.Mass()


# --- small helpers ---------------------------------------------------------------------------------


def _boolean(operation, what: str):
    operation.Build()
    if not operation.IsDone():
        raise RuntimeError(f"{what}: the boolean operation failed")
    return operation.Shape()


def _single_solid(shape, what: str):
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopoDS import TopoDS

    solids = _explore(shape, TopAbs_SOLID)
    if len(solids) != 1:
        raise RuntimeError(f"{what}: {len(solids)} solids, expected 1")
    return TopoDS.Solid(solids[0])


def _real_array(values):
    from OCP.OCP.collections import Array1_double

    out = Array1_double(1, len(values))
    for i, x in enumerate(values):
        out.SetValue(i + 1, float(x))
    return out


def _int_array(values):
    from OCP.OCP.collections import Array1_int

    out = Array1_int(1, len(values))
    for i, x in enumerate(values):
        out.SetValue(i + 1, int(x))
    return out

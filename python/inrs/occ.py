"""Domains from OpenCASCADE faces: the trimming loops of a ``TopoDS_Face`` in its surface's
parameter space ``(u, v)``, converted exactly, as an :class:`inrs.Domain`.

For users who already hold OpenCASCADE objects through the Python binding OCP (PyPI package
``cadquery-ocp-novtk``, or ``cadquery-ocp``). OCP is imported when this module is imported,
never by ``import inrs``; without it the import fails with an ``ImportError`` that names the
package to install. (The examples are OCP 8's; OCP 7 spells the casts ``TopoDS.Face_s``.)

>>> import inrs.occ
>>> from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
>>> from OCP.TopExp import TopExp_Explorer
>>> from OCP.TopAbs import TopAbs_FACE
>>> from OCP.TopoDS import TopoDS
>>> box = BRepPrimAPI_MakeBox(2.0, 3.0, 4.0).Shape()
>>> face = TopoDS.Face(TopExp_Explorer(box, TopAbs_FACE).Current())
>>> round(inrs.occ.face_domain(face).area, 12)
12.0
"""

from __future__ import annotations

import inspect
import warnings
from typing import List, Optional, Tuple

import numpy as np

import inrs

try:
    from OCP.BRepAdaptor import BRepAdaptor_Curve2d
    from OCP.BRepTools import BRepTools, BRepTools_WireExplorer
    from OCP.Geom2d import Geom2d_OffsetCurve, Geom2d_TrimmedCurve
    from OCP.Geom2dConvert import Geom2dConvert
    from OCP.TopAbs import TopAbs_EXTERNAL, TopAbs_FORWARD, TopAbs_INTERNAL, TopAbs_REVERSED, TopAbs_WIRE
    from OCP.TopoDS import TopoDS, TopoDS_Iterator
except ImportError as e:  # pragma: no cover - depends on the environment
    raise ImportError(
        "inrs.occ needs OpenCASCADE's Python binding OCP: pip install cadquery-ocp-novtk "
        f"(or cadquery-ocp) ({e})"
    ) from e

__all__ = ["face_domain", "face_loops", "CurveArrays"]

#: One curve as :meth:`inrs.Domain.from_curves` takes it: ``(degree, knots (K,), control points
#: (M, 2), weights (M,) or None)``, with ``K = M + degree + 1`` (clamped, non-periodic).
CurveArrays = Tuple[int, np.ndarray, np.ndarray, Optional[np.ndarray]]

# Casts of a TopoDS_Shape to a face or wire: static methods `TopoDS.Face_s` in OCP 7, functions
# of the namespace `TopoDS` in OCP 8.
_as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
_as_wire = getattr(TopoDS, "Wire_s", None) or TopoDS.Wire


def face_domain(face, closure_tol: Optional[float] = None, *, name: Optional[str] = None) -> "inrs.Domain":
    """The region of an OpenCASCADE face in its surface's parameter space ``(u, v)``, as an
    :class:`inrs.Domain` bounded by the face's pcurves, converted exactly (see
    :func:`face_loops`: lines stay degree 1, circles and other conics are rational quadratics,
    B-splines keep their degree, knots and weights).

    ``face`` is an OCP ``TopoDS_Face`` (a ``TopoDS_Shape`` of type face is cast). Its loops are
    those of the face taken ``FORWARD``, so the outer loop runs counter-clockwise and the holes
    clockwise whenever the file is consistent, and the area is positive; a face used
    ``REVERSED`` in its shell covers the same ``(u, v)`` region (only its normal flips).

    ``closure_tol`` is the closure tolerance of the loops, relative to the diagonal of the
    domain's bounding box (the largest gap between one pcurve's end and the next one's start
    that still counts as meeting; default ``1e-9``), handed on to
    ``inrs.Domain.from_curves(..., closure_tol=)``. OpenCASCADE's pcurves may miss each other
    by the edges' tolerance: ``1e-5`` closes every face of the test files but two. Versions of
    :mod:`inrs` whose ``from_curves`` has no such argument use their default, and a
    ``closure_tol`` given then is ignored with a ``UserWarning``. ``name`` names the domain.

    Raises ``ValueError`` naming the wire and edge (counted from 0, outer wire first) when an
    edge has no pcurve on the face or a pcurve with no exact B-spline form (offset curves), and
    when the face has no boundary.

    >>> import inrs.occ
    >>> from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    >>> from OCP.TopExp import TopExp_Explorer
    >>> from OCP.TopAbs import TopAbs_FACE
    >>> from OCP.TopoDS import TopoDS
    >>> cyl = BRepPrimAPI_MakeCylinder(1.0, 5.0).Shape()
    >>> side = TopoDS.Face(TopExp_Explorer(cyl, TopAbs_FACE).Current())
    >>> d = inrs.occ.face_domain(side)
    >>> round(d.area, 12)  # u in [0, 2 pi], v in [0, 5]
    31.415926535898
    >>> d.classify([[3.0, 2.5], [3.0, 6.0]]).tolist()
    [1, 0]
    """
    curves = [c for loop in face_loops(face) for c in loop]
    if not curves:
        raise ValueError("the face has no boundary edges with pcurves")
    kwargs = {}
    if closure_tol is not None:
        if _from_curves_takes_closure_tol():
            kwargs["closure_tol"] = float(closure_tol)
        else:
            warnings.warn(
                "this version of inrs.Domain.from_curves has no closure_tol: the default "
                "closure tolerance is used",
                UserWarning,
                stacklevel=2,
            )
    return inrs.Domain.from_curves(curves, name=name, **kwargs)


def face_loops(face) -> List[List[CurveArrays]]:
    """The trimming loops of ``face`` in ``(u, v)``: the outer wire first
    (``BRepTools.OuterWire``), then the other wires in the face's order; in each, the edges in
    connection order (``BRepTools_WireExplorer``), each edge's pcurve on the face trimmed to
    the edge's range and run backwards when the edge is ``REVERSED`` in the wire, as the arrays
    of :meth:`inrs.Domain.from_curves` (flat clamped knot vectors, weights ``None`` for
    polynomial curves).

    The face is taken ``FORWARD`` (see :func:`face_domain`). ``INTERNAL`` and ``EXTERNAL``
    edges are left out: they bound no region (material on both sides, or on neither).
    Degenerated edges (the pole of a sphere, the apex of a cone) are kept: in ``(u, v)`` they
    are segments of the loop.

    The conversion is exact: ``Geom2dConvert.CurveToBSplineCurve`` of the trimmed pcurve,
    which keeps B-splines and Bezier curves as they are (segmented to the range), gives lines
    degree 1 and conics rational quadratic pieces; offset pcurves, which it would approximate,
    raise ``ValueError`` instead. A periodic result is made non-periodic (the same curve).
    """
    face = _as_face(_as_face(face).Oriented(TopAbs_FORWARD))
    outer = BRepTools.OuterWire_s(face)
    wires = [] if outer.IsNull() else [outer]
    it = TopoDS_Iterator(face)
    while it.More():
        shape = it.Value()
        if shape.ShapeType() == TopAbs_WIRE and (outer.IsNull() or not shape.IsSame(outer)):
            wires.append(_as_wire(shape))
        it.Next()
    return [_wire_loop(face, w, i) for i, w in enumerate(wires)]


def _wire_loop(face, wire, index: int) -> List[CurveArrays]:
    """The curves of wire ``index`` of ``face`` in loop order (see :func:`face_loops`)."""
    expected = 0
    it = TopoDS_Iterator(wire)
    while it.More():
        if it.Value().Orientation() not in (TopAbs_INTERNAL, TopAbs_EXTERNAL):
            expected += 1
        it.Next()
    loop = []
    visited = 0
    explorer = BRepTools_WireExplorer(wire, face)
    # The explorer visits each edge occurrence at most once, so `expected + 1` bounds the loop
    # even on a corrupt wire.
    while explorer.More() and visited <= expected:
        edge = explorer.Current()
        # The edge's own orientation in the wire (composed with the wire's and the face's).
        # `explorer.Orientation()` is another thing: the orientation of the explorer's current
        # vertex in the edge, ambiguous on a closed edge (a full circle).
        orientation = edge.Orientation()
        if orientation not in (TopAbs_INTERNAL, TopAbs_EXTERNAL):
            where = f"wire {index}, edge {visited}"
            loop.append(_edge_curve(face, edge, orientation == TopAbs_REVERSED, where))
            visited += 1
        explorer.Next()
    if visited != expected:
        # A wire whose edges do not connect in (u, v): the explorer stops early and a part of
        # the boundary would be lost without a word.
        raise ValueError(
            f"wire {index}: the wire explorer visited {visited} of its {expected} edges "
            "(the edges do not connect in (u, v))"
        )
    return loop


def _edge_curve(face, edge, reverse: bool, where: str) -> CurveArrays:
    """The pcurve of ``edge`` on ``face`` over the edge's range, as exact B-spline arrays,
    reversed if ``reverse``; ``where`` names the edge in errors."""
    try:
        adaptor = BRepAdaptor_Curve2d(edge, face)
        curve = adaptor.Curve()
        first, last = adaptor.FirstParameter(), adaptor.LastParameter()
    except Exception as e:  # OCP raises its own exception types (Standard_Failure, ...)
        raise ValueError(f"{where}: no pcurve on the face ({e})") from None
    if curve is None:
        raise ValueError(f"{where}: no pcurve on the face")
    basis = curve
    # A trimmed curve's basis may be trimmed again; a chain longer than a few is not a real
    # file's, and the bound keeps a corrupt one from looping.
    for _ in range(16):
        if not isinstance(basis, Geom2d_TrimmedCurve):
            break
        basis = basis.BasisCurve()
    if isinstance(basis, Geom2d_OffsetCurve):
        raise ValueError(f"{where}: an offset pcurve has no exact B-spline form")
    if not (np.isfinite(first) and np.isfinite(last) and first < last):
        raise ValueError(f"{where}: the edge's range [{first}, {last}] is not a finite interval")
    try:
        bspline = Geom2dConvert.CurveToBSplineCurve_s(Geom2d_TrimmedCurve(curve, first, last))
        if bspline.IsPeriodic():
            bspline.SetNotPeriodic()
    except Exception as e:
        raise ValueError(f"{where}: the pcurve cannot be converted to a B-spline ({e})") from None
    return _bspline_arrays(bspline, reverse, where)


def _bspline_arrays(bspline, reverse: bool, where: str) -> CurveArrays:
    """Degree, flat knot vector (each knot repeated by its multiplicity), poles and weights of
    a non-periodic ``Geom2d_BSplineCurve``, reversed if ``reverse``."""
    degree = bspline.Degree()
    knots = np.repeat(
        [bspline.Knot(i) for i in range(1, bspline.NbKnots() + 1)],
        [bspline.Multiplicity(i) for i in range(1, bspline.NbKnots() + 1)],
    ).astype(np.float64)
    n = bspline.NbPoles()
    points = np.array([[p.X(), p.Y()] for p in (bspline.Pole(i) for i in range(1, n + 1))], dtype=np.float64)
    weights = (
        np.array([bspline.Weight(i) for i in range(1, n + 1)], dtype=np.float64) if bspline.IsRational() else None
    )
    if len(knots) != n + degree + 1:
        raise ValueError(f"{where}: the B-spline has {len(knots)} knots for {n} poles of degree {degree}")
    if reverse:
        # The same curve run backwards: t -> a + b - t maps the knots onto themselves reversed.
        knots = (knots[0] + knots[-1]) - knots[::-1]
        points = points[::-1].copy()
        weights = None if weights is None else weights[::-1].copy()
    return degree, knots, points, weights


def _from_curves_takes_closure_tol() -> bool:
    """True when ``inrs.Domain.from_curves`` accepts ``closure_tol`` (added with the CAD
    readers)."""
    try:
        return "closure_tol" in inspect.signature(inrs.Domain.from_curves).parameters
    except (TypeError, ValueError):
        return False

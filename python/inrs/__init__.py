"""Exact point containment for planar domains bounded by NURBS and rational Bezier curves.

Points are classified exactly as inside, outside or on the boundary (within a tolerance relative
to the domain's size) by the inRS algorithm, on NumPy arrays, with the GIL released and all cores
at work. Winding numbers, well-spaced sampling, curved triangulations and splines on them
(quasi-interpolation of a function, ``C^1`` interpolation of scattered data) come with it.

>>> import numpy as np, inrs
>>> d = inrs.Domain.from_json('{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}')
>>> d.classify(np.array([[0.0, 0.0], [2.0, 0.0], [1.0, 0.0]])).tolist()
[1, 0, 2]
"""

from __future__ import annotations

import hashlib
import operator
import functools
import os
import threading
import warnings
from typing import Any, Callable, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _inrs

__all__ = [
    "Domain",
    "DomainSummary",
    "Formula",
    "LoopSummary",
    "Spline",
    "OUTSIDE",
    "INSIDE",
    "BOUNDARY",
    "DEFAULT_TOLERANCE",
    "sample",
    "mesh",
    "halton_points",
    "fit",
    "interpolate",
    "convex_domain",
    "cad_faces",
    "cad_model",
    "CadModel",
    "CadFace",
    "CadEdge",
    "CadShell",
    "CadSolid",
    "CadProperties",
    "FaceProperties",
    "SolidProperties",
    "classify_many",
    "CellCoverage",
    "EBCoverage",
    "cell_fractions",
    "to_xarray",
    "cubature",
    "MAX_CUBATURE_DEGREE",
    "MAX_CELLS",
    "MAX_EDGES",
    "DEFAULT_CONVEX_TOLERANCE",
    "__version__",
]

#: Code of a point outside the domain.
OUTSIDE: int = _inrs.OUTSIDE
#: Code of a point inside the domain.
INSIDE: int = _inrs.INSIDE
#: Code of a point on the boundary (within the tolerance).
BOUNDARY: int = _inrs.BOUNDARY
#: Default boundary tolerance, relative to the diagonal of the domain's bounding box.
DEFAULT_TOLERANCE: float = _inrs.DEFAULT_TOLERANCE
__version__: str = _inrs.__version__
#: Default relative growth tolerance of :func:`convex_domain` (``inrs convex-domain --tol``).
DEFAULT_CONVEX_TOLERANCE: float = _inrs.DEFAULT_CONVEX_TOLERANCE
#: Most cells one call of :meth:`Domain.cell_fractions` computes (``2**28``, 2 GiB of
#: fractions); :func:`inrs.dask.cell_fractions` computes larger grids by blocks of rows.
MAX_CELLS: int = _inrs.MAX_CELLS
#: Most edges along one axis of a grid (``2**26``).
MAX_EDGES: int = _inrs.MAX_EDGES
#: The highest degree of :func:`cubature` and :meth:`Domain.integrate` (40, at most 861 nodes;
#: ``inrs cubature --degree``).
MAX_CUBATURE_DEGREE: int = _inrs.MAX_CUBATURE_DEGREE

#: What :meth:`Domain.summary` returns: read-only attributes ``curves``, ``bezier_pieces``,
#: ``max_degree``, ``rational``, ``loops`` (a list of :class:`LoopSummary`), ``filled_area``,
#: ``signed_area``, ``areas_converged``, ``bounds``.
DomainSummary = _inrs.DomainSummary
#: One boundary loop of a :class:`DomainSummary`: read-only attributes ``first_curve``,
#: ``last_curve`` (the loop is the curves ``first_curve..=last_curve``), ``closed``, ``gap``,
#: ``signed_area`` (positive counter-clockwise).
LoopSummary = _inrs.LoopSummary

_METHODS = ("fast", "inrs1", "inrs2", "gwn")

ArrayLike = Any


def _points(x: ArrayLike, y: Optional[ArrayLike]) -> Tuple[Any, tuple]:
    """The points as the native queries take them, and the shape of one value per point:
    ``(xy, (N,))`` for ``(N, 2)`` points, ``((x, y), shape)`` for two arrays of one shape
    (flattened). Float64 input of any memory layout is passed as it is (the native code reads
    strides); other types are converted."""
    if y is None:
        xy = np.asarray(x, dtype=np.float64)
        if xy.ndim != 2 or xy.shape[1] != 2:
            raise ValueError(f"points must have shape (N, 2), got {xy.shape}")
        return xy, (xy.shape[0],)
    xa, ya = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    if xa.shape != ya.shape:
        raise ValueError(f"x and y must have the same shape, got {xa.shape} and {ya.shape}")
    return (xa.reshape(-1), ya.reshape(-1)), xa.shape


def _non_negative_int(value: Any, what: str) -> int:
    """``value`` as an ``int`` >= 0, else a ``ValueError`` naming it ``what``."""
    try:
        value = operator.index(value)
    except TypeError:
        raise ValueError(f"{what} must be an integer, got {value!r}") from None
    if value < 0:
        raise ValueError(f"{what} must be an integer >= 0, got {value}")
    return value


def _threads(threads: Optional[int]) -> int:
    if threads is None:
        return 0
    if threads < 1:
        raise ValueError(f"threads must be at least 1, got {threads}")
    return int(threads)


class CellCoverage(NamedTuple):
    """What :meth:`Domain.cell_fractions` returns when centroids or apertures are asked for:
    float64 arrays, ``None`` for the parts not asked for. Row ``j``, column ``i`` is the cell
    ``[x_i, x_{i+1}] x [y_j, y_{j+1}]``."""

    #: ``(ny, nx)``: the covered fraction of each cell's area (revolved: of its ring's
    #: volume), in ``[0, 1]``.
    fractions: np.ndarray
    #: ``(ny, nx, 2)``: the centroid ``(x, y)`` of each cell's covered part (inside the cell),
    #: ``NaN`` where the fraction is 0 (with ``centroids=True``).
    centroids: Optional[np.ndarray]
    #: ``(ny, nx + 1)``: the covered fraction of each vertical face ``x = x_i``, ``y`` in
    #: ``[y_j, y_{j+1}]`` (with ``apertures=True``).
    x_apertures: Optional[np.ndarray]
    #: ``(ny + 1, nx)``: the covered fraction of each horizontal face ``y = y_j``, ``x`` in
    #: ``[x_i, x_{i+1}]`` (with ``apertures=True``).
    y_apertures: Optional[np.ndarray]

    def to_xarray(self, x_edges: ArrayLike, y_edges: ArrayLike) -> Any:
        """:func:`inrs.to_xarray` of this result: an ``xarray.Dataset``."""
        return to_xarray(self, x_edges, y_edges)


class EBCoverage(NamedTuple):
    """What :meth:`Domain.cell_fractions` returns when the boundary's geometry or the face
    centroids are asked for: the fields of :class:`CellCoverage` first (so that code reading
    those by position still works), then the embedded boundary's. Float64 arrays, ``None``
    for the parts not asked for; ``NaN`` where a value does not exist."""

    #: ``(ny, nx)``: as :attr:`CellCoverage.fractions`.
    fractions: np.ndarray
    #: ``(ny, nx, 2)``: as :attr:`CellCoverage.centroids`.
    centroids: Optional[np.ndarray]
    #: ``(ny, nx + 1)``: as :attr:`CellCoverage.x_apertures`.
    x_apertures: Optional[np.ndarray]
    #: ``(ny + 1, nx)``: as :attr:`CellCoverage.y_apertures`.
    y_apertures: Optional[np.ndarray]
    #: ``(ny, nx)``: the length of the boundary inside each cell, 0 where there is none (a
    #: boundary running on a face counts in the cell left of it or below it) (with
    #: ``boundary=True``).
    boundary_lengths: Optional[np.ndarray] = None
    #: ``(ny, nx, 2)``: the centroid ``(x, y)`` of the boundary's length inside each cell,
    #: ``NaN`` where there is none (with ``boundary=True``).
    boundary_centroids: Optional[np.ndarray] = None
    #: ``(ny, nx, 2)``: the unit vector along the integral of the boundary's normal over its
    #: part in each cell, pointing out of the covered part (AMReX's ``bnorm``); ``NaN`` where
    #: there is no boundary or the integral is 0 (with ``boundary=True``).
    boundary_normals: Optional[np.ndarray] = None
    #: ``(ny, nx + 1)``: the ``y`` of the centroid of each vertical face's covered part,
    #: ``NaN`` where it is not covered (with ``face_centroids=True``).
    x_face_centroids: Optional[np.ndarray] = None
    #: ``(ny + 1, nx)``: the ``x`` of the centroid of each horizontal face's covered part,
    #: ``NaN`` where it is not covered (with ``face_centroids=True``).
    y_face_centroids: Optional[np.ndarray] = None

    def to_xarray(self, x_edges: ArrayLike, y_edges: ArrayLike) -> Any:
        """:func:`inrs.to_xarray` of this result: an ``xarray.Dataset``."""
        return to_xarray(self, x_edges, y_edges)


#: The dimensions of each array of a coverage in :func:`to_xarray`.
_XARRAY_DIMS = {
    "fractions": ("y", "x"),
    "centroids": ("y", "x", "component"),
    "x_apertures": ("y", "x_face"),
    "y_apertures": ("y_face", "x"),
    "boundary_lengths": ("y", "x"),
    "boundary_centroids": ("y", "x", "component"),
    "boundary_normals": ("y", "x", "component"),
    "x_face_centroids": ("y", "x_face"),
    "y_face_centroids": ("y_face", "x"),
}


def to_xarray(result: Any, x_edges: ArrayLike, y_edges: ArrayLike) -> Any:
    """A result of :meth:`Domain.cell_fractions`, :func:`inrs.cell_fractions` (or
    :func:`inrs.dask.cell_fractions`) on the grid of ``x_edges``, ``y_edges`` as an xarray
    object (xarray is not a dependency of inrs: ``pip install xarray``).

    The fractions alone (a NumPy or a dask array of shape ``(ny, nx)``) give a ``DataArray``
    named ``fractions`` on the dimensions ``('y', 'x')``; a :class:`CellCoverage` or
    :class:`EBCoverage` gives a ``Dataset`` of the arrays it holds (those not asked for are
    left out). Coordinates: ``x``, ``y`` the cell centres (``(x_i + x_{i+1}) / 2``), and for
    the faces' arrays ``x_face``, ``y_face`` the edges themselves: vertical faces are on
    ``('y', 'x_face')``, horizontal faces on ``('y_face', 'x')``; centroids and normals have
    a last dimension ``component`` with coordinates ``['x', 'y']``. Several materials'
    results (:func:`inrs.cell_fractions` with a sequence of domains: fractions of shape
    ``(k, ny, nx)``) have a leading dimension ``material`` on every array, with coordinates
    ``0 .. k - 1`` (the domains' order). A dask array is wrapped as it is (lazily, nothing is
    computed). ``ValueError`` when the arrays' shapes do not match the edges; ``ImportError``
    without xarray.

    >>> d = Domain.from_json('{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}')
    >>> xs = ys = np.linspace(-1, 1, 5)
    >>> da = to_xarray(d.cell_fractions(xs, ys), xs, ys)  # doctest: +SKIP
    >>> da.dims, da.x.values                                # doctest: +SKIP
    (('y', 'x'), array([-0.75, -0.25,  0.25,  0.75]))
    """
    try:
        import xarray
    except ImportError:
        raise ImportError("inrs.to_xarray needs xarray, which is not installed: pip install xarray") from None
    x = _edges("x_edges", x_edges)
    y = _edges("y_edges", y_edges)
    nx, ny = len(x) - 1, len(y) - 1
    is_tuple = isinstance(result, (CellCoverage, EBCoverage))
    if not is_tuple and not hasattr(result, "shape"):
        result = np.asarray(result, dtype=np.float64)
    fractions = result.fractions if is_tuple else result
    # Several materials: a leading axis on every array.
    lead: tuple = ("material",) if len(getattr(fractions, "shape", ())) == 3 else ()
    k = fractions.shape[0] if lead else 0
    coords: dict = {
        "material": ("material", np.arange(k)),
        "x": ("x", 0.5 * (x[:-1] + x[1:])),
        "y": ("y", 0.5 * (y[:-1] + y[1:])),
        "x_face": ("x_face", x),
        "y_face": ("y_face", y),
        "component": ("component", np.array(["x", "y"])),
    }
    sizes = {"material": k, "x": nx, "y": ny, "x_face": nx + 1, "y_face": ny + 1, "component": 2}

    def dims(name: str) -> tuple:
        return lead + _XARRAY_DIMS[name]

    def checked(name: str, array: Any) -> Any:
        want = tuple(sizes[d] for d in dims(name))
        if tuple(array.shape) != want:
            raise ValueError(
                f"{name} has shape {tuple(array.shape)}, but the edges give {want} on {dims(name)}"
            )
        return array

    if is_tuple:
        arrays = {k: v for k, v in result._asdict().items() if v is not None}
        used = {d for name in arrays for d in dims(name)}
        return xarray.Dataset(
            {name: (dims(name), checked(name, v)) for name, v in arrays.items()},
            coords={d: c for d, c in coords.items() if d in used},
        )
    return xarray.DataArray(
        checked("fractions", result),
        dims=dims("fractions"),
        coords={d: coords[d] for d in dims("fractions")},
        name="fractions",
    )


def cell_fractions(
    domains: Union["Domain", Sequence["Domain"]],
    x_edges: ArrayLike,
    y_edges: ArrayLike,
    centroids: bool = False,
    apertures: bool = False,
    *,
    boundary: bool = False,
    face_centroids: bool = False,
    axisymmetric: Optional[str] = None,
    replace: bool = True,
    fill_rule: str = "even-odd",
    threads: Optional[int] = None,
) -> Union[np.ndarray, CellCoverage, EBCoverage]:
    """Several materials on one grid: the exact coverage of every cell by each of ``domains``
    (a sequence of :class:`Domain`, the materials in that order), as
    :meth:`Domain.cell_fractions` gives it for one domain, every array with a leading axis of
    ``k = len(domains)``: fractions ``(k, ny, nx)``, centroids ``(k, ny, nx, 2)``,
    ``x_apertures`` ``(k, ny, nx + 1)``, and so on, in the same result types (the bare array
    of fractions, a :class:`CellCoverage` with ``centroids`` or ``apertures``, an
    :class:`EBCoverage` with ``boundary`` or ``face_centroids``). Material ``m`` is index
    ``m``: ``result.fractions[m]``.

    With ``replace`` (the default) a later domain replaces the earlier ones where it lies
    (Axom's shaping rule): material ``m`` holds its domain minus the domains after it, so a
    cell's fractions sum to at most 1 (up to rounding), the last material is its domain's own
    coverage bit for bit, and a material replaced everywhere is zeros (``NaN`` centroids).
    With ``replace=False`` each material is its domain's own coverage (overlaps counted in
    each), equal to :meth:`Domain.cell_fractions` bit for bit. ``fill_rule`` applies to every
    domain; ``axisymmetric``, ``boundary``, ``face_centroids`` and the edges are those of
    :meth:`Domain.cell_fractions`. One call of the library (``MaterialCoverage``, which
    decides the regions) with the GIL released, on all cores (``threads`` limits them); each
    material's grid is limited to :data:`MAX_CELLS` cells (:func:`inrs.dask.cell_fractions`
    takes several domains too, by blocks of rows). :func:`inrs.to_xarray` labels the leading
    axis ``material``.

    A single :class:`Domain` (not in a sequence) gives :meth:`Domain.cell_fractions`'s result,
    without the leading axis. An empty sequence is a ``ValueError``; anything but a
    :class:`Domain` in it a ``TypeError`` naming its index. The library's errors (those of
    :meth:`Domain.cell_fractions`, and boundaries of different domains whose intersections
    are not found) are ``ValueError`` with its one-line message.

    >>> disc = lambda x: Domain.from_json(
    ...     '{"curves": [{"circle": {"center": [%r, 0], "radius": 1}}]}' % x)
    >>> f = cell_fractions([disc(-0.5), disc(0.5)], [-2, 2], [-2, 2])  # one cell: 16 x fraction
    >>> lens = 2 * np.pi / 3 - np.sqrt(3) / 2
    >>> f.shape, bool(np.allclose(16 * f[:, 0, 0], [np.pi - lens, np.pi], rtol=0, atol=1e-12))
    ((2, 1, 1), True)
    """
    if isinstance(domains, Domain):
        return domains.cell_fractions(
            x_edges,
            y_edges,
            centroids,
            apertures,
            boundary=boundary,
            face_centroids=face_centroids,
            axisymmetric=axisymmetric,
            fill_rule=fill_rule,
            threads=threads,
        )
    natives = _natives(domains)
    arrays = _inrs.material_coverage(
        natives,
        _edges("x_edges", x_edges),
        _edges("y_edges", y_edges),
        bool(replace),
        bool(centroids),
        bool(apertures),
        str(fill_rule),
        _threads(threads),
        bool(boundary),
        bool(face_centroids),
        None if axisymmetric is None else str(axisymmetric),
    )
    return _coverage_result(arrays, centroids or apertures, boundary or face_centroids)


def _coverage_result(arrays: tuple, cell: Any, eb: Any) -> Union[np.ndarray, CellCoverage, EBCoverage]:
    """The arrays of one coverage call as the result type the outputs asked for: an
    :class:`EBCoverage` with the boundary or face centroids (``eb``), a :class:`CellCoverage`
    with centroids or apertures (``cell``), else the fractions alone."""
    if eb:
        return EBCoverage(*arrays)
    if cell:
        return CellCoverage(*arrays[:4])
    return arrays[0]


def _natives(domains: Any) -> "list[_inrs.NativeDomain]":
    """The native domains of a non-empty sequence of :class:`Domain`: ``TypeError`` for
    anything else (naming the index of an element that is not a Domain), ``ValueError`` for
    an empty sequence."""
    if isinstance(domains, (str, bytes, Mapping)) or not isinstance(domains, (Sequence, np.ndarray)):
        raise TypeError(
            f"domains must be an inrs.Domain or a sequence of them, got a {type(domains).__name__}"
        )
    domains = list(domains)
    if not domains:
        raise ValueError("domains is empty: give at least one inrs.Domain")
    for i, d in enumerate(domains):
        if not isinstance(d, Domain):
            raise TypeError(f"domains[{i}] is a {type(d).__name__}, not an inrs.Domain")
    return [d._native for d in domains]


def _edges(name: str, edges: ArrayLike) -> np.ndarray:
    """Grid edges as a 1-D float64 array (any layout; the library checks their values)."""
    try:
        a = np.asarray(edges, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ValueError(f"{name} must be numbers ({e})") from None
    if a.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array of edges, got shape {a.shape}")
    return a


# Domains rebuilt from pickles are shared within a process, so that the tasks of a Dask or
# multiprocessing worker build each domain's index once.
_CACHE: "dict[str, _inrs.NativeDomain]" = {}
_CACHE_LOCK = threading.Lock()


def _from_json_shared(text: str) -> "Domain":
    key = hashlib.sha256(text.encode()).hexdigest()
    with _CACHE_LOCK:
        native = _CACHE.get(key)
        if native is None:
            native = _inrs.NativeDomain.from_json(text)
            if len(_CACHE) > 64:
                _CACHE.clear()
            _CACHE[key] = native
    return Domain(native)


def _curve_arrays(i: int, curve: Any) -> tuple:
    """Curve ``i`` of :meth:`Domain.from_curves` as ``(degree, knots, control points (M, 2),
    weights or None)`` in float64; its shape and types only (the Rust constructor checks the
    rest)."""
    if isinstance(curve, Mapping):
        unknown = set(curve) - {"degree", "knots", "control_points", "weights"}
        missing = [k for k in ("degree", "knots", "control_points") if k not in curve]
        if unknown or missing:
            raise ValueError(
                f"curve {i}: expected the keys degree, knots, control_points and optionally "
                f"weights, got {sorted(curve)}"
            )
        parts = (curve["degree"], curve["knots"], curve["control_points"], curve.get("weights"))
    elif isinstance(curve, (tuple, list)) and len(curve) in (3, 4):
        parts = tuple(curve) + (None,) * (4 - len(curve))
    else:
        raise ValueError(
            f"curve {i}: expected a dict or a tuple (degree, knots, control_points[, weights])"
        )
    degree, knots, points, weights = parts
    degree = _non_negative_int(degree, f"curve {i}: degree")

    def array(what: str, value: Any, ndim: int) -> np.ndarray:
        try:
            a = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ValueError(f"curve {i}: {what} must be numbers ({e})") from None
        shape = "(M, 2)" if ndim == 2 else "(M,)"
        if a.ndim != ndim or (ndim == 2 and a.shape[1] != 2):
            raise ValueError(f"curve {i}: {what} must have shape {shape}, got {a.shape}")
        return a

    return (
        degree,
        array("knots", knots, 1),
        array("control points", points, 2),
        None if weights is None else array("weights", weights, 1),
    )


class Domain:
    """A planar domain bounded by NURBS curves: one or more loops (holes, several parts).

    Build it with :meth:`Domain.load`, :meth:`Domain.from_json` or :meth:`Domain.from_curves`.
    Its indexes (monotone boxes, the point-location grid, the winding-number field) are built
    on first use and kept; a domain pickles by its JSON form (the indexes are rebuilt where it
    is unpickled).
    """

    __slots__ = ("_native", "_summary", "_rules")

    def __init__(self, native: "_inrs.NativeDomain") -> None:
        if not isinstance(native, _inrs.NativeDomain):
            raise TypeError("use Domain.load(path), Domain.from_json(text) or Domain.from_curves(curves)")
        self._native = native
        self._summary: Optional[DomainSummary] = None
        # Cubature rules by degree, built on first use and kept (the domain never changes).
        self._rules: "dict[tuple[int, str], _inrs.CubatureRule]" = {}

    @classmethod
    def load(cls, path: Union[str, os.PathLike], closure_tol: Optional[float] = None) -> "Domain":
        """Reads a domain file: JSON, SVG, DXF, a font glyph such as ``"font.ttf#B"``, or a face
        of a STEP or IGES part in its ``(u, v)`` such as ``"part.step#face:3"`` (:func:`cad_faces`
        lists them).

        ``closure_tol``: the largest gap between consecutive curves that still counts as
        meeting, relative to the diagonal of the domain's bounding box (default ``1e-9``; for a
        CAD face the larger of it and the file's own tolerance).

        Raises ``OSError`` if the file cannot be read and ``ValueError`` if it is not a domain.
        An SVG ``path`` whose data has an error is drawn up to its last complete segment, as
        renderers draw it, with a ``UserWarning`` naming the element and the error.
        """
        native, recovered = _inrs.NativeDomain.load(os.fspath(path), closure_tol)
        for message in recovered:
            warnings.warn(message, UserWarning, stacklevel=2)
        return cls(native)

    @classmethod
    def from_json(cls, text: str) -> "Domain":
        """A domain from the text of a JSON domain file. Raises ``ValueError`` on bad input."""
        return cls(_inrs.NativeDomain.from_json(text))

    @classmethod
    def from_curves(
        cls, curves: Sequence[Any], name: Optional[str] = None, closure_tol: Optional[float] = None
    ) -> "Domain":
        """A domain from NURBS curves given as arrays, without JSON.

        Each curve is a dict with the keys of the JSON file's NURBS form, ``degree``, ``knots``,
        ``control_points`` (shape ``(M, 2)``) and optionally ``weights`` (``(M,)``, default all
        1), or a tuple ``(degree, knots, control_points)`` or ``(degree, knots, control_points,
        weights)``. The curves are checked as the JSON reader checks them (the same Rust
        constructor: knot count and order, finite coordinates, positive weights, the limits)
        and grouped into loops the same way (``closure_tol``: the relative closure tolerance, as
        in :meth:`load`). Bad input raises ``ValueError`` naming the curve by its index
        (``"curve 1: ..."``).

        >>> import math
        >>> s = math.sqrt(0.5)
        >>> circle = {
        ...     "degree": 2,
        ...     "knots": [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
        ...     "control_points": [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]],
        ...     "weights": [1, s, 1, s, 1, s, 1, s, 1],
        ... }
        >>> round(Domain.from_curves([circle]).area, 12)
        3.14159265359
        """
        if isinstance(curves, Mapping) or not isinstance(curves, Sequence):
            raise ValueError("curves must be a list of curves (dicts or tuples)")
        return cls(
            _inrs.NativeDomain.from_curves(
                [_curve_arrays(i, c) for i, c in enumerate(curves)], name, closure_tol
            )
        )

    def to_json(self) -> str:
        """The JSON domain file; ``Domain.from_json(d.to_json())`` gives the same curves."""
        return self._native.to_json()

    @property
    def name(self) -> Optional[str]:
        """The domain's name, if its file gives one."""
        return self._native.name

    def summary(self) -> DomainSummary:
        """Facts about the domain, as ``inrs info`` prints them: a :class:`DomainSummary` with
        read-only attributes ``curves`` (number of NURBS curves), ``bezier_pieces``,
        ``max_degree``, ``rational``, ``loops`` (a list of :class:`LoopSummary`: ``first_curve``,
        ``last_curve``, ``closed``, ``gap``, ``signed_area``), ``fill_rule`` (``"even-odd"``),
        ``filled_area`` (the even-odd area, ``None`` for open, coincident or crossing loops:
        :meth:`filled_area` says why), ``signed_area`` (sum over the loops), ``areas_converged``
        and ``bounds`` ``(xmin, ymin, xmax, ymax)``. Computed once and kept (the domain never
        changes).

        >>> s = Domain.from_json('{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}').summary()
        >>> s.curves, len(s.loops), round(s.filled_area, 12), s.bounds
        (1, 1, 3.14159265359, (-1.0, -1.0, 1.0, 1.0))
        """
        if self._summary is None:
            self._summary = self._native.summary()
        return self._summary

    def filled_area(self, fill_rule: str = "even-odd") -> float:
        """The area the domain fills under ``fill_rule`` (``even-odd`` or ``nonzero``), as
        ``inrs info --fill-rule`` prints it: exact for closed loops that do not cross each other
        or themselves. ``ValueError`` (one line, naming the crossing or the loop) for open,
        coincident or crossing loops, whose nesting does not decide the fill.

        >>> d = Domain.from_json('{"curves": [{"circle": {"center": [0, 0], "radius": 2}},'
        ...                      ' {"circle": {"center": [0, 0], "radius": 1}}]}')
        >>> round(d.filled_area() / np.pi, 12), round(d.filled_area("nonzero") / np.pi, 12)
        (3.0, 4.0)
        """
        return self._native.filled_area(str(fill_rule))

    @property
    def area(self) -> float:
        """The area filled by the even-odd rule (holes subtracted); for open loops, the
        absolute value of the signed area. ``ValueError`` for coincident or crossing loops
        (see :meth:`filled_area`)."""
        s = self.summary()
        if s.filled_area is not None:
            return float(s.filled_area)
        if not all(loop.closed for loop in s.loops):
            return abs(s.signed_area)
        return self.filled_area()

    @property
    def bounds(self) -> Tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` of the curves, as shapely orders it."""
        return self.summary().bounds

    @property
    def loops(self) -> "list[LoopSummary]":
        """The boundary loops: :class:`LoopSummary` objects with ``first_curve``,
        ``last_curve``, ``closed``, ``gap``, ``signed_area``."""
        return self.summary().loops

    def __repr__(self) -> str:
        s = self.summary()
        name = f"{self.name!r}, " if self.name else ""
        b = s.bounds
        return (
            f"Domain({name}curves={s.curves}, loops={len(s.loops)}, area={self.area:.6g}, "
            f"bounds=({b[0]:.6g}, {b[1]:.6g}, {b[2]:.6g}, {b[3]:.6g}))"
        )

    def __reduce__(self):
        return (_from_json_shared, (self.to_json(),))

    def classify(
        self,
        x: ArrayLike,
        y: Optional[ArrayLike] = None,
        *,
        method: str = "fast",
        tol: float = DEFAULT_TOLERANCE,
        fill_rule: str = "even-odd",
        threads: Optional[int] = None,
    ) -> np.ndarray:
        """Locations of points: an int8 array of :data:`OUTSIDE`, :data:`INSIDE`, :data:`BOUNDARY`.

        ``classify(xy)`` with ``xy`` of shape ``(N, 2)``, or ``classify(x, y)`` with two arrays
        of one shape (the result has that shape); any float type and memory layout. A point is
        on the boundary when it is within ``tol`` times the bounding-box diagonal of the curves
        (measured vertically or horizontally); all methods (``fast``, ``inrs1``, ``inrs2``,
        ``gwn``) agree elsewhere. ``fill_rule`` says which winding numbers are inside:
        ``even-odd`` (odd) or ``nonzero`` (not 0), for every method and any loops (nested,
        overlapping, crossing themselves). ``gwn`` rounds the generalized winding number and
        accepts open boundaries. ``threads`` limits the cores used (default all).
        """
        if method not in _METHODS:
            raise ValueError(f"unknown method {method!r} (one of {', '.join(_METHODS)})")
        points, shape = _points(x, y)
        return self._native.classify(
            points, method, float(tol), fill_rule, _threads(threads)
        ).reshape(shape)

    def contains_xy(self, x: ArrayLike, y: Optional[ArrayLike] = None, **kwargs) -> np.ndarray:
        """True strictly inside, boundary excluded (as ``shapely.contains_xy``)."""
        return self.classify(x, y, **kwargs) == INSIDE

    def covers_xy(self, x: ArrayLike, y: Optional[ArrayLike] = None, **kwargs) -> np.ndarray:
        """True inside or on the boundary (as ``shapely.covers``)."""
        return self.classify(x, y, **kwargs) != OUTSIDE

    def winding(
        self,
        x: ArrayLike,
        y: Optional[ArrayLike] = None,
        *,
        tol: float = DEFAULT_TOLERANCE,
        algorithm: str = "adaptive",
        threads: Optional[int] = None,
    ) -> np.ndarray:
        """Generalized winding numbers (float64): 1 inside a counter-clockwise loop, 0 outside,
        fractional near gaps of open boundaries. A point within ``tol`` times the bounding-box
        diagonal of a curve (the points :meth:`classify` calls boundary) gets the average
        across the jump: 0 inside a straight piece, 1/2 on a smooth closed curve, the interior
        angle over 2 pi at a corner.

        ``algorithm`` is a name of ``inrs winding --algorithm``: ``"adaptive"`` (the default:
        the paper's adaptive algorithm, accelerated), or the GWN paper's ray-casting baselines
        ``"binary-search"`` and ``"bezier-clipping"`` (for comparisons; slower, the same values
        up to rounding)."""
        points, shape = _points(x, y)
        return self._native.winding(points, float(tol), _threads(threads), algorithm).reshape(shape)

    def cell_fractions(
        self,
        x_edges: ArrayLike,
        y_edges: ArrayLike,
        centroids: bool = False,
        apertures: bool = False,
        *,
        boundary: bool = False,
        face_centroids: bool = False,
        axisymmetric: Optional[str] = None,
        fill_rule: str = "even-odd",
        threads: Optional[int] = None,
    ) -> Union[np.ndarray, CellCoverage, EBCoverage]:
        """The exact covered fraction of every cell of a rectilinear grid (volume fractions of
        cut-cell and embedded-boundary methods), optionally the covered parts' centroids, the
        faces' apertures, the boundary's length, centroid and normal in each cell and the
        faces' centroids; planar, or revolved about an axis.

        ``x_edges`` (``nx + 1`` values) and ``y_edges`` (``ny + 1``) are 1-D arrays of strictly
        increasing finite edges, uniform or not: row ``j``, column ``i`` is the cell ``[x_i,
        x_{i+1}] x [y_j, y_{j+1}]``, ``y`` increasing with the row. Without any of the extra
        outputs the result is the float64 array of fractions, shape ``(ny, nx)``. With
        ``centroids`` or ``apertures`` alone, a :class:`CellCoverage` named tuple
        ``(fractions, centroids, x_apertures, y_apertures)`` whose parts not asked for are
        ``None``: ``centroids`` ``(ny, nx, 2)`` (``NaN`` where a cell is empty),
        ``x_apertures`` ``(ny, nx + 1)`` (the covered fraction of each vertical face),
        ``y_apertures`` ``(ny + 1, nx)`` (each horizontal face). With ``boundary`` or
        ``face_centroids``, an :class:`EBCoverage`: those four, then ``boundary_lengths``
        ``(ny, nx)`` (the boundary's length in each cell, 0 where there is none),
        ``boundary_centroids`` and ``boundary_normals`` ``(ny, nx, 2)`` (the centroid of that
        length, and the unit integral of the normal pointing out of the covered part; ``NaN``
        where there is none), ``x_face_centroids`` ``(ny, nx + 1)`` (the ``y`` of the centroid
        of each vertical face's covered part) and ``y_face_centroids`` ``(ny + 1, nx)`` (the
        ``x`` of each horizontal face's; ``NaN`` where a face is not covered).
        :func:`inrs.to_xarray` (or the tuples' ``to_xarray``) labels any of them for xarray;
        ``docs/CLI.md`` maps them to AMReX's EB2 names (``volfrac``, ``vcent``, ``barea``,
        ``bcent``, ``bnorm``, ``apx``, ``fcx``).

        ``axisymmetric`` (``'x'`` or ``'y'``) revolves the domain about that coordinate axis
        (``'y'``: the radius is ``x``, r-z coordinates; ``'x'``: the radius is ``y``): a cell
        stands for the ring it sweeps, its fraction is the covered fraction of the ring's
        volume (``int int r dA`` over the ring's), the centroids are weighted by ``r``, the
        apertures of faces across the axis are fractions of annuli. The domain and the grid
        must each lie on one side of the axis (touching it is fine), and ``boundary`` and
        ``face_centroids`` are planar only: ``ValueError`` otherwise.

        ``fill_rule`` is ``even-odd`` (the default) or ``nonzero`` (filled where the winding
        number is not zero, from the loops' orientations: two nested counter-clockwise circles
        fill the outer disc, with opposite orientations the ring), for closed loops that do not
        cross (holes, nesting, touching loops are fine): loops that cross each other or
        themselves are a ``ValueError`` naming the crossing, as is an unknown rule. Values are
        exact up to rounding (within about ``1e-12`` of the cell's area;
        cells the boundary misses are exactly 0 or 1); a face on which the boundary runs takes
        the value of the line just to its right (vertical) or just above it (horizontal). The
        grid need not cover the domain. One call of the library (``GridCoverage``) with the GIL
        released, on all cores (``threads`` limits them).

        Limits and errors (``ValueError`` with a one-line message): edges that are not 1-D,
        fewer than 2 along an axis (no cell), reversed, repeated, ``NaN`` or infinite; more than
        :data:`MAX_EDGES` per axis; more than :data:`MAX_CELLS` cells (use
        :func:`inrs.dask.cell_fractions`, which computes blocks of rows); an open boundary.
        Coverage needs closed loops: for an open or self-overlapping collection of curves the
        route is the generalized winding number (:meth:`winding`, or ``classify(method="gwn")``
        at points of the cells), which is not exact per cell.

        >>> d = Domain.from_json('{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}')
        >>> f = d.cell_fractions([-1, 0, 1], [-1, 0, 1])   # four quarter discs
        >>> bool(np.allclose(f, np.pi / 4, rtol=0, atol=1e-15)), f.shape
        (True, (2, 2))
        >>> eb = d.cell_fractions([-1, 0, 1], [-1, 0, 1], boundary=True)
        >>> bool(np.isclose(eb.boundary_lengths.sum(), 2 * np.pi, rtol=1e-14))
        True
        """
        return self._coverage(
            x_edges,
            y_edges,
            None,
            centroids,
            apertures,
            fill_rule,
            _threads(threads),
            boundary=boundary,
            face_centroids=face_centroids,
            axisymmetric=axisymmetric,
        )

    def _coverage(
        self,
        x_edges: ArrayLike,
        y_edges: ArrayLike,
        rows: Optional[Tuple[int, int]],
        centroids: bool,
        apertures: bool,
        fill_rule: str,
        threads: int,
        *,
        boundary: bool = False,
        face_centroids: bool = False,
        axisymmetric: Optional[str] = None,
    ) -> Union[np.ndarray, CellCoverage, EBCoverage]:
        """:meth:`cell_fractions` on the whole grid (``rows`` ``None``) or on its rows
        ``j0 .. j1`` (``rows = (j0, j1)``, one band on the calling thread)."""
        arrays = _inrs.cell_coverage(
            self._native,
            _edges("x_edges", x_edges),
            _edges("y_edges", y_edges),
            rows,
            bool(centroids),
            bool(apertures),
            str(fill_rule),
            threads,
            bool(boundary),
            bool(face_centroids),
            None if axisymmetric is None else str(axisymmetric),
        )
        return _coverage_result(arrays, centroids or apertures, boundary or face_centroids)

    def _cubature_rule(self, degree: int, fill_rule: str = "even-odd") -> "_inrs.CubatureRule":
        """The cubature rule of degree ``degree`` on the set the domain fills under
        ``fill_rule``, built once (GIL released) and kept."""
        degree = _non_negative_int(degree, "degree")
        key = (degree, str(fill_rule))
        rule = self._rules.get(key)
        if rule is None:
            rule = _inrs.CubatureRule(self._native, degree, key[1])
            self._rules[key] = rule
        return rule

    def integrate(
        self,
        f: Union[str, Callable[[np.ndarray, np.ndarray], ArrayLike]],
        degree: int = 20,
        *,
        fill_rule: str = "even-odd",
    ) -> float:
        """The integral of ``f`` over the domain by the positive interior cubature rule of
        degree ``degree`` (:func:`cubature`, as ``inrs integrate --degree``): ``sum_i w_i f(x_i,
        y_i)``, exact up to the rule's residual (about ``1e-15`` relative) when ``f`` is a
        polynomial of total degree ``<= degree``, and as close as ``f`` is to one otherwise
        (for a smooth ``f`` the error falls fast with the degree).

        ``f`` is called once, as :func:`fit` calls it: ``f(x, y)`` with the two 1-D float64
        arrays of the nodes' coordinates (every node strictly inside the domain), and must
        return one value per node (an array of shape ``(N,)``) or a scalar (a constant, used at
        every node); or it is a formula's text, read as ``inrs integrate --function`` reads it
        (:class:`Formula`). The rule of each degree is built on the first call and kept. The domain is
        the set it fills under ``fill_rule`` (``even-odd`` or ``nonzero``, as
        :func:`cubature`).

        Errors (``ValueError``, one line): a degree above :data:`MAX_CUBATURE_DEGREE`, an open
        boundary, loops that cross, a domain too thin or too small against its bounding box
        for the rule's candidate points, ``f`` returning another shape or non-numbers, a value
        that is not finite (naming the node: its index and coordinates).

        >>> d = Domain.from_json('{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}')
        >>> bool(abs(d.integrate(lambda x, y: x**2 * y**2, degree=4) - np.pi / 24) < 1e-14)
        True
        """
        f = _callable(f)
        rule = self._cubature_rule(degree, fill_rule)
        nodes = rule.nodes()
        out = f(nodes[:, 0], nodes[:, 1])
        try:
            values = np.asarray(out, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ValueError(f"f must return numbers ({e})") from None
        n = len(nodes)
        if values.ndim == 0:
            values = np.full(n, float(values))
        elif values.shape != (n,):
            raise ValueError(
                f"f returned an array of shape {values.shape} for {n} nodes; expected ({n},) or a scalar"
            )
        return rule.integrate_values(np.ascontiguousarray(values))

    def flatten(self, accuracy: float) -> list:
        """The boundary as closed polylines within ``accuracy`` (absolute): one ``(M, 2)`` array
        per loop (for comparisons with polygon tools)."""
        return self._native.flatten(float(accuracy))


class Formula:
    """A formula in ``x`` and ``y``, read by the one grammar of ``inrs fit --function`` and
    ``inrs integrate --function``: numbers (``1e-3``, ``2.5E+4`` too), ``+ - * /``, ``^`` or
    ``**`` (right to left; ``-x^2`` is ``-(x^2)``), parentheses, the constants ``pi``, ``e``,
    ``tau`` and the functions ``inrs fit --help`` lists (``sin``, ``exp``, ``sqrt``,
    ``atan2(y, x)``, ...). A bad formula is a one-line ``ValueError`` naming the column and
    what was expected there. Calling it evaluates it on arrays (broadcast together), the GIL
    released; :func:`fit` and :meth:`Domain.integrate` take the text itself too.

    >>> f = Formula("-x^2 + 2.5E+1 * y - 1e-3")
    >>> f(np.array([3.0, 0.0]), 2.0).tolist()
    [40.999, 49.999]
    >>> Formula("foo(x)")
    Traceback (most recent call last):
    ...
    ValueError: formula "foo(x)": column 1: unknown function "foo" (see the functions in `inrs fit --help`)
    """

    __slots__ = ("_native",)

    def __init__(self, text: str):
        self._native = _inrs.Formula(str(text))

    @property
    def text(self) -> str:
        """The formula as written."""
        return self._native.text

    def __call__(self, x: ArrayLike, y: ArrayLike) -> np.ndarray:
        x, y = np.broadcast_arrays(np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64))
        values = self._native.evaluate(np.ravel(x), np.ravel(y))
        return values.reshape(x.shape)

    def __repr__(self) -> str:
        return f"Formula({self.text!r})"

    def __reduce__(self):
        return (Formula, (self.text,))


def _callable(f: Union[str, Callable[[np.ndarray, np.ndarray], ArrayLike]]):
    """``f`` itself, or the :class:`Formula` of a string."""
    return Formula(f) if isinstance(f, str) else f


class Spline:
    """A polynomial spline on a curved triangulation (see :func:`fit` and :func:`interpolate`)."""

    __slots__ = ("_native",)

    def __init__(self, native: "_inrs.NativeSpline") -> None:
        self._native = native

    @classmethod
    def from_json(cls, text: str) -> "Spline":
        """A spline from the text of a spline file (as ``inrs fit`` writes it)."""
        return cls(_inrs.NativeSpline.from_json(text))

    @classmethod
    def load(cls, path: Union[str, os.PathLike]) -> "Spline":
        """Reads a spline file."""
        with open(path, encoding="utf-8") as f:
            return cls.from_json(f.read())

    def to_json(self) -> str:
        """The spline file's text."""
        return self._native.to_json()

    def save(self, path: Union[str, os.PathLike]) -> None:
        """Writes the spline file."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.to_json())

    @property
    def degree(self) -> int:
        """The polynomial degree."""
        return self._native.summary()[0]

    @property
    def space(self) -> str:
        """The spline space, by its name in the spline file: ``"s0"`` (continuous, from
        :func:`fit`), or the ``C^1`` spaces of :func:`interpolate`: ``"s512"``, ``"ct"``,
        ``"ps"``, ``"min-energy"``."""
        return self._native.space

    @property
    def triangles(self) -> int:
        """Number of curved triangles."""
        return self._native.summary()[1]

    @property
    def dimension(self) -> int:
        """Number of coefficients of its space."""
        return self._native.summary()[2]

    def __repr__(self) -> str:
        return (
            f"Spline(space={self.space!r}, degree={self.degree}, triangles={self.triangles}, "
            f"coefficients={self.dimension})"
        )

    def __reduce__(self):
        return (Spline.from_json, (self.to_json(),))

    def __call__(self, x: ArrayLike, y: Optional[ArrayLike] = None) -> np.ndarray:
        """Values at the points (NaN outside the domain): :meth:`evaluate` without derivatives."""
        return self.evaluate(x, y)

    def evaluate(
        self,
        x: ArrayLike,
        y: Optional[ArrayLike] = None,
        *,
        derivatives: bool = False,
        threads: Optional[int] = None,
    ) -> np.ndarray:
        """Values anywhere in the domain (NaN outside); with ``derivatives``, an array of shape
        ``(..., 3)``: value, d/dx, d/dy."""
        points, shape = _points(x, y)
        out = self._native.evaluate(points, bool(derivatives), _threads(threads))
        return out.reshape(shape + ((3,) if derivatives else ()))


def sample(domain: Domain, ny: Optional[int] = None, *, count: Optional[int] = None) -> Tuple[np.ndarray, np.ndarray]:
    """Well-spaced points (Algorithm 11.1 of Schumaker and Yu): ``(points (N, 2), on_boundary
    (N,) bool)``; about ``ny`` rows of points over the domain's height (default 20), as
    ``inrs sample --ny``. With ``count`` instead: the first ``count`` Halton points inside the
    domain (``inrs sample --count``; ``on_boundary`` all false)."""
    if count is not None:
        if ny is not None:
            raise ValueError("give ny (well-spaced points) or count (Halton points), not both")
        if operator.index(count) < 0:
            raise ValueError(f"count must be positive, got {count}")
        pts = _inrs.sample_halton(domain._native, operator.index(count))
        return pts, np.zeros(len(pts), dtype=bool)
    return _inrs.sample(domain._native, int(20 if ny is None else ny))


def halton_points(n: int, bounds: Tuple[float, float, float, float], start: int = 0) -> np.ndarray:
    """Halton points ``start .. start + n`` in bases 2 and 3, starting with the box's corner
    ``(xmin, ymin)`` at index 0, mapped to ``bounds = (xmin, ymin, xmax, ymax)`` (the order of
    :attr:`Domain.bounds`): the quasi-random test clouds of the papers, as an ``(n, 2)`` array.
    Blocks of one long sequence can be made apart (on Dask workers) with ``start``."""
    if n < 0 or start < 0:
        raise ValueError(f"n and start must be non-negative, got n={n}, start={start}")
    return _inrs.halton_points(int(n), tuple(float(v) for v in bounds), int(start))


def mesh(domain: Domain, ny: int, refine: str = "none") -> dict:
    """The curved triangulation of :func:`sample`'s points, optionally refined (``"ct"``
    Clough-Tocher, ``"ps"`` Powell-Sabin): a dict of arrays ``vertices`` (N, 2), ``triangles``
    (T, 3) and ``curved_edges`` (a dict of arrays ``triangle, edge, curve, loop, u0, u1, start,
    end``)."""
    return _inrs.mesh(domain._native, int(ny), refine)


def fit(
    domain: Domain,
    f: Union[str, Callable[[np.ndarray, np.ndarray], ArrayLike]],
    *,
    ny: int = 9,
    degree: int = 5,
    refine: str = "none",
) -> Spline:
    """The quasi-interpolating spline of degree ``degree`` of ``f`` on the curved triangulation
    of ``mesh(domain, ny, refine)`` (continuous, exact for polynomials of that degree). ``f``
    is called once, with the arrays ``x``, ``y`` of every point it is needed at; or it is a
    formula's text, read as ``inrs fit --function`` reads it (:class:`Formula`)."""
    f = _callable(f)
    plan = _inrs.FitPlan(domain._native, int(ny), int(degree), refine)
    xy = plan.points()
    values = np.ascontiguousarray(np.broadcast_to(f(xy[:, 0], xy[:, 1]), (len(xy),)), dtype=np.float64)
    return Spline(plan.finish(values))


def cubature(domain: Domain, degree: int, *, fill_rule: str = "even-odd") -> Tuple[np.ndarray, np.ndarray]:
    """A positive interior cubature rule of degree ``degree`` on ``domain`` (Sommariva and
    Vianello; ``inrs cubature --degree``): ``(nodes, weights)``, float64 arrays of shapes
    ``(N, 2)`` and ``(N,)``.

    At most ``(degree + 1)(degree + 2) / 2`` nodes, every one strictly inside the domain
    (:meth:`Domain.classify` says :data:`INSIDE`), every weight positive, and ``sum_i w_i
    x_i^a y_i^b`` equal to the integral of ``x^a y^b`` over the set the domain fills under
    ``fill_rule`` (``even-odd``, the default, or ``nonzero``) for ``a + b <= degree``, up to a
    relative residual of about ``1e-15``: the weights add up to the filled area. Built with the
    GIL released, once per domain, degree and rule (kept for :meth:`Domain.integrate`).
    Errors (``ValueError``, one line): a degree above :data:`MAX_CUBATURE_DEGREE`, an open
    boundary, loops that cross each other or themselves (naming the crossing), a domain too
    thin or too small against its bounding box for the candidate points, the residual not
    reached.

    >>> d = Domain.from_json('{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}')
    >>> nodes, weights = cubature(d, 6)
    >>> nodes.shape[1], len(nodes) <= 28, bool((weights > 0).all()), round(float(weights.sum()), 12)
    (2, True, True, 3.14159265359)
    """
    rule = domain._cubature_rule(degree, fill_rule)
    return rule.nodes(), rule.weights()


def interpolate(domain: Domain, xy: ArrayLike, z: ArrayLike, *, space: str = "ct") -> Spline:
    """The ``C^1`` spline through scattered data: ``s(xy[i]) = z[i]``, as ``inrs fit --data
    --space`` computes it (Schumaker and Yu's Problem 9.1): the curved triangulation whose
    vertices are the data points, refined as the space needs, then a two-stage method (local
    least-squares fits for the derivatives, then Hermite macro-elements) or minimal energy.

    ``xy`` is an ``(N, 2)`` array of distinct points of the closed domain (points within 1e-9
    of its size of the boundary are moved onto it), ``z`` the ``N`` values. ``space`` sets the
    spline space and so the degree: ``"ct"`` (cubic ``S_3^1`` on the Clough-Tocher refinement,
    the default), ``"ps"`` (quadratic ``S_2^1`` on the Powell-Sabin refinement), ``"s512"``
    (quintic ``S_5^{1,2}``) or ``"min-energy"`` (``S_2^1``, minimal energy). The two-stage
    spaces reproduce polynomials of their local fits' degree (cubic for ``ct`` and ``s512``,
    quadratic for ``ps``); minimal energy reproduces linear functions. The space fixes the
    degree and the data points are the triangulation's vertices, so unlike :func:`fit` there is
    no ``ny`` or ``degree``. Give points on the boundary too (as :func:`sample` makes them):
    data points between a boundary arc and its chord cannot be vertices, and are left out with
    a ``UserWarning`` naming them. Bad input (shapes, points outside the domain or repeated, values that are not
    finite, an unknown space) raises ``ValueError``.
    """
    xy = np.asarray(xy, dtype=np.float64)
    if xy.ndim != 2 or xy.shape[1] != 2:
        raise ValueError(f"xy must have shape (N, 2), got {xy.shape}")
    z = np.asarray(z, dtype=np.float64)
    if z.ndim != 1:
        raise ValueError(f"z must have shape (N,), got {z.shape}")
    native, _added, unused = _inrs.interpolate(domain._native, xy, z, space)
    if unused:
        shown = ", ".join(f"xy[{i}]" for i in unused[:5]) + (", ..." if len(unused) > 5 else "")
        warnings.warn(
            f"{len(unused)} data points lie between a boundary arc and its chord, are not "
            f"vertices and are not interpolated ({shown})",
            stacklevel=2,
        )
    return Spline(native)


def classify_many(
    domains: Sequence["Domain"],
    points: Union[ArrayLike, Sequence[ArrayLike]],
    *,
    method: str = "fast",
    tol: float = DEFAULT_TOLERANCE,
    fill_rule: str = "even-odd",
    threads: Optional[int] = None,
    errors: str = "raise",
) -> "list[Optional[np.ndarray]]":
    """Locations of points in many domains at once: per domain, an int8 array of
    :data:`OUTSIDE`, :data:`INSIDE`, :data:`BOUNDARY` (what :meth:`Domain.classify` returns).

    ``points`` is one ``(N, 2)`` array that every domain classifies, or a list of ``(N_k, 2)``
    arrays, one per domain (a list of lists of pairs is read as one array when it has shape
    ``(N, 2)``; pass a tuple or list of NumPy arrays for one array per domain). ``method``,
    ``tol``, ``fill_rule`` and ``threads`` are those of :meth:`Domain.classify`, and each
    answer equals it. The domains are spread over the cores with the GIL released (the
    library's ``locate_many``: each domain built and answered on one core, a large batch of
    one domain split over the cores), which is what makes thousands of small domains (a CAD
    part's faces, a font's glyphs) cheap: nothing is cached on the domains.

    The result is in the order of ``domains``. A domain that cannot be prepared (an open
    boundary with a crossing method) raises ``ValueError`` naming its index when ``errors`` is
    ``"raise"`` (the default); with ``errors="none"`` its entry is ``None`` and the others
    still answer. Bad arguments (shapes, method, tolerance, a list of arrays of another length
    than ``domains``) raise ``ValueError``.
    """
    if method not in _METHODS:
        raise ValueError(f"unknown method {method!r} (one of {', '.join(_METHODS)})")
    if errors not in ("raise", "none"):
        raise ValueError(f"errors must be 'raise' or 'none', got {errors!r}")
    natives = []
    for k, d in enumerate(domains):
        if not isinstance(d, Domain):
            raise TypeError(f"domains[{k}] is a {type(d).__name__}, not an inrs.Domain")
        natives.append(d._native)
    args = (method, float(tol), fill_rule, _threads(threads))
    shared = None
    each = None
    if isinstance(points, np.ndarray) or not isinstance(points, (list, tuple)):
        shared = np.asarray(points, dtype=np.float64)
    elif points and all(isinstance(p, np.ndarray) for p in points):
        each = [np.asarray(p, dtype=np.float64) for p in points]
    else:
        # A list of pairs (or an empty list) is one array of points.
        shared = np.asarray(points, dtype=np.float64)
        if shared.size == 0:
            shared = shared.reshape(0, 2)
    for k, a in enumerate([shared] if each is None else each):
        if a.ndim != 2 or a.shape[1] != 2:
            where = "points" if each is None else f"points[{k}]"
            raise ValueError(f"{where} must have shape (N, 2), got {a.shape}")
    arrays, failures = _inrs.classify_many(natives, shared, each, *args)
    if errors == "raise":
        for k, e in enumerate(failures):
            if e is not None:
                raise ValueError(f"domain {k}: {e}")
    return arrays


class CadFace:
    """One face of a STEP or IGES file, as :func:`cad_model` and :func:`cad_faces` give it.

    Read-only attributes: ``index`` (``Domain.load(f"{path}#face:{index}")`` reads it),
    ``entity`` (``"#123"`` for STEP, ``"DE 57"`` for IGES), ``surface`` (the surface type as
    the file names it), ``loops``, ``curves``, ``area`` (of the face's ``(u, v)`` domain),
    ``bbox`` (``(umin, vmin, umax, vmax)``), ``error`` (why the face is refused, or ``None``),
    ``domain`` (the face as a :class:`Domain`, or ``None`` when refused), ``closure_tolerance``
    (the gap its loops were closed within, in ``(u, v)``), ``width`` (twice its area over its
    loops' length), ``narrow`` (narrower than its closure tolerance: its shape is then no more
    exact than the file's tolerance), ``pcurve_deviation`` (the bound of pcurves fitted to 3-D
    edges, model units, or ``None``) and ``natural_bounds`` (bounded by its surface's
    parameter box).

    Faces from :func:`cad_model` also have their surface and edges in 3-D:
    ``surface_kind`` (``"plane"``, ``"cylinder"``, ``"cone"``, ``"sphere"``, ``"torus"``,
    ``"revolution"``, ``"extrusion"``, ``"offset"``, ``"bspline"``, ``"reparam"``, or ``None``
    when the surface was not read), ``same_sense`` (the face's outward normal is the surface's
    ``S_u x S_v``), :meth:`points`, :meth:`normals` and ``edges``; and their mass properties
    in 3-D (:meth:`CadModel.properties`, computed once for the whole model on first use):
    ``properties`` (a :class:`FaceProperties`), ``surface_area`` (the face's area in space,
    where ``area`` is its ``(u, v)`` domain's), ``centroid`` and ``second_moments``. These raise
    ``ValueError`` with the library's one-line reason for a face whose properties cannot be
    computed (its surface not read, ...).
    """

    __slots__ = ("_native", "_domain", "_model", "_properties")

    def __init__(
        self,
        native: "_inrs.CadFace",
        domain: Optional["Domain"],
        model: "Optional[_inrs.NativeCadModel]" = None,
        properties: "Optional[_ModelProperties]" = None,
    ) -> None:
        self._native = native
        self._domain = domain
        self._model = model
        self._properties = properties

    index = property(lambda self: self._native.index)
    entity = property(lambda self: self._native.entity)
    surface = property(lambda self: self._native.surface)
    loops = property(lambda self: self._native.loops)
    curves = property(lambda self: self._native.curves)
    area = property(lambda self: self._native.area)
    bbox = property(lambda self: self._native.bbox)
    error = property(lambda self: self._native.error)
    domain = property(lambda self: self._domain)
    closure_tolerance = property(lambda self: self._native.closure_tolerance)
    width = property(lambda self: self._native.width)
    narrow = property(lambda self: self._native.narrow)
    pcurve_deviation = property(lambda self: self._native.pcurve_deviation)
    natural_bounds = property(lambda self: self._native.natural_bounds)

    def _need_model(self) -> "_inrs.NativeCadModel":
        if self._model is None:
            raise ValueError("this face comes from cad_faces(); read the file with cad_model() for its surface and edges")
        return self._model

    @property
    def surface_kind(self) -> Optional[str]:
        """The kind of the face's surface as this library evaluates it, or ``None``."""
        return self._need_model().surface_of(self.index)[0]

    @property
    def same_sense(self) -> bool:
        """Whether the face's outward normal is its surface's ``S_u x S_v`` (not reversed)."""
        return self._need_model().surface_of(self.index)[1]

    @property
    def surface_error(self) -> Optional[str]:
        """Why the face's surface was not read, or ``None``."""
        return self._need_model().surface_of(self.index)[2]

    def points(self, uv) -> np.ndarray:
        """The surface's points ``S(u, v)`` at the rows of ``uv`` (``(n, 2)``): an ``(n, 3)``
        array in the file's length unit (placed in the assembly, for a component)."""
        return self._surface_at(uv, normals=False)

    def normals(self, uv) -> np.ndarray:
        """The face's outward unit normals at the rows of ``uv`` (``(n, 2)``): the surface's
        ``S_u x S_v`` normalised, reversed when the face is; NaN rows where the normal is
        undefined (a cone's apex)."""
        return self._surface_at(uv, normals=True)

    def _surface_at(self, uv, normals: bool) -> np.ndarray:
        uv = np.ascontiguousarray(uv, dtype=np.float64)
        return self._need_model().surface_at(
            self.index, uv.reshape(-1, 2) if uv.size == 0 else uv, normals
        )

    @property
    def properties(self) -> "FaceProperties":
        """The face's :class:`FaceProperties` (``ValueError`` when they cannot be computed)."""
        self._need_model()
        return self._properties.face(self.index)

    @property
    def surface_area(self) -> float:
        """The face's area in space (``area`` is its ``(u, v)`` domain's)."""
        return self.properties.area

    @property
    def centroid(self) -> np.ndarray:
        """The face's centroid ``int p dA / area``, shape ``(3,)``."""
        return self.properties.centroid

    @property
    def second_moments(self) -> np.ndarray:
        """The face's second moments of area about its centroid, ``int (p - c)(p - c)^T dA``,
        shape ``(3, 3)``."""
        return self.properties.second_moments

    @property
    def edges(self) -> "list[list[CadEdge]]":
        """The face's 3-D edges, loop by loop in loop order (empty when the face has none:
        natural bounds)."""
        m = self._need_model()
        return [
            [CadEdge(m, self.index, l, e, row) for e, row in enumerate(loop)]
            for l, loop in enumerate(m.edges(self.index))
        ]

    def __repr__(self) -> str:
        return repr(self._native)


class CadEdge:
    """A 3-D edge of a :class:`CadFace`: the window ``[t0, t1]`` of its curve between its
    vertices, run backwards in its loop when ``reversed``. ``entity`` names it in the file."""

    __slots__ = ("_model", "_where", "entity", "t0", "t1", "reversed")

    def __init__(self, model, face: int, loop: int, edge: int, row) -> None:
        self._model = model
        self._where = (face, loop, edge)
        self.entity, self.t0, self.t1, self.reversed = row

    def points(self, t) -> np.ndarray:
        """The curve's points at the parameters ``t`` (1-D): an ``(n, 3)`` array."""
        t = np.ascontiguousarray(t, dtype=np.float64).reshape(-1)
        return self._model.edge_points(*self._where, t)

    def sample(self, n: int = 64) -> np.ndarray:
        """``n >= 2`` points along the edge in loop order, at equal steps of its parameter."""
        return self._model.edge_sample(*self._where, int(n))

    def __repr__(self) -> str:
        face, loop, edge = self._where
        return f"CadEdge(face={face}, loop={loop}, edge={edge}, entity={self.entity!r}, t=[{self.t0}, {self.t1}], reversed={self.reversed})"


class CadShell(NamedTuple):
    """A shell of a :class:`CadModel`: its ``index``, ``entity``, whether the file says it is
    ``closed``, and its ``faces`` (indices into :attr:`CadModel.faces`)."""

    index: int
    entity: str
    closed: bool
    faces: "list[int]"


class _CadSolidFields(NamedTuple):
    index: int
    entity: str
    shells: "list[CadShell]"


class CadSolid(_CadSolidFields):
    """A solid of a :class:`CadModel` (``part.step#solid:K``): its ``index``, ``entity`` and
    ``shells`` (the outer one first, then the voids), a named tuple of these three.

    Its mass properties (:meth:`CadModel.properties`, computed once for the whole model on
    first use, for a uniform unit density, in the file's length unit): ``properties`` (a
    :class:`SolidProperties`), ``volume``, ``area`` (of its boundary), ``centroid``,
    ``inertia``, ``principal_moments`` and ``principal_axes``. These raise ``ValueError`` with
    the library's one-line reason for a solid whose properties cannot be computed (an open
    shell, a face that cannot be integrated), and for a solid built by hand (without its model).

    :meth:`classify` says where points of space lie. A solid of :func:`cad_model` pickles as its
    file, closure tolerance and index, and comes back with its model (each process reads a file
    once); a solid made by hand has no model.
    """

    def __new__(cls, index: int, entity: str, shells: "list[CadShell]", properties=None):
        self = super().__new__(cls, index, entity, shells)
        self._properties = properties
        return self

    def __getstate__(self):
        return None  # the model stays behind

    def __reduce__(self):
        source = getattr(self, "_source", None)
        if source is None:
            return super().__reduce__()
        # Unpickled, the solid reads its file again (the model is not pickled).
        path, closure_tol = source
        return (_solid_of_file, (path, closure_tol, self.index))

    def classify(self, xyz) -> np.ndarray:
        """Where the points ``xyz`` (an ``(n, 3)`` array, or one ``(x, y, z)``) lie: an int8
        array (``0`` outside, ``1`` inside, ``2`` boundary, the codes of :meth:`Domain.classify`),
        exact away from the boundary: the signed crossings of a ray with the trimmed faces,
        each crossing checked by the face's exact 2-D test (see docs/SEMANTICS.md, "Point in a
        solid"). ``boundary`` means within ``max(file tolerance, 1e-8 x the solid's box
        diagonal)`` of a face. The solid's classifier is built on the first call and kept;
        points are classified on all cores with the GIL released; thread-safe. Raises
        ``ValueError`` for an open shell (naming its free edges), inconsistent orientation, or
        points not of shape ``(n, 3)``."""
        native = getattr(self, "_native", None)
        if native is None:
            raise ValueError("this solid has no model (built by hand): read the file with cad_model()")
        a = np.asarray(xyz, dtype=np.float64)
        one = a.ndim == 1
        if one:
            a = a.reshape(1, -1)
        if a.ndim != 2 or a.shape[1] != 3:
            raise ValueError(f"points for a solid must have shape (n, 3) (x, y, z), got {np.shape(xyz)}")
        codes = native.classify_solid(self.index, np.ascontiguousarray(a))
        return codes[0] if one else codes

    def contains_xyz(self, xyz) -> np.ndarray:
        """Whether the points ``xyz`` (``(n, 3)``) are inside the solid (boundary points are
        not): a boolean array, :meth:`classify` ``== 1``."""
        return self.classify(xyz) == 1

    @property
    def faces(self) -> "list[int]":
        """The faces of all its shells, in shell order."""
        return [f for s in self.shells for f in s.faces]

    @property
    def properties(self) -> "SolidProperties":
        """The solid's :class:`SolidProperties` (``ValueError`` when they cannot be computed)."""
        cache = getattr(self, "_properties", None)
        if cache is None:
            raise ValueError("this solid has no model (built by hand): read the file with cad_model()")
        return cache.solid(self.index)

    @property
    def volume(self) -> float:
        """The solid's volume (its outer shell's minus its voids')."""
        return self.properties.volume

    @property
    def area(self) -> float:
        """The area of its boundary (every face of every shell)."""
        return self.properties.area

    @property
    def leak_area(self) -> float:
        """The length of the net area vector ``oint n dA`` over its boundary: rounding for a
        watertight one, else about the area of the gaps between its faces (see
        :class:`SolidProperties`)."""
        return self.properties.leak_area

    @property
    def centroid(self) -> np.ndarray:
        """The centre of its volume, shape ``(3,)``."""
        return self.properties.centroid

    @property
    def inertia(self) -> np.ndarray:
        """Its inertia tensor about the centroid for unit density, shape ``(3, 3)``:
        ``I_xx = int (y^2 + z^2) dV``, ``I_xy = -int x y dV``, ..."""
        return self.properties.inertia

    @property
    def principal_moments(self) -> np.ndarray:
        """The inertia tensor's eigenvalues, ascending, shape ``(3,)``."""
        return self.properties.principal_moments

    @property
    def principal_axes(self) -> np.ndarray:
        """The principal axes as the rows of a ``(3, 3)`` array, unit vectors: row ``k`` goes
        with ``principal_moments[k]``."""
        return self.properties.principal_axes


def _frozen(values, shape) -> np.ndarray:
    a = np.array(values, dtype=np.float64).reshape(shape)
    a.setflags(write=False)
    return a


class FaceProperties(NamedTuple):
    """A face's mass properties, in the file's length unit (:meth:`CadModel.properties`):
    ``area`` (in space), ``centroid`` (``(3,)``), ``second_moments`` (``(3, 3)``,
    ``int (p - c)(p - c)^T dA`` about the centroid), ``error`` (an estimate of the integrals'
    absolute error relative to the model's size) and ``converged`` (every adaptive rule met
    its tolerance). The arrays are read-only."""

    area: float
    centroid: np.ndarray
    second_moments: np.ndarray
    error: float
    converged: bool

    @classmethod
    def _of(cls, row) -> "FaceProperties":
        area, centroid, second, error, converged = row
        return cls(area, _frozen(centroid, 3), _frozen(second, (3, 3)), error, converged)


class SolidProperties(NamedTuple):
    """A solid's mass properties for a uniform unit density, in the file's length unit
    (:meth:`CadModel.properties`): ``volume``, ``area`` (of its boundary), ``centroid``
    (``(3,)``), ``inertia`` (``(3, 3)`` about the centroid: ``I_xx = int (y^2 + z^2) dV``,
    ``I_xy = -int x y dV``), ``principal_moments`` (``(3,)``, ascending),
    ``principal_axes`` (``(3, 3)``, row ``k`` the unit axis of moment ``k``), ``error`` (the
    worst of its faces'), ``converged`` and ``leak_area`` (the length of the net area vector
    ``oint n dA`` over its boundary: rounding for a watertight one, else about the area of
    the gaps between its faces, so that the volume and moments are defined only to about
    ``leak_area`` times the part's size). The arrays are read-only."""

    volume: float
    area: float
    centroid: np.ndarray
    inertia: np.ndarray
    principal_moments: np.ndarray
    principal_axes: np.ndarray
    error: float
    converged: bool
    leak_area: float

    @classmethod
    def _of(cls, row) -> "SolidProperties":
        volume, area, centroid, inertia, moments, axes, error, converged, leak_area = row
        return cls(
            volume,
            area,
            _frozen(centroid, 3),
            _frozen(inertia, (3, 3)),
            _frozen(moments, 3),
            _frozen(axes, (3, 3)),
            error,
            converged,
            leak_area,
        )


class CadProperties(NamedTuple):
    """The mass properties of every face and solid of a :class:`CadModel`
    (:meth:`CadModel.properties`), in the model's face and solid order: ``faces`` (a
    :class:`FaceProperties` each, ``None`` for a face whose properties cannot be computed) and
    ``solids`` (a :class:`SolidProperties` each, or ``None``), with ``face_errors`` and
    ``solid_errors`` (the library's one-line reason where the entry is ``None``, else
    ``None``)."""

    faces: "list[Optional[FaceProperties]]"
    solids: "list[Optional[SolidProperties]]"
    face_errors: "list[Optional[str]]"
    solid_errors: "list[Optional[str]]"


class _ModelProperties:
    """A model's :class:`CadProperties`, from one native call on first use (thread-safe)."""

    __slots__ = ("_native", "_value", "_lock")

    def __init__(self, native: "_inrs.NativeCadModel") -> None:
        self._native = native
        self._value: Optional[CadProperties] = None
        self._lock = threading.Lock()

    def get(self) -> CadProperties:
        value = self._value
        if value is None:
            with self._lock:
                if self._value is None:
                    faces, solids = self._native.properties()  # the GIL is released inside
                    self._value = CadProperties(
                        [None if r is None else FaceProperties._of(r) for r, _ in faces],
                        [None if r is None else SolidProperties._of(r) for r, _ in solids],
                        [e for _, e in faces],
                        [e for _, e in solids],
                    )
                value = self._value
        return value

    def face(self, k: int) -> FaceProperties:
        p = self.get()
        if p.faces[k] is None:
            raise ValueError(p.face_errors[k])
        return p.faces[k]

    def solid(self, k: int) -> SolidProperties:
        p = self.get()
        if p.solids[k] is None:
            raise ValueError(p.solid_errors[k])
        return p.solids[k]


class CadModel:
    """A STEP or IGES file read once into a boundary representation: ``faces``
    (:class:`CadFace`, with their surfaces and edges), ``shells`` (:class:`CadShell`) and
    ``solids`` (:class:`CadSolid`), each in OpenCASCADE's explorer order of the same file;
    ``format`` (``"STEP"`` or ``"IGES"``), ``tolerance`` (the file's stated tolerance in its
    length unit, or ``None``) and ``length_unit`` (``(name, millimetres per unit)``);
    :meth:`properties` gives the faces' and solids' mass properties."""

    __slots__ = ("_native", "_properties", "faces", "shells", "solids")

    def __init__(
        self, native: "_inrs.NativeCadModel", source: "Optional[Tuple[str, Optional[float]]]" = None
    ) -> None:
        self._native = native
        self._properties = _ModelProperties(native)
        self.faces = [
            CadFace(face, None if domain is None else Domain(domain), native, self._properties)
            for face, domain in native.faces()
        ]
        self.shells = [
            CadShell(k, entity, closed, list(faces)) for k, (entity, closed, faces) in enumerate(native.shells())
        ]
        self.solids = [
            CadSolid(k, entity, [self.shells[s] for s in shells], self._properties)
            for k, (entity, shells) in enumerate(native.solids())
        ]
        for solid in self.solids:
            solid._native = native
            solid._source = source

    format = property(lambda self: self._native.format())
    tolerance = property(lambda self: self._native.tolerance())
    #: ``(name, millimetres per unit)`` of the file's length unit (lengths stay in it), or
    #: ``None`` when the file states none.
    length_unit = property(lambda self: self._native.length_unit())

    def properties(self) -> CadProperties:
        """The mass properties of every face and solid (:class:`CadProperties`): area,
        centroid and second moments of each face; volume, boundary area, centroid, inertia
        tensor (unit density), principal moments and axes of each solid; ``None`` entries with
        their reasons where they cannot be computed. Computed by the library on the first call
        (with the GIL released: by the divergence theorem over the solids' faces and Green's
        theorem on each face's ``(u, v)`` loops, adaptive Gauss-Legendre) and kept: the faces'
        and solids' attributes (``face.centroid``, ``solid.volume``, ...) read the same.

        >>> m = inrs.cad_model("fixtures/cad/box_void.step")  # doctest: +SKIP
        >>> m.properties().solids[0].volume  # doctest: +SKIP
        59.81120979...
        """
        return self._properties.get()

    def __repr__(self) -> str:
        return f"CadModel({self.format}, {len(self.solids)} solids, {len(self.shells)} shells, {len(self.faces)} faces)"


def cad_model(path: Union[str, os.PathLike], closure_tol: Optional[float] = None) -> CadModel:
    """A STEP (``.step``, ``.stp``) or IGES (``.igs``, ``.iges``) file as a :class:`CadModel`:
    its faces (each with its ``(u, v)`` domain, surface and 3-D edges), shells and solids, from
    one read of the file. ``closure_tol`` is the relative closure tolerance of
    :meth:`Domain.load`. Raises ``OSError`` if the file cannot be read and ``ValueError`` if it
    is not STEP or IGES.

    >>> import inrs, numpy as np
    >>> m = inrs.cad_model("fixtures/cad/plate.step")  # doctest: +SKIP
    >>> m.faces[0].points(np.array([[1.0, 2.0]]))  # doctest: +SKIP
    """
    path = os.fspath(path)
    return CadModel(_inrs.NativeCadModel(path, closure_tol), (os.path.abspath(path), closure_tol))


@functools.lru_cache(maxsize=8)
def _model_of_file(path: str, closure_tol: Optional[float]) -> CadModel:
    """The file ``path`` read once per process (the models of unpickled solids)."""
    return cad_model(path, closure_tol)


def _solid_of_file(path: str, closure_tol: Optional[float], index: int) -> "CadSolid":
    """Solid ``index`` of the file ``path`` read with ``closure_tol`` (how a pickled solid comes
    back: a process reads each file once, and the solid's classifier is built once)."""
    return _model_of_file(path, closure_tol).solids[index]


def cad_faces(path: Union[str, os.PathLike], closure_tol: Optional[float] = None) -> "list[CadFace]":
    """The faces of a STEP (``.step``, ``.stp``) or IGES (``.igs``, ``.iges``) file, in the
    order OpenCASCADE's face explorer visits them (as ``inrs info --domain part.step`` lists
    them), each with its domain, from one read of the file (:func:`cad_model` gives their
    surfaces and edges too).

    Each :class:`CadFace` says whether the face reads (its loops, curves, ``(u, v)`` area and
    box, and ``domain``) or why it is refused (``error``); ``closure_tol`` is the relative
    closure tolerance of :meth:`Domain.load`. Raises ``OSError`` if the file cannot be read
    and ``ValueError`` if it is not STEP or IGES.
    """
    return [
        CadFace(native, None if domain is None else Domain(domain))
        for native, domain in _inrs.cad_faces(os.fspath(path), closure_tol)
    ]


def convex_domain(
    curve: Union[str, os.PathLike],
    free_index: int,
    box: Sequence[float],
    *,
    curve_index: int = 0,
    sign: str = "auto",
    tol: float = DEFAULT_CONVEX_TOLERANCE,
    max_level: int = 10,
) -> dict:
    """Where control point ``free_index`` of a curve may move, within ``box``, keeping the sign
    of the curvature (planar curve) or torsion (space curve), as ``inrs convex-domain``
    computes it (Ginnis, Karousos and Kaklis 2009).

    ``curve`` is a curve or domain JSON file (curve ``curve_index`` of a domain file), as
    ``--curve`` takes it, or that JSON text itself (a string starting with ``{``). ``box`` is
    ``(xmin, xmax, ymin, ymax)`` in the plane or ``(xmin, xmax, ymin, ymax, zmin, zmax)`` in
    space. ``sign`` is ``"positive"``, ``"negative"`` or ``"auto"`` (the curve's own sign at
    the middle of its first piece). Refinement stops when the relative growth is at most
    ``tol`` or at level ``max_level`` (at most 20).

    Returns a dict: ``levels`` (a list of dicts ``level, inequalities, measure, abs_error,
    rel_error``; the errors are ``None`` after an empty level), ``outer_measure`` (area or
    volume of the sampled outer bound), ``outcome`` (``"Converged"``, ``"Empty"`` or
    ``"NotConverged"``), ``sign`` kept (``"Positive"`` or ``"Negative"``), ``dimension`` (2 or
    3) and ``polygon``, the last inner polygon's vertices as an ``(N, 2)`` array (``None`` in
    space). An unreadable file raises ``OSError``; a bad curve, box, index, sign, tolerance or
    level ``ValueError``.
    """
    for name, value in (("free_index", free_index), ("curve_index", curve_index), ("max_level", max_level)):
        if operator.index(value) < 0:
            raise ValueError(f"{name} must be non-negative, got {value}")
    if isinstance(curve, str) and curve.lstrip().startswith("{"):
        path, text = None, curve
    else:
        path, text = os.fspath(curve), None
    return _inrs.convex_domain(
        path,
        text,
        operator.index(curve_index),
        operator.index(free_index),
        [float(v) for v in box],
        sign,
        float(tol),
        operator.index(max_level),
    )

"""Type stubs of the native module (the public API is in ``inrs``)."""

from typing import List, Optional, Tuple

import numpy as np
import numpy.typing as npt

OUTSIDE: int
INSIDE: int
BOUNDARY: int
DEFAULT_TOLERANCE: float
DEFAULT_CONVEX_TOLERANCE: float
FAST_METHOD_MIN_POINTS: int
MAX_CELLS: int
MAX_EDGES: int
MAX_CUBATURE_DEGREE: int
__version__: str

class LoopSummary:
    """One boundary loop: the curves ``first_curve..=last_curve``."""

    @property
    def first_curve(self) -> int: ...
    @property
    def last_curve(self) -> int: ...
    @property
    def closed(self) -> bool: ...
    @property
    def gap(self) -> float: ...
    @property
    def signed_area(self) -> float: ...

class CadFace:
    """One face of a STEP or IGES file."""

    @property
    def index(self) -> int: ...
    @property
    def entity(self) -> str: ...
    @property
    def surface(self) -> str: ...
    @property
    def loops(self) -> int: ...
    @property
    def curves(self) -> int: ...
    @property
    def area(self) -> float: ...
    @property
    def bbox(self) -> Optional[Tuple[float, float, float, float]]: ...
    @property
    def error(self) -> Optional[str]: ...
    @property
    def closure_tolerance(self) -> float: ...
    @property
    def width(self) -> float: ...
    @property
    def narrow(self) -> bool: ...
    @property
    def pcurve_deviation(self) -> Optional[float]: ...
    @property
    def natural_bounds(self) -> bool: ...

class NativeCadModel:
    """A CAD file read once: faces, surfaces, edges, shells, solids."""

    def __init__(self, path: str, closure_tol: Optional[float] = None) -> None: ...
    def format(self) -> str: ...
    def tolerance(self) -> Optional[float]: ...
    def length_unit(self) -> Optional[Tuple[str, float]]: ...
    def faces(self) -> list[Tuple[CadFace, Optional["NativeDomain"]]]: ...
    def shells(self) -> list[Tuple[str, bool, list[int]]]: ...
    def solids(self) -> list[Tuple[str, list[int]]]: ...
    def surface_of(self, face: int) -> Tuple[Optional[str], bool, Optional[str]]: ...
    def points(self, face: int, uv: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def normals(self, face: int, uv: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def edges(self, face: int) -> list[list[Tuple[str, float, float, bool]]]: ...
    def edge_points(
        self, face: int, loop: int, edge: int, t: npt.NDArray[np.float64]
    ) -> npt.NDArray[np.float64]: ...
    def edge_sample(self, face: int, loop: int, edge: int, n: int) -> npt.NDArray[np.float64]: ...
    def classify_solid(self, solid: int, xyz: npt.NDArray[np.float64]) -> npt.NDArray[np.int8]: ...

def classify_many(
    domains: list["NativeDomain"],
    shared: Optional[npt.NDArray[np.float64]],
    each: Optional[list[npt.NDArray[np.float64]]],
    method: str,
    tol: float,
    fill_rule: str,
    threads: int,
) -> Tuple[list[Optional[npt.NDArray[np.int8]]], list[Optional[str]]]: ...

def cad_faces(
    path: str, closure_tol: Optional[float] = None
) -> list[Tuple[CadFace, Optional["NativeDomain"]]]: ...

class DomainSummary:
    """Facts about a domain, as ``inrs info`` prints them."""

    @property
    def curves(self) -> int: ...
    @property
    def bezier_pieces(self) -> int: ...
    @property
    def max_degree(self) -> int: ...
    @property
    def rational(self) -> bool: ...
    @property
    def loops(self) -> list[LoopSummary]: ...
    @property
    def filled_area(self) -> Optional[float]: ...
    @property
    def signed_area(self) -> float: ...
    @property
    def areas_converged(self) -> bool: ...
    @property
    def bounds(self) -> Tuple[float, float, float, float]: ...

class NativeDomain:
    @staticmethod
    def load(path: str, closure_tol: Optional[float] = None) -> "NativeDomain": ...
    @staticmethod
    def from_json(text: str) -> "NativeDomain": ...
    @staticmethod
    def from_curves(
        curves: list[
            Tuple[
                int,
                npt.NDArray[np.float64],
                npt.NDArray[np.float64],
                Optional[npt.NDArray[np.float64]],
            ]
        ],
        name: Optional[str] = None,
        closure_tol: Optional[float] = None,
    ) -> "NativeDomain": ...
    def to_json(self) -> str: ...
    @property
    def name(self) -> Optional[str]: ...
    def summary(self) -> "DomainSummary": ...
    def classify_pairs(
        self, xy: npt.NDArray[np.float64], method: str, tol: float, fill_rule: str, threads: int
    ) -> npt.NDArray[np.int8]: ...
    def classify_columns(
        self,
        x: npt.NDArray[np.float64],
        y: npt.NDArray[np.float64],
        method: str,
        tol: float,
        fill_rule: str,
        threads: int,
    ) -> npt.NDArray[np.int8]: ...
    def winding_columns(
        self,
        x: npt.NDArray[np.float64],
        y: npt.NDArray[np.float64],
        tol: float,
        threads: int,
        algorithm: str = ...,
    ) -> npt.NDArray[np.float64]: ...
    def flatten(self, accuracy: float) -> list[npt.NDArray[np.float64]]: ...

class NativeSpline:
    @staticmethod
    def from_json(text: str) -> "NativeSpline": ...
    def to_json(self) -> str: ...
    def summary(self) -> Tuple[int, int, int]: ...
    @property
    def space(self) -> str: ...
    def evaluate_columns(
        self, x: npt.NDArray[np.float64], y: npt.NDArray[np.float64], derivatives: bool, threads: int
    ) -> npt.NDArray[np.float64]: ...

class FitPlan:
    def __init__(self, domain: NativeDomain, ny: int, degree: int, refine: str = ...) -> None: ...
    def points(self) -> npt.NDArray[np.float64]: ...
    def finish(self, values: npt.NDArray[np.float64]) -> NativeSpline: ...

def sample(domain: NativeDomain, ny: int) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.bool_]]: ...
def sample_halton(domain: NativeDomain, count: int) -> npt.NDArray[np.float64]: ...
def mesh(domain: NativeDomain, ny: int, refine: str = ...) -> dict: ...
def interpolate(
    domain: NativeDomain, xy: npt.NDArray[np.float64], z: npt.NDArray[np.float64], space: str
) -> Tuple[NativeSpline, int, list[int]]: ...
def halton_points(
    n: int, bounds: Tuple[float, float, float, float], start: int
) -> npt.NDArray[np.float64]: ...
def convex_domain(
    path: Optional[str],
    text: Optional[str],
    curve_index: int,
    free_index: int,
    bbox: list[float],
    sign: str,
    tol: float,
    max_level: int,
) -> dict: ...

def cell_coverage(
    domain: NativeDomain,
    x_edges: npt.NDArray[np.float64],
    y_edges: npt.NDArray[np.float64],
    rows: Optional[Tuple[int, int]],
    centroids: bool,
    apertures: bool,
    fill_rule: str,
    threads: int,
    boundary: bool = False,
    face_centroids: bool = False,
    axisymmetric: Optional[str] = None,
) -> Tuple[
    npt.NDArray[np.float64],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
]:
    """Exact cell coverage of the grid ``x_edges`` x ``y_edges`` (the whole grid, or the rows
    ``j0 .. j1`` when ``rows = (j0, j1)``) under ``fill_rule`` (``even-odd`` or ``nonzero``),
    revolved about ``axisymmetric`` (``None``, ``'x'`` or ``'y'``): ``(fractions (R, nx),
    centroids (R, nx, 2), x_apertures (R, nx + 1), y_apertures (R + 1, nx), boundary_lengths
    (R, nx), boundary_centroids (R, nx, 2), boundary_normals (R, nx, 2), x_face_centroids
    (R, nx + 1), y_face_centroids (R + 1, nx))`` for ``R`` rows, ``None`` for those not asked
    for."""
    ...

def material_coverage(
    domains: List[NativeDomain],
    x_edges: npt.NDArray[np.float64],
    y_edges: npt.NDArray[np.float64],
    replace: bool,
    centroids: bool,
    apertures: bool,
    fill_rule: str,
    threads: int,
    boundary: bool = False,
    face_centroids: bool = False,
    axisymmetric: Optional[str] = None,
) -> Tuple[
    npt.NDArray[np.float64],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
    Optional[npt.NDArray[np.float64]],
]:
    """Several materials on one grid (``MaterialCoverage::new`` then ``all``, the GIL
    released): the arrays of :func:`cell_coverage`, each with a leading axis of
    ``len(domains)``; with ``replace`` later domains replace earlier ones. ``ValueError`` with
    the library's message (and for an empty list)."""
    ...

class NativeMaterials:
    """Several materials prepared on one grid (``MaterialCoverage::new``), whose bands of rows
    are computed one material at a time (the blocks of ``inrs.dask.cell_fractions``)."""

    def __init__(
        self,
        domains: List[NativeDomain],
        x_edges: npt.NDArray[np.float64],
        y_edges: npt.NDArray[np.float64],
        fill_rule: str,
        replace: bool,
    ) -> None: ...
    def __len__(self) -> int:
        """The number of materials."""
        ...
    def rows(
        self, k: int, j0: int, j1: int, axisymmetric: Optional[str] = None
    ) -> npt.NDArray[np.float64]:
        """Material ``k``'s fractions of the rows ``j0 .. j1``, shape ``(j1 - j0, nx)``, on the
        calling thread (``MaterialCoverage::rows``), the GIL released."""
        ...

def coverage_band_rows(
    nx: int,
    ny: int,
    centroids: bool,
    apertures: bool,
    boundary: bool = False,
    face_centroids: bool = False,
) -> int:
    """The rows of each band the library cuts a grid of ``nx`` x ``ny`` cells into
    (``inrs::coverage::band_rows`` on this process's threads): about 8 MiB of output a band,
    at least one row, at least four bands a thread when the grid has the rows."""
    ...

class CubatureRule:
    """A positive interior cubature rule of a domain (``inrs.cubature``, ``Domain.integrate``)."""

    def __init__(self, domain: NativeDomain, degree: int) -> None: ...
    def nodes(self) -> npt.NDArray[np.float64]:
        """The nodes, shape ``(N, 2)``."""
        ...
    def weights(self) -> npt.NDArray[np.float64]:
        """The weights, shape ``(N,)``, all positive."""
        ...
    @property
    def degree(self) -> int: ...
    @property
    def residual(self) -> float: ...
    @property
    def candidates(self) -> int: ...
    def integrate_values(self, values: npt.NDArray[np.float64]) -> float:
        """``sum_i w_i values[i]``; ``ValueError`` for another length or a value that is not
        finite (naming the node)."""
        ...

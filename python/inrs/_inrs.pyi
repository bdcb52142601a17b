"""Type stubs of the native module (the public API is in ``inrs``)."""

from typing import Optional, Tuple

import numpy as np
import numpy.typing as npt

OUTSIDE: int
INSIDE: int
BOUNDARY: int
DEFAULT_TOLERANCE: float
FAST_METHOD_MIN_POINTS: int
__version__: str

class NativeDomain:
    @staticmethod
    def load(path: str) -> "NativeDomain": ...
    @staticmethod
    def from_json(text: str) -> "NativeDomain": ...
    def to_json(self) -> str: ...
    @property
    def name(self) -> Optional[str]: ...
    def summary(
        self,
    ) -> Tuple[
        int,
        int,
        Optional[float],
        float,
        Tuple[float, float, float, float],
        list[Tuple[int, int, bool, float]],
    ]: ...
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
        self, x: npt.NDArray[np.float64], y: npt.NDArray[np.float64], tol: float, threads: int
    ) -> npt.NDArray[np.float64]: ...
    def kernel_seconds(self, xy: npt.NDArray[np.float64], threads: int) -> float: ...
    def flatten(self, accuracy: float) -> list[npt.NDArray[np.float64]]: ...

class NativeSpline:
    @staticmethod
    def from_json(text: str) -> "NativeSpline": ...
    def to_json(self) -> str: ...
    def summary(self) -> Tuple[int, int, int]: ...
    def evaluate_columns(
        self, x: npt.NDArray[np.float64], y: npt.NDArray[np.float64], derivatives: bool, threads: int
    ) -> npt.NDArray[np.float64]: ...

class FitPlan:
    def __init__(self, domain: NativeDomain, ny: int, degree: int, refine: str = ...) -> None: ...
    def points(self) -> npt.NDArray[np.float64]: ...
    def finish(self, values: npt.NDArray[np.float64]) -> NativeSpline: ...

def sample(domain: NativeDomain, ny: int) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.bool_]]: ...
def mesh(domain: NativeDomain, ny: int, refine: str = ...) -> dict: ...
def halton_points(
    n: int, bounds: Tuple[float, float, float, float], start: int
) -> npt.NDArray[np.float64]: ...

"""Shared helpers: the repository's fixtures, Halton points as the inRS paper defines them,
and the command-line tool (built with cargo) for comparisons. The package itself is imported
where it is used, so that tests of OCC-only helpers (test_cad_parts.py) run without it."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "fixtures"
PAPER = ["s3_m_shape", "s4_disk_ellipse_segment", "s5_lune", "circle", "l_shape", "leaf_cubic"]


def halton(n: int, box) -> np.ndarray:
    """The first ``n`` Halton points (bases 2, 3, starting at (0, 0)) of ``(xmin, xmax, ymin,
    ymax)``, by the package's generator (checked against exact values in test_halton.py)."""
    import inrs

    xmin, xmax, ymin, ymax = box
    return inrs.halton_points(n, (xmin, ymin, xmax, ymax))


def require(module: str):
    """``module``, imported; CI installs the optional ones tests need (dask, distributed,
    xarray: ``.ci/run``), so there (with ``INRS_REQUIRE_SYSTEM_FILES=1``) a missing one fails,
    elsewhere it skips only the tests that need it."""
    if os.environ.get("INRS_REQUIRE_SYSTEM_FILES") == "1":
        return __import__(module)
    return pytest.importorskip(module)


def circle(cx: float, cy: float, r: float):
    """The disc of radius ``r`` about ``(cx, cy)`` as an ``inrs.Domain`` (the JSON circle)."""
    import inrs

    return inrs.Domain.from_json(
        f'{{"curves": [{{"circle": {{"center": [{cx}, {cy}], "radius": {r}}}}}]}}'
    )


def fixture_meta(name: str) -> dict:
    return json.loads((FIXTURES / "inrs-paper" / f"{name}.json").read_text())


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    """The ``inrs`` binary: ``$INRS_CLI`` if set, else built by cargo (quick when up to date)."""
    given = os.environ.get("INRS_CLI")
    if given:
        path = pathlib.Path(given)
        if not path.is_file():
            raise FileNotFoundError(f"INRS_CLI={given} is not a file")
        return path
    subprocess.run(["cargo", "build", "--quiet", "-p", "inrs-cli"], cwd=ROOT, check=True)
    return ROOT / "target" / "debug" / "inrs"

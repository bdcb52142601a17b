"""Cell fractions (``Domain.cell_fractions``, ``inrs.dask.cell_fractions``) against closed
forms: circle segments on the unit disc, the annulus' area, rectangles' overlaps with cells."""

import math
import threading
import time

import numpy as np
import pytest

import inrs
from conftest import FIXTURES, require


DISC = '{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}'
ANNULUS = (
    '{"curves": [{"circle": {"center": [0, 0], "radius": 1}},'
    ' {"circle": {"center": [0, 0], "radius": 2}}]}'
)


def quadrant_area(x: float, y: float) -> float:
    """Area of the unit disc within ``[0, x] x [0, y]`` (signed for negative ``x``, ``y``, so
    that inclusion-exclusion over a rectangle's corners gives its overlap with the disc).

    For ``x, y >= 0`` (clipped to 1): ``x y`` when the corner is inside the circle; otherwise
    the rectangle ``[0, x0] x [0, y]`` below the circle's crossing ``x0 = sqrt(1 - y^2)`` with
    the line ``Y = y``, plus the circle segment ``int_x0^x sqrt(1 - t^2) dt`` with the
    antiderivative ``(t sqrt(1 - t^2) + asin t) / 2``."""
    sign = math.copysign(1.0, x) * math.copysign(1.0, y)
    x, y = min(abs(x), 1.0), min(abs(y), 1.0)
    if x * x + y * y <= 1.0:
        return sign * x * y
    x0 = math.sqrt(1.0 - y * y)

    def g(t: float) -> float:
        return 0.5 * (t * math.sqrt(max(0.0, 1.0 - t * t)) + math.asin(t))

    return sign * (x0 * y + g(x) - g(x0))


def disc_fractions(xs, ys) -> np.ndarray:
    """The unit disc's fraction of every cell, by inclusion-exclusion of ``quadrant_area``."""
    out = np.empty((len(ys) - 1, len(xs) - 1))
    for j in range(len(ys) - 1):
        for i in range(len(xs) - 1):
            a, b, c, d = xs[i], xs[i + 1], ys[j], ys[j + 1]
            area = quadrant_area(b, d) - quadrant_area(a, d) - quadrant_area(b, c) + quadrant_area(a, c)
            out[j, i] = area / ((b - a) * (d - c))
    return out


def irregular_edges(seed: int, lo: float, hi: float) -> np.ndarray:
    """Edges from ``lo`` past ``hi`` with random gaps between 0.07 and 0.3."""
    gaps = np.random.default_rng(seed).uniform(0.07, 0.3, size=200)
    edges = lo + np.concatenate([[0.0], np.cumsum(gaps)])
    return edges[: np.searchsorted(edges, hi) + 1]


@pytest.mark.parametrize(
    "xs, ys",
    [
        (np.linspace(-1, 1, 17), np.linspace(-1, 1, 17)),  # 16 x 16, the circle through vertices
        (irregular_edges(1, -1.3, 1.3), irregular_edges(2, -1.2, 1.25)),
    ],
    ids=["uniform-16", "irregular"],
)
def test_unit_disc_equals_circle_segments_in_every_cell(xs, ys):
    d = inrs.Domain.from_json(DISC)
    got = d.cell_fractions(xs, ys)
    want = disc_fractions(xs, ys)
    assert got.dtype == np.float64 and got.shape == (len(ys) - 1, len(xs) - 1)
    # Fractions are areas over the cell's area: 1e-12 of the cell's area.
    assert np.max(np.abs(got - want)) <= 1e-12
    # Cells the circle misses are exactly 0 or 1, and some cells are cut.
    assert set(np.unique(got[(want == 0) | (want == 1)])) <= {0.0, 1.0}
    assert np.count_nonzero((got > 0) & (got < 1)) >= 12


def test_annulus_sums_to_three_pi_with_exact_hole_and_ring_cells():
    d = inrs.Domain.from_json(ANNULUS)
    xs, ys = irregular_edges(3, -2.4, 2.4), np.linspace(-2.3, 2.2, 41)
    f = d.cell_fractions(xs, ys)
    areas = np.outer(np.diff(ys), np.diff(xs))
    assert math.fsum((f * areas).ravel()) == pytest.approx(3 * math.pi, rel=1e-13, abs=0)
    assert f.min() >= 0.0 and f.max() <= 1.0
    # Cells wholly within the hole are 0, wholly within the ring are 1 (their corners' radii).
    cx, cy = np.meshgrid(xs, ys)
    r = np.hypot(cx, cy)
    rmax = np.maximum.reduce([r[:-1, :-1], r[1:, :-1], r[:-1, 1:], r[1:, 1:]])
    near = np.hypot(np.clip(0, cx[:-1, :-1], cx[1:, 1:]), np.clip(0, cy[:-1, :-1], cy[1:, 1:]))
    assert np.all(f[rmax < 1] == 0.0)
    assert np.all(f[(near > 1) & (rmax < 2)] == 1.0)
    assert np.all(f[near > 2] == 0.0)


def test_nonzero_fills_nested_circles_of_one_orientation():
    # ANNULUS: two counter-clockwise circles (radii 1 and 2). Nonzero fills the disc of
    # radius 2, whose fraction of a cell is the unit disc's in the cell scaled by 1/2.
    d = inrs.Domain.from_json(ANNULUS)
    xs, ys = irregular_edges(3, -2.4, 2.4), np.linspace(-2.3, 2.2, 41)
    areas = np.outer(np.diff(ys), np.diff(xs))
    f = d.cell_fractions(xs, ys, fill_rule="nonzero")
    assert np.abs(f - disc_fractions(xs / 2, ys / 2)).max() <= 1e-12
    assert math.fsum((f * areas).ravel()) == pytest.approx(4 * math.pi, rel=1e-13, abs=0)
    even_odd = d.cell_fractions(xs, ys, fill_rule="even-odd")
    assert np.array_equal(even_odd, d.cell_fractions(xs, ys))
    assert math.fsum((even_odd * areas).ravel()) == pytest.approx(3 * math.pi, rel=1e-13, abs=0)
    # Only the outer circle bounds the filled set: the apertures are the disc of radius 2's.
    disc2 = inrs.Domain.from_json(DISC.replace('"radius": 1', '"radius": 2'))
    got = d.cell_fractions(xs, ys, apertures=True, fill_rule="nonzero")
    want = disc2.cell_fractions(xs, ys, apertures=True)
    assert np.abs(got.x_apertures - want.x_apertures).max() <= 1e-12
    assert np.abs(got.y_apertures - want.y_apertures).max() <= 1e-12
    assert np.abs(got.fractions - want.fractions).max() <= 1e-12
    with pytest.raises(ValueError, match="unknown fill rule"):
        d.cell_fractions(xs, ys, fill_rule="winding")


def rectangle_coverage(rect, xs, ys):
    """Fractions, centroids and apertures of the rectangle ``(x0, x1, y0, y1)`` on the grid,
    from the overlaps of intervals; a face on the rectangle's side takes the value just to its
    right (vertical) or just above it (horizontal)."""
    x0, x1, y0, y1 = rect

    def overlap(a, b, lo, hi):
        return max(0.0, min(b, hi) - max(a, lo)), (max(a, lo) + min(b, hi)) / 2

    ny, nx = len(ys) - 1, len(xs) - 1
    f = np.zeros((ny, nx))
    c = np.full((ny, nx, 2), np.nan)
    xa = np.zeros((ny, nx + 1))
    ya = np.zeros((ny + 1, nx))
    for j in range(ny):
        h, my = overlap(ys[j], ys[j + 1], y0, y1)
        for i in range(nx):
            w, mx = overlap(xs[i], xs[i + 1], x0, x1)
            f[j, i] = w * h / ((xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]))
            if f[j, i] > 0:
                c[j, i] = (mx, my)
        for i in range(nx + 1):
            inside = x0 <= xs[i] < x1  # the line just to the right of x_i
            xa[j, i] = h / (ys[j + 1] - ys[j]) if inside else 0.0
    for j in range(ny + 1):
        for i in range(nx):
            w, _ = overlap(xs[i], xs[i + 1], x0, x1)
            inside = y0 <= ys[j] < y1  # the line just above y_j
            ya[j, i] = w / (xs[i + 1] - xs[i]) if inside else 0.0
    return f, c, xa, ya


def square(x0, x1, y0, y1):
    pts = [[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]
    return inrs.Domain.from_curves([(1, [0, 0] + list(range(1, 4)) + [4, 4], pts)])


@pytest.mark.parametrize(
    "rect, xs, ys",
    [
        ((1.0, 3.0, 1.0, 3.0), np.arange(5.0), np.arange(5.0)),  # on the grid lines
        ((0.5, 2.25, 0.75, 3.5), np.array([0, 1, 1.5, 2.5, 4]), np.array([-1, 0.5, 1, 2, 3, 4.5])),
    ],
    ids=["aligned", "offset"],
)
def test_rectangle_centroids_and_apertures_are_its_overlaps(rect, xs, ys):
    d = square(*rect)
    assert d.area == pytest.approx((rect[1] - rect[0]) * (rect[3] - rect[2]), rel=1e-15)
    got = d.cell_fractions(xs, ys, centroids=True, apertures=True)
    assert isinstance(got, inrs.CellCoverage)
    ny, nx = len(ys) - 1, len(xs) - 1
    assert got.fractions.shape == (ny, nx)
    assert got.centroids.shape == (ny, nx, 2)
    assert got.x_apertures.shape == (ny, nx + 1)
    assert got.y_apertures.shape == (ny + 1, nx)
    f, c, xa, ya = rectangle_coverage(rect, xs, ys)
    assert np.allclose(got.fractions, f, rtol=0, atol=1e-14)
    assert np.array_equal(np.isnan(got.centroids), np.isnan(c))
    assert np.allclose(got.centroids, c, rtol=0, atol=1e-14, equal_nan=True)
    assert np.allclose(got.x_apertures, xa, rtol=0, atol=1e-14)
    assert np.allclose(got.y_apertures, ya, rtol=0, atol=1e-14)
    # Each part alone; the fractions alone are a bare array.
    only_c = d.cell_fractions(xs, ys, centroids=True)
    assert only_c.x_apertures is None and only_c.y_apertures is None
    assert np.array_equal(only_c.centroids, got.centroids, equal_nan=True)
    only_a = d.cell_fractions(xs, ys, apertures=True)
    assert only_a.centroids is None and np.array_equal(only_a.y_apertures, got.y_apertures)
    bare = d.cell_fractions(xs, ys)
    assert isinstance(bare, np.ndarray) and np.array_equal(bare, got.fractions)


def test_threads_and_edge_layouts_give_the_same_values():
    d = inrs.Domain.load(FIXTURES / "axom-contours" / "butterfly.svg")
    b = d.bounds
    xs, ys = np.linspace(b[0], b[2], 97), np.linspace(b[1], b[3], 65)
    f = d.cell_fractions(xs, ys)
    areas = np.outer(np.diff(ys), np.diff(xs))
    assert math.fsum((f * areas).ravel()) == pytest.approx(d.area, rel=1e-12)
    # One thread (one band) and all threads; edges as a list or a strided view.
    assert np.array_equal(d.cell_fractions(list(xs), ys, threads=1), f)
    wide = np.empty(2 * len(xs))
    wide[::2] = xs  # a strided view is read as it is
    assert np.array_equal(d.cell_fractions(wide[::2], ys, threads=1), f)


def test_the_gil_is_released_while_the_library_works():
    # Another Python thread keeps running during the call: with the GIL held it could not
    # record a time strictly inside the call (only before it enters Rust or after it returns).
    d = inrs.Domain.from_json(DISC)
    xs, ys = np.linspace(-1, 1, 4097), np.linspace(-1, 1, 1025)
    stamps, stop = [], threading.Event()

    def tick():
        while not stop.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0.001)

    ticker = threading.Thread(target=tick)
    ticker.start()
    try:
        time.sleep(0.01)
        t0 = time.perf_counter()
        # With centroids and apertures: the fractions alone now take about 10 ms here.
        d.cell_fractions(xs, ys, centroids=True, apertures=True, threads=1)
        t1 = time.perf_counter()
    finally:
        stop.set()
        ticker.join()
    assert t1 - t0 > 0.04, f"the call took {t1 - t0:.3f} s: too short to tell"
    inside = [t for t in stamps if t0 + 0.01 < t < t1 - 0.01]
    assert len(inside) >= 3, f"{len(inside)} ticks in a call of {t1 - t0:.3f} s"


def test_dask_blocks_equal_the_eager_array_bit_for_bit():
    require("dask")
    import inrs.dask

    d = inrs.Domain.load(FIXTURES / "axom-contours" / "butterfly.svg")
    b = d.bounds
    xs, ys = np.linspace(b[0], b[2], 71), np.linspace(b[1], b[3], 54)
    lazy = inrs.dask.cell_fractions(d, xs, ys, row_chunk=7)
    assert lazy.dtype == np.float64 and lazy.shape == (53, 70)
    assert lazy.chunks == ((7,) * 7 + (4,), (70,))
    assert np.array_equal(lazy.compute(), d.cell_fractions(xs, ys))
    disc = inrs.Domain.from_json(DISC)
    xs, ys = np.linspace(-1, 1, 17), irregular_edges(4, -1.2, 1.2)
    want = disc.cell_fractions(xs, ys)
    for chunk in (1, 3, 100, None):
        assert np.array_equal(inrs.dask.cell_fractions(disc, xs, ys, row_chunk=chunk).compute(), want)


def test_dask_blocks_default_to_the_librarys_bands():
    require("dask")
    import inrs.dask
    from inrs import _inrs

    # The library's one rule (``band_rows``): about 2**20 cells a band, at least four a thread.
    threads_rows = _inrs.coverage_band_rows(300, 202, False, False)
    assert 1 <= threads_rows <= -(-202 // 4)
    assert _inrs.coverage_band_rows(4096, 1 << 20, False, False) == 256
    assert _inrs.coverage_band_rows(4096, 1 << 20, True, True) == (1 << 20) // 5 // 4096
    disc = inrs.Domain.from_json(DISC)
    xs, ys = np.linspace(-1.03, 0.97, 301), np.linspace(-1.1, 1.05, 203)
    lazy = inrs.dask.cell_fractions(disc, xs, ys)
    rows = threads_rows
    assert lazy.chunks[0] == (rows,) * (202 // rows) + ((202 % rows,) if 202 % rows else ())
    assert np.array_equal(lazy.compute(), disc.cell_fractions(xs, ys))


def test_dask_blocks_take_the_fill_rule():
    require("dask")
    import inrs.dask

    d = inrs.Domain.from_json(ANNULUS)
    xs, ys = np.linspace(-2.2, 2.1, 30), irregular_edges(5, -2.1, 2.3)
    want = d.cell_fractions(xs, ys, fill_rule="nonzero")
    lazy = inrs.dask.cell_fractions(d, xs, ys, row_chunk=4, fill_rule="nonzero")
    assert np.array_equal(lazy.compute(), want)
    assert not np.array_equal(want, d.cell_fractions(xs, ys))
    with pytest.raises(ValueError, match="unknown fill rule"):
        inrs.dask.cell_fractions(d, xs, ys, fill_rule="odd")


def test_dask_blocks_on_worker_processes_equal_the_eager_array():
    distributed = require("distributed")
    import inrs.dask

    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "s5_lune.json")
    xs, ys = irregular_edges(5, -1.1, 1.1), np.linspace(-1.05, 1.1, 90)
    want = d.cell_fractions(xs, ys)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster):
        got = inrs.dask.cell_fractions(d, xs, ys, row_chunk=10).compute()
    assert np.array_equal(got, want)
    areas = np.outer(np.diff(ys), np.diff(xs))
    assert math.fsum((want * areas).ravel()) == pytest.approx(d.area, rel=1e-12)


def test_dask_computes_a_band_of_a_grid_too_large_for_one_call():
    require("dask")
    import inrs.dask

    d = inrs.Domain.from_json(DISC)
    xs, ys = np.linspace(-1, 1, 2**15 + 1), np.linspace(-1, 1, 2**14 + 1)
    assert (len(xs) - 1) * (len(ys) - 1) > inrs.MAX_CELLS
    with pytest.raises(ValueError, match=r"exceed the limit of 268435456 cells .*row bands"):
        d.cell_fractions(xs, ys)
    lazy = inrs.dask.cell_fractions(d, xs, ys, row_chunk=64)
    assert lazy.shape == (2**14, 2**15)
    # Only the blocks of the rows asked for are computed. The middle row [0, h] holds
    # int_0^h 2 sqrt(1 - y^2) dy = h sqrt(1 - h^2) + asin(h) of the disc. (Its cells are
    # 2^-27 in area: the corners' inclusion-exclusion of `disc_fractions` would lose 1e-8 of
    # them, so the row is checked by its sum and against one eager call on that row.)
    j, h = 2**13, 2.0**-13
    assert ys[j] == 0.0 and ys[j + 1] == h
    mid = lazy[j : j + 1].compute()[0]
    row_area = math.fsum(mid * np.diff(xs) * h)
    assert row_area == pytest.approx(h * math.sqrt(1 - h * h) + math.asin(h), rel=1e-12, abs=0)
    assert np.all(mid[2**14 // 2 : 2**15 - 2**14 // 2] == 1.0)
    assert 0 < mid[-1] < 1 and 0 < mid[0] < 1
    assert np.allclose(mid, d.cell_fractions(xs, ys[j : j + 2])[0], rtol=0, atol=1e-15)


@pytest.mark.parametrize(
    "xs, ys, message",
    [
        ([1.0, 0.0], [0.0, 1.0], r"^x edges must increase strictly: edge 1 \(0\.0\) is not above edge 0 \(1\.0\)$"),
        ([0.0, 1.0], [0.0, 1.0, 1.0], r"^y edges must increase strictly"),
        ([0.0, np.nan], [0.0, 1.0], r"^x edge 1 is NaN: edges must be finite"),
        ([0.0, 1.0], [-np.inf, 1.0], r"^y edge 0 is -inf: edges must be finite"),
        ([0.0], [0.0, 1.0], r"^a grid needs at least 2 x edges \(one cell\), got 1$"),
        ([], [0.0, 1.0], r"^a grid needs at least 2 x edges \(one cell\), got 0$"),
        ([[0.0, 1.0]], [0.0, 1.0], r"^x_edges must be a 1-D array of edges, got shape \(1, 2\)$"),
        (["a", "b"], [0.0, 1.0], r"^x_edges must be numbers"),
    ],
)
def test_bad_edges_raise_one_line_value_errors(xs, ys, message):
    require("dask")
    import inrs.dask

    d = inrs.Domain.from_json(DISC)
    with pytest.raises(ValueError, match=message) as e:
        d.cell_fractions(xs, ys)
    assert "\n" not in str(e.value)
    with pytest.raises(ValueError, match=message):
        inrs.dask.cell_fractions(d, xs, ys)  # refused before any compute()


def test_open_boundary_raises_value_error_naming_it():
    require("dask")
    import inrs.dask

    cubic = inrs.Domain.from_json(
        '{"curves": [{"degree": 3, "control_points": [[0, 0], [0, 1], [-1, 1], [-1, 0]]}]}'
    )
    for call in (
        lambda: cubic.cell_fractions([-1, 0], [0, 1]),
        lambda: cubic.cell_fractions([-1, 0], [0, 1], centroids=True),
        lambda: inrs.dask.cell_fractions(cubic, [-1, 0], [0, 1]),
    ):
        with pytest.raises(ValueError, match=r"^open boundary: ") as e:
            call()
        assert "\n" not in str(e.value)
    with pytest.raises(ValueError, match="row_chunk must be an integer >= 1, got 0"):
        inrs.dask.cell_fractions(inrs.Domain.from_json(DISC), [0, 1], [0, 1], row_chunk=0)

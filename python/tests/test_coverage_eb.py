"""Embedded-boundary outputs of ``Domain.cell_fractions`` (the boundary's length, centroid
and normal in each cell, face centroids), revolved volume fractions (``axisymmetric``)
against the closed-form volumes of a torus and a sphere, ``inrs.to_xarray``, and the blocks of
``inrs.dask.cell_fractions`` against the one-shot grid bit for bit (a circle through grid
vertices, the fixture domains), planar and revolved."""

import json
import math
import sys

import numpy as np
import pytest

import inrs
from conftest import FIXTURES, PAPER, circle, require


def ring_volumes(xs: np.ndarray, ys: np.ndarray, axis: str) -> np.ndarray:
    """``(ny, nx)``: the volume of the ring each cell sweeps about the axis, ``pi h (r1^2 -
    r0^2)`` (radius ``x`` about ``y``, ``y`` about ``x``)."""
    if axis == "y":
        return np.outer(np.diff(ys), math.pi * np.diff(xs**2))
    return np.outer(math.pi * np.diff(ys**2), np.diff(xs))


def test_new_outputs_have_their_shapes_and_old_fields_come_first():
    d = circle(0.1, -0.05, 1.0)
    xs, ys = np.linspace(-1.2, 1.3, 11), np.linspace(-1.25, 1.1, 8)
    nx, ny = 10, 7
    eb = d.cell_fractions(xs, ys, True, True, boundary=True, face_centroids=True)
    assert isinstance(eb, inrs.EBCoverage)
    assert eb._fields[:4] == inrs.CellCoverage._fields
    shapes = {
        "fractions": (ny, nx),
        "centroids": (ny, nx, 2),
        "x_apertures": (ny, nx + 1),
        "y_apertures": (ny + 1, nx),
        "boundary_lengths": (ny, nx),
        "boundary_centroids": (ny, nx, 2),
        "boundary_normals": (ny, nx, 2),
        "x_face_centroids": (ny, nx + 1),
        "y_face_centroids": (ny + 1, nx),
    }
    for name, shape in shapes.items():
        a = getattr(eb, name)
        assert a.shape == shape and a.dtype == np.float64, name
    # The old four by position, as before, and the same values as the old call.
    f, c, xa, ya = eb[:4]
    old = d.cell_fractions(xs, ys, True, True)
    assert type(old) is inrs.CellCoverage and len(old) == 4
    for a, b in zip((f, c, xa, ya), old):
        assert np.array_equal(a, b, equal_nan=True)
    # NaN conventions: no boundary in a cell = length 0 and NaN centroid and normal.
    none = eb.boundary_lengths == 0
    assert np.isnan(eb.boundary_centroids[none]).all() and np.isnan(eb.boundary_normals[none]).all()
    assert np.isfinite(eb.boundary_centroids[~none]).all()
    assert np.allclose(np.hypot(*np.moveaxis(eb.boundary_normals[~none], -1, 0)), 1.0, atol=1e-15)
    assert math.fsum(eb.boundary_lengths.ravel()) == pytest.approx(2 * math.pi, rel=1e-13)
    assert np.array_equal(np.isnan(eb.x_face_centroids), eb.x_apertures == 0)
    assert np.array_equal(np.isnan(eb.y_face_centroids), eb.y_apertures == 0)
    # Only what was asked for; the fractions alone stay an array, revolved too.
    only_faces = d.cell_fractions(xs, ys, face_centroids=True)
    assert only_faces.boundary_lengths is None and only_faces.centroids is None
    assert np.array_equal(only_faces.x_face_centroids, eb.x_face_centroids, equal_nan=True)
    assert isinstance(circle(0.0, 2.0, 1.0).cell_fractions(xs, ys + 2.0, axisymmetric="x"), np.ndarray)


def test_the_boundary_normals_point_out_of_the_covered_part():
    d = circle(0.0, 0.0, 1.0)
    xs = ys = np.linspace(-1, 1, 3)
    eb = d.cell_fractions(xs, ys, boundary=True)
    s = math.sqrt(0.5)
    # Quadrant cells: the normal integral over a quarter circle points along the diagonal.
    want = np.array([[[-s, -s], [s, -s]], [[-s, s], [s, s]]])
    assert np.allclose(eb.boundary_normals, want, atol=1e-15)
    assert np.allclose(eb.boundary_lengths, math.pi / 2, rtol=1e-14)


def test_the_normals_are_amrex_bnorm_from_the_apertures():
    # AMReX (AMReX_EB2_2D_C.cpp) takes the normal from the apertures: int n ds over the
    # boundary in a cell = ((axm - axp) dy, (aym - ayp) dx) by the divergence theorem; its
    # |.| is at most the boundary's length (equal for a straight boundary).
    d = circle(0.1, 0.05, 1.0)
    xs, ys = np.linspace(-1.3, 1.2, 11), np.linspace(-1.2, 1.4, 9)
    e = d.cell_fractions(xs, ys, True, True, boundary=True)
    dx, dy = np.diff(xs)[None, :], np.diff(ys)[:, None]
    n_x = (e.x_apertures[:, :-1] - e.x_apertures[:, 1:]) * dy
    n_y = (e.y_apertures[:-1] - e.y_apertures[1:]) * dx
    size = np.hypot(n_x, n_y)
    cut = e.boundary_lengths > 0
    assert np.allclose(e.boundary_normals[..., 0][cut], n_x[cut] / size[cut], rtol=0, atol=1e-15)
    assert np.allclose(e.boundary_normals[..., 1][cut], n_y[cut] / size[cut], rtol=0, atol=1e-15)
    assert np.all(e.boundary_lengths[cut] >= size[cut] * (1 - 1e-14))
    assert np.all(size[~cut] == 0)


@pytest.mark.parametrize("axis", ["y", "x"])
def test_a_revolved_disc_is_a_torus(axis):
    r, big_r, zc = 0.5, 2.0, 0.3
    radius = np.linspace(0.0, 3.0, 76)  # touching the axis
    along = np.linspace(-0.5, 1.1, 41)
    if axis == "y":
        d, xs, ys = circle(big_r, zc, r), radius, along
    else:
        d, xs, ys = circle(zc, big_r, r), along, radius
    f = d.cell_fractions(xs, ys, axisymmetric=axis)
    volume = math.fsum((f * ring_volumes(xs, ys, axis)).ravel())
    torus = 2 * math.pi**2 * r**2 * big_r
    assert volume == pytest.approx(torus, rel=1e-12, abs=0)
    # Revolved centroids lie farther out than the planar ones (weighted by the radius).
    cov = d.cell_fractions(xs, ys, True, True, axisymmetric=axis)
    planar = d.cell_fractions(xs, ys, True)
    k = 0 if axis == "y" else 1
    total_rev = np.nansum(cov.fractions * ring_volumes(xs, ys, axis) * cov.centroids[..., k])
    assert total_rev / torus == pytest.approx(big_r + r * r / (4 * big_r), rel=1e-12)
    assert np.nanmean(cov.centroids[..., k]) > np.nanmean(planar.centroids[..., k])


def test_a_revolved_half_disc_on_the_axis_is_a_sphere():
    r = 0.75
    half = inrs.Domain.from_json(
        '{"curves": ['
        f'{{"arc": {{"center": [0, 0], "radius": {r}, "start_angle": {-math.pi / 2}, "sweep": {math.pi}}}}},'
        f'{{"segment": {{"from": [0, {r}], "to": [0, {-r}]}}}}]}}'
    )
    xs, ys = np.linspace(0.0, 0.9, 37), np.linspace(-0.8, 0.85, 43)
    f = half.cell_fractions(xs, ys, axisymmetric="y")
    volume = math.fsum((f * ring_volumes(xs, ys, "y")).ravel())
    assert volume == pytest.approx(4 / 3 * math.pi * r**3, rel=1e-12, abs=0)


def test_axis_errors_and_planar_only_outputs_are_value_errors():
    d = circle(0.0, 0.0, 1.0)
    xs = ys = np.linspace(-1, 1, 5)
    with pytest.raises(ValueError, match="the grid crosses the axis of revolution"):
        d.cell_fractions(xs, ys, axisymmetric="y")
    with pytest.raises(ValueError, match="the domain crosses the axis of revolution"):
        d.cell_fractions(np.linspace(0, 1, 3), ys, axisymmetric="y")
    with pytest.raises(ValueError, match="planar cells only"):
        d.cell_fractions(xs, np.linspace(0, 1, 3), boundary=True, axisymmetric="x")
    with pytest.raises(ValueError, match="planar cells only"):
        d.cell_fractions(xs, np.linspace(0, 1, 3), face_centroids=True, axisymmetric="x")
    with pytest.raises(ValueError, match="axisymmetric must be None, 'x' or 'y'"):
        d.cell_fractions(xs, ys, axisymmetric="z")


def test_to_xarray_labels_cells_and_faces():
    xr = require("xarray")
    d = circle(0.0, 0.0, 1.0)
    xs, ys = np.linspace(-1.1, 1.1, 6), np.array([-1.2, -0.3, 0.0, 0.4, 1.3])
    f = d.cell_fractions(xs, ys)
    da = inrs.to_xarray(f, xs, ys)
    assert isinstance(da, xr.DataArray) and da.name == "fractions"
    assert da.dims == ("y", "x")
    assert np.array_equal(da.x.values, (xs[:-1] + xs[1:]) / 2)
    assert np.array_equal(da.y.values, (ys[:-1] + ys[1:]) / 2)
    assert np.array_equal(da.values, f)
    eb = d.cell_fractions(xs, ys, True, True, boundary=True, face_centroids=True)
    ds = eb.to_xarray(xs, ys)
    assert isinstance(ds, xr.Dataset)
    assert set(ds.data_vars) == set(inrs.EBCoverage._fields)
    assert ds.x_apertures.dims == ("y", "x_face") and ds.y_apertures.dims == ("y_face", "x")
    assert ds.x_face_centroids.dims == ("y", "x_face")
    assert ds.y_face_centroids.dims == ("y_face", "x")
    assert ds.centroids.dims == ("y", "x", "component")
    assert ds.boundary_normals.dims == ("y", "x", "component")
    assert list(ds.component.values) == ["x", "y"]
    assert np.array_equal(ds.x_face.values, xs) and np.array_equal(ds.y_face.values, ys)
    assert np.array_equal(ds.boundary_lengths.values, eb.boundary_lengths)
    # Selecting by coordinate: the face x = 0.22 of row 2 (centre y = 0.2).
    assert ds.x_apertures.sel(x_face=xs[3], y=0.2).item() == eb.x_apertures[2, 3]
    # Only what was asked for: no face dimensions without faces.
    small = d.cell_fractions(xs, ys, True).to_xarray(xs, ys)
    assert set(small.data_vars) == {"fractions", "centroids"} and "x_face" not in small.dims
    with pytest.raises(ValueError, match=r"fractions has shape \(4, 5\), but the edges give"):
        inrs.to_xarray(f, xs, ys[:-1])


def test_to_xarray_wraps_a_dask_array_lazily():
    require("xarray")
    require("dask")
    import dask.array as da
    import inrs.dask

    d = circle(0.0, 0.0, 1.0)
    xs, ys = np.linspace(-1.1, 1.1, 30), np.linspace(-1.2, 1.3, 41)
    lazy = inrs.dask.cell_fractions(d, xs, ys, row_chunk=8)
    wrapped = inrs.to_xarray(lazy, xs, ys)
    assert isinstance(wrapped.data, da.Array)  # not computed
    assert wrapped.chunks == lazy.chunks
    assert np.array_equal(wrapped.values, d.cell_fractions(xs, ys))


def test_to_xarray_without_xarray_names_the_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)  # import xarray now raises ImportError
    with pytest.raises(ImportError, match="pip install xarray"):
        inrs.to_xarray(np.zeros((1, 1)), [0, 1], [0, 1])


CHUNKS = (1, 3, 7, 64, None)


def differing_cells(got: np.ndarray, want: np.ndarray) -> list:
    """``(row, column, got, want)`` of every cell whose value (or NaN) differs, bit for bit."""
    same = (got == want) | (np.isnan(got) & np.isnan(want))
    return [(int(j), int(i), got[j, i], want[j, i]) for j, i in zip(*np.nonzero(~same))]


def assert_blocks_equal_one_shot(d: inrs.Domain, xs, ys, axisymmetric=None):
    import inrs.dask

    want = d.cell_fractions(xs, ys, axisymmetric=axisymmetric)
    for chunk in CHUNKS:
        got = inrs.dask.cell_fractions(
            d, xs, ys, row_chunk=chunk, axisymmetric=axisymmetric
        ).compute()
        assert got.shape == want.shape
        bad = differing_cells(got, want)
        assert not bad, (
            f"row_chunk={chunk}, axisymmetric={axisymmetric}: "
            f"cells (row, column, blocks, one-shot) {bad}"
        )


def test_dask_blocks_equal_the_one_shot_grid_where_a_circle_meets_grid_vertices():
    require("dask")
    # Radius 5 through the lattice points (3, 4), (4, 3), (5, 0), ...: vertices of the dyadic
    # grids of steps 1, 1/2 and 1/4 on [-6, 6]^2.
    d = circle(0.0, 0.0, 5.0)
    for n in (12, 24, 48):
        xs = ys = -6.0 + 12.0 * np.arange(n + 1) / n
        assert 3.0 in xs and 4.0 in xs and 5.0 in xs
        assert_blocks_equal_one_shot(d, xs, ys)
    # Revolved about the y axis: the circle of radius 5 about (8, 0) through (11, 4), (4, 3), ...
    d = circle(8.0, 0.0, 5.0)
    xs = np.linspace(0.0, 16.0, 65)  # step 1/4, exact
    ys = np.linspace(-6.0, 6.0, 49)
    assert_blocks_equal_one_shot(d, xs, ys, axisymmetric="y")


def test_row_bands_of_every_output_equal_the_one_shot_grid_at_grid_vertices():
    # The bands dask's blocks are made of (``Domain._coverage`` on rows j0 .. j1, the
    # library's ``GridCoverage::rows``), with every output: cells, faces (the lines shared by
    # two bands) and the boundary's geometry, against one call, bit for bit.
    d = circle(0.0, 0.0, 5.0)
    xs = ys = -6.0 + 12.0 * np.arange(49) / 48
    ny = len(ys) - 1
    want = d.cell_fractions(xs, ys, True, True, boundary=True, face_centroids=True)
    for chunk in (1, 3, 7, 64):
        bands = [
            d._coverage(xs, ys, (j0, min(j0 + chunk, ny)), True, True, "even-odd", 1,
                        boundary=True, face_centroids=True)
            for j0 in range(0, ny, chunk)
        ]
        for name in inrs.EBCoverage._fields:
            parts = [getattr(b, name) for b in bands]
            if name in ("y_apertures", "y_face_centroids"):
                # A band holds its bottom and top lines: the top one is the next band's bottom.
                parts = [p[:-1] for p in parts[:-1]] + parts[-1:]
            got = np.concatenate(parts)
            flat = lambda a: a.reshape(a.shape[0], -1)
            bad = differing_cells(flat(got), flat(getattr(want, name)))
            assert not bad, f"{name}, bands of {chunk} rows: (row, column, bands, one-shot) {bad}"


def shifted(d: inrs.Domain, dx: float) -> inrs.Domain:
    """``d`` moved by ``dx`` along x (its control points; a new domain, rounding and all)."""
    data = json.loads(d.to_json())
    for curve in data["curves"]:
        curve["control_points"] = [[x + dx, y] for x, y in curve["control_points"]]
    return inrs.Domain.from_json(json.dumps(data))


@pytest.mark.parametrize("name", PAPER)
def test_dask_blocks_equal_the_one_shot_grid_on_the_fixtures(name):
    require("dask")
    d = inrs.Domain.load(FIXTURES / "inrs-paper" / f"{name}.json")
    x0, y0, x1, y1 = d.bounds
    wx, wy = x1 - x0, y1 - y0
    xs = np.linspace(x0 - 0.03 * wx, x1 + 0.05 * wx, 38)
    ys = np.linspace(y0 - 0.04 * wy, y1 + 0.02 * wy, 45)
    assert_blocks_equal_one_shot(d, xs, ys)
    # Revolved about the y axis, the domain moved right of it (the grid from the axis on).
    moved = shifted(d, 0.5 * wx - x0)
    mx0, _, mx1, _ = moved.bounds
    assert mx0 > 0
    assert_blocks_equal_one_shot(moved, np.linspace(0.0, mx1 + 0.05 * wx, 43), ys, axisymmetric="y")

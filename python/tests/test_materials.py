"""Several materials on one grid: ``inrs.cell_fractions`` (the library's ``MaterialCoverage``)
against closed forms (two overlapping discs, a disc inside an annulus), replacement and plain
overlaps against ``Domain.cell_fractions`` bit for bit, a material replaced everywhere, the
lazy ``inrs.dask.cell_fractions`` against the eager call bit for bit, ``inrs.to_xarray``'s
``material`` dimension, the command line's files, and bad input."""

import math
import subprocess

import numpy as np
import pytest

import inrs
from conftest import circle, require

LENS = 2 * math.pi / 3 - math.sqrt(3) / 2
XS = np.linspace(-2.0, 2.0, 41)
YS = np.linspace(-1.5, 1.5, 31)
CELL = 0.1 * 0.1


def discs():
    return [circle(-0.5, 0.0, 1.0), circle(0.5, 0.0, 1.0)]


def same(a, b) -> bool:
    """Equal arrays (or both ``None``), ``NaN`` equal to ``NaN``, bit for bit otherwise."""
    if a is None or b is None:
        return a is None and b is None
    return a.shape == b.shape and np.array_equal(a, b, equal_nan=True)


def test_two_discs_replace_as_the_closed_forms_say():
    a, b = discs()
    eb = inrs.cell_fractions([a, b], XS, YS, True, True, boundary=True, face_centroids=True)
    assert isinstance(eb, inrs.EBCoverage)
    nx, ny = len(XS) - 1, len(YS) - 1
    shapes = {
        "fractions": (2, ny, nx),
        "centroids": (2, ny, nx, 2),
        "x_apertures": (2, ny, nx + 1),
        "y_apertures": (2, ny + 1, nx),
        "boundary_lengths": (2, ny, nx),
        "boundary_centroids": (2, ny, nx, 2),
        "boundary_normals": (2, ny, nx, 2),
        "x_face_centroids": (2, ny, nx + 1),
        "y_face_centroids": (2, ny + 1, nx),
    }
    for name, shape in shapes.items():
        assert getattr(eb, name).shape == shape, name
        assert getattr(eb, name).dtype == np.float64, name
    f = eb.fractions
    assert abs(f[0].sum() * CELL - (math.pi - LENS)) < 1e-12
    assert abs(f[1].sum() * CELL - math.pi) < 1e-12
    assert (f.sum(axis=0) <= 1 + 1e-12).all()
    # The last material is its domain's own coverage, bit for bit.
    alone = b.cell_fractions(XS, YS, True, True, boundary=True, face_centroids=True)
    for name in shapes:
        assert same(getattr(eb, name)[1], getattr(alone, name)), name
    # The result types follow the outputs asked for, as Domain.cell_fractions'.
    bare = inrs.cell_fractions([a, b], XS, YS)
    assert isinstance(bare, np.ndarray) and same(bare, f)
    cc = inrs.cell_fractions((a, b), XS, YS, centroids=True)
    assert isinstance(cc, inrs.CellCoverage) and cc.x_apertures is None
    assert same(cc.centroids, eb.centroids)


def test_without_replacement_each_material_is_its_domain():
    ds = discs() + [circle(0.25, 0.1, 0.6)]
    eb = inrs.cell_fractions(ds, XS, YS, True, True, boundary=True, face_centroids=True, replace=False)
    for k, d in enumerate(ds):
        alone = d.cell_fractions(XS, YS, True, True, boundary=True, face_centroids=True)
        for name in inrs.EBCoverage._fields:
            assert same(getattr(eb, name)[k], getattr(alone, name)), (k, name)
    assert abs(eb.fractions[0].sum() * CELL - math.pi) < 1e-12


def test_one_domain_is_domain_cell_fractions():
    d = circle(0.1, -0.05, 1.0)
    one = inrs.cell_fractions(d, XS, YS, True, apertures=True)
    want = d.cell_fractions(XS, YS, True, True)
    assert isinstance(one, inrs.CellCoverage)
    assert all(same(x, y) for x, y in zip(one, want))
    listed = inrs.cell_fractions([d], XS, YS, True, True)
    assert listed.fractions.shape == (1, len(YS) - 1, len(XS) - 1)
    assert all(same(x[0], y) for x, y in zip(listed, want))


def test_a_domain_replaced_everywhere_is_zeros_with_nan_centroids():
    a, b = circle(0, 0, 1), circle(0, 0, 1)
    eb = inrs.cell_fractions([a, b], XS, YS, True, True, boundary=True)
    assert (eb.fractions[0] == 0).all()
    assert np.isnan(eb.centroids[0]).all()
    assert (eb.boundary_lengths[0] == 0).all() and np.isnan(eb.boundary_normals[0]).all()
    assert (eb.x_apertures[0] == 0).all()
    assert abs(eb.fractions[1].sum() * CELL - math.pi) < 1e-12


def test_a_disc_in_an_annulus_takes_its_cells():
    ring = inrs.Domain.from_json(
        '{"curves": [{"circle": {"center": [0, 0], "radius": 2}},'
        ' {"circle": {"center": [0, 0], "radius": 1}}]}'
    )
    inner = circle(0, 0, 1.5)
    xs = ys = np.linspace(-2.5, 2.5, 51)
    f = inrs.cell_fractions([ring, inner], xs, ys)
    area = f.sum(axis=(1, 2)) * 0.1 * 0.1
    assert abs(area[0] - 1.75 * math.pi) < 1e-12
    assert abs(area[1] - 2.25 * math.pi) < 1e-12
    assert (f.sum(axis=0) <= 1 + 1e-12).all()
    # Without replacement the annulus is whole.
    plain = inrs.cell_fractions([ring, inner], xs, ys, replace=False)
    assert abs(plain[0].sum() * 0.01 - 3 * math.pi) < 1e-12


@pytest.mark.parametrize("row_chunk", [1, 3, 7, None])
@pytest.mark.parametrize("replace", [True, False])
def test_dask_blocks_equal_the_eager_call_bit_for_bit(row_chunk, replace):
    require("dask")
    import inrs.dask

    ds = discs() + [circle(0.04, 0.31, 0.53)]
    eager = inrs.cell_fractions(ds, XS, YS, replace=replace)
    lazy = inrs.dask.cell_fractions(ds, XS, YS, row_chunk=row_chunk, replace=replace)
    assert lazy.shape == eager.shape == (3, len(YS) - 1, len(XS) - 1)
    ny = len(YS) - 1
    if row_chunk is not None:
        # One task per material and band of rows.
        assert lazy.chunks[0] == (1, 1, 1)
        assert len(lazy.chunks[1]) == math.ceil(ny / row_chunk)
    assert np.array_equal(lazy.compute(), eager, equal_nan=True)


@pytest.mark.parametrize("row_chunk", [1, 3, 7, None])
def test_dask_blocks_equal_the_eager_call_at_a_tangent_through_a_grid_vertex(row_chunk):
    # The unit circle about (0, 0.6) on 48 cells over [-1.6, 1.6]: its leftmost point
    # (-1, 0.6) is the grid vertex (x_9, y_33) within rounding (y_33 = 0.6000000000000001).
    require("dask")
    import inrs.dask

    edges = np.array([-1.6 + 3.2 * k / 48 for k in range(48)] + [1.6])
    ds = discs() + [circle(0.0, 0.6, 1.0)]
    eager = inrs.cell_fractions(ds, edges, edges)
    lazy = inrs.dask.cell_fractions(ds, edges, edges, row_chunk=row_chunk)
    assert np.array_equal(lazy.compute(), eager, equal_nan=True)


def test_dask_revolved_and_a_single_domain_unchanged():
    require("dask")
    import inrs.dask

    ds = [circle(1.5, 0.0, 1.0), circle(2.0, 0.2, 0.5)]
    xs, ys = np.linspace(0.0, 3.0, 13), np.linspace(-1.2, 1.2, 9)
    eager = inrs.cell_fractions(ds, xs, ys, axisymmetric="y")
    lazy = inrs.dask.cell_fractions(ds, xs, ys, row_chunk=2, axisymmetric="y")
    assert np.array_equal(lazy.compute(), eager)
    single = inrs.dask.cell_fractions(ds[0], xs, ys, row_chunk=2)
    assert single.shape == (8, 12)
    assert np.array_equal(single.compute(), ds[0].cell_fractions(xs, ys))
    # The axis is checked now, naming the library's refusal.
    with pytest.raises(ValueError, match="crosses the axis"):
        inrs.dask.cell_fractions([ds[0], circle(0.0, 0.0, 1.0)], xs, ys, axisymmetric="y")


def test_to_xarray_has_a_material_dimension():
    require("xarray")
    a, b = discs()
    nx, ny = len(XS) - 1, len(YS) - 1
    da = inrs.to_xarray(inrs.cell_fractions([a, b], XS, YS), XS, YS)
    assert da.dims == ("material", "y", "x")
    assert da.material.values.tolist() == [0, 1]
    assert da.shape == (2, ny, nx)
    eb = inrs.cell_fractions([a, b], XS, YS, True, True, boundary=True, face_centroids=True)
    ds = eb.to_xarray(XS, YS)
    assert ds.fractions.dims == ("material", "y", "x")
    assert ds.centroids.dims == ("material", "y", "x", "component")
    assert ds.x_apertures.dims == ("material", "y", "x_face")
    assert ds.y_face_centroids.dims == ("material", "y_face", "x")
    assert ds.sizes["material"] == 2
    assert np.array_equal(ds.boundary_normals.values, eb.boundary_normals, equal_nan=True)
    # One domain keeps its dimensions.
    assert inrs.to_xarray(a.cell_fractions(XS, YS), XS, YS).dims == ("y", "x")
    with pytest.raises(ValueError, match="the edges give"):
        inrs.to_xarray(eb, XS[:-1], YS)


def test_to_xarray_wraps_the_lazy_materials():
    require("xarray")
    require("dask")
    import inrs.dask

    lazy = inrs.dask.cell_fractions(discs(), XS, YS, row_chunk=5)
    da = inrs.to_xarray(lazy, XS, YS)
    assert da.dims == ("material", "y", "x")
    assert da.chunks is not None
    assert np.array_equal(da.values, inrs.cell_fractions(discs(), XS, YS))


def test_the_command_line_writes_the_same_materials(cli, tmp_path):
    ds = discs() + [circle(0.04, 0.31, 0.53)]
    paths = []
    for k, d in enumerate(ds):
        p = tmp_path / f"d{k}.json"
        p.write_text(d.to_json())
        paths.append(str(p))
    grid = "--grid=-2,2,40,-1.5,1.5,30"
    xs = np.array([-2 + i * 4 / 40 if i < 40 else 2.0 for i in range(41)])
    ys = np.array([-1.5 + j * 3 / 30 if j < 30 else 1.5 for j in range(31)])
    for replace in (True, False):
        out = tmp_path / f"m{replace}.npy"
        args = [str(cli), "fractions", grid, "--centroids", "--boundary", "--output", str(out)]
        for p in paths:
            args += ["--domain", p]
        if not replace:
            args.append("--no-replace")
        subprocess.run(args, check=True, capture_output=True)
        eb = inrs.cell_fractions(ds, xs, ys, centroids=True, boundary=True, replace=replace)
        assert same(np.load(out), eb.fractions)
        assert same(np.load(tmp_path / f"m{replace}.centroids.npy"), eb.centroids)
        assert same(np.load(tmp_path / f"m{replace}.boundary_normals.npy"), eb.boundary_normals)


def test_bad_input_is_a_clear_error():
    a, b = discs()
    with pytest.raises(ValueError, match="domains is empty"):
        inrs.cell_fractions([], XS, YS)
    with pytest.raises(TypeError, match=r"domains\[1\] is a str, not an inrs.Domain"):
        inrs.cell_fractions([a, "b.json"], XS, YS)
    with pytest.raises(TypeError, match="sequence of them, got a str"):
        inrs.cell_fractions("a.json", XS, YS)
    with pytest.raises(TypeError, match="got a int"):
        inrs.cell_fractions(3, XS, YS)
    with pytest.raises(ValueError, match="increase strictly"):
        inrs.cell_fractions([a, b], XS[::-1], YS)
    with pytest.raises(ValueError, match="unknown|fill"):
        inrs.cell_fractions([a, b], XS, YS, fill_rule="odd")
    with pytest.raises(ValueError, match="planar cells only"):
        inrs.cell_fractions([a, b], XS, YS, boundary=True, axisymmetric="y")
    with pytest.raises(ValueError, match="crosses the axis"):
        inrs.cell_fractions([a, b], np.linspace(0, 2, 5), YS, axisymmetric="y")
    open_chain = inrs.Domain.from_json(
        '{"curves": [{"degree": 1, "control_points": [[0, 0], [1, 0]]}]}'
    )
    with pytest.raises(ValueError, match="open"):
        inrs.cell_fractions([a, open_chain], XS, YS)
    with pytest.raises(ValueError, match="open"):
        inrs.cell_fractions([open_chain, a], XS, YS, replace=False)


def test_dask_bad_input_is_a_clear_error():
    require("dask")
    import inrs.dask

    a, b = discs()
    with pytest.raises(ValueError, match="domains is empty"):
        inrs.dask.cell_fractions([], XS, YS)
    with pytest.raises(TypeError, match=r"domains\[0\] is a int"):
        inrs.dask.cell_fractions([1, a], XS, YS)
    with pytest.raises(TypeError, match="got a NoneType"):
        inrs.dask.cell_fractions(None, XS, YS)
    with pytest.raises(ValueError, match="row_chunk"):
        inrs.dask.cell_fractions([a, b], XS, YS, row_chunk=0)

"""Dask front ends: ``inrs.dask.classify(domain, xy)`` classifies chunked arrays of points (a
:class:`~inrs.CadSolid` for points of space, ``(N, 3)``);
``inrs.dask.cell_fractions(domain, x_edges, y_edges)`` computes the cell fractions of grids
larger than memory by blocks of rows.

The domain travels to the workers by pickle (its JSON form); each worker process builds its
index once and reuses it for all its chunks. A solid travels as its file and index, and each
worker process reads the file once.
"""

from __future__ import annotations

import numpy as np

from . import DEFAULT_TOLERANCE, CadSolid, Domain, _edges, _inrs


def _classify_block(block: np.ndarray, domain: Domain, method: str, tol: float) -> np.ndarray:
    return domain.classify(block, method=method, tol=tol, threads=1)


def _classify_solid_block(block: np.ndarray, solid: CadSolid) -> np.ndarray:
    return solid.classify(block)


def classify(domain: "Domain | CadSolid", xy, *, method: str = "fast", tol: float = DEFAULT_TOLERANCE):
    """Lazy int8 codes (``inrs.OUTSIDE``, ``INSIDE``, ``BOUNDARY``) of a ``dask.array`` of
    shape ``(N, 2)`` (or ``(N, 3)`` against a :class:`~inrs.CadSolid`, whose ``method`` and
    ``tol`` are its own), chunked along its rows: one task per chunk (``map_blocks``)."""
    import dask.array as da

    xy = da.asarray(xy)
    if isinstance(domain, CadSolid):
        if xy.ndim != 2 or xy.shape[1] != 3:
            raise ValueError(f"points for a solid must have shape (N, 3), got {xy.shape}")
        if len(xy.chunks[1]) != 1:
            xy = xy.rechunk({1: 3})
        return xy.map_blocks(_classify_solid_block, domain, drop_axis=1, dtype=np.int8)
    if xy.ndim != 2 or xy.shape[1] != 2:
        raise ValueError(f"points must have shape (N, 2), got {xy.shape}")
    if len(xy.chunks[1]) != 1:
        xy = xy.rechunk({1: 2})
    return xy.map_blocks(
        _classify_block,
        domain,
        method,
        float(tol),
        drop_axis=1,
        dtype=np.int8,
    )


def _fraction_rows(
    domain: Domain,
    x_edges: np.ndarray,
    y_edges: np.ndarray,
    fill_rule: str,
    axisymmetric,
    j0: int,
    j1: int,
) -> np.ndarray:
    # One band of rows on this task's thread: the library prepares the domain for the grid
    # (a cost independent of the band's size) and covers only the rows j0 .. j1, as its
    # band iterator (``GridCoverage::bands``) computes a band.
    return domain._coverage(
        x_edges, y_edges, (j0, j1), False, False, fill_rule, 1, axisymmetric=axisymmetric
    )


def cell_fractions(
    domain: Domain, x_edges, y_edges, *, row_chunk=None, fill_rule="even-odd", axisymmetric=None
):
    """Lazy :meth:`Domain.cell_fractions`: a float64 ``dask.array`` of shape ``(ny, nx)``
    (row ``j``, column ``i`` is the cell ``[x_i, x_{i+1}] x [y_j, y_{j+1}]``), for grids
    larger than memory or than :data:`inrs.MAX_CELLS` cells.

    Each block holds ``row_chunk`` rows (default: the library's band height,
    ``GridCoverage::band_rows`` on this process's threads: about ``2**20`` cells (8 MiB), at
    least one row, at least four blocks a thread when the grid has the rows) and is one task
    that covers only its rows (the library's ``GridCoverage::rows``, a band as its band
    iterator computes it), so no task ever holds the whole grid; write the result block by
    block (``dask.array.to_zarr``, ``store``) or reduce it. The values are those of the eager
    call, bit for bit (a cell's value does not depend on the band it is computed in, but for
    a few units in the last place at a grid vertex a curved boundary passes through). Each
    task prepares the domain for the grid again, a cost of the order of covering one row of a
    few thousand cells per block. ``fill_rule`` (``even-odd`` or ``nonzero``) and
    ``axisymmetric`` (``None``, ``'x'`` or ``'y'``: revolved volume fractions) are those of
    :meth:`Domain.cell_fractions`. :func:`inrs.to_xarray` wraps the result lazily.

    The grid and the domain are checked now, by covering the first row: bad edges (as
    :meth:`Domain.cell_fractions` lists them), an open boundary, an unknown ``fill_rule`` or
    ``axisymmetric``, an axis the domain or the grid crosses, or a bad ``row_chunk`` raise
    ``ValueError`` here rather than at ``compute()``.
    """
    import dask
    import dask.array as da

    x = _edges("x_edges", x_edges)
    y = _edges("y_edges", y_edges)
    if not isinstance(domain, Domain):
        raise TypeError(f"domain is a {type(domain).__name__}, not an inrs.Domain")
    # Checks the edges and the domain with the library's messages (one row of one band).
    fill_rule = str(fill_rule)
    axisymmetric = None if axisymmetric is None else str(axisymmetric)
    domain._coverage(x, y, (0, 1), False, False, fill_rule, 1, axisymmetric=axisymmetric)
    nx, ny = len(x) - 1, len(y) - 1
    if row_chunk is None:
        row_chunk = _inrs.coverage_band_rows(nx, ny, False, False)
    elif isinstance(row_chunk, bool) or not isinstance(row_chunk, (int, np.integer)) or row_chunk < 1:
        raise ValueError(f"row_chunk must be an integer >= 1, got {row_chunk!r}")
    row_chunk = int(min(row_chunk, ny))
    # The domain and the edges are one node each of the graph, shared by every block.
    shared = [dask.delayed(v, pure=True) for v in (domain, x, y)] + [fill_rule, axisymmetric]
    blocks = [
        da.from_delayed(
            dask.delayed(_fraction_rows, pure=True)(*shared, j0, min(j0 + row_chunk, ny)),
            shape=(min(j0 + row_chunk, ny) - j0, nx),
            dtype=np.float64,
            meta=np.empty((0, 0), dtype=np.float64),
        )
        for j0 in range(0, ny, row_chunk)
    ]
    return blocks[0] if len(blocks) == 1 else da.concatenate(blocks, axis=0)

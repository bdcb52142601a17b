"""Dask front ends: ``inrs.dask.classify(domain, xy)`` classifies chunked arrays of points (a
:class:`~inrs.CadSolid` for points of space, ``(N, 3)``);
``inrs.dask.cell_fractions(domain, x_edges, y_edges)`` computes the cell fractions of grids
larger than memory by blocks of rows (of several materials: a sequence of domains).

The domain travels to the workers by pickle (its JSON form); each worker process builds its
index once and reuses it for all its chunks. Several materials are prepared once per worker
process (the library's ``MaterialCoverage``) and reused for all their blocks. A solid travels
as its file and index, and each worker process reads the file once.
"""

from __future__ import annotations

import collections

import hashlib
import threading

import numpy as np

from . import DEFAULT_TOLERANCE, CadSolid, Domain, _edges, _inrs, _natives


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
    domain,
    x_edges,
    y_edges,
    *,
    row_chunk=None,
    fill_rule="even-odd",
    axisymmetric=None,
    replace=True,
):
    """Lazy :meth:`Domain.cell_fractions`: a float64 ``dask.array`` of shape ``(ny, nx)``
    (row ``j``, column ``i`` is the cell ``[x_i, x_{i+1}] x [y_j, y_{j+1}]``), for grids
    larger than memory or than :data:`inrs.MAX_CELLS` cells. With a sequence of ``k``
    domains, lazy :func:`inrs.cell_fractions`: the materials' fractions, shape ``(k, ny,
    nx)``, ``replace`` as there (later domains replace earlier ones; ``False``: plain
    overlaps), one task per material and block of rows (the library's
    ``MaterialCoverage::rows``); each worker process prepares the materials once (the
    regions and their indexes) and reuses them for all its tasks. The values are those of
    the eager :func:`inrs.cell_fractions`, bit for bit.

    Each block holds ``row_chunk`` rows (default: the library's band height,
    ``GridCoverage::band_rows`` on this process's threads: about ``2**20`` cells (8 MiB), at
    least one row, at least four blocks a thread when the grid has the rows) and is one task
    that covers only its rows (the library's ``GridCoverage::rows``, a band as its band
    iterator computes it), so no task ever holds the whole grid; write the result block by
    block (``dask.array.to_zarr``, ``store``) or reduce it. The values are those of the eager
    call, bit for bit, for any ``row_chunk`` (a cell's value does not depend on the band it is
    computed in, also where the boundary passes through or touches a grid vertex). Each
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
        return _material_fractions(domain, x, y, row_chunk, str(fill_rule), axisymmetric, bool(replace))
    # Checks the edges and the domain with the library's messages (one row of one band).
    fill_rule = str(fill_rule)
    axisymmetric = None if axisymmetric is None else str(axisymmetric)
    domain._coverage(x, y, (0, 1), False, False, fill_rule, 1, axisymmetric=axisymmetric)
    nx, ny = len(x) - 1, len(y) - 1
    row_chunk = _row_chunk(row_chunk, nx, ny)
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


def _row_chunk(row_chunk, nx: int, ny: int) -> int:
    """The rows of a block: the library's band height by default, else ``row_chunk`` checked
    (an integer >= 1), at most ``ny``."""
    if row_chunk is None:
        row_chunk = _inrs.coverage_band_rows(nx, ny, False, False)
    elif isinstance(row_chunk, bool) or not isinstance(row_chunk, (int, np.integer)) or row_chunk < 1:
        raise ValueError(f"row_chunk must be an integer >= 1, got {row_chunk!r}")
    return int(min(row_chunk, ny))


# Materials prepared in this process, by the key of their domains, grid, fill rule and
# replacement: the tasks of a worker prepare them once.
_MATERIALS: "collections.OrderedDict[str, _inrs.NativeMaterials]" = collections.OrderedDict()
_MATERIALS_LOCK = threading.Lock()
# Most prepared material sets a process keeps (the least recently used goes first).
_MATERIALS_KEPT = 8


def _materials_key(domains, x: np.ndarray, y: np.ndarray, fill_rule: str, replace: bool) -> str:
    h = hashlib.sha256()
    for d in domains:
        text = d.to_json().encode()
        h.update(len(text).to_bytes(8, "little"))
        h.update(text)
    for edges in (x, y):
        h.update(len(edges).to_bytes(8, "little"))
        h.update(np.ascontiguousarray(edges, dtype="<f8").tobytes())
    h.update(f"{fill_rule}\0{bool(replace)}".encode())
    return h.hexdigest()


def _materials(key: str, domains, x, y, fill_rule: str, replace: bool) -> "_inrs.NativeMaterials":
    """The materials of ``key``, prepared on first use in this process and kept (the
    :data:`_MATERIALS_KEPT` most recently used). The preparation (intersections of the
    boundaries) runs outside the lock, so other material sets are not held up; two tasks that
    prepare the same set at once keep the first."""
    with _MATERIALS_LOCK:
        m = _MATERIALS.get(key)
        if m is not None:
            _MATERIALS.move_to_end(key)
            return m
    m = _inrs.NativeMaterials([d._native for d in domains], x, y, fill_rule, replace)
    with _MATERIALS_LOCK:
        m = _MATERIALS.setdefault(key, m)
        _MATERIALS.move_to_end(key)
        while len(_MATERIALS) > _MATERIALS_KEPT:
            _MATERIALS.popitem(last=False)
    return m


def _material_rows(key, domains, x, y, fill_rule, replace, axisymmetric, k, j0, j1) -> np.ndarray:
    # One band of one material on this task's thread, the materials prepared once a process.
    return _materials(key, domains, x, y, fill_rule, replace).rows(k, j0, j1, axisymmetric)


def _material_fractions(domains, x, y, row_chunk, fill_rule, axisymmetric, replace):
    """:func:`cell_fractions` for a sequence of domains: ``(k, ny, nx)``."""
    import dask
    import dask.array as da

    _natives(domains)  # TypeError / ValueError for what is not a non-empty list of Domains
    domains = tuple(domains)
    axisymmetric = None if axisymmetric is None else str(axisymmetric)
    key = _materials_key(domains, x, y, fill_rule, replace)
    # Prepared here (the library's errors now, not at compute()), and kept for the tasks of
    # this process; every material's first row checks the options.
    m = _materials(key, domains, x, y, fill_rule, replace)
    for k in range(len(domains)):
        m.rows(k, 0, 1, axisymmetric)
    nx, ny = len(x) - 1, len(y) - 1
    row_chunk = _row_chunk(row_chunk, nx, ny)
    shared = [key] + [dask.delayed(v, pure=True) for v in (domains, x, y)]
    shared += [fill_rule, replace, axisymmetric]
    materials = []
    for k in range(len(domains)):
        blocks = [
            da.from_delayed(
                dask.delayed(_material_rows, pure=True)(*shared, k, j0, min(j0 + row_chunk, ny)),
                shape=(min(j0 + row_chunk, ny) - j0, nx),
                dtype=np.float64,
                meta=np.empty((0, 0), dtype=np.float64),
            )
            for j0 in range(0, ny, row_chunk)
        ]
        materials.append(blocks[0] if len(blocks) == 1 else da.concatenate(blocks, axis=0))
    return da.stack(materials, axis=0)

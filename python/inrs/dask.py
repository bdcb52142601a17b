"""Classification of chunked Dask arrays: ``inrs.dask.classify(domain, xy)``.

The domain travels to the workers by pickle (its JSON form); each worker process builds its
index once and reuses it for all its chunks.
"""

from __future__ import annotations

import numpy as np

from . import DEFAULT_TOLERANCE, Domain


def _classify_block(block: np.ndarray, domain: Domain, method: str, tol: float) -> np.ndarray:
    return domain.classify(block, method=method, tol=tol, threads=1)


def classify(domain: Domain, xy, *, method: str = "fast", tol: float = DEFAULT_TOLERANCE):
    """Lazy int8 codes (``inrs.OUTSIDE``, ``INSIDE``, ``BOUNDARY``) of a ``dask.array`` of
    shape ``(N, 2)``, chunked along its rows: one task per chunk (``map_blocks``)."""
    import dask.array as da

    xy = da.asarray(xy)
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

"""Dask: a chunked array classified on a local cluster of two worker processes equals the
in-process result element for element."""

import os

import numpy as np
import pytest

import inrs
from conftest import FIXTURES, halton

if os.environ.get("INRS_REQUIRE_SYSTEM_FILES") == "1":
    # CI installs dask: a missing one must fail, not skip.
    import dask
    import distributed
else:
    dask = pytest.importorskip("dask")
    distributed = pytest.importorskip("distributed")


def test_dask_local_cluster_equals_in_process():
    import dask.array as da
    import inrs.dask

    d = inrs.Domain.load(FIXTURES / "inrs-paper" / "s5_lune.json")
    pts = halton(400_000, (-1, 1, -1, 1))
    want = d.classify(pts)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        xy = da.from_array(pts, chunks=(50_000, 2))
        lazy = inrs.dask.classify(d, xy)
        assert lazy.dtype == np.int8 and lazy.shape == (len(pts),)
        got = lazy.compute()
        assert len(client.scheduler_info()["workers"]) == 2
    assert np.array_equal(got, want)

"""CadSolid.classify / contains_xyz on the box with a spherical void (fixtures/cad/box_void.step):
the closed form on random points, the boundary, pickling, threads and the shape error."""

import os
import pathlib
import pickle
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import inrs

BOX_VOID = pathlib.Path(__file__).resolve().parents[2] / "fixtures" / "cad" / "box_void.step"


def test_classify_matches_the_closed_form():
    solid = inrs.cad_model(BOX_VOID).solids[0]
    rng = np.random.default_rng(3)
    xyz = rng.uniform(-2.5, 2.5, size=(20000, 3))
    cube = 2.0 - np.abs(xyz).max(axis=1)
    ball = np.linalg.norm(xyz, axis=1) - 1.0
    far = (np.abs(cube) > 1e-9) & (np.abs(ball) > 1e-9)
    want = ((cube > 0) & (ball > 0)).astype(np.int8)
    got = solid.classify(xyz)
    assert got.dtype == np.int8
    assert np.array_equal(got[far], want[far])
    assert np.array_equal(solid.contains_xyz(xyz), got == 1)
    assert solid.classify((2.0, 0.0, 0.0)) == 2
    assert solid.classify((0.0, 0.0, 0.0)) == 0


def test_pickled_solids_and_threads_give_the_same_codes():
    solid = inrs.cad_model(BOX_VOID).solids[0]
    xyz = np.random.default_rng(4).uniform(-2.5, 2.5, size=(5000, 3))
    want = solid.classify(xyz)
    again = pickle.loads(pickle.dumps(solid))
    assert np.array_equal(again.classify(xyz), want)
    with ThreadPoolExecutor(4) as pool:
        for got in pool.map(lambda _: solid.classify(xyz), range(8)):
            assert np.array_equal(got, want)


def test_points_of_the_wrong_width_are_refused():
    solid = inrs.cad_model(BOX_VOID).solids[0]
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        solid.classify(np.zeros((4, 2)))


def test_dask_classifies_chunked_points_of_space_as_in_process():
    try:
        import dask.array as da
    except ImportError:  # CI installs dask: only a local run without it may skip
        if os.environ.get("INRS_REQUIRE_SYSTEM_FILES"):
            raise
        pytest.skip("dask is not installed")
    import inrs.dask

    solid = inrs.cad_model(BOX_VOID).solids[0]
    xyz = np.random.default_rng(5).uniform(-2.5, 2.5, size=(9000, 3))
    lazy = inrs.dask.classify(solid, da.from_array(xyz, chunks=(1000, 3)))
    assert np.array_equal(lazy.compute(scheduler="processes"), solid.classify(xyz))
    with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
        inrs.dask.classify(solid, da.zeros((10, 2), chunks=5))

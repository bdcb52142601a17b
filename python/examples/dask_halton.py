"""Classify 10^8 Halton points on a local Dask cluster and check the inside fraction against the
domain's area over its bounding box.

    python python/examples/dask_halton.py [--points 100000000] [--workers 2]

The points are generated on the workers, chunk by chunk (nothing large is shipped); the domain
travels by pickle and each worker builds its index once.
"""

import argparse
import pathlib
import time

import numpy as np

import inrs
import inrs.dask

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=100_000_000)
    ap.add_argument("--chunk", type=int, default=2_000_000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--domain", default=str(ROOT / "fixtures/inrs-paper/s5_lune.json"))
    args = ap.parse_args()

    import dask.array as da
    from distributed import Client, LocalCluster

    d = inrs.Domain.load(args.domain)
    xmin, ymin, xmax, ymax = d.bounds

    def block(block_info=None):
        (start, stop), _ = block_info[None]["array-location"]
        n = stop - start
        return inrs.halton_points(n, (xmin, ymin, xmax, ymax), start=start)

    with LocalCluster(n_workers=args.workers, threads_per_worker=1, dashboard_address=None) as cluster, Client(
        cluster
    ):
        chunks = ((args.chunk,) * (args.points // args.chunk) + ((args.points % args.chunk,) if args.points % args.chunk else ()), (2,))
        xy = da.map_blocks(block, chunks=chunks, dtype=np.float64)
        codes = inrs.dask.classify(d, xy)
        start = time.perf_counter()
        inside = int((codes == inrs.INSIDE).sum().compute())
        seconds = time.perf_counter() - start
        # The same graph without the classification: what generating the points costs.
        start = time.perf_counter()
        xy[:, 0].sum().compute()
        generation = time.perf_counter() - start
    fraction = inside / args.points
    expected = d.area / ((xmax - xmin) * (ymax - ymin))
    print(f"{args.points} points, {args.workers} workers: {seconds:.2f} s in all, of which generating the points alone takes {generation:.2f} s")
    classify = max(seconds - generation, 1e-9)
    print(f"classification: {classify:.2f} s, {args.points / classify / 1e6:.1f} M points/s")
    print(f"inside fraction {fraction:.8f}, area / box area {expected:.8f}, difference {abs(fraction - expected):.2e}")
    assert abs(fraction - expected) < 1e-4, "the inside fraction must match the area ratio"


if __name__ == "__main__":
    main()

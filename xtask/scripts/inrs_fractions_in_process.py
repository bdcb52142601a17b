"""Whole-grid cell fractions through the Python package, timed beside NumPy writing an array of
the same shape: the in-process row of `cargo xtask bench --only speed`.

Usage: python inrs_fractions_in_process.py N REPS

The unit disc on an N x N grid over [-1.02, 1.02]^2 (`Domain.cell_fractions`, all threads) and
`numpy.ones((N, N))`, alternated REPS times. Prints one line:
`cell_fractions <median s> ones <median s> sum <sum of the fractions>`.
Exits with status 2 and one line on stderr if inrs or numpy cannot be imported.
"""

import statistics
import sys
import time


def main() -> int:
    try:
        import numpy as np
        import inrs
    except ImportError as e:
        print(f"inrs unavailable: {e}", file=sys.stderr)
        return 2
    n, reps = int(sys.argv[1]), int(sys.argv[2])
    disc = inrs.Domain.from_json('{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}')
    edges = np.linspace(-1.02, 1.02, n + 1)
    ours, ones, total = [], [], 0.0
    for _ in range(max(reps, 1)):
        start = time.perf_counter()
        f = disc.cell_fractions(edges, edges)
        ours.append(time.perf_counter() - start)
        total = float(f.sum())
        del f
        start = time.perf_counter()
        a = np.ones((n, n))
        ones.append(time.perf_counter() - start)
        del a
    print(
        f"cell_fractions {statistics.median(ours):.6f} ones {statistics.median(ones):.6f} "
        f"sum {total!r}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

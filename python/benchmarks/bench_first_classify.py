"""Many CAD faces: what the first ``Domain.classify`` of a face costs against the same call on
the warm domain (its indexes built by the first call).

    python python/benchmarks/bench_first_classify.py [FILE ...] [--points 400] [--rounds 5]
        [--threads 1] [--dump FILE]

Every face of the FreeCAD IDF parts (or the files given) that reads and classifies, 400
uniform random points in the face's (u, v) bounding box. Per round, per face: a fresh domain
(read afresh, nothing built), ``classify`` timed once (first), then again on the same domain
(warm); the sums over the faces are the round's figures. Prints the medians over the rounds
and first / warm (the issue's row "many CAD faces: first classify / warm classify", goal
<= 2.5). ``--dump`` writes every face's codes (int8, the faces in order) to compare trees.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

# The many-faces workload (the same faces and points), from the script beside this one.
from many_faces_bench import fresh_domains, workload_from_args


def one_round(files, keep, points, threads):
    domains = fresh_domains(files, keep)
    first = warm = 0.0
    codes = []
    clock = time.perf_counter
    for d, p in zip(domains, points):
        t0 = clock()
        a = d.classify(p, threads=threads)
        t1 = clock()
        b = d.classify(p, threads=threads)
        t2 = clock()
        first += t1 - t0
        warm += t2 - t1
        if not np.array_equal(a, b):
            raise SystemExit("first and warm classify disagree")
        codes.append(a)
    return first, warm, codes


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dump", default=None)
    a, files, keep, points = workload_from_args(ap)
    n = len(keep)
    firsts, warms, ratios = [], [], []
    codes = None
    for _ in range(a.rounds):
        f, w, codes = one_round(files, keep, points, a.threads)
        firsts.append(f)
        warms.append(w)
        ratios.append(f / w)
    mf, mw = statistics.median(firsts), statistics.median(warms)
    print(f"first classify: {1e6 * mf / n:.2f} us/face, warm: {1e6 * mw / n:.2f} us/face")
    print(f"first / warm: {mf / mw:.2f} (median of rounds' ratios {statistics.median(ratios):.2f})")
    if a.dump:
        np.concatenate(codes).astype(np.int8).tofile(a.dump)


if __name__ == "__main__":
    main()

"""The issue #34 workload through Python: every face of the FreeCAD IDF parts (or the files
given), 400 uniform random points in each face's bounding box, classified per face by a loop
of ``Domain.classify`` on fresh domains (the build is what is measured) against one call of
``inrs.classify_many`` on the same faces and points; alternated, the same run.

    python python/benchmarks/many_faces_bench.py [FILE ...] [--points 400] [--rounds 5] [--threads N]

Prints ms per face for each way (median over the
rounds; wall and process CPU time), their ratios, and checks that both give the same answers.
"""

from __future__ import annotations

import argparse
import glob
import statistics
import time

import numpy as np

import inrs

IDF = "/usr/share/freecad/Mod/Idf/Idflibs"


def files_or_idf(files):
    """The files given, else FreeCAD's IDF parts; exits with one line if there are none."""
    files = files or sorted(glob.glob(f"{IDF}/*.stp") + glob.glob(f"{IDF}/*.igs"))
    if not files:
        raise SystemExit(f"no files (give some, or install freecad-common for {IDF})")
    return files


def fresh_domains(files, keep):
    """The domains of the faces `keep` (pairs of file and face index), read afresh: nothing
    built on them yet (a `Domain` keeps what it builds)."""
    faces = {f: inrs.cad_faces(f) for f in files}
    return [faces[f][k].domain for f, k in keep]


def workload(files, n_points, seed=1):
    """The faces that read and classify (a face the reader accepts may still have a loop that
    does not close for inRS: left out), and per face its points, uniform in the face's
    bounding box."""
    rng = np.random.default_rng(seed)
    keep, points = [], []
    for path in files:
        for face in inrs.cad_faces(path):
            if face.domain is None:
                continue
            u0, v0, u1, v1 = face.bbox
            pts = np.column_stack([rng.uniform(u0, u1, n_points), rng.uniform(v0, v1, n_points)])
            try:
                face.domain.classify(pts[:1])
            except ValueError:
                continue
            keep.append((path, face.index))
            points.append(pts)
    return keep, points


def workload_from_args(ap):
    """Adds the workload's options (files, ``--points``, ``--rounds``, ``--threads``) to the
    parser `ap`, parses the command line, prints the workload's line and returns the arguments,
    the files, the faces kept and their points (see `workload`)."""
    ap.add_argument("files", nargs="*")
    ap.add_argument("--points", type=int, default=400)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--threads", type=int, default=None, help="cores (default all)")
    a = ap.parse_args()
    files = files_or_idf(a.files)
    keep, points = workload(files, a.points)
    threads = a.threads or "all"
    print(f"{len(files)} files, {len(keep)} faces, {a.points} points per face, threads={threads}")
    return a, files, keep, points


def loop(domains, points, threads):
    start, cpu = time.perf_counter(), time.process_time()
    out = [d.classify(p, threads=threads) for d, p in zip(domains, points)]
    return (time.perf_counter() - start, time.process_time() - cpu), out


def many(domains, points, threads):
    start, cpu = time.perf_counter(), time.process_time()
    out = inrs.classify_many(domains, points, threads=threads)
    return (time.perf_counter() - start, time.process_time() - cpu), out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    a, files, keep, points = workload_from_args(ap)
    n = len(keep)
    t_loop, t_many = [], []
    for r in range(a.rounds):
        # Alternated, the order flipped every round.
        first, second = (loop, many) if r % 2 == 0 else (many, loop)
        ta, oa = first(fresh_domains(files, keep), points, a.threads)
        tb, ob = second(fresh_domains(files, keep), points, a.threads)
        (t_loop if first is loop else t_many).append(ta)
        (t_many if first is loop else t_loop).append(tb)
        for x, y in zip(oa, ob):
            if not np.array_equal(x, y):
                raise SystemExit("classify_many and Domain.classify disagree")
    ml, mm = (statistics.median(w for w, _ in t) for t in (t_loop, t_many))
    cl, cm = (statistics.median(c for _, c in t) for t in (t_loop, t_many))
    # CPU time (all threads of the process) tells the work apart from the cores it found free.
    print(f"Domain.classify per face: {1e3 * ml / n:.4f} ms/face wall, {1e3 * cl / n:.4f} ms/face CPU")
    print(f"inrs.classify_many:       {1e3 * mm / n:.4f} ms/face wall, {1e3 * cm / n:.4f} ms/face CPU")
    print(f"ratio: {ml / mm:.2f}x wall, {cl / cm:.2f}x CPU (answers identical)")


if __name__ == "__main__":
    main()

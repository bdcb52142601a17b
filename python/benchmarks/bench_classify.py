"""Python package speed: ``Domain.classify`` against the same Rust kernel timed without Python
(the call's overhead), and against ``shapely.contains_xy`` on the boundary flattened within
1e-10 (the Python user's alternative). Prints a Markdown table.

    python python/benchmarks/bench_classify.py [--sizes 1000000,10000000] [--reps 5]
        [--domain s5_lune] [--no-rust]

How the overhead is measured. For N points from 50,000 on, ``classify`` (method ``fast``, all
cores) runs the grid point locator, whose index the domain builds once and keeps. The package
has no timing hook of its own; the Rust figure comes from the project's benchmark, run here as

    cargo xtask bench --only locator --domains <domain> --sizes N --reps <reps>

whose table "Locator queries alone (index built once)" gives, in its "<k> threads, new vector"
column, the median throughput of ``PointLocator::locate_all_parallel`` on the same N Halton
points of the domain's bounding box (``inrs.halton_points(N, domain.bounds)`` makes the very
same points), on all cores, in a separate process without Python. Overhead = Python time /
Rust time - 1: the cost of crossing into Python (argument checks, the result array, the GIL
release) and of the package's chunked loop, against the library's own parallel call. The
report prints the throughput rounded to a whole million points per second, so the Rust time is
known to about +-0.5 Mpts/s (0.3% at 150 Mpts/s); both medians are taken on one machine but
not in the same run, so a noisy machine shows as scatter between runs. ``--no-rust`` skips
cargo (the first run builds xtask in release, a few minutes). ``--domain`` is a fixture of
``fixtures/inrs-paper/`` (the only domains ``cargo xtask bench`` takes).
"""

import argparse
import pathlib
import re
import statistics
import subprocess
import time

import numpy as np

import inrs

ROOT = pathlib.Path(__file__).resolve().parents[2]


def median_seconds(reps, f):
    times = []
    for _ in range(reps):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def rust_seconds(domain, n, reps):
    """Median seconds of ``locate_all_parallel`` on ``n`` Halton points of ``domain``, all
    cores, index built once, from ``cargo xtask bench --only locator`` (see the docstring)."""
    out = subprocess.run(
        ["cargo", "xtask", "bench", "--only", "locator", "--domains", domain, "--sizes", str(n),
         "--reps", str(reps)],
        cwd=ROOT, check=True, capture_output=True, text=True,
    ).stdout
    lines = out.splitlines()
    for i, line in enumerate(lines):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if cells[:2] != ["domain", "build"]:
            continue
        parallel = [k for k, c in enumerate(cells) if re.fullmatch(r"\d+ threads, new vector", c)]
        if not parallel:
            continue
        for row in lines[i + 2:]:
            if not row.startswith("|"):
                break
            values = [c.strip() for c in row.strip().strip("|").split("|")]
            if values[0] == domain:
                return n / (float(values[parallel[0]]) * 1e6)
    raise RuntimeError(
        f"no '<k> threads, new vector' figure for {domain} in the output of cargo xtask bench "
        "--only locator (has its table changed?)"
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", default="1000000,10000000")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--domain", default="s5_lune", help="a fixture name of fixtures/inrs-paper/")
    ap.add_argument("--no-rust", action="store_true", help="skip the Rust timing (no cargo)")
    args = ap.parse_args()
    d = inrs.Domain.load(ROOT / "fixtures" / "inrs-paper" / f"{args.domain}.json")
    try:
        import shapely

        rings = d.flatten(1e-10)
        polygon = shapely.Polygon(rings[0], rings[1:]) if len(rings) > 1 else shapely.Polygon(rings[0])
        shapely.prepare(polygon)
        sides = sum(len(r) for r in rings)
    except ImportError:
        shapely = None
    print(f"Domain {args.domain}, median of {args.reps} runs, all cores.\n")
    print("| N | Python classify | Rust kernel (cargo xtask bench) | overhead | Mpts/s | shapely.contains_xy (polygon within 1e-10) | inrs vs shapely |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for n in [int(s) for s in args.sizes.split(",")]:
        xy = inrs.halton_points(n, d.bounds)
        d.classify(xy[: inrs._inrs.FAST_METHOD_MIN_POINTS])  # build the locator's index
        t_py = median_seconds(args.reps, lambda: d.classify(xy))
        if args.no_rust:
            rust_cells = "- | -"
        elif n < inrs._inrs.FAST_METHOD_MIN_POINTS:
            rust_cells = "- | - (inRS2 below FAST_METHOD_MIN_POINTS, not the locator)"
        else:
            t_rs = rust_seconds(args.domain, n, args.reps)
            rust_cells = f"{t_rs:.4f} s | {100 * (t_py / t_rs - 1):.1f}%"
        if shapely is not None:
            reps = max(1, args.reps // 2)
            t_sh = median_seconds(reps, lambda: shapely.contains_xy(polygon, xy[:, 0], xy[:, 1]))
            inside = d.contains_xy(xy)
            agree = np.mean(inside == shapely.contains_xy(polygon, xy[:, 0], xy[:, 1]))
            shapely_cells = f"{t_sh:.3f} s ({sides} vertices, agree {agree:.6f})"
            ratio = f"{t_sh / t_py:.0f}x"
        else:
            shapely_cells, ratio = "shapely not installed", "-"
        print(
            f"| {n} | {t_py:.4f} s | {rust_cells} | {n / t_py / 1e6:.0f} | {shapely_cells} | {ratio} |"
        )


if __name__ == "__main__":
    main()

"""Python package speed: the Python call against the Rust kernel on the same points in the same
run (the call's overhead), and against shapely.contains_xy on the boundary flattened within
1e-10 (the Python user's alternative). Prints a Markdown table.

    python python/benchmarks/bench_classify.py [--sizes 1000000,10000000] [--reps 5]
"""

import argparse
import pathlib
import statistics
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


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1000000,10000000")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--domain", default=str(ROOT / "fixtures/inrs-paper/s5_lune.json"))
    args = ap.parse_args()
    d = inrs.Domain.load(args.domain)
    xmin, ymin, xmax, ymax = d.bounds
    try:
        import shapely

        rings = d.flatten(1e-10)
        polygon = shapely.Polygon(rings[0], rings[1:]) if len(rings) > 1 else shapely.Polygon(rings[0])
        shapely.prepare(polygon)
        sides = sum(len(r) for r in rings)
    except ImportError:
        shapely = None
    print(f"Domain {pathlib.Path(args.domain).name}, median of {args.reps} runs, all cores.\n")
    print("| N | Python classify | Rust kernel | overhead | Mpts/s | shapely.contains_xy (polygon within 1e-10) | inrs vs shapely |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for n in [int(s) for s in args.sizes.split(",")]:
        xy = inrs.halton_points(n, (xmin, ymin, xmax, ymax))
        d.classify(xy[:1000])  # build the index
        t_py = median_seconds(args.reps, lambda: d.classify(xy))
        t_rs = statistics.median(d._kernel_seconds(xy) for _ in range(args.reps))
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
            f"| {n} | {t_py:.4f} s | {t_rs:.4f} s | {100 * (t_py / t_rs - 1):.1f}% | {n / t_py / 1e6:.0f} | {shapely_cells} | {ratio} |"
        )


if __name__ == "__main__":
    main()

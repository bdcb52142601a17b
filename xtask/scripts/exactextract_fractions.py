"""Cell coverage fractions by exactextract, timed: the peer of `cargo xtask bench --only coverage`.

Usage: python exactextract_fractions.py POLYGON.geojson XMIN YMIN XMAX YMAX NX NY REPS AREA

Reads one GeoJSON Feature (a Polygon or MultiPolygon: the flattened boundary), builds an
NX x NY raster over [XMIN, XMAX] x [YMIN, YMAX] (exactextract's NumPy raster source), and times
exact_extract's per-cell coverage fractions (ops cell_id and coverage, scattered into a dense
array, as a user wanting the fraction of every cell would) REPS times. Prints one line:
`seconds <fastest> <median> area_relative_error <|sum of fraction x cell area - AREA| / AREA>`.
Exits with status 2 and one line on stderr if exactextract cannot be imported.
"""

import json
import sys
import time


def main() -> int:
    try:
        import numpy as np
        from exactextract import exact_extract
        from exactextract.raster import NumPyRasterSource
    except ImportError as e:
        print(f"exactextract unavailable: {e}", file=sys.stderr)
        return 2
    path = sys.argv[1]
    xmin, ymin, xmax, ymax = (float(v) for v in sys.argv[2:6])
    nx, ny, reps = (int(v) for v in sys.argv[6:9])
    area = float(sys.argv[9])
    with open(path) as f:
        feature = json.load(f)
    raster = NumPyRasterSource(
        np.zeros((ny, nx), dtype=np.float32), xmin, ymin, xmax, ymax
    )
    times = []
    fractions = None
    for _ in range(max(reps, 1)):
        start = time.perf_counter()
        out = exact_extract(raster, [feature], ["cell_id", "coverage"], output="geojson")
        fractions = np.zeros(nx * ny)
        for props in (o["properties"] for o in out):
            fractions[np.asarray(props["cell_id"], dtype=np.int64)] += np.asarray(
                props["coverage"]
            )
        times.append(time.perf_counter() - start)
    cell = (xmax - xmin) / nx * ((ymax - ymin) / ny)
    error = abs(fractions.sum() * cell - area) / area
    times.sort()
    print(f"seconds {times[0]:.6f} {times[len(times) // 2]:.6f} area_relative_error {error:.3e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

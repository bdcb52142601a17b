"""OpenCASCADE's mass properties of whole CAD files, timed: the peer of `cargo xtask bench
--only properties` (which runs it).

For each file given: read it with OCC's STEP or IGES reader (not timed), then time
``BRepGProp.VolumeProperties`` plus ``BRepGProp.SurfaceProperties`` of the whole shape at OCC's
default (the fixed Gauss rule) and with the adaptive rule at ``eps = 1e-9`` (median of
``--reps`` runs each). Prints one line per file: ``ok default_s eps_s volume area`` (OCC's
volume and area at ``eps = 1e-9``, for the accuracy column), or ``error`` and the reason.
Needs OCP (``pip install cadquery-ocp-novtk``).
"""

import argparse
import statistics
import sys
import time


def read(path: str):
    from OCP.IFSelect import IFSelect_RetDone

    if path.lower().endswith((".igs", ".iges")):
        from OCP.IGESControl import IGESControl_Reader as Reader
    else:
        from OCP.STEPControl import STEPControl_Reader as Reader
    reader = Reader()
    if reader.ReadFile(path) != IFSelect_RetDone:
        raise RuntimeError(f"{path}: OCC cannot read it")
    reader.TransferRoots()
    return reader.OneShape()


def properties(shape, eps):
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    volume, area = GProp_GProps(), GProp_GProps()
    if eps is None:
        BRepGProp.VolumeProperties_s(shape, volume)
        BRepGProp.SurfaceProperties_s(shape, area)
    else:
        BRepGProp.VolumeProperties_s(shape, volume, eps, True)
        BRepGProp.SurfaceProperties_s(shape, area, eps, True)
    return volume.Mass(), area.Mass()


def timed(shape, eps, reps):
    times = []
    for _ in range(reps):
        start = time.perf_counter()
        got = properties(shape, eps)
        times.append(time.perf_counter() - start)
    return statistics.median(times), got


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+")
    parser.add_argument("--reps", type=int, default=3)
    args = parser.parse_args()
    for path in args.files:
        try:
            shape = read(path)
            default_s, _ = timed(shape, None, args.reps)
            eps_s, (volume, area) = timed(shape, 1e-9, args.reps)
            row = f"ok {default_s!r} {eps_s!r} {volume!r} {area!r}"
        except Exception as e:  # one file's failure is its row
            row = "error " + (str(e).splitlines()[0] if str(e) else type(e).__name__)
        print(row, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""OpenCASCADE's point-in-solid test, timed: the peer of `cargo xtask bench --only solid` (which
runs it).

``occ_solid.py FILE POINTS [--tol T]``: reads ``FILE`` with OCC's STEP or IGES reader (not
timed), lists its solids with ``TopExp_Explorer(shape, TopAbs_SOLID)`` (the order of inrs's
solid indices), and classifies the points of ``POINTS`` (text, one ``k x y z`` a line, in
millimetres, OCC's unit) against solid ``k``: ``BRepClass3d_SolidClassifier(solid)`` built once
per solid (timed), then ``Perform(gp_Pnt(x, y, z), T)`` and ``State()`` per point (timed over all
the solid's points, the Python loop included). Prints JSON objects, one a line: first
``{"solids": n, "overhead_s": s}`` (``s``: seconds per point of the same loop making the
``gp_Pnt`` alone, the Python share of the timing), then per solid
``{"solid": k, "n": count, "build_s": s, "perform_s": s, "states": "IO..."}`` (``I`` IN, ``O``
OUT, ``N`` ON, ``U`` UNKNOWN, in the order of the points) or ``{"solid": k, "error": why}``; or
one ``{"error": why}`` when the file cannot be read.

``occ_solid.py --write-parts DIR``: writes the OCC test parts of ``python/tests/cad_parts.py``
(STEP and IGES B-rep mode) into ``DIR`` and prints their paths, one a line.

Needs OCP (``pip install cadquery-ocp-novtk``).
"""

import argparse
import json
import pathlib
import sys
import time

# The one reader of a STEP or IGES file into an OCC shape: occ_properties.py's, beside this one.
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from occ_properties import read  # noqa: E402


def quiet():
    """Silences OpenCASCADE's messages below failures (its readers print to standard output)."""
    from OCP.Message import Message, Message_Gravity

    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)


def solids(shape) -> list:
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    found = []
    e = TopExp_Explorer(shape, TopAbs_SOLID)
    while e.More():
        found.append(TopoDS.Solid(e.Current()))
        e.Next()
    return found


def read_points(path: str) -> dict:
    """``{k: [(x, y, z), ...]}`` in the file's order."""
    points: dict = {}
    with open(path) as f:
        for line in f:
            w = line.split()
            if len(w) == 4:
                points.setdefault(int(w[0]), []).append((float(w[1]), float(w[2]), float(w[3])))
    return points


def classify(path: str, points_path: str, tol: float) -> None:
    from OCP.BRepClass3d import BRepClass3d_SolidClassifier
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_IN, TopAbs_ON, TopAbs_OUT

    letter = {TopAbs_IN: "I", TopAbs_OUT: "O", TopAbs_ON: "N"}
    try:
        found = solids(read(path))
    except Exception as e:  # the file's failure is the answer
        print(json.dumps({"error": str(e).splitlines()[0] if str(e) else type(e).__name__}))
        return
    points = read_points(points_path)
    # The Python share of the loop below: the same loop making the points alone.
    everything = [p for ps in points.values() for p in ps]
    start = time.perf_counter()
    for x, y, z in everything:
        gp_Pnt(x, y, z)
    overhead = (time.perf_counter() - start) / max(len(everything), 1)
    print(json.dumps({"solids": len(found), "overhead_s": overhead}), flush=True)
    for k, ps in points.items():
        if k >= len(found):
            print(json.dumps({"solid": k, "error": f"OCC finds {len(found)} solids"}), flush=True)
            continue
        try:
            start = time.perf_counter()
            c = BRepClass3d_SolidClassifier(found[k])
            build = time.perf_counter() - start
            states = []
            start = time.perf_counter()
            for x, y, z in ps:
                c.Perform(gp_Pnt(x, y, z), tol)
                states.append(c.State())
            perform = time.perf_counter() - start
            row = {
                "solid": k,
                "n": len(ps),
                "build_s": build,
                "perform_s": perform,
                "states": "".join(letter.get(s, "U") for s in states),
            }
        except Exception as e:  # one solid's failure is its row
            row = {"solid": k, "error": str(e).splitlines()[0] if str(e) else type(e).__name__}
        print(json.dumps(row), flush=True)


def write_parts(directory: str) -> None:
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "python" / "tests"))
    import cad_parts

    for part in cad_parts.write_parts(pathlib.Path(directory)).values():
        print(part.step)
        print(part.iges_brep)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="*")
    parser.add_argument("--tol", type=float, default=1e-7)
    parser.add_argument("--write-parts", metavar="DIR")
    args = parser.parse_args()
    quiet()
    if args.write_parts:
        write_parts(args.write_parts)
        return 0
    if len(args.files) != 2:
        parser.error("give FILE POINTS")
    classify(args.files[0], args.files[1], args.tol)
    return 0


if __name__ == "__main__":
    sys.exit(main())

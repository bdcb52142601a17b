"""Markdown tables of the real CAD files against OpenCASCADE, for docs/CAD.md.

    python python/tests/cad_table.py [FILE ...] [--points N] [--parts]

Without files: the files of test_cad_occ.py (freecad-common's IDF parts and gmsh-doc's demos;
the gzipped ones are decompressed into a temporary directory); ``--parts`` adds the test parts
OCC makes (cad_parts.py: STEP, IGES faces mode and IGES B-rep mode). For each file: the faces OCC
reads, what ``inrs.occ.face_domain`` makes of them and how its classification compares with
OCC's, then, where this build has ``inrs.cad_model`` (the Rust readers), the faces read and
refused (with the distinct reasons), the faces with fitted pcurves, the largest distance of our
surfaces from OCC's (relative to the part's size), and the same comparison. Needs OCP (``pip install
cadquery-ocp-novtk``); missing files are listed, not fatal.
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import tempfile
import time

import inrs

import cad_files
from cad_files import OccFile


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "files", nargs="*", type=pathlib.Path, help="STEP/IGES files (.gz too); default: the test's files"
    )
    parser.add_argument("--points", type=int, default=cad_files.POINTS_PER_FACE, help="random (u, v) points per face")
    parser.add_argument("--parts", action="store_true", help="add the test parts OCC makes (cad_parts.py)")
    args = parser.parse_args(argv)
    try:
        cad_files.load_ocp()
    except ImportError as e:
        print(f"OCP is not installed (pip install cadquery-ocp-novtk): {e}", file=sys.stderr)
        return 2
    sources = [(p.name[: -len(".gz")] if p.suffix == ".gz" else p.name, p) for p in args.files] or cad_files.all_files()
    readers = hasattr(inrs, "cad_model")
    occ_rows, reader_rows, reasons, missing = [], [], [], []
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as scratch:
        if args.parts:
            import cad_parts

            cad_parts.quiet()
            parts = cad_parts.write_parts(pathlib.Path(scratch) / "parts")
            sources += [(path.name, path) for part in parts.values() for path in part.files().values()]
        for name, source in sources:
            if not source.exists():
                missing.append(cad_files.missing_message(source))
                continue
            path = cad_files.materialize(source, pathlib.Path(scratch))
            occ = OccFile.read(path)
            for k in range(len(occ.faces)):
                occ.face_sample(k, args.points)
            a = cad_files.check_occ_faces(occ)
            occ_rows.append(
                [name, occ.format, a.faces, a.built, len(a.open), len(a.degenerate)]
                + [a.compared, a.excluded, len(a.disagreements)]
            )
            if a.problems:
                reasons.append((name, "inrs.occ", {p: [] for p in a.problems}))
            if readers:
                try:
                    b = cad_files.check_readers(path, occ)
                except (OSError, ValueError) as e:
                    reader_rows.append([name, a.faces, "file refused"] + [""] * 7)
                    reasons.append((name, "inrs.cad_model", {str(e): []}))
                    continue
                refused = sum(map(len, b.refused.values()))
                reader_rows.append(
                    [name, b.occ_faces, b.faces, b.read, refused, b.fitted]
                    + [f"{b.surface_deviation:.1e}", b.compared, len(b.disagreements), b.other_parameterisation]
                )
                if b.refused or b.problems:
                    reasons.append((name, "inrs.cad_model", {**b.refused, **{p: [] for p in b.problems}}))
    print(f"Points per face: {args.points}, in each face's (u, v) box grown by 5% on each side; points")
    print("on the boundary for either side or within 1e-5 of the box diagonal of a loop are left out.\n")
    print("#### `inrs.occ.face_domain` (OCC's pcurves) against `BRepClass_FaceClassifier`\n")
    print(f"Closure tolerance: {cad_files.closure_kwargs().get('closure_tol', 1e-9):g} of the diagonal.\n")
    table(
        ["File", "Format", "Faces (OCC)", "Built", "Open (gap)", "Degenerate"]
        + ["Points compared", "Left out", "Disagree"],
        occ_rows,
    )
    if readers:
        print("\n#### `inrs.cad_model` (the readers and surfaces) against OpenCASCADE\n")
        table(
            ["File", "Faces (OCC)", "Faces (inrs)", "Read", "Refused", "Fitted pcurves"]
            + ["Surface deviation / size", "Points compared", "Disagree", "Not compared (parameterisation)"],
            reader_rows,
        )
    else:
        print("\n(This build of inrs has no `cad_model`: the readers' columns are left out.)")
    if reasons:
        print("\n#### Refusals and problems\n")
        for name, who, found in reasons:
            for text, faces in found.items():
                shown = ", ".join(map(str, faces[:12])) + (", ..." if len(faces) > 12 else "")
                print(f"- {name}, {who}: {text}" + (f" ({len(faces)} faces: {shown})" if faces else ""))
    for m in missing:
        print(f"- missing: {m}")
    print(f"\n({time.perf_counter() - start:.0f} s)", file=sys.stderr)
    return 0


def table(header, rows) -> None:
    """Prints a Markdown table, numbers right-aligned, and a row of totals."""
    print("| " + " | ".join(header) + " |")
    print("|" + "|".join("---" if i == 0 else "---:" for i in range(len(header))) + "|")
    for row in rows:
        print("| " + " | ".join(f"`{c}`" if i == 0 else str(c) for i, c in enumerate(row)) + " |")
    totals = ["**all**"] + [
        str(sum(r[i] for r in rows if isinstance(r[i], int))) if any(isinstance(r[i], int) for r in rows) else ""
        for i in range(1, len(header))
    ]
    print("| " + " | ".join(totals) + " |")


if __name__ == "__main__":
    sys.exit(main())

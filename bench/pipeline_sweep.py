#!/usr/bin/python3
"""Runs decimate -> trace -> flip -> refine -> check -> overlay on every mesh of a folder (default ../shared/data)
with the geotri tools, and prints a Markdown table: faces, coarse faces, validity after trace, after flip (with the
minimum corner angle) and at the end (with the conditions that failed), and the wall time of each tool, loading and
writing included. G is refined only when flip made it valid.

    bench/pipeline_sweep.py [--faces N | --coarsest] [--min-angle A] [--threads N] [--timeout S] [--build DIR]
                            [--data DIR] [--keep DIR] [--require [--open MESH]...] [MESH ...]

Where the topology stops decimation above N faces, the mesh is what geotri-decimate gives: that coarsest mesh, or
a finer one where the coarsest one's geodesics tangle (it backs off). --coarsest decimates every mesh as coarse as
its topology allows (geotri-decimate --coarsest), as a target of 4 faces did before the back-off. The outputs
go to a temporary folder that is removed at the end, or with --keep to DIR, where they stay (MESH.off, .paths,
.gtri, .flip.gtri, .refine.gtri, .vtu, named by the mesh's file name without its extension).

With --require (the test sweep of CI), it exits 1 unless every mesh is valid after flip and at the end, reaches the
angle with no corner left below it but at cones of T that force one, and its overlay covers T, and unless every mesh
named by --open (relative to --data: meshes with a boundary) is refused by geotri-decimate; stderr names the meshes
that fall short. Without meshes (no --data folder), it says so and exits 77, which ctest counts as skipped.
"""
import argparse
import contextlib
import pathlib
import sys
import tempfile

import geotri_tools

ROOT = pathlib.Path(__file__).resolve().parent.parent


TIMEOUT = 600.0  # seconds per tool run; set by --timeout


def run(tool, args, build):
    return geotri_tools.run(tool, args, build, TIMEOUT)


def verdict_of(check):
    """'valid', or 'invalid (conditions)' from geotri-check's summary."""
    if check["valid"]:
        return "valid"
    return "invalid (" + ", ".join(str(c) for c in range(1, 5) if check[f"condition_{c}"] > 0) + ")"


def sweep_one(mesh, options, work):
    """One table row: decimate -> trace -> flip -> refine -> check -> overlay on `mesh`."""
    name = str(mesh.relative_to(options.data)) if mesh.is_relative_to(options.data) else mesh.name
    stem = work / mesh.stem
    for suffix in OUTPUTS:  # with --keep, what an earlier run left must not pass for this run's
        pathlib.Path(f"{stem}{suffix}").unlink(missing_ok=True)
    threads = ["--threads", str(options.threads)] if options.threads else []
    times = {}
    row = [name]
    short = []  # what --require asks that this mesh does not meet

    def stop(why, ok=False):
        cells = row + [why] + ["-"] * (6 - len(row))
        cells += [f"{times[t]:.2f}" if t in times else "-" for t in STAGES]
        cells.append(f"{sum(times.values()):.2f}")
        if not ok:
            short.append(why)
        return "| " + " | ".join(cells) + " |", short

    target = ["--coarsest"] if options.coarsest else ["--faces", str(options.faces)]
    code, dec, times["decimate"], err = run("decimate", [str(mesh), "-o", f"{stem}.off", "--paths", f"{stem}.paths",
                                                        *target],
                                            options.build)
    if code != 0:
        return stop(f"refused: {err.splitlines()[-1] if err else code}", ok=name in options.open and code == 1)
    if name in options.open:
        short.append("a mesh with a boundary was not refused")
    row += [str(dec["faces"]), str(dec["coarse_faces"])]
    code, _, times["trace"], err = run("trace", [str(mesh), f"{stem}.off", "--paths", f"{stem}.paths", "-o",
                                                     f"{stem}.gtri", *threads],
                                       options.build)
    if code != 0:
        return stop(f"trace failed: {err}")
    code, chk, _, err = run("check", [f"{stem}.gtri"], options.build)
    if chk is None:
        return stop(f"check failed: {err}")
    row.append(verdict_of(chk))
    thorough = ["--thorough", str(options.thorough)] if options.thorough is not None else []
    code, flp, times["flip"], err = run("flip", [f"{stem}.gtri", "-o", f"{stem}.flip.gtri", *threads, *thorough],
                                        options.build)
    if flp is None:
        return stop(f"flip failed: {err}")
    row.append(("valid" if flp["valid"] else "INVALID") +
               f", {flp['min_corner_angle_deg_before']:.1f}° → {flp['min_corner_angle_deg']:.1f}°")
    if not flp["valid"]:
        short.append("invalid after flip")
    final = f"{stem}.flip.gtri"
    if flp["valid"] and options.min_angle > 0:
        code, ref, times["refine"], err = run("refine", [final, "-o", f"{stem}.refine.gtri", "--min-angle",
                                                         str(options.min_angle)], options.build)
        if ref is None:
            return stop(f"refine failed: {err}")
        row.append(f"{ref['faces']} faces, {ref['min_corner_angle_deg']:.1f}°" +
                   (f", {ref['small_corners_left']} left" if ref["small_corners_left"] else "") +
                   (f", {ref['wide_corners_left']} above 180°" if ref.get("wide_corners_left") else "") +
                   ("" if ref["valid"] else ", INVALID"))
        if ref["small_corners_left"]:
            short.append(f"{ref['small_corners_left']} corners below {options.min_angle:g}°")
        final = f"{stem}.refine.gtri"
    else:
        row.append("-")
    code, chk, times["check"], err = run("check", [final], options.build)
    if chk is None:
        return stop(f"check failed: {err}")
    code, ov, times["overlay"], err = run("overlay", [final, "-o", f"{stem}.vtu"], options.build)
    if ov is None:
        return stop(f"overlay failed: {err}")
    result = verdict_of(chk)
    if chk["valid"] and ov["relative_area_error"] > 1e-9:
        result += f", AREA MISMATCH {ov['relative_area_error']:.1e}"
    return stop(result, ok=result == "valid")


STAGES = ["decimate", "trace", "flip", "refine", "check", "overlay"]
OUTPUTS = [".off", ".paths", ".gtri", ".flip.gtri", ".refine.gtri", ".vtu"]  # after the mesh's name


def main():
    global TIMEOUT
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("meshes", nargs="*", type=pathlib.Path)
    target = parser.add_mutually_exclusive_group()
    target.add_argument("--faces", type=int, default=320)
    target.add_argument("--coarsest", action="store_true", help="decimate as coarse as the topology allows")
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--min-angle", type=float, default=25.0, help="refine to this angle (0: no refinement)")
    parser.add_argument("--thorough", type=int, choices=[0, 1, 2],
                        help="geotri-flip --thorough LEVEL (default: geotri-flip's own, level 2 within its budget)")
    parser.add_argument("--timeout", type=float, default=TIMEOUT, help="stop a tool run after this many seconds")
    parser.add_argument("--build", type=pathlib.Path, default=ROOT / "build")
    parser.add_argument("--data", type=pathlib.Path, default=ROOT.parent / "shared" / "data")
    parser.add_argument("--keep", type=pathlib.Path, help="write the outputs to this folder and keep them")
    parser.add_argument("--require", action="store_true",
                        help="exit 1 unless every mesh is valid after flip and at the end, and reaches the angle")
    parser.add_argument("--open", action="append", default=[], metavar="MESH",
                        help="with --require: a mesh (relative to --data) that geotri-decimate must refuse; repeatable")
    options = parser.parse_args()
    options.data = options.data.resolve()
    TIMEOUT = options.timeout
    meshes = options.meshes or sorted(p for p in options.data.rglob("*")
                                      if p.suffix in (".off", ".obj", ".ply", ".stl") and p.is_file())
    if not meshes:
        print(f"pipeline_sweep.py: no meshes under {options.data}: nothing to sweep", file=sys.stderr)
        sys.exit(77 if options.require else 1)
    if options.keep:
        # The outputs are named after the meshes (MESH.off among them): never in a folder that holds one.
        if any(mesh.resolve().parent == options.keep.resolve() for mesh in meshes):
            sys.exit(f"pipeline_sweep.py: --keep {options.keep} holds a mesh of the sweep; give another folder")
        options.keep.mkdir(parents=True, exist_ok=True)
    print("| mesh | faces | coarse faces | traced | flipped, min angle | refined | final | " +
          " | ".join(f"{stage} (s)" for stage in STAGES) + " | total (s) |")
    print("|---|---:|---:|---|---|---|---|" + "---:|" * (len(STAGES) + 1))
    folder = (contextlib.nullcontext(options.keep) if options.keep
              else tempfile.TemporaryDirectory(prefix="geotri-sweep-"))
    falling_short = []
    with folder as work:
        for mesh in meshes:
            row, short = sweep_one(mesh.resolve(), options, pathlib.Path(work))
            print(row, flush=True)
            if short:
                falling_short.append(f"{mesh}: {'; '.join(short)}")
    if options.require and falling_short:
        print(f"pipeline_sweep.py: {len(falling_short)} of {len(meshes)} meshes fall short:", file=sys.stderr)
        for line in falling_short:
            print("  " + line, file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Runs geotri-curve on every G in a folder (the flipped G's that `pipeline_sweep.py --keep DIR` leaves there, by
default) and prints a Markdown table: G's faces, the elements made, how many are certified valid against their corners'
plane and against T, how many fail validity, quality or distance at the end, the smallest certified min J / max J, the
largest certified distance to T over the diagonal, the refinement rounds and the wall time of the run.

    bench/curve_sweep.py DIR [--suffix SUFFIX] [--order P] [--timeout S] [--build DIR]
                          [--curve-options "OPTIONS"] [NAME ...]

The curved meshes are written beside each G as NAME.curved.msh. A run stopped at the timeout gets a row that says so.
"""
import argparse
import pathlib
import sys

import geotri_tools

ROOT = pathlib.Path(__file__).resolve().parent.parent


def row_of(gtri, options):
    """One table row: geotri-curve on `gtri`."""
    name = gtri.name.removesuffix(options.suffix)
    output = gtri.with_name(name + ".curved.msh")
    code, summary, seconds, err = geotri_tools.run(
        "curve", [str(gtri), "-o", str(output), "--order", str(options.order), *options.curve_options],
        options.build, options.timeout)
    if summary is None:
        why = err.splitlines()[-1] if err else f"exit {code}"
        return f"| {name} | {why} |" + " |" * 6 + f" {seconds:.1f} |", False
    rounds = str(summary["refinement_rounds"]) + (" (cap)" if summary["round_cap_reached"] else "")
    cells = [name, str(summary["faces_before"]), str(summary["elements"]),
             f"{summary['certified_plane']}, {summary['certified_surface']}", str(summary["failing"]),
             f"{summary['min_quality']:.3f}", f"{summary['max_distance']:.2e}", rounds, f"{seconds:.1f}"]
    return "| " + " | ".join(cells) + " |", summary["failing"] == 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=pathlib.Path)
    parser.add_argument("meshes", nargs="*", help="only these names (NAME of NAME + SUFFIX)")
    parser.add_argument("--suffix", default=".flip.gtri", help="the files of FOLDER whose names end so are G")
    parser.add_argument("--order", type=int, default=3)
    parser.add_argument("--timeout", type=float, default=90.0, help="stop a run after this many seconds")
    parser.add_argument("--build", type=pathlib.Path, default=ROOT / "build")
    parser.add_argument("--curve-options", default="", help="more geotri-curve options, in one string")
    options = parser.parse_args()
    options.curve_options = options.curve_options.split()
    meshes = sorted(options.folder.glob("*" + options.suffix))
    if options.meshes:
        meshes = [m for m in meshes if m.name.removesuffix(options.suffix) in options.meshes]
    if not meshes:
        sys.exit(f"curve_sweep.py: no G (*{options.suffix}) in {options.folder}")
    print("| mesh | G faces | elements | certified (plane, T) | failing | smallest min J / max J "
          "| largest distance / diagonal | rounds | wall (s) |")
    print("|---|---:|---:|---|---:|---:|---:|---:|---:|")
    certified = 0
    for gtri in meshes:
        row, all_certified = row_of(gtri, options)
        certified += all_certified
        print(row, flush=True)
    print(f"\nEvery element certified: {certified} of {len(meshes)}")


if __name__ == "__main__":
    main()

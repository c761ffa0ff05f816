#!/usr/bin/python3
"""Runs geotri-curve on every G in a folder (the flipped G's that `pipeline_sweep.py --keep DIR` leaves there, by
default) and prints a Markdown table: G's faces, the elements made, how many are certified valid against their corners'
plane and against T, how many fail validity, quality or distance at the end, the smallest certified min J / max J, the
largest certified distance to T over the diagonal, the refinement rounds and the wall time of the run.

    bench/curve_sweep.py DIR [--suffix SUFFIX] [--order P] [--timeout S] [--build DIR]
                          [--curve-options "OPTIONS"] [--check-with-gmsh] [NAME ...]

The curved meshes are written beside each G as NAME.curved.msh. A run stopped at the timeout gets a row that says so.

With --check-with-gmsh, gmsh's own Jacobian check (Plugin(AnalyseMeshQuality), python3-gmsh) judges every file, and
the sweep exits 1 unless it agrees with geotri-curve's certificates on every element of every mesh: no element that
gmsh finds inverted is certified valid against its corners' plane, and every element that geotri-curve certifies
has gmsh's min J / max J at least the smallest quality allowed (--min-quality, 0.1 unless --curve-options says
otherwise). A run that crashes or stops at the timeout fails the sweep too; elements that geotri-curve leaves
uncertified (exit 3) do not. Exits 77, skipped, when python3-gmsh is missing or FOLDER holds no G.
"""
import argparse
import pathlib
import sys

import geotri_tools

ROOT = pathlib.Path(__file__).resolve().parent.parent


def gmsh_quality(msh):
    """gmsh's min J / max J of each element of `msh`, by element tag, from its own Bezier-bounded check."""
    import gmsh
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.merge(str(msh))
        gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 1)
        gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 1)
        gmsh.plugin.run("AnalyseMeshQuality")
        for view in gmsh.view.getTags():
            if gmsh.option.getString(f"View[{gmsh.view.getIndex(view)}].Name").startswith("minJ/maxJ"):
                _, tags, data, _, _ = gmsh.view.getModelData(view, 0)
                return {int(tag): values[0] for tag, values in zip(tags, data)}
        return {}
    finally:
        gmsh.finalize()


def disagreements_with_gmsh(msh, summary, min_quality):
    """Where gmsh's check of `msh` contradicts geotri-curve's certificates (its --json `summary`): a list of lines."""
    quality = gmsh_quality(msh)
    if len(quality) != summary["elements"]:
        return [f"gmsh judges {len(quality)} elements of {summary['elements']}"]
    # Element tags are coarse faces plus one.
    failing = {f["face"] + 1: f for f in summary["failing_elements"]}
    found = []
    for tag, value in sorted(quality.items()):
        if tag in failing:
            if value <= 0 and failing[tag]["plane"] == "valid":
                found.append(f"element {tag}: gmsh finds it inverted (min J / max J {value:.3g}), geotri-curve "
                             "certifies it valid against its corners' plane")
        elif value < min_quality:
            found.append(f"element {tag}: certified with min J / max J >= {min_quality}, gmsh finds {value:.3g}")
    return found


def row_of(gtri, options):
    """One table row: geotri-curve on `gtri`, and whether all its elements are certified. With --check-with-gmsh,
    the lines where gmsh disagrees are appended to options.disagreements."""
    name = gtri.name.removesuffix(options.suffix)
    output = gtri.with_name(name + ".curved.msh")
    code, summary, seconds, err = geotri_tools.run(
        "curve", [str(gtri), "-o", str(output), "--order", str(options.order), *options.curve_options],
        options.build, options.timeout)
    if summary is None:
        why = err.splitlines()[-1] if err else f"exit {code}"
        options.disagreements.append(f"{name}: {why}")
        return f"| {name} | {why} |" + " |" * 6 + f" {seconds:.1f} |", False
    if options.check_with_gmsh:
        options.disagreements += [f"{name}: {line}" for line in
                                  disagreements_with_gmsh(output, summary, options.min_quality)]
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
    parser.add_argument("--check-with-gmsh", action="store_true",
                        help="judge every file with gmsh's Jacobian check; exit 1 where it disagrees")
    options = parser.parse_args()
    options.curve_options = options.curve_options.split()
    quality_option = [i for i, o in enumerate(options.curve_options) if o == "--min-quality"]
    options.min_quality = float(options.curve_options[quality_option[-1] + 1]) if quality_option else 0.1
    options.disagreements = []
    if options.check_with_gmsh:
        try:
            import gmsh  # noqa: F401
        except ImportError as missing:
            print(f"curve_sweep.py: skipped: {missing}", file=sys.stderr)
            sys.exit(77)
    meshes = sorted(options.folder.glob("*" + options.suffix))
    if options.meshes:
        meshes = [m for m in meshes if m.name.removesuffix(options.suffix) in options.meshes]
    if not meshes:
        print(f"curve_sweep.py: no G (*{options.suffix}) in {options.folder}", file=sys.stderr)
        sys.exit(77 if options.check_with_gmsh else 1)
    print("| mesh | G faces | elements | certified (plane, T) | failing | smallest min J / max J "
          "| largest distance / diagonal | rounds | wall (s) |")
    print("|---|---:|---:|---|---:|---:|---:|---:|---:|")
    certified = 0
    for gtri in meshes:
        row, all_certified = row_of(gtri, options)
        certified += all_certified
        print(row, flush=True)
    print(f"\nEvery element certified: {certified} of {len(meshes)}")
    if options.disagreements:
        print("\nFailures" + (" and disagreements with gmsh's check" if options.check_with_gmsh else "") + ":")
        for line in options.disagreements:
            print(f"- {line}")
        if options.check_with_gmsh:
            sys.exit(1)
    elif options.check_with_gmsh:
        print("gmsh's check agrees with every certificate")


if __name__ == "__main__":
    main()

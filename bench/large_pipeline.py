#!/usr/bin/python3
"""The whole pipeline on a mesh of millions of faces, each tool a process of its own: decimate to 320 faces, trace,
flip, refine to 25 degrees, check and overlay. Prints a Markdown table of each tool's wall seconds and peak resident
memory (from /usr/bin/time), loading and writing included, and the totals.

    bench/large_pipeline.py [--faces N] [--mesh MESH] [--threads N] [--work DIR] [--build DIR]

The large mesh is made from a shared one (default classic/bunny_closed_cgal.off) and kept in --work (default
/tmp/geotri-large) for the next run: Loop-subdivided once (geotri-bench-subdivide, OpenMesh's subdivider), decimated
to N/16 faces by geotri-decimate, then Loop-subdivided twice, for N faces (default 4.3M). Needs a build with the
benchmarks (GEOTRI_BUILD_BENCH, on by default).
"""
import argparse
import pathlib
import subprocess
import sys

import geotri_tools

ROOT = pathlib.Path(__file__).resolve().parent.parent


def timed(tool, args, build):
    """Runs geotri-TOOL with --json --quiet under /usr/bin/time; returns (exit code, parsed JSON or None, stderr,
    wall seconds, peak resident bytes)."""
    done = subprocess.run(["/usr/bin/time", "-f", "@@time %e %M", *geotri_tools.command(tool, args, build)],
                          capture_output=True, text=True)
    lines = done.stderr.splitlines()
    marks = [line for line in lines if line.startswith("@@time ")]
    if not marks:
        sys.exit(f"large_pipeline.py: no timing from geotri-{tool}: {done.stderr.strip()}")
    _, wall, kilobytes = marks[-1].split()
    stderr = "\n".join(line for line in lines if not line.startswith("@@time "))
    return done.returncode, geotri_tools.summary_of(done.stdout), stderr, float(wall), int(kilobytes) * 1024


def make_mesh(options):
    """The subdivided mesh of options.faces faces in options.work, made once."""
    mesh = options.work / f"{options.mesh.stem}_{options.faces}.ply"
    if mesh.exists():
        return mesh
    options.work.mkdir(parents=True, exist_ok=True)
    subdivide = options.build / "bench" / "geotri-bench-subdivide"
    if not subdivide.exists():
        sys.exit(f"large_pipeline.py: {subdivide} not found: build with the benchmarks (GEOTRI_BUILD_BENCH=ON)")
    once = options.work / f"{options.mesh.stem}_once.ply"
    decimated = options.work / f"{options.mesh.stem}_{options.faces // 16}.off"
    steps = [[subdivide, options.mesh, once, 1],
             [geotri_tools.tool_path(options.build, "decimate"), once, "-o", decimated, "--faces",
              options.faces // 16, "--quiet"],
             [subdivide, decimated, mesh, 2]]
    for step in steps:
        print(f"large_pipeline.py: {' '.join(map(str, step))}", file=sys.stderr)
        if subprocess.run(list(map(str, step)), stdout=sys.stderr).returncode != 0:
            mesh.unlink(missing_ok=True)
            sys.exit(f"large_pipeline.py: {step[0]} failed")
    return mesh


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--faces", type=int, default=4_300_000)
    parser.add_argument("--mesh", type=pathlib.Path, default=ROOT.parent / "shared" / "data" / "classic" /
                        "bunny_closed_cgal.off")
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--work", type=pathlib.Path, default=pathlib.Path("/tmp/geotri-large"))
    parser.add_argument("--build", type=pathlib.Path, default=ROOT / "build")
    options = parser.parse_args()
    if not options.mesh.is_file():
        sys.exit(f"large_pipeline.py: {options.mesh}: no such mesh")
    mesh = make_mesh(options)
    stem = options.work / mesh.stem
    threads = ["--threads", str(options.threads)] if options.threads else []
    steps = [
        ("decimate", [mesh, "-o", f"{stem}.off", "--paths", f"{stem}.paths", "--faces", "320"]),
        ("trace", [mesh, f"{stem}.off", "--paths", f"{stem}.paths", "-o", f"{stem}.gtri", *threads]),
        ("flip", [f"{stem}.gtri", "-o", f"{stem}.flip.gtri", *threads]),
        ("refine", [f"{stem}.flip.gtri", "-o", f"{stem}.refine.gtri", "--min-angle", "25", *threads]),
        ("check", [f"{stem}.refine.gtri", *threads]),
        ("overlay", [f"{stem}.refine.gtri", "-o", f"{stem}.vtu", *threads]),
    ]
    print(f"{mesh.name}: the pipeline, {options.threads or 'all'} threads\n")
    print("| tool | wall (s) | peak memory (MB) | result |")
    print("|---|---:|---:|---|")
    total, peak = 0.0, 0
    for tool, args in steps:
        code, summary, err, wall, memory = timed(tool, args, options.build)
        summary = summary or {}
        if tool == "decimate":
            result = f"{summary.get('coarse_faces')} coarse faces from {summary.get('faces')}"
        elif tool in ("flip", "check"):
            result = "valid" if summary.get("valid") else "INVALID"
        elif tool == "refine":
            result = (f"{summary.get('faces')} faces, {summary.get('min_corner_angle_deg', 0):.1f}°, "
                      f"{summary.get('small_corners_left')} corners left")
        else:
            result = ""
        if code not in (0, 3):
            result = f"failed ({code}): {err.splitlines()[-1] if err else ''}"
        print(f"| geotri-{tool} | {wall:.1f} | {memory / 1e6:.0f} | {result} |", flush=True)
        total += wall
        peak = max(peak, memory)
        if code not in (0, 3):
            break
    print(f"| **total** | **{total:.1f}** | **{peak / 1e6:.0f}** | |")


if __name__ == "__main__":
    main()

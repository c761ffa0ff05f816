#!/usr/bin/python3
"""Runs decimate -> trace -> check -> overlay on every mesh of a folder (default ../shared/data) with the geotri
tools, and prints a Markdown table: faces, coarse faces, validity (and the conditions that failed) and the wall
time of each tool, loading and writing included.

    bench/pipeline_sweep.py [--faces N] [--threads N] [--build DIR] [--data DIR] [MESH ...]

Meshes whose topology needs more than N faces are decimated to the coarsest that it allows instead. The outputs
go to a temporary folder that is removed at the end.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def run(tool, args, build):
    """Runs geotri-TOOL with --json --quiet; returns (exit code, parsed JSON or None, wall seconds, stderr)."""
    start = time.perf_counter()
    done = subprocess.run([str(build / "tools" / f"geotri-{tool}"), "--json", "--quiet", *args],
                          capture_output=True, text=True)
    seconds = time.perf_counter() - start
    try:
        summary = json.loads(done.stdout) if done.stdout.strip() else None
    except json.JSONDecodeError:
        summary = None
    return done.returncode, summary, seconds, done.stderr.strip()


def sweep_one(mesh, options, work):
    name = str(mesh.relative_to(options.data)) if mesh.is_relative_to(options.data) else mesh.name
    stem = work / mesh.stem
    threads = ["--threads", str(options.threads)] if options.threads else []
    code, dec, t_dec, err = run("decimate", [str(mesh), "-o", f"{stem}.off", "--faces", str(options.faces)], options.build)
    if code != 0:
        return f"| {name} | - | - | refused: {err.splitlines()[-1] if err else code} | - | - | - | - | - |"
    if not dec["target_reached"]:  # the topology needs more faces: take the coarsest
        code, dec, t_dec, err = run("decimate", [str(mesh), "-o", f"{stem}.off", "--coarsest"], options.build)
    code, tr, t_tr, err = run("trace", [str(mesh), f"{stem}.off", "-o", f"{stem}.gtri", *threads], options.build)
    if code != 0:
        return f"| {name} | {dec['faces']} | {dec['coarse_faces']} | trace failed: {err} | {t_dec:.2f} | - | - | - | - |"
    code, chk, t_chk, err = run("check", [f"{stem}.gtri"], options.build)
    if chk is None:
        return f"| {name} | {dec['faces']} | {dec['coarse_faces']} | check failed: {err} | {t_dec:.2f} | {t_tr:.2f} | - | - | - |"
    failed = [str(c) for c in range(1, 5) if chk[f"condition_{c}"] > 0]
    verdict = "valid" if chk["valid"] else "invalid (" + ", ".join(failed) + ")"
    code, ov, t_ov, err = run("overlay", [f"{stem}.gtri", "-o", f"{stem}.vtu"], options.build)
    if ov is None:
        return f"| {name} | {dec['faces']} | {dec['coarse_faces']} | {verdict}; overlay failed: {err} | {t_dec:.2f} | {t_tr:.2f} | {t_chk:.2f} | - | - |"
    if chk["valid"] and ov["relative_area_error"] > 1e-9:
        verdict += f", AREA MISMATCH {ov['relative_area_error']:.1e}"
    total = t_dec + t_tr + t_chk + t_ov
    return (f"| {name} | {dec['faces']} | {dec['coarse_faces']} | {verdict} | {t_dec:.2f} | {t_tr:.2f} | "
            f"{t_chk:.2f} | {t_ov:.2f} | {total:.2f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("meshes", nargs="*", type=pathlib.Path)
    parser.add_argument("--faces", type=int, default=320)
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--build", type=pathlib.Path, default=ROOT / "build")
    parser.add_argument("--data", type=pathlib.Path, default=ROOT.parent / "shared" / "data")
    options = parser.parse_args()
    options.data = options.data.resolve()
    meshes = options.meshes or sorted(p for p in options.data.rglob("*")
                                      if p.suffix in (".off", ".obj", ".ply", ".stl") and p.is_file())
    if not meshes:
        sys.exit(f"pipeline_sweep.py: no meshes under {options.data}")
    print("| mesh | faces | coarse faces | result | decimate (s) | trace (s) | check (s) | overlay (s) | total (s) |")
    print("|---|---:|---:|---|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory(prefix="geotri-sweep-") as work:
        for mesh in meshes:
            print(sweep_one(mesh.resolve(), options, pathlib.Path(work)), flush=True)


if __name__ == "__main__":
    main()

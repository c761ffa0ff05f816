#!/usr/bin/python3
"""Times libgeodesic (geotri-bench-propagation, freeing and keeping windows) and VTP (bench/vtp/build.sh) on the
same meshes, in the same run, taking turns, and prints a Markdown table: the median over the rounds of each
program's median of 3 propagations (CPU seconds), each one's peak memory, and the largest difference of their
distances relative to the largest distance.

    bench/vtp/compare.py [--rounds N] [--build DIR] [--vtp BINARY] MESH...

MESH is what geotri-bench-propagation takes (a file, or gen:KIND:FACES); each is written once as OBJ for VTP, which
reads only OBJ. The source is vertex num_vertices / 2, as the benchmark's default. VTP handles one connected
component only (it exits on the lumbar spine).
"""
import argparse
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent


def ours(build, obj, keep, dump=None):
    """(seconds, peak MB) of geotri-bench-propagation on obj."""
    command = [str(build / "bench" / "geotri-bench-propagation"), "--no-cgal", "--no-header", "--repeat", "3"]
    command += ["--keep-windows"] if keep else []
    command += ["--dump", str(dump)] if dump else []
    row = subprocess.run(command + [str(obj)], capture_output=True, text=True, check=True).stdout
    cells = [c.strip() for c in row.strip().strip("|").split("|")]
    return float(cells[2]), float(cells[6])


def vtp(binary, obj, source, dump=None):
    """(seconds, peak MB) of vtp-bench on obj."""
    command = [str(binary), str(obj), str(source), "3"] + ([str(dump)] if dump else [])
    line = subprocess.run(command, capture_output=True, text=True, check=True).stdout
    seconds = float(re.search(r"propagate_median_s=(\S+)", line).group(1))
    return seconds, float(re.search(r"peak_rss_mb=(\S+)", line).group(1))


def largest_difference(a_path, b_path):
    a = [float(x) for x in pathlib.Path(a_path).read_text().split()]
    b = [float(x) for x in pathlib.Path(b_path).read_text().split()]
    if len(a) != len(b):
        return float("nan")
    finite = [x for x in b if x != float("inf")]
    largest = max(finite) if finite else 1.0
    return max((abs(x - y) for x, y in zip(a, b) if x != float("inf") or y != float("inf")), default=0.0) / largest


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--build", type=pathlib.Path, default=ROOT / "build")
    parser.add_argument("--vtp", type=pathlib.Path, default=ROOT / "build" / "vtp-bench")
    parser.add_argument("meshes", nargs="+")
    options = parser.parse_args()
    if not options.vtp.exists():
        sys.exit(f"compare.py: no {options.vtp}: build it with bench/vtp/build.sh VTP_SOURCE_DIR")
    print("| mesh | faces | ours, freeing (s) | ours, keeping (s) | VTP (s) | VTP / ours freeing | VTP / ours keeping"
          " | peak MB: freeing, keeping, VTP | largest difference |")
    print("|---|---:|---:|---:|---:|---:|---:|---|---:|")
    with tempfile.TemporaryDirectory() as work:
        work = pathlib.Path(work)
        for mesh in options.meshes:
            obj, ours_txt, vtp_txt = work / "mesh.obj", work / "ours.txt", work / "vtp.txt"
            subprocess.run([str(options.build / "bench" / "geotri-bench-propagation"), "--no-cgal", "--repeat", "1",
                            "--write-obj", str(obj), "--dump", str(ours_txt), mesh],
                           capture_output=True, check=True)
            text = obj.read_text()
            vertices, faces = text.count("\nv ") + text.startswith("v "), text.count("\nf ")
            source = vertices // 2
            times = {"free": [], "keep": [], "vtp": []}
            memory = {}
            for _ in range(options.rounds):
                for name in times:
                    if name == "vtp":
                        seconds, mb = vtp(options.vtp, obj, source, vtp_txt)
                    else:
                        seconds, mb = ours(options.build, obj, name == "keep")
                    times[name].append(seconds)
                    memory[name] = mb
            median = {name: statistics.median(values) for name, values in times.items()}
            label = mesh if mesh.startswith("gen:") else pathlib.Path(mesh).name
            print(f"| {label} | {faces} | {median['free']:.3f} | {median['keep']:.3f} | {median['vtp']:.3f} | "
                  f"{median['vtp'] / median['free']:.2f} | {median['vtp'] / median['keep']:.2f} | "
                  f"{memory['free']:.0f}, {memory['keep']:.0f}, {memory['vtp']:.0f} | "
                  f"{largest_difference(vtp_txt, ours_txt):.1e} |", flush=True)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Measures how geotri-curve's certified distance bound converges under h- and p-refinement, on a sphere.

It makes a fine icosphere T of radius 1 (an icosahedron subdivided K times, every new vertex projected onto the
unit sphere), decimates it to a ladder of coarse meshes (about 20, 80, 320 and 1280 faces by default), makes each one
a geodesic triangulation G exactly as bench/pipeline_sweep.py does (geotri-decimate --paths, geotri-trace --paths,
geotri-flip), and runs `geotri-curve G --order P --no-adapt --json` on each G for P = 2, 3 and 4. With --no-adapt,
G is not refined, so each run measures the elements of that G as they are; exit code 3 (some elements above the
default tolerance) is expected on the coarse G and its JSON summary is read all the same.

    bench/curve_convergence.py [--subdivisions K] [--faces N ...] [--orders P ...] [--threads N] [--timeout S]
                               [--build DIR] [--keep DIR]

It prints Markdown tables:

- T and its faceting scale, then the ladder of G: faces, h and the time of each tool;
- (a) the largest certified distance bound over the elements of each G, for each P: geotri-curve's `max_distance`,
  relative to the diagonal of T's bounding box (about 2 sqrt(3)), and that times the diagonal (absolute, for the
  unit sphere); it should fall as P goes 2 -> 3 -> 4;
- (b) for each P, the observed rate log(d_i / d_i+1) / log(h_i / h_i+1) between consecutive G, next to P + 1, the
  rate of interpolating a smooth surface by elements of order P;
- (c) how far the elements are from the sphere, measured on a lattice of points of each element read back from the
  .msh file (not certified), its ratio to the bound and its rates: what the elements achieve, apart from what the
  proof of the bound loses; a bound below the measured distance minus T's facet gap would be broken, and is
  flagged;
- the details of every geotri-curve run (elements, those that fail the default tolerance or quality, the certified
  quality, seconds).

h is the mean length of G's edges, each the length of its geodesic as the .gtri file holds it (on the unit sphere,
about 1.5 sqrt(4 pi / faces); that column is printed too). The largest bound comes from the largest elements, and
decimation does not make G uniform, so the rates are also given against G's largest edge.

T is itself a faceted sphere, and the bound is a distance to T, not to the sphere: a smooth element cannot follow T's
facets and ridges more closely than their own scale, about e^2 / 8 for a fine edge length e (the sagitta of one fine
edge on the unit sphere; the facets' largest gap to the sphere is about e^2 / 6). So the bound cannot fall much below
that floor, and the rates flatten as it nears it: measured with coarser T (--subdivisions 5 or 6), the bounds level
off at about 2 times e^2/8. The script prints the floor, marks the bounds within 10 times of it, and says where one
is within 3 times of it, at the floor. K defaults to the smallest subdivision count that gives at least 500,000 fine
faces (8: 1,310,720 faces, e about 0.005, a floor near 3e-6; about 6 minutes on 2 shared cores, more than half of it
in the 12 runs of geotri-curve, 8-24 s each).

T is written as binary little-endian PLY with double coordinates (read exactly, and faster than OFF's text). The
outputs go to a temporary folder that is removed at the end, or with --keep to DIR, where they stay (sphere.ply,
gN.off, gN.paths, gN.gtri, gN.flip.gtri and gN.pP.msh, N the target face count).
"""
import argparse
import contextlib
import math
import pathlib
import sys
import tempfile
import time

import geotri_tools

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent

TIMEOUT = 600.0  # seconds per tool run; set by --timeout
NEAR_FLOOR = 10.0  # a bound within this factor of T's faceting floor is marked
# The bounds level off at 1.9 to 2.3 times e^2/8 where a coarser T lets the ladder reach it (5 and 6 subdivisions,
# orders 3 and 4 at 320 and 1280 faces): within this factor, a bound is at the floor.
AT_FLOOR = 3.0
SAMPLES = 40  # the measured distance samples each element on a lattice of (SAMPLES + 1)(SAMPLES + 2) / 2 points


def run(tool, args, build):
    return geotri_tools.run(tool, args, build, TIMEOUT)


def icosphere(subdivisions):
    """Vertices (n x 3) and counter-clockwise faces (m x 3) of the icosahedron subdivided `subdivisions` times,
    every vertex on the unit sphere."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    vertices = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t],
                         [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], dtype=float)
    faces = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
                      [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
                      [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]], dtype=np.int64)
    vertices /= np.linalg.norm(vertices, axis=1, keepdims=True)
    for _ in range(subdivisions):
        # One new vertex per edge, shared by its two faces: number the edges once, by their sorted ends.
        halfedges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
        edges, edge_of = np.unique(np.sort(halfedges, axis=1), axis=0, return_inverse=True)
        edge_of = edge_of.reshape(-1) + len(vertices)
        middles = vertices[edges[:, 0]] + vertices[edges[:, 1]]
        vertices = np.concatenate([vertices, middles / np.linalg.norm(middles, axis=1, keepdims=True)])
        m = len(faces)
        a, b, c = edge_of[:m], edge_of[m:2 * m], edge_of[2 * m:]  # the middles of edges 01, 12 and 20
        faces = np.concatenate([np.stack([faces[:, 0], a, c], axis=1), np.stack([a, faces[:, 1], b], axis=1),
                                np.stack([c, b, faces[:, 2]], axis=1), np.stack([a, b, c], axis=1)])
    return vertices, faces


def write_binary_ply(path, vertices, faces):
    """Binary little-endian PLY, coordinates as doubles so that T's vertices are exactly the ones measured here."""
    header = ("ply\nformat binary_little_endian 1.0\n"
              f"element vertex {len(vertices)}\nproperty double x\nproperty double y\nproperty double z\n"
              f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    records = np.zeros(len(faces), dtype=[("count", "u1"), ("corners", "<i4", (3,))])
    records["count"] = 3
    records["corners"] = faces
    with open(path, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(np.ascontiguousarray(vertices, dtype="<f8").tobytes())
        out.write(records.tobytes())


def faceting(vertices, faces):
    """T's own scale: (mean edge length, largest edge length, largest gap between a facet and the unit sphere)."""
    halfedges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    lengths = np.linalg.norm(vertices[halfedges[:, 0]] - vertices[halfedges[:, 1]], axis=1)
    # A facet's deepest point is where its plane comes closest to the centre (the foot of the perpendicular lies
    # inside these near-equilateral facets).
    p0, p1, p2 = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    normals = np.cross(p1 - p0, p2 - p0)
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    gap = 1.0 - np.abs(np.einsum("ij,ij->i", normals, p0)).min()
    return lengths.mean(), lengths.max(), gap


def gtri_edge_lengths(path):
    """The geodesic lengths of G's edges, from the `edge I FROM TO K LENGTH` lines of a .gtri file."""
    lengths = []
    with open(path) as gtri:
        for line in gtri:
            if line.startswith("edge "):
                lengths.append(float(line.split()[5]))
    return np.array(lengths)


def lattice(order):
    """gmsh's node order of a triangle of this order, as lattice points (i, j) of the reference triangle, (i / P,
    j / P): the corners, the inner nodes of edges 01, 12 and 20 in that direction, then the inner triangle,
    recursively."""
    if order == 0:
        return [(0, 0)]
    points = [(0, 0), (order, 0), (0, order)]
    points += [(k, 0) for k in range(1, order)] + [(order - k, k) for k in range(1, order)]
    points += [(0, order - k) for k in range(1, order)]
    if order >= 3:
        points += [(i + 1, j + 1) for i, j in lattice(order - 3)]
    return points


def read_msh_triangles(path):
    """The node coordinates of every triangle of an ASCII gmsh 4.1 file, as an (elements, nodes, 3) array."""
    lines = pathlib.Path(path).read_text().split("\n")
    at = lines.index("$Nodes") + 1
    blocks = int(lines[at].split()[0])
    at += 1
    position = {}
    for _ in range(blocks):
        count = int(lines[at].split()[3])
        tags = [int(t) for t in lines[at + 1:at + 1 + count]]
        for k, tag in enumerate(tags):
            position[tag] = [float(x) for x in lines[at + 1 + count + k].split()]
        at += 1 + 2 * count
    at = lines.index("$Elements") + 1
    blocks = int(lines[at].split()[0])
    at += 1
    elements = []
    for _ in range(blocks):
        count = int(lines[at].split()[3])
        elements += [[position[int(t)] for t in line.split()[1:]] for line in lines[at + 1:at + 1 + count]]
        at += 1 + count
    return np.array(elements)


def sampled_sphere_distance(path, order, samples=SAMPLES):
    """The largest | |x| - 1 | over a lattice of samples of every element: how far the elements are from the sphere
    itself, measured, not certified. It is independent of geotri-curve's bound, which is a distance to T (within
    T's facet gap of this) and includes whatever its proof loses."""
    monomials = [(a, b) for a in range(order + 1) for b in range(order + 1 - a)]
    nodes = np.array(lattice(order), dtype=float) / order
    vandermonde = np.array([[x ** a * y ** b for a, b in monomials] for x, y in nodes])
    where = [(i / samples, j / samples) for i in range(samples + 1) for j in range(samples + 1 - i)]
    shapes = np.array([[x ** a * y ** b for a, b in monomials] for x, y in where]) @ np.linalg.inv(vandermonde)
    points = np.einsum("sn,enk->esk", shapes, read_msh_triangles(path))
    return float(np.abs(np.linalg.norm(points, axis=2) - 1.0).max())


def make_ladder_step(target, sphere, options, work):
    """decimate -> trace -> flip to about `target` faces, as bench/pipeline_sweep.py runs them. Returns a dict with
    the flipped G's path, faces, h and times, or with 'error'."""
    stem = work / f"g{target}"
    threads = ["--threads", str(options.threads)] if options.threads else []
    step = {"target": target, "times": {}}
    code, dec, step["times"]["decimate"], err = run("decimate", [str(sphere), "-o", f"{stem}.off", "--paths",
                                                                 f"{stem}.paths", "--faces", str(target)],
                                                    options.build)
    if code != 0 or dec is None:
        step["error"] = f"decimate failed ({code}): {err}"
        return step
    code, _, step["times"]["trace"], err = run("trace", [str(sphere), f"{stem}.off", "--paths", f"{stem}.paths",
                                                         "-o", f"{stem}.gtri", *threads], options.build)
    if code != 0:
        step["error"] = f"trace failed ({code}): {err}"
        return step
    code, flp, step["times"]["flip"], err = run("flip", [f"{stem}.gtri", "-o", f"{stem}.flip.gtri", *threads],
                                                options.build)
    if flp is None:
        step["error"] = f"flip failed ({code}): {err}"
        return step
    lengths = gtri_edge_lengths(f"{stem}.flip.gtri")
    step.update(gtri=pathlib.Path(f"{stem}.flip.gtri"), faces=flp["faces"], vertices=flp["vertices"],
                valid=flp["valid"], min_angle=flp["min_corner_angle_deg"], h=lengths.mean(), h_max=lengths.max())
    return step


def curve(step, order, options):
    """One geotri-curve run without refinement; exit code 3 only says that some elements exceed the tolerance."""
    threads = ["--threads", str(options.threads)] if options.threads else []
    out = step["gtri"].with_name(f"g{step['target']}.p{order}.msh")
    code, summary, seconds, err = run("curve", [str(step["gtri"]), "-o", str(out), "--order", str(order),
                                                "--no-adapt", *threads], options.build)
    if code not in (0, 3) or summary is None:
        return {"error": f"exit {code}: {err.splitlines()[-1] if err else 'no summary'}", "seconds": seconds}
    return {"code": code, "summary": summary, "seconds": seconds, "sampled": sampled_sphere_distance(out, order)}


def observed_rate(d_a, d_b, h_a, h_b):
    """log(d_a / d_b) / log(h_a / h_b) as a table cell, or '-' where a value is missing."""
    if not d_a or not d_b or h_a == h_b:
        return "-"
    return f"{math.log(d_a / d_b) / math.log(h_a / h_b):.2f}"


def default_subdivisions(min_faces):
    """The smallest subdivision count whose icosphere has at least `min_faces` faces (20 * 4^k)."""
    k = 0
    while 20 * 4 ** k < min_faces:
        k += 1
    return k


def main():
    global TIMEOUT
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--subdivisions", type=int, metavar="K", help="subdivide the icosahedron K times "
                        "(default: the fewest that give 500,000 faces, 8)")
    parser.add_argument("--faces", type=int, nargs="+", default=[20, 80, 320, 1280], metavar="N",
                        help="the ladder of G: geotri-decimate --faces N for each (default 20 80 320 1280)")
    parser.add_argument("--orders", type=int, nargs="+", default=[2, 3, 4], metavar="P",
                        help="geotri-curve --order P for each (default 2 3 4)")
    parser.add_argument("--threads", type=int, default=0, metavar="N", help="the tools' --threads (0: all cores)")
    parser.add_argument("--timeout", type=float, default=TIMEOUT, metavar="S",
                        help="stop a tool run after this many seconds")
    parser.add_argument("--build", type=pathlib.Path, default=ROOT / "build", metavar="DIR",
                        help="a build folder (the tools in its tools/) or a folder that holds the tools")
    parser.add_argument("--keep", type=pathlib.Path, metavar="DIR",
                        help="write the outputs to this folder and keep them")
    options = parser.parse_args()
    TIMEOUT = options.timeout
    if not geotri_tools.tool_path(options.build, "curve").exists():
        sys.exit(f"curve_convergence.py: no geotri-curve in {options.build} or {options.build / 'tools'}")
    k = options.subdivisions if options.subdivisions is not None else default_subdivisions(500_000)
    faces_list = sorted(options.faces)
    if options.keep:
        options.keep.mkdir(parents=True, exist_ok=True)
    folder = (contextlib.nullcontext(options.keep) if options.keep
              else tempfile.TemporaryDirectory(prefix="geotri-curve-convergence-"))
    with folder as work:
        work = pathlib.Path(work)
        for target in faces_list:  # with --keep, what an earlier run left must not pass for this run's
            for suffix in [".off", ".paths", ".gtri", ".flip.gtri"] + [f".p{p}.msh" for p in options.orders]:
                (work / f"g{target}{suffix}").unlink(missing_ok=True)

        start = time.perf_counter()
        vertices, faces = icosphere(k)
        sphere = work / "sphere.ply"
        write_binary_ply(sphere, vertices, faces)
        make_seconds = time.perf_counter() - start
        diagonal = float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))
        edge_mean, edge_max, gap = faceting(vertices, faces)
        floor = edge_mean ** 2 / 8.0
        print(f"## T: icosphere, {k} subdivisions\n")
        print("| vertices | faces | bounding-box diagonal | fine edge e: mean, max | floor e^2/8: absolute, "
              "relative | largest facet gap to the sphere | made and written (s) |")
        print("|---:|---:|---:|---|---|---:|---:|")
        print(f"| {len(vertices)} | {len(faces)} | {diagonal:.6f} | {edge_mean:.3e}, {edge_max:.3e} | "
              f"{floor:.2e}, {floor / diagonal:.2e} | {gap:.2e} | {make_seconds:.2f} |\n", flush=True)

        ladder = []
        for target in faces_list:
            step = make_ladder_step(target, sphere, options, work)
            if "error" not in step:
                step["curves"] = {p: curve(step, p, options) for p in options.orders}
            ladder.append(step)
            # The tables need the whole ladder; meanwhile, say how far it has got.
            print(f"curve_convergence.py: {target} faces done, {time.perf_counter() - start:.0f} s",
                  file=sys.stderr, flush=True)

        print("## The ladder of G\n")
        print("| target faces | faces | vertices | valid | min corner angle | h: mean geodesic edge | largest edge | "
              "sqrt(4 pi / faces) | decimate (s) | trace (s) | flip (s) |")
        print("|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|")
        for step in ladder:
            times = " | ".join(f"{step['times'][t]:.2f}" if t in step["times"] else "-"
                               for t in ("decimate", "trace", "flip"))
            if "error" in step:
                print(f"| {step['target']} | {step['error']} | - | - | - | - | - | - | {times} |")
                continue
            print(f"| {step['target']} | {step['faces']} | {step['vertices']} | "
                  f"{'valid' if step['valid'] else 'INVALID'} | {step['min_angle']:.1f}° | {step['h']:.4f} | "
                  f"{step['h_max']:.4f} | {math.sqrt(4 * math.pi / step['faces']):.4f} | {times} |")
        good = [s for s in ladder if "error" not in s]

        def bound(step, p):
            """The largest distance bound, relative to the diagonal, or None where geotri-curve failed."""
            run_ = step["curves"][p]
            return run_["summary"]["max_distance"] if "summary" in run_ else None

        def mark(relative):
            return "*" if relative * diagonal <= NEAR_FLOOR * floor else ""

        print("\n## (a) Largest certified distance bound, per order (relative to the diagonal; absolute)\n")
        print(f"\\* within {NEAR_FLOOR:g} times of T's faceting floor e^2/8 = {floor:.2e}.\n")
        print("| faces | h | " + " | ".join(f"p = {p}: relative | p = {p}: absolute" for p in options.orders) +
              " | " + " | ".join(f"p{a} / p{b}" for a, b in zip(options.orders, options.orders[1:])) + " |")
        print("|---:|---:|" + "---:|---:|" * len(options.orders) + "---:|" * (len(options.orders) - 1))
        for step in good:
            cells, values = [], []
            for p in options.orders:
                d = bound(step, p)
                values.append(d)
                cells += ([f"{d:.3e}{mark(d)}", f"{d * diagonal:.3e}"] if d is not None
                          else [step["curves"][p]["error"], "-"])
            ratios = [f"{a / b:.1f}" if a is not None and b else "-" for a, b in zip(values, values[1:])]
            print(f"| {step['faces']} | {step['h']:.4f} | " + " | ".join(cells + ratios) + " |")

        def print_rates(value, rows):
            """One row per (h, order): log(d_i / d_i+1) / log(h_i / h_i+1) between consecutive G, d = value(step,
            p) absolute, and over the whole ladder; * where d_i+1 is within NEAR_FLOOR of the floor."""
            if len(good) < 2:
                print("(one G only: no rate)")
                return
            steps = [f"{a['faces']} → {b['faces']}" for a, b in zip(good, good[1:])]
            print("| p | h | expected p + 1 | " + " | ".join(steps) + " | over the whole ladder |")
            print("|---:|---|---:|" + "---:|" * (len(steps) + 1))
            for h, label in rows:
                for p in options.orders:
                    cells = []
                    for a, b in zip(good, good[1:]):
                        cells.append(observed_rate(value(a, p), value(b, p), a[h], b[h]))
                        cells[-1] += "*" if cells[-1] != "-" and value(b, p) <= NEAR_FLOOR * floor else ""
                    cells.append(observed_rate(value(good[0], p), value(good[-1], p), good[0][h], good[-1][h])
                                 if len(good) > 1 else "-")
                    print(f"| {p} | {label} | {p + 1} | " + " | ".join(cells) + " |")

        def absolute_bound(step, p):
            d = bound(step, p)
            return None if d is None else d * diagonal

        print("\n## (b) Observed rate of the bound, log(d_i / d_i+1) / log(h_i / h_i+1)\n")
        print("h: the mean geodesic edge of G, and, in the rows below, G's largest edge (the largest bound comes "
              "from the largest elements). \\* where d_i+1 is within "
              f"{NEAR_FLOOR:g} times of the floor.\n")
        print_rates(absolute_bound, (("h", "mean edge"), ("h_max", "largest edge")))

        def sampled(step, p):
            return step["curves"][p].get("sampled")

        print("\n## (c) Measured distance of the elements to the sphere, not certified\n")
        print(f"The largest | |x| - 1 | over a lattice of {(SAMPLES + 1) * (SAMPLES + 2) // 2} points of each "
              "element (read back from the .msh), for "
              "comparison with the bound: the bound is a distance to T, which lies within the facet gap "
              f"{gap:.2e} of the sphere, so the bound is at least this minus that gap (BROKEN where it is "
              "not).\n")
        print("| faces | h | " + " | ".join(f"p = {p}: measured | p = {p}: bound / measured" for p in options.orders)
              + " |")
        print("|---:|---:|" + "---:|---:|" * len(options.orders))
        for step in good:
            cells = []
            for p in options.orders:
                m, d = sampled(step, p), absolute_bound(step, p)
                # T lies between the sphere and its facet gap inside it, so a point this far from the sphere is
                # at least m - gap from T: a bound below that would be broken.
                broken = " BROKEN" if m is not None and d is not None and m - gap > d else ""
                cells += [f"{m:.3e}", f"{d / m:.1f}{broken}"] if m is not None and d is not None else ["-", "-"]
            print(f"| {step['faces']} | {step['h']:.4f} | " + " | ".join(cells) + " |")
        print()
        print_rates(sampled, (("h", "mean edge"),))

        near = [(s["faces"], p, bound(s, p)) for s in good for p in options.orders
                if bound(s, p) is not None and bound(s, p) * diagonal <= NEAR_FLOOR * floor]
        print()
        if near:
            print(f"Near T's faceting floor (e^2/8 = {floor:.2e} absolute): " +
                  ", ".join(f"{f} faces p = {p} ({d * diagonal:.2e}, {d * diagonal / floor:.1f} times the floor)"
                            for f, p, d in near) +
                  ". The rates that end there measure T's facets as much as the elements.")
            reached = [(f, p) for f, p, d in near if d * diagonal <= AT_FLOOR * floor]
            if reached:
                print(f"The floor is reached (a bound within {AT_FLOOR:g} times of e^2/8, where the bounds level off) "
                      "at " + ", ".join(f"{f} faces p = {p}" for f, p in reached) + ".")
        else:
            print(f"No bound comes within {NEAR_FLOOR:g} times of T's faceting floor ({floor:.2e} absolute).")

        print("\n## geotri-curve runs (--no-adapt)\n")
        print("| faces | p | exit | elements | failing (tolerance or quality) | certified plane, surface | "
              "min quality | seconds |")
        print("|---:|---:|---:|---:|---:|---|---:|---:|")
        for step in good:
            for p in options.orders:
                r = step["curves"][p]
                if "summary" not in r:
                    print(f"| {step['faces']} | {p} | {r['error']} | - | - | - | - | {r['seconds']:.2f} |")
                    continue
                s = r["summary"]
                print(f"| {step['faces']} | {p} | {r['code']} | {s['elements']} | {s['failing']} | "
                      f"{s['certified_plane']}, {s['certified_surface']} | {s['min_quality']:.3f} | "
                      f"{r['seconds']:.2f} |")
        failed = [(s["faces"], p, s["curves"][p]["error"]) for s in good for p in options.orders
                  if "error" in s["curves"][p]]
        failed += [(s["target"], "-", s["error"]) for s in ladder if "error" in s]
        if failed:
            print("\nFailed: " + "; ".join(f"{f} faces p = {p}: {e}" for f, p, e in failed))
        print(f"\nTotal: {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Compares two routes to curved P3 triangles on closed triangle meshes T, and prints a Markdown table:

  geotri  geotri-decimate --faces 320 -> geotri-trace -> geotri-flip (the command lines of pipeline_sweep.py), then
          geotri-curve --order 3 --json with its defaults (tolerance 1e-3 of T's bounding-box diagonal, min quality
          0.1); exit 3 (some elements not certified) is recorded, the file is still judged;
  gmsh    gmsh's own route through its Python API: merge T (converted to STL with meshio unless it is one),
          classifySurfaces(40°, boundary, parametrizable patches, 180°), createGeometry, a uniform mesh size chosen
          from T's area so that the triangle count comes close to geotri's element count (one retry with a size
          corrected by the count it got), generate(2), setOrder(3), then the high-order optimiser
          (Mesh.HighOrderOptimize 2: elastic analogy, then optimisation, the same as gmsh's own meshing pipeline).

Both outputs are then judged by the same code, which neither route wrote:
  - gmsh's Plugin(AnalyseMeshQuality) with JacobianDeterminant=1, in a fresh gmsh process: the elements it finds
    inverted (minJ <= 0) and the worst minJ/maxJ;
  - a dense sampler (numpy): every P3 element evaluated on a barycentric grid of step 1/12 (91 points), and each
    sample's exact distance to T (point-to-triangle, with a uniform grid of buckets). The largest one, over the
    diagonal of T's bounding box, is reported. It is ONE-SIDED (element -> T): it does not see a part of T that no
    element covers, and it is a lower bound of the element-to-T distance between the samples.
and geotri's own certified figures (elements certified, the certified lower bound of min J / max J, the proven
bound of the distance to T) are shown beside them.

    bench/curve_vs_gmsh.py [--build DIR] [--data DIR] [--keep DIR] [--timeout S] [--faces N]
                           [--gmsh-optimize 0|1|2|3] [MESH ...]

Without MESH, five meshes under --data (default ../shared/data): a vertebra, a brain, the closed bunny, fandisk and a
CAD part with many needle triangles. --build is the folder that holds the geotri tools (default build/tools; a build
folder with a tools/ inside it works too). Every step (each geotri tool, gmsh's meshing, each judgement) is stopped
after --timeout seconds. Times are wall seconds: geotri's total covers its four tools (loading and writing
included), with geotri-curve's share in parentheses; gmsh's covers merge to write, but not the first meshing of a
retried size. The outputs go to a temporary folder removed at the end, or with --keep to DIR (MESH.geotri.msh,
MESH.gmsh.msh and the intermediate files, named by the mesh's file name without its extension).

Runs with /usr/bin/python3 (Debian's gmsh module, meshio, numpy); gmsh runs in child processes of this script, so
that a crash or a hang of gmsh is contained and reported.
"""
import argparse
import contextlib
import json
import math
import pathlib
import subprocess
import sys
import tempfile
import time

import geotri_tools

ROOT = pathlib.Path(__file__).resolve().parent.parent

DEFAULT_MESHES = [
    "anatomy/lumbar_vertebra_mean_2nd.ply",
    "anatomy/brain_conte69_32k_lh.ply",
    "classic/bunny_closed_cgal.off",
    "cad/fandisk.off",
    # the smallest file of hard/ whose needles (faces below 1°) number in the thousands: 2016 of 5344 faces
    "hard/thingi88566_8parts.stl",
]

ORDER = 3
SAMPLE_STEP = 12  # barycentric grid of step 1/SAMPLE_STEP per element
TIMEOUT = 600.0   # seconds per step; set by --timeout
WORKER = "--gmsh-worker"  # how this script calls itself in a child process that runs gmsh


# ---------------------------------------------------------------------------------------------------------------------
# The geotri route


def run_tool(name, args, build):
    return geotri_tools.run(name, args, build, TIMEOUT)


def last_line(text, fallback):
    return text.splitlines()[-1] if text else str(fallback)


def geotri_route(mesh, stem, options):
    """decimate -> trace -> flip -> curve. Returns a dict: 'msh' (the output, or None), 'failure' (why there is none),
    geotri-curve's JSON summary and exit code, and the wall seconds of all four tools and of geotri-curve."""
    result = {"msh": None, "failure": None, "seconds": 0.0, "curve_seconds": None, "curve": None, "code": None}
    code, dec, seconds, err = run_tool("decimate", [str(mesh), "-o", f"{stem}.off", "--paths", f"{stem}.paths",
                                                    "--faces", str(options.faces)], options.build)
    result["seconds"] += seconds
    if code != 0:
        result["failure"] = f"decimate: {last_line(err, code)}"
        return result
    result["coarse_faces"] = dec["coarse_faces"]
    code, _, seconds, err = run_tool("trace", [str(mesh), f"{stem}.off", "--paths", f"{stem}.paths", "-o",
                                               f"{stem}.gtri"], options.build)
    result["seconds"] += seconds
    if code != 0:
        result["failure"] = f"trace: {last_line(err, code)}"
        return result
    code, flp, seconds, err = run_tool("flip", [f"{stem}.gtri", "-o", f"{stem}.flip.gtri"], options.build)
    result["seconds"] += seconds
    if flp is None:
        result["failure"] = f"flip: {last_line(err, code)}"
        return result
    if not flp["valid"]:  # geotri-curve needs a valid G; say so rather than let it refuse
        result["failure"] = "flip left G invalid"
        return result
    msh = pathlib.Path(f"{stem}.geotri.msh")
    code, curve, seconds, err = run_tool("curve", [f"{stem}.flip.gtri", "-o", str(msh), "--order", str(ORDER)],
                                         options.build)
    result["seconds"] += seconds
    result["curve_seconds"] = seconds
    result["code"], result["curve"] = code, curve
    if code in (0, 3) and msh.exists():  # 3: written, some elements not certified
        result["msh"] = msh
    else:
        result["failure"] = f"curve: {last_line(err, code)}"
    return result


# ---------------------------------------------------------------------------------------------------------------------
# gmsh, in a child process: the route, and the judge


def run_worker(job, timeout):
    """Runs this script as a gmsh worker on `job` (a dict); returns (its JSON result or None, why there is none)."""
    try:
        done = subprocess.run([sys.executable, str(pathlib.Path(__file__).resolve()), WORKER, json.dumps(job)],
                              capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, f"gmsh stopped after {timeout:.0f} s"
    lines = done.stdout.strip().splitlines()
    if done.returncode == 0 and lines:
        try:
            return json.loads(lines[-1]), None
        except json.JSONDecodeError:
            pass
    if done.returncode < 0:
        return None, f"gmsh crashed (signal {-done.returncode})"
    return None, f"gmsh failed: {last_line(done.stderr.strip(), done.returncode)}"


def triangle_count():
    import gmsh
    _, tags, _ = gmsh.model.mesh.getElements(2)
    return int(sum(len(t) for t in tags))


def worker_mesh(job):
    """gmsh's route to P3 triangles on job['input'] at the uniform size job['size'], written to job['output']. When
    the triangle count misses job['target'] by more than 10% and job['retry'] is set, it stops there and returns
    the count, so that the route is run again, at a corrected size, in a fresh process: re-meshing in the same one
    after gmsh.model.mesh.clear() can make gmsh abort where a fresh start at that size does not."""
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.logger.start()
    result = {"notes": []}
    start = time.perf_counter()
    gmsh.merge(job["input"])
    gmsh.model.mesh.classifySurfaces(40 * math.pi / 180, True, True, math.pi)
    gmsh.model.mesh.createGeometry()
    gmsh.option.setNumber("Mesh.MeshSizeMin", job["size"])
    gmsh.option.setNumber("Mesh.MeshSizeMax", job["size"])
    gmsh.model.mesh.generate(2)
    result["surfaces"] = len(gmsh.model.getEntities(2))
    result["linear_triangles"] = triangle_count()
    if job["retry"] and abs(result["linear_triangles"] / job["target"] - 1) > 0.1:
        gmsh.finalize()
        return result
    # setOrder only places the nodes: gmsh's generate() then runs the passes that Mesh.HighOrderOptimize names
    # (1 optimisation, 2 elastic analogy then optimisation, 3 elastic analogy), and so does this, in that order.
    level = job["optimize"]
    steps = [("setOrder", lambda: gmsh.model.mesh.setOrder(ORDER))]
    if level in (2, 3):
        steps.append(("optimiser (elastic)", lambda: gmsh.model.mesh.optimize("HighOrderElastic")))
    if level in (1, 2):
        steps.append(("optimiser", lambda: gmsh.model.mesh.optimize("HighOrder")))
    for step, call in steps:
        try:
            call()
        except Exception as error:  # gmsh raises on any logged error, often with a usable mesh: judge what it wrote
            result["notes"].append(f"{step}: {error}")
    gmsh.write(job["output"])
    result["seconds"] = time.perf_counter() - start
    result["warnings"] = [line for line in gmsh.logger.get() if line.startswith("Warning") and "jac. < 0" in line]
    gmsh.logger.stop()
    gmsh.finalize()
    return result


def worker_judge(job):
    """gmsh's own Jacobian check of job['input']: AnalyseMeshQuality with JacobianDeterminant=1."""
    import re
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.logger.start()
    gmsh.merge(job["input"])
    gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 1)
    gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 1)
    gmsh.plugin.run("AnalyseMeshQuality")
    ratio = None
    for view in gmsh.view.getTags():
        if gmsh.option.getString(f"View[{gmsh.view.getIndex(view)}].Name").startswith("minJ/maxJ"):
            _, _, data, _, _ = gmsh.view.getModelData(view, 0)
            ratio = [d[0] for d in data]
    log = gmsh.logger.get()
    gmsh.logger.stop()
    gmsh.finalize()
    if ratio is None:
        raise RuntimeError("AnalyseMeshQuality made no minJ/maxJ view")
    # The plugin's view holds minJ/maxJ where maxJ > 0, so an element whose J changes sign (minJ <= 0) is <= 0 there;
    # an element negative all over shows maxJ/minJ > 0, and is counted only in a warning of the log.
    whole = sum(int(m.group(1)) for line in log
                for m in [re.search(r"(\d+) elements? (?:is|are) completely inverted", line)] if m)
    return {"elements": len(ratio), "inverted": sum(1 for q in ratio if not q > 0) + whole, "whole": whole,
            "worst": min(ratio)}


def worker_main():
    job = json.loads(sys.argv[2])
    result = (worker_mesh if job["kind"] == "mesh" else worker_judge)(job)
    print(json.dumps(result))


# ---------------------------------------------------------------------------------------------------------------------
# The distance sampler


def meshio_read(path):
    """meshio.read, with what it prints (a bare newline for MSH 4.1) kept off stdout, which holds the table."""
    import meshio
    with contextlib.redirect_stdout(sys.stderr):
        return meshio.read(str(path))


def read_triangles(path):
    """(points, triangles) of a triangle mesh, with meshio (an STL stays a soup: distances do not mind)."""
    import numpy as np
    mesh = meshio_read(path)
    faces = np.concatenate([c.data for c in mesh.cells if c.type == "triangle"])
    return np.asarray(mesh.points, dtype=float), faces.astype(np.int64)


def p3_shape_matrix(step):
    """The values of the 10 P3 Lagrange shape functions, gmsh's node order, at a barycentric grid of `step`: an array
    (samples, 10). Built from the reference nodes through a Vandermonde matrix, so that the node order is the one
    thing written out by hand: corners (0,0) (1,0) (0,1), the edge nodes of 0->1, 1->2, 2->0, then the centre."""
    import numpy as np
    t = 1.0 / 3.0
    nodes = np.array([[0, 0], [1, 0], [0, 1], [t, 0], [2 * t, 0], [2 * t, t], [t, 2 * t], [0, 2 * t], [0, t],
                      [t, t]])
    powers = [(i, j) for i in range(ORDER + 1) for j in range(ORDER + 1 - i)]

    def monomials(uv):
        return np.stack([uv[:, 0] ** i * uv[:, 1] ** j for i, j in powers], axis=1)

    samples = np.array([[i / step, j / step] for i in range(step + 1) for j in range(step + 1 - i)])
    return monomials(samples) @ np.linalg.inv(monomials(nodes))


class Surface:
    """T, for exact point-to-T distances: its faces in a uniform grid of buckets (each face in every cell that its
    bounding box meets)."""

    def __init__(self, points, faces):
        import numpy as np
        a, b, c = points[faces[:, 0]], points[faces[:, 1]], points[faces[:, 2]]
        # What every point-to-face distance needs, once per face: corners, edges, the normal and, per edge, the
        # in-plane normal pointing into the face (a point projects inside when it is on the inner side of all three).
        self.corners = (a, b, c)
        self.edges = (b - a, c - b, a - c)
        self.edge_length2 = tuple(np.einsum("fx,fx->f", e, e) for e in self.edges)
        self.normal = np.cross(b - a, c - a)
        self.normal2 = np.einsum("fx,fx->f", self.normal, self.normal)
        self.inward = tuple(np.cross(self.normal, e) for e in self.edges)
        low, high = points.min(axis=0), points.max(axis=0)
        self.diagonal = float(np.linalg.norm(high - low))
        self.area = float(0.5 * np.sqrt(self.normal2).sum())
        # A few faces per cell on a fine mesh, and a grid small enough that its buckets stay cheap to gather.
        cells = int(np.clip(math.sqrt(len(faces)) / 4, 4, 64))
        self.cell = float((high - low).max()) / cells * (1 + 1e-9)
        self.low = low
        self.dims = np.floor((high - low) / self.cell).astype(np.int64) + 1
        first = self.cell_of(np.minimum(np.minimum(a, b), c))
        last = self.cell_of(np.maximum(np.maximum(a, b), c))
        span = last - first + 1
        count = span.prod(axis=1)
        face = np.repeat(np.arange(len(faces)), count)
        k = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
        sx, sy = span[face, 0], span[face, 1]
        ijk = first[face] + np.stack([k % sx, (k // sx) % sy, k // (sx * sy)], axis=1)
        key = self.flat(ijk)
        order = np.argsort(key, kind="stable")
        self.bucket_faces = face[order]
        self.bucket_start = np.concatenate([[0], np.cumsum(np.bincount(key, minlength=self.dims.prod()))])

    def cell_of(self, p):
        import numpy as np
        return np.clip(np.floor((p - self.low) / self.cell).astype(np.int64), 0, self.dims - 1)

    def flat(self, ijk):
        return (ijk[:, 2] * self.dims[1] + ijk[:, 1]) * self.dims[0] + ijk[:, 0]

    def faces_in_box(self, first, last):
        """The faces registered in the cells from `first` to `last` (inclusive, inside the grid)."""
        import numpy as np
        axes = [np.arange(first[d], last[d] + 1) for d in range(3)]
        i, j, k = np.meshgrid(*axes, indexing="ij")
        cells = self.flat(np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1))
        starts, ends = self.bucket_start[cells], self.bucket_start[cells + 1]
        lengths = ends - starts
        index = np.repeat(starts - (np.cumsum(lengths) - lengths), lengths) + np.arange(lengths.sum())
        return np.unique(self.bucket_faces[index])

    def squared_distances(self, p, faces):
        """(len(p),) squared distances of the points p to the nearest of `faces`: the smaller of the distance to
        each edge segment and, where the point projects inside the face, to its plane. Exact up to rounding, and
        sound on degenerate faces (a needle or a zero-area face is its edges)."""
        import numpy as np
        best = np.full((len(p), len(faces)), np.inf)
        normal, normal2 = self.normal[faces], self.normal2[faces]
        inside = np.broadcast_to(normal2 > 0, best.shape).copy()
        for corner, edge, length2, inward in zip(self.corners, self.edges, self.edge_length2, self.inward):
            w = p[:, None, :] - corner[faces][None]
            edge = edge[faces]
            length2 = length2[faces]
            t = np.clip(np.einsum("mfx,fx->mf", w, edge) / np.where(length2 > 0, length2, 1), 0, 1)
            r = w - t[..., None] * edge
            np.minimum(best, np.einsum("mfx,mfx->mf", r, r), out=best)
            inside &= np.einsum("mfx,fx->mf", w, inward[faces]) >= 0
        plane = np.einsum("mfx,fx->mf", w, normal) ** 2 / np.where(normal2 > 0, normal2, 1)  # w: from a corner
        return np.where(inside, np.minimum(best, plane), best).min(axis=1)

    def brute_force(self, p):
        import numpy as np
        everything = np.arange(len(self.normal))
        chunk = max(1, 2_000_000 // len(everything))
        return np.concatenate([self.squared_distances(p[i:i + chunk], everything) for i in range(0, len(p), chunk)])

    def distances(self, points):
        """Exact distances of `points` to T. The points of one cell search a box of cells around it, first that
        cell alone, then growing; a point is done when its nearest face found is nearer than the box's walls (a wall
        on the grid's boundary does not count: no face lies beyond it), for then no face outside could be nearer."""
        import numpy as np
        result = np.full(len(points), np.inf)
        finite = np.isfinite(points).all(axis=1)
        centre = self.low + 0.5 * self.dims * self.cell
        far = finite & (np.abs(points - centre).max(axis=1) > 2 * self.diagonal)
        if far.any():  # a node flung far off the surface: its distance is what matters, not the speed
            result[far] = np.sqrt(self.brute_force(points[far]))
        near = np.flatnonzero(finite & ~far)
        home = self.cell_of(points[near])  # a point just outside the grid goes with the boundary cell nearest it
        key = self.flat(home)
        order = np.argsort(key, kind="stable")
        top = self.dims - 1
        for group in np.split(order, np.flatnonzero(np.diff(key[order])) + 1):
            cell = home[group[0]]
            pending = near[group]
            k = 0
            while len(pending):
                first, last = np.maximum(cell - k, 0), np.minimum(cell + k, top)
                faces = self.faces_in_box(first, last)
                p = points[pending]
                d2 = self.squared_distances(p, faces) if len(faces) else np.full(len(pending), np.inf)
                below = np.where(first > 0, p - (self.low + first * self.cell), np.inf)
                above = np.where(last < top, self.low + (last + 1) * self.cell - p, np.inf)
                margin = np.minimum(below, above).min(axis=1)
                done = d2 <= margin ** 2
                result[pending[done]] = np.sqrt(d2[done])
                pending = pending[~done]
                k = 2 * k if k else 1
        return result


def sampled_distance(msh, surface, shape):
    """The largest distance from the P3 elements of `msh` to T, sampled; or a string saying why there is none."""
    import numpy as np
    mesh = meshio_read(msh)
    elements = [c.data for c in mesh.cells if c.type == "triangle10"]
    if not elements:
        return f"no P3 triangles ({', '.join(sorted({c.type for c in mesh.cells}))})"
    used = np.concatenate(elements)
    points = np.asarray(mesh.points, dtype=float)
    broken = int((~np.isfinite(points[np.unique(used)]).all(axis=1)).sum())
    if broken:  # say how many, rather than an infinite distance alone
        return f"inf ({broken} nodes not finite)"
    samples = np.einsum("sn,enx->esx", shape, points[used]).reshape(-1, 3)
    return float(surface.distances(samples).max()) / surface.diagonal


# ---------------------------------------------------------------------------------------------------------------------
# The table


def judge(msh, surface, shape):
    """(gmsh's inverted count, gmsh's worst minJ/maxJ, sampled distance) as table cells."""
    verdict, why = run_worker({"kind": "judge", "input": str(msh)}, TIMEOUT)
    if verdict is None:
        inverted = worst = why
    else:
        inverted, worst = str(verdict["inverted"]), f"{verdict['worst']:.3g}"
    try:
        distance = sampled_distance(msh, surface, shape)
        distance = f"{distance:.2e}" if isinstance(distance, float) else distance
    except Exception as error:  # a file that meshio cannot read is a finding too
        distance = f"sampler failed: {error}"
    return [inverted, worst, distance]


def gmsh_input(mesh, stem):
    """T as gmsh reads it well: STL as it is; anything else written to STL by meshio (gmsh 4.8 reads no OFF, and
    its binary PLY reader is experimental)."""
    if mesh.suffix.lower() == ".stl":
        return mesh
    import meshio
    points, faces = read_triangles(mesh)
    path = pathlib.Path(f"{stem}.input.stl")
    meshio.write(str(path), meshio.Mesh(points, [("triangle", faces)]), binary=True)
    return path


def compare_one(mesh, options, work, shape):
    """One table row."""
    name = str(mesh.relative_to(options.data)) if mesh.is_relative_to(options.data) else mesh.name
    stem = work / mesh.stem
    for suffix in (".off", ".paths", ".gtri", ".flip.gtri", ".geotri.msh", ".gmsh.msh", ".input.stl"):
        pathlib.Path(f"{stem}{suffix}").unlink(missing_ok=True)  # with --keep, an earlier run's must not count
    try:
        points, faces = read_triangles(mesh)
    except Exception as error:
        return "| " + " | ".join([name, f"unreadable: {error}"] + ["-"] * (len(COLUMNS) - 2)) + " |"
    surface = Surface(points, faces)
    row = [name, str(len(faces))]

    geo = geotri_route(mesh, stem, options)
    if geo["msh"] is None:
        row += [geo["failure"], "-", "-", "-", f"{geo['seconds']:.1f}", "-", "-", "-"]
    else:
        curve = geo["curve"] or {}
        elements = curve.get("elements", "?")
        row += [str(elements)] + judge(geo["msh"], surface, shape)
        row.append(f"{geo['seconds']:.1f} ({geo['curve_seconds']:.1f})")
        certified = f"{elements - curve['failing']}/{elements}" if "failing" in curve else "?"
        if geo["code"] == 3:
            certified += " (exit 3)"
        row += [certified, f"{curve['min_quality']:.3g}" if "min_quality" in curve else "?",
                f"{curve['max_distance']:.2e}" if "max_distance" in curve else "?"]

    # gmsh aims at geotri's element count; without one, at G's face count (geotri-curve refines G, so this is low).
    target = (geo["curve"] or {}).get("elements") or geo.get("coarse_faces") or options.faces
    size = math.sqrt(4 * surface.area / (math.sqrt(3) * target))  # `target` equilateral triangles of this side cover T
    gmsh_msh = pathlib.Path(f"{stem}.gmsh.msh")
    job = {"kind": "mesh", "output": str(gmsh_msh), "size": size, "target": target, "retry": True,
           "optimize": options.gmsh_optimize}
    try:
        job["input"] = str(gmsh_input(mesh, stem))
        made, why = run_worker(job, TIMEOUT)
        if made is not None and "seconds" not in made:
            # The count goes as 1/size²: one correction brings it close. The first try is a cost of this comparison,
            # not of gmsh's route (a user would know the size), so only the second is timed.
            first = made["linear_triangles"]
            job.update(size=size * math.sqrt(first / target), retry=False)
            made, why = run_worker(job, TIMEOUT)
            if made is None:
                why += f" (at the corrected size; {first} triangles at the first)"
    except Exception as error:
        made, why = None, f"conversion to STL failed: {error}"
    if made is None or not gmsh_msh.exists():
        row += [why or "gmsh wrote nothing", "-", "-", "-", "-"]
    else:
        cell = str(made["linear_triangles"])
        if not geo["curve"]:
            cell += f" (aimed at {target}: geotri made none)"
        if made["notes"]:
            cell += "; " + "; ".join(made["notes"])
        row += [cell] + judge(gmsh_msh, surface, shape) + [f"{made['seconds']:.1f}"]
        for line in made.get("warnings", [])[-1:]:
            print(f"{name}: gmsh: {line}", file=sys.stderr)
    return "| " + " | ".join(row) + " |"


COLUMNS = ["mesh", "T faces",
           "geotri elements", "geotri inverted (gmsh)", "geotri worst minJ/maxJ (gmsh)",
           "geotri max dist/diag (sampled)", "geotri time s (curve)",
           "geotri certified", "geotri certified min quality", "geotri certified dist/diag bound",
           "gmsh elements", "gmsh inverted (gmsh)", "gmsh worst minJ/maxJ (gmsh)", "gmsh max dist/diag (sampled)",
           "gmsh time s"]


def main():
    global TIMEOUT
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("meshes", nargs="*", type=pathlib.Path)
    parser.add_argument("--faces", type=int, default=320, help="geotri-decimate --faces N")
    parser.add_argument("--gmsh-optimize", type=int, choices=[0, 1, 2, 3], default=2,
                        help="gmsh's high-order optimiser, as Mesh.HighOrderOptimize (default 2: elastic, then "
                             "optimisation)")
    parser.add_argument("--timeout", type=float, default=TIMEOUT, help="stop a step after this many seconds")
    parser.add_argument("--build", type=pathlib.Path, default=ROOT / "build" / "tools",
                        help="the folder of the geotri tools")
    parser.add_argument("--data", type=pathlib.Path, default=ROOT.parent / "shared" / "data")
    parser.add_argument("--keep", type=pathlib.Path, help="write the outputs to this folder and keep them")
    options = parser.parse_args()
    options.data = options.data.resolve()
    options.build = options.build.resolve()
    TIMEOUT = options.timeout
    if not geotri_tools.tool_path(options.build, "curve").exists():
        sys.exit(f"curve_vs_gmsh.py: no geotri-curve in {options.build} (give --build)")
    meshes = options.meshes
    if not meshes:
        meshes = []
        for relative in DEFAULT_MESHES:
            path = options.data / relative
            if path.is_file():
                meshes.append(path)
            else:
                print(f"curve_vs_gmsh.py: skipped {relative}: not in {options.data}", file=sys.stderr)
    if not meshes:
        sys.exit(f"curve_vs_gmsh.py: no meshes (none given, none of the defaults under {options.data})")
    if options.keep:
        if any(mesh.resolve().parent == options.keep.resolve() for mesh in meshes):
            sys.exit(f"curve_vs_gmsh.py: --keep {options.keep} holds a mesh of the comparison; give another folder")
        options.keep.mkdir(parents=True, exist_ok=True)
    shape = p3_shape_matrix(SAMPLE_STEP)
    print("| " + " | ".join(COLUMNS) + " |")
    print("|---|---:|" + "---:|" * (len(COLUMNS) - 2))
    folder = (contextlib.nullcontext(options.keep) if options.keep
              else tempfile.TemporaryDirectory(prefix="geotri-curve-vs-gmsh-"))
    with folder as work:
        for mesh in meshes:
            print(compare_one(mesh.resolve(), options, pathlib.Path(work).resolve(), shape), flush=True)


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == WORKER:
        worker_main()
    else:
        main()

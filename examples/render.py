#!/usr/bin/python3
"""Renders geotri results, headless, as side-by-side panels in one PNG.

Runs with Debian's VTK 9 bindings (python3-vtk9) under /usr/bin/python3, and re-executes itself under xvfb-run
when there is no display. See `render.py --help`.
"""

import argparse
import colorsys
import importlib.util
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import types
import zlib

PROG = "render.py"
SYSTEM_PYTHON = "/usr/bin/python3"
# Set in the environment of the re-executed process, so that it never re-executes again.
REEXEC_GUARD = "GEOTRI_RENDER_REEXECUTED"
XVFB_SERVER_ARGS = "-screen 0 4096x2048x24"
INSTALL_HINT = "scripts/install-deps.sh --render installs it"
VTK_MODULES = [
    "vtkCommonCore", "vtkCommonDataModel", "vtkCommonMath", "vtkCommonTransforms", "vtkFiltersCore",
    "vtkFiltersGeometry", "vtkIOGeometry", "vtkIOImage", "vtkIOLegacy", "vtkIOPLY", "vtkIOXML",
    "vtkImagingColor", "vtkImagingCore", "vtkRenderingCore", "vtkRenderingFreeType", "vtkRenderingOpenGL2",
]

MESH_EXTENSIONS = (".off", ".obj", ".ply", ".stl", ".vtp", ".vtk")
CURVE_EXTENSIONS = (".vtp", ".vtk", ".obj")

# Colours as RGB in [0, 1].
BACKGROUND = (1.0, 1.0, 1.0)
COARSE_SURFACE = (0.94, 0.89, 0.78)
COARSE_EDGES = (0.12, 0.12, 0.16)
FINE_SURFACE = (0.80, 0.80, 0.80)
CURVE_COLOUR = (0.10, 0.10, 0.14)
TITLE_COLOUR = (0.15, 0.15, 0.15)
# Tableau 10, with its grey swapped for a light blue so that no patch looks unpainted.
PALETTE = [
    "#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
    "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#a0cbe8",
]

EPILOG = """\
panels:
  coarse:MESH                  a straight triangle mesh: flat shaded, its edges drawn dark
  curves:FINE_MESH:CURVES      the fine mesh, smooth grey, with the geodesic curves on it as dark tubes
  overlay:OVERLAY.vtu[:CURVES] geotri-overlay's triangles coloured by their 'colour' cell array,
                               optionally with the curves on top
  curved:CURVED.vtu            geotri-curve's curved elements (Lagrange or Bezier cells), each subdivided so
                               that it shows its curvature, coloured by its certified min J / max J ('quality':
                               red at 0, yellow at 0.5, green at 1), with its curved sides drawn dark
  MESH and FINE_MESH: .off, .obj, .ply, .stl (or VTK .vtp, .vtk); CURVES: polylines in .vtp, .vtk,
  or .obj ('l' lines).

All panels share one camera, fitted to the union of their bounds, so that they can be compared. The view looks
along -z with +y up, turned by --azimuth about +y and then raised by --elevation.

example:
  render.py fig.png coarse:bone.coarse.off curves:bone.stl:bone.vtp overlay:bone.vtu:bone.vtp \\
      --title coarse geodesic flipped

Without a display (no DISPLAY), render.py re-runs itself under xvfb-run; it needs python3-vtk9, xvfb, xauth
and libgl1-mesa-dri (scripts/install-deps.sh --render).

exit codes:
  0  the PNG was written
  1  error: bad input, unreadable file, missing VTK or xvfb-run (no PNG is left behind)
  2  usage error
"""


# The VTK modules as one namespace; filled by import_vtk() once we know that VTK and a display are there.
vtk = None


class InputError(Exception):
    """Bad input or a missing dependency: reported as one line, exit code 1."""


# ----------------------------------------------------------------------------------------------------------------
# Command line


def panel_size(text):
    """argparse type for --width and --height."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not an integer")
    if not 32 <= value <= 4096:
        raise argparse.ArgumentTypeError(f"{value} is out of range [32, 4096]")
    return value


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog=PROG,
        usage="%(prog)s OUT.png PANEL [PANEL ...] [--width W] [--height H] [--azimuth A] [--elevation E]\n"
              "                 [--title TEXT ...] [--true-colour]",
        description="Renders geotri results headless as side-by-side panels, one PNG.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("out", metavar="OUT.png", help="the PNG to write (replaced atomically)")
    parser.add_argument("panels", metavar="PANEL", nargs="+",
                        help="coarse:..., curves:..., overlay:... or curved:... (below)")
    parser.add_argument("--width", type=panel_size, default=800, metavar="W",
                        help="width of each panel in pixels (default: %(default)s)")
    parser.add_argument("--height", type=panel_size, default=700, metavar="H",
                        help="height of each panel in pixels (default: %(default)s)")
    parser.add_argument("--azimuth", type=float, default=35.0, metavar="A",
                        help="turn the view about +y, in degrees (default: %(default)s)")
    parser.add_argument("--elevation", type=float, default=20.0, metavar="E",
                        help="raise the view towards +y, in degrees (default: %(default)s)")
    parser.add_argument("--title", nargs="+", default=[], metavar="TEXT",
                        help="one title per panel, in order, drawn at its top; '' for none (default: no titles)")
    parser.add_argument("--true-colour", action="store_true",
                        help="write 24-bit colour instead of a 256-colour palette: about three times larger "
                             "(default: off)")
    args = parser.parse_args(argv)
    if len(args.title) > len(args.panels):
        parser.error(f"{len(args.title)} titles for {len(args.panels)} panels")
    if not -90.0 < args.elevation < 90.0:
        parser.error(f"--elevation {args.elevation:g} is out of range (-90, 90)")
    return args


def parse_panel(spec):
    """Splits a PANEL argument into (kind, [files]); checks that the files exist."""
    kind, _, rest = spec.partition(":")
    parts = rest.split(":") if rest else []
    expected = {"coarse": (1, 1), "curves": (2, 2), "overlay": (1, 2), "curved": (1, 1)}
    if kind not in expected:
        raise InputError(f"{spec}: unknown panel kind '{kind}' (expected coarse:, curves:, overlay: or curved:)")
    low, high = expected[kind]
    if not low <= len(parts) <= high or not all(parts):
        forms = {"coarse": "coarse:MESH", "curves": "curves:FINE_MESH:CURVES",
                 "overlay": "overlay:OVERLAY.vtu[:CURVES]", "curved": "curved:CURVED.vtu"}
        raise InputError(f"{spec}: expected {forms[kind]}")
    for path in parts:
        if not os.path.isfile(path):
            raise InputError(f"{path}: no such file")
    return kind, parts


def check_output_folder(out):
    folder = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(folder):
        raise InputError(f"{out}: folder {folder} does not exist")
    if os.path.isdir(out):
        raise InputError(f"{out}: is a folder")


# ----------------------------------------------------------------------------------------------------------------
# Finding VTK and a display


def vtk_importable(python):
    """Whether `python` can import VTK, without importing it here (it is slow to load)."""
    if python == sys.executable:
        return importlib.util.find_spec("vtkmodules") is not None
    if not os.access(python, os.X_OK):
        return False
    result = subprocess.run([python, "-c", "import vtkmodules.vtkRenderingOpenGL2"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return result.returncode == 0


def reexec_if_needed(argv):
    """Re-runs this script under xvfb-run when there is no display, and under /usr/bin/python3 when this
    Python has no VTK (a pyenv or venv python first on PATH). Returns only when no re-run is needed."""
    if os.environ.get(REEXEC_GUARD):
        return
    needs_display = not os.environ.get("DISPLAY")
    python = sys.executable
    if not vtk_importable(python):
        if python != SYSTEM_PYTHON and vtk_importable(SYSTEM_PYTHON):
            python = SYSTEM_PYTHON
        else:
            raise InputError(f"python3-vtk9 is not installed ({INSTALL_HINT})")
    if not needs_display and python == sys.executable:
        return
    command = [python, os.path.abspath(__file__)] + argv
    if needs_display:
        for program, package in (("xvfb-run", "xvfb"), ("xauth", "xauth")):
            if shutil.which(program) is None:
                raise InputError(f"{program} is not installed (package {package}; {INSTALL_HINT})")
        command = [shutil.which("xvfb-run"), "-a", "-s", XVFB_SERVER_ARGS] + command
    os.environ[REEXEC_GUARD] = "1"
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(command[0], command)


def import_vtk():
    """Imports the VTK modules used here as one namespace, `vtk`. RenderingOpenGL2 and RenderingFreeType are
    needed for their side effect: they register the classes that make windows and text actually draw."""
    global vtk
    try:
        modules = [importlib.import_module("vtkmodules." + name) for name in VTK_MODULES]
    except ImportError:
        raise InputError(f"python3-vtk9 is not installed ({INSTALL_HINT})")
    vtk = types.SimpleNamespace(**{name: getattr(module, name)
                                   for module in modules for name in dir(module) if name.startswith("vtk")},
                                reference=modules[0].reference)  # vtkCommonCore's by-reference argument


# ----------------------------------------------------------------------------------------------------------------
# Reading


def numbers(fields, count, kind):
    """The first `count` fields converted by `kind`, or None when there are too few or one is malformed."""
    try:
        return [kind(f) for f in fields[:count]] if len(fields) >= count else None
    except ValueError:
        return None


def read_off(path):
    """An ASCII OFF file (OFF, COFF, NOFF, ...: the extra per-vertex fields are ignored)."""
    with open(path, "r", errors="replace") as f:
        tokens_by_line = []
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                tokens_by_line.append(line)
    if not tokens_by_line or not tokens_by_line[0][0].endswith("OFF"):
        raise InputError(f"{path}: not an ASCII OFF file (no OFF header)")
    header = tokens_by_line[0][1:] or (tokens_by_line[1] if len(tokens_by_line) > 1 else [])
    rows = tokens_by_line[1:] if tokens_by_line[0][1:] else tokens_by_line[2:]
    counts = numbers(header, 2, int)
    if counts is None:
        raise InputError(f"{path}: bad OFF header")
    n_vertices, n_faces = counts
    if len(rows) < n_vertices + n_faces:
        raise InputError(f"{path}: truncated OFF file")
    points = vtk.vtkPoints()
    points.SetDataTypeToDouble()
    for row in rows[:n_vertices]:
        xyz = numbers(row, 3, float)
        if xyz is None:
            raise InputError(f"{path}: bad vertex line '{' '.join(row)}'")
        points.InsertNextPoint(xyz)
    polys = vtk.vtkCellArray()
    for row in rows[n_vertices:n_vertices + n_faces]:
        ids = face_ids(path, row, n_vertices)
        polys.InsertNextCell(len(ids), ids)
    return make_polydata(points, polys=polys)


def face_ids(path, row, n_vertices):
    """An OFF face line's vertex indices, checked: 'n i1 ... in'."""
    try:
        n = int(row[0])
        ids = [int(i) for i in row[1:1 + n]]
    except (ValueError, IndexError):
        ids = []
    if len(ids) < 3 or len(ids) != n or not all(0 <= i < n_vertices for i in ids):
        raise InputError(f"{path}: bad face line '{' '.join(row)}'")
    return ids


def read_obj(path):
    """An OBJ file's vertices, faces ('f') and polylines ('l'); texture and normal indices are ignored."""
    points = vtk.vtkPoints()
    points.SetDataTypeToDouble()
    polys = vtk.vtkCellArray()
    lines = vtk.vtkCellArray()
    with open(path, "r", errors="replace") as f:
        for line in f:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "v":
                xyz = numbers(fields[1:], 3, float)
                if xyz is None:
                    raise InputError(f"{path}: bad vertex line '{line.strip()}'")
                points.InsertNextPoint(xyz)
            elif fields[0] in ("f", "l"):
                ids = obj_ids(path, line, fields[1:], points.GetNumberOfPoints())
                if fields[0] == "f":
                    polys.InsertNextCell(len(ids), ids)
                else:
                    lines.InsertNextCell(len(ids), ids)
    return make_polydata(points, polys=polys, lines=lines)


def obj_ids(path, line, fields, n_vertices):
    """OBJ indices are 1-based, negative ones count back from the last vertex, and may carry /vt/vn."""
    ids = []
    for field in fields:
        try:
            i = int(field.split("/")[0])
        except ValueError:
            raise InputError(f"{path}: bad element line '{line.strip()}'")
        i = i - 1 if i > 0 else n_vertices + i
        if not 0 <= i < n_vertices:
            raise InputError(f"{path}: index out of range in '{line.strip()}'")
        ids.append(i)
    if len(ids) < 2:
        raise InputError(f"{path}: bad element line '{line.strip()}'")
    return ids


def make_polydata(points, polys=None, lines=None):
    data = vtk.vtkPolyData()
    data.SetPoints(points)
    if polys is not None and polys.GetNumberOfCells():
        data.SetPolys(polys)
    if lines is not None and lines.GetNumberOfCells():
        data.SetLines(lines)
    return data


def run_vtk_reader(path, reader, what):
    """Runs a VTK reader, turning its error events (which it would print and ignore) into an InputError."""
    errors = []
    reader.AddObserver("ErrorEvent", lambda _obj, _event: errors.append(True))
    reader.SetFileName(path)
    reader.Update()
    output = reader.GetOutput()
    if errors or output is None or output.GetNumberOfPoints() == 0:
        raise InputError(f"{path}: not a readable {what}")
    return output


def read_legacy_polydata(path, what):
    reader = vtk.vtkPolyDataReader()
    reader.SetFileName(path)
    if not reader.IsFilePolyData():
        raise InputError(f"{path}: not a legacy VTK polydata file")
    return run_vtk_reader(path, reader, what)


def read_mesh(path):
    """A surface mesh as vtkPolyData with polygons."""
    ext = os.path.splitext(path)[1].lower()
    if ext == ".off":
        data = read_off(path)
    elif ext == ".obj":
        data = read_obj(path)
    elif ext == ".ply":
        data = run_vtk_reader(path, vtk.vtkPLYReader(), "PLY mesh")
    elif ext == ".stl":
        data = run_vtk_reader(path, vtk.vtkSTLReader(), "STL mesh")
    elif ext == ".vtp":
        data = run_vtk_reader(path, vtk.vtkXMLPolyDataReader(), "VTK XML polydata")
    elif ext == ".vtk":
        data = read_legacy_polydata(path, "VTK polydata")
    else:
        raise InputError(f"{path}: unknown mesh format (expected {', '.join(MESH_EXTENSIONS)})")
    if data.GetNumberOfPolys() == 0:
        raise InputError(f"{path}: has no faces")
    return data


def read_curves(path):
    """Polylines as vtkPolyData with lines."""
    ext = os.path.splitext(path)[1].lower()
    if ext == ".vtp":
        data = run_vtk_reader(path, vtk.vtkXMLPolyDataReader(), "VTK XML polydata")
    elif ext == ".vtk":
        data = read_legacy_polydata(path, "VTK polydata")
    elif ext == ".obj":
        data = read_obj(path)
    else:
        raise InputError(f"{path}: unknown curves format (expected {', '.join(CURVE_EXTENSIONS)})")
    if data.GetNumberOfLines() == 0:
        raise InputError(f"{path}: has no polylines")
    return data


def read_overlay(path):
    """geotri-overlay's unstructured grid, as polydata whose cells keep the integer 'colour' array."""
    if os.path.splitext(path)[1].lower() != ".vtu":
        raise InputError(f"{path}: an overlay must be a .vtu file (geotri-overlay -o X.vtu)")
    grid = run_vtk_reader(path, vtk.vtkXMLUnstructuredGridReader(), "VTK XML unstructured grid")
    colour = grid.GetCellData().GetArray("colour")
    if colour is None:
        raise InputError(f"{path}: has no 'colour' cell array (write it with geotri-overlay)")
    if colour.GetNumberOfComponents() != 1:
        raise InputError(f"{path}: the 'colour' cell array has {colour.GetNumberOfComponents()} components")
    surface = vtk.vtkGeometryFilter()
    surface.SetInputData(grid)
    surface.Update()
    data = surface.GetOutput()
    if data.GetNumberOfPolys() == 0:
        raise InputError(f"{path}: has no triangles")
    return data


# Points per curved side, and the subdivision level of each curved element's surface: enough for a smooth picture
# of elements of order up to 4.
CURVED_SIDE_POINTS = 16
CURVED_SUBDIVISION = 3
VTK_LAGRANGE_TRIANGLE, VTK_BEZIER_TRIANGLE = 69, 76  # VTK's cell types


def read_curved(path):
    """geotri-curve's unstructured grid of curved triangles: (the elements' surface, subdivided, as polydata whose
    cells keep the 'quality' array; the elements' sides as polylines, evaluated on the cells)."""
    if os.path.splitext(path)[1].lower() != ".vtu":
        raise InputError(f"{path}: curved elements must be a .vtu file (geotri-curve -o X.vtu)")
    grid = run_vtk_reader(path, vtk.vtkXMLUnstructuredGridReader(), "VTK XML unstructured grid")
    if grid.GetCellData().GetArray("quality") is None:
        raise InputError(f"{path}: has no 'quality' cell array (write it with geotri-curve)")
    curved_types = (VTK_LAGRANGE_TRIANGLE, VTK_BEZIER_TRIANGLE)
    if grid.GetNumberOfCells() == 0 or any(grid.GetCellType(c) not in curved_types
                                           for c in range(grid.GetNumberOfCells())):
        raise InputError(f"{path}: not every cell is a Lagrange or Bezier triangle")
    surface = vtk.vtkDataSetSurfaceFilter()
    surface.SetInputData(grid)
    surface.SetNonlinearSubdivisionLevel(CURVED_SUBDIVISION)
    surface.Update()
    # Each side of each cell, evaluated at parametric points: the cells' own curves, not the subdivision's chords.
    points, lines = vtk.vtkPoints(), vtk.vtkCellArray()
    corners = ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))
    x, weights = [0.0] * 3, [0.0] * 64
    sub = vtk.reference(0)
    for c in range(grid.GetNumberOfCells()):
        cell = grid.GetCell(c)
        for side in range(3):
            (u0, v0), (u1, v1) = corners[side], corners[(side + 1) % 3]
            lines.InsertNextCell(CURVED_SIDE_POINTS + 1)
            for k in range(CURVED_SIDE_POINTS + 1):
                t = k / CURVED_SIDE_POINTS
                cell.EvaluateLocation(sub, [u0 + t * (u1 - u0), v0 + t * (v1 - v0), 0.0], x, weights)
                lines.InsertCellPoint(points.InsertNextPoint(x))
    sides = vtk.vtkPolyData()
    sides.SetPoints(points)
    sides.SetLines(lines)
    return surface.GetOutput(), sides


def load_panel(kind, files):
    """Reads one panel's files: a dict with 'surface' (polydata) and maybe 'curves' (polydata)."""
    if kind == "curved":
        surface, sides = read_curved(files[0])
        return {"kind": kind, "surface": surface, "curves": sides}
    if kind == "coarse":
        return {"kind": kind, "surface": read_mesh(files[0])}
    if kind == "curves":
        return {"kind": kind, "surface": read_mesh(files[0]), "curves": read_curves(files[1])}
    panel = {"kind": kind, "surface": read_overlay(files[0])}
    if len(files) > 1:
        panel["curves"] = read_curves(files[1])
    return panel


# ----------------------------------------------------------------------------------------------------------------
# Camera


def view_axes(azimuth, elevation):
    """Unit vectors (towards the camera, up, right) of the view: -z with +y up, turned about +y by the azimuth,
    then raised by the elevation."""
    a, e = math.radians(azimuth), math.radians(elevation)
    back = (math.cos(e) * math.sin(a), math.sin(e), math.cos(e) * math.cos(a))
    up = (-math.sin(e) * math.sin(a), math.cos(e), -math.sin(e) * math.cos(a))
    right = (up[1] * back[2] - up[2] * back[1],
             up[2] * back[0] - up[0] * back[2],
             up[0] * back[1] - up[1] * back[0])
    return back, up, right


def view_bounds(datasets, axes):
    """Bounds of all points along (right, up, back): VTK transforms the points, so no Python loop over them."""
    back, up, right = axes
    matrix = vtk.vtkMatrix4x4()
    for row, axis in enumerate((right, up, back)):
        for col in range(3):
            matrix.SetElement(row, col, axis[col])
    transform = vtk.vtkTransform()
    transform.SetMatrix(matrix)
    box = vtk.vtkBoundingBox()
    for data in datasets:
        moved = vtk.vtkPoints()
        transform.TransformPoints(data.GetPoints(), moved)
        box.AddBounds(moved.GetBounds())
    bounds = [0.0] * 6
    box.GetBounds(bounds)
    return bounds


def fit_camera(datasets, args, title_band):
    """One parallel-projection camera setting for every panel, fitted to the union of all points, leaving
    `title_band` pixels free at the top. Returns (settings, world size of one pixel)."""
    axes = view_axes(args.azimuth, args.elevation)
    back, up, right = axes
    x0, x1, y0, y1, z0, z1 = view_bounds(datasets, axes)
    margin = 0.94  # the fraction of the free area that the mesh may fill
    free_height = args.height - title_band
    pixel = max((x1 - x0) / (args.width * margin), (y1 - y0) / (free_height * margin), 1e-12)
    # Centre of the points in view coordinates, moved up so that they sit centred below the title band.
    cx, cy, cz = (x0 + x1) / 2, (y0 + y1) / 2 + pixel * title_band / 2, (z0 + z1) / 2
    focal = [cx * right[i] + cy * up[i] + cz * back[i] for i in range(3)]
    distance = (z1 - z0) + (x1 - x0) + (y1 - y0)  # far enough to be in front of everything
    position = [focal[i] + distance * back[i] for i in range(3)]
    return {"focal": focal, "position": position, "up": up, "scale": pixel * args.height / 2}, pixel


def apply_camera(renderer, settings):
    camera = renderer.GetActiveCamera()
    camera.ParallelProjectionOn()
    camera.SetFocalPoint(settings["focal"])
    camera.SetPosition(settings["position"])
    camera.SetViewUp(settings["up"])
    camera.SetParallelScale(settings["scale"])
    renderer.ResetCameraClippingRange()


# ----------------------------------------------------------------------------------------------------------------
# Actors


def hex_rgb(text):
    return tuple(int(text[i:i + 2], 16) for i in (1, 3, 5))


def category_colour(index):
    """The palette's colours, then as many more distinct hues as needed (golden-angle steps)."""
    if index < len(PALETTE):
        return hex_rgb(PALETTE[index])
    hue = (index * 0.618033988749895) % 1.0
    return tuple(int(255 * c) for c in colorsys.hsv_to_rgb(hue, 0.55, 0.85))


def smooth_normals(data):
    """Point normals for smooth shading; sharp edges are not split, so the fine mesh looks like one surface."""
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputData(data)
    normals.SplittingOff()
    normals.ConsistencyOn()
    normals.Update()
    return normals.GetOutput()


def surface_actor(data, colour, smooth):
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(smooth_normals(data) if smooth else data)
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetColor(colour)
    prop.SetInterpolationToPhong() if smooth else prop.SetInterpolationToFlat()
    prop.SetAmbient(0.15)  # keeps the faces turned away from the lights from going near black
    prop.SetDiffuse(0.85)
    prop.SetSpecular(0.15 if smooth else 0.05)
    prop.SetSpecularPower(30)
    return actor


def coarse_actor(data, args):
    actor = surface_actor(data, COARSE_SURFACE, smooth=False)
    prop = actor.GetProperty()
    prop.EdgeVisibilityOn()
    prop.SetEdgeColor(COARSE_EDGES)
    prop.SetLineWidth(max(1.0, args.height / 450))
    return actor


def overlay_actor(data):
    """Each cell painted by its 'colour' index, as direct RGB so that no lookup table blends neighbours."""
    colour = data.GetCellData().GetArray("colour")
    rgb = vtk.vtkUnsignedCharArray()
    rgb.SetName("rgb")
    rgb.SetNumberOfComponents(3)
    rgb.SetNumberOfTuples(data.GetNumberOfCells())
    cache = {}
    for cell in range(data.GetNumberOfCells()):
        index = max(0, int(colour.GetTuple1(cell)))
        if index not in cache:
            cache[index] = category_colour(index)
        rgb.SetTypedTuple(cell, cache[index])
    painted = smooth_normals(data)
    painted.GetCellData().SetScalars(rgb)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(painted)
    mapper.SetScalarModeToUseCellData()
    mapper.SetColorModeToDirectScalars()
    return painted_actor(mapper)


def painted_actor(mapper):
    """A smooth-shaded actor whose colours come from its mapper's cell data."""
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetInterpolationToPhong()
    prop.SetAmbient(0.15)
    prop.SetDiffuse(0.85)
    prop.SetSpecular(0.1)
    return actor


def quality_actor(data):
    """Each cell painted by its 'quality' (certified min J / max J): red at 0, through yellow at 0.5, to green at 1."""
    table = vtk.vtkLookupTable()
    table.SetHueRange(0.0, 0.33)
    table.SetSaturationRange(0.75, 0.75)
    table.SetValueRange(0.95, 0.85)
    table.SetTableRange(0.0, 1.0)
    table.Build()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(smooth_normals(data))
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray("quality")
    mapper.SetLookupTable(table)
    mapper.UseLookupTableScalarRangeOn()
    mapper.ScalarVisibilityOn()
    return painted_actor(mapper)


def curves_actor(data, pixel, args):
    """Dark tubes of a fixed width in pixels (about 2.6 at the default height), so that the curves stay visible
    at any mesh size without drowning a small picture."""
    clean = vtk.vtkCleanPolyData()  # the tube filter cannot orient a segment between repeated points
    clean.SetInputData(data)
    clean.SetTolerance(0.0)
    tubes = vtk.vtkTubeFilter()
    tubes.SetInputConnection(clean.GetOutputPort())
    tubes.SetRadius(max(0.75, 1.3 * args.height / 700) * pixel)
    tubes.SetNumberOfSides(8)
    tubes.CappingOn()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(tubes.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(CURVE_COLOUR)
    actor.GetProperty().SetSpecular(0.2)
    return actor


def title_actor(text, args):
    actor = vtk.vtkTextActor()
    actor.SetInput(text)
    prop = actor.GetTextProperty()
    prop.SetFontSize(max(10, round(args.height * 0.04)))
    prop.SetColor(TITLE_COLOUR)
    prop.SetJustificationToCentered()
    prop.SetVerticalJustificationToTop()
    actor.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    actor.SetPosition(0.5, 0.975)
    return actor


def panel_actors(panel, args, pixel):
    if panel["kind"] == "coarse":
        actors = [coarse_actor(panel["surface"], args)]
    elif panel["kind"] == "curves":
        actors = [surface_actor(panel["surface"], FINE_SURFACE, smooth=True)]
    elif panel["kind"] == "curved":
        actors = [quality_actor(panel["surface"])]
    else:
        actors = [overlay_actor(panel["surface"])]
    if "curves" in panel:
        actors.append(curves_actor(panel["curves"], pixel, args))
    return actors


# ----------------------------------------------------------------------------------------------------------------
# Rendering and writing


def render_panels(panels, args):
    """Renders each panel in turn in one offscreen window; returns the panels side by side as one image."""
    titles = args.title + [""] * (len(panels) - len(args.title))
    title_band = round(args.height * 0.07) if any(titles) else 0
    datasets = [data for panel in panels for data in (panel["surface"], panel.get("curves")) if data is not None]
    camera, pixel = fit_camera(datasets, args, title_band)

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)  # never flash a window on a real display
    window.SetSize(args.width, args.height)
    window.SetMultiSamples(8)
    row = vtk.vtkImageAppend()
    row.SetAppendAxis(0)
    for panel, title in zip(panels, titles):
        renderer = vtk.vtkRenderer()
        renderer.SetBackground(BACKGROUND)
        vtk.vtkLightKit().AddLightsToRenderer(renderer)  # key, fill and back lights: softer than a headlight
        for actor in panel_actors(panel, args, pixel):
            renderer.AddActor(actor)
        if title:
            renderer.AddActor2D(title_actor(title, args))
        window.AddRenderer(renderer)
        apply_camera(renderer, camera)
        window.Render()
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(window)
        grab.SetInputBufferTypeToRGB()
        grab.ReadFrontBufferOff()
        grab.Update()
        image = vtk.vtkImageData()
        image.DeepCopy(grab.GetOutput())
        row.AddInputData(image)
        window.RemoveRenderer(renderer)
    row.Update()
    window.Finalize()
    return row.GetOutput()


def quantized_png_bytes(image):
    """The image as an indexed PNG of 256 colours. vtkPNGWriter writes only true colour, where the smooth shading
    costs about 170 KB a panel; a palette PNG is a third of that and looks the same."""
    quantize = vtk.vtkImageQuantizeRGBToIndex()
    quantize.SetInputData(image)
    quantize.SetNumberOfColors(256)
    to_bytes = vtk.vtkImageCast()  # the indices come as unsigned short
    to_bytes.SetInputConnection(quantize.GetOutputPort())
    to_bytes.SetOutputScalarTypeToUnsignedChar()
    to_bytes.Update()
    width, height, _ = image.GetDimensions()
    pixels = bytes(memoryview(to_bytes.GetOutput().GetPointData().GetScalars()))
    # VTK's rows run bottom to top, PNG's top to bottom; each PNG row starts with its filter type (0: none, which
    # suits palette indices best).
    rows = b"".join(b"\0" + pixels[y * width:(y + 1) * width] for y in reversed(range(height)))
    table = quantize.GetLookupTable()
    palette = b"".join(bytes(round(255 * c) for c in table.GetTableValue(i)[:3])
                       for i in range(table.GetNumberOfColors()))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, 3, 0, 0, 0)  # 8-bit indices, colour type 3 (palette)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"PLTE", palette)
            + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def write_true_colour_png(image, path):
    writer = vtk.vtkPNGWriter()
    writer.SetCompressionLevel(9)
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()
    if writer.GetErrorCode() != 0 or os.path.getsize(path) == 0:
        raise OSError(f"vtkPNGWriter failed (VTK error code {writer.GetErrorCode()})")


def write_png(image, out, true_colour):
    """Writes to a temporary file in the same folder, then renames it: a failure never leaves a partial PNG."""
    folder = os.path.dirname(os.path.abspath(out))
    fd, temporary = tempfile.mkstemp(prefix="." + os.path.basename(out) + ".", suffix=".tmp", dir=folder)
    try:
        if true_colour:
            os.close(fd)
            write_true_colour_png(image, temporary)
        else:
            with os.fdopen(fd, "wb") as f:
                f.write(quantized_png_bytes(image))
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # mkstemp makes it private; give it a normal file's mode
        os.replace(temporary, out)
    except BaseException as error:
        if os.path.exists(temporary):
            os.remove(temporary)
        if isinstance(error, OSError):
            raise InputError(f"{out}: cannot write the PNG: {error.strerror or error}")
        raise


def main(argv):
    args = parse_args(argv)
    try:
        specs = [parse_panel(spec) for spec in args.panels]
        check_output_folder(args.out)
        reexec_if_needed(argv)
        import_vtk()
        if not os.environ.get("DISPLAY"):
            raise InputError("no display, even under xvfb-run (scripts/install-deps.sh --render installs Xvfb)")
        vtk.vtkObject.GlobalWarningDisplayOff()  # readers' errors are caught and reported as one line instead
        panels = [load_panel(kind, files) for kind, files in specs]
        write_png(render_panels(panels, args), args.out, args.true_colour)
    except InputError as error:
        print(f"{PROG}: error: {error}", file=sys.stderr)
        return 1
    except OSError as error:
        name = error.filename or args.out
        print(f"{PROG}: error: {name}: {error.strerror or error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

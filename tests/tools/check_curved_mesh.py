#!/usr/bin/python3
"""Reads curved elements written by geotri-curve with clients that nobody here wrote, and checks them:

    check_curved_mesh.py FILE.msh ORDER MIN_QUALITY     gmsh reads it: the element type of ORDER, its own node order,
                                                        and its own Jacobian check (AnalyseMeshQuality, Bezier bounds)
                                                        finds no inverted element and a worst minJ/maxJ >= MIN_QUALITY;
                                                        meshio reads the same nodes and elements
    check_curved_mesh.py FILE.vtu ORDER                 meshio and VTK read it: Lagrange triangles of ORDER, and VTK
                                                        evaluates each cell at its own nodes to their positions

Exits 0 when every check passes, 1 with a message when one fails, and 77 when gmsh, meshio or VTK is missing.
"""
import sys


def fail(message):
    print(f"check_curved_mesh.py: {message}", file=sys.stderr)
    sys.exit(1)


def nodes_per_triangle(order):
    return (order + 1) * (order + 2) // 2


def check_msh(path, order, min_quality):
    try:
        import gmsh
        import meshio
    except ImportError as missing:
        print(f"check_curved_mesh.py: skipped: {missing}", file=sys.stderr)
        sys.exit(77)
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.merge(path)
    types, tags, _ = gmsh.model.mesh.getElements(2)
    expected_type = gmsh.model.mesh.getElementType("Triangle", order)
    if list(types) != [expected_type]:
        fail(f"{path}: gmsh reads element types {list(types)}, not the triangle of order {order} ({expected_type})")
    elements = len(tags[0])
    # gmsh's own node order of the triangle of this order, from its reference coordinates: every node that gmsh puts
    # on an edge of the reference triangle is used by the two elements of that edge (the mesh is closed and
    # conforming), every interior one by this element alone, and along each edge, the nodes lie farther and farther
    # from the edge's first corner in gmsh's order of their reference coordinates.
    per = nodes_per_triangle(order)
    local = gmsh.model.mesh.getElementProperties(expected_type)[4]  # (u, v) per node
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    position = {int(t): coords[3 * i:3 * i + 3] for i, t in enumerate(node_tags)}
    element_nodes = [int(t) for t in gmsh.model.mesh.getElements(2)[2][0]]
    users = {}
    for t in element_nodes:
        users[t] = users.get(t, 0) + 1
    eps = 1e-9
    # Per reference edge: its first corner, and the parameter of a node along it.
    edges = [(0, lambda u, v: v < eps, lambda u, v: u), (1, lambda u, v: abs(u + v - 1) < eps, lambda u, v: v),
             (2, lambda u, v: u < eps, lambda u, v: 1 - v)]
    for e in range(elements):
        tags_e = element_nodes[per * e:per * (e + 1)]
        for q in range(per):
            u, v = local[2 * q], local[2 * q + 1]
            on_edge = any(on(u, v) for _, on, _ in edges)
            corner = q < 3
            expected = None if corner else (2 if on_edge else 1)
            if expected is not None and users[tags_e[q]] != expected:
                fail(f"{path}: node {q} of element {e + 1} (reference {u:.3f}, {v:.3f}) is used by "
                     f"{users[tags_e[q]]} elements, not {expected}")
        for first, on, along in edges:
            run = sorted((along(local[2 * q], local[2 * q + 1]), q) for q in range(3, per)
                         if on(local[2 * q], local[2 * q + 1]))
            start = position[tags_e[first]]
            distances = [sum((position[tags_e[q]][c] - start[c]) ** 2 for c in range(3)) ** 0.5 for _, q in run]
            if any(b <= a for a, b in zip(distances, distances[1:])):
                fail(f"{path}: element {e + 1}: the nodes of its edge from corner {first} are not in order")
    gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 1)
    gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 1)
    gmsh.plugin.run("AnalyseMeshQuality")
    worst = None
    for view in gmsh.view.getTags():
        name = gmsh.option.getString(f"View[{gmsh.view.getIndex(view)}].Name")
        if name.startswith("minJ/maxJ"):
            _, _, data, _, _ = gmsh.view.getModelData(view, 0)
            worst = min(d[0] for d in data)
    gmsh.finalize()
    if worst is None:
        fail(f"{path}: gmsh's AnalyseMeshQuality made no minJ/maxJ view")
    if worst <= 0:
        fail(f"{path}: gmsh finds an inverted element (minJ/maxJ {worst})")
    if worst < min_quality:
        fail(f"{path}: gmsh's worst minJ/maxJ is {worst}, below {min_quality}")

    mesh = meshio.read(path)
    cells = [c for c in mesh.cells if c.data.shape[1] == per]
    if sum(len(c.data) for c in cells) != elements:
        fail(f"{path}: meshio reads {sum(len(c.data) for c in cells)} triangles of {per} nodes, gmsh {elements}")
    if len(mesh.points) != len(node_tags):
        fail(f"{path}: meshio reads {len(mesh.points)} nodes, gmsh {len(node_tags)}")
    print(f"{path}: {elements} elements of order {order}; gmsh: none inverted, worst minJ/maxJ {worst:.4f}")


def check_vtu(path, order):
    try:
        import meshio
        import vtk
    except ImportError as missing:
        print(f"check_curved_mesh.py: skipped: {missing}", file=sys.stderr)
        sys.exit(77)
    per = nodes_per_triangle(order)
    mesh = meshio.read(path)
    triangles = sum(len(c.data) for c in mesh.cells if c.data.shape[1] == per)
    if triangles == 0:
        fail(f"{path}: meshio reads no triangle of {per} nodes")
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfCells() != triangles:
        fail(f"{path}: VTK reads {grid.GetNumberOfCells()} cells, meshio {triangles}")
    for c in range(grid.GetNumberOfCells()):
        cell = grid.GetCell(c)
        if cell.GetCellType() != vtk.VTK_LAGRANGE_TRIANGLE or cell.GetNumberOfPoints() != per:
            fail(f"{path}: cell {c} is not a Lagrange triangle of {per} nodes")
        parametric = cell.GetParametricCoords()
        weights = [0.0] * per
        for q in range(min(per, 64)):
            pcoords = [parametric[3 * q], parametric[3 * q + 1], parametric[3 * q + 2]]
            cell.InterpolateFunctions(pcoords, weights)
            x = [sum(weights[k] * cell.GetPoints().GetPoint(k)[d] for k in range(per)) for d in range(3)]
            node = cell.GetPoints().GetPoint(q)
            if max(abs(x[d] - node[d]) for d in range(3)) > 1e-9 * (1 + max(abs(v) for v in node)):
                fail(f"{path}: VTK's cell {c} at its parametric node {q} is not that node")
    print(f"{path}: {triangles} Lagrange triangles of order {order}, read by meshio and VTK")


def main():
    if len(sys.argv) < 3:
        fail("usage: check_curved_mesh.py FILE ORDER [MIN_QUALITY]")
    path, order = sys.argv[1], int(sys.argv[2])
    if path.endswith(".msh"):
        check_msh(path, order, float(sys.argv[3]) if len(sys.argv) > 3 else 0.0)
    elif path.endswith(".vtu"):
        check_vtu(path, order)
    else:
        fail(f"{path}: not .msh or .vtu")


if __name__ == "__main__":
    main()

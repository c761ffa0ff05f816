#!/usr/bin/python3
"""Reads curved elements written by geotri-curve with clients that nobody here wrote, and checks them:

    check_curved_mesh.py FILE.msh ORDER MIN_QUALITY     gmsh reads it: the element type of ORDER, its own node order,
                                                        and its own Jacobian check (AnalyseMeshQuality, Bezier bounds)
                                                        finds no inverted element and a worst minJ/maxJ >= MIN_QUALITY;
                                                        meshio reads the same nodes and elements
    check_curved_mesh.py FILE.vtu ORDER                 meshio and VTK read it: Lagrange triangles of ORDER, and VTK
                                                        evaluates each cell at its own nodes to their positions
    check_curved_mesh.py FILE.vtu ORDER LAGRANGE.vtu    FILE holds Bezier triangles: VTK evaluates each one at the
                                                        parametric nodes to the nodes of LAGRANGE.vtu's same cell
    check_curved_mesh.py FILE.mesh ORDER SAME.msh       an MFEM mesh v1.0, read here by the rules of MFEM's format
                                                        (its H1 degrees of freedom: vertices, edges numbered as they
                                                        first appear, their nodes from the lower vertex, interiors in
                                                        lexicographic order): each element's nodes, by reference
                                                        coordinates, are those that gmsh reads for it from SAME.msh

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


def vtk_grid(path):
    import vtk
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def close(x, y):
    return max(abs(x[d] - y[d]) for d in range(3)) <= 1e-9 * (1 + max(abs(v) for v in y))


def check_bezier_vtu(path, order, lagrange_path):
    """VTK evaluates each Bezier cell at its parametric nodes; the Lagrange cell of the same index has its nodes
    there, so the two files are the same surface."""
    try:
        import vtk
    except ImportError as missing:
        print(f"check_curved_mesh.py: skipped: {missing}", file=sys.stderr)
        sys.exit(77)
    per = nodes_per_triangle(order)
    bezier, lagrange = vtk_grid(path), vtk_grid(lagrange_path)
    if bezier.GetNumberOfCells() != lagrange.GetNumberOfCells():
        fail(f"{path}: {bezier.GetNumberOfCells()} cells, {lagrange_path} {lagrange.GetNumberOfCells()}")
    weights = [0.0] * per
    for c in range(bezier.GetNumberOfCells()):
        cell = bezier.GetCell(c)
        if cell.GetCellType() != vtk.VTK_BEZIER_TRIANGLE or cell.GetNumberOfPoints() != per:
            fail(f"{path}: cell {c} is not a Bezier triangle of {per} control points")
        reference = lagrange.GetCell(c)
        parametric = reference.GetParametricCoords()
        for q in range(per):
            cell.InterpolateFunctions([parametric[3 * q], parametric[3 * q + 1], parametric[3 * q + 2]], weights)
            x = [sum(weights[k] * cell.GetPoints().GetPoint(k)[d] for k in range(per)) for d in range(3)]
            if not close(x, reference.GetPoints().GetPoint(q)):
                fail(f"{path}: Bezier cell {c} at parametric node {q} is {x}, not the Lagrange node "
                     f"{reference.GetPoints().GetPoint(q)}")
    print(f"{path}: {bezier.GetNumberOfCells()} Bezier triangles of order {order}, through the Lagrange nodes")


def read_mfem_nodes(path, order):
    """The elements' vertices and, per element, its nodes as {(u, v): position} from an MFEM mesh v1.0 file with a
    nodes grid function of H1 with equispaced nodes (H1@U_2D_Pp), by MFEM's documented numbering of H1 degrees of
    freedom."""
    words = open(path).read().split("\n")
    if words[0].strip() != "MFEM mesh v1.0":
        fail(f"{path}: not an MFEM mesh v1.0 (first line {words[0]!r})")
    lines = [w.strip() for w in words if w.strip() and not w.strip().startswith("#")]
    at = lines.index("dimension")
    if lines[at + 1] != "2":
        fail(f"{path}: dimension {lines[at + 1]}, not 2")
    at = lines.index("elements")
    count = int(lines[at + 1])
    elements = []
    for line in lines[at + 2:at + 2 + count]:
        attribute, geometry, *vertices = (int(w) for w in line.split())
        if geometry != 2 or len(vertices) != 3 or attribute < 1:
            fail(f"{path}: element line {line!r} is not a triangle with a positive attribute")
        elements.append(vertices)
    if lines[lines.index("boundary") + 1] != "0":
        fail(f"{path}: a closed surface has no boundary elements")
    vertex_count = int(lines[lines.index("vertices") + 1])
    at = lines.index("nodes")
    header = dict(line.split(": ", 1) for line in lines[at + 2:at + 5])
    if lines[at + 1] != "FiniteElementSpace" or header.get("FiniteElementCollection") != f"H1@U_2D_P{order}" \
            or header.get("VDim") != "3" or header.get("Ordering") != "1":
        fail(f"{path}: nodes are not H1@U_2D_P{order}, VDim 3, Ordering 1: {lines[at + 1:at + 5]}")
    values = [float(w) for line in lines[at + 5:] for w in line.split()]
    p = order
    # MFEM numbers an edge when it first meets it, looping the elements and their sides 0-1, 1-2, 2-0.
    edge_index = {}
    for vertices in elements:
        for s in range(3):
            key = tuple(sorted((vertices[s], vertices[(s + 1) % 3])))
            edge_index.setdefault(key, len(edge_index))
    if 2 * len(edge_index) != 3 * len(elements):
        fail(f"{path}: {len(edge_index)} edges for {len(elements)} triangles: not a closed surface")
    interior = (p - 1) * (p - 2) // 2
    total = vertex_count + (p - 1) * len(edge_index) + interior * len(elements)
    if len(values) != 3 * total:
        fail(f"{path}: {len(values) // 3} nodes, MFEM's H1 space of order {p} here has {total}")

    def node(dof):
        return values[3 * dof:3 * dof + 3]

    corners = [(0, 0), (p, 0), (0, p)]  # reference (u, v) times p
    result = []
    for e, vertices in enumerate(elements):
        nodes = {corners[s]: node(vertices[s]) for s in range(3)}
        for s in range(3):
            a, b = vertices[s], vertices[(s + 1) % 3]
            first = vertex_count + (p - 1) * edge_index[tuple(sorted((a, b)))]
            for m in range(1, p):  # m/p of the way from corner s to corner s + 1
                k = m - 1 if a < b else p - 1 - m  # an edge's nodes run from its lower vertex
                u = corners[s][0] + m * (corners[(s + 1) % 3][0] - corners[s][0]) // p
                v = corners[s][1] + m * (corners[(s + 1) % 3][1] - corners[s][1]) // p
                nodes[(u, v)] = node(first + k)
        first = vertex_count + (p - 1) * len(edge_index) + interior * e
        k = 0
        for j in range(1, p):
            for i in range(1, p - j):
                nodes[(i, j)] = node(first + k)
                k += 1
        result.append(nodes)
    return result


def check_mfem(path, order, msh_path):
    try:
        import gmsh
    except ImportError as missing:
        print(f"check_curved_mesh.py: skipped: {missing}", file=sys.stderr)
        sys.exit(77)
    mfem = read_mfem_nodes(path, order)
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.merge(msh_path)
    element_type = gmsh.model.mesh.getElementType("Triangle", order)
    local = gmsh.model.mesh.getElementProperties(element_type)[4]
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    position = {int(t): coords[3 * i:3 * i + 3] for i, t in enumerate(node_tags)}
    tags, element_nodes = gmsh.model.mesh.getElementsByType(element_type)
    gmsh.finalize()
    per = nodes_per_triangle(order)
    by_tag = {int(t): [int(n) for n in element_nodes[per * i:per * (i + 1)]] for i, t in enumerate(tags)}
    if len(by_tag) != len(mfem):
        fail(f"{path}: {len(mfem)} elements, gmsh reads {len(by_tag)} from {msh_path}")
    for e, nodes in enumerate(mfem):
        ours = by_tag[e + 1]
        for q in range(per):
            uv = (round(local[2 * q] * order), round(local[2 * q + 1] * order))
            if not close(nodes[uv], position[ours[q]]):
                fail(f"{path}: element {e + 1} at reference {uv}/{order} is {nodes[uv]}, gmsh's node there "
                     f"{list(position[ours[q]])}")
    print(f"{path}: {len(mfem)} elements of order {order}, node by node those of {msh_path}")


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
    grid = vtk_grid(path)
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
            if not close(x, cell.GetPoints().GetPoint(q)):
                fail(f"{path}: VTK's cell {c} at its parametric node {q} is not that node")
    print(f"{path}: {triangles} Lagrange triangles of order {order}, read by meshio and VTK")


def main():
    if len(sys.argv) < 3:
        fail("usage: check_curved_mesh.py FILE ORDER [MIN_QUALITY | LAGRANGE.vtu | SAME.msh]")
    path, order = sys.argv[1], int(sys.argv[2])
    third = sys.argv[3] if len(sys.argv) > 3 else None
    if path.endswith(".msh"):
        check_msh(path, order, float(third) if third else 0.0)
    elif path.endswith(".vtu") and third:
        check_bezier_vtu(path, order, third)
    elif path.endswith(".vtu"):
        check_vtu(path, order)
    elif path.endswith(".mesh") and third:
        check_mfem(path, order, third)
    else:
        fail(f"{path}: not .msh, .vtu (with a Lagrange .vtu for Bezier cells) or .mesh (with the same .msh)")


if __name__ == "__main__":
    main()

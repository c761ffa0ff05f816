#pragma once
// Writing curved elements for solvers and viewers (DESIGN.md §5): gmsh's MSH 4.1 and 2.2, VTK's XML unstructured
// grid with Lagrange or Bézier triangles, and MFEM's mesh v1.0. Every file is written from the one node table of a
// CurvedMesh.

#include <geotri/curved_elements.h>

#include <string>

namespace geotri {

/// The MSH versions that write_msh() writes.
enum class MshVersion { v41, v22 };

/// The cells that write_vtu() writes.
enum class VtuCells {
    lagrange,  ///< VTK_LAGRANGE_TRIANGLE (69) through the nodes
    bezier,    ///< VTK_BEZIER_TRIANGLE (76) on the control points (bezier_control_points()): the same surface
};

/// gmsh's element type of the Lagrange triangle of order p (2, 9, 21, 23, 25, 42, 43, 44 for p = 1 .. 8).
/// Throws InvalidInput for p outside [1, 8].
int gmsh_triangle_type(int order);

/// Writes `curved` as gmsh MSH, ASCII: one surface entity per component of T (tag component + 1), each its own
/// physical group ("component N"); every node of the table once, tagged from 1 in its order; one triangle of the
/// mesh's order per element, tagged from 1 in face order, nodes in gmsh's order. Writes to a temporary file in the
/// same folder and renames it. Throws IOError when the file cannot be written.
void write_msh(const std::string& path, const CurvedMesh& curved, MshVersion version = MshVersion::v41);

/// Writes `curved` as a VTK XML unstructured grid (.vtu): the node table as points (or the control points, for
/// Bézier cells), one triangle per element in gmsh's node order (which is VTK's), and per cell its coarse face,
/// component, patch colour, certified minJ/maxJ lower bound, certificates (1 valid, 0 invalid, -1 undecided) and
/// distance bound relative to the diagonal. Atomic, as write_msh(). Throws IOError when the file cannot be written.
void write_vtu(const std::string& path, const CurvedMesh& curved, VtuCells cells = VtuCells::lagrange);

/// Writes `curved` as an MFEM mesh v1.0 (.mesh): a surface (dimension 2) whose vertices are G's, one triangle per
/// element with attribute component + 1, no boundary, and the curved nodes as the `nodes` grid function of the
/// collection H1@U_2D_Pp (equispaced nodes, which are ours), 3 values per node. The values follow MFEM's degrees
/// of freedom: vertices; then edges, numbered as they first appear looping the elements and their sides 0-1, 1-2,
/// 2-0, each edge's inner nodes running from its lower vertex to its higher; then each element's interior nodes in
/// lexicographic order. Atomic, as write_msh(). Throws IOError when the file cannot be written.
void write_mfem(const std::string& path, const CurvedMesh& curved);

/// How write_curved_mesh() writes each format.
struct CurvedFileOptions {
    MshVersion msh_version = MshVersion::v41;
    VtuCells vtu_cells = VtuCells::lagrange;
};

/// write_msh() for ".msh", write_vtu() for ".vtu" and write_mfem() for ".mesh". Throws InvalidInput for another
/// extension.
void write_curved_mesh(const std::string& path, const CurvedMesh& curved, const CurvedFileOptions& options = {});

}  // namespace geotri

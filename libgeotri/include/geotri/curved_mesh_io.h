#pragma once
// Writing curved elements for solvers and viewers (DESIGN.md §5): gmsh's MSH 4.1 and 2.2, and VTK's XML
// unstructured grid with Lagrange triangles. Every file is written from the one node table of a CurvedMesh.

#include <geotri/curved_elements.h>

#include <string>

namespace geotri {

/// The MSH versions that write_msh() writes.
enum class MshVersion { v41, v22 };

/// gmsh's element type of the Lagrange triangle of order p (2, 9, 21, 23, 25, 42, 43, 44 for p = 1 .. 8).
/// Throws InvalidInput for p outside [1, 8].
int gmsh_triangle_type(int order);

/// Writes `curved` as gmsh MSH, ASCII: one surface entity per component of T (tag component + 1), each its own
/// physical group ("component N"); every node of the table once, tagged from 1 in its order; one triangle of the
/// mesh's order per element, tagged from 1 in face order, nodes in gmsh's order. Writes to a temporary file in the
/// same folder and renames it. Throws IOError when the file cannot be written.
void write_msh(const std::string& path, const CurvedMesh& curved, MshVersion version = MshVersion::v41);

/// Writes `curved` as a VTK XML unstructured grid (.vtu): the node table as points, one VTK_LAGRANGE_TRIANGLE
/// (69) per element in the same node order, and per cell its coarse face, component, patch colour, certified
/// minJ/maxJ lower bound, certificates (1 valid, 0 invalid, -1 undecided) and distance bound relative to the
/// diagonal. Atomic, as write_msh(). Throws IOError when the file cannot be written.
void write_vtu(const std::string& path, const CurvedMesh& curved);

/// write_msh() for ".msh" and write_vtu() for ".vtu". Throws InvalidInput for another extension.
void write_curved_mesh(const std::string& path, const CurvedMesh& curved, MshVersion version = MshVersion::v41);

}  // namespace geotri

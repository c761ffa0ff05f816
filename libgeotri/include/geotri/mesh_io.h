#pragma once
// Reading and writing triangle meshes with coordinates kept bit for bit.

#include <geotri/fine_mesh.h>
#include <geotri/mesh_data.h>

#include <string>

namespace geotri {

/// Reads `.stl` (binary or ASCII; vertices welded by exact position), `.off` (COFF colour columns allowed), `.obj`
/// and `.ply` (ASCII or binary, float or double). Every coordinate reads back bit for bit as the file holds it.
/// Throws IOError with a message that starts with the path: unreadable, unknown extension, empty, truncated,
/// malformed, NaN or infinite coordinates, indices out of range, non-triangular faces.
MeshData read_mesh(const std::string& path);

/// Writes by extension (`.off`, `.obj`, `.ply`), every double printed so that it reads back exactly (`%.17g`, or
/// binary doubles in PLY). Writes to a temporary file in the same folder and renames it, so that a failure never
/// leaves a partial file. Throws IOError.
void write_mesh(const std::string& path, const MeshData& mesh);

/// Reads `path` exactly (read_mesh) and checks it (make_fine_mesh). Throws IOError for a file problem,
/// TopologyError for a mesh that is not closed, manifold and oriented, and InvalidInput for bad numbers (a
/// coordinate that is not finite or beyond 1e75, a mesh or component of zero area; faces of zero area are allowed);
/// every message starts with the path and says what is wrong and how much of it ("14 boundary edges", "vertex 812
/// is non-manifold").
FineMesh load_fine_mesh(const std::string& path);

}  // namespace geotri

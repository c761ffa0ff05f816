#pragma once
// Reading and writing triangle meshes with coordinates kept bit for bit.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace geotri {

/// Positions and triangles, as loaded: indices refer to the load order of the vertices.
struct MeshData {
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::array<int, 3>> triangles;
};

/// Reads `.stl` (binary or ASCII; vertices welded by exact position), `.off` (COFF colour columns allowed), `.obj`
/// and `.ply` (ASCII or binary, float or double). Every coordinate reads back bit for bit as the file holds it.
/// Throws IOError with a message that starts with the path: unreadable, unknown extension, empty, truncated,
/// malformed, NaN or infinite coordinates, indices out of range, non-triangular faces.
MeshData read_mesh(const std::string& path);

/// Writes by extension (`.off`, `.obj`, `.ply`), every double printed so that it reads back exactly (`%.17g`, or
/// binary doubles in PLY). Writes to a temporary file in the same folder and renames it, so that a failure never
/// leaves a partial file. Throws IOError.
void write_mesh(const std::string& path, const MeshData& mesh);

}  // namespace geotri

#pragma once
// A triangle mesh as plain arrays: what the readers give and the writers take.

#include <Eigen/Core>

#include <array>
#include <vector>

namespace geotri {

/// Positions and triangles, as loaded: indices refer to the load order of the vertices.
struct MeshData {
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::array<int, 3>> triangles;
};

}  // namespace geotri

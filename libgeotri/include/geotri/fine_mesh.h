#pragma once
// The fine mesh T (DESIGN.md §1): loaded once, exactly, checked, and never changed.

#include <geodesic/mesh.h>
#include <geotri/mesh_data.h>

#include <cstdint>
#include <string>
#include <vector>

namespace geotri {

/// T as loaded and checked: closed, edge- and vertex-manifold, consistently oriented, finite coordinates.
/// Several components are allowed. Zero-area faces are allowed (they are reported in the counts, not refused).
struct FineMesh {
    std::string path;                ///< where it was read from (empty when built from arrays)
    geodesic::Mesh mesh;             ///< positions and triangles in load order, with the geodesic adjacency
    std::uint64_t checksum = 0;      ///< of the positions (bit patterns) and triangles, as loaded (fine_mesh_checksum)
    std::vector<int> component;      ///< per vertex: its connected component, numbered in order of first vertex
    int num_components = 0;
    int num_zero_area_faces = 0;
    std::vector<int> genus;          ///< per component: V - F/2 = 2 - 2 genus, since T is closed (E = 3F/2)
};

/// The largest coordinate (in absolute value) that a fine or coarse mesh may have: below it every length, area and
/// the geodesic arithmetic stay finite (a face's area squares its squared edge lengths, which overflows from about
/// 1e77). The readers read any finite value exactly; this bound is the geometry's.
constexpr double k_max_coordinate = 1e75;

/// Checks the arrays as load_fine_mesh does; `name` prefixes the messages.
FineMesh make_fine_mesh(MeshData data, const std::string& name);

/// A checksum of a mesh as loaded: the same arrays always give the same value on every platform.
std::uint64_t fine_mesh_checksum(const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<std::array<int, 3>>& triangles);

}  // namespace geotri

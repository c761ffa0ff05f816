#pragma once
// CGAL's Surface_mesh_shortest_path (Xin and Wang's exact algorithm) as an independent reference for the benchmark.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace geotri::bench {

struct CgalRun {
    double seconds = 0.0;           ///< adding the source and building the sequence tree
    std::vector<double> distances;  ///< per vertex; +inf where CGAL reports no path
    std::string error;              ///< non-empty when CGAL could not run on this mesh
};

/// Single-source distances from vertex `source` to every vertex.
CgalRun cgal_vertex_distances(const std::vector<Eigen::Vector3d>& positions,
                              const std::vector<std::array<int, 3>>& triangles, int source);

}  // namespace geotri::bench

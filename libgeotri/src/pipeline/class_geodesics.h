#pragma once
// Private to libgeotri: the geodesic of each coarse edge in the class that the decimation gave it, for trace().

#include <geotri/edge_paths_io.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/trace.h>

#include <vector>

namespace geotri::detail {

/// Per coarse edge, in edge order: its path of `paths` along its first halfedge, after checking that the paths
/// fit g (its vertices located, not yet traced). Throws IOError("NAME: problem") when they were made for another T
/// or another coarse mesh, or when a path does not join the fine vertices of its edge's ends.
std::vector<std::vector<int>> reference_paths(const GeodesicTriangulation& g, const EdgePaths& paths);

/// With the shortest geodesics traced in g: straightens every reference path with the coarse vertices pinned
/// (geodesic::straighten_path) and, unless g is valid already, gives g the class geodesics where they differ
/// from the shortest when that makes g valid or leaves fewer violations. Fills the class_geodesics_* counts of
/// `result`. Throws IOError("NAME: coarse edge (A, B): problem") for a path that is not one along edges of T.
void prefer_class_geodesics(GeodesicTriangulation& g, const std::vector<std::vector<int>>& reference,
                            const std::string& name, int threads, TraceResult& result);

}  // namespace geotri::detail

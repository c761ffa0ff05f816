#pragma once
// Private to libgeotri: the geodesic of each coarse edge in the class that the decimation gave it, for trace().

#include <geotri/edge_paths_io.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/trace.h>

namespace geotri::detail {

/// With the shortest geodesics traced in g: straightens every edge's path of `paths` with the coarse vertices
/// pinned (geodesic::straighten_path) and, unless g is valid already, gives g the class geodesics where they differ
/// from the shortest when that makes g valid or leaves fewer violations. Fills the class_geodesics_* counts of
/// `result`. Throws IOError("NAME: problem") when the paths were made for another T or another coarse mesh.
void prefer_class_geodesics(GeodesicTriangulation& g, const EdgePaths& paths, int threads, TraceResult& result);

}  // namespace geotri::detail

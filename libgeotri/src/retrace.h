#pragma once
// Retracing the edges of one coarse vertex: what collapse and relocation do after they change the vertex's fan.

#include <geotri/geodesic_triangulation.h>

#include <string>
#include <vector>

namespace geotri {

namespace geodesic {
class ExactGeodesic;
}

/// Makes the edges from coarse vertex v to each of `to` the shortest geodesics from v's location, with one
/// propagation (`propagation` when given, else one of its own). Returns why one could not be found (then some
/// edges may be retraced and others not), or empty.
std::string retrace_edges(GeodesicTriangulation& g, OpenMesh::VertexHandle v, const std::vector<OpenMesh::VertexHandle>& to,
                   geodesic::ExactGeodesic* propagation);

}  // namespace geotri

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
/// propagation (`propagation` when given, else one of its own), and with `check_validity` validates all of G
/// afterwards. Returns why a geodesic could not be found or G is not valid (then G is partly changed: the caller
/// restores it), or empty. What collapse and relocation do after they change v's fan.
std::string retrace_edges(GeodesicTriangulation& g, OpenMesh::VertexHandle v,
                          const std::vector<OpenMesh::VertexHandle>& to, geodesic::ExactGeodesic* propagation,
                          bool check_validity);

}  // namespace geotri

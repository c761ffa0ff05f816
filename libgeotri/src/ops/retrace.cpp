#include "ops/retrace.h"

#include <geodesic/exact_geodesic.h>
#include <geotri/validate.h>

#include <memory>
#include <string>

namespace geotri {

std::string retrace_edges(GeodesicTriangulation& g, OpenMesh::VertexHandle v,
                          const std::vector<OpenMesh::VertexHandle>& to, geodesic::ExactGeodesic* propagation,
                          bool check_validity) {
    std::unique_ptr<geodesic::ExactGeodesic> own;
    if (!propagation) {
        own = std::make_unique<geodesic::ExactGeodesic>(g.fine().mesh);
        propagation = own.get();
    }
    geodesic::PropagationOptions options;
    for (OpenMesh::VertexHandle u : to) options.stop_points.push_back(g.location(u));
    options.goal_directed = true;
    propagation->propagate({g.location(v)}, options);
    for (OpenMesh::VertexHandle u : to) {
        Polyline path = propagation->shortest_path(g.location(u));
        if (path.size() < 2)
            return "no geodesic from coarse vertex " + std::to_string(v.idx()) + " to " + std::to_string(u.idx());
        g.set_path(g.coarse().find_halfedge(v, u), std::move(path));
    }
    if (!check_validity) return {};
    const ValidationReport report = validate(g);
    return report.valid ? std::string() : "the result is not valid (" + report.violations.front().what + ")";
}

}  // namespace geotri

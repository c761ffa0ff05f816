#include "ops/spokes.h"

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/tangent_angles.h>

#include "core/patch_region.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace geotri::detail {

using geodesic::Mesh;
using OpenMesh::VertexHandle;

namespace {

double cone_of(const GeodesicTriangulation& g, VertexHandle v) { return cone_angle(g.fine().mesh, g.location(v)); }

/// Empty when `path` is acceptable for `spoke` from a new vertex at a point of cone angle `theta`, else why not.
std::string check_spoke(const GeodesicTriangulation& g, const Spoke& spoke, const Polyline& path, double theta) {
    const Mesh& mesh = g.fine().mesh;
    const std::string name = "the geodesic to coarse vertex " + std::to_string(spoke.to.idx());
    const std::size_t n = path.size();
    if (n < 2) return name + " is empty";
    // A path from a point within rounding of a fine edge can step from the point's face straight into the face
    // beyond that edge: two points that share no face, no polyline of T. The spoke is refused, as any other that
    // is not a geodesic of T.
    std::string bend;
    try {
        bend = straightness_defect(mesh, path);
    } catch (const InvalidInput& e) {
        return name + " is not a polyline of T (" + e.what() + ")";
    }
    if (!bend.empty()) return name + " " + bend;
    if (spoke.has_wedge &&
        !split_corner(spoke.wedge_from, polar_angle(mesh, path[0], path[1]), spoke.wedge_to, theta).ok)
        return name + " does not leave the new vertex inside the patch";
    if (!split_corner(start_direction(g, spoke.corner_from), polar_angle(mesh, path[n - 1], path[n - 2]),
                      start_direction(g, spoke.corner_to), cone_of(g, spoke.to))
             .ok)
        return name + " does not reach it inside the corner of the patch";
    const std::string meeting = first_meeting(mesh, path, spoke.around);
    return meeting.empty() ? meeting : name + ": " + meeting;
}

}  // namespace

std::string find_spokes(const GeodesicTriangulation& g, const SurfacePoint& from, std::vector<Spoke>& spokes,
                        const SplitOptions& options, const Workspace& workspace, bool checked) {
    if (workspace.propagated && !workspace.propagation)
        throw InvalidInput("split: Workspace::propagated without a propagation");
    const Mesh& mesh = g.fine().mesh;
    const double theta = cone_angle(mesh, from);
    std::unique_ptr<geodesic::ExactGeodesic> own;
    geodesic::ExactGeodesic* propagation = workspace.propagation;
    if (!propagation) {
        own = std::make_unique<geodesic::ExactGeodesic>(mesh);
        propagation = own.get();
    }
    if (!workspace.propagated) {
        geodesic::PropagationOptions propagation_options;
        for (const Spoke& s : spokes) propagation_options.stop_points.push_back(g.location(s.to));
        propagation_options.goal_directed = true;
        propagation->propagate({from}, propagation_options);
    }

    for (Spoke& s : spokes) {
        s.path = propagation->shortest_path(g.location(s.to));
        if (!checked) {
            if (s.path.size() < 2) return "no geodesic to coarse vertex " + std::to_string(s.to.idx());
            continue;
        }
        std::string why = check_spoke(g, s, s.path, theta);
        if (why.empty()) continue;
        if (!options.region_fallback) return why;
        PatchRegion::Path inside;
        try {
            const PatchRegion region = workspace.overlay ? PatchRegion(g, *workspace.overlay, {s.patch})
                                                       : PatchRegion(g, {s.patch});
            inside = region.shortest_path(from, g.location(s.to));
        } catch (const InvalidInput& e) {
            return why + "; inside the patch: " + e.what();
        }
        if (inside.polyline.empty()) return why + "; inside the patch: " + inside.failure;
        const std::string why_inside = check_spoke(g, s, inside.polyline, theta);
        if (!why_inside.empty()) return why + "; inside the patch: " + why_inside;
        s.path = std::move(inside.polyline);
        s.in_region = true;
    }
    return {};
}


std::string spokes_apart(const Mesh& mesh, const SurfacePoint& from, const std::vector<Spoke>& spokes) {
    const double theta = cone_angle(mesh, from);
    const std::size_t n = spokes.size();
    std::vector<double> out(n);
    for (std::size_t k = 0; k < n; ++k) out[k] = polar_angle(mesh, spokes[k].path[0], spokes[k].path[1]);
    double turn = 0.0, smallest = theta;
    for (std::size_t k = 0; k < n; ++k) {
        const double angle = ccw_angle(out[k], out[(k + 1) % n], theta);
        turn += angle;
        smallest = std::min(smallest, angle);
    }
    if (!(smallest > k_min_new_corner) || std::abs(turn - theta) > 1e-9 * theta)
        return "the new geodesics do not leave the new vertex in the order of the corners around it";
    for (std::size_t k = 0; k < n; ++k)
        for (std::size_t j = k + 1; j < n; ++j) {
            const std::string meeting = first_meeting(mesh, spokes[k].path, {{spokes[j].path, 0, "a new geodesic"}});
            if (!meeting.empty()) return "two new geodesics meet: " + meeting;
        }
    return {};
}

}  // namespace geotri::detail

#include "core/patch_location.h"

#include <geodesic/errors.h>
#include <geotri/straight_geodesic.h>
#include <geotri/tangent_angles.h>

#include "core/plane_segments.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <unordered_map>

namespace geotri::detail {

using geodesic::Mesh;
using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;

namespace {

// Rays tried, evenly spread around p, before giving up; turned by this fraction of their spacing from p's reference
// direction, so that none runs along a fine edge through p on a regular mesh (an edge point's rays at 0 and π
// would: along its edge).
constexpr int k_rays = 3;
constexpr double k_ray_turn = 0.6180339887498949;
// × the longest edge of a fine face: a ray that passes this close to an end of a polyline's segment gives no clear
// answer, nor one that starts this close to a segment; one that ends this close to a segment (where it crosses a
// fine edge that a polyline runs along) crosses it there.
constexpr double k_clearance = 1e-9;

/// A segment of a coarse edge's polyline, oriented along the edge's first halfedge.
struct Segment {
    SurfacePoint from, to;
    EdgeHandle edge;
};
using SegmentsByFace = std::unordered_map<int, std::vector<Segment>>;

/// What a ray (a straight polyline of T from p) meets first among the segments.
struct Crossing {
    enum Kind { none, crossed, unclear, starts_on_polyline } kind = none;
    /// When crossed: the halfedge of the crossed edge whose left side the ray leaves.
    HalfedgeHandle leaves = HalfedgeHandle();
};

Crossing first_crossing(const GeodesicTriangulation& g, const Polyline& ray, const SegmentsByFace& segments) {
    const Mesh& mesh = g.fine().mesh;
    for (std::size_t i = 0; i + 1 < ray.size(); ++i) {
        if (on_common_edge(mesh, ray[i], ray[i + 1])) return Crossing{Crossing::unclear};
        const int face = common_face(mesh, ray[i], ray[i + 1]);
        if (face < 0) return Crossing{Crossing::unclear};
        const auto found = segments.find(face);
        if (found == segments.end()) continue;
        const double tolerance =
            k_clearance * std::max({mesh.length(3 * face), mesh.length(3 * face + 1), mesh.length(3 * face + 2)});
        const Eigen::Vector2d r0 = halfedge_coordinates(mesh, 3 * face, ray[i]);
        const Eigen::Vector2d r1 = halfedge_coordinates(mesh, 3 * face, ray[i + 1]);
        const Eigen::Vector2d r = r1 - r0;
        double first = std::numeric_limits<double>::infinity();
        Crossing crossing;
        for (const Segment& s : found->second) {
            const Eigen::Vector2d q0 = halfedge_coordinates(mesh, 3 * face, s.from);
            const Eigen::Vector2d q1 = halfedge_coordinates(mesh, 3 * face, s.to);
            if (point_segment_distance(q0, r0, r1) < tolerance || point_segment_distance(q1, r0, r1) < tolerance)
                return Crossing{Crossing::unclear};
            const Eigen::Vector2d q = q1 - q0;
            double along;
            if (point_segment_distance(r0, q0, q1) < tolerance) {
                if (i == 0) return Crossing{Crossing::starts_on_polyline};  // within rounding
                along = 0.0;  // where a polyline along a fine edge is crossed
            } else if (point_segment_distance(r1, q0, q1) < tolerance) {
                along = 1.0;
            } else {
                if ((cross(r, q0 - r0) > 0.0) == (cross(r, q1 - r0) > 0.0)) continue;  // both ends on one side
                along = cross(q0 - r0, q) / cross(r, q);
                if (along < 0.0 || along > 1.0) continue;
            }
            if (std::abs(cross(q, r)) <= k_clearance * q.norm() * r.norm()) return Crossing{Crossing::unclear};
            if (along >= first) continue;
            first = along;
            // A ray that crosses q to its right leaves the left side of the edge's first halfedge.
            crossing = {Crossing::crossed, g.coarse().halfedge_handle(s.edge, cross(q, r) < 0.0 ? 0 : 1)};
        }
        if (crossing.kind == Crossing::crossed) return crossing;
    }
    return Crossing{};
}

}  // namespace

std::optional<FaceHandle> patch_holding(const GeodesicTriangulation& g, const std::vector<FaceHandle>& faces,
                                        const SurfacePoint& p) {
    const Mesh& mesh = g.fine().mesh;
    const CoarseMesh& coarse = g.coarse();
    const SurfacePoint point = mesh.canonical(p);

    // The polylines' segments, under each fine face that holds them (both faces of a segment along a fine edge).
    std::vector<EdgeHandle> edges;
    for (FaceHandle f : faces)
        for (EdgeHandle e : coarse.fe_range(f)) edges.push_back(e);
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    SegmentsByFace segments;
    double perimeter = 0.0;
    for (EdgeHandle e : edges) {
        perimeter += g.length(e);
        const Polyline& path = g.polyline(e);
        for (std::size_t i = 0; i + 1 < path.size(); ++i) {
            // On a polyline, p is strictly inside no patch that the polyline does not cross.
            if (path[i] == point || path[i + 1] == point) return FaceHandle();
            if (on_common_edge(mesh, path[i], path[i + 1])) {
                const auto [u, v] = common_edge(path[i], path[i + 1]);
                for (int h : {mesh.find_halfedge(u, v), mesh.find_halfedge(v, u)})
                    if (h >= 0) segments[Mesh::face_of(h)].push_back({path[i], path[i + 1], e});
            } else {
                const int face = common_face(mesh, path[i], path[i + 1]);
                if (face < 0) return std::nullopt;
                segments[face].push_back({path[i], path[i + 1], e});
            }
        }
    }

    const double theta = cone_angle(mesh, point);
    bool walked_on = true;  // every ray walked the whole perimeter without meeting a polyline
    for (int k = 0; k < k_rays; ++k) {
        StraightGeodesicResult ray;
        try {
            ray = trace_straight_geodesic(mesh, point, (k + k_ray_turn) * theta / k_rays, perimeter);
        } catch (const Error&) {
            return std::nullopt;
        }
        const Crossing crossing = first_crossing(g, ray.path, segments);
        switch (crossing.kind) {
            case Crossing::starts_on_polyline: return std::nullopt;  // so does every ray
            case Crossing::unclear: walked_on = false; continue;
            case Crossing::none:
                walked_on = walked_on && !ray.stopped_at_vertex && !ray.stopped_at_boundary;
                continue;
            case Crossing::crossed: break;
        }
        // p lies in the patch that the ray leaves: one of `faces`, or else none of them.
        const FaceHandle holder = coarse.face_handle(crossing.leaves);
        return std::find(faces.begin(), faces.end(), holder) != faces.end() ? holder : FaceHandle();
    }
    // A patch that held p would hold three straight geodesics from it longer than all the patches' perimeter: only
    // one shaped like a balloon can (on lucy_100k, such points were curved vertices within a circumcircle but on
    // another part of the body, whose tries each cost a propagation across it).
    if (walked_on) return FaceHandle();
    return std::nullopt;
}

}  // namespace geotri::detail

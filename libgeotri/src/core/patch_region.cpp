#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/tangent_angles.h>

#include "core/patch_overlay.h"
#include "core/patch_region.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <limits>

namespace geotri {

using geodesic::Mesh;
using geodesic::PointKind;

namespace {

// How far outside an overlay triangle (in its barycentric coordinates) a point may lie and still be in it: the
// overlay's cut points are rounded, so a point on a polyline may fall a hair outside the triangles on either side.
constexpr double k_inside_tolerance = 1e-9;

}  // namespace

bool same_point(const Mesh& mesh, const SurfacePoint& p, const SurfacePoint& q) {
    return mesh.canonical(p) == mesh.canonical(q);
}

PatchRegion::PatchRegion(const GeodesicTriangulation& g, const Overlay& overlay, const std::vector<int>& coarse_faces) {
    cut_out(g, overlay, coarse_faces);
}

PatchRegion::PatchRegion(const GeodesicTriangulation& g, const std::vector<int>& coarse_faces)
    : own_overlay_(std::make_shared<const Overlay>(detail::build_patch_overlay(g, coarse_faces))) {
    cut_out(g, *own_overlay_, coarse_faces);
}

void PatchRegion::cut_out(const GeodesicTriangulation& g, const Overlay& overlay,
                          const std::vector<int>& coarse_faces) {
    fine_ = &g.fine().mesh;
    overlay_ = &overlay;
    for (int f : coarse_faces)
        if (std::binary_search(overlay.bad_patches.begin(), overlay.bad_patches.end(), f))
            throw InvalidInput("the patch of coarse face " + std::to_string(f) + " is not a disk");
    std::vector<int> region_vertex(overlay.positions.size(), -1);
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::array<int, 3>> triangles;
    for (std::size_t t = 0; t < overlay.triangles.size(); ++t) {
        if (std::find(coarse_faces.begin(), coarse_faces.end(), overlay.patch[t]) == coarse_faces.end()) continue;
        std::array<int, 3> tri{};
        for (std::size_t i = 0; i < 3; ++i) {
            const auto v = static_cast<std::size_t>(overlay.triangles[t][i]);
            if (region_vertex[v] < 0) {
                region_vertex[v] = static_cast<int>(positions.size());
                positions.push_back(overlay.positions[v]);
                overlay_vertex_.push_back(static_cast<int>(v));
            }
            tri[i] = region_vertex[v];
        }
        triangles.push_back(tri);
        fine_face_.push_back(overlay.fine_face[t]);
    }
    if (triangles.empty()) throw InvalidInput("the region has no triangles");
    mesh_.emplace(std::move(positions), std::move(triangles));
}

std::optional<SurfacePoint> PatchRegion::to_region(const SurfacePoint& p) const {
    const SurfacePoint point = fine_->canonical(p);
    for (std::size_t v = 0; v < overlay_vertex_.size(); ++v)
        if (overlay_->points[static_cast<std::size_t>(overlay_vertex_[v])] == point)
            return SurfacePoint::at_vertex(static_cast<int>(v));
    if (point.kind == PointKind::vertex) return std::nullopt;  // a vertex of T in the region is a region vertex

    // The region face that holds the point best: largest smallest barycentric coordinate.
    const std::vector<int> faces = faces_holding(*fine_, point);
    int best = -1;
    Eigen::Vector3d best_lambda;
    double best_min = -std::numeric_limits<double>::infinity();
    for (std::size_t r = 0; r < fine_face_.size(); ++r) {
        const int f = fine_face_[r];
        if (std::find(faces.begin(), faces.end(), f) == faces.end()) continue;
        Eigen::Matrix3d corners;
        for (int i = 0; i < 3; ++i) {
            const int v = overlay_vertex_[static_cast<std::size_t>(mesh_->triangle(static_cast<int>(r))[i])];
            const std::array<double, 3> b = barycentric_in(*fine_, f, overlay_->points[static_cast<std::size_t>(v)]);
            corners.col(i) = Eigen::Vector3d(b[0], b[1], b[2]);
        }
        const std::array<double, 3> b = barycentric_in(*fine_, f, point);
        const Eigen::FullPivLU<Eigen::Matrix3d> lu(corners);
        if (!lu.isInvertible()) continue;  // a zero-area overlay triangle
        const Eigen::Vector3d lambda = lu.solve(Eigen::Vector3d(b[0], b[1], b[2]));
        if (lambda.minCoeff() > best_min) {
            best_min = lambda.minCoeff();
            best = static_cast<int>(r);
            best_lambda = lambda;
        }
    }
    if (best < 0 || best_min < -k_inside_tolerance) return std::nullopt;
    best_lambda = best_lambda.cwiseMax(0.0);
    best_lambda /= best_lambda.sum();
    return mesh_->canonical(SurfacePoint::in_face(best, {best_lambda[0], best_lambda[1], best_lambda[2]}));
}

SurfacePoint PatchRegion::to_fine(const SurfacePoint& q) const {
    auto fine_point = [&](int region_vertex) {
        return overlay_->points[static_cast<std::size_t>(overlay_vertex_[static_cast<std::size_t>(region_vertex)])];
    };
    int face = -1;
    std::array<int, 3> vertices{};
    std::array<double, 3> weights{};
    switch (q.kind) {
    case PointKind::vertex: return fine_point(q.vertex);
    case PointKind::edge: {
        int h = mesh_->find_halfedge(q.edge_v0, q.edge_v1);
        if (h < 0) h = mesh_->find_halfedge(q.edge_v1, q.edge_v0);
        face = Mesh::face_of(h);
        vertices = {q.edge_v0, q.edge_v1, q.edge_v1};
        weights = {1.0 - q.t, q.t, 0.0};
        break;
    }
    case PointKind::face:
        face = q.face;
        vertices = mesh_->triangle(q.face);
        weights = q.bary;
        break;
    }
    const int f = fine_face_[static_cast<std::size_t>(face)];
    std::array<double, 3> b{0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < 3; ++i) {
        if (weights[i] == 0.0) continue;
        const std::array<double, 3> corner = barycentric_in(*fine_, f, fine_point(vertices[i]));
        for (std::size_t k = 0; k < 3; ++k) b[k] += weights[i] * corner[k];
    }
    return fine_->canonical(SurfacePoint::in_face(f, b));
}

PatchRegion::Path PatchRegion::shortest_path(const SurfacePoint& from, const SurfacePoint& to) const {
    return shortest_paths(from, {to}).front();
}

std::vector<PatchRegion::Path> PatchRegion::shortest_paths(const SurfacePoint& from,
                                                           const std::vector<SurfacePoint>& to) const {
    std::vector<Path> results(to.size());
    const std::optional<SurfacePoint> start = to_region(from);
    std::vector<std::optional<SurfacePoint>> ends;
    geodesic::PropagationOptions options;
    for (std::size_t i = 0; i < to.size(); ++i) {
        ends.push_back(start ? to_region(to[i]) : std::nullopt);
        if (ends.back()) options.stop_points.push_back(*ends.back());
        else results[i].failure = "an end of the path is not in the region";
    }
    if (options.stop_points.empty()) return results;
    options.goal_directed = true;
    geodesic::ExactGeodesic propagation(*mesh_);
    propagation.propagate({*start}, options);
    for (std::size_t i = 0; i < to.size(); ++i)
        if (ends[i]) results[i] = path_back(propagation, from, *ends[i], to[i]);
    return results;
}

PatchRegion::Path PatchRegion::path_back(const geodesic::ExactGeodesic& propagation, const SurfacePoint& from,
                                         const SurfacePoint& end, const SurfacePoint& to) const {
    Path result;
    const Polyline inside = propagation.shortest_path(end);
    if (inside.size() < 2) {
        result.failure = "there is no path inside the region";
        return result;
    }
    Polyline path{fine_->canonical(from)};
    for (std::size_t i = 1; i + 1 < inside.size(); ++i) {
        const SurfacePoint& q = inside[i];
        const bool on_boundary =
            q.kind == PointKind::vertex
                ? mesh_->is_boundary_vertex(q.vertex)
                : q.kind == PointKind::edge && (mesh_->find_halfedge(q.edge_v0, q.edge_v1) < 0 ||
                                                mesh_->find_halfedge(q.edge_v1, q.edge_v0) < 0);
        if (on_boundary) {
            result.failure = "the shortest path inside the region touches its boundary";
            result.touches_boundary = true;
            return result;
        }
        const SurfacePoint p = to_fine(q);
        // A point inside a fine face lies on an overlay edge that is not a fine edge: the path is straight through
        // it, and a polyline keeps only the points where it enters or leaves fine faces.
        if (p.kind == PointKind::face || p == path.back()) continue;
        path.push_back(p);
    }
    const SurfacePoint last = fine_->canonical(to);
    if (path.back() == last) {
        result.failure = "the path has fewer than two points";
        return result;
    }
    path.push_back(last);
    result.polyline = std::move(path);
    return result;
}

}  // namespace geotri

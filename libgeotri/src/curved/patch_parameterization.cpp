#include "curved/patch_parameterization.h"

#include "core/plane_segments.h"

#include <geodesic/errors.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>

namespace geotri::detail {

namespace {

using geodesic::PointKind;

/// Barycentric coordinates of overlay point p in fine face `face`, which holds it (on its closure).
std::array<double, 3> in_face(const geodesic::Mesh& mesh, const SurfacePoint& p, int face) {
    const std::array<int, 3>& corners = mesh.triangle(face);
    std::array<double, 3> bary{0.0, 0.0, 0.0};
    auto slot = [&](int vertex) {
        for (std::size_t k = 0; k < 3; ++k)
            if (corners[k] == vertex) return k;
        throw InvalidInput("curved elements: an overlay point is not on the fine face of its triangle");
    };
    switch (p.kind) {
        case PointKind::vertex:
            bary[slot(p.vertex)] = 1.0;
            break;
        case PointKind::edge:
            bary[slot(p.edge_v0)] = 1.0 - p.t;
            bary[slot(p.edge_v1)] = p.t;
            break;
        case PointKind::face:
            if (p.face != face)
                throw InvalidInput("curved elements: an overlay point is not on the fine face of its triangle");
            bary = p.bary;
            break;
    }
    return bary;
}

/// tan(angle / 2) of the angle between e1 and e2, without forming the angle: |e1 × e2| / (|e1||e2| + e1 · e2).
double tan_half_angle(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
    return e1.cross(e2).norm() / (e1.norm() * e2.norm() + e1.dot(e2));
}

}  // namespace

std::vector<std::vector<int>> triangles_by_patch(const Overlay& overlay, std::size_t faces) {
    std::vector<std::vector<int>> by_patch(faces);
    for (std::size_t t = 0; t < overlay.triangles.size(); ++t) {
        const int patch = overlay.patch[t];
        if (patch >= 0 && static_cast<std::size_t>(patch) < faces)
            by_patch[static_cast<std::size_t>(patch)].push_back(static_cast<int>(t));
    }
    return by_patch;
}

PatchParameterization::PatchParameterization(const GeodesicTriangulation& g, const Overlay& overlay,
                                             OpenMesh::FaceHandle f, const std::vector<int>& patch_triangles)
    : fine_(&g.fine().mesh), overlay_(&overlay) {
    const CoarseMesh& coarse = g.coarse();
    const int face = f.idx();
    const std::string name = "coarse face " + std::to_string(face);
    if (std::binary_search(overlay.bad_patches.begin(), overlay.bad_patches.end(), face))
        throw InvalidInput(name + ": its patch is not a disk bounded by its three polylines");

    // The patch's overlay triangles, with their vertices numbered locally in order of first use.
    if (patch_triangles.empty()) throw InvalidInput(name + ": its patch holds no overlay triangle");
    std::unordered_map<int, int> local;
    std::vector<int> vertex_of;  // per local vertex: its overlay vertex
    for (int t : patch_triangles)
        for (int v : overlay.triangles[static_cast<std::size_t>(t)])
            if (local.emplace(v, static_cast<int>(vertex_of.size())).second) vertex_of.push_back(v);
    const std::size_t n = vertex_of.size();
    auto position = [&](int l) -> const Eigen::Vector3d& { return overlay.positions[static_cast<std::size_t>(vertex_of[static_cast<std::size_t>(l)])]; };

    // The boundary: the directed edges whose reverse no triangle of the patch has, one loop with the patch on its
    // left, which leaves each of its vertices once.
    std::map<std::pair<int, int>, int> directed;
    for (int t : patch_triangles) {
        const auto& tri = overlay.triangles[static_cast<std::size_t>(t)];
        for (int k = 0; k < 3; ++k) ++directed[{local.at(tri[k]), local.at(tri[(k + 1) % 3])}];
    }
    std::vector<int> boundary_next(n, -1);
    for (const auto& [edge, count] : directed) {
        if (count != 1) throw InvalidInput(name + ": its patch uses an overlay edge twice in one direction");
        if (directed.count({edge.second, edge.first})) continue;
        if (boundary_next[static_cast<std::size_t>(edge.first)] != -1)
            throw InvalidInput(name + ": its patch's boundary touches itself");
        boundary_next[static_cast<std::size_t>(edge.first)] = edge.second;
    }

    // The corners, on the boundary at the locations of the face's vertices, and the three sides between them.
    std::array<int, 3> corner{-1, -1, -1};
    {
        int k = 0;
        for (OpenMesh::HalfedgeHandle h : coarse.fh_range(f)) {
            const SurfacePoint& at = g.location(coarse.from_vertex_handle(h));
            for (std::size_t l = 0; l < n; ++l)
                if (boundary_next[l] != -1 && overlay.points[static_cast<std::size_t>(vertex_of[l])] == at)
                    corner[static_cast<std::size_t>(k)] = static_cast<int>(l);
            if (corner[static_cast<std::size_t>(k)] == -1)
                throw InvalidInput(name + ": corner " + std::to_string(k) + " is not on its patch's boundary");
            ++k;
        }
    }
    std::vector<Eigen::Vector2d> reference(n, Eigen::Vector2d::Zero());
    std::vector<char> on_boundary(n, 0);
    const std::array<Eigen::Vector2d, 3> reference_corner{Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 0.0),
                                                          Eigen::Vector2d(0.0, 1.0)};
    std::size_t walked = 0;
    for (std::size_t side = 0; side < 3; ++side) {
        const int from = corner[side], to = corner[(side + 1) % 3];
        std::vector<int> run{from};
        std::vector<double> length{0.0};
        while (run.back() != to) {
            const int next = boundary_next[static_cast<std::size_t>(run.back())];
            if (next == -1 || next == corner[(side + 2) % 3] || run.size() > n)
                throw InvalidInput(name + ": its patch's boundary does not run through its corners in order");
            length.push_back(length.back() + (position(next) - position(run.back())).norm());
            run.push_back(next);
        }
        walked += run.size() - 1;
        if (!(length.back() > 0.0)) throw InvalidInput(name + ": side " + std::to_string(side) + " has no length");
        for (std::size_t i = 0; i < run.size(); ++i) {
            const double s = i + 1 == run.size() ? 1.0 : length[i] / length.back();
            const auto l = static_cast<std::size_t>(run[i]);
            reference[l] = (1.0 - s) * reference_corner[side] + s * reference_corner[(side + 1) % 3];
            on_boundary[l] = 1;
        }
    }
    std::size_t boundary_count = 0;
    for (int next : boundary_next) boundary_count += next != -1;
    if (walked != boundary_count) throw InvalidInput(name + ": its patch's boundary is more than one loop");

    // Mean-value weights: w_ij = (tan(a/2) + tan(b/2)) / |x_j - x_i|, with a and b the angles at i of the two
    // triangles at edge ij. They are positive but where a triangle is degenerate (a zero edge, a straight angle);
    // there the edge gets the mean of its vertex's other weights (any positive weight keeps the map one-to-one).
    std::vector<int> unknown(n, -1);
    int unknowns = 0;
    for (std::size_t l = 0; l < n; ++l)
        if (!on_boundary[l]) unknown[l] = unknowns++;
    std::vector<std::map<int, double>> weights(n);
    for (int t : patch_triangles) {
        const auto& tri = overlay.triangles[static_cast<std::size_t>(t)];
        for (int k = 0; k < 3; ++k) {
            const int i = local.at(tri[k]), j = local.at(tri[(k + 1) % 3]), m = local.at(tri[(k + 2) % 3]);
            if (on_boundary[static_cast<std::size_t>(i)]) continue;
            const Eigen::Vector3d ej = position(j) - position(i), em = position(m) - position(i);
            const double half = tan_half_angle(ej, em);
            weights[static_cast<std::size_t>(i)][j] += half / ej.norm();
            weights[static_cast<std::size_t>(i)][m] += half / em.norm();
        }
    }
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(unknowns, 2);
    for (std::size_t i = 0; i < n; ++i) {
        if (on_boundary[i]) continue;
        double sum = 0.0;
        int good = 0;
        for (const auto& [j, w] : weights[i])
            if (std::isfinite(w) && w > 0.0) {
                sum += w;
                ++good;
            }
        const double fallback = good > 0 ? sum / good : 1.0;
        double diagonal = 0.0;
        for (const auto& [j, raw] : weights[i]) {
            const double w = std::isfinite(raw) && raw > 0.0 ? raw : fallback;
            diagonal += w;
            const auto jj = static_cast<std::size_t>(j);
            if (on_boundary[jj]) {
                rhs.row(unknown[i]) += w * reference[jj].transpose();
            } else {
                entries.emplace_back(unknown[i], unknown[jj], -w);
            }
        }
        entries.emplace_back(unknown[i], unknown[i], diagonal);
    }
    if (unknowns > 0) {
        Eigen::SparseMatrix<double> system(unknowns, unknowns);
        system.setFromTriplets(entries.begin(), entries.end());
        Eigen::SparseLU<Eigen::SparseMatrix<double>> solver;
        solver.compute(system);
        if (solver.info() != Eigen::Success)
            throw NumericalError(name + ": the linear system of its patch's map cannot be factorised");
        const Eigen::MatrixXd solution = solver.solve(rhs);
        if (solver.info() != Eigen::Success || !solution.allFinite())
            throw NumericalError(name + ": the linear system of its patch's map cannot be solved");
        for (std::size_t l = 0; l < n; ++l)
            if (unknown[l] >= 0) reference[l] = solution.row(unknown[l]).transpose();
    }

    triangles_.reserve(patch_triangles.size());
    for (int t : patch_triangles) {
        Triangle triangle;
        const auto& tri = overlay.triangles[static_cast<std::size_t>(t)];
        for (std::size_t k = 0; k < 3; ++k) {
            const auto l = static_cast<std::size_t>(local.at(tri[k]));
            triangle.vertices[k] = tri[k];
            triangle.reference[k] = reference[l];
            triangle.positions[k] = position(static_cast<int>(l));
        }
        triangle.fine_face = overlay.fine_face[static_cast<std::size_t>(t)];
        triangles_.push_back(triangle);
    }
}

std::optional<PatchParameterization::Preimage> PatchParameterization::preimage(const Eigen::Vector2d& xi) const {
    // The triangle that holds xi most inside it; degenerate ones (all three points on one side) hold nothing.
    const Triangle* best = nullptr;
    std::array<double, 3> best_bary{};
    double best_margin = -std::numeric_limits<double>::infinity();
    for (const Triangle& triangle : triangles_) {
        const auto& r = triangle.reference;
        const double area = cross(r[1] - r[0], r[2] - r[0]);
        if (!(area > 0.0)) continue;
        const std::array<double, 3> bary{cross(r[1] - xi, r[2] - xi) / area, cross(r[2] - xi, r[0] - xi) / area,
                                         cross(r[0] - xi, r[1] - xi) / area};
        const double margin = std::min({bary[0], bary[1], bary[2]});
        if (margin > best_margin) {
            best_margin = margin;
            best = &triangle;
            best_bary = bary;
        }
    }
    if (!best || best_margin < -1e-9) return std::nullopt;
    double sum = 0.0;
    for (double& b : best_bary) sum += (b = std::max(b, 0.0));
    for (double& b : best_bary) b /= sum;

    std::array<double, 3> bary{0.0, 0.0, 0.0};
    for (std::size_t k = 0; k < 3; ++k) {
        const std::array<double, 3> corner = in_face(
            *fine_, overlay_->points[static_cast<std::size_t>(best->vertices[k])], best->fine_face);
        for (std::size_t c = 0; c < 3; ++c) bary[c] += best_bary[k] * corner[c];
    }
    const SurfacePoint point = fine_->canonical(SurfacePoint::in_face(best->fine_face, bary));
    return Preimage{point, fine_->point(point)};
}

}  // namespace geotri::detail

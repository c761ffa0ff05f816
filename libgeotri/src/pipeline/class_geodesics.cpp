#include "pipeline/class_geodesics.h"

#include <geodesic/errors.h>
#include <geodesic/straighten_path.h>
#include <geotri/validate.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>

namespace geotri::detail {

namespace {

// Lengths closer than this (relative) are the same geodesic found twice.
constexpr double k_same_length = 1e-9;

int violations(const ValidationReport& report) {
    return std::accumulate(report.violation_count.begin(), report.violation_count.end(), 0);
}

// Whether two polylines are the same geodesic: lengths that differ are not, and neither are two routes of one
// length (around a symmetric part): their points must agree too, to the tolerance of two propagations.
bool same_geodesic(const geodesic::Mesh& mesh, const Polyline& p, double p_length, const Polyline& q, double q_length) {
    if (std::abs(p_length - q_length) > k_same_length * q_length || p.size() != q.size()) return false;
    const double tolerance = 1e-9 * mesh.size();
    for (std::size_t i = 0; i < p.size(); ++i)
        if ((mesh.point(p[i]) - mesh.point(q[i])).norm() > tolerance) return false;
    return true;
}

// The fine vertex where coarse vertex v lies; the paths of a decimation start and end on fine vertices.
int fine_vertex_of(const GeodesicTriangulation& g, const EdgePaths& paths, OpenMesh::VertexHandle v) {
    const SurfacePoint& p = g.location(v);
    if (p.kind != geodesic::PointKind::vertex)
        throw IOError(paths.name + ": coarse vertex " + std::to_string(v.idx()) +
                      " does not lie on a vertex of the fine mesh: the edge paths were made for another coarse "
                      "mesh");
    return p.vertex;
}

}  // namespace

std::vector<std::vector<int>> reference_paths(const GeodesicTriangulation& g, const EdgePaths& paths) {
    const FineMesh& fine = g.fine();
    const CoarseMesh& coarse = g.coarse();
    const std::string& name = paths.name;
    if (paths.fine_checksum != fine.checksum || paths.fine_vertices != fine.mesh.num_vertices())
        throw IOError(name + ": the edge paths were made for another fine mesh (checksum or vertex count differ)");
    if (paths.coarse_vertices != static_cast<int>(coarse.n_vertices()) || paths.edges.size() != coarse.n_edges())
        throw IOError(name + ": the edge paths were made for another coarse mesh (" +
                      std::to_string(paths.coarse_vertices) + " vertices and " + std::to_string(paths.edges.size()) +
                      " edges, not " + std::to_string(coarse.n_vertices()) + " and " +
                      std::to_string(coarse.n_edges()) + ")");

    // The coarse vertex on each fine vertex: an edge's path may pass through no other.
    std::vector<int> coarse_on(static_cast<std::size_t>(fine.mesh.num_vertices()), -1);
    for (const auto v : coarse.vertices()) coarse_on[static_cast<std::size_t>(fine_vertex_of(g, paths, v))] = v.idx();

    // Per edge, in edge order: the path of fine vertices along its first halfedge.
    std::vector<std::vector<int>> reference(coarse.n_edges());
    for (const auto e : coarse.edges()) {
        const auto h = coarse.halfedge_handle(e, 0);
        const int from = coarse.from_vertex_handle(h).idx(), to = coarse.to_vertex_handle(h).idx();
        const DecimatedEdge key{std::min(from, to), std::max(from, to), {}};
        const auto found = std::lower_bound(
            paths.edges.begin(), paths.edges.end(), key,
            [](const DecimatedEdge& x, const DecimatedEdge& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
        if (found == paths.edges.end() || found->a != key.a || found->b != key.b)
            throw IOError(name + ": coarse edge (" + std::to_string(key.a) + ", " + std::to_string(key.b) +
                          ") has no path: the edge paths were made for another coarse mesh");
        std::vector<int> path = found->fine_path;
        if (from != key.a) std::reverse(path.begin(), path.end());
        if (path.front() != fine_vertex_of(g, paths, coarse.vertex_handle(static_cast<unsigned>(from))) ||
            path.back() != fine_vertex_of(g, paths, coarse.vertex_handle(static_cast<unsigned>(to))))
            throw IOError(name + ": the path of coarse edge (" + std::to_string(key.a) + ", " + std::to_string(key.b) +
                          ") does not join the fine vertices of its ends");
        for (std::size_t i = 1; i + 1 < path.size(); ++i)
            if (coarse_on[static_cast<std::size_t>(path[i])] >= 0)
                throw IOError(name + ": the path of coarse edge (" + std::to_string(key.a) + ", " +
                              std::to_string(key.b) + ") passes through coarse vertex " +
                              std::to_string(coarse_on[static_cast<std::size_t>(path[i])]) + " (fine vertex " +
                              std::to_string(path[i]) + ")");
        for (std::size_t i = 0; i + 1 < path.size(); ++i)
            if (fine.mesh.find_halfedge(path[i], path[i + 1]) < 0 && fine.mesh.find_halfedge(path[i + 1], path[i]) < 0)
                throw IOError(name + ": the path of coarse edge (" + std::to_string(key.a) + ", " +
                              std::to_string(key.b) + ") jumps from fine vertex " + std::to_string(path[i]) + " to " +
                              std::to_string(path[i + 1]) + ", which share no edge");
        reference[static_cast<std::size_t>(e.idx())] = std::move(path);
    }

    return reference;
}

void prefer_class_geodesics(GeodesicTriangulation& g, const std::vector<std::vector<int>>& reference,
                            const std::string& name, int threads, TraceResult& result) {
    const FineMesh& fine = g.fine();
    const CoarseMesh& coarse = g.coarse();
    std::vector<unsigned char> pinned(static_cast<std::size_t>(fine.mesh.num_vertices()), 0);
    for (const auto v : coarse.vertices()) pinned[static_cast<std::size_t>(g.location(v).vertex)] = 1;

    const long total = static_cast<long>(reference.size());
    std::vector<std::optional<Polyline>> straightened(reference.size());
    std::vector<unsigned char> blocked(reference.size(), 0);
    std::vector<std::exception_ptr> errors(reference.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (long i = 0; i < total; ++i) {
        const std::size_t e = static_cast<std::size_t>(i);
        try {
            // A class can hold several geodesics where T is positively curved, and straightening from either
            // end may find another: the shorter one does not depend on the edge's orientation.
            geodesic::StraightenResult s = geodesic::straighten_path(fine.mesh, reference[e], pinned);
            std::vector<int> backwards(reference[e].rbegin(), reference[e].rend());
            geodesic::StraightenResult r = geodesic::straighten_path(fine.mesh, backwards, pinned);
            if (r.status == geodesic::StraightenStatus::geodesic &&
                (s.status != geodesic::StraightenStatus::geodesic || r.length < s.length * (1 - 1e-12))) {
                std::reverse(r.path.begin(), r.path.end());
                s = std::move(r);
            }
            if (s.status != geodesic::StraightenStatus::geodesic) {
                blocked[e] = 1;
                continue;
            }
            const OpenMesh::EdgeHandle edge(static_cast<int>(e));
            if (!same_geodesic(fine.mesh, s.path, s.length, g.polyline(edge), g.length(edge)))
                straightened[e] = std::move(s.path);
        } catch (const NumericalError&) {  // no class geodesic found: the edge keeps its shortest one
            blocked[e] = 1;
        } catch (const InvalidInput& error) {  // a path that is not one on T
            const auto h = coarse.halfedge_handle(OpenMesh::EdgeHandle(static_cast<int>(e)), 0);
            const int from = coarse.from_vertex_handle(h).idx(), to = coarse.to_vertex_handle(h).idx();
            errors[e] = std::make_exception_ptr(IOError(name + ": the path of coarse edge (" +
                                                        std::to_string(std::min(from, to)) + ", " +
                                                        std::to_string(std::max(from, to)) + "): " + error.what()));
        } catch (...) {
            errors[e] = std::current_exception();
        }
    }
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
    for (std::size_t e = 0; e < straightened.size(); ++e) {
        result.class_geodesics_differing += straightened[e] ? 1 : 0;
        result.class_geodesics_blocked += blocked[e];
    }
    if (result.class_geodesics_differing == 0) return;

    ValidationReport shortest = validate(g);
    if (shortest.valid) {
        result.report = std::move(shortest);
        return;
    }
    GeodesicTriangulation candidate = g;
    for (const auto e : coarse.edges())
        if (auto& path = straightened[static_cast<std::size_t>(e.idx())]) candidate.set_polyline(e, std::move(*path));
    ValidationReport by_class = validate(candidate);
    if (by_class.valid || violations(by_class) < violations(shortest)) {
        g = std::move(candidate);
        result.class_geodesics_kept = true;
        result.report = std::move(by_class);
    } else {
        result.report = std::move(shortest);
    }
}

}  // namespace geotri::detail

#include "class_geodesics.h"

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

// The fine vertex where coarse vertex v lies; the paths of a decimation start and end on fine vertices.
int fine_vertex_of(const GeodesicTriangulation& g, const EdgePaths& paths, OpenMesh::VertexHandle v) {
    const SurfacePoint& p = g.location(v);
    if (p.kind != geodesic::PointKind::vertex)
        throw InvalidInput(paths.name + ": coarse vertex " + std::to_string(v.idx()) +
                           " does not lie on a vertex of the fine mesh: the edge paths were made for another coarse "
                           "mesh");
    return p.vertex;
}

}  // namespace

void prefer_class_geodesics(GeodesicTriangulation& g, const EdgePaths& paths, int threads, TraceResult& result) {
    const FineMesh& fine = g.fine();
    const CoarseMesh& coarse = g.coarse();
    const std::string& name = paths.name;
    if (paths.fine_checksum != fine.checksum || paths.fine_vertices != fine.mesh.num_vertices())
        throw IOError(name + ": the edge paths were made for another fine mesh (checksum or vertex count differ)");
    if (paths.coarse_vertices != static_cast<int>(coarse.n_vertices()) || paths.edges.size() != coarse.n_edges())
        throw IOError(name + ": the edge paths were made for another coarse mesh (" +
                           std::to_string(paths.coarse_vertices) + " vertices and " +
                           std::to_string(paths.edges.size()) + " edges, not " + std::to_string(coarse.n_vertices()) +
                           " and " + std::to_string(coarse.n_edges()) + ")");

    std::vector<unsigned char> pinned(static_cast<std::size_t>(fine.mesh.num_vertices()), 0);
    for (const auto v : coarse.vertices()) pinned[static_cast<std::size_t>(fine_vertex_of(g, paths, v))] = 1;

    // Per edge, in edge order: the path of fine vertices along its first halfedge.
    std::vector<std::vector<int>> reference(coarse.n_edges());
    for (const auto e : coarse.edges()) {
        const auto h = coarse.halfedge_handle(e, 0);
        const int from = coarse.from_vertex_handle(h).idx(), to = coarse.to_vertex_handle(h).idx();
        const DecimatedEdge key{std::min(from, to), std::max(from, to), {}};
        const auto found = std::lower_bound(paths.edges.begin(), paths.edges.end(), key,
                                            [](const DecimatedEdge& x, const DecimatedEdge& y) {
                                                return std::tie(x.a, x.b) < std::tie(y.a, y.b);
                                            });
        if (found == paths.edges.end() || found->a != key.a || found->b != key.b)
            throw IOError(name + ": coarse edge (" + std::to_string(key.a) + ", " + std::to_string(key.b) +
                               ") has no path: the edge paths were made for another coarse mesh");
        std::vector<int> path = found->fine_path;
        if (from != key.a) std::reverse(path.begin(), path.end());
        if (path.front() != fine_vertex_of(g, paths, coarse.vertex_handle(static_cast<unsigned>(from))) ||
            path.back() != fine_vertex_of(g, paths, coarse.vertex_handle(static_cast<unsigned>(to))))
            throw IOError(name + ": the path of coarse edge (" + std::to_string(key.a) + ", " +
                               std::to_string(key.b) + ") does not join the fine vertices of its ends");
        reference[static_cast<std::size_t>(e.idx())] = std::move(path);
    }

    const long total = static_cast<long>(reference.size());
    std::vector<std::optional<Polyline>> straightened(reference.size());
    std::vector<unsigned char> blocked(reference.size(), 0);
    std::vector<std::exception_ptr> errors(reference.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (long i = 0; i < total; ++i) {
        const std::size_t e = static_cast<std::size_t>(i);
        try {
            geodesic::StraightenResult s = geodesic::straighten_path(fine.mesh, reference[e], pinned);
            if (s.status != geodesic::StraightenStatus::geodesic) {
                blocked[e] = 1;
                continue;
            }
            const double shortest = g.length(OpenMesh::EdgeHandle(static_cast<int>(e)));
            if (std::abs(s.length - shortest) > k_same_length * shortest) straightened[e] = std::move(s.path);
        } catch (const InvalidInput& error) {  // a path that is not one on T
            errors[e] = std::make_exception_ptr(IOError(name + ": " + error.what()));
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

    const ValidationReport shortest = validate(g);
    if (shortest.valid) return;
    GeodesicTriangulation candidate = g;
    for (const auto e : coarse.edges())
        if (auto& path = straightened[static_cast<std::size_t>(e.idx())]) candidate.set_polyline(e, std::move(*path));
    const ValidationReport by_class = validate(candidate);
    if (by_class.valid || violations(by_class) < violations(shortest)) {
        g = std::move(candidate);
        result.class_geodesics_kept = true;
    }
}

}  // namespace geotri::detail

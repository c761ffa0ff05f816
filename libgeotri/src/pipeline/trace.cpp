// GCC 12 warns inside OpenMesh's PropertyT<Vec3d>::push_back(), whose default-constructed point is deliberately
// left uninitialised; building a coarse mesh instantiates it here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "core/coarse_components.h"
#include "core/thread_count.h"
#include "pipeline/class_geodesics.h"

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/trace.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace geotri {

namespace {

using geodesic::PointKind;
using OpenMesh::EdgeHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

// ---- Locating coarse vertices ----------------------------------------------------------------------------------

/// Exact position key: the bit patterns of the coordinates, with -0.0 folded onto 0.0 so that equal values match.
struct PositionKey {
    std::uint64_t bits[3];
    bool operator==(const PositionKey& o) const {
        return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
    }
};

struct PositionKeyHash {
    std::size_t operator()(const PositionKey& k) const {
        std::uint64_t h = 0x9e3779b97f4a7c15ull;
        for (std::uint64_t b : k.bits) h = (h ^ b) * 0x100000001b3ull + (h >> 29);
        return static_cast<std::size_t>(h);
    }
};

PositionKey key_of(const Eigen::Vector3d& p) {
    PositionKey key{};
    for (int i = 0; i < 3; ++i) {
        const double x = p[i] == 0.0 ? 0.0 : p[i];
        std::memcpy(&key.bits[i], &x, sizeof x);
    }
    return key;
}

/// The closest point of triangle (a, b, c) to p, as barycentric coordinates (Voronoi regions of the vertices,
/// edges and interior, so that the coordinates of a vertex or edge region are exact zeros).
std::array<double, 3> closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const double t = d1 / (d1 - d3);
        return {1.0 - t, t, 0.0};
    }
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const double t = d2 / (d2 - d6);
        return {1.0 - t, 0.0, t};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0.0, 1.0 - t, t};
    }
    const double denom = va + vb + vc;
    if (!(denom > 0.0)) return {std::nan(""), 0.0, 0.0};  // a degenerate face: its edges belong to its neighbours
    const double v = vb / denom, w = vc / denom;
    return {1.0 - v - w, v, w};
}

/// The closest point of T to x, brute force over the faces (ties go to the lowest face index).
geodesic::SurfacePoint closest_point(const geodesic::Mesh& fine, const Eigen::Vector3d& x) {
    double best = std::numeric_limits<double>::infinity();
    int best_face = -1;
    std::array<double, 3> best_bary{};
    for (int f = 0; f < fine.num_faces(); ++f) {
        const auto& t = fine.triangle(f);
        const Eigen::Vector3d &a = fine.position(t[0]), &b = fine.position(t[1]), &c = fine.position(t[2]);
        const std::array<double, 3> bary = closest_on_triangle(x, a, b, c);
        if (!std::isfinite(bary[0])) continue;
        const double d = (bary[0] * a + bary[1] * b + bary[2] * c - x).squaredNorm();
        if (d < best) {
            best = d;
            best_face = f;
            best_bary = bary;
        }
    }
    if (best_face < 0) throw NumericalError("no face of the fine mesh has a closest point (all faces degenerate?)");
    for (double& b : best_bary) b = std::max(b, 0.0);
    geodesic::SurfacePoint p = fine.canonical(geodesic::SurfacePoint::in_face(best_face, best_bary));
    if (p.kind == PointKind::face) {
        // Make the coordinates sum to exactly 1, so that canonical() leaves them as they are: a location then
        // survives a write and read of the .gtri file bit for bit.
        std::array<double, 3> b = p.bary;
        b[2] = 1.0 - (b[0] + b[1]);
        if (b[2] > 0.0 && b[0] + b[1] + b[2] == 1.0) p.bary = b;
    }
    return p;
}

int fine_component_of(const FineMesh& fine, const geodesic::SurfacePoint& p) {
    switch (p.kind) {
        case PointKind::vertex: return fine.component[static_cast<std::size_t>(p.vertex)];
        case PointKind::edge: return fine.component[static_cast<std::size_t>(p.edge_v0)];
        case PointKind::face: return fine.component[static_cast<std::size_t>(fine.mesh.triangle(p.face)[0])];
    }
    return -1;
}

/// Sets every coarse vertex's location; returns the move figures in `result`.
void locate_vertices(GeodesicTriangulation& g, TraceResult& result) {
    const FineMesh& fine = g.fine();
    const CoarseMesh& coarse = g.coarse();
    std::unordered_map<PositionKey, int, PositionKeyHash> fine_vertex_at;
    fine_vertex_at.reserve(static_cast<std::size_t>(fine.mesh.num_vertices()));
    for (int v = 0; v < fine.mesh.num_vertices(); ++v) fine_vertex_at.emplace(key_of(fine.mesh.position(v)), v);

    const int n = static_cast<int>(coarse.n_vertices());
    std::vector<geodesic::SurfacePoint> location(static_cast<std::size_t>(n));
    std::vector<int> moved;
    for (int v = 0; v < n; ++v) {
        const auto& q = coarse.point(VertexHandle(v));
        const auto found = fine_vertex_at.find(key_of(Eigen::Vector3d(q[0], q[1], q[2])));
        if (found != fine_vertex_at.end()) {
            location[static_cast<std::size_t>(v)] = geodesic::SurfacePoint::at_vertex(found->second);
        } else {
            moved.push_back(v);
        }
    }
    // Each search is independent and deterministic, so the order of the threads does not matter.
    std::vector<std::exception_ptr> errors(moved.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (long i = 0; i < static_cast<long>(moved.size()); ++i) {
        try {
            const auto& q = coarse.point(VertexHandle(moved[static_cast<std::size_t>(i)]));
            location[static_cast<std::size_t>(moved[static_cast<std::size_t>(i)])] =
                closest_point(fine.mesh, Eigen::Vector3d(q[0], q[1], q[2]));
        } catch (...) {
            errors[static_cast<std::size_t>(i)] = std::current_exception();
        }
    }
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);

    result.moved_vertices = static_cast<int>(moved.size());
    result.largest_location_move = 0.0;
    result.largest_move_vertex = -1;
    for (const int v : moved) {
        const auto& q = coarse.point(VertexHandle(v));
        const double move =
            (fine.mesh.point(location[static_cast<std::size_t>(v)]) - Eigen::Vector3d(q[0], q[1], q[2])).norm();
        if (result.largest_move_vertex < 0 || move > result.largest_location_move) {
            result.largest_location_move = move;
            result.largest_move_vertex = v;
        }
    }
    for (int v = 0; v < n; ++v) g.set_location(VertexHandle(v), location[static_cast<std::size_t>(v)]);
}

/// Each coarse component on one fine component, no two coarse components on the same one, no two coarse vertices
/// at the same point: otherwise some edge could not be a geodesic between distinct points. Every fine component
/// covered, each by a coarse component of its genus: flips, splits and collapses keep the coarse topology, so
/// otherwise G could never be valid.
void check_locations(const GeodesicTriangulation& g) {
    const CoarseMesh& coarse = g.coarse();
    const int n = static_cast<int>(coarse.n_vertices());
    const detail::CoarseComponents components = detail::coarse_components(coarse);
    std::map<int, int> first_vertex_of;           // coarse component -> its first vertex
    std::map<int, int> coarse_component_of_fine;  // fine component -> coarse component
    std::map<std::string, int> vertex_at;
    for (int v = 0; v < n; ++v) {
        const geodesic::SurfacePoint& p = g.location(VertexHandle(v));
        const int mine = components.of_vertex[static_cast<std::size_t>(v)];
        const int component = fine_component_of(g.fine(), p);
        const auto first = first_vertex_of.emplace(mine, v);
        const int first_component = fine_component_of(g.fine(), g.location(VertexHandle(first.first->second)));
        if (component != first_component)
            throw InvalidInput("coarse vertices " + std::to_string(first.first->second) + " and " +
                               std::to_string(v) + " belong to one coarse component but lie on different components "
                               "of the fine mesh (" + std::to_string(first_component) + " and " +
                               std::to_string(component) + ")");
        const auto owner = coarse_component_of_fine.emplace(component, mine);
        if (owner.first->second != mine)
            throw InvalidInput("coarse vertices " + std::to_string(first_vertex_of[owner.first->second]) + " and " +
                               std::to_string(v) + " belong to different coarse components but lie on the same "
                               "component of the fine mesh (" + std::to_string(component) + ")");
        const auto same = vertex_at.emplace(geodesic::to_spec(p), v);
        if (!same.second)
            throw InvalidInput("coarse vertices " + std::to_string(same.first->second) + " and " + std::to_string(v) +
                               " lie on the same point of the fine mesh (" + same.first->first + ")");
    }
    const std::vector<int>& fine_genus = g.fine().genus;
    const bool several = fine_genus.size() > 1;
    for (std::size_t c = 0; c < fine_genus.size(); ++c) {
        const auto covering = coarse_component_of_fine.find(static_cast<int>(c));
        if (covering == coarse_component_of_fine.end())
            throw InvalidInput("no coarse vertex lies on component " + std::to_string(c) + " of the fine mesh: the "
                               "coarse mesh must cover each component");
        const int genus = components.genus[static_cast<std::size_t>(covering->second)];
        if (genus != fine_genus[c])
            throw InvalidInput("the coarse mesh" +
                               (several ? " on component " + std::to_string(c) + " of the fine mesh" : "") +
                               " has genus " + std::to_string(genus) + " but the fine mesh" +
                               (several ? " there" : "") + " has genus " + std::to_string(fine_genus[c]) +
                               ": no geodesic triangulation with that connectivity can be valid");
    }
}

// ---- One propagation per edge ----------------------------------------------------------------------------------

/// An edge to trace, from the from-vertex of `halfedge`, with one goal-directed propagation.
struct EdgeToTrace {
    HalfedgeHandle halfedge;  ///< halfedge_handle(e, 0)
    double reach = 0.0;       ///< straight-line length between the located ends
};

/// Every edge on its own, traced from the from-vertex of its first halfedge. Goal-directed propagation towards one
/// stop point explores little beyond the geodesic, so one propagation per edge covers much less ground than one
/// per vertex towards all of its neighbours, which spreads all around it (vertebra: 0.94M → 0.13M windows,
/// turbineblade 37.5M → 1.6M). The longest first, so that the dynamic schedule does not end waiting on one.
std::vector<EdgeToTrace> edges_to_trace(const GeodesicTriangulation& g) {
    const CoarseMesh& coarse = g.coarse();
    const geodesic::Mesh& mesh = g.fine().mesh;
    std::vector<EdgeToTrace> edges;
    edges.reserve(coarse.n_edges());
    for (EdgeHandle e : coarse.edges()) {
        const HalfedgeHandle h = coarse.halfedge_handle(e, 0);
        const double reach =
            (mesh.point(g.location(coarse.from_vertex_handle(h))) - mesh.point(g.location(coarse.to_vertex_handle(h))))
                .norm();
        edges.push_back({h, reach});
    }
    std::stable_sort(edges.begin(), edges.end(),
                     [](const EdgeToTrace& x, const EdgeToTrace& y) { return x.reach > y.reach; });
    return edges;
}

}  // namespace

// ---- Tracing ---------------------------------------------------------------------------------------------------

TraceResult trace(GeodesicTriangulation& g, const TraceOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    TraceResult result;
    locate_vertices(g, result);
    check_locations(g);
    std::vector<std::vector<int>> reference;  // before tracing, so that paths that do not fit fail at once
    if (options.edge_paths) reference = detail::reference_paths(g, *options.edge_paths);

    const std::vector<EdgeToTrace> edges = edges_to_trace(g);
    const long total = static_cast<long>(edges.size());
    const FineMesh& fine = g.fine();

    // Results land in per-edge slots and are merged afterwards in one fixed order, so that neither the thread
    // count nor the schedule can change the output.
    std::vector<Polyline> paths(edges.size());
    std::vector<std::size_t> windows(edges.size(), 0);
    std::vector<std::exception_ptr> errors(edges.size());
    std::atomic<bool> failed{false};
    int done = 0;
    const int threads = detail::team_size(options.threads);
#pragma omp parallel num_threads(threads)
    {
        std::unique_ptr<geodesic::ExactGeodesic> geodesic;  // one per thread, reused across edges
#pragma omp for schedule(dynamic, 1)
        for (long i = 0; i < total; ++i) {
            if (failed.load(std::memory_order_relaxed)) continue;
            const std::size_t slot = static_cast<std::size_t>(i);
            try {
                if (!geodesic) geodesic = std::make_unique<geodesic::ExactGeodesic>(fine.mesh);
                const CoarseMesh& coarse = g.coarse();
                const VertexHandle from = coarse.from_vertex_handle(edges[slot].halfedge);
                const VertexHandle to = coarse.to_vertex_handle(edges[slot].halfedge);
                geodesic::PropagationOptions propagation_options;
                propagation_options.stop_points = {g.location(to)};
                propagation_options.goal_directed = true;
                geodesic->propagate({g.location(from)}, propagation_options);
                windows[slot] = geodesic->stats().windows_created;
                paths[slot] = geodesic->shortest_path(g.location(to));
                if (paths[slot].empty())
                    throw NumericalError("no geodesic found from coarse vertex " + std::to_string(from.idx()) +
                                         " to coarse vertex " + std::to_string(to.idx()));
            } catch (...) {
                errors[slot] = std::current_exception();
                failed = true;
            }
            if (options.progress) {
#pragma omp critical(geotri_trace_progress)
                {
                    ++done;
                    try {
                        if (!errors[slot]) options.progress(done, static_cast<int>(total));
                    } catch (...) {
                        errors[slot] = std::current_exception();
                        failed = true;
                    }
                }
            }
        }
    }
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);

    for (std::size_t i = 0; i < edges.size(); ++i) {
        g.set_path(edges[i].halfedge, std::move(paths[i]));
        result.longest_propagation =
            std::max(result.longest_propagation, g.length(g.coarse().edge_handle(edges[i].halfedge)));
        result.windows_created += windows[i];
    }
    result.propagations = static_cast<int>(total);
    if (options.edge_paths) detail::prefer_class_geodesics(g, reference, options.edge_paths->name, threads, result);
    for (const auto e : g.coarse().edges()) result.polyline_points += g.polyline(e).size();
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace geotri

#include <geodesic/errors.h>
#include <geotri/decimate_backoff.h>
#include <geotri/edge_paths_io.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/trace.h>
#include <geotri/validate.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>

namespace geotri {

namespace {

// A level traced, with its edges and tangles per component of T.
struct TracedLevel {
    BackoffLevel level;
    std::vector<int> edges, tangled;  // per component
};

// Traces the decimation's coarse mesh in its class and counts how its geodesics tangle, per component of T (that
// of the first vertex that a violation names). Nothing when tracing fails: then there is nothing to judge by.
std::optional<TracedLevel> trace_level(const std::shared_ptr<const FineMesh>& fine,
                                       const DecimateResult& decimation, const BackoffOptions& backoff) {
    TracedLevel traced;
    traced.level.faces = decimation.coarse.triangles.size();
    if (backoff.stage) backoff.stage("tracing the " + std::to_string(traced.level.faces) + "-face mesh");
    try {
        GeodesicTriangulation g(fine, make_coarse_mesh(decimation.coarse, fine->path + " (decimated)"));
        const EdgePaths paths = make_edge_paths(*fine, decimation);
        TraceOptions options;
        options.threads = backoff.threads;
        options.edge_paths = &paths;
        const TraceResult result = trace(g, options);
        ValidationOptions conditions_1_to_3;
        conditions_1_to_3.overlay = false;  // condition 4 is not counted: the overlay costs the most
        const ValidationReport report = result.report ? *result.report : validate(g, conditions_1_to_3);
        const CoarseMesh& coarse = g.coarse();
        // Coarse vertices are fine vertices, in the order of decimation.fine_vertex.
        auto component_of = [&](int v) {
            return fine->component[static_cast<std::size_t>(decimation.fine_vertex[static_cast<std::size_t>(v)])];
        };
        auto first_vertex_of = [&](OpenMesh::EdgeHandle e) {
            return coarse.from_vertex_handle(coarse.halfedge_handle(e, 0)).idx();
        };
        traced.edges.assign(static_cast<std::size_t>(fine->num_components), 0);
        traced.tangled.assign(static_cast<std::size_t>(fine->num_components), 0);
        for (auto e : coarse.edges()) ++traced.edges[static_cast<std::size_t>(component_of(first_vertex_of(e)))];
        for (const Violation& violation : report.violations) {
            if (violation.condition != 2 && violation.condition != 3) continue;
            int v = -1;
            if (!violation.coarse_vertices.empty()) v = violation.coarse_vertices.front();
            else if (!violation.coarse_edges.empty())
                v = first_vertex_of(OpenMesh::EdgeHandle(violation.coarse_edges.front()));
            if (v >= 0) ++traced.tangled[static_cast<std::size_t>(component_of(v))];
        }
        traced.level.edges = coarse.n_edges();
        traced.level.tangled = report.violation_count[1] + report.violation_count[2];
    } catch (const Error&) {
        return std::nullopt;
    }
    return traced;
}

}  // namespace

BackoffResult decimate_backing_off(const std::shared_ptr<const FineMesh>& fine, const DecimateOptions& options,
                                   const BackoffOptions& backoff) {
    BackoffResult result;
    result.decimation = decimate(*fine, options);
    if (result.decimation.target_reached || result.decimation.aborted || options.coarsest) return result;
    const std::size_t first_target = result.decimation.target_faces;

    // Tracing needs the edge paths, which the caller may not have asked for.
    DecimateOptions finer = options;
    finer.edge_paths = true;
    if (!options.edge_paths) {
        DecimateResult with_paths = decimate(*fine, finer);
        if (with_paths.aborted) {  // the mesh reached stands, without the back-off
            result.decimation.aborted = true;
            return result;
        }
        result.decimation = std::move(with_paths);
    }
    // Only the components that the topology stopped above their shares may get more faces.
    std::vector<char> stopped;
    for (const DecimateComponent& component : result.decimation.components)
        stopped.push_back(component.faces > component.target_faces);
    std::optional<TracedLevel> traced = trace_level(fine, result.decimation, backoff);
    if (traced) result.levels.push_back(traced->level);
    for (int round = 0; traced && round < backoff.max_rounds; ++round) {
        // A stopped component whose geodesics tangle aims at twice its faces; the others at what they aimed at,
        // which gives them the same decimation again.
        std::vector<int> targets;
        std::size_t sum = 0;
        bool more = false;
        for (std::size_t c = 0; c < stopped.size(); ++c) {
            const DecimateComponent& component = result.decimation.components[c];
            const bool tangled = static_cast<double>(traced->tangled[c]) >
                                 backoff.max_tangled_per_edge * static_cast<double>(traced->edges[c]);
            int target = component.target_faces;
            if (stopped[c] && tangled && 2 * component.faces < component.fine_faces) {
                target = 2 * component.faces;
                more = true;
            }
            targets.push_back(target);
            sum += static_cast<std::size_t>(target);
        }
        if (!more) break;
        finer.target_faces = sum;
        finer.target_vertices = 0;
        finer.ratio = 0.0;
        finer.component_targets = std::move(targets);
        if (backoff.stage) backoff.stage("decimating again, to " + std::to_string(sum) + " faces");
        DecimateResult decimation = decimate(*fine, finer);
        if (decimation.aborted) {  // the last level, complete, stands
            result.decimation.aborted = true;
            break;
        }
        result.decimation = std::move(decimation);
        result.backed_off = true;
        traced = trace_level(fine, result.decimation, backoff);
        if (traced) result.levels.push_back(traced->level);
    }
    if (result.backed_off) {  // the target is still the one asked for, and it is not reached
        result.decimation.target_faces = first_target;
        result.decimation.target_reached = false;
    }
    if (!options.edge_paths) result.decimation.edges.clear();
    return result;
}

}  // namespace geotri

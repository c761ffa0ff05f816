#include <geotri/decimate_backoff.h>
#include <geotri/edge_paths_io.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/trace.h>
#include <geotri/validate.h>

#include <utility>

namespace geotri {

namespace {

// Traces the decimation's coarse mesh in its class and counts how its geodesics tangle.
BackoffLevel trace_level(const std::shared_ptr<const FineMesh>& fine, const DecimateResult& decimation,
                         const BackoffOptions& backoff) {
    BackoffLevel level;
    level.faces = decimation.coarse.triangles.size();
    if (backoff.tracing) backoff.tracing(level.faces);
    GeodesicTriangulation g(fine, make_coarse_mesh(decimation.coarse, fine->path + " (decimated)"));
    level.edges = g.coarse().n_edges();
    const EdgePaths paths = make_edge_paths(*fine, decimation);
    TraceOptions options;
    options.threads = backoff.threads;
    options.edge_paths = &paths;
    const TraceResult traced = trace(g, options);
    ValidationOptions conditions_1_to_3;
    conditions_1_to_3.overlay = false;  // condition 4 is not counted: the overlay costs the most
    const ValidationReport report = traced.report ? *traced.report : validate(g, conditions_1_to_3);
    level.tangled = report.violation_count[1] + report.violation_count[2];
    return level;
}

bool too_tangled(const BackoffLevel& level, const BackoffOptions& backoff) {
    return static_cast<double>(level.tangled) > backoff.max_tangled_per_edge * static_cast<double>(level.edges);
}

}  // namespace

BackoffResult decimate_backing_off(const std::shared_ptr<const FineMesh>& fine, const DecimateOptions& options,
                                   const BackoffOptions& backoff) {
    BackoffResult result;
    result.decimation = decimate(*fine, options);
    const std::size_t first_target = result.decimation.target_faces;
    if (result.decimation.target_reached || result.decimation.aborted || options.coarsest) return result;

    // Tracing needs the edge paths, which the caller may not have asked for.
    DecimateOptions with_paths = options;
    with_paths.edge_paths = true;
    if (!options.edge_paths) result.decimation = decimate(*fine, with_paths);
    result.levels.push_back(trace_level(fine, result.decimation, backoff));
    const std::size_t fine_faces = static_cast<std::size_t>(fine->mesh.num_faces());
    for (int round = 0; round < backoff.max_rounds && too_tangled(result.levels.back(), backoff); ++round) {
        const std::size_t faces = 2 * result.levels.back().faces;
        if (faces >= fine_faces) break;
        DecimateOptions finer = with_paths;
        finer.target_faces = faces;
        finer.target_vertices = 0;
        finer.ratio = 0.0;
        DecimateResult decimation = decimate(*fine, finer);
        if (decimation.aborted) break;
        result.decimation = std::move(decimation);
        result.levels.push_back(trace_level(fine, result.decimation, backoff));
    }
    if (result.backed_off()) {  // the target is still the one asked for, and it is not reached
        result.decimation.target_faces = first_target;
        result.decimation.target_reached = false;
    }
    if (!options.edge_paths) result.decimation.edges.clear();
    return result;
}

}  // namespace geotri

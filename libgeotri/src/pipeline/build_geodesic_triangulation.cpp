#include <geodesic/errors.h>
#include <geotri/build_geodesic_triangulation.h>

#include <utility>

namespace geotri {

BuildResult build_geodesic_triangulation(const std::shared_ptr<const FineMesh>& fine, const BuildOptions& options) {
    if (!fine) throw InvalidInput("build_geodesic_triangulation: no fine mesh");
    auto stage = [&options](const std::string& line) {
        if (options.stage) options.stage(line);
    };
    DecimateOptions decimate_options = options.decimation;
    decimate_options.edge_paths = true;
    stage("decimating");
    BackoffResult decimation;
    if (options.back_off) {
        BackoffOptions backoff;
        backoff.threads = options.threads;
        backoff.stage = options.stage;
        decimation = decimate_backing_off(fine, decimate_options, backoff);
    } else {
        decimation.decimation = decimate(*fine, decimate_options);
    }

    stage("tracing");
    const EdgePaths paths = make_edge_paths(*fine, decimation.decimation);
    GeodesicTriangulation traced(fine, make_coarse_mesh(decimation.decimation.coarse, "the decimated mesh"));
    TraceOptions trace_options;
    trace_options.threads = options.threads;
    trace_options.edge_paths = &paths;
    const TraceResult tracing = trace(traced, trace_options);

    // The tools hand G on in a .gtri file, which numbers its edges anew: the flips follow that numbering.
    GeodesicTriangulation g = renumbered_as_read(traced);
    UntangleAndFlipOptions flip_options = options.flips;
    flip_options.untangling.threads = options.threads;
    flip_options.flipping.threads = options.threads;
    const UntangleAndFlipResult flips = untangle_and_flip(g, flip_options);

    stage("validating");
    ValidationReport report = validate(g);
    return {std::move(g), std::move(report), std::move(decimation), tracing, flips};
}

}  // namespace geotri

// geotri-trace: a coarse mesh of T made into a geodesic triangulation, written as a .gtri file.
//
//   geotri-trace FINE COARSE -o OUT.gtri [--paths PATHS] [--threads N] [--quiet] [--json]

#include "output.h"
#include "progress.h"
#include "tool.h"

#include <geodesic/errors.h>
#include <geotri/fine_mesh.h>
#include <geotri/gtri_io.h>
#include <geotri/mesh_io.h>
#include <geotri/trace.h>
#include <geotri/validate.h>

#include <memory>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace {

namespace tools = geotri::tools;

struct Arguments {
    std::string fine_path;
    std::string coarse_path;
    std::string output;
    std::string paths;
};

int run(tools::Tool& tool) {
    CLI::App& app = tool.app;
    app.description("Makes every edge of a coarse mesh an exact geodesic of the fine mesh FINE, and writes the\n"
                    "geodesic triangulation as a .gtri file (docs/gtri-format.md). Coarse vertices that coincide\n"
                    "with vertices of FINE map to them; the others move to the closest point of FINE.");
    tool.set_help_footer({"geotri-trace bone.stl bone.coarse.off -o bone.gtri --paths bone.paths",
                          "geotri-trace bone.stl bone.coarse.off -o bone.gtri --threads 4 --json"});
    Arguments args;
    app.add_option("FINE", args.fine_path, "The fine mesh T: closed triangle mesh (.stl, .off, .obj, .ply)")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("COARSE", args.coarse_path, "The coarse mesh, with the topology of FINE (.stl, .off, .obj, .ply)")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("-o,--output", args.output, "The geodesic triangulation: .gtri")
        ->required()
        ->check(tools::extension_validator({".gtri"}));
    app.add_option("--paths", args.paths,
                   "Edge paths from geotri-decimate --paths: when the shortest geodesics do not make a valid\n"
                   "triangulation, each edge is also traced the way round that the decimation meant, and the\n"
                   "better of the two is kept")
        ->check(CLI::ExistingFile);
    tool.parse();
    tools::refuse_same_files({{"FINE", args.fine_path}, {"COARSE", args.coarse_path}, {"--paths", args.paths}},
                             {{"-o", args.output}});

    tools::Progress progress(tool.program(), tool.verbose());
    progress.stage("loading " + args.fine_path);
    const double load_start = tools::now_seconds();
    auto fine = std::make_shared<const geotri::FineMesh>(geotri::load_fine_mesh(args.fine_path));
    geotri::CoarseMesh coarse = geotri::make_coarse_mesh(geotri::read_mesh(args.coarse_path), args.coarse_path);
    geotri::EdgePaths edge_paths;
    if (!args.paths.empty()) edge_paths = geotri::read_edge_paths(args.paths);
    const double load_seconds = tools::now_seconds() - load_start;

    geotri::GeodesicTriangulation g(fine, std::move(coarse));
    geotri::TraceOptions options;
    options.threads = tool.common.threads;
    if (!args.paths.empty()) options.edge_paths = &edge_paths;
    options.progress = [&progress](int done, int total) { progress.update(done, total); };
    progress.stage("tracing: propagations");
    geotri::TraceResult traced;
    try {
        traced = geotri::trace(g, options);
    } catch (const geotri::InvalidInput& e) {
        throw geotri::InvalidInput(args.coarse_path + ": " + e.what());
    }

    progress.stage("checking");
    const double check_start = tools::now_seconds();
    const geotri::ValidationReport report = traced.report ? *traced.report : geotri::validate(g);
    const double check_seconds = tools::now_seconds() - check_start;

    progress.stage("writing " + args.output);
    const double write_start = tools::now_seconds();
    geotri::write_gtri(args.output, g);
    const double write_seconds = tools::now_seconds() - write_start;
    progress.clear();

    int threads = 1;
#ifdef _OPENMP
    threads = tool.common.threads > 0 ? tool.common.threads : omp_get_max_threads();
#endif
    const geotri::CoarseMesh& c = g.coarse();
    if (tool.common.json) {
        tools::JsonSummary summary;
        summary.add("fine", args.fine_path);
        summary.add("coarse", args.coarse_path);
        summary.add("output", args.output);
        summary.add("fine_vertices", fine->mesh.num_vertices());
        summary.add("fine_faces", fine->mesh.num_faces());
        summary.add("vertices", c.n_vertices());
        summary.add("edges", c.n_edges());
        summary.add("faces", c.n_faces());
        summary.add("threads", threads);
        summary.add("propagations", traced.propagations);
        summary.add("moved_vertices", traced.moved_vertices);
        summary.add("largest_location_move", traced.largest_location_move);
        summary.add("largest_move_vertex", traced.largest_move_vertex);
        summary.add("longest_propagation", traced.longest_propagation);
        summary.add("windows_created", traced.windows_created);
        summary.add("polyline_points", traced.polyline_points);
        if (!args.paths.empty()) {
            summary.add("class_geodesics_differing", traced.class_geodesics_differing);
            summary.add("class_geodesics_blocked", traced.class_geodesics_blocked);
            summary.add("class_geodesics_kept", traced.class_geodesics_kept);
        }
        summary.add("load_seconds", load_seconds);
        summary.add("trace_seconds", traced.seconds);
        summary.add("write_seconds", write_seconds);
        summary.add("valid", report.valid);
        for (int c = 0; c < 4; ++c)
            summary.add("condition_" + std::to_string(c + 1) + "_violations", report.violation_count[static_cast<std::size_t>(c)]);
        summary.add("check_seconds", check_seconds);
        std::printf("%s\n", summary.str().c_str());
    }
    if (tool.verbose()) {
        const char* program = tool.program().c_str();
        std::fprintf(stderr, "%s: %zu coarse vertices, %zu edges, %zu faces on %d fine faces\n", program,
                     c.n_vertices(), c.n_edges(), c.n_faces(), fine->mesh.num_faces());
        std::fprintf(stderr, "%s: traced in %.3f s with %d propagations on %d thread%s (%zu polyline points)\n",
                     program, traced.seconds, traced.propagations, threads, threads == 1 ? "" : "s",
                     traced.polyline_points);
        if (traced.moved_vertices == 0) {
            std::fprintf(stderr, "%s: every coarse vertex is a vertex of the fine mesh (largest move 0)\n", program);
        } else {
            std::fprintf(stderr, "%s: %d coarse vertices moved onto the fine mesh, the largest by %s (vertex %d)\n",
                         program, traced.moved_vertices, tools::format_double(traced.largest_location_move).c_str(),
                         traced.largest_move_vertex);
        }
        if (!args.paths.empty())
            std::fprintf(stderr, "%s: %d edges have a geodesic in the decimation's class other than the shortest, %d "
                                 "run through another coarse vertex; G holds the %s geodesics\n",
                         program, traced.class_geodesics_differing, traced.class_geodesics_blocked,
                         traced.class_geodesics_kept ? "class" : "shortest");
        if (report.valid) {
            std::fprintf(stderr, "%s: valid geodesic triangulation (checked in %.3f s)\n", program, check_seconds);
        } else {
            std::fprintf(stderr, "%s: NOT valid: %d, %d, %d, %d violations of conditions 1-4 (checked in %.3f s; "
                         "run geotri-check for details)\n", program, report.violation_count[0], report.violation_count[1],
                         report.violation_count[2], report.violation_count[3], check_seconds);
        }
        std::fprintf(stderr, "%s: wrote %s (load %.3f s, write %.3f s)\n", program, args.output.c_str(), load_seconds,
                     write_seconds);
    }
    return tools::k_exit_ok;
}

}  // namespace

int main(int argc, char** argv) { return tools::run_tool("trace", argc, argv, run); }

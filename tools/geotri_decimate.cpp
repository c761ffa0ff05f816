// geotri-decimate: a coarse mesh of a closed triangle mesh by halfedge collapses, with the coarse vertices at exact
// positions of the input's vertices and every component's topology kept.
//
//   geotri-decimate INPUT -o COARSE (--faces N | --vertices N | --ratio R | --coarsest) [--paths PATHS]
//                   [--no-backoff] [--json] [--quiet]

#include "output.h"
#include "progress.h"
#include "tool.h"

#include <geotri/decimate.h>
#include <geotri/decimate_backoff.h>
#include <geotri/edge_paths_io.h>
#include <geotri/fine_mesh.h>
#include <geotri/mesh_io.h>

#include <cstdio>
#include <limits>
#include <memory>
#include <string>

namespace {

namespace tools = geotri::tools;

// Meshes are indexed by int.
constexpr double k_most = std::numeric_limits<int>::max();

struct Arguments {
    std::string input;
    std::string output;
    std::size_t faces = 0;
    std::size_t vertices = 0;
    double ratio = 0.0;
    bool coarsest = false;
    std::string strategy = "multiple-choice";
    std::string paths;
    bool no_backoff = false;
};

int run(tools::Tool& tool) {
    CLI::App& app = tool.app;
    app.description("Decimates a closed triangle mesh by halfedge collapses: the coarse vertices are input vertices at\n"
                    "their exact positions, and every component keeps its topology (genus). The target is split\n"
                    "between the components in proportion to their area.");
    tool.set_help_footer({"geotri-decimate bone.stl -o bone.coarse.off --faces 320 --paths bone.paths",
                          "geotri-decimate bone.stl -o bone.coarse.off --coarsest --json"});
    Arguments args;
    app.add_option("INPUT", args.input, "Closed triangle mesh: .stl, .off, .obj or .ply")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("-o,--output", args.output, "Coarse mesh: .off, .obj or .ply (exact coordinates)")
        ->required()
        ->check(tools::extension_validator({".off", ".obj", ".ply"}, ".off, .obj or .ply"));
    // Exactly one target, checked by CLI11 while parsing.
    CLI::Option_group* target = app.add_option_group("Target", "Exactly one of these");
    target->add_option("--faces", args.faces, "At most this many faces in all")
        ->check(tools::number_in(0, k_most, true, true));
    target->add_option("--vertices", args.vertices, "At most this many vertices in all")
        ->check(tools::number_in(0, k_most, true, true));
    target->add_option("--ratio", args.ratio, "At most this fraction of the input's faces, in (0, 1]")
        ->check(tools::number_in(0, 1, true));
    target->add_flag("--coarsest", args.coarsest, "As coarse as each component's topology allows (a sphere: 4 faces)");
    target->require_option(1);
    app.add_option("--strategy", args.strategy,
                   "multiple-choice (default: random candidates while far from the target) or priority-queue")
        ->check(CLI::IsMember({"multiple-choice", "priority-queue"}));
    app.add_option("--paths", args.paths,
                   "Also write what each coarse edge is on the input, for geotri-trace --paths (a text file)");
    app.add_flag("--no-backoff", args.no_backoff,
                 "Where the topology stops decimation above the target, keep that mesh even when its\n"
                 "geodesics tangle (by default it is traced, and each component whose geodesics cross or\n"
                 "leave their vertex out of order more than once per three edges gets twice its faces)");
    tool.parse();
    tools::refuse_same_files({{"INPUT", args.input}}, {{"-o", args.output}, {"--paths", args.paths}});

    tools::Progress progress(tool.program(), tool.verbose());
    progress.stage("loading " + args.input);
    const double load_start = tools::now_seconds();
    const auto shared_fine = std::make_shared<const geotri::FineMesh>(geotri::load_fine_mesh(args.input));
    const geotri::FineMesh& fine = *shared_fine;
    const double load_seconds = tools::now_seconds() - load_start;

    geotri::DecimateOptions options;
    options.target_faces = args.faces;
    options.target_vertices = args.vertices;
    options.ratio = args.ratio;
    options.coarsest = args.coarsest;
    options.edge_paths = !args.paths.empty();
    options.strategy = args.strategy == "priority-queue" ? geotri::DecimateStrategy::priority_queue
                                                         : geotri::DecimateStrategy::multiple_choice;
    options.progress = [&progress](const geotri::DecimateProgress& p) {
        progress.update(static_cast<long long>(p.fine_faces) - static_cast<long long>(p.current_faces),
                        static_cast<long long>(p.fine_faces) - static_cast<long long>(p.target_faces));
        return true;
    };
    progress.stage("decimating: faces removed");
    const double decimate_start = tools::now_seconds();
    geotri::BackoffOptions backoff;
    backoff.threads = tool.common.threads;
    backoff.stage = [&progress](const std::string& stage) { progress.stage(stage); };
    geotri::BackoffResult backed;
    if (args.no_backoff) backed.decimation = geotri::decimate(fine, options);
    else backed = geotri::decimate_backing_off(shared_fine, options, backoff);
    const geotri::DecimateResult& result = backed.decimation;
    const double decimate_seconds = tools::now_seconds() - decimate_start;

    progress.stage("writing " + args.output);
    const double write_start = tools::now_seconds();
    tools::StagedOutputs outputs;  // the coarse mesh and its paths, or neither
    outputs.write(args.output, [&](const std::string& path) { geotri::write_mesh(path, result.coarse); });
    if (!args.paths.empty())
        outputs.write(args.paths, [&](const std::string& path) {
            geotri::write_edge_paths(path, geotri::make_edge_paths(fine, result));
        });
    outputs.commit();
    const double write_seconds = tools::now_seconds() - write_start;
    progress.clear();

    int min_faces = 0;
    for (const geotri::DecimateComponent& c : result.components) min_faces += c.min_faces;
    const std::size_t coarse_vertices = result.coarse.positions.size();
    const std::size_t coarse_faces = result.coarse.triangles.size();
    if (tool.common.json) {
        tools::JsonSummary summary;
        summary.add("input", args.input);
        summary.add("vertices", fine.mesh.num_vertices());
        summary.add("faces", fine.mesh.num_faces());
        summary.add("components", fine.num_components);
        summary.add("target_faces", result.target_faces);
        summary.add("min_faces", min_faces);
        summary.add("coarse_vertices", coarse_vertices);
        summary.add("coarse_faces", coarse_faces);
        summary.add("target_reached", result.target_reached);
        summary.add("backed_off", backed.backed_off);
        if (!backed.levels.empty()) {
            summary.add("faces_where_topology_stops", backed.levels.front().faces);
            summary.add("tangled_where_topology_stops", backed.levels.front().tangled);
            summary.add("edges_where_topology_stops", backed.levels.front().edges);
            if (backed.levels.back().faces == coarse_faces) summary.add("tangled", backed.levels.back().tangled);
        }
        summary.add("strategy", args.strategy);
        summary.add("load_seconds", load_seconds);
        summary.add("decimate_seconds", decimate_seconds);
        summary.add("write_seconds", write_seconds);
        summary.add("output", args.output);
        if (!args.paths.empty()) summary.add("paths", args.paths);
        std::printf("%s\n", summary.str().c_str());
    }
    if (tool.verbose()) {
        std::fprintf(stderr, "%s: %d vertices, %d faces, %d component%s -> %zu vertices, %zu faces (load %.3f s, "
                             "decimate %.3f s)\n",
                     tool.program().c_str(), fine.mesh.num_vertices(), fine.mesh.num_faces(), fine.num_components,
                     fine.num_components == 1 ? "" : "s", coarse_vertices, coarse_faces, load_seconds,
                     decimate_seconds);
        if (!result.target_reached) {
            const std::size_t stopped_at = backed.levels.empty() ? coarse_faces : backed.levels.front().faces;
            std::fprintf(stderr, "%s: target of %zu faces not reached: the topology needs at least %d, and no further "
                                 "collapse below %zu keeps it and the triangles' shape\n",
                         tool.program().c_str(), result.target_faces, min_faces, stopped_at);
        }
        if (!backed.levels.empty()) {
            const geotri::BackoffLevel& first = backed.levels.front();
            std::fprintf(stderr, "%s: traced there, its %zu edges' geodesics have %d crossings and vertices out of "
                                 "order%s\n",
                         tool.program().c_str(), first.edges, first.tangled,
                         backed.backed_off ? "" : ": kept");
        }
        if (backed.backed_off) {
            const geotri::BackoffLevel& last = backed.levels.back();
            std::fprintf(stderr, "%s: backed off to %zu faces", tool.program().c_str(), coarse_faces);
            if (last.faces == coarse_faces) std::fprintf(stderr, ", where %zu edges have %d", last.edges, last.tangled);
            std::fprintf(stderr, " (--no-backoff keeps the coarsest)\n");
        }
    }
    return tools::k_exit_ok;
}

}  // namespace

int main(int argc, char** argv) { return tools::run_tool("decimate", argc, argv, run); }

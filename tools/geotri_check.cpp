// geotri-check: says whether a geodesic triangulation is valid (DESIGN.md §1, conditions 1-4).
//
//   geotri-check IN.gtri [--fine PATH] [--json] [--quiet]
//
// Exit codes: 0 valid, 3 invalid, 1 bad input, 2 usage error.

#include "output.h"
#include "progress.h"
#include "tool.h"

#include <geodesic/errors.h>
#include <geotri/gtri_io.h>
#include <geotri/validate.h>

#include <cstdio>
#include <numeric>
#include <string>

namespace {

namespace tools = geotri::tools;

constexpr int k_exit_invalid = 3;

const char* const k_condition_names[4] = {
    "every edge is a geodesic between its end vertices",
    "the geodesics at every vertex are in order and wind once",
    "no two geodesics meet except at a common end vertex",
    "the geodesics cut T into one disk per coarse face",
};

std::string join(const std::vector<int>& ids) {
    std::string s;
    for (int id : ids) s += (s.empty() ? "" : " ") + std::to_string(id);
    return s;
}

/// The genus of T, all components together: what the coarse mesh's must be.
int fine_genus(const geotri::FineMesh& fine) { return std::accumulate(fine.genus.begin(), fine.genus.end(), 0); }

void print_report(const std::string& path, const geotri::ValidationReport& r, const geotri::FineMesh& fine) {
    std::printf("%s: %s\n", path.c_str(), r.valid ? "valid" : "INVALID");
    std::printf("  coarse mesh: %d vertices, %d edges, %d faces, %d component%s, genus %d\n", r.vertices, r.edges,
                r.faces, r.components, r.components == 1 ? "" : "s", r.genus);
    std::printf("  fine mesh: %d vertices, %d faces, %d component%s, genus %d\n", fine.mesh.num_vertices(),
                fine.mesh.num_faces(), fine.num_components, fine.num_components == 1 ? "" : "s", fine_genus(fine));
    std::printf("  corner angles: %.6g to %.6g degrees\n", r.min_corner_angle_deg, r.max_corner_angle_deg);
    std::printf("  edge lengths: min %.9g, mean %.9g, max %.9g\n", r.min_edge_length, r.mean_edge_length,
                r.max_edge_length);
    if (r.overlay_checked) {
        const double relative = r.fine_area > 0.0 ? (r.patch_area - r.fine_area) / r.fine_area : 0.0;
        std::printf("  patch area %.12g of fine area %.12g (relative difference %.3g)\n", r.patch_area, r.fine_area,
                    relative);
    }
    for (int c = 0; c < 4; ++c) {
        const int n = r.violation_count[static_cast<std::size_t>(c)];
        std::printf("  condition %d (%s): %s\n", c + 1, k_condition_names[c],
                    n == 0 ? "ok" : (std::to_string(n) + " violation" + (n == 1 ? "" : "s")).c_str());
    }
    if (r.violations.empty()) return;
    std::printf("violations:\n");
    for (const geotri::Violation& v : r.violations) {
        std::printf("  [%d] %s", v.condition, v.what.c_str());
        std::string involved;
        if (!v.coarse_vertices.empty()) involved += "vertices " + join(v.coarse_vertices);
        if (!v.coarse_edges.empty()) involved += std::string(involved.empty() ? "" : "; ") + "edges " + join(v.coarse_edges);
        if (!v.coarse_faces.empty()) involved += std::string(involved.empty() ? "" : "; ") + "faces " + join(v.coarse_faces);
        if (!involved.empty()) std::printf(" {%s}", involved.c_str());
        std::printf("\n");
    }
}

int run(tools::Tool& tool) {
    CLI::App& app = tool.app;
    app.description("Checks that a geodesic triangulation (.gtri) is valid: its edges are geodesics of T, the\n"
                    "geodesics at each vertex are in order and wind once, no two of them meet except at a common\n"
                    "end, and they cut T into one disk per coarse face.");
    tool.set_help_footer({"geotri-check bone.gtri", "geotri-check bone.gtri --json --quiet > bone.check.json"},
                         "the geodesic triangulation is valid", {"3  the geodesic triangulation is not valid (the report names the violations)"});
    std::string input, fine_override;
    app.add_option("IN", input, "The geodesic triangulation: .gtri")->required()->check(CLI::ExistingFile);
    app.add_option("--fine", fine_override, "The fine mesh T, instead of the path that the .gtri file holds")
        ->check(CLI::ExistingFile);
    tool.parse();

    tools::Progress progress(tool.program(), tool.verbose());
    progress.stage("loading " + input);
    const double load_start = tools::now_seconds();
    const geotri::GeodesicTriangulation g = geotri::read_gtri(input, fine_override);
    const double load_seconds = tools::now_seconds() - load_start;

    progress.stage("validating");
    const double validate_start = tools::now_seconds();
    geotri::ValidationReport r;
    try {
        r = geotri::validate(g);
    } catch (const geotri::Error& e) {
        throw geotri::InvalidInput(input + ": " + e.what());
    }
    const double validate_seconds = tools::now_seconds() - validate_start;
    progress.clear();

    if (tool.common.json) {
        tools::JsonSummary summary;
        summary.add("input", input);
        summary.add("fine", g.fine().path);
        summary.add("valid", r.valid);
        for (int c = 0; c < 4; ++c)
            summary.add("condition_" + std::to_string(c + 1), r.violation_count[static_cast<std::size_t>(c)]);
        summary.add("violations", r.violations.size());
        summary.add("vertices", r.vertices);
        summary.add("edges", r.edges);
        summary.add("faces", r.faces);
        summary.add("components", r.components);
        summary.add("genus", r.genus);
        summary.add("fine_genus", fine_genus(g.fine()));
        summary.add("min_corner_angle_deg", r.min_corner_angle_deg);
        summary.add("max_corner_angle_deg", r.max_corner_angle_deg);
        summary.add("min_edge_length", r.min_edge_length);
        summary.add("mean_edge_length", r.mean_edge_length);
        summary.add("max_edge_length", r.max_edge_length);
        summary.add("patch_area", r.patch_area);
        summary.add("fine_area", r.fine_area);
        summary.add("fine_vertices", g.fine().mesh.num_vertices());
        summary.add("fine_faces", g.fine().mesh.num_faces());
        summary.add("load_seconds", load_seconds);
        summary.add("validate_seconds", validate_seconds);
        std::printf("%s\n", summary.str().c_str());
    } else if (tool.verbose()) {
        print_report(input, r, g.fine());
    }
    if (tool.verbose())
        std::fprintf(stderr, "%s: %s is %s (load %.3f s, check %.3f s)\n", tool.program().c_str(), input.c_str(),
                     r.valid ? "valid" : "invalid", load_seconds, validate_seconds);
    std::fflush(stdout);
    return r.valid ? tools::k_exit_ok : k_exit_invalid;
}

}  // namespace

int main(int argc, char** argv) { return tools::run_tool("check", argc, argv, run); }

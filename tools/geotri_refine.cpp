// geotri-refine: refines a valid geodesic triangulation by longest-edge bisection (to a geodesic edge length or a
// face count) and then by inserting circumcentres (to a minimum corner angle), and writes the result.
//
//   geotri-refine IN.gtri -o OUT.gtri [--max-length L] [--faces N] [--min-angle A] [--no-flip] [--fine PATH]
//                 [--quiet] [--json]
//
// Exit codes: 0 when OUT is valid, 3 when OUT is written but invalid, 1 bad input (an invalid IN among it),
// 2 usage error.

#include "output.h"
#include "progress.h"
#include "tool.h"

#include <geodesic/errors.h>
#include <geotri/gtri_io.h>
#include <geotri/refine.h>

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace {

namespace tools = geotri::tools;

constexpr int k_exit_invalid = 3;

/// How a refinement of the input differs from the others, for the report on stderr.
std::string describe(const geotri::RefineAttempt& attempt) {
    char edge[32] = "default";
    if (attempt.min_edge_length > 0.0) std::snprintf(edge, sizeof edge, "%.4g", attempt.min_edge_length);
    char text[160];
    std::snprintf(text, sizeof text, "shortest edge %s, vertices of T curved beyond %.3g of the angle, %s", edge,
                  attempt.curved_fraction, attempt.vertex_moves ? "with vertex moves" : "without vertex moves");
    return text;
}

int run(tools::Tool& tool) {
    CLI::App& app = tool.app;
    app.description("Refines a valid geodesic triangulation (.gtri): splits the longest edge at its geodesic midpoint\n"
                    "until no edge is longer than --max-length and G has --faces faces, then inserts circumcentres\n"
                    "until every corner angle is at least --min-angle, first moving a vertex of the worst triangle to\n"
                    "the centre of its star, or taking out an input vertex at a short edge, where that mends the\n"
                    "corners around it. Every new edge is an exact geodesic, and every step keeps G valid or is\n"
                    "refused. Where some corners are left below --min-angle, the input is refined again in a few\n"
                    "other ways, and the best result is kept.");
    tool.set_help_footer({"geotri-refine bone.flip.gtri -o bone.fine.gtri --min-angle 25",
                          "geotri-refine bone.flip.gtri -o bone.fine.gtri --faces 2000 --json"},
                         "the result is written, and it is valid", {"3  the result is written, but it is not valid (the input was not)"});
    std::string input, output, fine_override;
    geotri::RefineOptions options;
    bool no_flip = false;
    app.add_option("IN", input, "The geodesic triangulation, valid (geotri-flip makes it so): .gtri")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("-o,--output", output, "The refined geodesic triangulation: .gtri")
        ->required()
        ->check(tools::extension_validator({".gtri"}));
    app.add_option("--max-length", options.max_length,
                   "Bisect until no edge is longer than this geodesic length (default: no bound)")
        ->check(tools::number_in(0, std::numeric_limits<double>::max(), true));
    app.add_option("--faces", options.target_faces, "Bisect until G has at least this many faces (default: none)")
        ->check(tools::number_in(0, std::numeric_limits<int>::max(), true, true));
    app.add_option("--min-angle", options.min_angle_deg,
                   "Then refine until every corner angle is at least this many degrees, at most 35 (default: none);\n"
                   "corners at points of T whose cone angle is below three times it are exempt. Then corners above\n"
                   "180 degrees are cut in two where every new corner stays at least this")
        ->check(tools::number_in(0, 35));
    app.add_option("--max-new-vertices", options.max_new_vertices,
                   "At most this many new vertices in each phase (default: none for bisection; for --min-angle,\n"
                   "four times the faces of G plus 100, doubled once when fewer than 5% of the faces are then below\n"
                   "the angle). On scanned surfaces whose every fine vertex is curved, refinement stops there while\n"
                   "the corners below the angle still fall: more leaves fewer. Past the default cap, the corners\n"
                   "above 180 degrees left are still cut; a cap given is never passed")
        ->check(tools::number_in(0, std::numeric_limits<int>::max(), true, true));
    app.add_flag("--no-flip", no_flip, "Do not flip towards geodesic Delaunay around new vertices");
    bool keep_vertices = false;
    app.add_flag("--keep-vertices", keep_vertices,
                 "Never take out or move a vertex of the input G (by default --min-angle may take out one at the\n"
                 "end of a short edge, reconnecting its star, when every corner around it is then at least the\n"
                 "angle, and move one to the centre of its star where that raises the corners around it)");
    app.add_option("--fine", fine_override, "The fine mesh T, instead of the path that the .gtri file holds")
        ->check(CLI::ExistingFile);
    tool.parse();
    tools::refuse_same_files({{"IN", input}}, {{"-o", output}});  // a .gtri output is never the fine mesh
    if (options.max_length == 0.0 && options.target_faces == 0 && options.min_angle_deg == 0.0)
        throw CLI::ValidationError("give at least one of --max-length, --faces and --min-angle");
    options.flip = !no_flip;
    options.threads = tool.common.threads;
    options.keep_vertices = keep_vertices;

    tools::Progress progress(tool.program(), tool.verbose());
    progress.stage("loading " + input);
    const double load_start = tools::now_seconds();
    geotri::GeodesicTriangulation g = geotri::read_gtri(input, fine_override);
    const double load_seconds = tools::now_seconds() - load_start;
    const std::size_t faces_before = g.coarse().n_faces();

    options.progress = [&progress](const std::string& where) { progress.stage(where); };
    progress.stage("refining");
    geotri::RefineResult r;
    try {
        r = geotri::refine(g, options);
    } catch (const geotri::InvalidInput& e) {
        throw geotri::InvalidInput(input + ": " + e.what());
    }

    progress.stage("writing " + output);
    const double write_start = tools::now_seconds();
    geotri::write_gtri(output, g);
    const double write_seconds = tools::now_seconds() - write_start;
    progress.clear();

    // Bisection stops where every split that is left is refused (a new edge would be shorter than refinement's
    // bound, or its patches too thin): the user must hear that the target was not reached.
    const bool length_reached = options.max_length == 0.0 || r.longest_edge <= options.max_length;
    const bool faces_reached =
        options.target_faces == 0 || static_cast<int>(g.coarse().n_faces()) >= options.target_faces;
    if (tool.common.json) {
        tools::JsonSummary summary;
        summary.add("input", input);
        summary.add("output", output);
        summary.add("bisection_target_reached", length_reached && faces_reached);
        summary.add("faces_before", faces_before);
        summary.add("vertices", g.coarse().n_vertices());
        summary.add("edges", g.coarse().n_edges());
        summary.add("faces", g.coarse().n_faces());
        summary.add("valid", r.valid_after);
        summary.add("edge_splits", r.edge_splits);
        summary.add("face_splits", r.face_splits);
        summary.add("refused_splits", r.refused_splits);
        summary.add("removed_vertices", r.removed_vertices);
        summary.add("moved_vertices", r.moved_vertices);
        summary.add("moves_onto_saddles", r.moves_onto_saddles);
        summary.add("splits_at_saddles", r.splits_at_saddles);
        summary.add("inside_splits", r.inside_splits);
        summary.add("flips", r.flips);
        summary.add("exempt_corners", r.exempt_corners);
        summary.add("small_corners_left", r.small_corners_left);
        summary.add("wide_corners_left", r.wide_corners_left);
        summary.add("vertex_cap_reached", r.vertex_cap_reached);
        std::vector<tools::JsonSummary> attempts;
        for (const geotri::RefineAttempt& attempt : r.attempts) {
            tools::JsonSummary one;
            one.add("min_edge_length", attempt.min_edge_length);
            one.add("curved_fraction", attempt.curved_fraction);
            one.add("vertex_moves", attempt.vertex_moves);
            one.add("corners_left", attempt.small_corners_left);
            one.add("smallest_corner_deg", attempt.min_angle_deg);
            one.add("kept", attempt.kept);
            one.add("error", attempt.error);
            attempts.push_back(one);
        }
        summary.add("attempts", attempts);
        summary.add("longest_edge", r.longest_edge);
        tools::add_corner_angles(summary, r.angles_before, r.angles_after);
        summary.add("load_seconds", load_seconds);
        summary.add("refine_seconds", r.seconds);
        summary.add("write_seconds", write_seconds);
        std::printf("%s\n", summary.str().c_str());
        std::fflush(stdout);
    }
    if (tool.verbose()) {
        const char* program = tool.program().c_str();
        std::fprintf(stderr,
                     "%s: %zu -> %zu faces: %d edge splits, %d face splits (%d well inside a patch), %d splits at "
                     "vertices of T in the end game, %d vertices taken out, %d moved (%d onto saddles), %d flips, %d "
                     "splits refused%s\n",
                     program, faces_before, g.coarse().n_faces(), r.edge_splits, r.face_splits, r.inside_splits,
                     r.splits_at_saddles, r.removed_vertices, r.moved_vertices, r.moves_onto_saddles, r.flips,
                     r.refused_splits, r.vertex_cap_reached ? "; stopped at the vertex cap (--max-new-vertices)" : "");
        std::fprintf(stderr, "%s: corner angles: min %.4g -> %.4g, mean %.4g -> %.4g degrees; longest edge %.6g\n",
                     program, r.angles_before.min_deg, r.angles_after.min_deg, r.angles_before.mean_deg,
                     r.angles_after.mean_deg, r.longest_edge);
        if (!length_reached)
            std::fprintf(stderr, "%s: --max-length %g not reached: the longest edge is %.6g, and every split left was "
                                 "refused\n",
                         program, options.max_length, r.longest_edge);
        if (!faces_reached)
            std::fprintf(stderr, "%s: --faces %d not reached: %zu faces, and every split left was refused\n", program,
                         options.target_faces, g.coarse().n_faces());
        if (options.min_angle_deg > 0.0 && r.exempt_corners + r.small_corners_left > 0)
            std::fprintf(stderr, "%s: %d corners below %g degrees at cone points that force them, %d where refinement "
                                 "gave up\n",
                         program, r.exempt_corners, options.min_angle_deg, r.small_corners_left);
        if (r.attempts.size() > 1)
            for (std::size_t k = 0; k < r.attempts.size(); ++k) {
                const geotri::RefineAttempt& attempt = r.attempts[k];
                if (!attempt.error.empty())
                    std::fprintf(stderr, "%s: attempt %zu (%s) stopped: %s\n", program, k + 1,
                                 describe(attempt).c_str(), attempt.error.c_str());
                else
                    std::fprintf(stderr, "%s: attempt %zu (%s): %d %s left, smallest %.2f degrees%s\n", program,
                                 k + 1, describe(attempt).c_str(), attempt.small_corners_left,
                                 attempt.small_corners_left == 1 ? "corner" : "corners", attempt.min_angle_deg,
                                 attempt.kept ? "; kept" : "");
            }
        if (r.wide_corners_left > 0)
            std::fprintf(stderr, "%s: %d corners above 180 degrees left\n", program, r.wide_corners_left);
        std::fprintf(stderr, "%s: %s; refined in %.3f s\n", program, r.valid_after ? "valid" : "INVALID", r.seconds);
    }
    return r.valid_after ? tools::k_exit_ok : k_exit_invalid;
}

}  // namespace

int main(int argc, char** argv) { return tools::run_tool("refine", argc, argv, run); }

// geotri-flip: makes a geodesic triangulation valid by flips (untangle), then flips it towards geodesic Delaunay
// (improve), and writes the result.
//
//   geotri-flip IN.gtri -o OUT.gtri [--criterion angle|length] [--thorough LEVEL] [--fine PATH] [--threads N]
//               [--quiet] [--json]
//
// Exit codes: 0 when OUT is valid, 3 when OUT is written but still invalid, 1 bad input, 2 usage error.

#include "output.h"
#include "progress.h"
#include "tool.h"

#include <geodesic/errors.h>
#include <geotri/gtri_io.h>
#include <geotri/untangle_and_flip.h>

#include <cstdio>
#include <map>
#include <string>

namespace {

namespace tools = geotri::tools;

constexpr int k_exit_invalid = 3;

std::string counts(const std::array<int, 4>& c) {
    std::string s;
    for (std::size_t i = 0; i < 4; ++i)
        s += std::string(i ? ", " : "") + "condition " + std::to_string(i + 1) + ": " + std::to_string(c[i]);
    return s;
}

int total(const std::array<int, 4>& c) { return c[0] + c[1] + c[2] + c[3]; }

int run(tools::Tool& tool) {
    CLI::App& app = tool.app;
    app.description("Makes a geodesic triangulation (.gtri) valid (untangle: edge flips, then edge splits at\n"
                    "forks and meetings, edge collapses and vertex moves where no flip helps), then flips edges while that improves the\n"
                    "triangles (geodesic Delaunay), and writes the result. Every new edge is an exact geodesic.");
    tool.set_help_footer({"geotri-flip bone.gtri -o bone.flip.gtri", "geotri-flip bone.gtri -o bone.flip.gtri --criterion length --json"},
                         "the result is written, and it is valid", {"3  the result is written, but untangling could not make it valid (the report says what is left)"});
    std::string input, output, fine_override, criterion_name = "angle";
    app.add_option("IN", input, "The geodesic triangulation: .gtri")->required()->check(CLI::ExistingFile);
    app.add_option("-o,--output", output, "The flipped geodesic triangulation: .gtri")
        ->required()
        ->check(tools::extension_validator({".gtri"}));
    app.add_option("--criterion", criterion_name,
                   "angle: flip when that raises the minimum corner angle of the two triangles (default);\n"
                   "length: intrinsic Delaunay on the geodesic edge lengths")
        ->check(CLI::IsMember({"angle", "length"}));
    int thorough = 2;
    CLI::Option* thorough_option =
        app.add_option("--thorough", thorough,
                       "Where untangling is stuck with few violations left, 1: also try each edge collapse\n"
                       "there, judged after untangling what it leaves; 2: then with that untangling ending\n"
                       "with such collapses too; 0: neither. Default: 2, until these and the other last\n"
                       "resorts (pairs of flips, wider vertex moves) have made 10^8 windows of propagation\n"
                       "(10-28 s on 2 cores; the same result on any machine). Given, they go on to the end,\n"
                       "which can take minutes where they mend nothing")
            ->check(CLI::Range(0, 2));
    int bisection_rounds = geotri::UntangleOptions{}.bisection_rounds;
    app.add_option("--bisection-rounds", bisection_rounds,
                   "Where untangling is still stuck after all that, split every edge that a violation\n"
                   "names at the middle of its polyline and go on: at most this many times (default 4;\n"
                   "0: never). It adds vertices where G is too coarse to be untangled")
        ->check(CLI::Range(0, 100));
    app.add_option("--fine", fine_override, "The fine mesh T, instead of the path that the .gtri file holds")
        ->check(CLI::ExistingFile);
    tool.parse();
    tools::refuse_same_files({{"IN", input}}, {{"-o", output}});  // a .gtri output is never the fine mesh

    tools::Progress progress(tool.program(), tool.verbose());
    progress.stage("loading " + input);
    const double load_start = tools::now_seconds();
    geotri::GeodesicTriangulation g = geotri::read_gtri(input, fine_override);
    const double load_seconds = tools::now_seconds() - load_start;

    geotri::UntangleAndFlipOptions options;
    options.untangling.threads = tool.common.threads;
    options.untangling.thorough = thorough;
    options.untangling.bisection_rounds = bisection_rounds;
    if (thorough_option->count() > 0) options.untangling.thorough_budget = 0;
    options.flipping.threads = tool.common.threads;
    options.flipping.criterion =
        criterion_name == "length" ? geotri::FlipCriterion::length : geotri::FlipCriterion::angle;
    options.untangling.progress = [&progress](const std::string& where) { progress.stage(where); };
    options.flipping.progress = options.untangling.progress;
    progress.stage("flipping");
    geotri::UntangleAndFlipResult r;
    try {
        r = geotri::untangle_and_flip(g, options);
    } catch (const geotri::InvalidInput& e) {
        throw geotri::InvalidInput(input + ": " + e.what());
    }

    progress.stage("writing " + output);
    const double write_start = tools::now_seconds();
    geotri::write_gtri(output, g);
    const double write_seconds = tools::now_seconds() - write_start;
    progress.clear();

    const geotri::UntangleResult& u = r.untangling;
    const geotri::FlipToDelaunayResult& f = r.flipping;
    int refused = 0;
    for (int n : f.refused) refused += n;
    if (tool.common.json) {
        tools::JsonSummary summary;
        summary.add("input", input);
        summary.add("output", output);
        summary.add("criterion", criterion_name);
        summary.add("vertices", g.coarse().n_vertices());
        summary.add("edges", g.coarse().n_edges());
        summary.add("faces", g.coarse().n_faces());
        summary.add("valid_before", u.valid_before);
        summary.add("valid", r.valid_after);
        for (std::size_t c = 0; c < 4; ++c) {
            summary.add("condition_" + std::to_string(c + 1) + "_before", u.violations_before[c]);
            summary.add("condition_" + std::to_string(c + 1), r.violations_after[c]);
        }
        summary.add("untangle_flips", u.flips);
        summary.add("untangle_fork_splits", u.fork_splits);
        summary.add("untangle_meeting_splits", u.meeting_splits);
        summary.add("untangle_collapses", u.collapses);
        summary.add("untangle_relocations", u.relocations);
        summary.add("untangle_bisections", u.bisections);
        summary.add("untangle_kept_bisection_vertices", u.kept_bisection_vertices);
        summary.add("untangle_rejected", u.rejected);
        summary.add("untangle_refused", u.refused);
        summary.add("untangle_stuck", u.stuck);
        summary.add("last_resorts_tried", u.last_resorts_tried);
        summary.add("thorough_budget_spent", u.thorough_budget_spent);
        summary.add("thorough_windows", u.thorough_windows);
        summary.add("improve_flips", f.flips);
        summary.add("improve_passes", f.passes);
        summary.add("improve_plans", f.plans);
        summary.add("improve_region_flips", f.region_flips);
        for (int k = 1; k < 5; ++k) {
            std::string key = geotri::to_string(static_cast<geotri::FlipRefusal>(k));
            for (char& ch : key)
                if (ch == ' ') ch = '_';
            summary.add("refused_" + key, f.refused[static_cast<std::size_t>(k)]);
        }
        summary.add("improve_skipped", f.skipped);
        summary.add("pass_cap_reached", f.pass_cap_reached);
        summary.add("improve_reverted", f.reverted);
        tools::add_corner_angles(summary, r.angles_before, r.angles_after);
        summary.add("load_seconds", load_seconds);
        summary.add("flip_seconds", r.seconds);
        summary.add("write_seconds", write_seconds);
        std::printf("%s\n", summary.str().c_str());
        std::fflush(stdout);
    }
    if (tool.verbose()) {
        const char* program = tool.program().c_str();
        std::fprintf(stderr, "%s: before: %s (%s)\n", program, u.valid_before ? "valid" : "INVALID",
                     counts(u.violations_before).c_str());
        std::fprintf(stderr,
                     "%s: untangle: %d flips, %d fork splits, %d splits at meetings, %d collapses and %d vertex moves "
                     "kept, %d edges bisected, %d tried and undone, %d not possible%s\n",
                     program, u.flips, u.fork_splits, u.meeting_splits, u.collapses,
                     u.relocations, u.bisections,
                     u.rejected, u.refused,
                     u.stuck ? "; stuck: no operation lowers the violations left" : "");
        if (u.kept_bisection_vertices)
            std::fprintf(stderr, "%s: untangled a second time, keeping the vertices that bisections added\n", program);
        if (f.skipped) {
            std::fprintf(stderr, "%s: improve: skipped, G is not valid\n", program);
        } else {
            std::fprintf(stderr, "%s: improve (%s): %d flips (%d inside the patches) in %d sweeps (%d computed)%s%s; %d refused (",
                         program, criterion_name.c_str(), f.flips, f.region_flips, f.passes,
                         f.plans,
                         f.pass_cap_reached ? ", sweep cap reached" : "",
                         f.reverted ? ", UNDONE: the result was invalid" : "", refused);
            for (int k = 1; k < 5; ++k)
                std::fprintf(stderr, "%s%s %d", k > 1 ? ", " : "", geotri::to_string(static_cast<geotri::FlipRefusal>(k)),
                             f.refused[static_cast<std::size_t>(k)]);
            std::fprintf(stderr, ")\n");
        }
        std::fprintf(stderr, "%s: corner angles before: min %.4g, mean %.4g, max %.4g degrees\n", program,
                     r.angles_before.min_deg, r.angles_before.mean_deg, r.angles_before.max_deg);
        std::fprintf(stderr, "%s: corner angles after:  min %.4g, mean %.4g, max %.4g degrees\n", program,
                     r.angles_after.min_deg, r.angles_after.mean_deg, r.angles_after.max_deg);
        std::fprintf(stderr, "%s: after: %s (%s); flipped in %.3f s\n", program, r.valid_after ? "valid" : "INVALID",
                     counts(r.violations_after).c_str(), r.seconds);
        if (!r.valid_after) {
            std::fprintf(stderr, "%s: %s is written but still invalid: %d violation%s left, the first: %s\n", program,
                         output.c_str(), total(r.violations_after), total(r.violations_after) == 1 ? "" : "s",
                         r.remaining.empty() ? "?" : r.remaining.front().what.c_str());
            if (u.thorough_budget_spent)
                std::fprintf(stderr, "%s: untangling's last resorts stopped at their budget of work; --thorough 2 "
                                     "tries them to the end, at a cost of minutes\n",
                             program);
            else if (u.last_resorts_tried && thorough < 2)
                std::fprintf(stderr, "%s: --thorough %d may mend it, at a cost of seconds to minutes\n", program,
                             thorough + 1);
            std::fprintf(stderr, "%s: a coarse mesh with more faces (geotri-decimate --faces) has shorter geodesics, "
                                 "which tangle less\n",
                         program);
        }
    }
    return r.valid_after ? tools::k_exit_ok : k_exit_invalid;
}

}  // namespace

int main(int argc, char** argv) { return tools::run_tool("flip", argc, argv, run); }

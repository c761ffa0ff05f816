// geotri-curve: curved high-order elements on a valid geodesic triangulation, each one certified valid and within a
// proven distance of the surface, refining G where an element fails; written as gmsh MSH, VTK VTU or MFEM mesh.
//
//   geotri-curve IN.gtri -o OUT.{msh,vtu,mesh} [--order P] [--tolerance EPS] [--min-quality Q] [--no-adapt]
//                [--gtri-out G.gtri] [--msh-version 4.1|2.2] [--bezier] [--fine PATH] [--quiet] [--json]
//
// Exit codes: 0 when every element is certified, 3 when OUT is written but some elements are not, 1 bad input (an
// invalid IN among it), 2 usage error.

#include "output.h"
#include "progress.h"
#include "tool.h"

#include <geodesic/errors.h>
#include <geotri/curved_elements.h>
#include <geotri/curved_mesh_io.h>
#include <geotri/gtri_io.h>
#include <geotri/validate.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace {

namespace tools = geotri::tools;

constexpr int k_exit_uncertified = 3;

int run(tools::Tool& tool) {
    CLI::App& app = tool.app;
    app.description("Makes one curved Lagrange triangle of order P per face of a valid geodesic triangulation (.gtri):\n"
                    "corners at G's vertices, edge nodes on its geodesics at even arc lengths, interior nodes on T\n"
                    "through a bijective map of each patch. Every element is certified by Bernstein bounds: its\n"
                    "Jacobian is positive against the plane of its corners and against every face of T it covers,\n"
                    "its min J / max J is at least --min-quality, and it lies within --tolerance of its patch. G is\n"
                    "refined around the elements that fail, with vertices on the creases and corners of T that\n"
                    "they reach over, or else by bisection, until none does.");
    tool.set_help_footer({"geotri-curve bone.flip.gtri -o bone.msh", "geotri-curve bone.flip.gtri -o bone.vtu --order 4 --json",
                          "geotri-curve bone.flip.gtri -o bone.mesh --order 2"},
                         "every element is certified",
                         {"3  the file is written, but some elements are not certified (--no-adapt, or the round cap)"});
    std::string input, output, gtri_output, fine_override, msh_version = "4.1";
    geotri::CurveAdaptOptions options;
    bool no_adapt = false, bezier = false;
    app.add_option("IN", input, "The geodesic triangulation, valid (geotri-flip makes it so): .gtri")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("-o,--output", output, "The curved elements: .msh (gmsh), .vtu (VTK, ParaView) or .mesh (MFEM)")
        ->required()
        ->check(tools::extension_validator({".msh", ".vtu", ".mesh"}, ".msh, .vtu or .mesh"));
    app.add_option("--order", options.curve.order, "Order P of the elements, 1 to 8 (default 3)")
        ->check(tools::number_in(1, 8, false, true));
    app.add_option("--tolerance", options.tolerance,
                   "Largest distance from an element to its patch, relative to the diagonal of T's bounding box\n"
                   "(default 1e-3)")
        ->check(tools::number_in(0, 1, true));
    app.add_option("--min-quality", options.min_quality,
                   "Smallest certified min J / max J of an element (default 0.1, gmsh's threshold)")
        ->check(tools::number_in(0, 1));
    app.add_option("--max-rounds", options.max_rounds, "Rounds of refinement at most (default 20)")
        ->check(tools::number_in(0, 1000, false, true));
    app.add_flag("--no-adapt", no_adapt, "Do not refine G: write the elements of G as it is");
    app.add_option("--gtri-out", gtri_output, "Also write G as refined: .gtri")
        ->check(tools::extension_validator({".gtri"}));
    app.add_option("--msh-version", msh_version, "4.1 (default) or 2.2 (for MFEM before 4.9, NekMesh and PETSc)")
        ->check(CLI::IsMember({"4.1", "2.2"}));
    app.add_flag("--bezier", bezier,
                 "With a .vtu output: Bezier triangles on their control points, not Lagrange triangles\n"
                 "through the nodes (the same surface)");
    app.add_option("--fine", fine_override, "The fine mesh T, instead of the path that the .gtri file holds")
        ->check(CLI::ExistingFile);
    tool.parse();
    if (bezier && tools::extension_of(output) != ".vtu")
        throw CLI::ValidationError("--bezier", "needs a .vtu output, not " + output);
    tools::refuse_same_files({{"IN", input}}, {{"-o", output}, {"--gtri-out", gtri_output}});
    if (no_adapt) options.max_rounds = 0;
    options.curve.threads = tool.common.threads;

    tools::Progress progress(tool.program(), tool.verbose());
    progress.stage("loading " + input);
    const double start = tools::now_seconds();
    geotri::GeodesicTriangulation g = geotri::read_gtri(input, fine_override);
    progress.stage("checking " + input);
    const geotri::ValidationReport report = geotri::validate(g);
    if (!report.valid)
        throw geotri::InvalidInput(input + ": G is not valid (" +
                                   (report.violations.empty() ? std::string("?") : report.violations.front().what) +
                                   "); geotri-flip makes it valid");
    const std::size_t faces_before = g.coarse().n_faces();

    progress.stage("curving");
    geotri::CurveAdaptResult r;
    try {
        r = geotri::curve_adaptively(g, options);
    } catch (const geotri::InvalidInput& e) {
        throw geotri::InvalidInput(input + ": " + e.what());
    }
    const double curve_seconds = tools::now_seconds() - start;

    progress.stage("writing " + output);
    tools::StagedOutputs outputs;  // the curved mesh and the refined G, or neither
    geotri::CurvedFileOptions file;
    file.msh_version = msh_version == "2.2" ? geotri::MshVersion::v22 : geotri::MshVersion::v41;
    file.vtu_cells = bezier ? geotri::VtuCells::bezier : geotri::VtuCells::lagrange;
    outputs.write(output, [&](const std::string& path) { geotri::write_curved_mesh(path, r.curved, file); });
    if (!gtri_output.empty())
        outputs.write(gtri_output, [&](const std::string& path) { geotri::write_gtri(path, g); });
    outputs.commit();
    progress.clear();

    const double max_distance = options.tolerance * r.curved.diagonal;
    int plane_valid = 0, surface_valid = 0;
    double worst_quality = 1.0, largest_distance = 0.0;
    std::vector<const geotri::CurvedElement*> failing;  // named in the report
    for (const geotri::CurvedElement& element : r.curved.elements) {
        plane_valid += element.certificate.plane == geotri::Certification::valid;
        surface_valid += element.certificate.surface == geotri::Certification::valid;
        worst_quality = std::min(worst_quality, element.certificate.quality_lower);
        largest_distance = std::max(largest_distance, element.certificate.distance / r.curved.diagonal);
        if (!element.passes(options.min_quality, max_distance)) failing.push_back(&element);
    }
    if (tool.common.json) {
        tools::JsonSummary summary;
        summary.add("input", input);
        summary.add("output", output);
        summary.add("order", r.curved.order);
        summary.add("faces_before", faces_before);
        summary.add("elements", r.curved.elements.size());
        summary.add("nodes", r.curved.nodes.size());
        summary.add("certified_plane", plane_valid);
        summary.add("certified_surface", surface_valid);
        summary.add("failing", r.failing);
        // Each failing element by its coarse face (element face + 1 of the .msh file), with its certificate.
        std::vector<tools::JsonSummary> failures;
        for (const geotri::CurvedElement* element : failing) {
            const geotri::ElementCertificate& c = element->certificate;
            tools::JsonSummary failure;
            failure.add("face", element->face.idx());
            failure.add("plane", geotri::to_string(c.plane));
            failure.add("surface", geotri::to_string(c.surface));
            failure.add("quality", c.quality_lower);
            failure.add("distance", c.distance / r.curved.diagonal);
            failures.push_back(std::move(failure));
        }
        summary.add("failing_elements", failures);
        summary.add("min_quality", worst_quality);
        summary.add("max_distance", largest_distance);
        summary.add("tolerance", options.tolerance);
        summary.add("refinement_rounds", r.rounds);
        summary.add("splits", r.splits);
        summary.add("moves", r.moves);
        summary.add("flips", r.flips);
        summary.add("round_cap_reached", r.round_cap_reached);
        summary.add("seconds", curve_seconds);
        std::printf("%s\n", summary.str().c_str());
    }
    if (tool.verbose()) {
        const char* program = tool.program().c_str();
        std::fprintf(stderr,
                     "%s: %zu elements of order %d (%zu faces before, %d splits, %d moves and %d flips in %d rounds): "
                     "%d of them certified against their corners' plane, %d against T; smallest min J / max J %.3g, "
                     "largest distance %.3g of the diagonal (%.3f s)\n",
                     program, r.curved.elements.size(), r.curved.order, faces_before, r.splits, r.moves, r.flips,
                     r.rounds, plane_valid, surface_valid, worst_quality, largest_distance, curve_seconds);
        if (r.failing > 0) {
            std::fprintf(stderr, "%s: %d element%s not certified (%s):", program, r.failing,
                         r.failing == 1 ? " is" : "s are",
                         no_adapt              ? "--no-adapt"
                         : r.round_cap_reached ? "the round cap was reached"
                                               : "no change of G mends them");
            for (std::size_t i = 0; i < std::min<std::size_t>(failing.size(), 8); ++i) {
                const geotri::ElementCertificate& c = failing[i]->certificate;
                std::fprintf(stderr, " face %d (plane %s, surface %s, quality >= %.3g, distance <= %.3g)",
                             failing[i]->face.idx(), geotri::to_string(c.plane), geotri::to_string(c.surface),
                             c.quality_lower, c.distance / r.curved.diagonal);
            }
            std::fprintf(stderr, "%s\n", failing.size() > 8 ? " ..." : "");
        }
    }
    return r.failing == 0 ? tools::k_exit_ok : k_exit_uncertified;
}

}  // namespace

int main(int argc, char** argv) { return tools::run_tool("curve", argc, argv, run); }

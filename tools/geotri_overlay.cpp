// geotri-overlay: the fine mesh cut along every geodesic of G, with each piece tagged by its patch, for viewers.
//
//   geotri-overlay IN.gtri -o OUT.{vtu,ply,obj} [--curves CURVES.{vtp,vtk,obj}] [--fine PATH] [--quiet] [--json]

#include "output.h"
#include "progress.h"
#include "tool.h"

#include <geodesic/errors.h>
#include <geotri/gtri_io.h>
#include <geotri/overlay.h>
#include <geotri/overlay_io.h>

#include <cmath>
#include <string>
#include <vector>

namespace {

namespace tools = geotri::tools;

struct Arguments {
    std::string input;
    std::string output;
    std::string curves;
    std::string fine;
};

std::string id_list(const std::vector<int>& ids, std::size_t most) {
    std::string text;
    for (std::size_t i = 0; i < ids.size() && i < most; ++i) text += (i ? " " : "") + std::to_string(ids[i]);
    if (ids.size() > most) text += " ...";
    return text;
}

int run(tools::Tool& tool) {
    CLI::App& app = tool.app;
    app.description("Cuts the fine mesh of a geodesic triangulation along all its geodesics and writes the pieces,\n"
                    "each tagged with its patch (coarse face), its fine face and a colour that differs between\n"
                    "adjacent patches. Reports the patches that are not disks bounded by their three geodesics\n"
                    "(validity condition 4); the overlay is written in either case.");
    tool.set_help_footer({"geotri-overlay bone.gtri -o bone.overlay.vtu --curves bone.geodesics.vtp",
                          "geotri-overlay bone.gtri -o bone.overlay.ply"});
    Arguments args;
    app.add_option("IN", args.input, "The geodesic triangulation: .gtri")->required()->check(CLI::ExistingFile);
    app.add_option("-o,--output", args.output,
                   "The overlay: .vtu (ParaView, cell data patch, fine_face, colour), .ply (face colours) or .obj "
                   "(a group per patch)")
        ->required()
        ->check(tools::extension_validator({".vtu", ".ply", ".obj"}));
    app.add_option("--curves", args.curves, "Also write the geodesics, one polyline per coarse edge: .vtp, .vtk or .obj")
        ->check(tools::extension_validator({".vtp", ".vtk", ".obj"}));
    app.add_option("--fine", args.fine, "The fine mesh, instead of the path that IN holds")->check(CLI::ExistingFile);
    tool.parse();

    tools::Progress progress(tool.program(), tool.verbose());
    progress.stage("loading " + args.input);
    const double load_start = tools::now_seconds();
    const geotri::GeodesicTriangulation g = geotri::read_gtri(args.input, args.fine);
    const double load_seconds = tools::now_seconds() - load_start;
    // The fine mesh is known once G is loaded, and an output must not replace it either.
    tools::refuse_same_files({{"IN", args.input}, {"fine mesh", g.fine().path}},
                             {{"-o", args.output}, {"--curves", args.curves}});

    progress.stage("cutting");
    const double cut_start = tools::now_seconds();
    const geotri::Overlay overlay = geotri::build_overlay(g);
    const double cut_seconds = tools::now_seconds() - cut_start;

    progress.stage("writing " + args.output);
    const double write_start = tools::now_seconds();
    tools::StagedOutputs outputs;  // the overlay and the curves, or neither
    outputs.write(args.output, [&](const std::string& path) { geotri::write_overlay(path, overlay); });
    if (!args.curves.empty())
        outputs.write(args.curves, [&](const std::string& path) { geotri::write_curves(path, g); });
    outputs.commit();
    const double write_seconds = tools::now_seconds() - write_start;
    progress.clear();

    const double fine_area = g.fine().mesh.total_area();
    const double patch_area = overlay.total_patch_area();
    const double relative_area_error = fine_area > 0.0 ? std::abs(patch_area - fine_area) / fine_area : 0.0;
    const int patches = static_cast<int>(g.coarse().n_faces()) - static_cast<int>(overlay.bad_patches.size());
    if (tool.common.json) {
        tools::JsonSummary summary;
        summary.add("input", args.input);
        summary.add("output", args.output);
        if (!args.curves.empty()) summary.add("curves", args.curves);
        summary.add("fine_faces", g.fine().mesh.num_faces());
        summary.add("coarse_faces", g.coarse().n_faces());
        summary.add("triangles", overlay.triangles.size());
        summary.add("vertices", overlay.positions.size());
        summary.add("regions", overlay.num_regions);
        summary.add("good_patches", patches);
        summary.add("bad_patches", overlay.bad_patches.size());
        summary.add("broken_edges", overlay.broken_edges.size());
        summary.add("unclaimed_regions", overlay.unclaimed_regions);
        summary.add("colours", overlay.num_colours);
        summary.add("valid", overlay.valid());
        summary.add("patch_area", patch_area);
        summary.add("fine_area", fine_area);
        summary.add("relative_area_error", relative_area_error);
        summary.add("load_seconds", load_seconds);
        summary.add("overlay_seconds", cut_seconds);
        summary.add("write_seconds", write_seconds);
        std::printf("%s\n", summary.str().c_str());
    }
    if (tool.verbose()) {
        const char* program = tool.program().c_str();
        std::fprintf(stderr, "%s: %zu triangles in %d regions, %d of %zu patches are disks bounded by their geodesics "
                     "(%d colours)\n",
                     program, overlay.triangles.size(), overlay.num_regions, patches, g.coarse().n_faces(),
                     overlay.num_colours);
        std::fprintf(stderr, "%s: patch area %s, area of T %s (relative difference %.3g)\n", program,
                     tools::format_double(patch_area).c_str(), tools::format_double(fine_area).c_str(),
                     relative_area_error);
        if (!overlay.bad_patches.empty())
            std::fprintf(stderr, "%s: %zu bad patches (coarse faces): %s\n", program, overlay.bad_patches.size(),
                         id_list(overlay.bad_patches, 20).c_str());
        if (!overlay.broken_edges.empty())
            std::fprintf(stderr, "%s: %zu coarse edges could not be cut in full: %s\n", program,
                         overlay.broken_edges.size(), id_list(overlay.broken_edges, 20).c_str());
        if (overlay.unclaimed_regions > 0)
            std::fprintf(stderr, "%s: %d regions (area %s) belong to no patch\n", program, overlay.unclaimed_regions,
                         tools::format_double(overlay.unclaimed_area).c_str());
        std::fprintf(stderr, "%s: wrote %s%s%s (load %.3f s, overlay %.3f s, write %.3f s)\n", program,
                     args.output.c_str(), args.curves.empty() ? "" : " and ", args.curves.c_str(), load_seconds,
                     cut_seconds, write_seconds);
    }
    return tools::k_exit_ok;
}

}  // namespace

int main(int argc, char** argv) { return tools::run_tool("overlay", argc, argv, run); }

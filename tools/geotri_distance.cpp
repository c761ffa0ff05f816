// geotri-distance: exact geodesic distances on a triangle mesh, from libgeodesic alone.
//
//   geotri-distance MESH --source SPEC [--source SPEC ...] [--stop SPEC ...] [--max-distance D] -o OUT
//                   [--path-to SPEC --path-out FILE] [--json] [--quiet]

#include "output.h"
#include "progress.h"
#include "tool.h"

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geodesic/mesh.h>
#include <geodesic/surface_point.h>
#include <geotri/mesh_io.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>

namespace {

using geotri::geodesic::SurfacePoint;
namespace tools = geotri::tools;

struct Arguments {
    std::string mesh_path;
    std::vector<std::string> sources;
    std::vector<std::string> stops;
    double max_distance = std::numeric_limits<double>::infinity();
    std::string output;
    std::string path_to;
    std::string path_out;
};

/// Checks the spelling of a surface point at parse time; whether it refers to the mesh is checked after loading.
CLI::Validator spec_validator() {
    return CLI::Validator(
        [](std::string& spec) -> std::string {
            try {
                geotri::geodesic::parse_spec(spec);
                return {};
            } catch (const geotri::Error& e) {
                return e.what();
            }
        },
        "SPEC");
}

/// The geodesic mesh of the file, with the file's name on every error.
geotri::geodesic::Mesh load_mesh(const std::string& path) {
    geotri::MeshData data = geotri::read_mesh(path);
    try {
        return geotri::geodesic::Mesh(std::move(data.positions), std::move(data.triangles));
    } catch (const geotri::TopologyError& e) {
        throw geotri::TopologyError(path + ": " + e.what());
    } catch (const geotri::InvalidInput& e) {
        throw geotri::InvalidInput(path + ": " + e.what());
    }
}

/// A point of the command line, checked against the mesh.
SurfacePoint resolve(const geotri::geodesic::Mesh& mesh, const std::string& option, const std::string& spec) {
    try {
        return mesh.canonical(geotri::geodesic::parse_spec(spec));
    } catch (const geotri::InvalidInput& e) {
        throw geotri::InvalidInput(option + " " + spec + ": " + e.what());
    }
}

template <typename T>
void put_little_endian(std::FILE* file, T value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    const std::uint16_t probe = 1;
    unsigned char first = 0;
    std::memcpy(&first, &probe, 1);
    if (first != 1) {
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    }
    std::fwrite(bytes, 1, sizeof(T), file);
}

void write_distances(const std::string& path, const geotri::geodesic::Mesh& mesh,
                     const std::vector<double>& distances) {
    if (tools::extension_of(path) == ".txt") {
        tools::write_file_atomically(path, [&](std::FILE* file) {
            for (const double d : distances) std::fprintf(file, "%s\n", tools::format_double(d).c_str());
        });
        return;
    }
    tools::write_file_atomically(path, [&](std::FILE* file) {
        std::fprintf(file,
                     "ply\nformat binary_little_endian 1.0\ncomment geotri-distance: exact geodesic distance per "
                     "vertex (inf where not reached)\nelement vertex %d\nproperty double x\nproperty double y\n"
                     "property double z\nproperty double distance\nelement face %d\n"
                     "property list uchar int vertex_indices\nend_header\n",
                     mesh.num_vertices(), mesh.num_faces());
        for (int v = 0; v < mesh.num_vertices(); ++v) {
            const Eigen::Vector3d& p = mesh.position(v);
            put_little_endian(file, p.x());
            put_little_endian(file, p.y());
            put_little_endian(file, p.z());
            put_little_endian(file, distances[static_cast<std::size_t>(v)]);
        }
        for (int f = 0; f < mesh.num_faces(); ++f) {
            put_little_endian(file, static_cast<unsigned char>(3));
            for (const int v : mesh.triangle(f)) put_little_endian(file, static_cast<std::int32_t>(v));
        }
    });
}

void write_path(const std::string& path, const geotri::geodesic::Mesh& mesh, const std::vector<SurfacePoint>& points) {
    std::vector<Eigen::Vector3d> positions;
    positions.reserve(points.size());
    for (const SurfacePoint& p : points) positions.push_back(mesh.point(p));
    auto xyz = [](std::FILE* file, const Eigen::Vector3d& p) {
        std::fprintf(file, "%s %s %s\n", tools::format_double(p.x()).c_str(), tools::format_double(p.y()).c_str(),
                     tools::format_double(p.z()).c_str());
    };
    if (tools::extension_of(path) == ".obj") {
        tools::write_file_atomically(path, [&](std::FILE* file) {
            std::fprintf(file, "# geotri-distance: geodesic path, %zu points\n", positions.size());
            for (const Eigen::Vector3d& p : positions) {
                std::fprintf(file, "v ");
                xyz(file, p);
            }
            std::fprintf(file, "l");
            for (std::size_t i = 0; i < positions.size(); ++i) std::fprintf(file, " %zu", i + 1);
            std::fprintf(file, "\n");
        });
        return;
    }
    tools::write_file_atomically(path, [&](std::FILE* file) {
        std::fprintf(file, "# vtk DataFile Version 3.0\ngeotri-distance geodesic path\nASCII\nDATASET POLYDATA\n");
        std::fprintf(file, "POINTS %zu double\n", positions.size());
        for (const Eigen::Vector3d& p : positions) xyz(file, p);
        std::fprintf(file, "LINES 1 %zu\n%zu", positions.size() + 1, positions.size());
        for (std::size_t i = 0; i < positions.size(); ++i) std::fprintf(file, " %zu", i);
        std::fprintf(file, "\n");
    });
}

int run(tools::Tool& tool) {
    CLI::App& app = tool.app;
    app.description("Exact geodesic distances on a triangle mesh, from one or more source points.\n"
                    "SPEC is a surface point: v:I (vertex I), e:I,J:T (on edge I-J at (1-T)*p(I) + T*p(J)) or\n"
                    "f:I:B0,B1,B2 (in face I, barycentric coordinates in its vertex order).");
    tool.set_help_footer({"geotri-distance bone.stl --source v:0 -o bone.distance.ply",
                          "geotri-distance bone.stl -s v:0 -s f:12:0.2,0.3,0.5 -o d.txt --path-to v:900 --path-out path.obj"});
    Arguments args;
    app.add_option("MESH", args.mesh_path, "Triangle mesh: .stl, .off, .obj or .ply")
        ->required()
        ->check(CLI::ExistingFile);
    // One value per occurrence, so that a positional argument after --source is never taken for a source.
    app.add_option("-s,--source", args.sources, "Source point (repeat for several sources)")
        ->required()
        ->allow_extra_args(false)
        ->check(spec_validator());
    app.add_option("--stop", args.stops,
                   "Stop once this point's distance is final (repeatable; default: none); farther vertices report inf")
        ->allow_extra_args(false)
        ->check(spec_validator());
    app.add_option("--max-distance", args.max_distance, "Compute nothing farther than this; farther is inf (default: no limit)")
        ->check(tools::number_in(0, std::numeric_limits<double>::infinity()));
    app.add_option("-o,--output", args.output,
                   "Distances: .txt (one line per vertex, in load order) or .ply (the mesh with a distance property)")
        ->required()
        ->check(tools::extension_validator({".txt", ".ply"}));
    CLI::Option* path_to = app.add_option("--path-to", args.path_to, "Trace the shortest path from the sources to this point")
                               ->check(spec_validator());
    CLI::Option* path_out = app.add_option("--path-out", args.path_out, "Where to write that path: .obj or .vtk")
                                ->check(tools::extension_validator({".obj", ".vtk"}));
    path_to->needs(path_out);
    path_out->needs(path_to);
    tool.parse();
    tools::refuse_same_files({{"MESH", args.mesh_path}}, {{"-o", args.output}, {"--path-out", args.path_out}});

    tools::Progress progress(tool.program(), tool.verbose());
    progress.stage("loading " + args.mesh_path);
    const double load_start = tools::now_seconds();
    const geotri::geodesic::Mesh mesh = load_mesh(args.mesh_path);
    const double load_seconds = tools::now_seconds() - load_start;

    std::vector<SurfacePoint> sources;
    for (const std::string& spec : args.sources) sources.push_back(resolve(mesh, "--source", spec));
    geotri::geodesic::PropagationOptions options;
    options.max_distance = args.max_distance;
    // Vertex distances and at most one path: the windows can go as the wavefront passes (memory for the wavefront
    // only, on meshes of millions of faces), and the path is found again by a propagation towards its end.
    options.keep_windows = false;
    for (const std::string& spec : args.stops) options.stop_points.push_back(resolve(mesh, "--stop", spec));
    std::optional<SurfacePoint> target;
    if (!args.path_to.empty()) {
        target = resolve(mesh, "--path-to", args.path_to);
        // With stop points, the propagation must also settle the path's end.
        if (!options.stop_points.empty()) options.stop_points.push_back(*target);
    }

    progress.stage("propagating");
    const double propagation_start = tools::now_seconds();
    geotri::geodesic::ExactGeodesic geodesic(mesh);
    geodesic.propagate(sources, options);
    const std::vector<double> distances = geodesic.vertex_distances();
    const double propagation_seconds = tools::now_seconds() - propagation_start;

    std::vector<SurfacePoint> path;
    double path_length = std::numeric_limits<double>::quiet_NaN();
    if (target) {
        progress.stage("tracing the path");
        path = geodesic.shortest_path(*target);
        if (path.empty()) {
            throw geotri::InvalidInput("--path-to " + args.path_to + ": not reachable from the sources" +
                                       (std::isfinite(args.max_distance) ? " within --max-distance" : ""));
        }
        path_length = geotri::geodesic::path_length(mesh, path);
    }

    progress.stage("writing " + args.output);
    tools::StagedOutputs outputs;  // the distances and the path, or neither
    outputs.write(args.output, [&](const std::string& file) { write_distances(file, mesh, distances); });
    if (target) outputs.write(args.path_out, [&](const std::string& file) { write_path(file, mesh, path); });
    outputs.commit();
    progress.clear();

    double max_finite = 0.0;
    std::size_t reached = 0;
    for (const double d : distances) {
        if (std::isfinite(d)) {
            max_finite = std::max(max_finite, d);
            ++reached;
        }
    }
    const geotri::geodesic::PropagationStats& stats = geodesic.stats();
    if (tool.common.json) {
        tools::JsonSummary summary;
        summary.add("mesh", args.mesh_path);
        summary.add("vertices", mesh.num_vertices());
        summary.add("faces", mesh.num_faces());
        summary.add("sources", sources.size());
        summary.add("reached_vertices", reached);
        summary.add("max_finite_distance", max_finite);
        summary.add("load_seconds", load_seconds);
        summary.add("propagation_seconds", propagation_seconds);
        summary.add("windows_created", stats.windows_created);
        summary.add("windows_propagated", stats.windows_propagated);
        summary.add("windows_pruned", stats.windows_pruned);
        summary.add("peak_queue_size", stats.peak_queue_size);
        summary.add("stopped_early", stats.stopped_early);
        summary.add("output", args.output);
        if (target) {
            summary.add("path_points", path.size());
            summary.add("path_length", path_length);
            summary.add("path_output", args.path_out);
        }
        std::printf("%s\n", summary.str().c_str());
    }
    if (tool.verbose()) {
        std::fprintf(stderr, "%s: %d vertices, %d faces; %zu reached, farthest at %s (load %.3f s, propagation %.3f s)\n",
                     tool.program().c_str(), mesh.num_vertices(), mesh.num_faces(), reached,
                     tools::format_double(max_finite).c_str(), load_seconds, propagation_seconds);
        if (target) {
            std::fprintf(stderr, "%s: path of %zu points, length %s, written to %s\n", tool.program().c_str(),
                         path.size(), tools::format_double(path_length).c_str(), args.path_out.c_str());
        }
    }
    return tools::k_exit_ok;
}

}  // namespace

int main(int argc, char** argv) { return tools::run_tool("distance", argc, argv, run); }

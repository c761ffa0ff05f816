// geotri-bench-propagation: times single-source exact geodesic propagation to every vertex, and compares the
// distances with CGAL's Surface_mesh_shortest_path on the same mesh and source when CGAL is available. With
// --pairs, times point-to-point queries instead, plain and goal-directed.
// Prints one Markdown table row per mesh on stdout; progress and errors go to stderr.

#include "cgal_reference.h"

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geodesic/mesh.h>
#include <geotri/mesh_io.h>
#include <geotri_test/procedural_meshes.h>

#include <sys/resource.h>

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

using geotri::geodesic::ExactGeodesic;
using geotri::geodesic::SurfacePoint;
using geotri::test::TriangleMesh;

constexpr const char* usage = R"(usage: geotri-bench-propagation [options] MESH...

Times single-source exact geodesic propagation from one vertex to all vertices and, where CGAL was found at build
time, CGAL's Surface_mesh_shortest_path on the same mesh and source. One table row per mesh on stdout.

MESH is a mesh file (.off .obj .ply .stl), or a generated mesh gen:KIND:FACES with KIND one of
  icosphere      icosahedron split into frequency^2 triangles per face, on the unit sphere
  torus          torus R = 1, r = 0.4, n_major = 2 n_minor
  grid           flat square grid
  cube           closed cube, n x n quads per face
  noisy-sphere   icosphere with every vertex moved radially by up to a quarter of an edge (seed 1)
and FACES the approximate face count (suffixes k and M allowed: gen:icosphere:400k).

options:
  --repeat N           propagations timed per mesh; the median is reported (default 3)
  --source V           source vertex (default: num_vertices / 2)
  --cgal-max-faces N   skip CGAL above N faces (default 250000)
  --no-cgal            never run CGAL
  --no-header          print no table header
  --label TEXT         name of the mesh in the table (default: the argument, without folders for files)
  --keep-windows       keep every window, as the library does by default so that paths are traced at once;
                       without it they are freed as the wavefront passes (PropagationOptions::keep_windows)
  --dump FILE          write the vertex distances (%.17g, one a line) to FILE, for comparing builds; one mesh only
  --write-obj FILE     write the mesh, as loaded or generated, to FILE as OBJ (coordinates %.17g), to run other
                       implementations on the very same input; one mesh only
  --pairs N            instead: N point-to-point queries between vertices drawn with a fixed seed, each a
                       propagation with the target as its stop point, plain and goal-directed (A*); the mean CPU
                       time and windows of each, and the largest relative difference of their distances
  -h, --help           this text
)";

struct Options {
    int repeat = 3;
    long source = -1;
    long cgal_max_faces = 250000;
    bool cgal = true;
    bool header = true;
    bool keep_windows = false;
    std::string label;
    std::string dump;
    std::string write_obj;
    long pairs = 0;
    std::vector<std::string> meshes;
};

[[noreturn]] void usage_error(const std::string& message) {
    std::cerr << "geotri-bench-propagation: error: " << message << "\n" << usage;
    std::exit(2);
}

long parse_count(const std::string& text) {
    if (text.empty()) usage_error("empty number");
    double scale = 1.0;
    std::string digits = text;
    if (digits.back() == 'k' || digits.back() == 'K') scale = 1e3, digits.pop_back();
    else if (digits.back() == 'M') scale = 1e6, digits.pop_back();
    char* end = nullptr;
    const double value = std::strtod(digits.c_str(), &end);
    if (end == digits.c_str() || *end != '\0' || !(value >= 0)) usage_error("not a number: " + text);
    return std::lround(value * scale);
}

Options parse(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage_error(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "-h" || arg == "--help") {
            std::cout << usage;
            std::exit(0);
        } else if (arg == "--repeat") {
            options.repeat = static_cast<int>(parse_count(value()));
            if (options.repeat < 1) usage_error("--repeat must be at least 1");
        } else if (arg == "--source") {
            options.source = parse_count(value());
        } else if (arg == "--cgal-max-faces") {
            options.cgal_max_faces = parse_count(value());
        } else if (arg == "--no-cgal") {
            options.cgal = false;
        } else if (arg == "--no-header") {
            options.header = false;
        } else if (arg == "--label") {
            options.label = value();
        } else if (arg == "--keep-windows") {
            options.keep_windows = true;
        } else if (arg == "--dump") {
            options.dump = value();
        } else if (arg == "--write-obj") {
            options.write_obj = value();
        } else if (arg == "--pairs") {
            options.pairs = parse_count(value());
            if (options.pairs < 1) usage_error("--pairs must be at least 1");
        } else if (!arg.empty() && arg[0] == '-') {
            usage_error("unknown option " + arg);
        } else {
            options.meshes.push_back(arg);
        }
    }
    if (options.meshes.empty()) usage_error("no mesh given");
    if (!options.label.empty() && options.meshes.size() > 1) usage_error("--label needs a single mesh");
    if (!options.dump.empty() && options.meshes.size() > 1) usage_error("--dump needs a single mesh");
    if (!options.write_obj.empty() && options.meshes.size() > 1) usage_error("--write-obj needs a single mesh");
    const std::string& obj = options.write_obj;
    if (!obj.empty() && (obj.size() < 4 || obj.compare(obj.size() - 4, 4, ".obj") != 0))
        usage_error("--write-obj needs a file ending in .obj");
    return options;
}

TriangleMesh generated(const std::string& spec) {
    const auto colon = spec.find(':', 4);
    if (colon == std::string::npos) usage_error("generated meshes are gen:KIND:FACES, not " + spec);
    const std::string kind = spec.substr(4, colon - 4);
    const double faces = static_cast<double>(parse_count(spec.substr(colon + 1)));
    const auto at_least = [](double x, int lo) { return std::max(lo, static_cast<int>(std::lround(x))); };
    if (kind == "icosphere") return geotri::test::geodesic_sphere(at_least(std::sqrt(faces / 20.0), 1));
    if (kind == "noisy-sphere") {
        const int frequency = at_least(std::sqrt(faces / 20.0), 1);
        return geotri::test::perturbed_sphere(frequency, std::min(0.25, 0.25 / frequency), 1);
    }
    if (kind == "torus") {
        const int n_minor = at_least(std::sqrt(faces / 4.0), 3);
        return geotri::test::torus(1.0, 0.4, 2 * n_minor, n_minor);
    }
    if (kind == "grid") {
        const int n = at_least(std::sqrt(faces / 2.0), 1);
        return geotri::test::flat_grid(n, n, 1.0, 1.0);
    }
    if (kind == "cube") return geotri::test::cube(at_least(std::sqrt(faces / 12.0), 1));
    usage_error("unknown generated mesh kind '" + kind + "'");
}

double peak_rss_mb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

std::string fixed(double x, int digits) {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(digits);
    out << x;
    return out.str();
}

std::string scientific(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1e", x);
    return buffer;
}

// CPU time of the process, as VTP's published figures are: this machine is shared, so wall time is noise.
double cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string label_of(const std::string& spec, const Options& options) {
    if (!options.label.empty()) return options.label;
    return spec.rfind("gen:", 0) == 0 ? spec.substr(4) : spec.substr(spec.find_last_of('/') + 1);
}

TriangleMesh load(const std::string& spec, const std::string& label) {
    TriangleMesh arrays;
    if (spec.rfind("gen:", 0) == 0) {
        arrays = generated(spec);
    } else {
        geotri::MeshData data = geotri::read_mesh(spec);
        arrays.positions = std::move(data.positions);
        arrays.triangles = std::move(data.triangles);
    }
    std::cerr << label << ": " << arrays.triangles.size() << " faces\n";
    return arrays;
}

/// The mesh as OBJ (coordinates that read back exactly), the only format that VTP reads (bench/vtp/compare.py).
void write_obj(const TriangleMesh& arrays, const std::string& path) {
    geotri::write_mesh(path, geotri::MeshData{arrays.positions, arrays.triangles});
}

// Point-to-point queries, plain and goal-directed. Returns false when their distances differ beyond 1e-12
// relative: both must be exact.
bool run_pairs(const std::string& spec, const Options& options) {
    const std::string label = label_of(spec, options);
    const TriangleMesh arrays = load(spec, label);
    if (!options.write_obj.empty()) write_obj(arrays, options.write_obj);
    const geotri::geodesic::Mesh mesh(arrays.positions, arrays.triangles);
    std::uint64_t state = 12345;  // a fixed linear congruential sequence: the same pairs on every run
    auto next_vertex = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<int>((state >> 33) % static_cast<std::uint64_t>(mesh.num_vertices()));
    };
    ExactGeodesic propagation(mesh);
    double seconds[2] = {0.0, 0.0}, windows[2] = {0.0, 0.0}, worst = 0.0;
    for (long k = 0; k < options.pairs; ++k) {
        const SurfacePoint from = SurfacePoint::at_vertex(next_vertex()), to = SurfacePoint::at_vertex(next_vertex());
        double distance[2];
        for (int directed = 0; directed < 2; ++directed) {
            geotri::geodesic::PropagationOptions query;
            query.stop_points = {to};
            query.goal_directed = directed == 1;
            const double start = cpu_seconds();
            propagation.propagate({from}, query);
            distance[directed] = propagation.distance(to);
            seconds[directed] += cpu_seconds() - start;
            windows[directed] += static_cast<double>(propagation.stats().windows_created);
        }
        if (std::isfinite(distance[0]) || std::isfinite(distance[1]))
            worst = std::max(worst, std::abs(distance[1] - distance[0]) / std::max(distance[0], 1e-300));
    }
    const double n = static_cast<double>(options.pairs);
    std::cout << "| " << label << " | " << arrays.triangles.size() << " | " << options.pairs << " | "
              << fixed(1e3 * seconds[0] / n, 2) << " | " << fixed(windows[0] / n, 0) << " | "
              << fixed(1e3 * seconds[1] / n, 2) << " | " << fixed(windows[1] / n, 0) << " | "
              << fixed(seconds[0] / seconds[1], 1) << " | " << scientific(worst) << " |" << std::endl;
    return worst <= 1e-12;
}

// Returns false when the distances disagree with CGAL beyond 1e-9 of the largest distance.
bool run_one(const std::string& spec, const Options& options) {
    const std::string label = label_of(spec, options);
    const TriangleMesh arrays = load(spec, label);
    if (!options.write_obj.empty()) write_obj(arrays, options.write_obj);

    double start = cpu_seconds();
    const geotri::geodesic::Mesh mesh(arrays.positions, arrays.triangles);
    const double setup = cpu_seconds() - start;
    const int source = options.source >= 0 ? static_cast<int>(options.source) : mesh.num_vertices() / 2;
    if (source >= mesh.num_vertices()) throw geotri::InvalidInput("--source is not a vertex of " + label);

    ExactGeodesic propagation(mesh);
    geotri::geodesic::PropagationOptions everywhere;
    everywhere.keep_windows = options.keep_windows;
    std::vector<double> times;
    for (int k = 0; k < options.repeat; ++k) {
        start = cpu_seconds();
        propagation.propagate({SurfacePoint::at_vertex(source)}, everywhere);
        times.push_back(cpu_seconds() - start);
    }
    std::sort(times.begin(), times.end());
    const double ours = times[times.size() / 2];
    const std::vector<double> distances = propagation.vertex_distances();
    const auto stats = propagation.stats();
    std::cerr << label << ": windows created " << stats.windows_created << ", propagated " << stats.windows_propagated
              << ", pruned " << stats.windows_pruned << ", merged " << stats.windows_merged << ", freed "
              << stats.windows_freed << ", not made " << stats.windows_not_made << ", vertex emissions "
              << stats.vertex_emissions << ", peak queue " << stats.peak_queue_size << "\n";
    if (!options.dump.empty()) {
        std::FILE* file = std::fopen(options.dump.c_str(), "w");
        if (file == nullptr) throw geotri::IOError("cannot write " + options.dump);
        for (double d : distances) std::fprintf(file, "%.17g\n", d);
        std::fclose(file);
    }
    const double rss = peak_rss_mb();

    std::string cgal_time = "-", ratio = "-", difference = "-";
    bool agrees = true;
    const bool cgal_built =
#ifdef GEOTRI_BENCH_WITH_CGAL
        true;
#else
        false;
#endif
    if (cgal_built && options.cgal && static_cast<long>(arrays.triangles.size()) <= options.cgal_max_faces) {
        std::cerr << label << ": running CGAL\n";
        const geotri::bench::CgalRun cgal = geotri::bench::cgal_vertex_distances(arrays.positions, arrays.triangles, source);
        if (!cgal.error.empty()) {
            std::cerr << label << ": " << cgal.error << "\n";
            cgal_time = "failed";
        } else {
            double largest = 0.0, worst = 0.0;
            int reachability = 0;
            for (std::size_t v = 0; v < distances.size(); ++v) {
                if (std::isinf(distances[v]) != std::isinf(cgal.distances[v])) {
                    ++reachability;
                    continue;
                }
                if (std::isinf(distances[v])) continue;
                largest = std::max(largest, distances[v]);
                worst = std::max(worst, std::abs(distances[v] - cgal.distances[v]));
            }
            const double relative = largest > 0.0 ? worst / largest : worst;
            cgal_time = fixed(cgal.seconds, 3);
            ratio = fixed(cgal.seconds / ours, 1);
            difference = scientific(relative);
            if (reachability > 0) {
                difference += " (" + std::to_string(reachability) + " reachability mismatches)";
                agrees = false;
            }
            if (!(relative < 1e-9)) {
                difference += " (!)";
                agrees = false;
            }
        }
    }
    const double window_mb = static_cast<double>(stats.window_bytes) / (1024.0 * 1024.0);
    std::cout << "| " << label << " | " << arrays.triangles.size() << " | " << fixed(ours, 3) << " | " << cgal_time
              << " | " << ratio << " | " << difference << " | " << fixed(rss, 0) << " | " << stats.windows_created
              << " | " << fixed(setup, 3) << " | " << fixed(window_mb, 1) << " | " << stats.queue_pops << " |"
              << std::endl;
    return agrees;
}

}  // namespace

int main(int argc, char** argv) {
    const Options options = parse(argc, argv);
    if (options.header && options.pairs > 0) {
        std::cout << "| mesh | faces | pairs | plain (ms) | plain windows | goal-directed (ms) | goal-directed windows | "
                     "speed-up | max rel diff |\n"
                     "|---|---:|---:|---:|---:|---:|---:|---:|---:|"
                  << std::endl;
    } else if (options.header) {
        std::cout << "| mesh | faces | ours (s) | CGAL (s) | ratio | max rel diff | MB | windows | setup (s) | window MB | "
                     "queue pops |\n"
                     "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
                  << std::endl;
    }
    int status = 0;
    for (const auto& spec : options.meshes) {
        try {
            if (!(options.pairs > 0 ? run_pairs(spec, options) : run_one(spec, options))) status = 3;
        } catch (const std::exception& error) {
            std::cerr << "geotri-bench-propagation: error: " << spec << ": " << error.what() << "\n";
            status = 1;
        }
    }
    return status;
}

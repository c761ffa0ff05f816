// embed: geotri used from a program of your own, through the installed package.
//
//   embed MESH [FACES [OUT.gtri]]
//
// 1. Loads MESH, a closed triangle mesh (.stl, .off, .obj, .ply), as the fine mesh T.
// 2. libgeodesic: the exact geodesic distance from vertex 0 to every vertex, the farthest vertex, and the shortest
//    path to it, whose length must equal its distance.
// 3. libgeotri: decimates T to about FACES faces (default 320), traces every coarse edge as an exact geodesic of T,
//    untangles and flips towards geodesic Delaunay, checks the result, and writes it to OUT.gtri when given.
//
// Exit codes: 0 when every step ran (even if G is still invalid: that is reported, not an error), 1 when geotri
// refused the input or failed, 2 for a wrong command line.

#include <geodesic/errors.h>          // geotri::Error and the typed exceptions derived from it
#include <geodesic/exact_geodesic.h>  // geotri::geodesic::ExactGeodesic, path_length
#include <geotri/geotri.h>               // the whole public API, and build_geodesic_triangulation()

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace gd = geotri::geodesic;

namespace {

constexpr int k_exit_ok = 0;
constexpr int k_exit_error = 1;
constexpr int k_exit_usage = 2;

constexpr std::size_t k_default_faces = 320;

// libgeodesic promises that a shortest path is as long as the distance of its end; both are sums of doubles
// computed differently, so they may differ in the last bits.
constexpr double k_length_tolerance = 1e-12;

void print_usage(std::FILE* out)
{
    std::fprintf(out,
                 "usage: embed MESH [FACES [OUT.gtri]]\n"
                 "  MESH      a closed triangle mesh: .stl, .off, .obj or .ply\n"
                 "  FACES     faces of the geodesic triangulation (default %zu)\n"
                 "  OUT.gtri  where to write the geodesic triangulation (optional)\n",
                 k_default_faces);
}

// A whole, positive number: "320" but not "0", "-3", "12abc" or "".
bool parse_face_count(const char* text, std::size_t& faces)
{
    char* end = nullptr;
    errno = 0;
    const long long value = std::strtoll(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || value <= 0)
        return false;
    faces = static_cast<std::size_t>(value);
    return true;
}

// Step 2, libgeodesic alone: it needs nothing but a geodesic::Mesh (FineMesh holds one), so a program that only
// wants distances can link geotri::geodesic and build its Mesh from its own arrays.
void report_distance_field(const geotri::FineMesh& fine)
{
    gd::ExactGeodesic geodesic(fine.mesh);  // reusable for further propagations on the same mesh
    geodesic.propagate({gd::SurfacePoint::at_vertex(0)});
    const std::vector<double> distances = geodesic.vertex_distances();

    // Vertices on other components than vertex 0's are unreachable: their distance is +inf.
    std::size_t farthest_index = 0;
    for (std::size_t v = 0; v < distances.size(); ++v) {
        if (std::isfinite(distances[v]) && distances[v] > distances[farthest_index])
            farthest_index = v;
    }
    const int farthest = static_cast<int>(farthest_index);
    const double distance = distances[farthest_index];
    std::printf("distance field from vertex 0: farthest vertex %d at distance %.17g\n", farthest, distance);

    // The path runs from the source to the target, both included, through points on edges and vertices of T.
    const std::vector<gd::SurfacePoint> path = geodesic.shortest_path(gd::SurfacePoint::at_vertex(farthest));
    const double length = gd::path_length(fine.mesh, path);
    const double difference = std::abs(length - distance) / std::max(1.0, distance);
    if (difference > k_length_tolerance) {
        throw geotri::NumericalError("the shortest path to vertex " + std::to_string(farthest) + " is " +
                                     std::to_string(length) + " long, not its distance " + std::to_string(distance));
    }
    std::printf("shortest path to vertex %d: %zu points, length %.17g (agrees with the distance, relative "
                "difference %.1e)\n", farthest, path.size(), length, difference);
}

// Step 3, libgeotri: what geotri-decimate, geotri-trace and geotri-flip do, in one call, with the same result.
void report_geodesic_triangulation(const std::shared_ptr<const geotri::FineMesh>& fine, std::size_t faces,
                                   const std::string& gtri_path)
{
    geotri::BuildOptions options;
    options.decimation.target_faces = faces;
    const geotri::BuildResult built = geotri::build_geodesic_triangulation(fine, options);

    // The coarse vertices are vertices of T at their exact positions, and each component keeps its genus; where
    // the topology needs more faces than asked for, the target is not reached.
    const geotri::DecimateResult& decimated = built.decimation.decimation;
    std::printf("decimated to %zu faces (target %zu%s)\n", decimated.coarse.triangles.size(), faces,
                decimated.target_reached ? "" : ", not reached: the topology or the mesh needs more");
    std::printf("traced %zu edges as exact geodesics (%d propagations)\n", decimated.edges.size(),
                built.tracing.propagations);

    // Traced geodesics may cross or fold over one another; flips, splits, collapses and vertex moves untangle
    // them, then flips make the triangles better shaped. Untangling may not succeed on every mesh: the result says so.
    const geotri::UntangleResult& untangled = built.flips.untangling;
    std::printf("untangling (%s before): %d flips, %d fork splits, %d splits at meetings, %d collapses, %d vertex "
                "moves; %d flips towards Delaunay\n",
                untangled.valid_before ? "valid" : "invalid", untangled.flips, untangled.fork_splits,
                untangled.meeting_splits, untangled.collapses, untangled.relocations, built.flips.flipping.flips);

    // The judge: the four validity conditions, and summary figures. It reports an invalid G, it does not throw.
    const geotri::ValidationReport& report = built.report;
    if (report.valid) {
        std::printf("G: %d faces, valid, min corner angle %.2f degrees\n", report.faces,
                    report.min_corner_angle_deg);
    } else {
        std::printf("G: %d faces, INVALID (violations of conditions 1-4: %d, %d, %d, %d; the first: %s)\n",
                    report.faces, report.violation_count[0], report.violation_count[1], report.violation_count[2],
                    report.violation_count[3],
                    report.violations.empty() ? "?" : report.violations.front().what.c_str());
    }

    // The .gtri refers to T by its path (relative to the .gtri's folder) and checksum; the geotri-* tools read it.
    if (!gtri_path.empty()) {
        geotri::write_gtri(gtri_path, built.g);
        std::printf("wrote %s\n", gtri_path.c_str());
    }
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 2 || argc > 4) {
        print_usage(stderr);
        return k_exit_usage;
    }
    const std::string mesh_path = argv[1];
    std::size_t faces = k_default_faces;
    if (argc > 2 && !parse_face_count(argv[2], faces)) {
        std::fprintf(stderr, "embed: error: FACES must be a positive whole number, not '%s'\n", argv[2]);
        print_usage(stderr);
        return k_exit_usage;
    }
    const std::string gtri_path = argc > 3 ? argv[3] : "";

    // The libraries never print or exit: every failure is an exception whose message names the file and the problem.
    try {
        // Step 1: T is read exactly and checked (closed, manifold, oriented); it never changes afterwards.
        const auto fine = std::make_shared<const geotri::FineMesh>(geotri::load_fine_mesh(mesh_path));
        std::printf("mesh %s: %d vertices, %d faces, %d component%s\n", mesh_path.c_str(), fine->mesh.num_vertices(),
                    fine->mesh.num_faces(), fine->num_components, fine->num_components == 1 ? "" : "s");

        report_distance_field(*fine);
        report_geodesic_triangulation(fine, faces, gtri_path);
    } catch (const geotri::Error& error) {  // InvalidInput, TopologyError, IOError, NumericalError
        std::fprintf(stderr, "embed: error: %s\n", error.what());
        return k_exit_error;
    } catch (const std::exception& error) {  // out of memory, or an error from below geotri
        std::fprintf(stderr, "embed: error: %s\n", error.what());
        return k_exit_error;
    }
    std::printf("done\n");
    return k_exit_ok;
}

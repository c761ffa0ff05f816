// Times VTP (Qin et al. 2016) the way geotri-bench-propagation times libgeodesic: the CPU time of single-source
// propagations to every vertex, the mesh loaded once and not timed, the median reported. VTP is not part of
// geotri; bench/vtp/build.sh builds this against its sources (bench/vtp/README.md).
//
//     vtp-bench MESH.obj SOURCE REPEAT [DISTANCES]
//
// prints `MESH faces=F vertices=V propagate_median_s=T construct_s=C peak_rss_mb=M` on stdout, and writes the
// distances of the last run, one a line (%.17g, in the file's vertex order), to DISTANCES if given.

#include "geodesic_algorithm_exact.h"
#include "geodesic_mesh.h"

#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace {

double cpu_seconds() {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

// VTP leaves the windows still on edges when it returns; freed here, untimed, so that repeats do not pile them up.
void free_windows_left(geodesic::GeodesicAlgorithmExact& vtp, geodesic::Mesh& mesh) {
    for (unsigned i = 0; i < mesh.edges().size(); ++i) {
        geodesic::edge_pointer e = &mesh.edges()[i];
        for (geodesic::list_pointer list : {vtp.interval_list_0(e), vtp.interval_list_1(e)}) {
            for (geodesic::interval_pointer w = list->begin(); w != nullptr;) {
                geodesic::interval_pointer next = w->next();
                delete w;
                w = next;
            }
            list->clear();
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: vtp-bench MESH.obj SOURCE REPEAT [DISTANCES]\n");
        return 2;
    }
    std::string path = argv[1];
    const long source_in_file = std::atol(argv[2]);
    const int repeat = std::max(1, std::atoi(argv[3]));

    std::vector<double> points;
    std::vector<unsigned> faces;
    std::vector<int> real_index;  // per vertex of the file: its index after VTP's loader merged equal positions
    int vertices_in_file = 0;
    // The loader reports on stdout, which is for the result line.
    std::fflush(stdout);
    const int saved_stdout = dup(1);
    dup2(2, 1);
    const bool loaded = geodesic::read_mesh_from_file(&path[0], points, faces, real_index, vertices_in_file);
    std::fflush(stdout);
    dup2(saved_stdout, 1);
    close(saved_stdout);
    if (!loaded) {
        std::fprintf(stderr, "vtp-bench: cannot read %s\n", path.c_str());
        return 1;
    }
    if (source_in_file < 0 || source_in_file >= static_cast<long>(real_index.size())) {
        std::fprintf(stderr, "vtp-bench: %s has no vertex %ld\n", path.c_str(), source_in_file);
        return 1;
    }
    const unsigned source = static_cast<unsigned>(real_index[source_in_file]);
    const unsigned vertices = static_cast<unsigned>(points.size() / 3);
    if (vertices != real_index.size())
        std::fprintf(stderr, "vtp-bench: %s: the loader merged %zu vertices into %u\n", path.c_str(),
                     real_index.size(), vertices);

    std::vector<double> construct_times, propagate_times, distances(vertices);
    for (int k = 0; k < repeat; ++k) {
        // VTP keeps its state in the mesh and never resets it: a fresh mesh each time, built untimed.
        auto mesh = std::make_unique<geodesic::Mesh>();
        mesh->initialize_mesh_data(points, faces);
        const double start = cpu_seconds();
        auto vtp = std::make_unique<geodesic::GeodesicAlgorithmExact>(mesh.get());
        const double constructed = cpu_seconds();
        vtp->propagate(source);
        const double propagated = cpu_seconds();
        construct_times.push_back(constructed - start);
        propagate_times.push_back(propagated - constructed);
        for (unsigned v = 0; v < vertices; ++v) distances[v] = mesh->vertices()[v].geodesic_distance();
        std::fprintf(stderr, "run %d: construct %.6f s, propagate %.6f s, window propagations %u, peak windows %u\n",
                     k, constructed - start, propagated - constructed, geodesic::m_windows_propagation,
                     geodesic::m_windows_peak);
        free_windows_left(*vtp, *mesh);
    }

    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("%s faces=%zu vertices=%zu propagate_median_s=%.6f construct_s=%.6f peak_rss_mb=%.1f\n",
                path.c_str(), faces.size() / 3, real_index.size(), median(propagate_times),
                median(construct_times), static_cast<double>(usage.ru_maxrss) / 1024.0);
    if (argc > 4) {
        std::FILE* file = std::fopen(argv[4], "w");
        if (file == nullptr) {
            std::fprintf(stderr, "vtp-bench: cannot write %s\n", argv[4]);
            return 1;
        }
        for (int index : real_index) {
            const double d = distances[index];
            if (d < geodesic::GEODESIC_INF) std::fprintf(file, "%.17g\n", d);
            else std::fprintf(file, "inf\n");
        }
        std::fclose(file);
    }
    return 0;
}

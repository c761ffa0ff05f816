#include "cgal_reference.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <ctime>
#include <exception>
#include <limits>

namespace geotri::bench {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, SurfaceMesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;

}  // namespace

CgalRun cgal_vertex_distances(const std::vector<Eigen::Vector3d>& positions,
                              const std::vector<std::array<int, 3>>& triangles, int source) {
    CgalRun run;
    try {
        SurfaceMesh mesh;
        std::vector<SurfaceMesh::Vertex_index> vertices;
        vertices.reserve(positions.size());
        for (const auto& p : positions) vertices.push_back(mesh.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
        for (const auto& t : triangles)
            if (mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]) == SurfaceMesh::null_face()) {
                run.error = "CGAL::Surface_mesh refused a face";
                return run;
            }
        ShortestPath shortest_paths(mesh);
        // CPU time, like ours (see propagation_bench.cpp).
        timespec t0{}, t1{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t0);
        shortest_paths.add_source_point(vertices[source]);
        shortest_paths.build_sequence_tree();
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t1);
        run.seconds = static_cast<double>(t1.tv_sec - t0.tv_sec) + 1e-9 * static_cast<double>(t1.tv_nsec - t0.tv_nsec);
        run.distances.resize(positions.size());
        for (std::size_t v = 0; v < positions.size(); ++v) {
            const double d = shortest_paths.shortest_distance_to_source_points(vertices[v]).first;
            run.distances[v] = d < 0.0 ? std::numeric_limits<double>::infinity() : d;
        }
    } catch (const std::exception& error) {
        run.error = std::string("CGAL threw: ") + error.what();
    }
    return run;
}

}  // namespace geotri::bench

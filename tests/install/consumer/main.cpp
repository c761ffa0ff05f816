// Uses the installed headers and libraries: exact geodesics on a regular octahedron, whose distances have closed
// forms, and a mesh file written and read back through libgeotri. Exits 0 when every check holds.

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geodesic/mesh.h>
#include <geotri/mesh_io.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace gd = geotri::geodesic;

namespace {

int failures = 0;

void check_near(const char* what, double actual, double expected)
{
    const bool ok = std::abs(actual - expected) <= 1e-12 * std::max(1.0, std::abs(expected));
    std::printf("%s %s: %.17g (expected %.17g)\n", ok ? "ok  " : "FAIL", what, actual, expected);
    failures += ok ? 0 : 1;
}

void check(const char* what, bool ok)
{
    std::printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    failures += ok ? 0 : 1;
}

// Vertices ±x, ±y, ±z (0: +x, 1: -x, 2: +y, 3: -y, 4: +z, 5: -z), one face per octant, normals outward.
geotri::MeshData octahedron()
{
    geotri::MeshData mesh;
    mesh.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    mesh.triangles = {{0, 2, 4}, {1, 4, 2}, {0, 4, 3}, {1, 3, 4}, {0, 5, 2}, {1, 2, 5}, {0, 3, 5}, {1, 5, 3}};
    return mesh;
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        // Round trip through libgeotri's exact mesh IO.
        const std::string path = std::string(argc > 1 ? argv[1] : ".") + "/octahedron.off";
        const geotri::MeshData written = octahedron();
        geotri::write_mesh(path, written);
        const geotri::MeshData data = geotri::read_mesh(path);
        check("mesh reads back exactly", data.positions == written.positions && data.triangles == written.triangles);

        // Edge length √2: a neighbour is √2 away; the opposite vertex √6, straight across the midpoint of an edge
        // of the two unfolded faces between them.
        const gd::Mesh mesh(data.positions, data.triangles);
        const gd::SurfacePoint source = gd::SurfacePoint::at_vertex(0);
        const gd::SurfacePoint target = gd::SurfacePoint::at_vertex(1);
        gd::ExactGeodesic geodesic(mesh);
        geodesic.propagate({source});
        check_near("distance to a neighbour", geodesic.distance(2), std::sqrt(2.0));
        check_near("distance to the opposite vertex", geodesic.distance(1), std::sqrt(6.0));

        const std::vector<gd::SurfacePoint> path_to_target = geodesic.shortest_path(target);
        check("path runs from the source to the target, across an edge",
              path_to_target.size() == 3 && path_to_target.front() == source && path_to_target.back() == target);
        check_near("path length", gd::path_length(mesh, path_to_target), std::sqrt(6.0));
    } catch (const geotri::Error& error) {
        std::fprintf(stderr, "geotri_consumer: error: %s\n", error.what());
        return 1;
    }
    return failures == 0 ? 0 : 1;
}

// straighten_path against closed forms: straight lines on flat grids, the side of a pinned vertex that a path keeps,
// helices that wind around a cylinder a given number of times, and the unfolding of a cube; on curved meshes,
// paths that the independent checker finds locally shortest, no longer than the edge path and no shorter than the
// exact distance.

#include "check_helpers.h"

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geodesic/straighten_path.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <queue>

namespace geotri::test {
namespace {

using geodesic::StraightenStatus;
using geodesic::SurfacePoint;

std::vector<unsigned char> pins(const geodesic::Mesh& mesh, const std::vector<int>& pinned = {}) {
    std::vector<unsigned char> flags(std::size_t(mesh.num_vertices()), 0);
    for (const int v : pinned) flags[std::size_t(v)] = 1;
    return flags;
}

// The path's length and its check as a geodesic polyline by the independent oracle.
void expect_geodesic(const TriangleMesh& arrays, const geodesic::StraightenResult& result, const std::string& name) {
    const Adjacency adjacency(arrays);
    const PathReport report = check_geodesic_path(arrays, adjacency, result.path, 1e-9);
    EXPECT_TRUE(report.problems.empty()) << name << ": " << (report.problems.empty() ? "" : report.problems[0]);
    EXPECT_NEAR(report.length, result.length, 1e-12 * std::max(1.0, result.length)) << name;
}

// Grid vertex (i, j) of flat_grid(n, n, 1, 1).
int grid(int n, int i, int j) { return j * (n + 1) + i; }

// A staircase of grid edges from (i0, j0) to (i1, j1): right or up, alternating while both are left.
std::vector<int> staircase(int n, int i0, int j0, int i1, int j1) {
    std::vector<int> path{grid(n, i0, j0)};
    int i = i0, j = j0;
    while (i != i1 || j != j1) {
        if (i != i1 && (j == j1 || (i - i0 + j - j0) % 2 == 0))
            i += i1 > i ? 1 : -1;
        else
            j += j1 > j ? 1 : -1;
        path.push_back(grid(n, i, j));
    }
    return path;
}

TEST(StraightenPath, StaircaseOnAFlatGridBecomesTheStraightSegment) {
    const int n = 12;
    for (const double perturbation : {0.0, 0.2}) {
        const TriangleMesh arrays = flat_grid(n, n, 1.0, 1.0, perturbation, 3);
        const geodesic::Mesh mesh = arrays.to_mesh();
        const std::vector<std::array<int, 4>> ends{{1, 1, 11, 7}, {2, 10, 9, 1}, {0, 0, 12, 12}};
        for (const auto& [i0, j0, i1, j1] : ends) {
            const std::vector<int> path = staircase(n, i0, j0, i1, j1);
            const auto result = geodesic::straighten_path(mesh, path, pins(mesh));
            const std::string name = "perturbation " + std::to_string(perturbation) + ", from " +
                                     std::to_string(path.front()) + " to " + std::to_string(path.back());
            EXPECT_EQ(result.status, StraightenStatus::geodesic) << name;
            EXPECT_NEAR(result.length, (mesh.position(path.back()) - mesh.position(path.front())).norm(), 1e-12)
                << name;
            expect_geodesic(arrays, result, name);
        }
    }
}

TEST(StraightenPath, KeepsItsSideOfAPinnedVertex) {
    // From (0, 0.5) to (1, 0.5), with the vertex at (0.5, 0.6) pinned: a path below it straightens to the segment,
    // one above it must wrap around it.
    const int n = 10;
    const TriangleMesh arrays = flat_grid(n, n, 1.0, 1.0);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const int pinned = grid(n, 5, 6);
    auto around_row = [&](int row) {
        std::vector<int> path{grid(n, 0, 5), grid(n, 1, 5)};
        for (int j = 5; j != row;) path.push_back(grid(n, 1, j += row > 5 ? 1 : -1));
        for (int i = 2; i <= 9; ++i) path.push_back(grid(n, i, row));
        for (int j = row; j != 5;) path.push_back(grid(n, 9, j += row > 5 ? -1 : 1));
        path.push_back(grid(n, 10, 5));
        return path;
    };
    const auto below = geodesic::straighten_path(mesh, around_row(2), pins(mesh, {pinned}));
    EXPECT_EQ(below.status, StraightenStatus::geodesic);
    EXPECT_NEAR(below.length, 1.0, 1e-14);
    expect_geodesic(arrays, below, "below");

    const auto above = geodesic::straighten_path(mesh, around_row(8), pins(mesh, {pinned}));
    EXPECT_EQ(above.status, StraightenStatus::through_pinned_vertex);
    EXPECT_EQ(above.vertex, pinned);
    EXPECT_NEAR(above.length, 2.0 * std::hypot(0.5, 0.1), 1e-14);

    // Without the pin, both sides are the same class.
    const auto free = geodesic::straighten_path(mesh, around_row(8), pins(mesh));
    EXPECT_EQ(free.status, StraightenStatus::geodesic);
    EXPECT_NEAR(free.length, 1.0, 1e-14);
}

TEST(StraightenPath, HelicesKeepTheirWindingAroundACylinder) {
    // With both cap centres pinned, the surface is an annulus: a path that winds w times around the mantle
    // straightens to the helix that does, as long as the mantle unrolled into a strip.
    const int sides = 8, rows = 6;
    const double radius = 1.0, height = 3.0;
    const TriangleMesh arrays = capped_cylinder(radius, height, sides, rows);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const int bottom = sides * (rows + 1), top = bottom + 1;
    const double side = 2.0 * radius * std::sin(k_pi / sides);
    auto at = [&](int col, int row) { return row * sides + ((col % sides) + sides) % sides; };
    for (const int winding : {0, 1, 2, -1}) {
        const int shift = 3;  // columns beyond the full turns
        std::vector<int> path{at(0, 1)};
        const int steps = winding * sides + (winding < 0 ? -shift : shift);
        for (int k = 1; k <= std::abs(steps); ++k) path.push_back(at(steps > 0 ? k : -k, 2));
        path.insert(path.begin() + 1, at(0, 2));
        for (int row = 3; row <= rows - 1; ++row) path.push_back(at(steps, row));
        const auto result = geodesic::straighten_path(mesh, path, pins(mesh, {bottom, top}));
        const std::string name = "winding " + std::to_string(winding);
        EXPECT_EQ(result.status, StraightenStatus::geodesic) << name;
        const double expected = std::hypot(std::abs(steps) * side, height * (rows - 2) / rows);
        EXPECT_NEAR(result.length, expected, 1e-12 * expected) << name << ", " << result.moves << " moves";
        expect_geodesic(arrays, result, name);
    }
}

TEST(StraightenPath, OverTheFrontOfACubeIsTheUnfoldedLine) {
    // From the centre of the bottom to the centre of the top, along edges over the front face: 0.5 + 1 + 0.5.
    const TriangleMesh arrays = cube(4);
    const geodesic::Mesh mesh = arrays.to_mesh();
    std::vector<int> path;
    auto add = [&](double x, double y, double z) { path.push_back(nearest_vertex(mesh, Eigen::Vector3d(x, y, z))); };
    // A detour along quarter-edges of the 4 x 4 lattice, over the bottom, the front (y = 0) and the top.
    for (const auto& [x, y, z] : std::vector<std::array<double, 3>>{
             {0.5, 0.5, 0.0}, {0.25, 0.5, 0.0}, {0.25, 0.25, 0.0}, {0.25, 0.0, 0.0}, {0.25, 0.0, 0.25},
             {0.25, 0.0, 0.5}, {0.5, 0.0, 0.5}, {0.75, 0.0, 0.5}, {0.75, 0.0, 0.75}, {0.75, 0.0, 1.0},
             {0.75, 0.25, 1.0}, {0.5, 0.25, 1.0}, {0.5, 0.5, 1.0}})
        add(x, y, z);
    std::vector<int> corners;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (mesh.cone_angle(v) < 1.6 * k_pi) corners.push_back(v);
    ASSERT_EQ(corners.size(), 8u);
    const auto result = geodesic::straighten_path(mesh, path, pins(mesh, corners));
    EXPECT_EQ(result.status, StraightenStatus::geodesic);
    EXPECT_NEAR(result.length, 2.0, 1e-13);
    expect_geodesic(arrays, result, "cube");
}

// The edge path of a shortest path along edges, by Dijkstra from `from`.
std::vector<int> edge_path(const geodesic::Mesh& mesh, int from, int to) {
    std::vector<double> distance(std::size_t(mesh.num_vertices()), std::numeric_limits<double>::infinity());
    std::vector<int> parent(std::size_t(mesh.num_vertices()), -1);
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    distance[std::size_t(from)] = 0.0;
    queue.push({0.0, from});
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > distance[std::size_t(v)]) continue;
        for (const int h : mesh.outgoing_halfedges(v)) {
            const int w = mesh.head(h);
            if (d + mesh.length(h) < distance[std::size_t(w)]) {
                distance[std::size_t(w)] = d + mesh.length(h);
                parent[std::size_t(w)] = v;
                queue.push({distance[std::size_t(w)], w});
            }
        }
    }
    std::vector<int> path{to};
    while (path.back() != from) path.push_back(parent[std::size_t(path.back())]);
    std::reverse(path.begin(), path.end());
    return path;
}

TEST(StraightenPath, EdgePathsOnCurvedMeshesBecomeGeodesics) {
    for (const auto& [name, arrays] : std::vector<std::pair<std::string, TriangleMesh>>{
             {"perturbed sphere", perturbed_sphere(12, 0.08, 4)}, {"torus", torus(3.0, 1.0, 48, 20)}}) {
        const geodesic::Mesh mesh = arrays.to_mesh();
        geodesic::ExactGeodesic propagation(mesh);
        const int n = mesh.num_vertices();
        for (int k = 0; k < 12; ++k) {
            const int from = (k * 7919) % n, to = (k * 104729 + 17) % n;
            if (from == to) continue;
            const std::vector<int> path = edge_path(mesh, from, to);
            double along_edges = 0.0;
            for (std::size_t i = 0; i + 1 < path.size(); ++i)
                along_edges += (mesh.position(path[i + 1]) - mesh.position(path[i])).norm();
            const auto result = geodesic::straighten_path(mesh, path, pins(mesh));
            const std::string case_name = name + ", " + std::to_string(from) + " to " + std::to_string(to);
            EXPECT_EQ(result.status, StraightenStatus::geodesic) << case_name;
            EXPECT_LE(result.length, along_edges * (1.0 + 1e-12)) << case_name;
            propagation.propagate({SurfacePoint::at_vertex(from)});
            EXPECT_GE(result.length, propagation.distance(to) * (1.0 - 1e-12)) << case_name;
            expect_geodesic(arrays, result, case_name);
        }
    }
}

TEST(StraightenPath, WrapsAroundTheReflexCornerOfAnL) {
    // The L of unit cells: x in [0, 1] up to y = 3, y in [0, 1] out to x = 3. From the top of one arm to the end of
    // the other, the shortest path bends at the reflex corner (1, 1), on the boundary: not a geodesic.
    const TriangleMesh arrays = flat_cell_polygon(l_shape_cells(), 4);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const Eigen::Vector3d from(0.5, 2.75, 0.0), to(2.75, 0.5, 0.0), corner(1.0, 1.0, 0.0);
    const std::vector<int> path = edge_path(mesh, nearest_vertex(mesh, from), nearest_vertex(mesh, to));
    const auto result = geodesic::straighten_path(mesh, path, pins(mesh));
    EXPECT_EQ(result.status, StraightenStatus::bends_at_boundary);
    EXPECT_EQ(result.vertex, nearest_vertex(mesh, corner));
    EXPECT_NEAR(result.length, (corner - from).norm() + (to - corner).norm(), 1e-12);
}

TEST(StraightenPath, OneEdgeIsItself) {
    const geodesic::Mesh mesh = flat_grid(2, 2, 1.0, 1.0).to_mesh();
    const auto result = geodesic::straighten_path(mesh, {0, 1, 0, 1}, pins(mesh));
    ASSERT_EQ(result.path.size(), 2u);
    EXPECT_EQ(result.path[0], SurfacePoint::at_vertex(0));
    EXPECT_EQ(result.path[1], SurfacePoint::at_vertex(1));
    EXPECT_DOUBLE_EQ(result.length, 0.5);
}

TEST(StraightenPath, RefusesBadPaths) {
    const geodesic::Mesh mesh = flat_grid(4, 4, 1.0, 1.0).to_mesh();
    EXPECT_THROW(geodesic::straighten_path(mesh, {0, 1, 2}, std::vector<unsigned char>(3, 0)), InvalidInput);
    EXPECT_THROW(geodesic::straighten_path(mesh, {0, 2}, pins(mesh)), InvalidInput);       // no edge
    EXPECT_THROW(geodesic::straighten_path(mesh, {0, 1, 0}, pins(mesh)), InvalidInput);    // no two ends
    EXPECT_THROW(geodesic::straighten_path(mesh, {0, 1, 6, 7}, pins(mesh, {6})), InvalidInput);  // pinned inside
    EXPECT_THROW(geodesic::straighten_path(mesh, {0, 99}, pins(mesh)), InvalidInput);
}

}  // namespace
}  // namespace geotri::test

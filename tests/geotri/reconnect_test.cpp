// Small polygon reconnection: on the G of a cube and of a box, where the polygons unfold into the plane and the best
// triangulation follows from planar geometry (an enumeration of every triangulation, sharing no code with the
// operator); refusals that leave G unchanged; and every vertex star of traced and flipped G on real meshes, checked
// with validate() (with the overlay and the patch areas).

#include <geodesic/errors.h>
#include <geotri/flip.h>
#include <geotri/reconnect.h>
#include <geotri/split.h>
#include <geotri/trace.h>
#include <geotri/untangle_and_flip.h>
#include <geotri/validate.h>
#include <geotri_test/fine_mesh.h>
#include <geotri_test/g_checks.h>
#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace geotri {
namespace {

using OpenMesh::FaceHandle;
using OpenMesh::VertexHandle;
using test::describe;
using test::expect_valid_with_area;
using test::unit_cube_g;

constexpr double k_pi = 3.14159265358979323846;

/// The coarse face of G with exactly these three corners (cube corner numbers), or an invalid handle.
FaceHandle face_with(const GeodesicTriangulation& g, std::array<int, 3> corners) {
    std::sort(corners.begin(), corners.end());
    for (FaceHandle f : g.coarse().faces()) {
        std::array<int, 3> mine{};
        int i = 0;
        for (VertexHandle v : g.coarse().fv_range(f)) mine[static_cast<std::size_t>(i++)] = v.idx();
        std::sort(mine.begin(), mine.end());
        if (mine == corners) return f;
    }
    return FaceHandle();
}

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

/// Whether the segment between corners p and q of the simple polygon `points` (counter-clockwise) is a diagonal
/// inside it: it passes through no other corner, crosses no side, and its midpoint is inside.
bool inside_diagonal(const std::vector<Eigen::Vector2d>& points, std::size_t p, std::size_t q) {
    const std::size_t k = points.size();
    const Eigen::Vector2d a = points[p], b = points[q];
    for (std::size_t r = 0; r < k; ++r) {
        if (r == p || r == q) continue;
        const double t = (points[r] - a).dot(b - a) / (b - a).squaredNorm();
        if (t > 0.0 && t < 1.0 && std::abs(cross(b - a, points[r] - a)) < 1e-12) return false;
    }
    for (std::size_t r = 0; r < k; ++r) {
        const std::size_t s = (r + 1) % k;
        if (r == p || r == q || s == p || s == q) continue;
        const Eigen::Vector2d c = points[r], d = points[s];
        if (cross(b - a, c - a) * cross(b - a, d - a) < 0.0 && cross(d - c, a - c) * cross(d - c, b - c) < 0.0)
            return false;
    }
    const Eigen::Vector2d mid = 0.5 * (a + b);
    bool in = false;
    for (std::size_t r = 0; r < k; ++r) {
        const Eigen::Vector2d c = points[r], d = points[(r + 1) % k];
        if ((c.y() > mid.y()) != (d.y() > mid.y()) && mid.x() < c.x() + (mid.y() - c.y()) / (d.y() - c.y()) * (d.x() - c.x()))
            in = !in;
    }
    return in;
}

/// The largest smallest angle over every triangulation of the simple planar polygon `points` (counter-clockwise)
/// by inside diagonals, by plain recursion over the triangle on each diagonal, with no zero angle.
double best_planar_triangulation(const std::vector<Eigen::Vector2d>& points) {
    auto angle = [&](std::size_t at, std::size_t p, std::size_t q) {
        const Eigen::Vector2d u = points[p] - points[at], v = points[q] - points[at];
        return std::atan2(std::abs(cross(u, v)), u.dot(v));
    };
    std::function<double(std::size_t, std::size_t)> best = [&](std::size_t i, std::size_t j) -> double {
        if (j == i + 1) return std::numeric_limits<double>::infinity();
        if (!(i == 0 && j == points.size() - 1) && !inside_diagonal(points, i, j)) return -1.0;
        double result = -1.0;
        for (std::size_t m = i + 1; m < j; ++m) {
            const double smallest = std::min({angle(i, m, j), angle(m, j, i), angle(j, i, m)});
            if (smallest < 1e-9 || cross(points[m] - points[i], points[j] - points[i]) <= 0.0) continue;
            result = std::max(result, std::min({best(i, m), best(m, j), smallest}));
        }
        return result;
    };
    return best(0, points.size() - 1);
}

TEST(Reconnect, removing_the_centre_of_a_cube_side_leaves_the_square_with_one_diagonal) {
    GeodesicTriangulation g = unit_cube_g();
    // Split the diagonal 0-3 of the side z = 0 at the side's centre, then take that vertex out again: the side is
    // a unit square, triangulated by one diagonal of length √2 with corners of 45°, 45° and 90°.
    const auto h = g.coarse().find_halfedge(VertexHandle(0), VertexHandle(3));
    const SplitResult split = split_edge(g, g.coarse().edge_handle(h), 0.5);
    ASSERT_TRUE(split.done) << split.reason;
    ASSERT_EQ(g.coarse().n_faces(), 14u);
    const ReconnectResult r = reconnect_vertex(g, split.vertex);
    ASSERT_TRUE(r.done) << r.reason;
    EXPECT_EQ(r.corners, 4);
    EXPECT_EQ(r.removed_vertices, 1);
    EXPECT_EQ(r.diagonals, 1);
    EXPECT_NEAR(r.min_corner_before, k_pi / 4, 1e-12);  // the centre's four corners are right angles, the others 45°
    EXPECT_NEAR(r.min_corner_after, k_pi / 4, 1e-12);
    EXPECT_EQ(g.coarse().n_faces(), 12u);
    EXPECT_EQ(g.coarse().n_vertices(), 8u);
    int diagonals = 0;
    for (auto e : g.coarse().edges()) {
        const double length = g.length(e);
        if (std::abs(length - std::sqrt(2.0)) < 1e-12) ++diagonals;
        else EXPECT_NEAR(length, 1.0, 1e-12);
    }
    EXPECT_EQ(diagonals, 6);  // one per side
    expect_valid_with_area(g);
}

/// The box [0, a] x [0, 1] x [0, 1] (a lattice of 13 x 5 x 5 squares) with G made like unit_cube_g()'s: its
/// eight corners (corner k at (a·(k & 1), k >> 1 & 1, k >> 2 & 1)) and one diagonal per side, traced.
GeodesicTriangulation long_box_g(double a) {
    auto fine = test::fine_of(test::box(a, 1.0, 1.0, 13, 5, 5));
    MeshData data;
    for (int k = 0; k < 8; ++k)
        data.positions.push_back(fine->mesh.position(
            test::nearest_vertex(fine->mesh, Eigen::Vector3d(a * (k & 1), k >> 1 & 1, k >> 2 & 1))));
    data.triangles = {{0, 3, 1}, {0, 2, 3}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                      {2, 7, 3}, {2, 6, 7}, {0, 6, 2}, {0, 4, 6}, {1, 3, 7}, {1, 7, 5}};
    GeodesicTriangulation g(fine, make_coarse_mesh(data, "long box"));
    trace(g);
    return g;
}

TEST(Reconnect, a_polygon_over_a_box_edge_gets_the_best_planar_triangulation) {
    // The box 2.6 x 1 x 1. Face (0, 3, 1) of the side z = 0 is split at p = (1.8, 0.2, 0); then the polygon of two
    // of p's faces, (3, 1, p) and (1, 0, p), and of the side y = 0, (0, 1, 5) and (0, 5, 4), is reconnected. The
    // side y = 0 unfolds about the x axis into the plane of z = 0, so the polygon is the planar hexagon
    // 4 (0, -1), 5 (a, -1), 1 (a, 0), 3 (a, 1), p, 0 (0, 0), reflex at p, and its best triangulation follows from
    // planar geometry.
    const double a = 2.6;
    GeodesicTriangulation g = long_box_g(a);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    const SurfacePoint p =
        SurfacePoint::at_vertex(test::nearest_vertex(g.fine().mesh, Eigen::Vector3d(1.8, 0.2, 0.0)));
    const SplitResult split = split_face(g, face_with(g, {0, 3, 1}), p);
    ASSERT_TRUE(split.done) << split.reason;
    const int pv = split.vertex.idx();
    const std::vector<FaceHandle> faces = {face_with(g, {3, 1, pv}), face_with(g, {1, 0, pv}),
                                           face_with(g, {0, 1, 5}), face_with(g, {0, 5, 4})};
    for (FaceHandle f : faces) ASSERT_TRUE(f.is_valid());
    double old_smallest = std::numeric_limits<double>::infinity(), outside_smallest = old_smallest;
    for (FaceHandle f : g.coarse().faces()) {
        const std::array<double, 3> corners = corner_angles(g, f);
        const double smallest = *std::min_element(corners.begin(), corners.end());
        if (std::find(faces.begin(), faces.end(), f) != faces.end()) old_smallest = std::min(old_smallest, smallest);
        else outside_smallest = std::min(outside_smallest, smallest);
    }
    // Counter-clockwise in the (x, y) plane (a mirror image of the polygon seen from outside: the same angles).
    const std::vector<Eigen::Vector2d> hexagon = {{0, -1}, {a, -1}, {a, 0}, {a, 1}, {1.8, 0.2}, {0, 0}};
    const double expected = best_planar_triangulation(hexagon);
    ASSERT_GT(expected, old_smallest + 1e-3);  // so that the test tells the best triangulation from the old one

    const ReconnectResult r = reconnect_polygon(g, faces);
    ASSERT_TRUE(r.done) << r.reason;
    EXPECT_EQ(r.corners, 6);
    EXPECT_EQ(r.removed_vertices, 0);
    EXPECT_EQ(r.diagonals, 3);
    EXPECT_NEAR(r.min_corner_before, old_smallest, 1e-12);
    EXPECT_NEAR(r.min_corner_after, expected, 1e-12);
    EXPECT_EQ(g.coarse().n_faces(), 14u);
    expect_valid_with_area(g);
    double smallest = std::numeric_limits<double>::infinity();
    for (FaceHandle f : g.coarse().faces())
        for (double c : corner_angles(g, f)) smallest = std::min(smallest, c);
    EXPECT_NEAR(smallest, std::min(expected, outside_smallest), 1e-12);
    std::cout << "[ reconnect ] box hexagon: smallest corner " << r.min_corner_before * 180 / k_pi << " -> "
              << r.min_corner_after * 180 / k_pi << " deg (planar oracle " << expected * 180 / k_pi << ")\n";
}

TEST(Reconnect, a_required_gain_that_no_triangulation_reaches_is_refused_and_g_is_unchanged) {
    GeodesicTriangulation g = unit_cube_g();
    const GeodesicTriangulation before = g;
    // The side z = 0: both of its triangulations have 45° corners.
    ReconnectOptions options;
    options.required_gain = 1e-9;
    const ReconnectResult r = reconnect_polygon(g, {face_with(g, {0, 3, 1}), face_with(g, {0, 2, 3})}, options);
    EXPECT_FALSE(r.done);
    EXPECT_NE(r.reason.find("raises"), std::string::npos) << r.reason;
    for (auto e : g.coarse().edges()) EXPECT_EQ(g.polyline(e), before.polyline(e));
}

TEST(Reconnect, faces_that_are_not_one_disk_are_refused) {
    GeodesicTriangulation g = unit_cube_g();
    // Two faces that share only corner 0 make no disk with a simple polygon around it; two faces far apart make
    // two polygons; all twelve have no boundary.
    const ReconnectResult touching = reconnect_polygon(g, {face_with(g, {0, 3, 1}), face_with(g, {0, 6, 2})});
    EXPECT_FALSE(touching.done);
    EXPECT_FALSE(touching.reason.empty());
    const ReconnectResult apart = reconnect_polygon(g, {face_with(g, {0, 3, 1}), face_with(g, {4, 7, 6})});
    EXPECT_FALSE(apart.done);
    EXPECT_NE(apart.reason.find("not connected"), std::string::npos) << apart.reason;
    EXPECT_FALSE(apart.reason.empty());
    std::vector<FaceHandle> all(g.coarse().faces().begin(), g.coarse().faces().end());
    const ReconnectResult whole = reconnect_polygon(g, all);
    EXPECT_FALSE(whole.done);
    EXPECT_NE(whole.reason.find("no boundary"), std::string::npos) << whole.reason;
    ReconnectOptions small;
    small.max_corners = 5;
    const ReconnectResult big = reconnect_vertex(g, VertexHandle(0), small);  // six corners
    EXPECT_FALSE(big.done);
    EXPECT_NE(big.reason.find("6 corners"), std::string::npos) << big.reason;
    EXPECT_EQ(g.coarse().n_faces(), 12u);
}

TEST(Reconnect, a_tetrahedron_cannot_lose_a_vertex) {
    auto fine = test::fine_of(test::cube(4));
    MeshData data;
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(1, 0, 1),
                                    Eigen::Vector3d(0, 1, 1)})
        data.positions.push_back(fine->mesh.position(test::nearest_vertex(fine->mesh, x)));
    data.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
    GeodesicTriangulation g(fine, make_coarse_mesh(data, "tetrahedron"));
    trace(g);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    for (VertexHandle v : g.coarse().vertices()) {
        const ReconnectResult r = reconnect_vertex(g, v);
        EXPECT_FALSE(r.done);
        EXPECT_NE(r.reason.find("fewer than three"), std::string::npos) << r.reason;
    }
    EXPECT_EQ(g.coarse().n_faces(), 4u);
    expect_valid_with_area(g);
}

TEST(Reconnect, handles_that_are_not_in_g_are_invalid_input) {
    GeodesicTriangulation g = unit_cube_g();
    EXPECT_THROW(reconnect_vertex(g, VertexHandle()), InvalidInput);
    EXPECT_THROW(reconnect_vertex(g, VertexHandle(8)), InvalidInput);
    EXPECT_THROW(reconnect_polygon(g, {FaceHandle(12)}), InvalidInput);
}

/// Reconnects the star of every `stride`-th vertex of g, each on its own copy, with the local checks only (no
/// validate() inside): each one is either done, with G valid (and the patch areas summing to T's area) and one
/// vertex fewer, or refused with G unchanged.
void check_every_vertex_removal(const GeodesicTriangulation& g, const std::string& name, int stride) {
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    ReconnectOptions local;
    local.check_validity = false;
    int done = 0, tried = 0;
    for (VertexHandle v : g.coarse().vertices()) {
        if (v.idx() % stride != 0) continue;
        ++tried;
        GeodesicTriangulation copy = g;
        const ReconnectResult r = reconnect_vertex(copy, v, local);
        if (!r.done) {
            EXPECT_FALSE(r.reason.empty());
            EXPECT_EQ(copy.coarse().n_faces(), g.coarse().n_faces()) << r.reason;
            continue;
        }
        ++done;
        SCOPED_TRACE(name + ", vertex " + std::to_string(v.idx()));
        EXPECT_EQ(copy.coarse().n_faces(), g.coarse().n_faces() - 2);
        EXPECT_EQ(r.diagonals, r.corners - 3);
        EXPECT_GT(r.min_corner_after, 0.0);
        expect_valid_with_area(copy);
    }
    std::cout << "[ reconnect ] " << name << ", " << g.coarse().n_faces() << " coarse faces: " << done << " of "
              << tried << " vertex removals done\n";
    EXPECT_GT(done, tried / 2);
}

/// Reconnects, on its own copy of g, the polygon of every `stride`-th face and its three neighbours, asking for a
/// higher smallest corner, with the local checks only: each one is either done, with G valid and the smallest
/// corner of the polygon higher, or refused with G unchanged.
void check_every_face_polygon(const GeodesicTriangulation& g, const std::string& name, int stride) {
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    ReconnectOptions options;
    options.check_validity = false;
    options.required_gain = 1e-9;
    int done = 0, tried = 0;
    double gain = 0.0;
    for (FaceHandle f : g.coarse().faces()) {
        if (f.idx() % stride != 0) continue;
        ++tried;
        std::vector<FaceHandle> faces{f};
        for (FaceHandle n : g.coarse().ff_range(f)) faces.push_back(n);
        GeodesicTriangulation copy = g;
        const ReconnectResult r = reconnect_polygon(copy, faces, options);
        if (!r.done) {
            EXPECT_EQ(copy.coarse().n_faces(), g.coarse().n_faces()) << r.reason;
            for (auto e : copy.coarse().edges()) EXPECT_EQ(copy.polyline(e), g.polyline(e));
            continue;
        }
        ++done;
        SCOPED_TRACE(name + ", face " + std::to_string(f.idx()));
        // A vertex of valence three at a corner of the face is inside the polygon, and goes.
        EXPECT_EQ(copy.coarse().n_faces(), g.coarse().n_faces() - 2 * static_cast<std::size_t>(r.removed_vertices));
        EXPECT_GT(r.min_corner_after, r.min_corner_before);
        gain = std::max(gain, r.min_corner_after - r.min_corner_before);
        expect_valid_with_area(copy);
    }
    std::cout << "[ reconnect ] " << name << ": " << done << " of " << tried
              << " face polygons reconnected to a higher smallest corner (largest gain " << gain * 180 / k_pi
              << " deg)\n";
    EXPECT_GT(done, 0);
}

TEST(Reconnect, reconnections_of_a_traced_bundled_mesh_leave_g_valid_or_are_refused) {
    auto fine = std::make_shared<const FineMesh>(load_fine_mesh(std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply"));
    GeodesicTriangulation g(fine, test::decimated_coarse(*fine, 100));
    trace(g);
    check_every_vertex_removal(g, "bob_small", 1);
    check_every_face_polygon(g, "bob_small", 1);
}

TEST(Reconnect, reconnections_of_a_flipped_vertebra_leave_g_valid_or_are_refused) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir()
                     << "': the real-mesh reconnection test needs them";
    auto fine = std::make_shared<const FineMesh>(
        load_fine_mesh(test::shared_mesh("anatomy/lumbar_vertebra_mean_2nd.ply").path));
    GeodesicTriangulation g(fine, test::decimated_coarse(*fine, 320));
    trace(g);
    untangle_and_flip(g);
    check_every_vertex_removal(g, "lumbar vertebra", 5);  // every fifth: each check builds the overlay
    check_every_face_polygon(g, "lumbar vertebra", 5);
}

}  // namespace
}  // namespace geotri

// Vertex relocation: on the cube's G, where the retraced geodesics' lengths follow from unfolding; the
// checked move leaves G valid or unchanged, judged on all of G or, inside the vertex's star, by local checks (on
// the cube and on a real mesh, with validate() as the judge); refusals; and the vertices of T that untangling tries.

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/mesh_io.h>
#include <geotri/relocate.h>
#include <geotri/trace.h>
#include <geotri/untangle_and_flip.h>
#include <geotri/validate.h>

#include <geotri_test/g_checks.h>
#include <geotri_test/procedural_meshes.h>

#include "ops/with_workspace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <set>

namespace geotri {
namespace {

using OpenMesh::VertexHandle;
using test::describe;
using test::expect_valid_with_area;
using test::unit_cube_g;

TEST(Relocate, corner_of_the_cube_moved_along_an_edge_gives_the_unfolded_lengths) {
    GeodesicTriangulation g = unit_cube_g();
    const geodesic::Mesh& mesh = g.fine().mesh;
    // Corner 0 goes from the origin to (1/4, 0, 0), a vertex of the 4 x 4 grid. Its neighbours, corner k at
    // (k & 1, k >> 1 & 1, k >> 2 & 1), are then at these distances: on one side of the cube, straight; to corner 6
    // at (0, 1, 1), across the sides z = 0 and x = 0 unfolded into one plane: from (1/4, 0) to (-1, 1).
    const std::map<int, double> expected = {{1, 0.75},           {2, std::sqrt(1.0625)}, {3, 1.25},
                                            {4, std::sqrt(1.0625)}, {5, 1.25},           {6, std::sqrt(2.5625)}};
    const int target = test::nearest_vertex(mesh, Eigen::Vector3d(0.25, 0.0, 0.0));
    RelocateOptions unchecked;
    unchecked.check_validity = false;
    const RelocateResult r = relocate_vertex(g, VertexHandle(0), SurfacePoint::at_vertex(target), unchecked);
    ASSERT_TRUE(r.done) << r.reason;
    EXPECT_EQ(g.location(VertexHandle(0)), SurfacePoint::at_vertex(target));
    std::set<int> neighbours;
    for (VertexHandle u : g.coarse().vv_range(VertexHandle(0))) {
        neighbours.insert(u.idx());
        const double length = g.length(g.coarse().edge_handle(g.coarse().find_halfedge(VertexHandle(0), u)));
        ASSERT_TRUE(expected.count(u.idx()));
        EXPECT_NEAR(length, expected.at(u.idx()), 1e-12) << "to corner " << u.idx();
    }
    EXPECT_EQ(neighbours.size(), expected.size());
    EXPECT_EQ(validate(g).violation_count[0], 0) << describe(validate(g));
}

TEST(Relocate, checked_moves_on_the_cube_leave_g_valid_or_unchanged) {
    const GeodesicTriangulation cube = unit_cube_g();
    int done = 0, refused = 0;
    for (VertexHandle v : cube.coarse().vertices()) {
        for (int to : nearby_fine_vertices(cube, v, 1)) {
            GeodesicTriangulation g = cube;
            const RelocateResult r = relocate_vertex(g, v, SurfacePoint::at_vertex(to));
            if (r.done) {
                ++done;
                SCOPED_TRACE("corner " + std::to_string(v.idx()) + " to fine vertex " + std::to_string(to));
                expect_valid_with_area(g);
            } else {
                ++refused;
                EXPECT_FALSE(r.reason.empty());
                EXPECT_EQ(g.location(v), cube.location(v));
                for (auto e : g.coarse().edges()) EXPECT_EQ(g.polyline(e), cube.polyline(e));
            }
        }
    }
    std::cout << "[ relocate ] cube: " << done << " moves done, " << refused << " refused\n";
    EXPECT_GT(done, 0);
}

TEST(Relocate, moves_that_would_break_g_are_refused_and_bad_vertices_are_invalid_input) {
    GeodesicTriangulation g = unit_cube_g();
    const RelocateResult r = relocate_vertex(g, VertexHandle(0), g.location(VertexHandle(7)));
    EXPECT_FALSE(r.done);
    EXPECT_NE(r.reason.find("coarse vertex 7 is there"), std::string::npos) << r.reason;
    // Next to the opposite corner, 7, corner 0's geodesics would cross those of 7's fan: refused, G unchanged.
    const GeodesicTriangulation before = g;
    const int far = test::nearest_vertex(g.fine().mesh, Eigen::Vector3d(0.75, 0.75, 1.0));
    const RelocateResult across = relocate_vertex(g, VertexHandle(0), SurfacePoint::at_vertex(far));
    EXPECT_FALSE(across.done);
    EXPECT_NE(across.reason.find("not valid"), std::string::npos) << across.reason;
    EXPECT_EQ(g.location(VertexHandle(0)), before.location(VertexHandle(0)));
    for (auto e : g.coarse().edges()) EXPECT_EQ(g.polyline(e), before.polyline(e));
    EXPECT_THROW(relocate_vertex(g, VertexHandle(), g.location(VertexHandle(7))), InvalidInput);
    EXPECT_THROW(relocate_vertex(g, VertexHandle(8), g.location(VertexHandle(7))), InvalidInput);
}

TEST(Relocate, in_star_the_corner_of_the_cube_moved_along_an_edge_gives_the_unfolded_lengths) {
    GeodesicTriangulation g = unit_cube_g();
    // As in the first test: corner 0 to (1/4, 0, 0), inside its star; the local checks accept it.
    const int target = test::nearest_vertex(g.fine().mesh, Eigen::Vector3d(0.25, 0.0, 0.0));
    const RelocateResult r = relocate_vertex_in_star(g, VertexHandle(0), SurfacePoint::at_vertex(target));
    ASSERT_TRUE(r.done) << r.reason;
    const std::map<int, double> expected = {{1, 0.75},           {2, std::sqrt(1.0625)}, {3, 1.25},
                                            {4, std::sqrt(1.0625)}, {5, 1.25},           {6, std::sqrt(2.5625)}};
    for (VertexHandle u : g.coarse().vv_range(VertexHandle(0))) {
        const double length = g.length(g.coarse().edge_handle(g.coarse().find_halfedge(VertexHandle(0), u)));
        EXPECT_NEAR(length, expected.at(u.idx()), 1e-12) << "to corner " << u.idx();
    }
    expect_valid_with_area(g);
}

/// Moves every coarse vertex of `given` to each vertex of T within `rings` edges with relocate_vertex_in_star(),
/// and checks that each move done leaves G valid (validate(), overlay included) and each refused one leaves it as
/// it was; returns the moves done and refused.
std::pair<int, int> check_moves_in_star(const GeodesicTriangulation& given, int rings) {
    int done = 0, refused = 0;
    geodesic::ExactGeodesic propagation(given.fine().mesh);
    const Workspace workspace = propagation_only(propagation);
    for (VertexHandle v : given.coarse().vertices()) {
        for (int to : nearby_fine_vertices(given, v, rings)) {
            GeodesicTriangulation g = given;
            const RelocateResult r = relocate_vertex_in_star(g, v, SurfacePoint::at_vertex(to), workspace);
            SCOPED_TRACE("coarse vertex " + std::to_string(v.idx()) + " to fine vertex " + std::to_string(to));
            if (r.done) {
                ++done;
                expect_valid_with_area(g);
            } else {
                ++refused;
                EXPECT_FALSE(r.reason.empty());
                EXPECT_EQ(g.location(v), given.location(v));
                for (auto e : g.coarse().edges()) EXPECT_EQ(g.polyline(e), given.polyline(e));
            }
        }
    }
    return {done, refused};
}

TEST(Relocate, moves_in_star_on_the_cube_leave_g_valid_or_unchanged) {
    const auto [done, refused] = check_moves_in_star(unit_cube_g(), 3);
    std::cout << "[ relocate ] cube, in star: " << done << " moves done, " << refused << " refused\n";
    // Three rings reach past the stars of the corners (four fine edges to the next corner): both happen.
    EXPECT_GT(done, 0);
    EXPECT_GT(refused, 0);
}

TEST(Relocate, moves_in_star_on_bundled_bob_leave_g_valid_or_unchanged) {
    const std::string path = std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply";
    auto fine = std::make_shared<const FineMesh>(load_fine_mesh(path));
    GeodesicTriangulation g(fine, test::decimated_coarse(*fine, 60));
    trace(g);
    untangle_and_flip(g);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    const auto [done, refused] = check_moves_in_star(g, 2);
    std::cout << "[ relocate ] bob_small at 60 faces, flipped, in star: " << done << " moves done, " << refused
              << " refused\n";
    EXPECT_GT(done, 0);
}

TEST(Relocate, moves_in_star_onto_a_neighbour_or_out_of_the_star_are_refused) {
    GeodesicTriangulation g = unit_cube_g();
    const GeodesicTriangulation before = g;
    const RelocateResult onto = relocate_vertex_in_star(g, VertexHandle(0), g.location(VertexHandle(1)));
    EXPECT_FALSE(onto.done);
    EXPECT_NE(onto.reason.find("coarse vertex 1 is there"), std::string::npos) << onto.reason;
    const RelocateResult same = relocate_vertex_in_star(g, VertexHandle(0), g.location(VertexHandle(0)));
    EXPECT_FALSE(same.done);
    // Next to the opposite corner: the geodesics from there reach corner 0's ring from outside its star.
    const int far = test::nearest_vertex(g.fine().mesh, Eigen::Vector3d(0.75, 0.75, 1.0));
    const RelocateResult across = relocate_vertex_in_star(g, VertexHandle(0), SurfacePoint::at_vertex(far));
    EXPECT_FALSE(across.done);
    EXPECT_FALSE(across.reason.empty());
    EXPECT_EQ(g.location(VertexHandle(0)), before.location(VertexHandle(0)));
    for (auto e : g.coarse().edges()) EXPECT_EQ(g.polyline(e), before.polyline(e));
    EXPECT_THROW(relocate_vertex_in_star(g, VertexHandle(8), g.location(VertexHandle(7))), InvalidInput);
}

TEST(Relocate, nearby_fine_vertices_come_ring_by_ring_without_coarse_vertices) {
    const GeodesicTriangulation g = unit_cube_g();
    const geodesic::Mesh& mesh = g.fine().mesh;
    const int corner = g.location(VertexHandle(0)).vertex;
    std::set<int> ring1;
    for (int h : mesh.outgoing_halfedges(corner)) ring1.insert(mesh.head(h));
    const std::vector<int> one = nearby_fine_vertices(g, VertexHandle(0), 1);
    EXPECT_EQ(std::set<int>(one.begin(), one.end()), ring1);
    const std::vector<int> two = nearby_fine_vertices(g, VertexHandle(0), 2);
    ASSERT_GT(two.size(), one.size());
    // The first ring first, then the second; no vertex twice, and never the corner itself.
    EXPECT_EQ(std::vector<int>(two.begin(), two.begin() + static_cast<long>(one.size())), one);
    EXPECT_EQ(std::set<int>(two.begin(), two.end()).size(), two.size());
    EXPECT_EQ(std::count(two.begin(), two.end(), corner), 0);
    // Coarse vertices' locations are left out: corner 1 is four fine edges from corner 0 along the cube's edge, and
    // its fine neighbour at (3/4, 0, 0) is within three rings, so four rings would reach corner 1.
    const int before_corner_1 = test::nearest_vertex(mesh, Eigen::Vector3d(0.75, 0.0, 0.0));
    const std::vector<int> three = nearby_fine_vertices(g, VertexHandle(0), 3);
    EXPECT_EQ(std::count(three.begin(), three.end(), before_corner_1), 1);
    const std::vector<int> four = nearby_fine_vertices(g, VertexHandle(0), 4);
    EXPECT_GT(four.size(), three.size());
    for (VertexHandle u : g.coarse().vertices())
        EXPECT_EQ(std::count(four.begin(), four.end(), g.location(u).vertex), 0) << "coarse vertex " << u.idx();
    EXPECT_THROW(nearby_fine_vertices(g, VertexHandle(8), 1), InvalidInput);
}

}  // namespace
}  // namespace geotri

// Edge collapse: on the cube's G, where the new geodesics' lengths follow from unfolding; refusals that
// keep the topology; and every collapse of traced G on real meshes, checked with validate() (with the overlay and
// the patch areas).

#include <geodesic/errors.h>
#include <geotri/collapse.h>
#include <geotri/decimate.h>
#include <geotri/fine_mesh.h>
#include <geotri/trace.h>
#include <geotri/untangle_and_flip.h>
#include <geotri/validate.h>
#include <geotri_test/fine_mesh.h>
#include <geotri_test/g_checks.h>
#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

namespace geotri {
namespace {

using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;
using test::describe;
using test::expect_valid_with_area;
using test::unit_cube_g;

/// The position on T of coarse vertex v.
Eigen::Vector3d position_of(const GeodesicTriangulation& g, VertexHandle v) { return g.fine().mesh.point(g.location(v)); }

/// Coarse vertex of G at `x` (the cube's corners), or an invalid handle.
VertexHandle vertex_at(const GeodesicTriangulation& g, const Eigen::Vector3d& x) {
    for (VertexHandle v : g.coarse().vertices())
        if ((position_of(g, v) - x).norm() < 1e-12) return v;
    return VertexHandle();
}

TEST(Collapse, corner_of_the_cube_onto_its_neighbour_gives_the_unfolded_lengths) {
    GeodesicTriangulation g = unit_cube_g();
    // Corner 0 at the origin goes onto corner 1 at (1, 0, 0). Its faces (0, 3, 1) and (0, 1, 5) go, and corner 1
    // is joined to corner 0's other neighbours: 2 at (0, 1, 0) and 4 at (0, 0, 1) across one side of the cube
    // (length √2), and 6 at (0, 1, 1), the opposite corner of two sides unfolded into a 1 x 2 rectangle (√5).
    const auto h = g.coarse().find_halfedge(VertexHandle(0), VertexHandle(1));
    ASSERT_TRUE(h.is_valid());
    CollapseOptions unchecked;
    unchecked.check_validity = false;
    const std::size_t faces = g.coarse().n_faces();
    const CollapseResult r = collapse_edge(g, h, unchecked);
    ASSERT_TRUE(r.done) << r.reason;
    EXPECT_EQ(r.retraced, 3);
    EXPECT_EQ(g.coarse().n_faces(), faces - 2);
    EXPECT_EQ(g.coarse().n_vertices(), 7u);
    EXPECT_LT((position_of(g, r.kept) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);
    const std::pair<Eigen::Vector3d, double> expected[] = {
        {{0, 1, 0}, std::sqrt(2.0)}, {{0, 0, 1}, std::sqrt(2.0)}, {{0, 1, 1}, std::sqrt(5.0)}};
    for (const auto& [x, length] : expected) {
        const VertexHandle u = vertex_at(g, x);
        ASSERT_TRUE(u.is_valid());
        const auto kept_u = g.coarse().find_halfedge(r.kept, u);
        ASSERT_TRUE(kept_u.is_valid()) << "corner 1 is not joined to " << x.transpose();
        EXPECT_NEAR(g.length(g.coarse().edge_handle(kept_u)), length, 1e-12);
    }
    // Every polyline is still the exact geodesic between its ends (condition 1), whatever the other conditions say.
    EXPECT_EQ(validate(g).violation_count[0], 0) << describe(validate(g));
}

TEST(Collapse, checked_collapses_of_the_cube_leave_g_valid_or_unchanged) {
    const GeodesicTriangulation cube = unit_cube_g();
    int done = 0, refused = 0;
    for (HalfedgeHandle h : cube.coarse().halfedges()) {
        GeodesicTriangulation g = cube;
        const CollapseResult r = collapse_edge(g, h);
        if (r.done) {
            ++done;
            SCOPED_TRACE("halfedge " + std::to_string(h.idx()));
            expect_valid_with_area(g);
            EXPECT_EQ(g.coarse().n_vertices(), 7u);
        } else {
            ++refused;
            EXPECT_FALSE(r.reason.empty());
            EXPECT_EQ(g.coarse().n_vertices(), 8u);
            for (auto e : g.coarse().edges()) EXPECT_EQ(g.polyline(e), cube.polyline(e));
        }
    }
    std::cout << "[ collapse ] cube: " << done << " done, " << refused << " refused\n";
    EXPECT_GT(done, 0);
}

TEST(Collapse, a_tetrahedron_cannot_lose_a_vertex) {
    // Four alternate corners of the cube: a regular tetrahedron, the coarsest triangulation of a sphere.
    auto fine = test::fine_of(test::cube(4));
    MeshData data;
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(1, 0, 1),
                                    Eigen::Vector3d(0, 1, 1)})
        data.positions.push_back(fine->mesh.position(test::nearest_vertex(fine->mesh, x)));
    data.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
    GeodesicTriangulation g(fine, make_coarse_mesh(data, "tetrahedron"));
    trace(g);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    CollapseOptions unchecked;
    unchecked.check_validity = false;
    for (HalfedgeHandle h : g.coarse().halfedges()) {
        const CollapseResult r = collapse_edge(g, h, unchecked);
        EXPECT_FALSE(r.done);
        EXPECT_FALSE(r.reason.empty());
    }
    EXPECT_EQ(g.coarse().n_faces(), 4u);
}

TEST(Collapse, a_halfedge_that_is_not_in_g_is_invalid_input) {
    GeodesicTriangulation g = unit_cube_g();
    EXPECT_THROW(collapse_edge(g, HalfedgeHandle()), InvalidInput);
    EXPECT_THROW(collapse_edge(g, HalfedgeHandle(static_cast<int>(g.coarse().n_halfedges()))), InvalidInput);
}

/// Collapses every `stride`-th halfedge of g, each on its own copy, with the validity check: each one is either
/// done and G valid (with the patch areas summing to T's area), or refused and G unchanged.
void check_every_collapse(const GeodesicTriangulation& g, const std::string& name, int stride) {
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    int done = 0, tried = 0;
    for (HalfedgeHandle h : g.coarse().halfedges()) {
        if (h.idx() % stride != 0) continue;
        ++tried;
        GeodesicTriangulation copy = g;
        const CollapseResult r = collapse_edge(copy, h);
        if (!r.done) {
            EXPECT_EQ(copy.coarse().n_faces(), g.coarse().n_faces()) << r.reason;
            continue;
        }
        ++done;
        SCOPED_TRACE(name + ", halfedge " + std::to_string(h.idx()));
        EXPECT_EQ(copy.coarse().n_faces(), g.coarse().n_faces() - 2);
        expect_valid_with_area(copy);
    }
    std::cout << "[ collapse ] " << name << ", " << g.coarse().n_faces() << " coarse faces: " << done << " of " << tried
              << " collapses done (the others would leave G invalid)\n";
    EXPECT_GT(done, tried / 2);
}

TEST(Collapse, every_collapse_of_a_traced_bundled_mesh_leaves_g_valid_or_is_refused) {
    auto fine = std::make_shared<const FineMesh>(load_fine_mesh(std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply"));
    GeodesicTriangulation g(fine, test::decimated_coarse(*fine, 100));
    trace(g);
    check_every_collapse(g, "bob_small", 1);
}

TEST(Collapse, collapses_of_a_traced_vertebra_leave_g_valid_or_are_refused) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir()
                     << "': the real-mesh collapse test needs them";
    auto fine = std::make_shared<const FineMesh>(
        load_fine_mesh(test::shared_mesh("anatomy/lumbar_vertebra_mean_2nd.ply").path));
    GeodesicTriangulation g(fine, test::decimated_coarse(*fine, 320));
    trace(g);
    untangle_and_flip(g);  // the traced G is not valid at this size; flips make it so
    check_every_collapse(g, "lumbar vertebra", 7);  // every seventh: each check builds the overlay
}

}  // namespace
}  // namespace geotri

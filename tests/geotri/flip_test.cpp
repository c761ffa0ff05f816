// Flips of coarse edges and untangle_and_flip(): hand-made G on a procedural cube and sphere, checked
// against closed forms and validate(); and traced G on real meshes, checked with validate() after every change.

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/decimate.h>
#include <geotri/edge_paths_io.h>
#include <geotri/fine_mesh.h>
#include <geotri/flip.h>
#include <geotri/refine.h>
#include <geotri/trace.h>
#include <geotri/untangle_and_flip.h>
#include <geotri/validate.h>
#include <geotri_test/fine_mesh.h>
#include <geotri_test/g_checks.h>
#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace geotri {
namespace {

using geodesic::Mesh;
using geodesic::SurfacePoint;
using test::decimated_coarse;
using test::describe;
using test::expect_same_polylines;
using test::expect_valid_with_area;
using test::fine_of;
using test::nearest_vertex;
using OpenMesh::EdgeHandle;
using OpenMesh::VertexHandle;

constexpr double pi = 3.14159265358979323846;

/// G with coarse vertices at the fine vertices nearest to `corners`, the given triangles (turned to face away from
/// `centre`), traced by trace().
GeodesicTriangulation make_g(std::shared_ptr<const FineMesh> fine, const std::vector<Eigen::Vector3d>& corners,
                             std::vector<std::array<int, 3>> triangles, const Eigen::Vector3d& centre) {
    MeshData data;
    for (const Eigen::Vector3d& x : corners) data.positions.push_back(fine->mesh.position(nearest_vertex(fine->mesh, x)));
    for (auto& t : triangles) {
        const Eigen::Vector3d &a = data.positions[t[0]], &b = data.positions[t[1]], &c = data.positions[t[2]];
        if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - centre) < 0.0) std::swap(t[1], t[2]);
    }
    data.triangles = triangles;
    GeodesicTriangulation g(fine, make_coarse_mesh(data, "hand-made"));
    trace(g);
    return g;
}

/// The unit cube's eight corners (corner k at (k & 1, k >> 1 & 1, k >> 2 & 1)), each side split by a diagonal.
GeodesicTriangulation cube_g(std::shared_ptr<const FineMesh> fine) {
    std::vector<Eigen::Vector3d> corners;
    for (int k = 0; k < 8; ++k) corners.emplace_back(k & 1, k >> 1 & 1, k >> 2 & 1);
    return make_g(fine, corners,
                  {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                   {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}},
                  {0.5, 0.5, 0.5});
}

EdgeHandle edge_between(const CoarseMesh& coarse, int a, int b) {
    const auto h = coarse.find_halfedge(VertexHandle(a), VertexHandle(b));
    return h.is_valid() ? coarse.edge_handle(h) : EdgeHandle();
}

/// Everything that makes G: faces (vertex triples), every edge's ends and polyline, every location.
struct Snapshot {
    std::vector<std::vector<int>> faces;
    std::vector<std::array<int, 2>> ends;
    std::vector<Polyline> polylines;
    std::vector<double> lengths;
    std::vector<SurfacePoint> locations;
    bool operator==(const Snapshot& o) const {
        return faces == o.faces && ends == o.ends && polylines == o.polylines && lengths == o.lengths &&
               locations == o.locations;
    }
};

Snapshot snapshot(const GeodesicTriangulation& g) {
    Snapshot s;
    const CoarseMesh& coarse = g.coarse();
    for (auto f : coarse.faces()) {
        std::vector<int> vs;
        for (auto v : coarse.fv_range(f)) vs.push_back(v.idx());
        s.faces.push_back(vs);
    }
    for (auto e : coarse.edges()) {
        const auto h = coarse.halfedge_handle(e, 0);
        s.ends.push_back({coarse.from_vertex_handle(h).idx(), coarse.to_vertex_handle(h).idx()});
        s.polylines.push_back(g.polyline(e));
        s.lengths.push_back(g.length(e));
    }
    for (auto v : coarse.vertices()) s.locations.push_back(g.location(v));
    return s;
}

int total(const std::array<int, 4>& c) { return c[0] + c[1] + c[2] + c[3]; }

// ---- Corner angles ---------------------------------------------------------------------------------------------

TEST(Flip, corner_angles_of_the_cube_are_its_flat_angles) {
    // Each side of the unit cube is cut by a diagonal into two right isosceles triangles: 90° at the corner where
    // the diagonal does not pass, 45° at its two ends; the corners at a cube corner sum to its cone angle 3π/2.
    auto fine = fine_of(test::cube(4));
    const GeodesicTriangulation g = cube_g(fine);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    const CoarseMesh& coarse = g.coarse();
    for (auto f : coarse.faces()) {
        const std::array<double, 3> angles = corner_angles(g, f);
        int i = 0;
        for (auto h : coarse.fh_range(f)) {
            // The corner at from(h) is between h and the previous halfedge's edge: 90° unless one is a diagonal.
            const auto p = coarse.point(coarse.from_vertex_handle(h));
            const auto q = coarse.point(coarse.to_vertex_handle(h));
            const auto r = coarse.point(coarse.from_vertex_handle(coarse.prev_halfedge_handle(h)));
            const bool diagonal = (q - p).norm() > 1.2 || (r - p).norm() > 1.2;
            EXPECT_NEAR(angles[static_cast<std::size_t>(i)], diagonal ? pi / 4 : pi / 2, 1e-12);
            ++i;
        }
    }
    for (auto v : coarse.vertices()) {
        double sum = 0.0;
        for (auto h : coarse.voh_range(v)) sum += corner_angle(g, h);
        EXPECT_NEAR(sum, 1.5 * pi, 1e-12);
    }
}

// ---- Single flips ----------------------------------------------------------------------------------------------

TEST(Flip, diagonal_of_a_cube_side_flips_to_the_other_diagonal) {
    auto fine = fine_of(test::cube(4));
    GeodesicTriangulation g = cube_g(fine);
    const EdgeHandle e = edge_between(g.coarse(), 0, 3);
    ASSERT_TRUE(e.is_valid());
    const FlipPlan plan = flip(g, e);
    ASSERT_TRUE(plan.accepted()) << plan.reason;
    EXPECT_EQ(std::min(plan.c.idx(), plan.d.idx()), 1);
    EXPECT_EQ(std::max(plan.c.idx(), plan.d.idx()), 2);
    EXPECT_FALSE(edge_between(g.coarse(), 0, 3).is_valid());
    const EdgeHandle flipped = edge_between(g.coarse(), 1, 2);
    ASSERT_TRUE(flipped.is_valid());
    EXPECT_EQ(flipped, e);
    // The other diagonal of the unit square: straight across the side, √2 long.
    EXPECT_NEAR(g.length(flipped), std::sqrt(2.0), 1e-12);
    expect_valid_with_area(g);
    for (double corner : plan.corners) EXPECT_TRUE(std::abs(corner - pi / 4) < 1e-12 || std::abs(corner - pi / 2) < 1e-12) << corner;
}

TEST(Flip, flip_across_a_cube_edge_is_refused_and_g_is_unchanged) {
    // Coarse edge 0-1 runs along a cube edge between the sides z = 0 (face 0,1,3) and y = 0 (face 0,1,5). The
    // shortest geodesic from corner 3 to corner 5 crosses the side x = 1, outside the two patches, where it
    // crosses the polyline 1-7.
    auto fine = fine_of(test::cube(4));
    GeodesicTriangulation g = cube_g(fine);
    const EdgeHandle e = edge_between(g.coarse(), 0, 1);
    ASSERT_TRUE(e.is_valid());
    const Snapshot before = snapshot(g);
    const FlipPlan plan = flip(g, e);
    EXPECT_FALSE(plan.accepted());
    EXPECT_TRUE(plan.refusal == FlipRefusal::leaves_region || plan.refusal == FlipRefusal::bad_corner)
        << to_string(plan.refusal);
    EXPECT_FALSE(plan.reason.empty());
    EXPECT_TRUE(snapshot(g) == before);
    EXPECT_TRUE(validate(g).valid);

    // The oracle: the same flip forced through makes G invalid.
    FlipOptions force;
    force.check_validity = false;
    GeodesicTriangulation forced = g;
    ASSERT_TRUE(flip(forced, e, force).accepted());
    const ValidationReport r = validate(forced, ValidationOptions{false});
    EXPECT_FALSE(r.valid);
    EXPECT_GT(r.violation_count[1] + r.violation_count[2], 0) << describe(r);
}

TEST(Flip, edge_whose_opposite_vertices_are_joined_is_not_flippable) {
    // A tetrahedron: every edge's opposite vertices are already joined.
    auto fine = fine_of(test::icosphere(3));
    const double s = 1.0 / std::sqrt(3.0);
    GeodesicTriangulation g = make_g(fine, {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}},
                                     {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}, {0, 0, 0});
    const Snapshot before = snapshot(g);
    for (auto e : g.coarse().edges()) {
        const FlipPlan plan = flip(g, e);
        EXPECT_EQ(plan.refusal, FlipRefusal::not_flippable);
    }
    EXPECT_TRUE(snapshot(g) == before);
    EXPECT_THROW(plan_flip(g, EdgeHandle(100)), InvalidInput);
}

/// Every edge of G, flipped on a copy: each accepted flip leaves G valid (overlay included) with the area of T,
/// the new edge is the shortest geodesic (its length equals an independent full propagation's distance) unless it
/// is the path inside the two patches, and the corners of the plan are the ones G then has. Returns the number of
/// accepted flips; `region`: how many of them run inside the patches.
int check_every_flip(const GeodesicTriangulation& g, int& region) {
    int accepted = 0;
    region = 0;
    geodesic::ExactGeodesic exact(g.fine().mesh);
    for (auto e : g.coarse().edges()) {
        GeodesicTriangulation copy = g;
        const Snapshot before = snapshot(copy);
        const FlipPlan plan = flip(copy, e);
        if (!plan.accepted()) {
            EXPECT_TRUE(snapshot(copy) == before) << "refused flip of edge " << e.idx() << " changed G";
            continue;
        }
        ++accepted;
        expect_valid_with_area(copy);
        exact.propagate({copy.location(plan.c)});
        const double shortest = exact.distance(copy.location(plan.d));
        if (plan.in_region) {
            // The shortest geodesic leaves the two patches: the path inside them is a longer geodesic.
            ++region;
            EXPECT_GT(copy.length(e), shortest);
        } else {
            EXPECT_NEAR(copy.length(e), shortest, 1e-9 * copy.length(e));
        }
        const CoarseMesh& coarse = copy.coarse();
        const auto cd = coarse.find_halfedge(plan.c, plan.d), dc = coarse.opposite_halfedge_handle(cd);
        // Faces (a,d,c) and (b,c,d): corners at a, d, c, then at b, c, d.
        const auto ad = coarse.find_halfedge(plan.a, plan.d), bc = coarse.find_halfedge(plan.b, plan.c);
        const std::array<double, 6> measured = {corner_angle(copy, ad), corner_angle(copy, dc),
                                                corner_angle(copy, coarse.find_halfedge(plan.c, plan.a)),
                                                corner_angle(copy, bc), corner_angle(copy, cd),
                                                corner_angle(copy, coarse.find_halfedge(plan.d, plan.b))};
        for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(plan.corners[i], measured[i], 1e-12) << "corner " << i;
    }
    return accepted;
}

TEST(Flip, every_accepted_flip_of_a_decimated_sphere_leaves_g_valid) {
    auto fine = fine_of(test::perturbed_sphere(12, 0.02, 3));
    GeodesicTriangulation g(fine, decimated_coarse(*fine, 40));
    trace(g);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    int region = 0;
    const int accepted = check_every_flip(g, region);
    std::cout << "[ flip     ] perturbed sphere, 40 coarse faces: " << accepted << " of " << g.coarse().n_edges()
              << " flips accepted, " << region << " of them inside the two patches\n";
    EXPECT_GT(accepted, 0);
    // This G has an edge whose shortest c-d geodesic leaves the two patches: the fallback path is exercised.
    EXPECT_GT(region, 0);
}

TEST(Flip, every_accepted_flip_of_a_traced_real_mesh_leaves_g_valid) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir()
                     << "': the real-mesh flip test needs them";
    auto fine = std::make_shared<const FineMesh>(load_fine_mesh(test::shared_mesh("classic/bob_small.ply").path));
    GeodesicTriangulation g(fine, decimated_coarse(*fine, 100));
    trace(g);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    int region = 0;
    const int accepted = check_every_flip(g, region);
    std::cout << "[ flip     ] bob_small, " << g.coarse().n_faces() << " coarse faces: " << accepted << " of "
              << g.coarse().n_edges() << " flips accepted, " << region << " of them inside the two patches\n";
    EXPECT_GT(accepted, 0);
}

// ---- flip_to_delaunay ------------------------------------------------------------------------------------------

/// Improves G by `criterion` and checks: valid after, the minimum corner angle not lower (criterion angle), the
/// flips terminated without the cap, a second run flips nothing, and the run is deterministic.
void check_improve(std::shared_ptr<const FineMesh> fine, const CoarseMesh& coarse, FlipCriterion criterion) {
    GeodesicTriangulation g(fine, coarse);
    trace(g);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    const CornerAngleStats before = corner_angle_stats(g);
    UntangleAndFlipOptions options;
    options.flipping.criterion = criterion;
    GeodesicTriangulation twin = g;
    const UntangleAndFlipResult r = untangle_and_flip(g, options);
    EXPECT_TRUE(r.untangling.valid_before);
    EXPECT_TRUE(r.valid_after);
    EXPECT_FALSE(r.flipping.pass_cap_reached);
    EXPECT_FALSE(r.flipping.reverted);
    EXPECT_EQ(r.untangling.flips, 0);
    expect_valid_with_area(g);
    EXPECT_DOUBLE_EQ(r.angles_before.min_deg, before.min_deg);
    const CornerAngleStats after = corner_angle_stats(g);
    EXPECT_DOUBLE_EQ(r.angles_after.min_deg, after.min_deg);
    if (criterion == FlipCriterion::angle) {
        EXPECT_GE(after.min_deg, before.min_deg);
    }
    std::cout << "[ improve  ] " << to_string(criterion) << ": " << r.flipping.flips << " flips in "
              << r.flipping.passes << " sweeps, min corner " << before.min_deg << "° -> " << after.min_deg << "°\n";

    const UntangleAndFlipResult again = untangle_and_flip(g, options);
    EXPECT_EQ(again.flipping.flips, 0);
    untangle_and_flip(twin, options);
    EXPECT_TRUE(snapshot(twin) == snapshot(g));
}

TEST(FlipToDelaunay, angle_criterion_never_lowers_the_minimum_angle_and_terminates) {
    auto fine = fine_of(test::perturbed_sphere(12, 0.02, 5));
    check_improve(fine, decimated_coarse(*fine, 60), FlipCriterion::angle);
}

TEST(FlipToDelaunay, length_criterion_terminates_and_keeps_g_valid) {
    auto fine = fine_of(test::perturbed_sphere(12, 0.02, 5));
    check_improve(fine, decimated_coarse(*fine, 60), FlipCriterion::length);
}

TEST(FlipToDelaunay, cube_with_skinny_triangles_is_improved) {
    // Side z = 0 of the cube is cut by a fan from corner 0 through an extra vertex near corner 3, which makes
    // skinny triangles; flips must raise the minimum angle.
    auto fine = fine_of(test::cube(8));
    std::vector<Eigen::Vector3d> corners;
    for (int k = 0; k < 8; ++k) corners.emplace_back(k & 1, k >> 1 & 1, k >> 2 & 1);
    corners.emplace_back(0.875, 0.75, 0.0);  // vertex 8
    GeodesicTriangulation g = make_g(fine, corners,
                                     {{0, 1, 8}, {1, 3, 8}, {3, 2, 8}, {2, 0, 8}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5},
                                      {0, 5, 4}, {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}},
                                     {0.5, 0.5, 0.5});
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    const UntangleAndFlipResult r = untangle_and_flip(g);
    EXPECT_TRUE(r.valid_after);
    EXPECT_GT(r.flipping.flips, 0);
    EXPECT_GT(r.angles_after.min_deg, r.angles_before.min_deg);
    expect_valid_with_area(g);
}

// ---- Real meshes -----------------------------------------------------------------------------------------------

TEST(FlipToDelaunay, traced_real_meshes_are_untangled_and_improved) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir()
                     << "': the real-mesh flip test needs them";
    // Ten meshes whose 320-face G is small enough to flip quickly, from every folder.
    const std::vector<std::string> names = {
        "anatomy/lumbar_vertebra_mean_2nd.ply", "anatomy/brain_mni_surface.ply",
        "anatomy/femur_thing157696.stl",        "classic/bob_small.ply",         "classic/eight.off",
        "classic/3holes.off",                   "cad/anchor.off",                "cad/rotor.off",
        "cad/pinion.off",
        // Its smallest bones are tetrahedra whose geodesics wind twice around a vertex: only a collapse mends them.
        "anatomy/footbones.ply",
        // A coarse vertex on the wrong side of a thin wall: only moving it mends it.
        "cad/couplingdown.off",
        // Two quads of one sweep wanted the same new edge here once, and the second flip failed.
        "classic/horse.ply"};
    int invalid = 0, made_valid = 0;
    for (const std::string& name : names) {
        const test::SharedMesh mesh = test::shared_mesh(name);
        auto fine = std::make_shared<const FineMesh>(load_fine_mesh(mesh.path));
        DecimateOptions options;
        options.target_faces = 320;
        DecimateResult decimated = decimate(*fine, options);
        if (!decimated.target_reached) {
            options = DecimateOptions{};
            options.coarsest = true;
            decimated = decimate(*fine, options);
        }
        GeodesicTriangulation g(fine, make_coarse_mesh(decimated.coarse, name));
        trace(g);
        const GeodesicTriangulation traced_g = g;
        const UntangleAndFlipResult r = untangle_and_flip(g);
        const ValidationReport check = validate(g);
        if (r.untangling.collapses + r.untangling.relocations > 0) {
            // Collapses renumber G and moves try many points: the result must not depend on the thread count.
            GeodesicTriangulation one_thread = traced_g;
            UntangleAndFlipOptions options;
            options.untangling.threads = 1;
            options.flipping.threads = 1;
            untangle_and_flip(one_thread, options);
            expect_same_polylines(one_thread, g, name);
        }
        EXPECT_EQ(check.valid, r.valid_after) << name;
        EXPECT_EQ(check.violation_count, r.violations_after) << name;
        EXPECT_LE(total(r.violations_after), total(r.untangling.violations_before)) << name;
        EXPECT_TRUE(r.valid_after) << name << ":\n" << describe(check);
        if (r.untangling.valid_before) {
            EXPECT_GE(r.angles_after.min_deg, r.angles_before.min_deg) << name;
        } else {
            ++invalid;
            if (r.valid_after) ++made_valid;
        }
        if (check.valid) {
            EXPECT_NEAR(check.patch_area, check.fine_area, 1e-9 * check.fine_area) << name;
        }
        std::cout << "[ flip     ] " << name << ": " << g.coarse().n_faces() << " faces, "
                  << (r.untangling.valid_before ? "valid" : "invalid") << " -> " << (r.valid_after ? "valid" : "INVALID")
                  << " (" << total(r.untangling.violations_before) << " -> " << total(r.violations_after)
                  << " violations), " << r.untangling.flips << " untangle flips + " << r.untangling.fork_splits
                  << " fork splits + " << r.untangling.collapses << " collapses + " << r.untangling.relocations
                  << " moves + " << r.flipping.flips << " improve flips, min corner " << r.angles_before.min_deg
                  << "° -> " << r.angles_after.min_deg << "°, " << r.seconds << " s\n";
    }
    std::cout << "[ flip     ] " << made_valid << " of " << invalid << " invalid traced G became valid\n";
}

/// `name` from the shared meshes, as traced_in_classes() does.
GeodesicTriangulation traced_as_the_pipeline_does(const std::string& name, bool coarsest) {
    return test::traced_in_classes(test::shared_mesh(name).path, name, coarsest);
}

TEST(Untangle, untangling_splits_geodesics_where_they_meet_at_a_vertex_of_t) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir()
                     << "': the test needs cad/boxpart.obj";
    // boxpart at the coarsest level, traced in the decimation's classes (as the pipeline does): geodesics of
    // different vertices pass through the same saddles of T there, and only splits at those meetings lower the count.
    const std::string name = "cad/boxpart.obj";
    const GeodesicTriangulation traced = traced_as_the_pipeline_does(name, true);

    // Without the collapses judged after untangling (thorough 0), which go on to make it valid, nor bisections.
    UntangleAndFlipOptions plain;
    plain.untangling.thorough = 0;
    plain.untangling.bisection_rounds = 0;
    GeodesicTriangulation g = traced;
    const UntangleAndFlipResult r = untangle_and_flip(g, plain);
    EXPECT_GE(r.untangling.meeting_splits, 1);
    EXPECT_LT(total(r.violations_after), total(r.untangling.violations_before));
    EXPECT_EQ(validate(g).violation_count, r.violations_after);
    // A split and the operations that settle it run in one trial, on one thread: the same G for any thread count.
    for (int threads : {1, 3}) {
        GeodesicTriangulation again = traced;
        plain.untangling.threads = threads;
        plain.flipping.threads = threads;
        const UntangleAndFlipResult same = untangle_and_flip(again, plain);
        EXPECT_EQ(same.untangling.meeting_splits, r.untangling.meeting_splits) << threads << " threads";
        expect_same_polylines(again, g, std::to_string(threads) + " threads");
    }
    std::cout << "[ flip     ] " << name << " at the coarsest level: " << total(r.untangling.violations_before) << " -> "
              << total(r.violations_after) << " violations, " << r.untangling.meeting_splits << " splits at meetings, "
              << r.untangling.fork_splits << " fork splits, " << r.seconds << " s\n";
}

TEST(Untangle, untangling_moves_a_vertex_further_or_flips_two_edges_when_nothing_else_helps) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir()
                     << "': the test needs cad/rotor.off, classic/eight.off and stress/42400-IDGH.stl";
    // Traced in the decimation's classes, as the pipeline does. At the coarsest level of rotor and eight, a vertex
    // whose geodesics wind twice must move 3-6 fine edges; at 320 faces, two tangles of 42400-IDGH each need two
    // flips of one face's edges, where either flip alone leaves the count as it is. Untangling was stuck on all
    // three before these moves.
    struct Case {
        std::string name;
        bool coarsest;
    };
    for (const Case& c : {Case{"cad/rotor.off", true}, Case{"classic/eight.off", true},
                          Case{"stress/42400-IDGH.stl", false}}) {
        const GeodesicTriangulation traced = traced_as_the_pipeline_does(c.name, c.coarsest);

        GeodesicTriangulation g = traced;
        const UntangleAndFlipResult r = untangle_and_flip(g);
        const ValidationReport check = validate(g);
        EXPECT_FALSE(r.untangling.valid_before) << c.name;
        EXPECT_TRUE(r.valid_after) << c.name << ":\n" << describe(check);
        EXPECT_TRUE(check.valid) << c.name;
        EXPECT_NEAR(check.patch_area, check.fine_area, 1e-9 * check.fine_area) << c.name;
        for (int threads : {1, 3}) {
            GeodesicTriangulation again = traced;
            UntangleAndFlipOptions with;
            with.untangling.threads = threads;
            with.flipping.threads = threads;
            untangle_and_flip(again, with);
            expect_same_polylines(again, g, c.name + ", " + std::to_string(threads) + " threads");
        }
        std::cout << "[ flip     ] " << c.name << (c.coarsest ? " at the coarsest level: " : " at 320 faces: ")
                  << total(r.untangling.violations_before) << " -> " << total(r.violations_after) << " violations, "
                  << r.untangling.flips << " flips, " << r.untangling.relocations << " moves, " << r.seconds << " s\n";
    }
}

TEST(Untangle, thorough_untangling_collapses_an_edge_where_that_helps_only_after_untangling_around_it) {
    const char* name = "stress/anchor_dense.off";
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir() << "': the test needs "
                     << name;
    // At its coarsest, untangling anchor_dense is stuck: no single move lowers the count, and no collapse does
    // until what it leaves is untangled around the vertex kept.
    const GeodesicTriangulation traced = traced_as_the_pipeline_does(name, true);

    UntangleAndFlipOptions plain;
    plain.untangling.thorough = 0;
    plain.untangling.bisection_rounds = 0;  // the last resort after these, which would go on
    GeodesicTriangulation without = traced;
    const UntangleAndFlipResult stuck = untangle_and_flip(without, plain);
    EXPECT_TRUE(stuck.untangling.stuck);
    EXPECT_TRUE(stuck.untangling.last_resorts_tried);  // geotri-flip then suggests --thorough
    EXPECT_FALSE(stuck.valid_after);

    UntangleAndFlipOptions thorough;
    thorough.untangling.thorough = 1;
    thorough.untangling.threads = 1;
    thorough.flipping.threads = 1;
    GeodesicTriangulation g = traced;
    const UntangleAndFlipResult r = untangle_and_flip(g, thorough);
    EXPECT_TRUE(r.valid_after);
    EXPECT_FALSE(r.untangling.thorough_budget_spent);
    expect_valid_with_area(g);

    GeodesicTriangulation again = traced;
    thorough.untangling.threads = 3;
    thorough.flipping.threads = 3;
    untangle_and_flip(again, thorough);
    expect_same_polylines(again, g, "3 threads");
    std::cout << "[ flip     ] " << name << " at the coarsest level, thorough: " << total(r.untangling.violations_before)
              << " -> " << total(r.violations_after) << " violations (" << total(stuck.violations_after)
              << " without), " << r.untangling.collapses << " collapses, " << r.seconds << " s\n";
}

TEST(Untangle, thorough_untangling_stops_where_its_budget_of_work_is_spent_the_same_for_any_thread_count) {
    const char* name = "stress/anchor_dense.off";
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir() << "': the test needs "
                     << name;
    // The last resorts share one budget of work. Their first trial that propagates (a pair of flips) spends a budget
    // of one window: no trial after it is read, whichever thread tried it and whatever the others tried, and
    // neither the wider moves nor the collapses of level 1, which mend anchor_dense (the test before), are tried.
    const GeodesicTriangulation traced = traced_as_the_pipeline_does(name, true);
    UntangleAndFlipOptions plain;
    plain.untangling.thorough = 0;
    plain.untangling.bisection_rounds = 0;
    GeodesicTriangulation without = traced;
    const UntangleAndFlipResult stuck = untangle_and_flip(without, plain);

    UntangleAndFlipOptions tight;
    tight.untangling.thorough = 2;
    tight.untangling.thorough_budget = 1;
    tight.untangling.bisection_rounds = 0;  // which would go on once the budget is spent
    tight.untangling.threads = 1;
    tight.flipping.threads = 1;
    GeodesicTriangulation g = traced;
    const UntangleAndFlipResult r = untangle_and_flip(g, tight);
    EXPECT_TRUE(r.untangling.thorough_budget_spent);
    EXPECT_FALSE(r.valid_after);
    // Plain untangling tries every pair of flips and every wider move within the default budget, and mends nothing
    // with them: the G is the one that it leaves, after fewer trials.
    EXPECT_FALSE(stuck.untangling.thorough_budget_spent);
    EXPECT_LT(r.untangling.rejected + r.untangling.refused, stuck.untangling.rejected + stuck.untangling.refused);
    EXPECT_EQ(r.untangling.collapses, stuck.untangling.collapses);
    expect_same_polylines(g, without, "a budget of one window");
    for (int threads : {2, 3}) {
        GeodesicTriangulation again = traced;
        tight.untangling.threads = threads;
        tight.flipping.threads = threads;
        const UntangleAndFlipResult other = untangle_and_flip(again, tight);
        EXPECT_TRUE(other.untangling.thorough_budget_spent) << threads << " threads";
        EXPECT_EQ(other.untangling.rejected, r.untangling.rejected) << threads << " threads";
        EXPECT_EQ(other.untangling.refused, r.untangling.refused) << threads << " threads";
        expect_same_polylines(again, g, std::to_string(threads) + " threads");
    }
}

TEST(Untangle, by_default_untangling_nests_those_collapses_and_makes_femur_cgal_valid_at_320_faces) {
    const char* name = "anatomy/femur_cgal.off";
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir() << "': the test needs "
                     << name;
    // Around its tiny handles, level 1 takes femur_cgal from 16 violations to 3 and sticks; level 2, the default
    // within its budget, goes on with collapses whose untangling may itself end with such collapses.
    const GeodesicTriangulation traced = traced_as_the_pipeline_does(name, false);

    UntangleAndFlipOptions level_1;
    level_1.untangling.thorough = 1;
    level_1.untangling.thorough_budget = 0;
    level_1.untangling.bisection_rounds = 0;
    GeodesicTriangulation stuck_g = traced;
    const UntangleAndFlipResult stuck = untangle_and_flip(stuck_g, level_1);
    EXPECT_FALSE(stuck.valid_after);

    GeodesicTriangulation g = traced;
    const UntangleAndFlipResult r = untangle_and_flip(g);
    EXPECT_TRUE(r.valid_after);
    EXPECT_FALSE(r.untangling.thorough_budget_spent);
    expect_valid_with_area(g);
    std::cout << "[ flip     ] " << name << " at 320 faces, by default: " << total(r.untangling.violations_before) << " -> "
              << total(r.violations_after) << " violations (" << total(stuck.violations_after) << " with 1), "
              << r.untangling.collapses << " collapses, " << r.seconds << " s\n";
}

TEST(Untangle, untangling_bisects_the_tangled_edges_where_nothing_else_helps) {
    // The bundled joint (genus 2) at its coarsest, 32 faces, traced in the decimation's classes: untangling, its
    // last resorts included, cannot make it valid; bisecting the edges that the violations name lets it go on.
    const GeodesicTriangulation traced =
        test::traced_in_classes(std::string(GEOTRI_TEST_DATA) + "/cad/joint.off", "cad/joint.off", true);
    UntangleAndFlipOptions without;
    without.untangling.bisection_rounds = 0;
    GeodesicTriangulation stuck_g = traced;
    const UntangleAndFlipResult stuck = untangle_and_flip(stuck_g, without);
    EXPECT_FALSE(stuck.valid_after);
    EXPECT_EQ(stuck.untangling.bisections, 0);

    GeodesicTriangulation g = traced;
    const UntangleAndFlipResult r = untangle_and_flip(g);
    EXPECT_GT(r.untangling.bisections, 0);
    EXPECT_TRUE(r.valid_after) << describe(validate(g));
    expect_valid_with_area(g);
    UntangleAndFlipOptions one_thread;
    one_thread.untangling.threads = 1;
    one_thread.flipping.threads = 1;
    GeodesicTriangulation again = traced;
    untangle_and_flip(again, one_thread);
    expect_same_polylines(again, g, "1 thread");

    // Refinement of that G to 25 degrees ends valid, each step judged by its local checks alone.
    RefineOptions to_25;
    to_25.min_angle_deg = 25.0;
    GeodesicTriangulation refined = g;
    const RefineResult refinement = refine(refined, to_25);
    EXPECT_TRUE(refinement.valid_after) << describe(validate(refined));
    expect_valid_with_area(refined);
    std::cout << "[ flip     ] bundled joint at its coarsest: " << total(r.untangling.violations_before) << " -> "
              << total(r.violations_after) << " violations (" << total(stuck.violations_after)
              << " without bisections), " << r.untangling.bisections << " edges bisected, " << g.coarse().n_faces()
              << " faces, " << r.seconds << " s; refined to " << refined.coarse().n_faces() << " faces, "
              << refinement.angles_after.min_deg << "°\n";
}

TEST(Untangle, untangling_again_with_the_vertices_of_bisections_kept_mends_fertility_at_its_coarsest) {
    const char* name = "classic/fertility.off";
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir() << "': the test needs "
                     << name;
    // At its coarsest (54 faces, genus 4), the collapses after each round of bisections take their vertices out
    // again, and G ends with 5 violations; untangling again from the G given, with those vertices kept, mends it.
    GeodesicTriangulation g = traced_as_the_pipeline_does(name, true);
    const UntangleAndFlipResult r = untangle_and_flip(g);
    EXPECT_TRUE(r.untangling.kept_bisection_vertices);
    EXPECT_GT(r.untangling.bisections, 0);
    EXPECT_TRUE(r.valid_after) << describe(validate(g));
    expect_valid_with_area(g);
    std::cout << "[ flip     ] " << name << " at its coarsest: " << total(r.untangling.violations_before) << " -> "
              << total(r.violations_after) << " violations, " << r.untangling.bisections << " edges bisected, "
              << g.coarse().n_faces() << " faces, " << r.seconds << " s\n";
}

}  // namespace
}  // namespace geotri

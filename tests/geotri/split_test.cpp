// Edge and face splits: a hand-made G on a procedural cube, checked against closed forms, and traced G on
// real meshes, checked with validate() (with the overlay and the patch areas) after every split.

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/decimate.h>
#include <geotri/fine_mesh.h>
#include <geotri/overlay.h>
#include <geotri/split.h>
#include <geotri/tangent_angles.h>
#include <geotri/trace.h>
#include <geotri/untangle_and_flip.h>
#include <geotri/validate.h>

#include <geotri_test/fine_mesh.h>
#include <geotri_test/g_checks.h>
#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include "ops/with_workspace.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace geotri {
namespace {

using geodesic::SurfacePoint;
using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::VertexHandle;
using test::describe;
using test::expect_valid_with_area;
using test::unit_cube_g;

EdgeHandle edge_between(const CoarseMesh& coarse, int a, int b) {
    const auto h = coarse.find_halfedge(VertexHandle(a), VertexHandle(b));
    return h.is_valid() ? coarse.edge_handle(h) : EdgeHandle();
}

Eigen::Vector3d position_of(const GeodesicTriangulation& g, VertexHandle v) {
    return g.fine().mesh.point(g.location(v));
}

TEST(Split, edge_split_of_a_cube_side_diagonal_meets_the_other_diagonal_at_the_centre) {
    GeodesicTriangulation g = unit_cube_g();
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    // The diagonal of the bottom side z = 0 from corner 0 (0,0,0) to corner 3 (1,1,0).
    const EdgeHandle e = edge_between(g.coarse(), 0, 3);
    ASSERT_TRUE(e.is_valid());
    const std::size_t faces = g.coarse().n_faces(), edges = g.coarse().n_edges();
    const SplitResult r = split_edge(g, e, 0.5);
    ASSERT_TRUE(r.done) << r.reason;
    EXPECT_EQ(g.coarse().n_faces(), faces + 2);
    EXPECT_EQ(g.coarse().n_edges(), edges + 3);
    EXPECT_LT((position_of(g, r.vertex) - Eigen::Vector3d(0.5, 0.5, 0.0)).norm(), 1e-15);
    // Its four geodesics are the halves of the two diagonals of the side.
    for (auto h : g.coarse().voh_range(r.vertex)) EXPECT_NEAR(g.length(g.coarse().edge_handle(h)), std::sqrt(0.5), 1e-15);
    expect_valid_with_area(g);
}

TEST(Split, edge_split_at_a_fraction_lies_at_that_arc_length) {
    GeodesicTriangulation g = unit_cube_g();
    const EdgeHandle e = edge_between(g.coarse(), 0, 3);
    const SplitResult r = split_edge(g, e, 0.3);
    ASSERT_TRUE(r.done) << r.reason;
    const Eigen::Vector3d x = position_of(g, r.vertex);
    // 0.3 of the way along the diagonal from whichever end the polyline starts.
    const bool from_origin = std::abs(x.x() - 0.3) < 1e-12;
    EXPECT_LT((x - (from_origin ? Eigen::Vector3d(0.3, 0.3, 0.0) : Eigen::Vector3d(0.7, 0.7, 0.0))).norm(), 1e-15);
    expect_valid_with_area(g);
}

TEST(Split, edge_split_fractions_outside_the_open_interval_are_invalid_input) {
    GeodesicTriangulation g = unit_cube_g();
    const EdgeHandle e = edge_between(g.coarse(), 0, 3);
    EXPECT_THROW(split_edge(g, e, 0.0), InvalidInput);
    EXPECT_THROW(split_edge(g, e, 1.0), InvalidInput);
    EXPECT_THROW(split_edge(g, e, std::nan("")), InvalidInput);
    EXPECT_THROW(split_edge(g, EdgeHandle(1000), 0.5), InvalidInput);
}

TEST(Split, edge_split_at_a_point_of_the_polyline_puts_the_vertex_there_and_keeps_both_parts) {
    GeodesicTriangulation g = unit_cube_g();
    const EdgeHandle e = edge_between(g.coarse(), 0, 3);
    const Polyline line = g.polyline(e);
    const double length = g.length(e);
    // The diagonal of a side crosses its fine grid of 4 x 4 squares: every inner point, at a vertex or on an edge.
    ASSERT_GE(line.size(), 3u);
    for (std::size_t index = 1; index + 1 < line.size(); ++index) {
        SCOPED_TRACE("point " + std::to_string(index) + ", " + geodesic::to_spec(line[index]));
        GeodesicTriangulation copy = g;
        const SplitResult r = split_edge_at_point(copy, e, index);
        ASSERT_TRUE(r.done) << r.reason;
        EXPECT_EQ(copy.location(r.vertex), g.fine().mesh.canonical(line[index]));
        const VertexHandle a = g.coarse().from_vertex_handle(g.coarse().halfedge_handle(e, 0));
        const VertexHandle b = g.coarse().to_vertex_handle(g.coarse().halfedge_handle(e, 0));
        const Polyline to_a = copy.path(copy.coarse().find_halfedge(r.vertex, a));
        const Polyline to_b = copy.path(copy.coarse().find_halfedge(r.vertex, b));
        EXPECT_EQ(to_a, Polyline(line.rend() - static_cast<long>(index) - 1, line.rend()));
        EXPECT_EQ(to_b, Polyline(line.begin() + static_cast<long>(index), line.end()));
        EXPECT_NEAR(copy.length(copy.coarse().edge_handle(copy.coarse().find_halfedge(r.vertex, a))) +
                        copy.length(copy.coarse().edge_handle(copy.coarse().find_halfedge(r.vertex, b))),
                    length, 1e-14);
        expect_valid_with_area(copy);
    }
    EXPECT_THROW(split_edge_at_point(g, e, 0), InvalidInput);
    EXPECT_THROW(split_edge_at_point(g, e, line.size() - 1), InvalidInput);
    EXPECT_THROW(split_edge_at_point(g, EdgeHandle(1000), 1), InvalidInput);
}

TEST(Split, face_split_inside_a_cube_side_joins_the_corners_with_straight_segments) {
    GeodesicTriangulation g = unit_cube_g();
    // Face (0, 3, 1) of the bottom side: corners (0,0,0), (1,1,0), (1,0,0). A point inside it, on the fine mesh.
    FaceHandle f;
    for (auto face : g.coarse().faces()) {
        std::vector<int> vs;
        for (auto v : g.coarse().fv_range(face)) vs.push_back(v.idx());
        if (std::find(vs.begin(), vs.end(), 0) != vs.end() && std::find(vs.begin(), vs.end(), 3) != vs.end() &&
            std::find(vs.begin(), vs.end(), 1) != vs.end())
            f = face;
    }
    ASSERT_TRUE(f.is_valid());
    const Eigen::Vector3d target(0.625, 0.375, 0.0);
    const int fine_face = [&] {
        const auto& mesh = g.fine().mesh;
        for (int k = 0; k < mesh.num_faces(); ++k) {
            const auto& t = mesh.triangle(k);
            Eigen::Vector3d centre = (mesh.position(t[0]) + mesh.position(t[1]) + mesh.position(t[2])) / 3.0;
            if ((centre - target).norm() < 0.1 && std::abs(centre.z()) < 1e-12) return k;
        }
        return -1;
    }();
    ASSERT_GE(fine_face, 0);
    const SurfacePoint p = SurfacePoint::in_face(fine_face, {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0});
    const Eigen::Vector3d x = g.fine().mesh.point(p);
    const SplitResult r = split_face(g, f, p);
    ASSERT_TRUE(r.done) << r.reason;
    EXPECT_EQ(r.region_paths, 0);
    for (auto h : g.coarse().voh_range(r.vertex)) {
        const Eigen::Vector3d corner = position_of(g, g.coarse().to_vertex_handle(h));
        EXPECT_NEAR(g.length(g.coarse().edge_handle(h)), (corner - x).norm(), 1e-14);
    }
    expect_valid_with_area(g);
}

TEST(Split, face_split_at_a_point_outside_the_patch_is_refused_and_g_is_unchanged) {
    GeodesicTriangulation g = unit_cube_g();
    const GeodesicTriangulation before = g;
    // A point on the top side z = 1 cannot be inside a patch of the bottom side.
    const int v = test::nearest_vertex(g.fine().mesh, {0.5, 0.5, 1.0});
    const FaceHandle f(0);
    const SplitResult r = split_face(g, f, SurfacePoint::at_vertex(v));
    EXPECT_FALSE(r.done);
    EXPECT_FALSE(r.reason.empty());
    EXPECT_EQ(g.coarse().n_vertices(), before.coarse().n_vertices());
    EXPECT_EQ(g.coarse().n_faces(), before.coarse().n_faces());
    for (auto e : g.coarse().edges()) EXPECT_EQ(g.polyline(e), before.polyline(e));
    // A propagation said to be made beforehand must be there.
    Workspace without;
    without.propagated = true;
    EXPECT_THROW(split_face(g, f, SurfacePoint::at_vertex(v), {}, without), InvalidInput);
}

/// The largest overlay triangle for which keep(t) holds, or -1 where there is none.
template <class Keep>
int largest_triangle(const Overlay& overlay, Keep keep) {
    int best = -1;
    double best_area = 0.0;
    for (std::size_t t = 0; t < overlay.triangles.size(); ++t) {
        if (!keep(t)) continue;
        const auto& tri = overlay.triangles[t];
        const double area = (overlay.positions[tri[1]] - overlay.positions[tri[0]])
                                .cross(overlay.positions[tri[2]] - overlay.positions[tri[0]])
                                .norm();
        if (area > best_area) {
            best_area = area;
            best = static_cast<int>(t);
        }
    }
    return best;
}

/// The centroid of overlay triangle t, as a point of T.
SurfacePoint centroid_of(const GeodesicTriangulation& g, const Overlay& overlay, int t) {
    const auto& mesh = g.fine().mesh;
    const int fine_face = overlay.fine_face[static_cast<std::size_t>(t)];
    std::array<double, 3> b{0.0, 0.0, 0.0};
    for (int corner : overlay.triangles[static_cast<std::size_t>(t)]) {
        const auto c = barycentric_in(mesh, fine_face, overlay.points[static_cast<std::size_t>(corner)]);
        for (std::size_t k = 0; k < 3; ++k) b[k] += c[k] / 3.0;
    }
    return mesh.canonical(SurfacePoint::in_face(fine_face, b));
}

/// A point strictly inside the patch of f: the centroid of its largest overlay triangle.
SurfacePoint inside_patch(const GeodesicTriangulation& g, const Overlay& overlay, int f) {
    return centroid_of(g, overlay, largest_triangle(overlay, [&](std::size_t t) { return overlay.patch[t] == f; }));
}

/// Splits every `stride`-th edge at its midpoint and every `stride`-th face inside its patch, each on its own copy
/// of G, and checks that every split that is done leaves G valid.
void check_every_split(const GeodesicTriangulation& g, const std::string& name, int stride = 1) {
    int edges_done = 0, faces_done = 0, region = 0;
    int edges_tried = 0, faces_tried = 0;
    // The edge splits once more with the overlay of all of g given, where the fallback otherwise cuts the patch
    // alone out of T: the same results, to the bit.
    const Overlay overlay = build_overlay(g);
    Workspace with_overlay;
    with_overlay.overlay = &overlay;
    for (auto e : g.coarse().edges()) {
        if (e.idx() % stride != 0) continue;
        ++edges_tried;
        GeodesicTriangulation copy = g, again = g;
        const SplitResult r = split_edge(copy, e, 0.5);
        const SplitResult r_again = split_edge(again, e, 0.5, {}, with_overlay);
        EXPECT_EQ(r_again.done, r.done);
        EXPECT_EQ(r_again.region_paths, r.region_paths);
        if (!r.done) {
            std::cout << "[ refused  ] " << r.reason << "\n";
            continue;
        }
        for (auto x : copy.coarse().edges()) EXPECT_EQ(again.polyline(x), copy.polyline(x));
        ++edges_done;
        region += r.region_paths;
        SCOPED_TRACE("edge " + std::to_string(e.idx()));
        expect_valid_with_area(copy);
    }
    for (auto f : g.coarse().faces()) {
        if (f.idx() % stride != 0) continue;
        ++faces_tried;
        GeodesicTriangulation copy = g;
        const SurfacePoint p = inside_patch(g, overlay, f.idx());
        const SplitResult r = split_face(copy, f, p);
        // Once more from a propagation made beforehand towards the corners of f and of a neighbour, as refinement
        // tries one point in several patches: the same split (its geodesics equal to rounding: another order of
        // propagation), and the neighbour refuses the point.
        const auto neighbour = g.coarse().opposite_face_handle(g.coarse().halfedge_handle(f));
        geodesic::ExactGeodesic propagation(g.fine().mesh);
        geodesic::PropagationOptions towards;
        towards.goal_directed = true;
        for (auto x : {f, neighbour})
            for (auto v : g.coarse().fv_range(x)) towards.stop_points.push_back(g.location(v));
        propagation.propagate({g.fine().mesh.canonical(p)}, towards);
        Workspace shared;
        shared.propagation = &propagation;
        shared.propagated = true;
        GeodesicTriangulation again = g, other = g;
        EXPECT_EQ(split_face(again, f, p, {}, shared).done, r.done);
        if (r.done) {
            for (auto x : copy.coarse().edges()) {
                EXPECT_EQ(again.polyline(x).size(), copy.polyline(x).size());
                EXPECT_NEAR(again.length(x), copy.length(x), 1e-12 * copy.length(x));
            }
        }
        EXPECT_FALSE(split_face(other, neighbour, p, {}, shared).done);
        if (!r.done) {
            std::cout << "[ refused  ] " << r.reason << "\n";
            continue;
        }
        ++faces_done;
        region += r.region_paths;
        SCOPED_TRACE("face " + std::to_string(f.idx()));
        expect_valid_with_area(copy);
    }
    std::cout << "[ split    ] " << name << ", " << g.coarse().n_faces() << " coarse faces: " << edges_done << " of "
              << edges_tried << " edge splits and " << faces_done << " of " << faces_tried
              << " face splits done, " << region << " new geodesics inside their patch\n";
    // Nearly all splits of a valid G on a smooth mesh go through; a refusal says why, but most must be done.
    EXPECT_GT(edges_done, edges_tried * 9 / 10);
    EXPECT_GT(faces_done, faces_tried * 9 / 10);
}

TEST(Split, every_split_of_a_traced_bundled_mesh_leaves_g_valid) {
    auto fine = std::make_shared<const FineMesh>(load_fine_mesh(std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply"));
    GeodesicTriangulation g(fine, test::decimated_coarse(*fine, 100));
    trace(g);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    check_every_split(g, "bob_small");
}

TEST(Split, every_split_of_a_traced_vertebra_leaves_g_valid) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir()
                     << "': the real-mesh split test needs them";
    auto fine = std::make_shared<const FineMesh>(
        load_fine_mesh(test::shared_mesh("anatomy/lumbar_vertebra_mean_2nd.ply").path));
    GeodesicTriangulation g(fine, test::decimated_coarse(*fine, 120));
    trace(g);
    untangle_and_flip(g);  // the traced G is not valid at this size; flips make it so
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    check_every_split(g, "lumbar vertebra", 3);  // every third: each check builds the overlay
}

/// Whether p lies on the closed fine face f (at a corner, on a side or inside).
bool on_closed_face(const geodesic::Mesh& mesh, int f, const SurfacePoint& p) {
    const auto& corners = mesh.triangle(f);
    auto corner = [&](int v) { return std::find(corners.begin(), corners.end(), v) != corners.end(); };
    switch (p.kind) {
        case geodesic::PointKind::vertex: return corner(p.vertex);
        case geodesic::PointKind::edge: return corner(p.edge_v0) && corner(p.edge_v1);
        case geodesic::PointKind::face: return p.face == f;
    }
    return false;
}

/// `line` with its point i, at vertex v of T, replaced by two points a hair (1e-16 of the edge) from v on the sides
/// at v of F, the face of halfedge h (leaving v), where the faces across those sides hold the points before and after
/// v; nothing where they do not.
std::optional<Polyline> through_the_corner_of(const geodesic::Mesh& mesh, const Polyline& line, std::size_t i, int h) {
    const int x = mesh.head(h), y = mesh.tail(geodesic::Mesh::prev(h));
    const int across_x = mesh.twin(h), across_y = mesh.twin(geodesic::Mesh::prev(h));
    if (across_x < 0 || across_y < 0) return std::nullopt;
    auto holds = [&](int across, const SurfacePoint& p) {
        return on_closed_face(mesh, geodesic::Mesh::face_of(across), p);
    };
    const bool forward = holds(across_x, line[i - 1]) && holds(across_y, line[i + 1]);
    if (!forward && !(holds(across_y, line[i - 1]) && holds(across_x, line[i + 1]))) return std::nullopt;
    const int v = line[i].vertex;
    Polyline hugging(line.begin(), line.begin() + static_cast<std::ptrdiff_t>(i));
    hugging.push_back(SurfacePoint::on_edge(v, forward ? x : y, 1e-16));
    hugging.push_back(SurfacePoint::on_edge(v, forward ? y : x, 1e-16));
    hugging.insert(hugging.end(), line.begin() + static_cast<std::ptrdiff_t>(i) + 1, line.end());
    return hugging;
}

TEST(Split, a_face_split_beside_a_geodesic_that_passes_a_vertex_of_t_a_hair_away_leaves_g_valid) {
    // A geodesic traced through a vertex v of T can come as two points on the edges of a fine face F at v, a hair
    // (1e-16 of the edge) from v, with a chord of F between them: validate() takes them for v. A face split at a
    // point of F leads geodesics out of F beside that chord, and its local checks pass it. The overlay must cut the
    // chord at v as well: laid out as a chord of no length, it would meet every other chord of F and leave the
    // patches about it no disks. On the bundled joint (a CAD part whose geodesics run along its creases through
    // vertices of T), vertices of polylines so moved, where G stays valid, each with the face split at the middle of
    // F's largest overlay triangle.
    GeodesicTriangulation g =
        test::traced_in_classes(std::string(GEOTRI_TEST_DATA) + "/cad/joint.off", "cad/joint.off", false);
    untangle_and_flip(g);
    ASSERT_TRUE(validate(g).valid) << describe(validate(g));
    const geodesic::Mesh& mesh = g.fine().mesh;
    int moved = 0, split = 0;
    for (auto e : g.coarse().edges()) {
        const Polyline line = g.polyline(e);
        for (std::size_t i = 1; i + 1 < line.size() && split < 12; ++i) {
            if (line[i].kind != geodesic::PointKind::vertex) continue;
            for (int h : mesh.outgoing_halfedges(line[i].vertex)) {
                const std::optional<Polyline> hugging = through_the_corner_of(mesh, line, i, h);
                if (!hugging) continue;
                GeodesicTriangulation moved_g = g;
                moved_g.set_polyline(e, *hugging);  // canonical: t from the end of smaller index
                if (!validate(moved_g).valid) continue;  // another geodesic passes the vertex too
                ++moved;
                const int f = geodesic::Mesh::face_of(h);
                const Overlay overlay = build_overlay(moved_g);
                const int largest = largest_triangle(
                    overlay, [&](std::size_t t) { return overlay.fine_face[t] == f && overlay.patch[t] >= 0; });
                if (largest < 0) continue;
                const FaceHandle coarse_face(overlay.patch[static_cast<std::size_t>(largest)]);
                if (!split_face(moved_g, coarse_face, centroid_of(moved_g, overlay, largest)).done) continue;
                ++split;
                SCOPED_TRACE("edge " + std::to_string(e.idx()) + ", vertex " + std::to_string(line[i].vertex) +
                             " of T, face " + std::to_string(f));
                expect_valid_with_area(moved_g);
                break;
            }
        }
    }
    std::cout << "[ split    ] bundled joint at 320 faces: " << moved << " geodesics moved a hair off a vertex of T, "
              << split << " face splits beside them\n";
    EXPECT_GT(split, 0);
}

/// The anchor (a CAD part of genus 4) decimated to 320 faces and traced: trace leaves forks there, pairs of
/// geodesics that leave a coarse vertex together and part at a saddle vertex of T.
GeodesicTriangulation traced_anchor() {
    return test::traced(std::string(GEOTRI_TEST_DATA) + "/cad/anchor.off", 320);
}

/// Violations of condition 2 (corners in order) that name coarse vertex v.
int order_violations_at(const ValidationReport& r, int v) {
    return static_cast<int>(std::count_if(r.violations.begin(), r.violations.end(), [&](const Violation& x) {
        return x.condition == 2 && std::find(x.coarse_vertices.begin(), x.coarse_vertices.end(), v) != x.coarse_vertices.end();
    }));
}

TEST(Split, fork_split_parts_the_geodesics_at_the_saddle_and_keeps_their_lengths) {
    GeodesicTriangulation g = traced_anchor();
    const geodesic::Mesh& mesh = g.fine().mesh;
    std::vector<Fork> forks;
    for (auto v : g.coarse().vertices())
        for (const Fork& f : find_forks(g, v)) forks.push_back(f);
    ASSERT_FALSE(forks.empty()) << "the traced anchor has no fork any more: the test needs another case";
    const ValidationReport before = validate(g);
    ASSERT_FALSE(before.valid);

    int done = 0;
    for (const Fork& fork : forks) {
        GeodesicTriangulation copy = g;
        const VertexHandle a = copy.coarse().from_vertex_handle(fork.first);
        // The run's far ends and old lengths, counter-clockwise from `first`.
        std::vector<std::pair<VertexHandle, double>> run;
        for (auto h = fork.first; static_cast<int>(run.size()) < fork.count;
             h = copy.coarse().opposite_halfedge_handle(copy.coarse().prev_halfedge_handle(h)))
            run.emplace_back(copy.coarse().to_vertex_handle(h), copy.length(copy.coarse().edge_handle(h)));
        const std::size_t faces = copy.coarse().n_faces();
        const SplitResult r = split_fork(copy, fork);
        if (!r.done) {
            std::cout << "[ refused  ] " << r.reason << "\n";
            continue;
        }
        ++done;
        EXPECT_EQ(copy.coarse().n_faces(), faces + 2);
        // Shortest geodesics from one point part only at a saddle vertex of T.
        const SurfacePoint& at = copy.location(r.vertex);
        ASSERT_EQ(at.kind, geodesic::PointKind::vertex);
        EXPECT_GT(mesh.cone_angle(at.vertex), 2.0 * M_PI);
        // a-v is the common part, and a-v followed by v-b is the old geodesic a-b.
        const auto av = copy.coarse().find_halfedge(a, r.vertex);
        ASSERT_TRUE(av.is_valid());
        const double common = copy.length(copy.coarse().edge_handle(av));
        for (const auto& [b, old_length] : run) {
            const auto vb = copy.coarse().find_halfedge(r.vertex, b);
            ASSERT_TRUE(vb.is_valid());
            EXPECT_NEAR(common + copy.length(copy.coarse().edge_handle(vb)), old_length, 1e-12 * old_length);
        }
        // The polylines are still geodesics between their ends (condition 1), and a has fewer bad corners.
        const ValidationReport after = validate(copy);
        EXPECT_EQ(after.violation_count[0], 0) << describe(after);
        EXPECT_LT(order_violations_at(after, a.idx()), order_violations_at(before, a.idx())) << describe(after);
    }
    EXPECT_GT(done, 0);
}

/// The cube's G with the geodesics of the first `count` edges leaving corner 0 (counter-clockwise) made to run
/// together for a first segment, to a point on a fine edge at corner 0: a hand-made fork of `count` edges. Returns
/// the first halfedge of the run. The polylines are no longer geodesics: only the fork's shape matters here.
OpenMesh::HalfedgeHandle make_fork_at_corner_0(GeodesicTriangulation& g, int count) {
    const geodesic::Mesh& mesh = g.fine().mesh;
    const SurfacePoint corner = g.location(VertexHandle(0));
    const int fine_neighbour = mesh.head(*mesh.outgoing_halfedges(corner.vertex).begin());
    const SurfacePoint together = mesh.canonical(SurfacePoint::on_edge(corner.vertex, fine_neighbour, 0.5));
    std::vector<OpenMesh::HalfedgeHandle> fan;
    for (auto h : g.coarse().voh_ccw_range(VertexHandle(0))) fan.push_back(h);
    for (int k = 0; k < count; ++k) {
        Polyline path = g.path(fan[k]);
        path.insert(path.begin() + 1, together);
        g.set_path(fan[k], path);
    }
    return fan.front();
}

TEST(Split, forks_leave_two_edges_of_the_fan_outside_and_others_are_refused) {
    const GeodesicTriangulation cube = unit_cube_g();
    const int valence = static_cast<int>(cube.coarse().valence(VertexHandle(0)));
    ASSERT_EQ(valence, 6);
    for (int count = 2; count <= valence; ++count) {
        SCOPED_TRACE("a run of " + std::to_string(count) + " edges");
        GeodesicTriangulation g = cube;
        const auto first = make_fork_at_corner_0(g, count);
        const std::vector<Fork> forks = find_forks(g, VertexHandle(0));
        if (count + 2 <= valence) {
            ASSERT_EQ(forks.size(), 1u);
            EXPECT_EQ(forks[0].first, first);
            EXPECT_EQ(forks[0].count, count);
            EXPECT_EQ(forks[0].common, 2u);
        } else {
            EXPECT_TRUE(forks.empty());
            // Asked all the same, split_fork refuses it (it would have no two distinct vertices to join).
            const std::size_t faces = g.coarse().n_faces();
            const SplitResult r = split_fork(g, Fork{first, count, 2});
            EXPECT_FALSE(r.done);
            EXPECT_NE(r.reason.find("fewer than two"), std::string::npos) << r.reason;
            EXPECT_EQ(g.coarse().n_faces(), faces);
        }
    }
}

TEST(Split, a_fork_whose_geodesics_reach_their_parting_vertex_one_as_a_vertex_one_as_an_edge_crossing_parts_there) {
    // Geodesics along a line of vertices of T (42400-IDGH) can pass a vertex as crossings of its edges at 1 - 1e-16:
    // two that run together to a vertex n, one through n and one by such crossings, must part at n itself, with
    // polylines that go on from n (split_fork once took the crossing, which shares no face with the other's next
    // point). Hand-made on the cube: the two geodesics leave corner 0 to n, then each crosses an edge of its own.
    const GeodesicTriangulation cube = unit_cube_g();
    const geodesic::Mesh& mesh = cube.fine().mesh;
    const int c = cube.location(VertexHandle(0)).vertex;
    const int n = mesh.head(*mesh.outgoing_halfedges(c).begin());
    auto halfway = [&](int w) { return mesh.canonical(SurfacePoint::on_edge(n, w, 0.5)); };
    std::vector<int> beyond;  // the neighbours of n but c, in order
    for (int h : mesh.outgoing_halfedges(n))
        if (mesh.head(h) != c) beyond.push_back(mesh.head(h));
    int y = -1, w = -1;  // two of them whose edges from n are on no common face
    for (int i : beyond)
        for (int j : beyond)
            if (y < 0 && i != j && common_face(mesh, halfway(i), halfway(j)) < 0) y = i, w = j;
    ASSERT_GE(y, 0);
    const double almost_1 = 1.0 - 1e-16;  // rounds to 1 - 2^-53
    ASSERT_LT(almost_1, 1.0);
    const Polyline through_n{SurfacePoint::at_vertex(c), SurfacePoint::at_vertex(n), halfway(w)};
    const Polyline past_n{SurfacePoint::at_vertex(c), SurfacePoint::on_edge(y, n, almost_1),
                          SurfacePoint::on_edge(y, n, almost_1 - 1e-16), halfway(y)};
    for (bool vertex_first : {true, false}) {
        SCOPED_TRACE(vertex_first ? "the polyline through n first" : "the polyline past n first");
        GeodesicTriangulation g = cube;
        std::vector<OpenMesh::HalfedgeHandle> fan;
        for (auto h : g.coarse().voh_ccw_range(VertexHandle(0))) fan.push_back(h);
        // Only the fork matters: each polyline then jumps to its far end.
        for (int k = 0; k < 2; ++k) {
            Polyline path = (k == 0) == vertex_first ? through_n : past_n;
            path.push_back(g.location(g.coarse().to_vertex_handle(fan[static_cast<std::size_t>(k)])));
            g.set_path(fan[static_cast<std::size_t>(k)], path);
        }
        const std::vector<Fork> forks = find_forks(g, VertexHandle(0));
        ASSERT_EQ(forks.size(), 1u);
        ASSERT_EQ(forks[0].common, 2u);
        const std::array<VertexHandle, 2> ends{g.coarse().to_vertex_handle(fan[0]), g.coarse().to_vertex_handle(fan[1])};
        const SplitResult r = split_fork(g, forks[0]);
        ASSERT_TRUE(r.done) << r.reason;
        EXPECT_EQ(g.location(r.vertex), SurfacePoint::at_vertex(n));
        const Polyline common = g.path(g.coarse().find_halfedge(VertexHandle(0), r.vertex));
        EXPECT_EQ(common, (Polyline{SurfacePoint::at_vertex(c), SurfacePoint::at_vertex(n)}));
        for (VertexHandle end : ends) {
            const Polyline onward = g.path(g.coarse().find_halfedge(r.vertex, end));
            ASSERT_GE(onward.size(), 2u);
            EXPECT_EQ(onward[0], SurfacePoint::at_vertex(n));
            EXPECT_GE(common_face(mesh, onward[0], onward[1]), 0) << geodesic::to_spec(onward[1]);
            // The crossings at n are left out, not kept as steps of 1e-16.
            EXPECT_GT((mesh.point(onward[1]) - mesh.point(onward[0])).norm(), 1e-3) << geodesic::to_spec(onward[1]);
        }
    }
}

TEST(Split, untangling_splits_the_forks_that_no_flip_mends) {
    GeodesicTriangulation g = traced_anchor();
    const UntangleAndFlipResult r = untangle_and_flip(g);
    EXPECT_FALSE(r.untangling.valid_before);
    EXPECT_TRUE(r.valid_after) << describe(validate(g));
    EXPECT_GE(r.untangling.fork_splits, 1);
    expect_valid_with_area(g);
    // Trials run a batch per thread; the first that helps in order is kept: the same G for any thread count.
    for (int threads : {1, 3}) {
        GeodesicTriangulation again = traced_anchor();
        UntangleAndFlipOptions options;
        options.untangling.threads = threads;
        options.flipping.threads = threads;
        const UntangleAndFlipResult same = untangle_and_flip(again, options);
        EXPECT_EQ(same.untangling.flips, r.untangling.flips) << threads << " threads";
        EXPECT_EQ(same.untangling.fork_splits, r.untangling.fork_splits) << threads << " threads";
        EXPECT_EQ(same.untangling.rejected, r.untangling.rejected) << threads << " threads";
        ASSERT_EQ(again.coarse().n_edges(), g.coarse().n_edges()) << threads << " threads";
        for (auto e : g.coarse().edges()) EXPECT_EQ(again.polyline(e), g.polyline(e)) << threads << " threads";
    }
}

}  // namespace
}  // namespace geotri

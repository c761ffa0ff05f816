// Validation of geodesic triangulations (DESIGN.md §1): hand-made valid and invalid G, one for each condition, on
// procedural meshes, plus a brute-force 3D oracle for crossings on a cube, and a sweep over real meshes.

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/decimate.h>
#include <geotri/fine_mesh.h>
#include <geotri/tangent_angles.h>
#include <geotri/trace.h>
#include <geotri/validate.h>
#include <geotri_test/fine_mesh.h>
#include <geotri_test/g_checks.h>
#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include "check/polyline_verdicts.h"  // libgeotri/src: untangling's verdicts kept between validations
#include "core/plane_segments.h"      // libgeotri/src: when two segments in a fine face meet

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <set>
#include <utility>
#include <vector>

namespace geotri {
namespace {

using geodesic::Mesh;
using geodesic::SurfacePoint;
using test::describe;
using test::fine_of;
using test::nearest_vertex;

constexpr double pi = 3.14159265358979323846;

/// A coarse mesh on the given fine vertices. Each triangle is turned to face away from `centre` (the test shapes
/// are star-shaped about it), so that the coarse orientation agrees with T's.
CoarseMesh coarse_mesh(const Mesh& fine, const std::vector<int>& fine_vertices,
                       std::vector<std::array<int, 3>> triangles, const Eigen::Vector3d& centre) {
    CoarseMesh coarse;
    for (int v : fine_vertices) {
        const Eigen::Vector3d& x = fine.position(v);
        coarse.add_vertex(CoarseMesh::Point(x.x(), x.y(), x.z()));
    }
    for (auto& t : triangles) {
        const Eigen::Vector3d a = fine.position(fine_vertices[t[0]]), b = fine.position(fine_vertices[t[1]]),
                              c = fine.position(fine_vertices[t[2]]);
        if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - centre) < 0.0) std::swap(t[1], t[2]);
        coarse.add_face(OpenMesh::VertexHandle(t[0]), OpenMesh::VertexHandle(t[1]), OpenMesh::VertexHandle(t[2]));
    }
    return coarse;
}

/// Every edge made the shortest geodesic between its ends, independently of trace(): one complete propagation per
/// halfedge's tail.
void trace_shortest(GeodesicTriangulation& g) {
    geodesic::ExactGeodesic exact(g.fine().mesh);
    for (auto e : g.coarse().edges()) {
        const auto h = g.coarse().halfedge_handle(e, 0);
        exact.propagate({g.location(g.coarse().from_vertex_handle(h))});
        g.set_path(h, exact.shortest_path(g.location(g.coarse().to_vertex_handle(h))));
    }
}

/// G on the fine mesh with coarse vertices at the given fine vertices and the given triangles, traced.
GeodesicTriangulation make_g(std::shared_ptr<const FineMesh> fine, const std::vector<int>& at,
                             const std::vector<std::array<int, 3>>& triangles, const Eigen::Vector3d& centre) {
    GeodesicTriangulation g(fine, coarse_mesh(fine->mesh, at, triangles, centre));
    for (auto v : g.coarse().vertices()) g.set_location(v, SurfacePoint::at_vertex(at[v.idx()]));
    trace_shortest(g);
    return g;
}

/// A regular tetrahedron inscribed in the unit icosphere.
GeodesicTriangulation tetrahedron_on_sphere(std::shared_ptr<const FineMesh> fine, bool reversed = false) {
    std::vector<int> at;
    for (const Eigen::Vector3d& d : {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, -1, -1), Eigen::Vector3d(-1, 1, -1),
                                     Eigen::Vector3d(-1, -1, 1)})
        at.push_back(nearest_vertex(fine->mesh, d.normalized()));
    GeodesicTriangulation g = make_g(fine, at, {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}, {0, 0, 0});
    if (!reversed) return g;
    // The same vertices and geodesics, with every coarse triangle turned over.
    CoarseMesh turned;
    for (auto v : g.coarse().vertices()) turned.add_vertex(g.coarse().point(v));
    for (auto f : g.coarse().faces()) {
        std::vector<OpenMesh::VertexHandle> vs;
        for (auto v : g.coarse().fv_range(f)) vs.push_back(v);
        turned.add_face(vs[0], vs[2], vs[1]);
    }
    GeodesicTriangulation r(fine, turned);
    for (auto v : r.coarse().vertices()) r.set_location(v, g.location(v));
    trace_shortest(r);
    return r;
}

/// The cube [0,1]^3 (n x n cells per side) with the eight corners as coarse vertices and each side split by a
/// diagonal. Corner k sits at (k & 1, k >> 1 & 1, k >> 2 & 1).
std::vector<std::array<int, 3>> cube_triangles() {
    return {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
            {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}};
}

std::vector<int> cube_corners(const Mesh& mesh) {
    std::vector<int> at;
    for (int k = 0; k < 8; ++k) at.push_back(nearest_vertex(mesh, Eigen::Vector3d(k & 1, k >> 1 & 1, k >> 2 & 1)));
    return at;
}

bool has_violation(const ValidationReport& r, int condition, const std::vector<int>& vertices,
                   const std::vector<int>& edges) {
    for (const Violation& v : r.violations) {
        if (v.condition != condition) continue;
        bool all = true;
        for (int x : vertices) all = all && std::count(v.coarse_vertices.begin(), v.coarse_vertices.end(), x) > 0;
        for (int x : edges) all = all && std::count(v.coarse_edges.begin(), v.coarse_edges.end(), x) > 0;
        if (all) return true;
    }
    return false;
}

int edge_between(const CoarseMesh& coarse, int a, int b) {
    const auto h = coarse.find_halfedge(OpenMesh::VertexHandle(a), OpenMesh::VertexHandle(b));
    return h.is_valid() ? coarse.edge_handle(h).idx() : -1;
}

// ---------------------------------------------------------------------------------------------------------------

TEST(Validate, tetrahedron_on_a_sphere_is_valid_with_its_summary) {
    const auto fine = fine_of(test::icosphere(3));
    const GeodesicTriangulation g = tetrahedron_on_sphere(fine);
    const ValidationReport r = validate(g);
    EXPECT_TRUE(r.valid) << describe(r);
    EXPECT_EQ(r.violation_count, (std::array<int, 4>{0, 0, 0, 0}));
    EXPECT_EQ(r.vertices, 4);
    EXPECT_EQ(r.edges, 6);
    EXPECT_EQ(r.faces, 4);
    EXPECT_EQ(r.components, 1);
    EXPECT_EQ(r.genus, 0);
    EXPECT_TRUE(r.overlay_checked);
    const double area = fine->mesh.total_area();
    EXPECT_EQ(r.fine_area, area);
    EXPECT_NEAR(r.patch_area, area, 1e-9 * area);

    // Edge lengths are the geodesic distances between the ends, from a fresh propagation.
    geodesic::ExactGeodesic exact(fine->mesh);
    double lo = 1e300, hi = 0.0, sum = 0.0;
    for (auto e : g.coarse().edges()) {
        const auto h = g.coarse().halfedge_handle(e, 0);
        exact.propagate({g.location(g.coarse().from_vertex_handle(h))});
        const double d = exact.distance(g.location(g.coarse().to_vertex_handle(h)));
        lo = std::min(lo, d);
        hi = std::max(hi, d);
        sum += d;
    }
    EXPECT_NEAR(r.min_edge_length, lo, 1e-12);
    EXPECT_NEAR(r.max_edge_length, hi, 1e-12);
    EXPECT_NEAR(r.mean_edge_length, sum / 6, 1e-12);
    // A regular spherical tetrahedron has corner angles of 120°; the polyhedral sphere is close to it.
    EXPECT_GT(r.min_corner_angle_deg, 110.0);
    EXPECT_LT(r.max_corner_angle_deg, 130.0);
}

TEST(Validate, cube_corners_on_a_cube_are_valid) {
    for (bool irregular : {false, true}) {
        const auto fine = fine_of(test::cube(4, 1.0, irregular, 2));
        const GeodesicTriangulation g = make_g(fine, cube_corners(fine->mesh), cube_triangles(), {0.5, 0.5, 0.5});
        const ValidationReport r = validate(g);
        EXPECT_TRUE(r.valid) << describe(r);
        EXPECT_EQ(r.genus, 0);
        // The corner angles of the coarse cube are 45° and 90° exactly (up to rounding).
        EXPECT_NEAR(r.min_corner_angle_deg, 45.0, 1e-9);
        EXPECT_NEAR(r.max_corner_angle_deg, 90.0, 1e-9);
        EXPECT_NEAR(r.min_edge_length, 1.0, 1e-12);
        EXPECT_NEAR(r.max_edge_length, std::sqrt(2.0), 1e-12);
        EXPECT_NEAR(r.patch_area, 6.0, 6e-9);
    }
}

TEST(Validate, two_components_count_their_genus) {
    const auto fine = fine_of(test::disjoint_union(test::cube(3), test::cube(2), {3, 0, 0}));
    std::vector<int> at = cube_corners(fine->mesh);
    for (int k = 0; k < 8; ++k)
        at.push_back(nearest_vertex(fine->mesh, Eigen::Vector3d(3 + (k & 1), k >> 1 & 1, k >> 2 & 1)));
    std::vector<std::array<int, 3>> triangles = cube_triangles();
    for (auto t : cube_triangles()) triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
    // Each cube is oriented about its own centre.
    std::vector<std::array<int, 3>> oriented;
    for (auto t : triangles) {
        const Eigen::Vector3d centre = t[0] < 8 ? Eigen::Vector3d(0.5, 0.5, 0.5) : Eigen::Vector3d(3.5, 0.5, 0.5);
        const Eigen::Vector3d a = fine->mesh.position(at[t[0]]), b = fine->mesh.position(at[t[1]]),
                              c = fine->mesh.position(at[t[2]]);
        if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - centre) < 0.0) std::swap(t[1], t[2]);
        oriented.push_back(t);
    }
    CoarseMesh both;
    for (int v : at) {
        const Eigen::Vector3d& x = fine->mesh.position(v);
        both.add_vertex(CoarseMesh::Point(x.x(), x.y(), x.z()));
    }
    for (const auto& t : oriented)
        both.add_face(OpenMesh::VertexHandle(t[0]), OpenMesh::VertexHandle(t[1]), OpenMesh::VertexHandle(t[2]));
    GeodesicTriangulation g(fine, both);
    for (auto v : g.coarse().vertices()) g.set_location(v, SurfacePoint::at_vertex(at[v.idx()]));
    trace_shortest(g);
    const ValidationReport r = validate(g);
    EXPECT_TRUE(r.valid) << describe(r);
    EXPECT_EQ(r.components, 2);
    EXPECT_EQ(r.genus, 0);
    EXPECT_EQ(r.faces, 24);
    EXPECT_NEAR(r.patch_area, 12.0, 12e-9);
}

// Condition 2: the same geodesics with every coarse triangle turned over. Around each vertex the coarse order is
// now clockwise on T: the geodesics wind twice, each corner is the cone angle minus the true one.
TEST(Validate, turned_over_tetrahedron_winds_twice) {
    const auto fine = fine_of(test::icosphere(3));
    const GeodesicTriangulation g = tetrahedron_on_sphere(fine, true);
    const ValidationReport r = validate(g);
    EXPECT_FALSE(r.valid);
    EXPECT_EQ(r.violation_count[0], 0) << describe(r);
    EXPECT_EQ(r.violation_count[1], 4) << describe(r);
    EXPECT_EQ(r.violation_count[2], 0) << describe(r);
    for (int c = 0; c < 4; ++c) EXPECT_TRUE(has_violation(r, 2, {c}, {})) << describe(r);
    for (const Violation& v : r.violations)
        if (v.condition == 2) {
            EXPECT_NE(v.what.find("wind 2 times"), std::string::npos) << v.what;
        }
    EXPECT_GT(r.min_corner_angle_deg, 230.0);  // 360° less about 120°
}

// Condition 2: on an icosahedron over a sphere, one neighbour Q of a vertex P is moved past the next neighbour R
// around P. P's outgoing geodesics are then out of the coarse order.
TEST(Validate, neighbour_moved_past_the_next_one_puts_corners_out_of_order) {
    const auto fine = fine_of(test::icosphere(4));
    const test::TriangleMesh ico = test::icosphere(0);
    std::vector<int> at;
    for (const auto& x : ico.positions) at.push_back(nearest_vertex(fine->mesh, x));
    GeodesicTriangulation valid = make_g(fine, at, ico.triangles, {0, 0, 0});
    ASSERT_TRUE(validate(valid).valid) << describe(validate(valid));

    const CoarseMesh& coarse = valid.coarse();
    const auto p = OpenMesh::VertexHandle(0);
    const auto hq = coarse.halfedge_handle(p);
    const auto hr = coarse.ccw_rotated_halfedge_handle(hq);
    const int q = coarse.to_vertex_handle(hq).idx(), r_ = coarse.to_vertex_handle(hr).idx();
    const Eigen::Vector3d xq = fine->mesh.position(at[q]), xr = fine->mesh.position(at[r_]);
    std::vector<int> moved = at;
    moved[q] = nearest_vertex(fine->mesh, (xr + 0.5 * (xr - xq)).normalized());
    // The valid mesh's connectivity, with Q's new location.
    GeodesicTriangulation h(fine, valid.coarse());
    for (auto v : h.coarse().vertices()) h.set_location(v, SurfacePoint::at_vertex(moved[v.idx()]));
    trace_shortest(h);
    const ValidationReport r = validate(h);
    EXPECT_FALSE(r.valid);
    EXPECT_EQ(r.violation_count[0], 0) << describe(r);
    EXPECT_TRUE(has_violation(r, 2, {0}, {})) << describe(r);
}

// Condition 1: a crossing moved along its edge bends the polyline there; a polyline that turns at a fine vertex
// between its ends bends there; a polyline stored backwards does not start at its first vertex.
TEST(Validate, polyline_that_is_not_straight_is_found) {
    const auto fine = fine_of(test::icosphere(3));
    GeodesicTriangulation g = tetrahedron_on_sphere(fine);
    int bent = -1;
    for (auto e : g.coarse().edges()) {
        Polyline path = g.polyline(e);
        for (std::size_t i = 1; i + 1 < path.size() && bent < 0; ++i) {
            if (path[i].kind != geodesic::PointKind::edge || path[i].t < 0.2 || path[i].t > 0.8) continue;
            path[i].t += 0.05;
            bent = e.idx();
            g.set_polyline(e, path);
        }
    }
    ASSERT_GE(bent, 0);
    const ValidationReport r = validate(g);
    EXPECT_EQ(r.violation_count[0], 1) << describe(r);
    EXPECT_TRUE(has_violation(r, 1, {}, {bent})) << describe(r);
    EXPECT_NE(r.violations.front().what.find("not straight"), std::string::npos) << describe(r);

    // A crossing moved by 1e-9 of its edge is off straight by far more than the 2e-12·size tolerance; moved by
    // 1e-15 it is within rounding.
    for (const double shift : {1e-9, 1e-15}) {
        GeodesicTriangulation s = tetrahedron_on_sphere(fine);
        const auto e = OpenMesh::EdgeHandle(bent);
        Polyline path = s.polyline(e);
        for (std::size_t i = 1; i + 1 < path.size(); ++i) {
            if (path[i].kind != geodesic::PointKind::edge || path[i].t < 0.2 || path[i].t > 0.8) continue;
            path[i].t += shift;
            break;
        }
        s.set_polyline(e, path);
        EXPECT_EQ(validate(s, ValidationOptions{false}).violation_count[0], shift > 1e-12 ? 1 : 0) << shift;
    }

    // Backwards.
    GeodesicTriangulation b = tetrahedron_on_sphere(fine);
    const auto e0 = OpenMesh::EdgeHandle(0);
    Polyline reversed = b.polyline(e0);
    std::reverse(reversed.begin(), reversed.end());
    b.set_polyline(e0, reversed);
    const ValidationReport rb = validate(b);
    EXPECT_TRUE(has_violation(rb, 1, {}, {0})) << describe(rb);
}

TEST(Validate, polyline_turning_at_a_fine_vertex_is_found) {
    const auto fine = fine_of(test::cube(4));
    GeodesicTriangulation g = make_g(fine, cube_corners(fine->mesh), cube_triangles(), {0.5, 0.5, 0.5});
    // The diagonal from corner 0 (0,0,0) to corner 3 (1,1,0), replaced by a detour through the fine vertex
    // (0.5, 0, 0) on the cube's edge: both pieces are geodesics, but the path turns by about 63° there.
    const int e = edge_between(g.coarse(), 0, 3);
    ASSERT_GE(e, 0);
    const int k = nearest_vertex(fine->mesh, {0.5, 0, 0});
    geodesic::ExactGeodesic exact(fine->mesh);
    exact.propagate({SurfacePoint::at_vertex(k)});
    Polyline first = exact.shortest_path(g.location(OpenMesh::VertexHandle(0)));
    std::reverse(first.begin(), first.end());
    const Polyline second = exact.shortest_path(g.location(OpenMesh::VertexHandle(3)));
    Polyline detour = first;
    detour.insert(detour.end(), second.begin() + 1, second.end());
    g.set_path(g.coarse().find_halfedge(OpenMesh::VertexHandle(0), OpenMesh::VertexHandle(3)), detour);
    const ValidationReport r = validate(g);
    EXPECT_TRUE(has_violation(r, 1, {0, 3}, {e})) << describe(r);
    EXPECT_EQ(r.violation_count[0], 1) << describe(r);
    bool named = false;
    for (const Violation& v : r.violations)
        named = named || v.what.find("bends at fine vertex " + std::to_string(k)) != std::string::npos;
    EXPECT_TRUE(named) << describe(r);
}

// ---------------------------------------------------------------------------------------------------------------
// Condition 3 on a cube against a brute-force oracle: the cube's sides are planar, so two polylines meet exactly
// when two of their straight 3D segments do (away from a common end), and a polyline passes through a coarse vertex
// when one of its segments does.

double segment_segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                                const Eigen::Vector3d& q1, Eigen::Vector3d& at) {
    // Sampled minimisation refined by a dense search: slow, but shares nothing with the validator.
    double best = 1e300;
    const int n = 64;
    double bs = 0, bt = 0;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double d = ((p0 + (p1 - p0) * i / n) - (q0 + (q1 - q0) * j / n)).norm();
            if (d < best) {
                best = d;
                bs = double(i) / n;
                bt = double(j) / n;
            }
        }
    // Exact closest points of two segments by clamped projection, started from the sampled optimum.
    double s = bs, t = bt;
    for (int it = 0; it < 50; ++it) {
        const Eigen::Vector3d u = p1 - p0, v = q1 - q0;
        const Eigen::Vector3d q = q0 + t * v;
        s = u.squaredNorm() > 0 ? std::clamp((q - p0).dot(u) / u.squaredNorm(), 0.0, 1.0) : 0.0;
        const Eigen::Vector3d p = p0 + s * u;
        t = v.squaredNorm() > 0 ? std::clamp((p - q0).dot(v) / v.squaredNorm(), 0.0, 1.0) : 0.0;
    }
    at = p0 + s * (p1 - p0);
    return std::min(best, ((p0 + s * (p1 - p0)) - (q0 + t * (q1 - q0))).norm());
}

std::set<std::pair<int, int>> oracle_meetings(const GeodesicTriangulation& g) {
    const Mesh& mesh = g.fine().mesh;
    const CoarseMesh& coarse = g.coarse();
    const int ne = static_cast<int>(coarse.n_edges());
    std::vector<std::vector<Eigen::Vector3d>> x(ne);
    std::vector<std::array<int, 2>> ends(ne);
    for (auto e : coarse.edges()) {
        for (const SurfacePoint& p : g.polyline(e)) x[e.idx()].push_back(mesh.point(p));
        const auto h = coarse.halfedge_handle(e, 0);
        ends[e.idx()] = {coarse.from_vertex_handle(h).idx(), coarse.to_vertex_handle(h).idx()};
    }
    std::set<std::pair<int, int>> meetings;
    const double eps = 1e-9;
    for (int a = 0; a < ne; ++a) {
        for (int b = a + 1; b < ne; ++b) {
            std::vector<Eigen::Vector3d> shared;
            for (int i : ends[a])
                for (int j : ends[b])
                    if (i == j) shared.push_back(mesh.point(g.location(OpenMesh::VertexHandle(i))));
            bool meet = false;
            for (std::size_t i = 0; i + 1 < x[a].size() && !meet; ++i) {
                for (std::size_t j = 0; j + 1 < x[b].size() && !meet; ++j) {
                    Eigen::Vector3d at;
                    if (segment_segment_distance(x[a][i], x[a][i + 1], x[b][j], x[b][j + 1], at) > eps) continue;
                    bool at_common_end = false;
                    for (const auto& s : shared) at_common_end = at_common_end || (at - s).norm() < eps;
                    meet = !at_common_end;
                }
            }
            if (meet) meetings.insert({a, b});
        }
        // Through a coarse vertex that is not an end: recorded as (edge, ne + vertex).
        for (auto v : coarse.vertices()) {
            if (v.idx() == ends[a][0] || v.idx() == ends[a][1]) continue;
            const Eigen::Vector3d c = mesh.point(g.location(v));
            for (std::size_t i = 0; i + 1 < x[a].size(); ++i) {
                Eigen::Vector3d at;
                if (segment_segment_distance(x[a][i], x[a][i + 1], c, c, at) <= eps) {
                    meetings.insert({a, ne + v.idx()});
                    break;
                }
            }
        }
    }
    return meetings;
}

std::set<std::pair<int, int>> reported_meetings(const GeodesicTriangulation& g, const ValidationReport& r) {
    const int ne = static_cast<int>(g.coarse().n_edges());
    std::set<std::pair<int, int>> meetings;
    for (const Violation& v : r.violations) {
        if (v.condition != 3) continue;
        if (v.coarse_edges.size() == 2) {
            meetings.insert({std::min(v.coarse_edges[0], v.coarse_edges[1]), std::max(v.coarse_edges[0], v.coarse_edges[1])});
        } else if (v.coarse_edges.size() == 1) {
            // passes through a coarse vertex: the one that is not an end of the edge
            const auto h = g.coarse().halfedge_handle(OpenMesh::EdgeHandle(v.coarse_edges[0]), 0);
            for (int c : v.coarse_vertices)
                if (c != g.coarse().from_vertex_handle(h).idx() && c != g.coarse().to_vertex_handle(h).idx())
                    meetings.insert({v.coarse_edges[0], ne + c});
        }
    }
    return meetings;
}

TEST(Validate, crossings_on_a_cube_match_a_brute_force_oracle) {
    const auto fine = fine_of(test::cube(4, 1.0, true, 9));
    const std::vector<int> corners = cube_corners(fine->mesh);
    // Corner 7 (1,1,1) moved to fine vertices of the top side and of the side x = 1, so that some of its
    // geodesics cross others.
    int scenarios_with_crossings = 0;
    for (const Eigen::Vector3d& target :
         {Eigen::Vector3d(0.25, 0.75, 1.0), Eigen::Vector3d(0.25, 0.25, 1.0), Eigen::Vector3d(1.0, 0.25, 0.25),
          Eigen::Vector3d(0.75, 0.5, 1.0), Eigen::Vector3d(0.5, 0.25, 1.0), Eigen::Vector3d(1.0, 0.75, 0.25),
          Eigen::Vector3d(0.25, 1.0, 0.5), Eigen::Vector3d(0.0, 0.25, 0.75)}) {
        GeodesicTriangulation g(fine, coarse_mesh(fine->mesh, corners, cube_triangles(), {0.5, 0.5, 0.5}));
        for (auto v : g.coarse().vertices()) g.set_location(v, SurfacePoint::at_vertex(corners[v.idx()]));
        g.set_location(OpenMesh::VertexHandle(7), SurfacePoint::at_vertex(nearest_vertex(fine->mesh, target)));
        trace_shortest(g);
        const ValidationReport r = validate(g);
        const auto expected = oracle_meetings(g);
        EXPECT_EQ(reported_meetings(g, r), expected) << describe(r);
        EXPECT_EQ(r.violation_count[2], static_cast<int>(expected.size())) << describe(r);
        if (!expected.empty()) ++scenarios_with_crossings;
        std::printf("corner 7 at (%g, %g, %g): %zu meetings\n", target.x(), target.y(), target.z(), expected.size());
    }
    EXPECT_GE(scenarios_with_crossings, 4);
}

// Condition 3: a coarse vertex placed on the middle of a geodesic between two others: at a fine vertex, on a fine
// edge, and inside a fine face.
// Bisecting a geodesic again and again inside one fine face leaves pieces on one line, and the orientation tests of
// two pieces are then rounding noise that can look like a crossing. These are four ends of such pieces, in the frame
// of a fine face of fandisk (the line through its corner at the origin, at 0.5, 0.75, 0.875 and 0.9375 of the way):
// the pieces are apart by an eighth of the line. Segments that truly cross still cross, even nearly parallel ones.
TEST(Validate, pieces_of_one_straight_geodesic_are_apart_and_crossing_segments_cross) {
    const Eigen::Vector2d half(0.0067341170456827765, 0.0067070851537115407);
    const Eigen::Vector2d three_quarters(0.0033670585228413883, 0.0033535425768557703);
    const Eigen::Vector2d seven_eighths(0.0016835292614206941, 0.0016767712884278852);
    const Eigen::Vector2d fifteen_sixteenths(0.00084176463071034707, 0.00083838564421394258);
    const double gap = (seven_eighths - three_quarters).norm();
    EXPECT_NEAR(detail::segment_distance(half, three_quarters, fifteen_sixteenths, seven_eighths), gap, 1e-15);
    EXPECT_NEAR(detail::segment_distance(fifteen_sixteenths, seven_eighths, half, three_quarters), gap, 1e-15);
    const Eigen::Vector2d across(-three_quarters.y(), three_quarters.x());
    EXPECT_EQ(detail::segment_distance(half, seven_eighths, three_quarters - across, three_quarters + across), 0.0);
    const Eigen::Vector2d tilt = 1e-6 * across;
    EXPECT_EQ(detail::segment_distance(half, fifteen_sixteenths, three_quarters - tilt + (half - three_quarters) / 4,
                                       three_quarters + tilt - (half - three_quarters) / 4),
              0.0);
}

TEST(Validate, geodesic_through_another_coarse_vertex_is_found) {
    const auto fine = fine_of(test::cube(4, 1.0, true, 5));
    const std::vector<int> corners = cube_corners(fine->mesh);
    // A ninth coarse vertex M splits the bottom triangle (0, 1, 3) and first sits inside it, at (0.75, 0.25, 0);
    // then it is moved onto the top diagonal from corner 4 (0,0,1) to corner 7 (1,1,1).
    CoarseMesh coarse;
    {
        CoarseMesh oriented = coarse_mesh(fine->mesh, corners, cube_triangles(), {0.5, 0.5, 0.5});
        for (auto v : oriented.vertices()) coarse.add_vertex(oriented.point(v));
        const auto m = coarse.add_vertex(CoarseMesh::Point(0.75, 0.25, 0.0));
        for (auto f : oriented.faces()) {
            std::vector<OpenMesh::VertexHandle> vs;
            for (auto v : oriented.fv_range(f)) vs.push_back(v);
            std::vector<int> ids{vs[0].idx(), vs[1].idx(), vs[2].idx()};
            std::sort(ids.begin(), ids.end());
            if (ids == std::vector<int>{0, 1, 3}) {
                for (int i = 0; i < 3; ++i) coarse.add_face(vs[i], vs[(i + 1) % 3], m);
            } else {
                coarse.add_face(vs[0], vs[1], vs[2]);
            }
        }
    }
    ASSERT_EQ(coarse.n_faces(), 14u);

    const GeodesicTriangulation base = [&] {
        GeodesicTriangulation g(fine, coarse);
        for (int v = 0; v < 8; ++v) g.set_location(OpenMesh::VertexHandle(v), SurfacePoint::at_vertex(corners[v]));
        g.set_location(OpenMesh::VertexHandle(8), SurfacePoint::at_vertex(nearest_vertex(fine->mesh, {0.75, 0.25, 0})));
        trace_shortest(g);
        return g;
    }();
    ASSERT_TRUE(validate(base).valid) << describe(validate(base));
    const int diagonal = edge_between(coarse, 4, 7);
    ASSERT_GE(diagonal, 0);
    const Polyline path = base.path(coarse.find_halfedge(OpenMesh::VertexHandle(4), OpenMesh::VertexHandle(7)));

    // Points on the diagonal: an interior polyline point, and the middle of each segment; and a hair (1e-15 of a
    // fine edge) away from each interior point at a fine vertex, on a fine edge at it.
    std::vector<SurfacePoint> places;
    const Mesh& mesh = fine->mesh;
    int hair_away = 0;
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
        places.push_back(path[i]);
        if (path[i].kind != geodesic::PointKind::vertex) continue;
        const int v = path[i].vertex, w = mesh.head(*mesh.outgoing_halfedges(v).begin());
        places.push_back(SurfacePoint::on_edge(v, w, 1e-15));
        ++hair_away;
    }
    ASSERT_GT(hair_away, 0) << "the diagonal should pass through a fine vertex";
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
        const Eigen::Vector3d mid = 0.5 * (mesh.point(path[i]) + mesh.point(path[i + 1]));
        if (on_common_edge(mesh, path[i], path[i + 1])) {
            int a = -1, b = -1;
            for (const SurfacePoint& p : {path[i], path[i + 1]}) {
                if (p.kind == geodesic::PointKind::edge) {
                    a = p.edge_v0;
                    b = p.edge_v1;
                }
            }
            if (a < 0) {
                a = path[i].vertex;
                b = path[i + 1].vertex;
            }
            const double t = (mid - mesh.position(a)).dot(mesh.position(b) - mesh.position(a)) /
                             (mesh.position(b) - mesh.position(a)).squaredNorm();
            places.push_back(SurfacePoint::on_edge(a, b, t));
        } else {
            const int f = common_face(mesh, path[i], path[i + 1]);
            const auto& t = mesh.triangle(f);
            const Eigen::Vector3d x0 = mesh.position(t[0]), x1 = mesh.position(t[1]), x2 = mesh.position(t[2]);
            const Eigen::Vector3d n = (x1 - x0).cross(x2 - x0);
            const double b0 = (x2 - x1).cross(mid - x1).dot(n) / n.squaredNorm();
            const double b1 = (x0 - x2).cross(mid - x2).dot(n) / n.squaredNorm();
            places.push_back(SurfacePoint::in_face(f, {b0, b1, 1.0 - b0 - b1}));
        }
    }
    std::set<geodesic::PointKind> kinds;
    for (const SurfacePoint& place : places) {
        GeodesicTriangulation g(fine, coarse);
        for (int v = 0; v < 8; ++v) g.set_location(OpenMesh::VertexHandle(v), SurfacePoint::at_vertex(corners[v]));
        g.set_location(OpenMesh::VertexHandle(8), place);
        trace_shortest(g);
        kinds.insert(g.location(OpenMesh::VertexHandle(8)).kind);
        const ValidationReport r = validate(g);
        bool found = false;
        for (const Violation& v : r.violations)
            found = found || (v.condition == 3 && v.coarse_edges == std::vector<int>{diagonal} &&
                              std::count(v.coarse_vertices.begin(), v.coarse_vertices.end(), 8) == 1 &&
                              v.what.find("passes through coarse vertex 8") != std::string::npos);
        EXPECT_TRUE(found) << geodesic::to_spec(place) << "\n" << describe(r);
    }
    EXPECT_EQ(kinds.size(), 3u) << "the diagonal should give a vertex, an edge and a face point";
}

// Condition 3: two coarse edges with the same polyline overlap, and two coarse vertices at one point meet.
TEST(Validate, overlapping_geodesics_and_coincident_vertices_are_found) {
    const auto fine = fine_of(test::icosphere(3));
    GeodesicTriangulation g = tetrahedron_on_sphere(fine);
    // Coarse vertex 3 moved onto coarse vertex 0: its three geodesics start where 0's do.
    g.set_location(OpenMesh::VertexHandle(3), g.location(OpenMesh::VertexHandle(0)));
    trace_shortest(g);
    const ValidationReport r = validate(g);
    EXPECT_FALSE(r.valid);
    bool coincident = false, overlap = false;
    const int e01 = edge_between(g.coarse(), 0, 1), e31 = edge_between(g.coarse(), 3, 1);
    for (const Violation& v : r.violations) {
        coincident = coincident || (v.condition == 3 && v.what.find("coarse vertices 0 and 3") != std::string::npos);
        overlap = overlap || (v.condition == 3 && v.coarse_edges.size() == 2 &&
                              std::count(v.coarse_edges.begin(), v.coarse_edges.end(), e01) == 1 &&
                              std::count(v.coarse_edges.begin(), v.coarse_edges.end(), e31) == 1);
    }
    EXPECT_TRUE(coincident) << describe(r);
    EXPECT_TRUE(overlap) << describe(r);
}

// Condition 4: the turned-over tetrahedron's patches are bounded the wrong way round, so the overlay cannot make
// them disks; with the overlay off, condition 4 is not checked and the other conditions are unchanged.
TEST(Validate, patches_that_do_not_cover_t_are_found) {
    const auto fine = fine_of(test::icosphere(3));
    const GeodesicTriangulation g = tetrahedron_on_sphere(fine, true);
    const ValidationReport r = validate(g);
    EXPECT_TRUE(r.overlay_checked);
    EXPECT_GT(r.violation_count[3], 0) << describe(r);
    const ValidationReport skipped = validate(g, ValidationOptions{false});
    EXPECT_FALSE(skipped.overlay_checked);
    EXPECT_EQ(skipped.violation_count[3], 0);
    EXPECT_EQ(skipped.violation_count[1], r.violation_count[1]);
}

// Untangling checks conditions 1-3 first and adds the overlay only when they allow: the report must then be the
// one that validate() gives, violation for violation.
TEST(Validate, overlay_check_added_later_gives_the_full_report) {
    const auto fine = fine_of(test::icosphere(3));
    for (bool turned_over : {false, true}) {
        const GeodesicTriangulation g = tetrahedron_on_sphere(fine, turned_over);
        const ValidationReport full = validate(g);
        ValidationReport later = validate(g, ValidationOptions{false});
        add_overlay_check(g, later);
        EXPECT_TRUE(later.overlay_checked);
        EXPECT_EQ(later.valid, full.valid);
        EXPECT_EQ(later.violation_count, full.violation_count);
        ASSERT_EQ(later.violations.size(), full.violations.size());
        for (std::size_t k = 0; k < full.violations.size(); ++k) EXPECT_EQ(later.violations[k].what, full.violations[k].what);
        EXPECT_EQ(later.patch_area, full.patch_area);
        // A second call adds nothing.
        add_overlay_check(g, later);
        EXPECT_EQ(later.violation_count, full.violation_count);
    }
}

TEST(Validate, verdicts_kept_from_another_g_give_the_same_report) {
    const auto fine = fine_of(test::icosphere(3));
    const GeodesicTriangulation g = tetrahedron_on_sphere(fine);
    const detail::PolylineVerdicts known(g, {});
    const ValidationOptions cheap{false};
    auto same = [&](const GeodesicTriangulation& copy) {
        const ValidationReport plain = validate(copy, cheap), kept = detail::validate(copy, cheap, known);
        EXPECT_EQ(kept.violation_count, plain.violation_count);
        EXPECT_EQ(kept.violations.size(), plain.violations.size());
        for (std::size_t k = 0; k < std::min(plain.violations.size(), kept.violations.size()); ++k)
            EXPECT_EQ(kept.violations[k].what, plain.violations[k].what);
        return plain;
    };
    EXPECT_TRUE(same(g).valid);

    // A copy with one polyline bent and another reversed: both are new polylines, judged afresh.
    GeodesicTriangulation changed = g;
    const auto e0 = OpenMesh::EdgeHandle(0), e1 = OpenMesh::EdgeHandle(1);
    Polyline bent = changed.polyline(e0);
    for (std::size_t i = 1; i + 1 < bent.size(); ++i)
        if (bent[i].kind == geodesic::PointKind::edge && bent[i].t > 0.2 && bent[i].t < 0.8) {
            bent[i].t += 0.05;
            break;
        }
    changed.set_polyline(e0, bent);
    Polyline reversed = changed.polyline(e1);
    std::reverse(reversed.begin(), reversed.end());
    changed.set_polyline(e1, reversed);
    const ValidationReport r = same(changed);
    EXPECT_TRUE(has_violation(r, 1, {}, {0})) << describe(r);
    EXPECT_TRUE(has_violation(r, 1, {}, {1})) << describe(r);

    // Verdicts kept from the changed G, for a copy where the polylines are as in g again.
    const detail::PolylineVerdicts from_changed(changed, known);
    GeodesicTriangulation restored = changed;
    restored.set_polyline(e0, g.polyline(e0));
    restored.set_polyline(e1, g.polyline(e1));
    EXPECT_TRUE(detail::validate(restored, cheap, from_changed).valid);
    EXPECT_EQ(detail::validate(changed, cheap, from_changed).violation_count, r.violation_count);
}

TEST(Validate, malformed_locations_are_refused) {
    const auto fine = fine_of(test::icosphere(1));
    GeodesicTriangulation g = tetrahedron_on_sphere(fine);
    g.set_polyline(OpenMesh::EdgeHandle(0), {});  // an untraced edge is a violation, not malformed
    EXPECT_TRUE(has_violation(validate(g), 1, {}, {0}));
    CoarseMesh coarse = g.coarse();
    GeodesicTriangulation h(fine, coarse);  // locations left unset: vertex -1
    EXPECT_THROW(validate(h), InvalidInput);
}

// ---------------------------------------------------------------------------------------------------------------
// Real meshes: the shortest geodesics that trace() makes satisfy condition 1, the summary matches T's topology, and
// validation is fast.

TEST(Validate, traced_real_meshes_have_geodesic_polylines) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at '" << test::configured_shared_data_dir()
                     << "' (set GEOTRI_SHARED_DATA)";
    for (const char* name : {"anatomy/lumbar_spine_L2-L5_mean.ply", "classic/3holes.off", "cad/fandisk.off",
                             "stress/triceratops.off"}) {
        const test::SharedMesh shared = test::shared_mesh(name);
        const auto fine = std::make_shared<const FineMesh>(load_fine_mesh(shared.path));
        DecimateOptions options;
        options.target_faces = fine->mesh.num_faces() > 100000 ? 1232 : 320;
        const DecimateResult decimated = decimate(*fine, options);
        CoarseMesh coarse;
        for (const auto& x : decimated.coarse.positions) coarse.add_vertex(CoarseMesh::Point(x.x(), x.y(), x.z()));
        for (const auto& t : decimated.coarse.triangles)
            coarse.add_face(OpenMesh::VertexHandle(t[0]), OpenMesh::VertexHandle(t[1]), OpenMesh::VertexHandle(t[2]));
        GeodesicTriangulation g(fine, coarse);
        trace(g);

        const auto start = std::chrono::steady_clock::now();
        const ValidationReport r = validate(g, ValidationOptions{false});
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_EQ(r.violation_count[0], 0) << name << "\n" << describe(r);
        EXPECT_EQ(r.faces, static_cast<int>(decimated.coarse.triangles.size()));
        int genus = 0;
        for (const DecimateComponent& c : decimated.components) genus += c.genus;
        EXPECT_EQ(r.genus, genus) << name;
        EXPECT_EQ(r.components, fine->num_components) << name;
        EXPECT_LT(seconds, 2.0) << name;  // well under a second on an idle core
        std::printf("%s: %d coarse faces, conditions 1-3 in %.3f s: %d/%d/%d violations, corners %.3g..%.3g deg\n",
                    name, r.faces, seconds, r.violation_count[0], r.violation_count[1], r.violation_count[2],
                    r.min_corner_angle_deg, r.max_corner_angle_deg);
    }
}

}  // namespace
}  // namespace geotri

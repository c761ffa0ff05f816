// Straightest geodesics (trace_straight_geodesic) against oracles that do not share its unfolding: straight lines in
// the plane, the cube unrolled by hand, 3D directions in the faces of a saddle fan, retracing, and exact geodesic
// distances (libgeodesic) on a real mesh.

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geodesic/mesh.h>
#include <geotri/fine_mesh.h>
#include <geotri/mesh_io.h>
#include <geotri/straight_geodesic.h>
#include <geotri/tangent_angles.h>
#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

namespace geotri {
namespace {

using geodesic::Mesh;
using geodesic::PointKind;
using geodesic::SurfacePoint;

constexpr double pi = 3.14159265358979323846;

/// Counter-clockwise angle from u to w about the axis n, in [0, 2π).
double ccw_about(const Eigen::Vector3d& n, const Eigen::Vector3d& u, const Eigen::Vector3d& w) {
    const double a = std::atan2(n.dot(u.cross(w)), u.dot(w));
    return a < 0.0 ? a + 2.0 * pi : a;
}

/// u rotated counter-clockwise by angle about the unit axis n (u orthogonal to n).
Eigen::Vector3d rotate_about(const Eigen::Vector3d& n, const Eigen::Vector3d& u, double angle) {
    return std::cos(angle) * u + std::sin(angle) * n.cross(u);
}

double circular_difference(double a, double b, double theta) {
    double d = std::fmod(a - b, theta);
    if (d > theta / 2) d -= theta;
    if (d <= -theta / 2) d += theta;
    return d;
}

/// The reference direction of tangent_angles.h at p, from the 3D positions alone.
Eigen::Vector3d reference_direction(const Mesh& mesh, const SurfacePoint& p) {
    const Eigen::Vector3d x = mesh.point(p);
    switch (p.kind) {
        case PointKind::vertex: return (mesh.position(mesh.head(mesh.outgoing(p.vertex))) - x).normalized();
        case PointKind::edge: return (mesh.position(std::max(p.edge_v0, p.edge_v1)) - x).normalized();
        case PointKind::face: return (mesh.position(mesh.triangle(p.face)[0]) - x).normalized();
    }
    return Eigen::Vector3d::Zero();
}

/// The surface point at a 3D position that lies on the mesh (within 1e-12), found by brute force over the faces.
SurfacePoint locate(const Mesh& mesh, const Eigen::Vector3d& x) {
    for (int f = 0; f < mesh.num_faces(); ++f) {
        const auto& t = mesh.triangle(f);
        const Eigen::Vector3d a = mesh.position(t[0]), b = mesh.position(t[1]), c = mesh.position(t[2]);
        const Eigen::Vector3d n = (b - a).cross(c - a);
        const double area2 = n.squaredNorm();
        if (area2 == 0.0 || std::abs(n.normalized().dot(x - a)) > 1e-12) continue;
        const double l0 = n.dot((b - x).cross(c - x)) / area2, l1 = n.dot((c - x).cross(a - x)) / area2;
        const double l2 = 1.0 - l0 - l1;
        if (l0 > 1e-12 && l1 > 1e-12 && l2 > 1e-12) return mesh.canonical(SurfacePoint::in_face(f, {l0, l1, l2}));
    }
    ADD_FAILURE() << "no face holds (" << x.transpose() << ") strictly inside";
    return SurfacePoint::at_vertex(0);
}

/// The invariants every result must satisfy, whatever the mesh.
void expect_well_formed(const Mesh& mesh, const SurfacePoint& start, double angle, double length,
                        const StraightGeodesicResult& r) {
    ASSERT_FALSE(r.path.empty());
    EXPECT_EQ(r.path.front(), mesh.canonical(start));
    EXPECT_EQ(r.path.back(), r.end);
    for (std::size_t i = 0; i < r.path.size(); ++i) {
        if (i > 0) {
            EXPECT_EQ(r.path[i], mesh.canonical(r.path[i])) << "point " << i << " is not canonical";
        }
        if (i > 0 && i + 1 < r.path.size()) {
            EXPECT_NE(r.path[i].kind, PointKind::face) << "interior point " << i << " is inside a face";
        }
        if (i > 0) {
            EXPECT_GE(common_face(mesh, r.path[i - 1], r.path[i]), 0) << "segment " << i << " leaves its face";
        }
    }
    EXPECT_NEAR(geodesic::path_length(mesh, r.path), r.length, 1e-12 * std::max(1.0, length));
    EXPECT_LE(r.length, length * (1.0 + 1e-12));
    if (!r.stopped_at_vertex && !r.stopped_at_boundary) {
        EXPECT_NEAR(r.length, length, 1e-12 * std::max(1.0, length));
    }
    if (r.stopped_at_vertex) {
        EXPECT_EQ(r.end.kind, PointKind::vertex);
    }
    if (r.stopped_at_boundary) {
        EXPECT_EQ(r.end.kind, PointKind::edge);
    }
    if (r.path.size() >= 2) {
        const double theta = cone_angle(mesh, r.path[0]);
        EXPECT_NEAR(circular_difference(initial_polar_angle(mesh, r.path), std::fmod(angle, theta), theta), 0.0, 1e-9);
        const double back = polar_angle(mesh, r.end, r.path[r.path.size() - 2]);
        const double theta_end = cone_angle(mesh, r.end);
        EXPECT_GE(r.arrival_angle, 0.0);
        EXPECT_LT(r.arrival_angle, theta_end);
        // Position-based angles lose accuracy over a short last segment: scale the tolerance by it.
        const double last = (mesh.point(r.end) - mesh.point(r.path[r.path.size() - 2])).norm();
        EXPECT_NEAR(circular_difference(r.arrival_angle, back, theta_end), 0.0, 1e-13 * mesh.size() / last + 1e-9);
    }
}

/// Retraces r from its end in its arrival direction and expects to come back to start.
void expect_retraces(const Mesh& mesh, const SurfacePoint& start, const StraightGeodesicResult& r, double tolerance) {
    const StraightGeodesicResult back = trace_straight_geodesic(mesh, r.end, r.arrival_angle, r.length);
    EXPECT_FALSE(back.stopped_at_boundary);
    EXPECT_LT((mesh.point(back.end) - mesh.point(start)).norm(), tolerance)
        << "from " << geodesic::to_spec(start) << " to " << geodesic::to_spec(r.end) << " and back to "
        << geodesic::to_spec(back.end);
    EXPECT_EQ(back.path.size(), r.path.size());
}

struct FlatCase {
    SurfacePoint start;
    double angle;
};

/// On a perturbed flat grid every straight geodesic is a straight segment of the plane.
TEST(StraightGeodesic, flat_grid_end_is_start_plus_length_times_direction) {
    const Mesh mesh = test::flat_grid(12, 12, 1.0, 1.0, 0.2, 7).to_mesh();
    const int centre = 6 * 13 + 6;
    std::vector<SurfacePoint> starts{SurfacePoint::at_vertex(centre), SurfacePoint::at_vertex(5 * 13 + 7)};
    for (int h : mesh.outgoing_halfedges(centre)) {
        starts.push_back(mesh.canonical(SurfacePoint::on_edge(mesh.tail(h), mesh.head(h), 0.37)));
        starts.push_back(mesh.canonical(SurfacePoint::in_face(Mesh::face_of(h), {0.2, 0.5, 0.3})));
    }
    const Eigen::Vector3d up(0.0, 0.0, 1.0);
    int stopped = 0, runs = 0;
    for (const SurfacePoint& start : starts) {
        const double theta = cone_angle(mesh, start);
        for (int i = 0; i < 23; ++i) {
            const double angle = theta * (i + 0.31) / 23.0;
            const double length = 0.17 + 0.013 * i;  // crosses up to ~8 faces, stays inside the square
            const StraightGeodesicResult r = trace_straight_geodesic(mesh, start, angle, length);
            ++runs;
            SCOPED_TRACE(geodesic::to_spec(start) + " angle " + std::to_string(angle));
            expect_well_formed(mesh, start, angle, length, r);
            EXPECT_FALSE(r.stopped_at_boundary);
            const Eigen::Vector3d dir = rotate_about(up, reference_direction(mesh, start), angle);
            const Eigen::Vector3d expected = mesh.point(start) + r.length * dir;
            EXPECT_LT((mesh.point(r.end) - expected).norm(), 1e-12 * length);
            for (const SurfacePoint& q : r.path) {
                const Eigen::Vector3d w = mesh.point(q) - mesh.point(start);
                EXPECT_LT(std::abs(dir.cross(w).z()), 1e-13) << "path point off the line";
            }
            if (r.stopped_at_vertex) {
                ++stopped;
                continue;
            }
            EXPECT_GE(r.path.size(), 2u);
            expect_retraces(mesh, start, r, 1e-12);
        }
    }
    EXPECT_LE(stopped, runs / 50) << "generic directions should almost never meet a vertex";
}

TEST(StraightGeodesic, flat_square_boundary_stops_where_the_ray_leaves) {
    const Mesh mesh = test::flat_grid(9, 7, 2.0, 1.0, 0.15, 3).to_mesh();
    const SurfacePoint start = locate(mesh, Eigen::Vector3d(0.83, 0.41, 0.0));
    const Eigen::Vector3d up(0.0, 0.0, 1.0);
    for (int i = 0; i < 16; ++i) {
        const double angle = 2.0 * pi * (i + 0.5) / 16.0;
        const StraightGeodesicResult r = trace_straight_geodesic(mesh, start, angle, 10.0);
        SCOPED_TRACE("angle " + std::to_string(angle));
        expect_well_formed(mesh, start, angle, 10.0, r);
        ASSERT_TRUE(r.stopped_at_boundary);
        EXPECT_FALSE(r.stopped_at_vertex);
        // Closed form: the first of the four sides of [0,2]x[0,1] that the ray meets.
        const Eigen::Vector3d p = mesh.point(start);
        const Eigen::Vector3d dir = rotate_about(up, reference_direction(mesh, start), angle);
        double reach = std::numeric_limits<double>::infinity();
        if (dir.x() > 0) reach = std::min(reach, (2.0 - p.x()) / dir.x());
        if (dir.x() < 0) reach = std::min(reach, -p.x() / dir.x());
        if (dir.y() > 0) reach = std::min(reach, (1.0 - p.y()) / dir.y());
        if (dir.y() < 0) reach = std::min(reach, -p.y() / dir.y());
        EXPECT_NEAR(r.length, reach, 1e-12);
        EXPECT_LT((mesh.point(r.end) - (p + reach * dir)).norm(), 1e-12);
    }
    // From the corner vertex (0, 0), a boundary vertex of cone angle π/2: every direction goes inside.
    const SurfacePoint corner = SurfacePoint::at_vertex(0);
    ASSERT_NEAR(cone_angle(mesh, corner), pi / 2, 1e-15);
    for (int i = 0; i < 8; ++i) {
        const double angle = (pi / 2) * (i + 0.5) / 8.0;
        const StraightGeodesicResult r = trace_straight_geodesic(mesh, corner, angle, 0.6);
        expect_well_formed(mesh, corner, angle, 0.6, r);
        EXPECT_FALSE(r.stopped_at_boundary || r.stopped_at_vertex);
        const Eigen::Vector3d dir = rotate_about(up, reference_direction(mesh, corner), angle);
        EXPECT_LT((mesh.point(r.end) - 0.6 * dir).norm(), 1e-12);
        expect_retraces(mesh, corner, r, 1e-12);
    }
}

TEST(StraightGeodesic, stops_exactly_at_a_vertex_on_the_ray) {
    const Mesh mesh = test::flat_grid(8, 8, 8.0, 8.0, 0.0, 5).to_mesh();  // integer vertex positions
    const auto index = [](int i, int j) { return j * 9 + i; };
    const Eigen::Vector3d up(0.0, 0.0, 1.0);
    const SurfacePoint from = SurfacePoint::at_vertex(index(2, 2));
    const int target = index(4, 3);  // direction (2, 1): crosses an edge at (3, 2.5), then meets this vertex
    const Eigen::Vector3d to = mesh.position(target) - mesh.position(index(2, 2));
    const double angle = ccw_about(up, reference_direction(mesh, from), to);
    for (double nudge : {0.0, 1e-15, -1e-15, 4e-15, -4e-15}) {
        const StraightGeodesicResult r = trace_straight_geodesic(mesh, from, angle + nudge, 20.0);
        expect_well_formed(mesh, from, angle + nudge, 20.0, r);
        EXPECT_TRUE(r.stopped_at_vertex) << "nudge " << nudge;
        EXPECT_EQ(r.end, SurfacePoint::at_vertex(target)) << "nudge " << nudge;
        EXPECT_NEAR(r.length, to.norm(), 1e-12);
        EXPECT_NEAR(circular_difference(r.arrival_angle, ccw_about(up, reference_direction(mesh, r.end), -to), 2 * pi),
                    0.0, 1e-12);
    }
    // Just long enough: ends on the vertex without being stopped.
    const StraightGeodesicResult exact = trace_straight_geodesic(mesh, from, angle, to.norm());
    EXPECT_EQ(exact.end, SurfacePoint::at_vertex(target));
    EXPECT_FALSE(exact.stopped_at_vertex);

    // From an edge point towards a vertex, and along an edge in both directions.
    const SurfacePoint mid = mesh.canonical(SurfacePoint::on_edge(index(3, 3), index(4, 3), 0.5));
    const Eigen::Vector3d to2 = mesh.position(index(5, 7)) - mesh.point(mid);  // direction (1.5, 4): no vertex
    const Eigen::Vector3d to3 = mesh.position(index(4, 4)) - mesh.point(mid);  // direction (0.5, 1)
    const StraightGeodesicResult r2 =
        trace_straight_geodesic(mesh, mid, ccw_about(up, reference_direction(mesh, mid), to2), 10.0);
    expect_well_formed(mesh, mid, r2.path.size() > 1 ? initial_polar_angle(mesh, r2.path) : 0.0, 10.0, r2);
    EXPECT_TRUE(r2.stopped_at_vertex);
    EXPECT_EQ(r2.end, SurfacePoint::at_vertex(index(5, 7)));
    EXPECT_NEAR(r2.length, to2.norm(), 1e-12);
    EXPECT_GE(r2.path.size(), 4u);
    const StraightGeodesicResult r3 =
        trace_straight_geodesic(mesh, mid, ccw_about(up, reference_direction(mesh, mid), to3), 10.0);
    EXPECT_TRUE(r3.stopped_at_vertex);
    EXPECT_EQ(r3.end, SurfacePoint::at_vertex(index(4, 4)));
    EXPECT_NEAR(r3.length, to3.norm(), 1e-12);
    const int big = std::max(index(3, 3), index(4, 3)), small = std::min(index(3, 3), index(4, 3));
    for (double a : {0.0, pi}) {
        const StraightGeodesicResult along = trace_straight_geodesic(mesh, mid, a, 3.0);
        expect_well_formed(mesh, mid, a, 3.0, along);
        EXPECT_TRUE(along.stopped_at_vertex);
        EXPECT_EQ(along.end, SurfacePoint::at_vertex(a == 0.0 ? big : small));
        EXPECT_NEAR(along.length, 0.5, 1e-15);
        const StraightGeodesicResult part = trace_straight_geodesic(mesh, mid, a, 0.25);
        ASSERT_EQ(part.end.kind, PointKind::edge);
        EXPECT_NEAR(mesh.point(part.end).x(), a == 0.0 ? 3.75 : 3.25, 1e-15);
    }
    // From a vertex along each of its edges.
    for (int h : mesh.outgoing_halfedges(index(4, 4))) {
        const SurfacePoint v = SurfacePoint::at_vertex(index(4, 4));
        const StraightGeodesicResult along = trace_straight_geodesic(mesh, v, mesh.polar_angle(h), 5.0);
        expect_well_formed(mesh, v, mesh.polar_angle(h), 5.0, along);
        EXPECT_TRUE(along.stopped_at_vertex);
        EXPECT_EQ(along.end, SurfacePoint::at_vertex(mesh.head(h)));
        EXPECT_EQ(along.path.size(), 2u);
        EXPECT_NEAR(along.length, mesh.length(h), 1e-15);
    }
}

/// Cube [0,1]^3: a ray leaving (x0, y0, 1) at the angle alpha from +x (seen from +z) runs over the top, down the face
/// x = 1 and over the bottom. Unrolled, the running coordinate is u = x0 + L cos(alpha).
Eigen::Vector3d cube_unrolled(double x0, double y0, double alpha, double length) {
    const double u = x0 + length * std::cos(alpha), y = y0 + length * std::sin(alpha);
    if (u <= 1.0) return {u, y, 1.0};
    if (u <= 2.0) return {1.0, y, 1.0 - (u - 1.0)};
    return {1.0 - (u - 2.0), y, 0.0};
}

TEST(StraightGeodesic, cube_rays_across_one_and_two_edges_match_the_unrolled_cube) {
    for (bool irregular : {false, true}) {
        const Mesh mesh = test::cube(3, 1.0, irregular, 11).to_mesh();
        const Eigen::Vector3d up(0.0, 0.0, 1.0);
        const double x0 = 0.3, y0 = 0.4;
        const SurfacePoint start = locate(mesh, Eigen::Vector3d(x0, y0, 1.0));
        int checked = 0;
        for (double alpha : {0.0, 0.2, -0.15, 0.25}) {
            const double angle = ccw_about(up, reference_direction(mesh, start), Eigen::Vector3d(std::cos(alpha),
                                                                                                 std::sin(alpha), 0));
            for (double length : {0.5, 1.2, 1.9, 2.3}) {
                const double y = y0 + length * std::sin(alpha);
                if (x0 + length * std::cos(alpha) > 2.9 || y < 0.01 || y > 0.99) continue;  // off the band
                ++checked;
                SCOPED_TRACE("alpha " + std::to_string(alpha) + " length " + std::to_string(length));
                const StraightGeodesicResult r = trace_straight_geodesic(mesh, start, angle, length);
                expect_well_formed(mesh, start, angle, length, r);
                ASSERT_FALSE(r.stopped_at_vertex);
                EXPECT_LT((mesh.point(r.end) - cube_unrolled(x0, y0, alpha, length)).norm(), 1e-12);
                expect_retraces(mesh, start, r, 1e-12);
            }
        }
        EXPECT_GE(checked, 14);
    }
}

TEST(StraightGeodesic, from_a_cube_corner_of_cone_angle_three_halves_pi) {
    const Mesh mesh = test::cube(4).to_mesh();
    int corner = -1;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (mesh.position(v) == Eigen::Vector3d(0.0, 0.0, 1.0)) corner = v;
    ASSERT_GE(corner, 0);
    const SurfacePoint c = SurfacePoint::at_vertex(corner);
    ASSERT_NEAR(cone_angle(mesh, c), 1.5 * pi, 1e-12);
    // Towards (0.7, 0.3, 1) over the top, then down the face x = 1.
    const SurfacePoint q = locate(mesh, Eigen::Vector3d(0.7, 0.3, 1.0));
    // The polar angle of that direction, from the fan's polar angles and the 3D angle inside the top face's corner.
    const Eigen::Vector3d up(0.0, 0.0, 1.0);
    double angle = -1.0;
    for (int h : mesh.outgoing_halfedges(corner)) {
        const Eigen::Vector3d e1 = mesh.position(mesh.head(h)) - mesh.position(corner);
        const Eigen::Vector3d e2 = mesh.position(mesh.tail(Mesh::prev(h))) - mesh.position(corner);
        if (e1.z() != 0.0 || e2.z() != 0.0) continue;  // not a face of the top
        const Eigen::Vector3d w = mesh.point(q) - mesh.position(corner);
        const double in = ccw_about(up, e1, w);
        if (in <= ccw_about(up, e1, e2) + 1e-15) angle = mesh.polar_angle(h) + in;
    }
    ASSERT_GE(angle, 0.0);
    const Eigen::Vector2d dir = Eigen::Vector2d(0.7, 0.3).normalized();
    for (double length : {0.5, 1.5}) {
        const StraightGeodesicResult r = trace_straight_geodesic(mesh, c, angle, length);
        expect_well_formed(mesh, c, angle, length, r);
        ASSERT_FALSE(r.stopped_at_vertex);
        const double u = length * dir.x(), y = length * dir.y();
        const Eigen::Vector3d expected = u <= 1.0 ? Eigen::Vector3d(u, y, 1.0) : Eigen::Vector3d(1.0, y, 2.0 - u);
        EXPECT_LT((mesh.point(r.end) - expected).norm(), 1e-12);
        expect_retraces(mesh, c, r, 1e-12);
    }
}

/// A fan of six triangles around a vertex at the origin whose rim zigzags up and down: a saddle (cone angle > 2π)
/// with a boundary.
test::TriangleMesh saddle_fan() {
    test::TriangleMesh m;
    m.positions.emplace_back(0.0, 0.0, 0.0);
    for (int k = 0; k < 6; ++k)
        m.positions.emplace_back(std::cos(pi * k / 3), std::sin(pi * k / 3), k % 2 == 0 ? 0.6 : -0.6);
    for (int k = 0; k < 6; ++k) m.triangles.push_back({0, 1 + k, 1 + (k + 1) % 6});
    return m;
}

TEST(StraightGeodesic, saddle_vertex_direction_picks_the_face_by_polar_angle) {
    const Mesh mesh = saddle_fan().to_mesh();
    const SurfacePoint v = SurfacePoint::at_vertex(0);
    const double theta = cone_angle(mesh, v);
    ASSERT_GT(theta, 2.0 * pi + 0.5);
    for (int i = 0; i < 40; ++i) {
        const double angle = theta * (i + 0.5) / 40.0;
        // The face and the 3D direction, from the corner angles of the fan and the 3D edge vectors.
        int face_h = -1;
        for (int h : mesh.outgoing_halfedges(0))
            if (mesh.polar_angle(h) <= angle && angle < mesh.polar_angle(h) + mesh.corner_angle(h)) face_h = h;
        ASSERT_GE(face_h, 0);
        const Eigen::Vector3d e1 = mesh.position(mesh.head(face_h)).normalized();
        const Eigen::Vector3d e2 = mesh.position(mesh.tail(Mesh::prev(face_h))).normalized();
        const double corner = std::acos(e1.dot(e2)), phi = angle - mesh.polar_angle(face_h);
        const Eigen::Vector3d dir = (std::sin(corner - phi) * e1 + std::sin(phi) * e2) / std::sin(corner);
        SCOPED_TRACE("angle " + std::to_string(angle));
        const StraightGeodesicResult r = trace_straight_geodesic(mesh, v, angle, 0.3);
        expect_well_formed(mesh, v, angle, 0.3, r);
        EXPECT_LT((mesh.point(r.end) - 0.3 * dir).norm(), 1e-14);
        EXPECT_EQ(common_face(mesh, r.end, r.end), Mesh::face_of(face_h));
        expect_retraces(mesh, v, r, 1e-14);
        // Far enough, it leaves the fan through its rim.
        const StraightGeodesicResult out = trace_straight_geodesic(mesh, v, angle, 5.0);
        expect_well_formed(mesh, v, angle, 5.0, out);
        EXPECT_TRUE(out.stopped_at_boundary);
        EXPECT_EQ(out.path.size(), 2u);
    }
    // An edge point of the rim, pointing out of the mesh: stopped at once.
    const SurfacePoint rim = mesh.canonical(SurfacePoint::on_edge(1, 2, 0.5));
    const int inside = mesh.find_halfedge(1, 2) >= 0 ? 0 : 1;  // (0, π) lies in the face left of 1 -> 2
    const double outward = inside == 0 ? 1.5 * pi : 0.5 * pi;
    const StraightGeodesicResult none = trace_straight_geodesic(mesh, rim, outward, 1.0);
    EXPECT_TRUE(none.stopped_at_boundary);
    EXPECT_EQ(none.path.size(), 1u);
    EXPECT_EQ(none.length, 0.0);
    const StraightGeodesicResult in = trace_straight_geodesic(mesh, rim, outward + pi, 0.2);
    expect_well_formed(mesh, rim, outward + pi, 0.2, in);
    EXPECT_FALSE(in.stopped_at_boundary);
}

TEST(StraightGeodesic, closed_curved_meshes_retrace_and_keep_their_length) {
    const test::TriangleMesh meshes[] = {test::torus(2.0, 0.7, 36, 18), test::perturbed_sphere(6, 0.1, 4)};
    for (const test::TriangleMesh& tm : meshes) {
        const Mesh mesh = tm.to_mesh();
        int saddles = 0;
        for (int v = 0; v < mesh.num_vertices(); v += 7) {
            const SurfacePoint start = SurfacePoint::at_vertex(v);
            const double theta = cone_angle(mesh, start);
            saddles += theta > 2.0 * pi;
            for (int i = 0; i < 3; ++i) {
                const double angle = theta * (i + 0.123 * (v % 5) + 0.2) / 3.0;
                const double length = 0.05 + 0.4 * i;
                const StraightGeodesicResult r = trace_straight_geodesic(mesh, start, angle, length);
                expect_well_formed(mesh, start, angle, length, r);
                EXPECT_FALSE(r.stopped_at_boundary);
                if (!r.stopped_at_vertex) expect_retraces(mesh, start, r, 1e-10);
            }
        }
        if (&tm == &meshes[0]) {
            EXPECT_GT(saddles, 10) << "the torus's inner vertices are saddles";
        }
    }
}

TEST(StraightGeodesic, bad_input_throws) {
    const Mesh mesh = test::cube(2).to_mesh();
    const SurfacePoint v = SurfacePoint::at_vertex(0);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    EXPECT_THROW(trace_straight_geodesic(mesh, v, nan, 1.0), InvalidInput);
    EXPECT_THROW(trace_straight_geodesic(mesh, v, inf, 1.0), InvalidInput);
    EXPECT_THROW(trace_straight_geodesic(mesh, v, 0.1, -1.0), InvalidInput);
    EXPECT_THROW(trace_straight_geodesic(mesh, v, 0.1, nan), InvalidInput);
    EXPECT_THROW(trace_straight_geodesic(mesh, v, 0.1, inf), InvalidInput);
    EXPECT_THROW(trace_straight_geodesic(mesh, SurfacePoint::at_vertex(mesh.num_vertices()), 0.1, 1.0), InvalidInput);
    EXPECT_THROW(trace_straight_geodesic(mesh, SurfacePoint::at_vertex(-1), 0.1, 1.0), InvalidInput);
    EXPECT_THROW(trace_straight_geodesic(mesh, SurfacePoint::in_face(mesh.num_faces(), {0.2, 0.3, 0.5}), 0.1, 1.0),
                 InvalidInput);
    EXPECT_THROW(trace_straight_geodesic(mesh, SurfacePoint::in_face(0, {nan, 0.5, 0.5}), 0.1, 1.0), InvalidInput);
    int far = -1;  // a vertex not adjacent to vertex 0
    for (int w = 1; w < mesh.num_vertices() && far < 0; ++w)
        if (mesh.find_halfedge(0, w) < 0 && mesh.find_halfedge(w, 0) < 0) far = w;
    ASSERT_GE(far, 0);
    EXPECT_THROW(trace_straight_geodesic(mesh, SurfacePoint::on_edge(0, far, 0.5), 0.1, 1.0), InvalidInput);

    // Length 0: the path is the start.
    const SurfacePoint e = mesh.canonical(SurfacePoint::on_edge(mesh.tail(0), mesh.head(0), 0.25));
    const StraightGeodesicResult zero = trace_straight_geodesic(mesh, e, 1.0, 0.0);
    ASSERT_EQ(zero.path.size(), 1u);
    EXPECT_EQ(zero.end, e);
    EXPECT_EQ(zero.length, 0.0);
    EXPECT_FALSE(zero.stopped_at_vertex || zero.stopped_at_boundary);

    // A long walk round and round the cube meets the crossing cap.
    const SurfacePoint f = locate(mesh, Eigen::Vector3d(0.3, 0.4, 1.0));
    StraightGeodesicOptions options;
    options.max_crossings = 20;
    EXPECT_THROW(trace_straight_geodesic(mesh, f, 0.1, 1000.0, options), NumericalError);
}

/// Short straight geodesics from vertices are shortest paths: libgeodesic's exact distance equals their length.
TEST(StraightGeodesic, real_mesh_short_straight_geodesics_are_shortest) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "the shared real meshes are missing: GEOTRI_SHARED_DATA ('" << test::configured_shared_data_dir()
                     << "') is not a folder; configure with -DGEOTRI_SHARED_DATA=<folder> to run this test";
    for (const char* name : {"classic/bunny_closed_cgal.off", "anatomy/lumbar_vertebra_mean_2nd.ply"}) {
        SCOPED_TRACE(name);
        const FineMesh fine = load_fine_mesh(test::shared_mesh(name).path);
        const Mesh& mesh = fine.mesh;
        double mean_edge = 0.0;
        for (int h = 0; h < mesh.num_halfedges(); ++h) mean_edge += mesh.length(h);
        mean_edge /= mesh.num_halfedges();
        geodesic::ExactGeodesic exact(mesh);
        int checked = 0, shortest = 0;
        const int step = std::max(1, mesh.num_vertices() / 60);
        for (int v = 0; v < mesh.num_vertices(); v += step) {
            const SurfacePoint start = SurfacePoint::at_vertex(v);
            const double theta = cone_angle(mesh, start);
            for (int i = 0; i < 4; ++i) {
                const double angle = theta * (i + 0.37) / 4.0;
                const double length = mean_edge * (0.6 + 0.7 * i);
                const StraightGeodesicResult r = trace_straight_geodesic(mesh, start, angle, length);
                expect_well_formed(mesh, start, angle, length, r);
                if (r.stopped_at_vertex) continue;
                geodesic::PropagationOptions options;
                options.stop_points = {r.end};
                options.max_distance = 2.0 * length;
                exact.propagate({start}, options);
                const double d = exact.distance(r.end);
                ++checked;
                // Never shorter than the exact distance; equal to it unless a convex vertex offers a shortcut.
                EXPECT_LE(d, r.length * (1.0 + 1e-12));
                if (std::abs(d - r.length) <= 1e-10 * r.length) ++shortest;
                expect_retraces(mesh, start, r, 1e-9 * mesh.size());
            }
        }
        EXPECT_GE(checked, 150);
        EXPECT_GE(shortest, checked * 9 / 10) << shortest << " of " << checked << " are shortest";
        std::cerr << name << ": " << shortest << " of " << checked << " straight geodesics are shortest\n";
    }
}

}  // namespace
}  // namespace geotri

// Polar angles at surface points, checked against directions computed independently from the 3D geometry: the
// plane z = 0 for a flat grid, the three face planes at a cube corner, and face normals on a curved sphere.

#include <geodesic/errors.h>
#include <geodesic/mesh.h>
#include <geotri/tangent_angles.h>
#include <geotri_test/procedural_meshes.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace geotri {
namespace {

using geodesic::Mesh;
using geodesic::SurfacePoint;

constexpr double pi = 3.14159265358979323846;
constexpr double tolerance = 1e-12;

/// Counter-clockwise angle from u to w about the axis n, in [0, 2π).
double ccw_about(const Eigen::Vector3d& n, const Eigen::Vector3d& u, const Eigen::Vector3d& w) {
    double a = std::atan2(n.dot(u.cross(w)), u.dot(w));
    return a < 0.0 ? a + 2.0 * pi : a;
}

/// Difference of two angles on a circle of circumference theta, in (-theta/2, theta/2].
double circular_difference(double a, double b, double theta) {
    double d = std::fmod(a - b, theta);
    if (d > theta / 2) d -= theta;
    if (d <= -theta / 2) d += theta;
    return d;
}

/// Points of face f: its vertices, a point on each edge and one inside.
std::vector<SurfacePoint> points_of_face(const Mesh& mesh, int f) {
    const auto& t = mesh.triangle(f);
    std::vector<SurfacePoint> points;
    for (int i = 0; i < 3; ++i) {
        points.push_back(SurfacePoint::at_vertex(t[i]));
        points.push_back(SurfacePoint::on_edge(t[i], t[(i + 1) % 3], 0.3 + 0.1 * i));
    }
    points.push_back(SurfacePoint::in_face(f, {0.5, 0.2, 0.3}));
    return points;
}

bool lies_on(const Mesh& mesh, int f, const SurfacePoint& p) {
    const auto& t = mesh.triangle(f);
    auto has = [&](int v) { return t[0] == v || t[1] == v || t[2] == v; };
    switch (p.kind) {
        case geodesic::PointKind::vertex: return has(p.vertex);
        case geodesic::PointKind::edge: return has(p.edge_v0) && has(p.edge_v1);
        case geodesic::PointKind::face: return p.face == f;
    }
    return false;
}

/// Every point of the faces around p, except p itself.
std::vector<SurfacePoint> points_around(const Mesh& mesh, const SurfacePoint& p) {
    std::vector<int> faces;
    if (p.kind == geodesic::PointKind::vertex) {
        for (int h : mesh.outgoing_halfedges(p.vertex)) faces.push_back(Mesh::face_of(h));
    } else if (p.kind == geodesic::PointKind::edge) {
        faces.push_back(Mesh::face_of(mesh.find_halfedge(p.edge_v0, p.edge_v1)));
        faces.push_back(Mesh::face_of(mesh.find_halfedge(p.edge_v1, p.edge_v0)));
    } else {
        faces.push_back(p.face);
    }
    std::vector<SurfacePoint> points;
    for (int f : faces)
        for (const SurfacePoint& q : points_of_face(mesh, f))
            if (mesh.point(q) != mesh.point(p)) points.push_back(q);
    return points;
}

// The plane z = 0 seen from +z: every polar angle is the counter-clockwise angle from the reference direction.
void expect_flat_angles(const Mesh& mesh, const SurfacePoint& p, const Eigen::Vector3d& reference_target) {
    const Eigen::Vector3d x = mesh.point(p);
    const Eigen::Vector3d z(0, 0, 1);
    EXPECT_NEAR(cone_angle(mesh, p), 2.0 * pi, 1e-12);
    const std::vector<SurfacePoint> around = points_around(mesh, p);
    ASSERT_FALSE(around.empty());
    for (const SurfacePoint& q : around) {
        const double expected = ccw_about(z, reference_target - x, mesh.point(q) - x);
        const double angle = polar_angle(mesh, p, q);
        EXPECT_GE(angle, 0.0);
        EXPECT_LT(angle, cone_angle(mesh, p));
        EXPECT_NEAR(circular_difference(angle, expected, 2.0 * pi), 0.0, tolerance)
            << geodesic::to_spec(p) << " -> " << geodesic::to_spec(q);
    }
}

TEST(TangentAngles, flat_grid_matches_planar_directions_at_every_point_kind) {
    const Mesh mesh = test::flat_grid(6, 5, 3.0, 2.0, 0.2, 7).to_mesh();
    int checked = 0;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
        if (mesh.is_boundary_vertex(v)) continue;
        // Vertex: from the fine halfedge outgoing(v).
        expect_flat_angles(mesh, SurfacePoint::at_vertex(v), mesh.position(mesh.head(mesh.outgoing(v))));
        ++checked;
    }
    for (int h = 0; h < mesh.num_halfedges(); ++h) {
        if (mesh.twin(h) < 0 || mesh.tail(h) > mesh.head(h)) continue;
        // Edge point: towards the larger vertex index. Both spellings of the edge mean the same point.
        const int a = mesh.tail(h), b = mesh.head(h);
        expect_flat_angles(mesh, SurfacePoint::on_edge(a, b, 0.37), mesh.position(b));
        expect_flat_angles(mesh, SurfacePoint::on_edge(b, a, 0.5), mesh.position(b));
    }
    for (int f = 0; f < mesh.num_faces(); ++f)  // face point: towards triangle(f)[0]
        expect_flat_angles(mesh, SurfacePoint::in_face(f, {0.2, 0.3, 0.5}), mesh.position(mesh.triangle(f)[0]));
    EXPECT_GT(checked, 10);
}

TEST(TangentAngles, along_a_fine_edge_is_the_mesh_polar_angle_exactly) {
    const Mesh mesh = test::icosphere(2).to_mesh();
    for (int h = 0; h < mesh.num_halfedges(); ++h) {
        const SurfacePoint v = SurfacePoint::at_vertex(mesh.tail(h));
        EXPECT_EQ(polar_angle(mesh, v, SurfacePoint::at_vertex(mesh.head(h))), mesh.polar_angle(h));
        EXPECT_EQ(polar_angle(mesh, v, SurfacePoint::on_edge(mesh.tail(h), mesh.head(h), 0.25)), mesh.polar_angle(h));
        EXPECT_EQ(polar_angle(mesh, v, SurfacePoint::on_edge(mesh.head(h), mesh.tail(h), 0.25)), mesh.polar_angle(h));
    }
}

// On a cube corner three quarter planes meet (cone angle 3π/2). Seen from outside the corner at the origin, the
// directions turn counter-clockwise from +x through the face y = 0 to +z, through x = 0 to +y, and through z = 0
// back to +x, so a direction's angle from +x unfolds face by face.
double cube_corner_angle(const Eigen::Vector3d& d) {
    if (std::abs(d.y()) == 0.0 && d.x() >= 0.0 && d.z() >= 0.0) return std::atan2(d.z(), d.x());
    if (std::abs(d.x()) == 0.0 && d.y() >= 0.0 && d.z() >= 0.0) return pi / 2 + std::atan2(d.y(), d.z());
    return pi + std::atan2(d.x(), d.y());
}

TEST(TangentAngles, cube_corner_unfolds_three_quarter_planes) {
    for (bool irregular : {false, true}) {
        const Mesh mesh = test::cube(3, 1.0, irregular, 3).to_mesh();
        int corner = -1;
        for (int v = 0; v < mesh.num_vertices(); ++v)
            if (mesh.position(v).isZero()) corner = v;
        ASSERT_GE(corner, 0);
        const SurfacePoint p = SurfacePoint::at_vertex(corner);
        const double theta = cone_angle(mesh, p);
        EXPECT_NEAR(theta, 1.5 * pi, 1e-14);
        const std::vector<SurfacePoint> around = points_around(mesh, p);
        ASSERT_GT(around.size(), 9u);
        for (const SurfacePoint& q1 : around) {
            for (const SurfacePoint& q2 : around) {
                const double expected = ccw_angle(cube_corner_angle(mesh.point(q1)), cube_corner_angle(mesh.point(q2)), theta);
                const double got = ccw_angle(polar_angle(mesh, p, q1), polar_angle(mesh, p, q2), theta);
                EXPECT_NEAR(circular_difference(got, expected, theta), 0.0, tolerance)
                    << geodesic::to_spec(q1) << " to " << geodesic::to_spec(q2);
            }
        }
    }
}

// An edge point on a cube edge (the x axis, between the faces y = 0 and z = 0): seen from outside, +x turns
// counter-clockwise through y = 0 to -x, and on through z = 0 back to +x.
TEST(TangentAngles, cube_edge_point_unfolds_across_the_fold) {
    const Mesh mesh = test::cube(3).to_mesh();
    int a = -1, b = -1;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
        const Eigen::Vector3d& x = mesh.position(v);
        if (x.y() == 0.0 && x.z() == 0.0 && std::abs(x.x() - 1.0 / 3.0) < 1e-15) a = v;
        if (x.y() == 0.0 && x.z() == 0.0 && std::abs(x.x() - 2.0 / 3.0) < 1e-15) b = v;
    }
    ASSERT_GE(a, 0);
    ASSERT_GE(b, 0);
    const SurfacePoint p = SurfacePoint::on_edge(a, b, 0.5);
    const Eigen::Vector3d x = mesh.point(p);
    auto fold_angle = [&](const Eigen::Vector3d& d) {
        if (d.y() == 0.0 && d.z() >= 0.0) return std::atan2(d.z(), d.x());
        return pi + std::atan2(d.y(), -d.x());
    };
    const Eigen::Vector3d towards_larger = mesh.position(std::max(a, b)) - x;
    for (const SurfacePoint& q : points_around(mesh, p)) {
        const double expected = ccw_angle(fold_angle(towards_larger), fold_angle(mesh.point(q) - x), 2.0 * pi);
        EXPECT_NEAR(circular_difference(polar_angle(mesh, p, q), expected, 2.0 * pi), 0.0, tolerance)
            << geodesic::to_spec(q);
    }
}

// On a curved surface, two directions into the same face differ by their 3D angle, signed by the face's normal.
TEST(TangentAngles, angle_between_directions_in_one_face_is_the_3d_angle) {
    const Mesh mesh = test::perturbed_sphere(4, 0.1, 5).to_mesh();
    std::vector<SurfacePoint> points;
    for (int v = 0; v < mesh.num_vertices(); v += 7) points.push_back(SurfacePoint::at_vertex(v));
    for (int h = 0; h < mesh.num_halfedges(); h += 11) points.push_back(SurfacePoint::on_edge(mesh.tail(h), mesh.head(h), 0.6));
    for (int f = 0; f < mesh.num_faces(); f += 5) points.push_back(SurfacePoint::in_face(f, {0.1, 0.6, 0.3}));
    int pairs = 0;
    for (const SurfacePoint& p : points) {
        const double theta = cone_angle(mesh, p);
        const Eigen::Vector3d x = mesh.point(p);
        for (const SurfacePoint& q1 : points_around(mesh, p)) {
            for (const SurfacePoint& q2 : points_around(mesh, p)) {
                if (on_common_edge(mesh, p, q1) || on_common_edge(mesh, p, q2)) continue;
                const int f = common_face(mesh, q1, q2);
                if (f < 0 || !lies_on(mesh, f, p)) continue;  // the 3D angle is intrinsic only inside one face
                const auto& t = mesh.triangle(f);
                const Eigen::Vector3d n = (mesh.position(t[1]) - mesh.position(t[0]))
                                              .cross(mesh.position(t[2]) - mesh.position(t[0]))
                                              .normalized();
                const Eigen::Vector3d d1 = mesh.point(q1) - x, d2 = mesh.point(q2) - x;
                const double signed_3d = std::atan2(n.dot(d1.cross(d2)), d1.dot(d2));
                const double got = ccw_angle(polar_angle(mesh, p, q1), polar_angle(mesh, p, q2), theta);
                EXPECT_NEAR(circular_difference(got, signed_3d, theta), 0.0, 1e-11)
                    << geodesic::to_spec(p) << ": " << geodesic::to_spec(q1) << " to " << geodesic::to_spec(q2);
                ++pairs;
            }
        }
    }
    EXPECT_GT(pairs, 1000);
}

// Around a vertex, directions through the opposite edges sweep counter-clockwise once: strictly increasing polar
// angles whose steps add up to the cone angle.
TEST(TangentAngles, sweep_through_opposite_edges_winds_once) {
    const Mesh mesh = test::perturbed_sphere(3, 0.2, 11).to_mesh();
    for (int v = 0; v < mesh.num_vertices(); ++v) {
        const int first = mesh.outgoing(v);
        std::vector<double> angles;
        for (int h = first;;) {
            for (double t : {0.0, 0.2, 0.5, 0.8}) {
                const int opposite = Mesh::next(h);
                angles.push_back(t == 0.0 ? polar_angle(mesh, SurfacePoint::at_vertex(v), SurfacePoint::at_vertex(mesh.head(h)))
                                          : polar_angle(mesh, SurfacePoint::at_vertex(v),
                                                        SurfacePoint::on_edge(mesh.tail(opposite), mesh.head(opposite), t)));
            }
            h = mesh.twin(Mesh::prev(h));
            if (h == first) break;
        }
        const double theta = mesh.cone_angle(v);
        double sum = 0.0;
        for (std::size_t i = 0; i < angles.size(); ++i) {
            const double step = ccw_angle(angles[i], angles[(i + 1) % angles.size()], theta);
            EXPECT_GT(step, 1e-6);
            sum += step;
        }
        EXPECT_NEAR(sum, theta, 1e-12) << "vertex " << v;
    }
}

TEST(TangentAngles, cone_angles_of_each_point_kind) {
    const Mesh mesh = test::cube(2).to_mesh();
    for (int v = 0; v < mesh.num_vertices(); ++v)
        EXPECT_EQ(cone_angle(mesh, SurfacePoint::at_vertex(v)), mesh.cone_angle(v));
    EXPECT_EQ(cone_angle(mesh, SurfacePoint::on_edge(mesh.tail(0), mesh.head(0), 0.5)), 2.0 * pi);
    EXPECT_EQ(cone_angle(mesh, SurfacePoint::in_face(3, {0.2, 0.3, 0.5})), 2.0 * pi);
    EXPECT_THROW(cone_angle(mesh, SurfacePoint::at_vertex(mesh.num_vertices())), InvalidInput);
}

TEST(TangentAngles, points_without_a_common_face_are_refused) {
    const Mesh mesh = test::icosphere(1).to_mesh();
    const SurfacePoint v = SurfacePoint::at_vertex(0);
    int far = -1;
    for (int w = 0; w < mesh.num_vertices() && far < 0; ++w)
        if (common_face(mesh, v, SurfacePoint::at_vertex(w)) < 0) far = w;
    ASSERT_GE(far, 0);
    EXPECT_THROW(polar_angle(mesh, v, SurfacePoint::at_vertex(far)), InvalidInput);
    EXPECT_THROW(polar_angle(mesh, v, v), InvalidInput);
    EXPECT_THROW(initial_polar_angle(mesh, {v}), InvalidInput);
    const int h = mesh.outgoing(0);
    EXPECT_THROW(polar_angle(mesh, SurfacePoint::on_edge(mesh.tail(h), mesh.head(h), 0.5),
                             SurfacePoint::on_edge(mesh.head(h), mesh.tail(h), 0.5)),
                 InvalidInput);
}

}  // namespace
}  // namespace geotri

// Curved elements: the Bernstein arithmetic against closed forms, flat patches against their straight triangles,
// and the certificates of curved elements against dense sampling with a Lagrange evaluator of the test's own.

#include <geodesic/errors.h>
#include <geotri/curved_elements.h>
#include <geotri/untangle_and_flip.h>
#include <geotri/validate.h>
#include <geotri_test/g_checks.h>

#include "curved/bernstein_triangle.h"
#include "curved/sign_bounds.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace geotri {
namespace {

using Point2 = Eigen::Vector2d;
using Point3 = Eigen::Vector3d;

// ---- The test's own Lagrange triangle --------------------------------------------------------------------------

/// The equispaced Lagrange basis function of node (i, j, k) of order p at barycentric l:
/// prod_{a<i} (p l0 - a)/(a + 1) prod_{b<j} (p l1 - b)/(b + 1) prod_{c<k} (p l2 - c)/(c + 1).
double lagrange_basis(const std::array<int, 3>& node, int p, const std::array<double, 3>& l) {
    double value = 1.0;
    for (std::size_t corner = 0; corner < 3; ++corner)
        for (int a = 0; a < node[corner]; ++a) value *= (p * l[corner] - a) / (a + 1);
    return value;
}

/// The element's point at (u, v), from its gmsh-ordered node positions.
Point3 lagrange_point(const std::vector<Point3>& positions, int p, const Point2& uv) {
    const std::array<double, 3> l{1.0 - uv.x() - uv.y(), uv.x(), uv.y()};
    const std::vector<std::array<int, 3>> order = gmsh_node_order(p);
    Point3 x = Point3::Zero();
    for (std::size_t n = 0; n < order.size(); ++n) x += lagrange_basis(order[n], p, l) * positions[n];
    return x;
}

/// (x_u × x_v) · normal at (u, v), by central differences of lagrange_point().
double sampled_jacobian(const std::vector<Point3>& positions, int p, const Point2& uv, const Point3& normal) {
    const double h = 1e-6;
    const Point3 xu =
        (lagrange_point(positions, p, uv + Point2(h, 0)) - lagrange_point(positions, p, uv - Point2(h, 0))) / (2 * h);
    const Point3 xv =
        (lagrange_point(positions, p, uv + Point2(0, h)) - lagrange_point(positions, p, uv - Point2(0, h))) / (2 * h);
    return xu.cross(xv).dot(normal);
}

/// Points of the reference triangle on a grid of `n` steps per side, kept `margin` inside it.
std::vector<Point2> grid(int n, double margin) {
    std::vector<Point2> points;
    for (int a = 0; a <= n; ++a)
        for (int b = 0; a + b <= n; ++b) {
            const double u = static_cast<double>(a) / n, v = static_cast<double>(b) / n;
            points.emplace_back(margin + (1 - 3 * margin) * u, margin + (1 - 3 * margin) * v);
        }
    return points;
}

/// The distance from x to the closest point of T's faces, by brute force.
double distance_to_surface(const geodesic::Mesh& mesh, const Point3& x) {
    double best = std::numeric_limits<double>::infinity();
    for (int f = 0; f < mesh.num_faces(); ++f) {
        const auto& t = mesh.triangle(f);
        const Point3 a = mesh.position(t[0]), b = mesh.position(t[1]), c = mesh.position(t[2]);
        // Ericson, Real-Time Collision Detection, 5.1.5.
        const Point3 ab = b - a, ac = c - a, ap = x - a;
        const double d1 = ab.dot(ap), d2 = ac.dot(ap);
        Point3 closest;
        if (d1 <= 0 && d2 <= 0) {
            closest = a;
        } else {
            const Point3 bp = x - b;
            const double d3 = ab.dot(bp), d4 = ac.dot(bp);
            const Point3 cp = x - c;
            const double d5 = ab.dot(cp), d6 = ac.dot(cp);
            const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
            if (d3 >= 0 && d4 <= d3) closest = b;
            else if (vc <= 0 && d1 >= 0 && d3 <= 0) closest = a + d1 / (d1 - d3) * ab;
            else if (d6 >= 0 && d5 <= d6) closest = c;
            else if (vb <= 0 && d2 >= 0 && d6 <= 0) closest = a + d2 / (d2 - d6) * ac;
            else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
                closest = b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
            else {
                const double denominator = 1.0 / (va + vb + vc);
                closest = a + ab * vb * denominator + ac * vc * denominator;
            }
        }
        best = std::min(best, (x - closest).norm());
    }
    return best;
}

/// The positions of an element's nodes, in its (gmsh's) order.
std::vector<Point3> positions_of(const CurvedMesh& curved, const CurvedElement& element) {
    std::vector<Point3> positions;
    for (int node : element.nodes) positions.push_back(curved.positions[static_cast<std::size_t>(node)]);
    return positions;
}

// ---- Bernstein arithmetic against closed forms -----------------------------------------------------------------

/// A cubic polynomial in (u, v), and its values at the equispaced nodes of degree 3.
double cubic(const Point2& q) {
    const double u = q.x(), v = q.y();
    return 0.3 - 1.2 * u + 2.0 * v + 0.7 * u * u - 1.1 * u * v + 0.4 * v * v + 1.3 * u * u * v - 0.9 * v * v * v +
           0.2 * u * u * u;
}

TEST(BernsteinTriangle, lagrange_values_give_coefficients_that_evaluate_to_the_polynomial) {
    for (int n : {3, 4, 6}) {
        std::vector<double> values;
        for (const auto& index : detail::multi_indices(n)) values.push_back(cubic(detail::node_of(index, n)));
        const std::vector<double> coefficients = detail::bernstein_from_lagrange(values, n);
        for (const Point2& q : grid(7, 0.0))
            EXPECT_NEAR(detail::evaluate(coefficients, n, q), cubic(q), 1e-12) << "degree " << n;
    }
}

TEST(BernsteinTriangle, restriction_to_a_triangle_is_the_polynomial_there) {
    const int n = 3;
    std::vector<double> values;
    for (const auto& index : detail::multi_indices(n)) values.push_back(cubic(detail::node_of(index, n)));
    const std::vector<double> coefficients = detail::bernstein_from_lagrange(values, n);
    // Any triangle of the plane, inside the reference triangle or not, clockwise or not.
    const Point2 a(0.1, 0.2), b(1.3, -0.4), c(-0.2, 0.9);
    const std::vector<double> restricted = detail::restrict_to_triangle(coefficients, n, a, b, c);
    for (const Point2& q : grid(6, 0.0)) {
        const Point2 mapped = (1 - q.x() - q.y()) * a + q.x() * b + q.y() * c;
        EXPECT_NEAR(detail::evaluate(restricted, n, q), cubic(mapped), 1e-12);
    }
}

TEST(BernsteinTriangle, jacobian_coefficients_evaluate_to_the_cross_product_of_the_derivatives) {
    // x(u, v) = (u + 0.3 v^2, v - 0.2 u v, 0.5 u^2 + v^2 u): x_u = (1, -0.2 v, u + v^2), x_v = (0.6 v, 1 - 0.2 u, 2uv).
    auto x = [](const Point2& q) {
        const double u = q.x(), v = q.y();
        return Point3(u + 0.3 * v * v, v - 0.2 * u * v, 0.5 * u * u + v * v * u);
    };
    auto jacobian = [](const Point2& q, const Point3& normal) {
        const double u = q.x(), v = q.y();
        return Point3(1, -0.2 * v, u + v * v).cross(Point3(0.6 * v, 1 - 0.2 * u, 2 * u * v)).dot(normal);
    };
    const int n = 3;
    std::vector<Point3> values;
    for (const auto& index : detail::multi_indices(n)) values.push_back(x(detail::node_of(index, n)));
    const std::vector<Point3> coefficients = detail::bernstein_from_lagrange(values, n);
    const Point3 normal(0.2, -0.1, 1.0);
    const std::vector<double> j = detail::jacobian_coefficients(coefficients, n, normal);
    ASSERT_EQ(j.size(), detail::coefficient_count(2 * (n - 1)));
    for (const Point2& q : grid(6, 0.0)) EXPECT_NEAR(detail::evaluate(j, 2 * (n - 1), q), jacobian(q, normal), 1e-12);
}

TEST(BernsteinTriangle, sign_bounds_prove_positive_invalid_and_bound_the_range) {
    // At least 0.25 - v^2/4 + 0.1 v >= 0.1 on the reference triangle (u^2 - uv >= -v^2/4).
    auto f = [](const Point2& q) { return 0.25 + q.x() * q.x() - q.x() * q.y() + 0.1 * q.y(); };
    const int n = 2;
    std::vector<double> values;
    for (const auto& index : detail::multi_indices(n)) values.push_back(f(detail::node_of(index, n)));
    const detail::SignBounds bounds = detail::bound_sign(detail::bernstein_from_lagrange(values, n), n, 6);
    EXPECT_EQ(bounds.verdict, Certification::valid);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Point2& q : grid(40, 0.0)) {
        lo = std::min(lo, f(q));
        hi = std::max(hi, f(q));
    }
    EXPECT_LE(bounds.min_lower, lo + 1e-15);
    EXPECT_GE(bounds.max_upper, hi - 1e-15);
    EXPECT_GE(bounds.min_value, lo - 1e-15);
    EXPECT_LE(bounds.max_value, hi + 1e-15);
    EXPECT_GT(bounds.min_lower, 0.0);

    // Negative only around the centroid, where u v (1 - u - v) reaches 1/27 > 0.03; positive at every node.
    auto g = [](const Point2& q) { return 0.03 - q.x() * q.y() * (1 - q.x() - q.y()); };
    std::vector<double> g_values;
    for (const auto& index : detail::multi_indices(3)) g_values.push_back(g(detail::node_of(index, 3)));
    EXPECT_EQ(detail::bound_sign(detail::bernstein_from_lagrange(g_values, 3), 3, 8).verdict,
              Certification::invalid);
}

TEST(BernsteinTriangle, a_p3_element_with_an_edge_node_pushed_across_the_opposite_side_is_certified_invalid) {
    // The straight P3 triangle (0,0), (1,0), (0,1) in the plane z = 0, its nodes where they belong; then the first
    // inner node of edge 0→1 pushed across edge 1→2, beyond the opposite side.
    const int p = 3;
    std::vector<Point3> nodes;
    for (const auto& index : detail::multi_indices(p)) {
        const Point2 uv = detail::node_of(index, p);
        nodes.emplace_back(uv.x(), uv.y(), 0.0);
    }
    const Point3 normal(0, 0, 1);
    const detail::SignBounds straight =
        detail::bound_sign(detail::jacobian_coefficients(detail::bernstein_from_lagrange(nodes, p), p, normal),
                           2 * (p - 1), 6);
    EXPECT_EQ(straight.verdict, Certification::valid);
    EXPECT_NEAR(straight.min_lower / straight.max_upper, 1.0, 1e-12);

    nodes[detail::multi_index_position(1, 0)] = Point3(0.6, 0.7, 0.0);  // (i, j, k) = (2, 1, 0): from (1/3, 0)
    const detail::SignBounds broken =
        detail::bound_sign(detail::jacobian_coefficients(detail::bernstein_from_lagrange(nodes, p), p, normal),
                           2 * (p - 1), 6);
    EXPECT_EQ(broken.verdict, Certification::invalid);
}

// ---- Elements on G ---------------------------------------------------------------------------------------------

TEST(GmshNodeOrder, corners_then_edges_then_the_interior_recursively) {
    using Index = std::array<int, 3>;
    EXPECT_EQ(gmsh_node_order(2),
              (std::vector<Index>{{2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}}));
    const std::vector<Index> p4 = gmsh_node_order(4);
    ASSERT_EQ(p4.size(), 15u);
    // gmsh's triangle of order 4: the three interior nodes are a P1 triangle in the order of the corners.
    EXPECT_EQ(p4[12], (Index{2, 1, 1}));
    EXPECT_EQ(p4[13], (Index{1, 2, 1}));
    EXPECT_EQ(p4[14], (Index{1, 1, 2}));
    EXPECT_EQ(p4[3], (Index{3, 1, 0}));
    EXPECT_EQ(p4[6], (Index{0, 3, 1}));
    EXPECT_EQ(p4[9], (Index{1, 0, 3}));
}

TEST(CurvedElements, flat_patches_give_their_straight_triangles) {
    const GeodesicTriangulation g = test::unit_cube_g();  // every patch is half of a flat side
    for (int p : {1, 2, 3, 4}) {
        CurveOptions options;
        options.order = p;
        const CurvedMesh curved = curve_elements(g, options);
        ASSERT_EQ(curved.elements.size(), g.coarse().n_faces());
        EXPECT_NEAR(curved.diagonal, std::sqrt(3.0), 1e-15);
        const std::vector<std::array<int, 3>> order = gmsh_node_order(p);
        for (const CurvedElement& element : curved.elements) {
            const std::string where = "order " + std::to_string(p) + ", face " + std::to_string(element.face.idx());
            ASSERT_EQ(element.nodes.size(), order.size()) << where;
            const std::vector<Point3> x = positions_of(curved, element);
            for (std::size_t n = 0; n < order.size(); ++n) {
                const Point3 straight = (order[n][0] * x[0] + order[n][1] * x[1] + order[n][2] * x[2]) / p;
                EXPECT_LT((x[n] - straight).norm(), 1e-12) << where << ", node " << n;
                const SurfacePoint& node = curved.nodes[static_cast<std::size_t>(element.nodes[n])];
                EXPECT_LT((g.fine().mesh.point(node) - x[n]).norm(), 1e-15) << where;
            }
            const ElementCertificate& c = element.certificate;
            EXPECT_EQ(c.plane, Certification::valid) << where;
            EXPECT_EQ(c.surface, Certification::valid) << where;
            EXPECT_NEAR(c.quality_lower, 1.0, 1e-12) << where;
            EXPECT_NEAR(c.quality_upper, 1.0, 1e-12) << where;
            EXPECT_LT(c.distance, 1e-12) << where;
        }
    }
}

/// The bundled bob (genus 1, 500 faces) at 320 coarse faces, untangled and flipped: curved patches.
GeodesicTriangulation flipped_bob() {
    GeodesicTriangulation g =
        test::traced_in_classes(std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply", "bob", false);
    untangle_and_flip(g);
    return g;
}

TEST(CurvedElements, elements_share_their_edge_nodes_which_lie_on_the_polylines_at_even_arc_lengths) {
    const GeodesicTriangulation g = flipped_bob();
    ASSERT_TRUE(validate(g).valid);
    const geodesic::Mesh& mesh = g.fine().mesh;
    const int p = 4;
    CurveOptions options;
    options.order = p;
    const CurvedMesh curved = curve_elements(g, options);
    // Each edge's inner nodes, as each of its two faces has them, from the edge's first halfedge's from-vertex.
    std::map<int, std::vector<std::vector<int>>> seen;
    for (const CurvedElement& element : curved.elements) {
        int side = 0;
        for (OpenMesh::HalfedgeHandle h : g.coarse().fh_range(element.face)) {
            const OpenMesh::EdgeHandle e = g.coarse().edge_handle(h);
            std::vector<int> inner(element.nodes.begin() + 3 + side * (p - 1),
                                   element.nodes.begin() + 3 + (side + 1) * (p - 1));
            if (g.coarse().halfedge_handle(e, 0) != h) std::reverse(inner.begin(), inner.end());
            seen[e.idx()].push_back(inner);
            ++side;
        }
    }
    ASSERT_EQ(seen.size(), g.coarse().n_edges());
    for (const auto& [edge, both] : seen) {
        ASSERT_EQ(both.size(), 2u) << "edge " << edge;
        EXPECT_EQ(both[0], both[1]) << "edge " << edge;
        // Node k lies at arc length k/p of the polyline: summed along the polyline's own segments.
        const Polyline& line = g.polyline(OpenMesh::EdgeHandle(edge));
        double total = 0.0;
        for (std::size_t i = 1; i < line.size(); ++i) total += (mesh.point(line[i]) - mesh.point(line[i - 1])).norm();
        for (int k = 1; k < p; ++k) {
            const Point3 node = curved.positions[static_cast<std::size_t>(both[0][static_cast<std::size_t>(k - 1)])];
            double walked = 0.0, nearest = std::numeric_limits<double>::infinity(), at = 0.0;
            for (std::size_t i = 1; i < line.size(); ++i) {
                const Point3 a = mesh.point(line[i - 1]), b = mesh.point(line[i]);
                const double t = std::clamp((node - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
                const double d = (a + t * (b - a) - node).norm();
                if (d < nearest) {
                    nearest = d;
                    at = walked + t * (b - a).norm();
                }
                walked += (b - a).norm();
            }
            EXPECT_LT(nearest, 1e-12 * total) << "edge " << edge << ", node " << k;
            EXPECT_NEAR(at / total, static_cast<double>(k) / p, 1e-9) << "edge " << edge << ", node " << k;
        }
    }
    // Every node once: corners, p - 1 per edge, (p - 1)(p - 2)/2 per face.
    EXPECT_EQ(curved.nodes.size(), g.coarse().n_vertices() + (p - 1) * g.coarse().n_edges() +
                                       (p - 1) * (p - 2) / 2 * g.coarse().n_faces());
}

TEST(CurvedElements, certificates_hold_against_dense_sampling) {
    const GeodesicTriangulation g = flipped_bob();
    const geodesic::Mesh& mesh = g.fine().mesh;
    for (int p : {2, 3}) {
        CurveOptions options;
        options.order = p;
        const CurvedMesh curved = curve_elements(g, options);
        int plane_valid = 0, surface_valid = 0;
        double worst_quality = 1.0, largest_distance = 0.0;
        for (const CurvedElement& element : curved.elements) {
            const ElementCertificate& c = element.certificate;
            surface_valid += c.surface == Certification::valid;
            worst_quality = std::min(worst_quality, c.quality_lower);
            largest_distance = std::max(largest_distance, c.distance / curved.diagonal);
            const std::string where = "order " + std::to_string(p) + ", face " + std::to_string(element.face.idx());
            const std::vector<Point3> x = positions_of(curved, element);
            const Point3 normal = (x[1] - x[0]).cross(x[2] - x[0]);
            double lo = std::numeric_limits<double>::infinity(), hi = -lo, farthest = 0.0;
            for (const Point2& q : grid(12, 1e-4)) {
                const double j = sampled_jacobian(x, p, q, normal);
                lo = std::min(lo, j);
                hi = std::max(hi, j);
                farthest = std::max(farthest, distance_to_surface(mesh, lagrange_point(x, p, q)));
            }
            // The bound of the distance to the patch bounds the distance to T.
            EXPECT_LE(farthest, c.distance * (1 + 1e-9) + 1e-15) << where;
            if (c.plane == Certification::valid) {
                ++plane_valid;
                EXPECT_GT(lo, 0.0) << where;
                EXPECT_LE(c.quality_lower, lo / hi * (1 + 1e-6)) << where;
            }
            if (c.plane == Certification::invalid) {
                EXPECT_LE(lo, 1e-9 * std::abs(hi)) << where;
            }
            EXPECT_LE(c.quality_lower, c.quality_upper) << where;
        }
        EXPECT_GT(plane_valid, 0) << "order " << p;
        std::cout << "[ curved   ] bob at " << curved.elements.size() << " faces, order " << p << ": " << plane_valid
                  << " certified valid against the corners' plane, " << surface_valid
                  << " against T's faces; smallest certified minJ/maxJ " << worst_quality
                  << ", largest distance bound " << largest_distance << " of the diagonal\n";
    }
}

TEST(CurvedElements, the_same_for_any_thread_count) {
    const GeodesicTriangulation g = flipped_bob();
    CurveOptions one;
    one.threads = 1;
    const CurvedMesh a = curve_elements(g, one);
    CurveOptions three;
    three.threads = 3;
    const CurvedMesh b = curve_elements(g, three);
    ASSERT_EQ(a.elements.size(), b.elements.size());
    EXPECT_EQ(a.nodes, b.nodes);
    EXPECT_EQ(a.positions, b.positions);
    for (std::size_t e = 0; e < a.elements.size(); ++e) {
        EXPECT_EQ(a.elements[e].nodes, b.elements[e].nodes);
        EXPECT_EQ(a.elements[e].certificate.distance, b.elements[e].certificate.distance);
        EXPECT_EQ(a.elements[e].certificate.quality_lower, b.elements[e].certificate.quality_lower);
    }
}

TEST(CurveAdaptively, refines_g_until_every_element_is_certified_and_keeps_g_valid) {
    GeodesicTriangulation g = flipped_bob();
    const std::size_t faces_before = g.coarse().n_faces();
    CurveAdaptOptions options;
    options.curve.order = 3;
    const CurveAdaptResult r = curve_adaptively(g, options);
    EXPECT_EQ(r.failing, 0);
    EXPECT_FALSE(r.round_cap_reached);
    EXPECT_GT(r.splits, 0);
    EXPECT_EQ(g.coarse().n_faces(), faces_before + 2 * static_cast<std::size_t>(r.splits));
    ASSERT_EQ(r.curved.elements.size(), g.coarse().n_faces());
    test::expect_valid_with_area(g);
    for (const CurvedElement& element : r.curved.elements)
        EXPECT_TRUE(element.passes(options.min_quality, options.tolerance * r.curved.diagonal))
            << "face " << element.face.idx();
    // Without rounds, the elements of G as it is, some of them failing.
    GeodesicTriangulation given = flipped_bob();
    options.max_rounds = 0;
    const CurveAdaptResult none = curve_adaptively(given, options);
    EXPECT_EQ(none.splits, 0);
    EXPECT_GT(none.failing, 0);
    EXPECT_TRUE(none.round_cap_reached);
    EXPECT_EQ(given.coarse().n_faces(), faces_before);
}

// A CAD part of flat sides meeting at sharp creases: an element across a crease keeps the crease's angle at every
// size, so bisection alone never certifies it (on this part it had 71 elements failing of 8094 after 40 rounds);
// splitting the edges where they cross a crease puts G's edges along the creases.
TEST(CurveAdaptively, elements_across_the_creases_of_a_cad_part_are_mended) {
    GeodesicTriangulation g =
        test::traced_in_classes(std::string(GEOTRI_TEST_DATA) + "/cad/joint.off", "joint", false);
    untangle_and_flip(g);
    ASSERT_TRUE(validate(g).valid);
    CurveAdaptOptions options;
    options.max_rounds = 40;
    const CurveAdaptResult r = curve_adaptively(g, options);
    EXPECT_EQ(r.failing, 0);
    EXPECT_FALSE(r.round_cap_reached);
    EXPECT_LT(r.curved.elements.size(), 2000u);
    test::expect_valid_with_area(g);
    for (const CurvedElement& element : r.curved.elements)
        EXPECT_TRUE(element.passes(options.min_quality, options.tolerance * r.curved.diagonal))
            << "face " << element.face.idx();
}

/// curve_adaptively() on the flipped G of bundled mesh `relative`, checking on the way that G is valid before, and
/// after with T's area, and that only splits add faces (two each).
CurveAdaptResult curve_bundled_mesh(const std::string& relative, const std::string& name) {
    GeodesicTriangulation g = test::traced_in_classes(std::string(GEOTRI_TEST_DATA) + "/" + relative, name, false);
    untangle_and_flip(g);
    EXPECT_TRUE(validate(g).valid) << name;
    const std::size_t faces_before = g.coarse().n_faces();
    CurveAdaptResult r = curve_adaptively(g);
    EXPECT_EQ(g.coarse().n_faces(), faces_before + 2 * static_cast<std::size_t>(r.splits)) << name;
    test::expect_valid_with_area(g);
    return r;
}

// A gear of flat faces meeting at right angles: an element whose patch reaches over a crease or past a corner, if
// only by a sliver that a geodesic passing the corner leaves, is flat on one side and meets the other side's faces
// edge-on, at every size; bisection never took those out (17 elements failing of 4760 after 20 rounds). Vertices
// of G on T's vertices there do, and leave G valid.
TEST(CurveAdaptively, elements_that_fold_over_the_corners_of_a_gear_are_mended_by_vertices_on_them) {
    const CurveAdaptResult r = curve_bundled_mesh("cad/pinion.off", "pinion");
    EXPECT_EQ(r.failing, 0);
    EXPECT_FALSE(r.round_cap_reached);
    const CurveAdaptOptions defaults;
    for (const CurvedElement& element : r.curved.elements)
        EXPECT_TRUE(element.passes(defaults.min_quality, defaults.tolerance * r.curved.diagonal))
            << "face " << element.face.idx();
}

// On joint, an element folds where a vertex of G stands on T's vertex already: an edge of G is flipped to join it to
// the next fold vertex along an edge of T. Flips keep the face count, and G stays valid.
TEST(CurveAdaptively, flips_that_join_vertices_of_g_along_edges_of_t_keep_g_valid) {
    const CurveAdaptResult r = curve_bundled_mesh("cad/joint.off", "joint");
    EXPECT_GT(r.flips, 0);
    const CurveAdaptOptions defaults;
    int failing = 0;
    for (const CurvedElement& element : r.curved.elements)
        failing += !element.passes(defaults.min_quality, defaults.tolerance * r.curved.diagonal);
    EXPECT_EQ(failing, r.failing);
}

TEST(CurvedElements, refuses_an_order_out_of_range) {
    const GeodesicTriangulation g = test::unit_cube_g();
    CurveOptions options;
    options.order = 0;
    EXPECT_THROW(curve_elements(g, options), InvalidInput);
    options.order = 9;
    EXPECT_THROW(curve_elements(g, options), InvalidInput);
}

}  // namespace
}  // namespace geotri

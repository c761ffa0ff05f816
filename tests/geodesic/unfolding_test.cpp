// Closed surfaces whose distances follow from unfolding: boxes (every face sequence unfolded, oracles.cpp) and the
// mantle of a capped prism (unrolled into a strip, where the straight path is obviously shorter than any path that
// touches a cap).

#include "check_helpers.h"

#include <geotri_test/procedural_meshes.h>

#include <gtest/gtest.h>

namespace geotri::test {
namespace {

using geodesic::ExactGeodesic;
using geodesic::SurfacePoint;

int vertex_at(const TriangleMesh& mesh, const Eigen::Vector3d& x) {
    for (int v = 0; v < static_cast<int>(mesh.positions.size()); ++v)
        if (mesh.positions[v] == x) return v;
    throw std::logic_error("no vertex there");
}

struct BoxCase {
    std::string name;
    Eigen::Vector3d size;
    std::array<int, 3> divisions;
    bool irregular;
    // Builds the source on the generated mesh.
    std::function<SurfacePoint(const TriangleMesh&)> source;
};

void PrintTo(const BoxCase& c, std::ostream* out) { *out << c.name; }

class BoxUnfolding : public testing::TestWithParam<BoxCase> {};

TEST_P(BoxUnfolding, distances_and_paths_match_the_shortest_unfolding) {
    const BoxCase& c = GetParam();
    const TriangleMesh arrays =
        box(c.size.x(), c.size.y(), c.size.z(), c.divisions[0], c.divisions[1], c.divisions[2], c.irregular, 3);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const SurfacePoint source = c.source(arrays);
    ExactGeodesic propagation(mesh);
    propagation.propagate({source});
    const Eigen::Vector3d s = point_position(arrays, source);
    OracleSweep options;
    options.floor = 1e-2 * c.size.norm();
    options.path_stride = 4;
    sweep_against_oracle(arrays, mesh, propagation, {source},
                         [&](const Eigen::Vector3d& x) { return box_surface_distance(c.size, s, x); }, options,
                         c.name + ", source " + spec(source));
}

// Sources on the top face (z = c): at an interior vertex, on a cube edge, at a corner, inside a face, on an edge of
// the mesh. Targets: every vertex (so every adjacent face and the opposite face) and sampled points.
const Eigen::Vector3d unit(1.0, 1.0, 1.0);
const Eigen::Vector3d slab(1.3, 2.1, 0.7);

SurfacePoint top_vertex(const TriangleMesh& m, const Eigen::Vector3d& size, double fx, double fy) {
    // The vertex of the top face nearest to (fx·a, fy·b, c).
    int best = -1;
    double best_distance = 1e300;
    for (int v = 0; v < static_cast<int>(m.positions.size()); ++v) {
        const auto& p = m.positions[v];
        if (p.z() != size.z()) continue;
        const double d = std::hypot(p.x() - fx * size.x(), p.y() - fy * size.y());
        if (d < best_distance) {
            best_distance = d;
            best = v;
        }
    }
    return SurfacePoint::at_vertex(best);
}

SurfacePoint top_face_point(const TriangleMesh& m, const Eigen::Vector3d& size, double fx, double fy) {
    const int v = top_vertex(m, size, fx, fy).vertex;
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
        const auto& t = m.triangles[f];
        if ((t[0] == v || t[1] == v || t[2] == v) && m.positions[t[0]].z() == size.z() &&
            m.positions[t[1]].z() == size.z() && m.positions[t[2]].z() == size.z())
            return SurfacePoint::in_face(f, {0.21, 0.33, 0.46});
    }
    throw std::logic_error("no top face");
}

SurfacePoint top_edge_point(const TriangleMesh& m, const Eigen::Vector3d& size, double fx, double fy) {
    const SurfacePoint f = top_face_point(m, size, fx, fy);
    const auto& t = m.triangles[f.face];
    return t[1] < t[2] ? SurfacePoint::on_edge(t[1], t[2], 0.41) : SurfacePoint::on_edge(t[2], t[1], 0.59);
}

std::string box_case_name(const testing::TestParamInfo<BoxCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(
    ExactGeodesicBox, BoxUnfolding,
    testing::Values(
        BoxCase{"cube_interior_vertex", unit, {6, 6, 6}, false,
                [](const TriangleMesh& m) { return top_vertex(m, unit, 0.34, 0.5); }},
        BoxCase{"cube_irregular_interior_vertex", unit, {6, 6, 6}, true,
                [](const TriangleMesh& m) { return top_vertex(m, unit, 0.17, 0.84); }},
        BoxCase{"cube_vertex_on_cube_edge", unit, {6, 6, 6}, true,
                [](const TriangleMesh& m) { return top_vertex(m, unit, 0.5, 0.0); }},
        BoxCase{"cube_corner", unit, {5, 5, 5}, true,
                [](const TriangleMesh& m) { return SurfacePoint::at_vertex(vertex_at(m, {1.0, 1.0, 1.0})); }},
        BoxCase{"cube_face_point", unit, {6, 6, 6}, true,
                [](const TriangleMesh& m) { return top_face_point(m, unit, 0.3, 0.6); }},
        BoxCase{"cube_edge_point", unit, {6, 6, 6}, true,
                [](const TriangleMesh& m) { return top_edge_point(m, unit, 0.8, 0.2); }},
        BoxCase{"box_interior_vertex", slab, {5, 7, 3}, true,
                [](const TriangleMesh& m) { return top_vertex(m, slab, 0.2, 0.43); }},
        BoxCase{"box_vertex_near_a_corner", slab, {5, 7, 3}, true,
                [](const TriangleMesh& m) { return top_vertex(m, slab, 0.8, 0.86); }},
        BoxCase{"box_face_point", slab, {5, 7, 3}, true,
                [](const TriangleMesh& m) { return top_face_point(m, slab, 0.6, 0.3); }},
        BoxCase{"box_edge_point", slab, {5, 7, 3}, false,
                [](const TriangleMesh& m) { return top_edge_point(m, slab, 0.4, 0.7); }}),
    box_case_name);

// The box oracle on cases worked out by hand.
TEST(BoxOracle, distances_of_hand_worked_cases) {
    // Opposite corners of the unit cube: √5 (two faces unfolded into a 1 x 2 rectangle).
    EXPECT_DOUBLE_EQ(box_surface_distance(unit, {0, 0, 0}, {1, 1, 1}), std::sqrt(5.0));
    // Centres of opposite faces: 2 (half a face, a whole side face, half a face).
    EXPECT_DOUBLE_EQ(box_surface_distance(unit, {0.5, 0.5, 1.0}, {0.5, 0.5, 0.0}), 2.0);
    // Same face: straight.
    EXPECT_DOUBLE_EQ(box_surface_distance(slab, {0.1, 0.2, 0.7}, {1.0, 2.0, 0.7}), std::hypot(0.9, 1.8));
    // Adjacent faces across the edge y = 0, z = 1 of the unit cube: (0.5, 0.5, 1) and (0.5, 0, 0.5) unfold to a
    // vertical segment of length 1.
    EXPECT_DOUBLE_EQ(box_surface_distance(unit, {0.5, 0.5, 1.0}, {0.5, 0.0, 0.5}), 1.0);
    // The spider and the fly: room 30 x 12 x 12, spider on an end wall 1 from the ceiling on the centre line, fly on
    // the other end wall 1 from the floor on the centre line. The best path (over five faces) is 40, not 42.
    const Eigen::Vector3d room(30.0, 12.0, 12.0);
    EXPECT_NEAR(box_surface_distance(room, {0.0, 6.0, 11.0}, {30.0, 6.0, 1.0}), 40.0, 1e-12);
}

// The mantle of a capped prism with `sides` sides, unrolled: a point's arc-length coordinate along the polygon's
// perimeter (using the actual side lengths) and its height.
class UnrolledPrism {
public:
    UnrolledPrism(const TriangleMesh& mesh, int sides, int side_subdivisions) {
        for (int j = 0; j < sides; ++j) corners_.push_back(mesh.positions[j * side_subdivisions].head<2>());
        offsets_.push_back(0.0);
        for (int j = 0; j < sides; ++j) offsets_.push_back(offsets_.back() + (corners_[(j + 1) % sides] - corners_[j]).norm());
        perimeter_ = offsets_.back();
    }
    bool on_mantle(const Eigen::Vector3d& x) const { return arc_or_negative(x) >= 0.0; }
    double arc(const Eigen::Vector3d& x) const {
        const double s = arc_or_negative(x);
        if (s < 0.0) throw std::logic_error("point is not on the mantle");
        return s;
    }
    double arc_or_negative(const Eigen::Vector3d& x) const {
        const int n = static_cast<int>(corners_.size());
        for (int j = 0; j < n; ++j) {
            const Eigen::Vector2d a = corners_[j], b = corners_[(j + 1) % n];
            const Eigen::Vector2d d = b - a, r = x.head<2>() - a;
            const double cross = d.x() * r.y() - d.y() * r.x();
            const double along = r.dot(d) / d.squaredNorm();
            if (std::abs(cross) <= 1e-12 * d.squaredNorm() && along >= -1e-12 && along <= 1.0 + 1e-12)
                return offsets_[j] + r.norm();
        }
        return -1.0;
    }
    double distance(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const {
        double ds = std::abs(arc(p) - arc(q));
        ds = std::min(ds, perimeter_ - ds);
        return std::hypot(ds, p.z() - q.z());
    }

private:
    std::vector<Eigen::Vector2d> corners_;
    std::vector<double> offsets_;
    double perimeter_ = 0.0;
};

struct PrismCase {
    std::string name;
    std::function<SurfacePoint(const TriangleMesh&)> source;
};

void PrintTo(const PrismCase& c, std::ostream* out) { *out << c.name; }

class PrismMantle : public testing::TestWithParam<PrismCase> {};

constexpr int k_sides = 12, k_rows = 12, k_sub = 2;
constexpr double k_height = 6.0;

TEST_P(PrismMantle, distances_on_the_mantle_match_the_unrolled_strip) {
    const TriangleMesh arrays = capped_cylinder(1.0, k_height, k_sides, k_rows, k_sub);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const SurfacePoint source = GetParam().source(arrays);
    ExactGeodesic propagation(mesh);
    propagation.propagate({source});
    const UnrolledPrism strip(arrays, k_sides, k_sub);
    const Eigen::Vector3d s = point_position(arrays, source);
    OracleSweep options;
    options.floor = 1e-2 * bounding_diagonal(arrays);
    options.path_stride = 3;
    // Only where the unrolled distance is clearly shorter than any path that reaches a cap: such a path climbs at
    // least from s to the rim and back down to x.
    options.accept = [&](const Eigen::Vector3d& x) {
        if (x.z() <= 1e-9 || x.z() >= k_height - 1e-9 || !strip.on_mantle(x)) return false;
        const double mantle = strip.distance(s, x);
        return mantle < std::min(s.z() + x.z(), 2.0 * k_height - s.z() - x.z()) - 1e-6;
    };
    sweep_against_oracle(arrays, mesh, propagation, {source},
                         [&](const Eigen::Vector3d& x) { return strip.distance(s, x); }, options,
                         GetParam().name + ", source " + spec(source));
}

std::string prism_case_name(const testing::TestParamInfo<PrismCase>& info) { return info.param.name; }

// Mantle vertex (column, row): row·columns + column.
INSTANTIATE_TEST_SUITE_P(
    ExactGeodesicCappedCylinder, PrismMantle,
    testing::Values(
        PrismCase{"mid_height_corner_vertex",
                  [](const TriangleMesh&) { return SurfacePoint::at_vertex(6 * k_sides * k_sub + 0); }},
        PrismCase{"mid_height_side_vertex",
                  [](const TriangleMesh&) { return SurfacePoint::at_vertex(6 * k_sides * k_sub + 5); }},
        PrismCase{"face_point_above_middle",
                  [](const TriangleMesh&) {
                      // Mantle quad (column 7, row 7) is split into faces 2·(7·columns + 7) and the next one.
                      return SurfacePoint::in_face(2 * (7 * k_sides * k_sub + 7), {0.3, 0.25, 0.45});
                  }},
        PrismCase{"edge_point_below_middle",
                  [](const TriangleMesh&) {
                      const int v = 5 * k_sides * k_sub + 13;
                      return SurfacePoint::on_edge(v, v + k_sides * k_sub, 0.7);
                  }}),
    prism_case_name);

}  // namespace
}  // namespace geotri::test

// Flat polygons: in a convex polygon the geodesic distance is the Euclidean distance; in a non-convex one it is the
// length of the shortest path inside the polygon, which bends only at reflex corners (Dijkstra on the visibility
// graph of the reflex corners, computed in oracles.cpp).

#include "check_helpers.h"

#include <geotri_test/procedural_meshes.h>

#include <gtest/gtest.h>

namespace geotri::test {
namespace {

using geodesic::ExactGeodesic;
using geodesic::SurfacePoint;

enum class SourceKind { vertex, edge, face };

std::string kind_name(SourceKind kind) {
    return kind == SourceKind::vertex ? "vertex" : kind == SourceKind::edge ? "edge" : "face";
}

// The face whose centroid is nearest to (x, y).
int face_near(const TriangleMesh& mesh, double x, double y) {
    int best = 0;
    double best_distance = 1e300;
    for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f) {
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (int v : mesh.triangles[f]) c += mesh.positions[v] / 3.0;
        const double d = (c - Eigen::Vector3d(x, y, 0.0)).norm();
        if (d < best_distance) {
            best_distance = d;
            best = f;
        }
    }
    return best;
}

// A source of the given kind near (x, y): the first vertex of the nearest face, a point of its first edge, or a
// point inside it.
SurfacePoint source_near(const TriangleMesh& mesh, double x, double y, SourceKind kind) {
    const int f = face_near(mesh, x, y);
    const auto& t = mesh.triangles[f];
    switch (kind) {
        case SourceKind::vertex: return SurfacePoint::at_vertex(t[0]);
        case SourceKind::edge:
            return t[0] < t[1] ? SurfacePoint::on_edge(t[0], t[1], 0.375) : SurfacePoint::on_edge(t[1], t[0], 0.625);
        case SourceKind::face: return SurfacePoint::in_face(f, {0.2, 0.3, 0.5});
    }
    return {};
}

void expect_euclidean(const TriangleMesh& arrays, const SurfacePoint& source, const std::string& name) {
    const geodesic::Mesh mesh = arrays.to_mesh();
    ExactGeodesic propagation(mesh);
    propagation.propagate({source});
    const Eigen::Vector3d s = point_position(arrays, source);
    OracleSweep options;
    options.floor = 1e-2 * bounding_diagonal(arrays);
    sweep_against_oracle(arrays, mesh, propagation, {source}, [&](const Eigen::Vector3d& x) { return (x - s).norm(); },
                         options, name);
}

TriangleMesh convex_grid() { return flat_grid(12, 9, 3.0, 2.0, 0.2, 11); }

TEST(ExactGeodesicFlat, convex_grid_from_interior_vertex_matches_euclidean) {
    const TriangleMesh arrays = convex_grid();
    expect_euclidean(arrays, SurfacePoint::at_vertex(4 * 13 + 5), "grid, source v:" + std::to_string(4 * 13 + 5));
}

TEST(ExactGeodesicFlat, convex_grid_from_corner_vertex_matches_euclidean) {
    const TriangleMesh arrays = convex_grid();
    expect_euclidean(arrays, SurfacePoint::at_vertex(0), "grid, source at the corner v:0");
}

TEST(ExactGeodesicFlat, convex_grid_from_boundary_vertex_matches_euclidean) {
    const TriangleMesh arrays = convex_grid();
    expect_euclidean(arrays, SurfacePoint::at_vertex(6), "grid, source on the bottom side v:6");
}

TEST(ExactGeodesicFlat, convex_grid_from_edge_point_matches_euclidean) {
    const TriangleMesh arrays = convex_grid();
    const SurfacePoint source = source_near(arrays, 1.1, 0.7, SourceKind::edge);
    expect_euclidean(arrays, source, "grid, source " + spec(source));
}

TEST(ExactGeodesicFlat, convex_grid_from_boundary_edge_point_matches_euclidean) {
    const TriangleMesh arrays = convex_grid();
    // The bottom side's edge between vertices 3 and 4 (unperturbed: they lie on y = 0).
    const SurfacePoint source = SurfacePoint::on_edge(3, 4, 0.3);
    expect_euclidean(arrays, source, "grid, source " + spec(source));
}

TEST(ExactGeodesicFlat, convex_grid_from_face_point_matches_euclidean) {
    const TriangleMesh arrays = convex_grid();
    const SurfacePoint source = source_near(arrays, 2.2, 1.3, SourceKind::face);
    expect_euclidean(arrays, source, "grid, source " + spec(source));
}

TEST(ExactGeodesicFlat, convex_grid_distance_at_a_source_is_zero) {
    const TriangleMesh arrays = convex_grid();
    const geodesic::Mesh mesh = arrays.to_mesh();
    ExactGeodesic propagation(mesh);
    for (const SurfacePoint& source : {SurfacePoint::at_vertex(17), source_near(arrays, 1.1, 0.7, SourceKind::edge),
                                       source_near(arrays, 2.2, 1.3, SourceKind::face)}) {
        propagation.propagate({source});
        EXPECT_EQ(propagation.distance(source), 0.0) << spec(source);
        if (source.kind == geodesic::PointKind::vertex) {
            EXPECT_EQ(propagation.distance(source.vertex), 0.0);
        }
    }
}

struct PolygonCase {
    std::string name;
    std::vector<std::string> cells;
    double source_x;  // where the source is, in cell units
    double source_y;
    SourceKind kind;
};

void PrintTo(const PolygonCase& c, std::ostream* out) { *out << c.name; }

std::string case_name(const testing::TestParamInfo<PolygonCase>& info) {
    return info.param.name + "_from_" + kind_name(info.param.kind);
}

class NonConvexPolygon : public testing::TestWithParam<PolygonCase> {};

TEST_P(NonConvexPolygon, distances_and_paths_match_visibility_graph_shortest_paths) {
    const PolygonCase& c = GetParam();
    const TriangleMesh arrays = flat_cell_polygon(c.cells, 4, 0.2, 5);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const SurfacePoint source = source_near(arrays, c.source_x, c.source_y, c.kind);
    ExactGeodesic propagation(mesh);
    propagation.propagate({source});
    const CellPolygon polygon(c.cells);
    const Eigen::Vector3d s = point_position(arrays, source);
    ASSERT_TRUE(polygon.contains(s.head<2>()));
    OracleSweep options;
    options.floor = 1e-2 * bounding_diagonal(arrays);
    options.path_stride = 3;
    sweep_against_oracle(
        arrays, mesh, propagation, {source},
        [&](const Eigen::Vector3d& x) { return polygon.shortest_path_length(s.head<2>(), x.head<2>()); }, options,
        c.name + ", source " + spec(source));
}

// Sources sit in a cell far from the opposite end of the shape, so that most targets are reached around corners.
INSTANTIATE_TEST_SUITE_P(
    ExactGeodesicFlat, NonConvexPolygon,
    testing::Values(PolygonCase{"l_shape", l_shape_cells(), 0.5, 2.6, SourceKind::vertex},
                    PolygonCase{"l_shape", l_shape_cells(), 0.4, 2.5, SourceKind::edge},
                    PolygonCase{"l_shape", l_shape_cells(), 0.6, 2.4, SourceKind::face},
                    PolygonCase{"u_shape", u_shape_cells(), 0.5, 2.5, SourceKind::vertex},
                    PolygonCase{"u_shape", u_shape_cells(), 0.3, 2.7, SourceKind::edge},
                    PolygonCase{"u_shape", u_shape_cells(), 0.5, 2.2, SourceKind::face},
                    PolygonCase{"comb", comb_cells(), 0.5, 2.5, SourceKind::vertex},
                    PolygonCase{"comb", comb_cells(), 2.5, 2.6, SourceKind::edge},
                    PolygonCase{"comb", comb_cells(), 4.4, 2.3, SourceKind::face},
                    PolygonCase{"s_shape", s_shape_cells(), 0.5, 4.5, SourceKind::vertex},
                    PolygonCase{"s_shape", s_shape_cells(), 0.3, 4.6, SourceKind::edge},
                    PolygonCase{"s_shape", s_shape_cells(), 0.6, 4.4, SourceKind::face},
                    PolygonCase{"square_with_hole", square_with_hole_cells(), 0.5, 1.5, SourceKind::vertex},
                    PolygonCase{"square_with_hole", square_with_hole_cells(), 0.3, 0.3, SourceKind::edge},
                    PolygonCase{"square_with_hole", square_with_hole_cells(), 2.6, 1.6, SourceKind::face}),
    case_name);

// The oracle itself, on cases worked out by hand, so that a wrong oracle cannot pass a wrong library.
TEST(CellPolygonOracle, shortest_paths_of_hand_worked_cases) {
    const CellPolygon l(l_shape_cells());
    // From the top of the L's arm to the end of its foot: around the reflex corner (1, 1).
    const double expected = (Eigen::Vector2d(0.5, 2.5) - Eigen::Vector2d(1, 1)).norm() +
                            (Eigen::Vector2d(1, 1) - Eigen::Vector2d(2.5, 0.5)).norm();
    EXPECT_DOUBLE_EQ(l.shortest_path_length({0.5, 2.5}, {2.5, 0.5}), expected);
    EXPECT_DOUBLE_EQ(l.shortest_path_length({0.5, 2.5}, {0.5, 0.25}), 2.25);
    EXPECT_FALSE(l.segment_inside({0.5, 2.5}, {2.5, 0.5}));
    EXPECT_TRUE(l.segment_inside({0, 3}, {0, 0}));  // along the boundary
    EXPECT_TRUE(l.segment_inside({0.5, 1.5}, {1.5, 0.5}));  // touching the reflex corner
    const CellPolygon hole(square_with_hole_cells());
    EXPECT_EQ(hole.reflex_corners().size(), 4u);
    // Across the hole from the middle of the left column to the middle of the right one: over a corner pair.
    EXPECT_DOUBLE_EQ(hole.shortest_path_length({0.5, 1.5}, {2.5, 1.5}),
                     2.0 * (Eigen::Vector2d(0.5, 1.5) - Eigen::Vector2d(1, 2)).norm() + 1.0);
    const CellPolygon u(u_shape_cells());
    EXPECT_DOUBLE_EQ(u.shortest_path_length({0.5, 2.5}, {2.5, 2.5}),
                     2.0 * (Eigen::Vector2d(0.5, 2.5) - Eigen::Vector2d(1, 1)).norm() + 1.0);
}

}  // namespace
}  // namespace geotri::test

// Edge cases: several components, zero-area faces, ties between equal shortest paths, rays that run along edges
// through vertices, bad sources, and reuse of one propagation object. Boundaries and holes are covered by
// flat_polygon_test.cpp.

#include "check_helpers.h"

#include <geotri_test/procedural_meshes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace geotri::test {
namespace {

using geodesic::ExactGeodesic;
using geodesic::PropagationOptions;
using geodesic::SurfacePoint;

constexpr double inf = std::numeric_limits<double>::infinity();

int vertex_at(const TriangleMesh& mesh, const Eigen::Vector3d& x) {
    for (int v = 0; v < static_cast<int>(mesh.positions.size()); ++v)
        if (mesh.positions[v] == x) return v;
    throw std::logic_error("no vertex there");
}

// --- Several components -----------------------------------------------------------------------------------------

TEST(ExactGeodesicComponents, distance_across_components_is_infinite_and_has_no_path) {
    const TriangleMesh cube_part = cube(4, 1.0, true, 2);
    const TriangleMesh arrays = disjoint_union(cube_part, icosphere(2), {4.0, 0.0, 0.0});
    const geodesic::Mesh mesh = arrays.to_mesh();
    const int cube_vertices = static_cast<int>(cube_part.positions.size());
    const int source = vertex_at(arrays, {0.5, 0.25, 1.0});
    ExactGeodesic propagation(mesh);
    propagation.propagate({SurfacePoint::at_vertex(source)});
    FailureLog log("source v:" + std::to_string(source) + " on the cube, targets on the sphere");
    for (int v = cube_vertices; v < mesh.num_vertices(); ++v) {
        if (propagation.distance(v) != inf) log.add("v:" + std::to_string(v) + ": distance " + exact(propagation.distance(v)));
        try {
            if (!propagation.shortest_path(SurfacePoint::at_vertex(v)).empty()) log.add("v:" + std::to_string(v) + ": a path");
        } catch (const std::exception& error) {
            log.add("v:" + std::to_string(v) + ": shortest_path() threw instead of returning an empty path: " + error.what());
        }
    }
    log.report();
    const int sphere_face = static_cast<int>(cube_part.triangles.size()) + 7;
    const SurfacePoint sphere_point = SurfacePoint::in_face(sphere_face, {0.2, 0.3, 0.5});
    EXPECT_EQ(propagation.distance(sphere_point), inf);
    std::vector<SurfacePoint> path;
    EXPECT_NO_THROW(path = propagation.shortest_path(sphere_point)) << spec(sphere_point) << " (unreachable)";
    EXPECT_TRUE(path.empty());
    // The cube part keeps the cube's own distances.
    OracleSweep options;
    options.floor = 1e-2 * std::sqrt(3.0);
    options.accept = [](const Eigen::Vector3d& x) { return x.x() <= 1.0; };
    const Eigen::Vector3d s = arrays.positions[source];
    sweep_against_oracle(arrays, mesh, propagation, {SurfacePoint::at_vertex(source)},
                         [&](const Eigen::Vector3d& x) { return box_surface_distance({1.0, 1.0, 1.0}, s, x); }, options,
                         "cube part of a cube + sphere");
}

TEST(ExactGeodesicComponents, one_source_per_component_reaches_every_vertex) {
    const TriangleMesh cube_part = cube(3);
    const TriangleMesh arrays = disjoint_union(cube_part, torus(1.0, 0.3, 16, 8), {4.0, 0.0, 0.0});
    const geodesic::Mesh mesh = arrays.to_mesh();
    ExactGeodesic propagation(mesh);
    const int second = static_cast<int>(cube_part.positions.size()) + 5;
    propagation.propagate({SurfacePoint::at_vertex(0), SurfacePoint::at_vertex(second)});
    for (int v = 0; v < mesh.num_vertices(); ++v) EXPECT_LT(propagation.distance(v), inf) << "v:" << v;
    EXPECT_EQ(propagation.distance(second), 0.0);
}

TEST(ExactGeodesicComponents, unreachable_stop_point_lets_the_propagation_finish) {
    const TriangleMesh cube_part = cube(3);
    const TriangleMesh arrays = disjoint_union(cube_part, cube(2), {3.0, 0.0, 0.0});
    const geodesic::Mesh mesh = arrays.to_mesh();
    ExactGeodesic full(mesh), stopped(mesh);
    full.propagate({SurfacePoint::at_vertex(0)});
    PropagationOptions options;
    options.stop_points = {SurfacePoint::at_vertex(mesh.num_vertices() - 1)};
    stopped.propagate({SurfacePoint::at_vertex(0)}, options);
    EXPECT_EQ(stopped.distance(mesh.num_vertices() - 1), inf);
    for (int v = 0; v < static_cast<int>(cube_part.positions.size()); ++v)
        EXPECT_TRUE(near_relative(stopped.distance(v), full.distance(v), 1e-12, 1e-2)) << "v:" << v;
}

// --- Zero-area faces --------------------------------------------------------------------------------------------

// Splits the edge a-b at its midpoint m with a zero-area face (a, b, m): the face that had a -> b becomes (a, m, c)
// and (m, b, c). The surface, and so every distance, is unchanged. Returns the index of the new zero-area face.
int insert_zero_area_face_directed(TriangleMesh& mesh, int a, int b) {
    int f = -1, slot = -1;
    for (int g = 0; g < static_cast<int>(mesh.triangles.size()) && f < 0; ++g)
        for (int i = 0; i < 3; ++i)
            if (mesh.triangles[g][i] == a && mesh.triangles[g][(i + 1) % 3] == b) {
                f = g;
                slot = i;
            }
    if (f < 0) throw std::logic_error("no directed edge a -> b");
    const int c = mesh.triangles[f][(slot + 2) % 3];
    const int m = static_cast<int>(mesh.positions.size());
    mesh.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]));
    mesh.triangles[f] = {a, m, c};
    mesh.triangles.push_back({m, b, c});
    mesh.triangles.push_back({a, b, m});
    return static_cast<int>(mesh.triangles.size()) - 1;
}

// The same for the undirected edge {a, b}, split from whichever face holds a -> b or b -> a first.
int insert_zero_area_face(TriangleMesh& mesh, int a, int b) {
    for (const auto& t : mesh.triangles)
        for (int i = 0; i < 3; ++i)
            if (t[i] == a && t[(i + 1) % 3] == b) return insert_zero_area_face_directed(mesh, a, b);
    return insert_zero_area_face_directed(mesh, b, a);
}

TEST(ExactGeodesicZeroArea, cube_with_a_zero_area_face_keeps_the_cube_distances) {
    TriangleMesh arrays = cube(4);
    // An edge inside the top face, away from the cube's edges (coordinates are multiples of 1/4: the midpoint is exact).
    const int a = vertex_at(arrays, {0.25, 0.5, 1.0}), b = vertex_at(arrays, {0.5, 0.5, 1.0});
    insert_zero_area_face(arrays, a, b);
    const geodesic::Mesh mesh = arrays.to_mesh();
    EXPECT_EQ(mesh.face_area(mesh.num_faces() - 1), 0.0);
    const Eigen::Vector3d size(1.0, 1.0, 1.0);
    const int m = mesh.num_vertices() - 1;
    for (const SurfacePoint& source : {SurfacePoint::at_vertex(m), SurfacePoint::at_vertex(a),
                                       SurfacePoint::at_vertex(vertex_at(arrays, {1.0, 0.25, 0.5}))}) {
        ExactGeodesic propagation(mesh);
        propagation.propagate({source});
        const Eigen::Vector3d s = point_position(arrays, source);
        OracleSweep options;
        options.floor = 1e-2 * size.norm();
        sweep_against_oracle(arrays, mesh, propagation, {source},
                             [&](const Eigen::Vector3d& x) { return box_surface_distance(size, s, x); }, options,
                             "cube with a zero-area face, source " + spec(source));
    }
}

TEST(ExactGeodesicZeroArea, source_inside_a_zero_area_face_is_the_point_on_its_segment) {
    TriangleMesh arrays = cube(4);
    const int a = vertex_at(arrays, {0.25, 0.5, 1.0}), b = vertex_at(arrays, {0.5, 0.5, 1.0});
    const int zero_face = insert_zero_area_face(arrays, a, b);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const SurfacePoint source = SurfacePoint::in_face(zero_face, {0.25, 0.25, 0.5});
    ExactGeodesic propagation(mesh);
    propagation.propagate({source});
    const Eigen::Vector3d s = point_position(arrays, source);
    OracleSweep options;
    options.floor = 1e-2 * std::sqrt(3.0);
    sweep_against_oracle(arrays, mesh, propagation, {source},
                         [&](const Eigen::Vector3d& x) { return box_surface_distance({1.0, 1.0, 1.0}, s, x); }, options,
                         "cube, source inside the zero-area face " + spec(source));
}

TEST(ExactGeodesicZeroArea, flat_grid_with_zero_area_faces_keeps_euclidean_distances) {
    TriangleMesh arrays = flat_grid(8, 8, 2.0, 2.0, 0.0, 3);  // unperturbed: midpoints are exact
    for (const auto& [p, q] : {std::pair<Eigen::Vector3d, Eigen::Vector3d>{{0.5, 0.5, 0.0}, {0.75, 0.5, 0.0}},
                               {{1.25, 1.0, 0.0}, {1.25, 1.25, 0.0}}}) {
        const int a = vertex_at(arrays, p), b = vertex_at(arrays, q);
        insert_zero_area_face(arrays, a, b);
    }
    const geodesic::Mesh mesh = arrays.to_mesh();
    for (const SurfacePoint& source : {SurfacePoint::at_vertex(0), SurfacePoint::at_vertex(mesh.num_vertices() - 1),
                                       SurfacePoint::at_vertex(vertex_at(arrays, {1.0, 0.75, 0.0}))}) {
        ExactGeodesic propagation(mesh);
        propagation.propagate({source});
        const Eigen::Vector3d s = point_position(arrays, source);
        OracleSweep options;
        options.floor = 1e-2 * bounding_diagonal(arrays);
        sweep_against_oracle(arrays, mesh, propagation, {source},
                             [&](const Eigen::Vector3d& x) { return (x - s).norm(); }, options,
                             "flat grid with zero-area faces, source " + spec(source));
    }
}

// --- Window counts ------------------------------------------------------------------------------------------

// On a flat mesh every window comes from the one source, split only where rays pass a vertex; the fragments of one
// ray family must be merged again, or their number grows with every vertex passed (it once went from 198k to 3.8M
// windows on a 100k-face grid, all exact, 20 times slower). A count, not a timing: it cannot be flaky.
TEST(ExactGeodesicWindows, flat_grid_needs_few_windows_per_edge) {
    const TriangleMesh arrays = flat_grid(100, 100, 1.0, 1.0);
    const geodesic::Mesh mesh = arrays.to_mesh();
    ExactGeodesic propagation(mesh);
    propagation.propagate({SurfacePoint::at_vertex(mesh.num_vertices() / 2)});
    EXPECT_LT(propagation.stats().windows_created, static_cast<std::size_t>(2 * mesh.num_halfedges()))
        << "windows per halfedge: "
        << static_cast<double>(propagation.stats().windows_created) / mesh.num_halfedges();
}

// --- Ties -------------------------------------------------------------------------------------------------------

TEST(ExactGeodesicTies, cube_corner_to_opposite_corner_is_sqrt5_over_three_tied_paths) {
    const TriangleMesh arrays = cube(4, 1.0, true, 9);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const Adjacency adjacency(arrays);
    const int a = vertex_at(arrays, {0, 0, 0}), b = vertex_at(arrays, {1, 1, 1});
    ExactGeodesic propagation(mesh);
    propagation.propagate({SurfacePoint::at_vertex(a)});
    EXPECT_NEAR(propagation.distance(b), std::sqrt(5.0), 1e-12 * std::sqrt(5.0));
    const auto path = propagation.shortest_path(SurfacePoint::at_vertex(b));
    ASSERT_FALSE(path.empty());
    const PathReport report = check_geodesic_path(arrays, adjacency, path, 1e-6);
    EXPECT_TRUE(report.problems.empty()) << report.problems.front();
    EXPECT_TRUE(report.representation.empty()) << report.representation.front();
    EXPECT_NEAR(report.length, std::sqrt(5.0), 1e-12 * std::sqrt(5.0));
    EXPECT_EQ(point_position(arrays, path.front()), arrays.positions[a]);
    EXPECT_EQ(point_position(arrays, path.back()), arrays.positions[b]);
}

TEST(ExactGeodesicTies, cube_face_centre_to_opposite_face_centre_is_two_over_four_tied_paths) {
    const TriangleMesh arrays = cube(4);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const Adjacency adjacency(arrays);
    const int a = vertex_at(arrays, {0.5, 0.5, 1.0}), b = vertex_at(arrays, {0.5, 0.5, 0.0});
    ExactGeodesic propagation(mesh);
    propagation.propagate({SurfacePoint::at_vertex(a)});
    EXPECT_NEAR(propagation.distance(b), 2.0, 2e-12);
    const auto path = propagation.shortest_path(SurfacePoint::at_vertex(b));
    ASSERT_FALSE(path.empty());
    const PathReport report = check_geodesic_path(arrays, adjacency, path, 1e-6);
    EXPECT_TRUE(report.problems.empty()) << report.problems.front();
    EXPECT_TRUE(report.representation.empty()) << report.representation.front();
    EXPECT_NEAR(report.length, 2.0, 2e-12);
}

TEST(ExactGeodesicTies, two_sources_at_equal_distance_split_a_flat_strip_in_the_middle) {
    const TriangleMesh arrays = flat_grid(8, 2, 4.0, 1.0, 0.0, 4);
    const geodesic::Mesh mesh = arrays.to_mesh();
    ExactGeodesic propagation(mesh);
    const int left = vertex_at(arrays, {0.0, 0.5, 0.0}), right = vertex_at(arrays, {4.0, 0.5, 0.0});
    propagation.propagate({SurfacePoint::at_vertex(left), SurfacePoint::at_vertex(right)});
    for (int v = 0; v < mesh.num_vertices(); ++v) {
        const Eigen::Vector3d& x = arrays.positions[v];
        const double expected = std::min((x - arrays.positions[left]).norm(), (x - arrays.positions[right]).norm());
        EXPECT_TRUE(near_relative(propagation.distance(v), expected, 1e-12, 1e-2 * bounding_diagonal(arrays))) << "v:" << v;
    }
    const int middle = vertex_at(arrays, {2.0, 0.5, 0.0});
    EXPECT_NEAR(propagation.distance(middle), 2.0, 2e-12);
    EXPECT_EQ(propagation.shortest_path(SurfacePoint::at_vertex(middle)).size() >= 2, true);
}

// --- Rays along edges -------------------------------------------------------------------------------------------

// A thin open prism of `sides` sides, `rows` rows of quads tall, each quad split along the same diagonal: the
// needles of a drilled hole in a CAD export. Rays from a vertex of the bottom ring run exactly along the long edges
// of the rows above it, through their vertices.
TriangleMesh thin_prism(int sides, int rows, double radius, double row_height) {
    TriangleMesh mesh;
    for (int j = 0; j <= rows; ++j)
        for (int i = 0; i < sides; ++i) {
            const double angle = 2.0 * M_PI * i / sides;
            mesh.positions.emplace_back(radius * std::cos(angle), radius * std::sin(angle), j * row_height);
        }
    auto at = [&](int i, int j) { return j * sides + i % sides; };
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < sides; ++i) {
            mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return mesh;
}

TEST(ExactGeodesicRaysAlongEdges, every_vertex_of_a_thin_prism_gets_its_unrolled_distance) {
    // The prism is developable and has no vertex of cone angle above 2π: unrolled around the axis, the distance
    // between two of its vertices is the straight line in the strip, going round one way or the other. A ray along
    // a long edge passes through a vertex at every row; the rounding of its far source once made it miss both
    // windows beside that vertex, and 30 vertices of 1476 got no distance.
    const int sides = 36, rows = 40;
    const double radius = 0.05, row_height = 0.187;
    const TriangleMesh arrays = thin_prism(sides, rows, radius, row_height);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const double side = 2.0 * radius * std::sin(M_PI / sides);
    ExactGeodesic propagation(mesh);
    for (int source = 0; source < sides; ++source) {
        propagation.propagate({SurfacePoint::at_vertex(source)});
        FailureLog log("thin prism, source v:" + std::to_string(source));
        for (int v = 0; v < mesh.num_vertices(); ++v) {
            const int around = std::abs(v % sides - source);
            const double unrolled = std::hypot(std::min(around, sides - around) * side, (v / sides) * row_height);
            if (!near_relative(propagation.distance(v), unrolled, 1e-12, row_height))
                log.add("v:" + std::to_string(v) + ": distance " + exact(propagation.distance(v)) + ", unrolled " +
                        exact(unrolled));
        }
        log.report();
    }
}

// --- Bad input --------------------------------------------------------------------------------------------------

TEST(ExactGeodesicInput, bad_sources_throw_invalid_input) {
    const TriangleMesh arrays = cube(2);
    const geodesic::Mesh mesh = arrays.to_mesh();
    ExactGeodesic propagation(mesh);
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    const auto& t0 = arrays.triangles[0];
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(propagation.propagate({}), InvalidInput);
    const std::vector<std::pair<std::string, SurfacePoint>> bad = {
        {"negative vertex", SurfacePoint::at_vertex(-1)},
        {"vertex past the end", SurfacePoint::at_vertex(nv)},
        {"edge that does not exist", SurfacePoint::on_edge(vertex_at(arrays, {0, 0, 0}), vertex_at(arrays, {1, 1, 1}), 0.5)},
        {"edge with a vertex out of range", SurfacePoint::on_edge(t0[0], nv + 3, 0.5)},
        {"edge parameter above 1", SurfacePoint::on_edge(t0[0], t0[1], 1.5)},
        {"edge parameter below 0", SurfacePoint::on_edge(t0[0], t0[1], -0.25)},
        {"edge parameter NaN", SurfacePoint::on_edge(t0[0], t0[1], nan)},
        {"negative face", SurfacePoint::in_face(-1, {0.2, 0.3, 0.5})},
        {"face past the end", SurfacePoint::in_face(nf, {0.2, 0.3, 0.5})},
        {"negative barycentric coordinate", SurfacePoint::in_face(0, {-0.2, 0.7, 0.5})},
        {"barycentric coordinates summing to 2", SurfacePoint::in_face(0, {0.5, 0.5, 1.0})},
        {"NaN barycentric coordinate", SurfacePoint::in_face(0, {nan, 0.5, 0.5})},
        {"infinite barycentric coordinate", SurfacePoint::in_face(0, {std::numeric_limits<double>::infinity(), 0.5, 0.5})},
    };
    for (const auto& [why, point] : bad) {
        EXPECT_THROW(propagation.propagate({point}), InvalidInput) << why;
        EXPECT_THROW(propagation.propagate({SurfacePoint::at_vertex(0), point}), InvalidInput) << why << " (second source)";
    }
    // The object still works after refusing bad input.
    propagation.propagate({SurfacePoint::at_vertex(0)});
    EXPECT_EQ(propagation.distance(0), 0.0);
    EXPECT_LT(propagation.distance(nv - 1), inf);
}

// --- Equivalent sources -----------------------------------------------------------------------------------------

TEST(ExactGeodesicInput, edge_source_given_in_either_vertex_order_gives_the_same_distances) {
    const TriangleMesh arrays = perturbed_sphere(6, 0.1, 3);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const auto& t = arrays.triangles[17];
    ExactGeodesic forward(mesh), backward(mesh);
    forward.propagate({SurfacePoint::on_edge(t[0], t[1], 0.25)});
    backward.propagate({SurfacePoint::on_edge(t[1], t[0], 0.75)});
    for (int v = 0; v < mesh.num_vertices(); ++v)
        EXPECT_TRUE(near_relative(backward.distance(v), forward.distance(v), 1e-12, 1e-2)) << "v:" << v;
}

TEST(ExactGeodesicInput, face_source_on_an_edge_or_vertex_equals_that_edge_or_vertex_source) {
    const TriangleMesh arrays = perturbed_sphere(6, 0.1, 3);
    const geodesic::Mesh mesh = arrays.to_mesh();
    const auto& t = arrays.triangles[40];
    ExactGeodesic as_face(mesh), as_edge(mesh), as_vertex(mesh);
    as_face.propagate({SurfacePoint::in_face(40, {0.0, 0.25, 0.75})});
    as_edge.propagate({SurfacePoint::on_edge(t[1], t[2], 0.75)});
    for (int v = 0; v < mesh.num_vertices(); ++v)
        EXPECT_TRUE(near_relative(as_face.distance(v), as_edge.distance(v), 1e-12, 1e-2)) << "v:" << v;
    as_face.propagate({SurfacePoint::in_face(40, {0.0, 1.0, 0.0})});
    as_vertex.propagate({SurfacePoint::at_vertex(t[1])});
    for (int v = 0; v < mesh.num_vertices(); ++v)
        EXPECT_TRUE(near_relative(as_face.distance(v), as_vertex.distance(v), 1e-12, 1e-2)) << "v:" << v;
}

TEST(ExactGeodesicInput, repeated_source_equals_a_single_source) {
    const TriangleMesh arrays = torus(1.0, 0.4, 24, 12);
    const geodesic::Mesh mesh = arrays.to_mesh();
    ExactGeodesic once(mesh), twice(mesh);
    once.propagate({SurfacePoint::at_vertex(5)});
    twice.propagate({SurfacePoint::at_vertex(5), SurfacePoint::at_vertex(5)});
    for (int v = 0; v < mesh.num_vertices(); ++v)
        EXPECT_TRUE(near_relative(twice.distance(v), once.distance(v), 1e-12, 1e-2)) << "v:" << v;
}

// --- Reuse ------------------------------------------------------------------------------------------------------

struct PropagationRun {
    std::vector<SurfacePoint> sources;
    PropagationOptions options;
};

std::vector<PropagationRun> varied_runs(const TriangleMesh& arrays) {
    PointSampler sampler(31);
    std::vector<PropagationRun> runs;
    runs.push_back({{SurfacePoint::at_vertex(3)}, {}});
    runs.push_back({{sampler.face_point(arrays)}, {}});
    PropagationRun limited{{SurfacePoint::at_vertex(100)}, {}};
    limited.options.max_distance = 0.7;
    runs.push_back(limited);
    PropagationRun stopped{{sampler.edge_point(arrays)}, {}};
    stopped.options.stop_points = {SurfacePoint::at_vertex(101), sampler.face_point(arrays)};
    runs.push_back(stopped);
    PropagationRun directed = stopped;  // the runs after it must not inherit its goals
    directed.options.goal_directed = true;
    runs.push_back(directed);
    runs.push_back({{SurfacePoint::at_vertex(7), sampler.edge_point(arrays), sampler.face_point(arrays)}, {}});
    runs.push_back({{SurfacePoint::at_vertex(3)}, {}});  // the first one again, after everything else
    return runs;
}

TEST(ExactGeodesicReuse, one_object_for_many_propagations_gives_the_results_of_fresh_objects) {
    const TriangleMesh arrays = perturbed_sphere(9, 0.2, 12);
    const geodesic::Mesh mesh = arrays.to_mesh();
    PointSampler sampler(32);
    std::vector<SurfacePoint> probes;
    for (int i = 0; i < 10; ++i) probes.push_back(i % 2 ? sampler.face_point(arrays) : sampler.edge_point(arrays));
    ExactGeodesic reused(mesh);
    EXPECT_EQ(reused.windows_created_total(), 0u);
    std::size_t windows = 0;
    int index = 0;
    for (const PropagationRun& run : varied_runs(arrays)) {
        SCOPED_TRACE("run " + std::to_string(index++));
        ExactGeodesic fresh(mesh);
        fresh.propagate(run.sources, run.options);
        reused.propagate(run.sources, run.options);
        EXPECT_EQ(reused.vertex_distances(), fresh.vertex_distances());
        EXPECT_EQ(reused.settled_radius(), fresh.settled_radius());
        for (const auto& p : probes) {
            EXPECT_EQ(reused.distance(p), fresh.distance(p)) << spec(p);
            EXPECT_EQ(reused.shortest_path(p), fresh.shortest_path(p)) << spec(p);
        }
        EXPECT_EQ(reused.stats().windows_created, fresh.stats().windows_created);
        EXPECT_EQ(reused.stats().queue_pops, fresh.stats().queue_pops);
        EXPECT_EQ(reused.stats().stopped_early, fresh.stats().stopped_early);
        // Only propagate()'s windows are work done (without keep_windows, the queries' own would count nowhere).
        windows += fresh.stats().windows_created;
        EXPECT_EQ(reused.windows_created_total(), windows);
        EXPECT_EQ(fresh.windows_created_total(), fresh.stats().windows_created);
    }
}

TEST(ExactGeodesicReuse, moved_object_keeps_its_propagation) {
    const TriangleMesh arrays = icosphere(2);
    const geodesic::Mesh mesh = arrays.to_mesh();
    ExactGeodesic original(mesh);
    original.propagate({SurfacePoint::at_vertex(0)});
    const std::vector<double> expected = original.vertex_distances();
    ExactGeodesic moved(std::move(original));
    EXPECT_EQ(moved.vertex_distances(), expected);
    ExactGeodesic assigned(mesh);
    assigned = std::move(moved);
    EXPECT_EQ(assigned.vertex_distances(), expected);
    assigned.propagate({SurfacePoint::at_vertex(1)});
    EXPECT_EQ(assigned.distance(1), 0.0);
}

}  // namespace
}  // namespace geotri::test

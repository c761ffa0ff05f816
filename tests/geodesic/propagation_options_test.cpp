// Several sources, sources on edges and inside faces, stop points and a maximum distance, each checked against
// full single-source propagations (and, on the cube, against the unfolding oracle).

#include "check_helpers.h"

#include <geotri_test/procedural_meshes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace geotri::test {
namespace {

using geodesic::ExactGeodesic;
using geodesic::PropagationOptions;
using geodesic::SurfacePoint;

constexpr double inf = std::numeric_limits<double>::infinity();

class Options : public GeneratedMeshTest {
protected:
    double full_distance(const std::vector<SurfacePoint>& sources, const SurfacePoint& at) const {
        ExactGeodesic propagation(*mesh_);
        propagation.propagate(sources);
        return propagation.distance(at);
    }
    std::vector<double> full_vertex_distances(const std::vector<SurfacePoint>& sources) const {
        ExactGeodesic propagation(*mesh_);
        propagation.propagate(sources);
        return propagation.vertex_distances();
    }
};

TEST_P(Options, several_sources_give_the_minimum_of_single_source_distances) {
    PointSampler sampler(21);
    const std::vector<SurfacePoint> sources = {SurfacePoint::at_vertex(sampler.vertex(arrays_)),
                                               sampler.edge_point(arrays_), sampler.face_point(arrays_)};
    std::vector<std::vector<double>> single;
    for (const auto& s : sources) single.push_back(full_vertex_distances({s}));
    ExactGeodesic propagation(*mesh_);
    propagation.propagate(sources);
    FailureLog log(GetParam().name + ": several sources");
    for (int v = 0; v < mesh_->num_vertices(); ++v) {
        const double expected = std::min({single[0][v], single[1][v], single[2][v]});
        const double got = propagation.distance(v);
        if (!near_relative(got, expected, 1e-12, 1e-2 * diagonal_))
            log.add("v:" + std::to_string(v) + " expected " + exact(expected) + " got " + exact(got));
    }
    // Paths start at the nearest source.
    const Adjacency adjacency(arrays_);
    for (int i = 0; i < 20; ++i) {
        const int v = sampler.vertex(arrays_);
        const auto path = propagation.shortest_path(SurfacePoint::at_vertex(v));
        ASSERT_FALSE(path.empty());
        int nearest = 0;
        for (int k = 1; k < 3; ++k)
            if (single[k][v] < single[nearest][v]) nearest = k;
        if ((point_position(arrays_, path.front()) - point_position(arrays_, sources[nearest])).norm() > 1e-12 * diagonal_)
            log.add("path to v:" + std::to_string(v) + " starts at " + spec(path.front()) + ", not at the nearest source " +
                    spec(sources[nearest]));
        const PathReport report = check_geodesic_path(arrays_, adjacency, path, 1e-6);
        for (const auto& p : report.problems) log.add("path to v:" + std::to_string(v) + ": " + p);
        for (const auto& p : report.representation) log.add("path to v:" + std::to_string(v) + ": " + p);
        if (!near_relative(report.length, propagation.distance(v), 1e-9, 1e-2 * diagonal_))
            log.add("path to v:" + std::to_string(v) + " has length " + exact(report.length) + ", distance " +
                    exact(propagation.distance(v)));
    }
    log.report();
}

TEST_P(Options, edge_and_face_sources_are_symmetric_with_vertex_sources) {
    PointSampler sampler(22);
    FailureLog log(GetParam().name + ": d(s, v) = d(v, s)");
    for (int round = 0; round < 3; ++round) {
        for (const SurfacePoint& s : {sampler.edge_point(arrays_), sampler.face_point(arrays_)}) {
            ExactGeodesic from_s(*mesh_);
            from_s.propagate({s});
            EXPECT_EQ(from_s.distance(s), 0.0) << spec(s);
            for (int k = 0; k < 3; ++k) {
                const int v = sampler.vertex(arrays_);
                const double there = from_s.distance(v);
                const double back = full_distance({SurfacePoint::at_vertex(v)}, s);
                if (!near_relative(there, back, 1e-9, 1e-2 * diagonal_))
                    log.add("source " + spec(s) + ", v:" + std::to_string(v) + ": d(s, v) = " + exact(there) +
                            ", d(v, s) = " + exact(back));
                const double straight = (point_position(arrays_, s) - arrays_.positions[v]).norm();
                if (there < straight * (1.0 - 1e-12))
                    log.add("source " + spec(s) + ", v:" + std::to_string(v) + ": d = " + exact(there) +
                            " is shorter than the straight line " + exact(straight));
            }
        }
    }
    log.report();
}

TEST_P(Options, stop_points_give_full_distances_within_the_settled_radius_and_inf_beyond) {
    PointSampler sampler(23);
    const SurfacePoint source = SurfacePoint::at_vertex(sampler.vertex(arrays_));
    ExactGeodesic full(*mesh_);
    full.propagate({source});
    const std::vector<double> all = full.vertex_distances();
    double farthest = 0.0;
    for (double d : all)
        if (d < inf) farthest = std::max(farthest, d);
    EXPECT_EQ(full.settled_radius(), inf);
    EXPECT_FALSE(full.stats().stopped_early);

    // Stop points in the nearer third of the surface, of every kind.
    PropagationOptions options;
    while (options.stop_points.size() < 3) {
        const int v = sampler.vertex(arrays_);
        if (all[v] < farthest / 3.0) options.stop_points.push_back(SurfacePoint::at_vertex(v));
    }
    while (options.stop_points.size() < 5) {
        const SurfacePoint p = options.stop_points.size() == 3 ? sampler.face_point(arrays_) : sampler.edge_point(arrays_);
        if (full.distance(p) < farthest / 3.0) options.stop_points.push_back(p);
    }
    ExactGeodesic stopped(*mesh_);
    stopped.propagate({source}, options);
    const double radius = stopped.settled_radius();
    EXPECT_TRUE(stopped.stats().stopped_early);
    EXPECT_LT(radius, inf);
    FailureLog log(GetParam().name + ": stop points (settled radius " + exact(radius) + ")");
    const Adjacency adjacency(arrays_);
    for (const auto& p : options.stop_points) {
        const double expected = full.distance(p), got = stopped.distance(p);
        if (!near_relative(got, expected, 1e-12, 1e-2 * diagonal_))
            log.add("stop point " + spec(p) + ": expected " + exact(expected) + ", got " + exact(got));
        if (!(radius >= expected)) log.add("stop point " + spec(p) + " at " + exact(expected) + " is beyond the settled radius");
        const auto path = stopped.shortest_path(p);
        const PathReport report = check_geodesic_path(arrays_, adjacency, path, 1e-6);
        for (const auto& problem : report.problems) log.add("path to stop point " + spec(p) + ": " + problem);
        for (const auto& issue : report.representation) log.add("path to stop point " + spec(p) + ": " + issue);
        if (!near_relative(report.length, expected, 1e-9, 1e-2 * diagonal_))
            log.add("path to stop point " + spec(p) + " has length " + exact(report.length) + ", expected " + exact(expected));
    }
    int inside = 0, outside = 0;
    for (int v = 0; v < mesh_->num_vertices(); ++v) {
        const double got = stopped.distance(v);
        if (all[v] < radius) {
            ++inside;
            if (!near_relative(got, all[v], 1e-12, 1e-2 * diagonal_))
                log.add("v:" + std::to_string(v) + " inside the settled radius: expected " + exact(all[v]) + ", got " + exact(got));
        } else if (all[v] > radius) {
            ++outside;
            if (got != inf) log.add("v:" + std::to_string(v) + " beyond the settled radius (full distance " + exact(all[v]) +
                                    ") reports " + exact(got) + ", not +inf");
        }
    }
    EXPECT_GT(inside, 0);
    EXPECT_GT(outside, 0) << "the stop points did not stop the propagation early";
    log.report();
}

TEST_P(Options, goal_directed_stop_points_are_exact_and_explore_less) {
    PointSampler sampler(25);
    FailureLog log(GetParam().name + ": goal-directed stop points");
    const Adjacency adjacency(arrays_);
    std::size_t plain_windows = 0, directed_windows = 0;
    for (int round = 0; round < 4; ++round) {
        const SurfacePoint source = SurfacePoint::at_vertex(sampler.vertex(arrays_));
        ExactGeodesic full(*mesh_);
        full.propagate({source});
        // One stop point of each kind, then the three together.
        const std::vector<SurfacePoint> points{SurfacePoint::at_vertex(sampler.vertex(arrays_)),
                                               sampler.edge_point(arrays_), sampler.face_point(arrays_)};
        std::vector<std::vector<SurfacePoint>> stop_sets{{points[0]}, {points[1]}, {points[2]}, points};
        for (const auto& stops : stop_sets) {
            PropagationOptions options;
            options.stop_points = stops;
            ExactGeodesic plain(*mesh_);
            plain.propagate({source}, options);
            options.goal_directed = true;
            ExactGeodesic directed(*mesh_);
            directed.propagate({source}, options);
            plain_windows += plain.stats().windows_created;
            directed_windows += directed.stats().windows_created;
            for (const auto& p : stops) {
                const double expected = full.distance(p), got = directed.distance(p);
                const std::string what = "from " + spec(source) + ", stop point " + spec(p) + " (of " +
                                         std::to_string(stops.size()) + ")";
                if (!near_relative(got, expected, 1e-12, 1e-2 * diagonal_))
                    log.add(what + ": expected " + exact(expected) + ", got " + exact(got));
                const PathReport report = check_geodesic_path(arrays_, adjacency, directed.shortest_path(p), 1e-6);
                for (const auto& problem : report.problems) log.add(what + ": path: " + problem);
                if (!near_relative(report.length, expected, 1e-9, 1e-2 * diagonal_))
                    log.add(what + ": path length " + exact(report.length) + ", expected " + exact(expected));
            }
            if (!directed.stats().stopped_early) continue;
            EXPECT_EQ(directed.settled_radius(), 0.0);
            // Nothing but the stop points (and the source, at 0) is promised: every other vertex reports +inf.
            for (int v = 0; v < mesh_->num_vertices(); v += 7) {
                const SurfacePoint at_v = SurfacePoint::at_vertex(v);
                if (at_v != source && std::find(stops.begin(), stops.end(), at_v) == stops.end() &&
                    directed.distance(v) != inf)
                    log.add("from " + spec(source) + ": v:" + std::to_string(v) + " is not a stop point but reports " +
                            exact(directed.distance(v)));
            }
        }
    }
    log.report();
    EXPECT_LT(directed_windows, plain_windows) << "goal-directed propagation explored no less";
    std::cout << GetParam().name << ": windows to reach the stop points " << plain_windows << " plain, "
              << directed_windows << " goal-directed\n";
}

TEST_P(Options, max_distance_gives_full_distances_within_and_inf_beyond) {
    PointSampler sampler(24);
    const std::vector<SurfacePoint> sources = {sampler.face_point(arrays_)};
    ExactGeodesic full(*mesh_);
    full.propagate(sources);
    const std::vector<double> all = full.vertex_distances();
    double farthest = 0.0;
    for (double d : all)
        if (d < inf) farthest = std::max(farthest, d);
    PropagationOptions options;
    options.max_distance = 0.4 * farthest;
    ExactGeodesic limited(*mesh_);
    limited.propagate(sources, options);
    FailureLog log(GetParam().name + ": max distance " + exact(options.max_distance));
    const double margin = 1e-12 * farthest;
    int inside = 0, outside = 0;
    for (int v = 0; v < mesh_->num_vertices(); ++v) {
        const double got = limited.distance(v);
        if (all[v] <= options.max_distance - margin) {
            ++inside;
            if (!near_relative(got, all[v], 1e-12, 1e-2 * diagonal_))
                log.add("v:" + std::to_string(v) + " within: expected " + exact(all[v]) + ", got " + exact(got));
        } else if (all[v] > options.max_distance + margin) {
            ++outside;
            if (got != inf) log.add("v:" + std::to_string(v) + " beyond (full " + exact(all[v]) + ") reports " + exact(got));
            if (!limited.shortest_path(SurfacePoint::at_vertex(v)).empty())
                log.add("v:" + std::to_string(v) + " beyond the maximum distance has a path");
        }
    }
    for (int i = 0; i < 40; ++i) {
        const SurfacePoint p = i % 2 ? sampler.face_point(arrays_) : sampler.edge_point(arrays_);
        const double expected = full.distance(p), got = limited.distance(p);
        if (expected <= options.max_distance - margin ? !near_relative(got, expected, 1e-12, 1e-2 * diagonal_)
                                                      : (expected > options.max_distance + margin && got != inf))
            log.add(spec(p) + ": full " + exact(expected) + ", limited " + exact(got));
    }
    EXPECT_GT(inside, 0);
    EXPECT_GT(outside, 0);
    log.report();
}

INSTANTIATE_TEST_SUITE_P(
    ExactGeodesicOptions, Options,
    testing::Values(MeshCase{"perturbed_sphere", [] { return perturbed_sphere(10, 0.15, 4); }},
                    MeshCase{"torus", [] { return torus(1.0, 0.35, 48, 16); }},
                    MeshCase{"irregular_cube", [] { return cube(7, 1.0, true, 5); }},
                    MeshCase{"flat_s_shape", [] { return flat_cell_polygon(s_shape_cells(), 4, 0.2, 6); }}),
    mesh_case_name);

TEST(ExactGeodesicOptions, several_sources_on_a_cube_match_the_nearest_unfolding) {
    const TriangleMesh arrays = cube(6, 1.0, true, 8);
    const geodesic::Mesh mesh = arrays.to_mesh();
    PointSampler sampler(25);
    const std::vector<SurfacePoint> sources = {SurfacePoint::at_vertex(sampler.vertex(arrays)), sampler.edge_point(arrays),
                                               sampler.face_point(arrays)};
    ExactGeodesic propagation(mesh);
    propagation.propagate(sources);
    std::vector<Eigen::Vector3d> s;
    for (const auto& p : sources) s.push_back(point_position(arrays, p));
    const Eigen::Vector3d size(1.0, 1.0, 1.0);
    OracleSweep options;
    options.floor = 1e-2 * size.norm();
    sweep_against_oracle(
        arrays, mesh, propagation, sources,
        [&](const Eigen::Vector3d& x) {
            double best = inf;
            for (const auto& si : s) best = std::min(best, box_surface_distance(size, si, x));
            return best;
        },
        options, "cube, three sources");
}

}  // namespace
}  // namespace geotri::test

// PropagationOptions::keep_windows = false frees windows as the wavefront passes. The vertex distances must be those
// of a propagation that keeps them, to the bit; distances at other points and shortest paths, which then come from a
// propagation to the point asked about, must agree with the kept windows' to rounding, and paths must still be as
// long as the distance. The meshes are large enough for windows to be freed several times over.

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

PropagationOptions freeing(PropagationOptions options = {}) {
    options.keep_windows = false;
    return options;
}

class KeepWindows : public GeneratedMeshTest {
protected:
    // Every vertex distance equal to the bit, and the same windows made but those that freeing does not make, which
    // keeping windows prunes: they came to an edge that the wavefront had passed.
    void expect_same_vertex_distances(const ExactGeodesic& kept, const ExactGeodesic& freed, const std::string& what) {
        FailureLog log(GetParam().name + ", " + what);
        for (int v = 0; v < mesh_->num_vertices(); ++v)
            if (!(kept.distance(v) == freed.distance(v)))
                log.add("v:" + std::to_string(v) + ": kept " + exact(kept.distance(v)) + ", freed " +
                        exact(freed.distance(v)));
        log.report();
        const auto& k = kept.stats();
        const auto& f = freed.stats();
        EXPECT_EQ(k.windows_created + k.windows_not_made, f.windows_created + f.windows_not_made) << what;
        EXPECT_EQ(k.windows_pruned + k.windows_not_made, f.windows_pruned + f.windows_not_made) << what;
        EXPECT_EQ(k.windows_propagated, f.windows_propagated) << what;
    }
};

TEST_P(KeepWindows, freeing_windows_changes_no_vertex_distance_and_holds_less_memory) {
    PointSampler sampler(31);
    const std::vector<std::vector<SurfacePoint>> source_sets = {
        {SurfacePoint::at_vertex(sampler.vertex(arrays_))},
        {SurfacePoint::at_vertex(sampler.vertex(arrays_)), sampler.edge_point(arrays_), sampler.face_point(arrays_)}};
    ExactGeodesic kept(*mesh_), freed(*mesh_);
    for (const auto& sources : source_sets) {
        const std::string what = std::to_string(sources.size()) + " source(s)";
        kept.propagate(sources);
        freed.propagate(sources, freeing());
        expect_same_vertex_distances(kept, freed, what);
        EXPECT_EQ(kept.stats().windows_not_made, 0u) << what;
        EXPECT_GT(freed.stats().windows_freed, 0u) << what;
        EXPECT_LT(freed.stats().window_bytes, kept.stats().window_bytes)
            << what << ": " << kept.stats().windows_created << " windows";
    }
}

TEST_P(KeepWindows, point_distances_and_paths_without_windows_agree_with_the_kept_windows) {
    PointSampler sampler(32);
    const std::vector<SurfacePoint> sources = {sampler.face_point(arrays_)};
    ExactGeodesic kept(*mesh_), freed(*mesh_);
    kept.propagate(sources);
    freed.propagate(sources, freeing());
    const Adjacency adjacency(arrays_);
    FailureLog log(GetParam().name + ": queries without windows");
    for (int i = 0; i < 12; ++i) {
        const SurfacePoint p = i % 3 == 0   ? SurfacePoint::at_vertex(sampler.vertex(arrays_))
                               : i % 3 == 1 ? sampler.edge_point(arrays_)
                                            : sampler.face_point(arrays_);
        const double expected = kept.distance(p), got = freed.distance(p);
        if (!near_relative(got, expected, 1e-13, 1e-3 * diagonal_))
            log.add(spec(p) + ": kept " + exact(expected) + ", freed " + exact(got));
        const std::vector<SurfacePoint> path = freed.shortest_path(p);
        if (path.size() < 2 || path.front() != mesh_->canonical(sources[0]) || path.back() != mesh_->canonical(p)) {
            log.add(spec(p) + ": the path does not run from the source to the point");
            continue;
        }
        // Found leg by leg when p is a vertex: the legs must meet as a geodesic does, bending only at saddles.
        const PathReport report = check_geodesic_path(arrays_, adjacency, path, 1e-6);
        for (const auto& problem : report.problems) log.add(spec(p) + ": path: " + problem);
        if (!near_relative(report.length, got, 1e-12, 1e-3 * diagonal_))
            log.add(spec(p) + ": path length " + exact(report.length) + ", distance " + exact(got));
    }
    log.report();
}

TEST_P(KeepWindows, one_object_alternating_between_keeping_and_freeing_gives_fresh_results) {
    PointSampler sampler(34);
    const std::vector<SurfacePoint> sources = {SurfacePoint::at_vertex(sampler.vertex(arrays_)),
                                               sampler.edge_point(arrays_)};
    ExactGeodesic fresh_kept(*mesh_), fresh_freed(*mesh_), reused(*mesh_);
    fresh_kept.propagate(sources);
    fresh_freed.propagate(sources, freeing());
    for (const bool keep : {false, true, false, true, false}) {
        const std::string what = keep ? "kept after freeing" : "freed after keeping";
        reused.propagate(sources, keep ? PropagationOptions{} : freeing());
        const ExactGeodesic& fresh = keep ? fresh_kept : fresh_freed;
        expect_same_vertex_distances(fresh, reused, what);
        // The storage that held every window is let go, or the freeing would wait for it to fill.
        if (!keep) {
            EXPECT_EQ(reused.stats().window_bytes, fresh_freed.stats().window_bytes) << what;
        }
    }
}

TEST_P(KeepWindows, stop_points_and_max_distance_are_kept_without_windows) {
    PointSampler sampler(33);
    const std::vector<SurfacePoint> sources = {SurfacePoint::at_vertex(sampler.vertex(arrays_))};
    ExactGeodesic full(*mesh_);
    full.propagate(sources);
    const std::vector<double> all = full.vertex_distances();
    const double farthest = *std::max_element(all.begin(), all.end());
    // A stop point about a third of the way out, so that part of the mesh lies beyond the settled region.
    int third = 0;
    for (int v = 0; v < mesh_->num_vertices(); ++v)
        if (std::abs(all[v] - farthest / 3) < std::abs(all[third] - farthest / 3)) third = v;

    PropagationOptions limit;
    limit.max_distance = 0.5 * farthest;
    PropagationOptions stop;
    stop.stop_points = {SurfacePoint::at_vertex(third)};
    for (const auto& [what, options] : {std::pair{"max distance", limit}, std::pair{"stop points", stop}}) {
        ExactGeodesic kept(*mesh_), freed(*mesh_);
        kept.propagate(sources, options);
        freed.propagate(sources, freeing(options));
        expect_same_vertex_distances(kept, freed, what);
        EXPECT_EQ(kept.settled_radius(), freed.settled_radius()) << what;
        FailureLog log(GetParam().name + ", " + what + ": queries without windows");
        std::vector<SurfacePoint> points = options.stop_points;
        for (int i = 0; i < 8; ++i) points.push_back(sampler.face_point(arrays_));
        int beyond = 0;
        for (const SurfacePoint& p : points) {
            const double expected = kept.distance(p), got = freed.distance(p);
            if (!near_relative(got, expected, 1e-13, 1e-3 * diagonal_))
                log.add(spec(p) + ": kept " + exact(expected) + ", freed " + exact(got));
            if (expected == inf) ++beyond;
            if (freed.shortest_path(p).empty() != (expected == inf))
                log.add(spec(p) + ": a path " + (expected == inf ? "beyond the settled region" : "missing"));
        }
        EXPECT_GT(beyond, 0) << what << ": no point beyond the settled region was asked about";
        log.report();
    }
}

// Large enough that windows are freed several times over (from 65536 windows on), small enough for a quick test.
INSTANTIATE_TEST_SUITE_P(ExactGeodesic, KeepWindows,
                         testing::Values(MeshCase{"sphere", [] { return geodesic_sphere(30); }},
                                         MeshCase{"perturbed_sphere", [] { return perturbed_sphere(30, 0.008, 2); }},
                                         MeshCase{"torus", [] { return torus(1.0, 0.4, 160, 80); }},
                                         // Paths bend at its reflex corners: paths found again leg by leg.
                                         MeshCase{"flat_s_shape",
                                                  [] { return flat_cell_polygon(s_shape_cells(), 32, 0.2, 6); }}),
                         mesh_case_name);

}  // namespace
}  // namespace geotri::test

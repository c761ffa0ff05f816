#pragma once
// Helpers shared by the libgeodesic tests: a failure log that reports the first few cases of a sweep precisely,
// and one sweep that compares a propagation with an oracle at every vertex and at sampled surface points.

#include "oracles.h"

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geodesic/mesh.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace geotri::test {

inline std::string exact(double x) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", x);
    return buffer;
}

inline std::string spec(const geodesic::SurfacePoint& p) { return geodesic::to_spec(p); }

/// Collects the failures of a sweep; report() adds one gtest failure with the count and the first cases.
class FailureLog {
public:
    explicit FailureLog(std::string what, std::size_t shown = 12) : what_(std::move(what)), shown_(shown) {}
    void add(const std::string& message) {
        if (messages_.size() < shown_) messages_.push_back(message);
        ++count_;
    }
    std::size_t count() const { return count_; }
    void report() const {
        if (count_ == 0) return;
        std::ostringstream out;
        out << what_ << ": " << count_ << " failure(s)";
        for (const auto& m : messages_) out << "\n  " << m;
        if (count_ > messages_.size()) out << "\n  ...";
        ADD_FAILURE() << out.str();
    }

private:
    std::string what_;
    std::size_t shown_;
    std::vector<std::string> messages_;
    std::size_t count_ = 0;
};

/// Compares distance(v) at every vertex, distance(p) at sampled face and edge points, and the shortest paths to a
/// subset of them, with `oracle(x)` (the exact distance of the 3D point x of the surface), to `relative` with
/// `floor` as the smallest scale (see near_relative). Paths must be valid geodesic polylines (to 1e-6 rad) that
/// start at a source and end at the target, whose length matches the oracle to `relative` too.
/// `accept(x)` restricts the comparison to points where the oracle is known to hold.
struct OracleSweep {
    double relative = 1e-12;
    double floor = 0.0;
    int sampled_points = 30;
    int path_stride = 5;  ///< a path to every path_stride-th vertex
    unsigned seed = 7;
    std::function<bool(const Eigen::Vector3d&)> accept = [](const Eigen::Vector3d&) { return true; };
};

inline void sweep_against_oracle(const TriangleMesh& arrays, const geodesic::Mesh& mesh,
                                 const geodesic::ExactGeodesic& propagation, const std::vector<geodesic::SurfacePoint>& sources,
                                 const std::function<double(const Eigen::Vector3d&)>& oracle, const OracleSweep& options,
                                 const std::string& case_name) {
    const Adjacency adjacency(arrays);
    const double diagonal = bounding_diagonal(arrays);
    FailureLog distances(case_name + ": distances differ from the oracle");
    FailureLog paths(case_name + ": shortest paths");
    FailureLog representation(case_name + ": vertex passages given as edge points");
    int compared = 0;

    std::vector<geodesic::SurfacePoint> targets;
    for (int v = 0; v < mesh.num_vertices(); ++v) targets.push_back(geodesic::SurfacePoint::at_vertex(v));
    PointSampler sampler(options.seed);
    for (int i = 0; i < options.sampled_points; ++i) {
        targets.push_back(sampler.face_point(arrays));
        targets.push_back(sampler.edge_point(arrays));
    }
    for (std::size_t i = 0; i < targets.size(); ++i) {
        const geodesic::SurfacePoint& target = targets[i];
        const Eigen::Vector3d x = point_position(arrays, target);
        if (!options.accept(x)) continue;
        ++compared;
        const double expected = oracle(x);
        const double got = target.kind == geodesic::PointKind::vertex ? propagation.distance(target.vertex)
                                                                      : propagation.distance(target);
        if (!near_relative(got, expected, options.relative, options.floor))
            distances.add("target " + spec(target) + " at (" + exact(x.x()) + ", " + exact(x.y()) + ", " +
                          exact(x.z()) + "): expected " + exact(expected) + ", got " + exact(got) + " (rel. error " +
                          exact(std::abs(got - expected) / std::max(expected, options.floor)) + ")");
        const bool want_path = target.kind != geodesic::PointKind::vertex ||
                               (options.path_stride > 0 && target.vertex % options.path_stride == 0);
        if (!want_path || std::isinf(expected)) continue;
        std::vector<geodesic::SurfacePoint> path;
        try {
            path = propagation.shortest_path(target);
        } catch (const std::exception& error) {
            paths.add("target " + spec(target) + " at distance " + exact(expected) + ": shortest_path() threw: " +
                      error.what());
            continue;
        }
        if (path.empty()) {
            paths.add("target " + spec(target) + ": empty path");
            continue;
        }
        const PathReport report = check_geodesic_path(arrays, adjacency, path, 1e-6);
        for (const auto& problem : report.problems) paths.add("target " + spec(target) + ": " + problem);
        for (const auto& issue : report.representation) representation.add("target " + spec(target) + ": " + issue);
        if (!near_relative(report.length, expected, options.relative, options.floor))
            paths.add("target " + spec(target) + ": path length " + exact(report.length) + ", expected " +
                      exact(expected) + " (" + std::to_string(path.size()) + " points)");
        const double library_length = geodesic::path_length(mesh, path);
        if (!near_relative(library_length, expected, options.relative, options.floor))
            paths.add("target " + spec(target) + ": path_length() " + exact(library_length) + ", expected " +
                      exact(expected));
        if ((point_position(arrays, path.back()) - x).norm() > 1e-12 * diagonal)
            paths.add("target " + spec(target) + ": the path ends at " + spec(path.back()));
        bool starts_at_source = false;
        for (const auto& s : sources)
            starts_at_source = starts_at_source ||
                               (point_position(arrays, path.front()) - point_position(arrays, s)).norm() <= 1e-12 * diagonal;
        if (!starts_at_source) paths.add("target " + spec(target) + ": the path starts at " + spec(path.front()) +
                                         ", not at a source");
    }
    EXPECT_GT(compared, 0) << case_name << ": no target was compared";
    distances.report();
    paths.report();
    representation.report();
}

/// A generated mesh for parameterised tests, named in the test's name.
struct MeshCase {
    std::string name;
    std::function<TriangleMesh()> make;
};

inline void PrintTo(const MeshCase& c, std::ostream* out) { *out << c.name; }

inline std::string mesh_case_name(const testing::TestParamInfo<MeshCase>& info) { return info.param.name; }

/// A test over MeshCases: the mesh as arrays and as a geodesic::Mesh, and its bounding diagonal.
class GeneratedMeshTest : public testing::TestWithParam<MeshCase> {
protected:
    void SetUp() override {
        arrays_ = GetParam().make();
        mesh_ = std::make_unique<geodesic::Mesh>(arrays_.to_mesh());
        diagonal_ = bounding_diagonal(arrays_);
    }

    TriangleMesh arrays_;
    std::unique_ptr<geodesic::Mesh> mesh_;
    double diagonal_ = 0.0;
};

}  // namespace geotri::test

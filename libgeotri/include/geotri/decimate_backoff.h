#pragma once
// Backing off from a decimation that the topology stopped above its target (geotri-decimate): where every collapse
// left would change the topology, the coarse edges are the few that the handles need, and their geodesics wind
// between the handles, tangled beyond what untangling mends in reasonable time. Such a coarse mesh is traced, and
// decimated again to twice as many faces while too many of its geodesics tangle.

#include <geotri/decimate.h>
#include <geotri/fine_mesh.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

namespace geotri {

struct BackoffOptions {
    /// Back off while the traced G has more violations of conditions 2 and 3 (geodesics that cross, or leave their
    /// vertex out of order) than this many per coarse edge. stress/cheese.off (genus 133), stopped at 1174 faces for
    /// a target of 320, has 0.65 and took minutes to untangle; at 2348 faces 0.10, untangled in 8 s. Every other
    /// shared mesh reaches 320 faces (with at most 0.12 there); stopped by the topology (a target of 4 faces), they
    /// have 0-0.22 but femur_cgal, skull_thing74168, knot1, boxpart and 42400-IDGH (0.42-0.90).
    double max_tangled_per_edge = 1.0 / 3.0;
    int max_rounds = 4;  ///< at most this many decimations after the first
    int threads = 0;     ///< for tracing; 0: as many as OpenMP likes (the result is the same for any count)
    /// Called before each level is traced, with its face count, from one thread.
    std::function<void(std::size_t faces)> tracing;
};

/// A coarse mesh that was traced to decide whether to back off from it.
struct BackoffLevel {
    std::size_t faces = 0;
    std::size_t edges = 0;
    int tangled = 0;  ///< violations of conditions 2 and 3 of the traced G
};

struct BackoffResult {
    DecimateResult decimation;         ///< the one to keep
    std::vector<BackoffLevel> levels;  ///< each level traced, the first (coarsest) first; empty if none was
    bool backed_off() const { return levels.size() > 1; }
};

/// decimate(T, options), and where the topology stops it above its target (not with DecimateOptions::coarsest,
/// which asks for exactly that mesh), traces the coarse mesh in the decimation's class (trace() with its edge
/// paths): while its geodesics tangle more than `backoff` allows, decimates T again to twice the faces of the last
/// level (the target given as faces), at most max_rounds times and never to more faces than T has. The levels'
/// traced G are not kept: geotri-trace traces the one kept again. Deterministic, as decimate() and trace() are.
/// Throws as those do.
BackoffResult decimate_backing_off(const std::shared_ptr<const FineMesh>& fine, const DecimateOptions& options,
                                   const BackoffOptions& backoff = {});

}  // namespace geotri

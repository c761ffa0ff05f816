#pragma once
// Backing off from a decimation that the topology stopped above its target (geotri-decimate): where every collapse
// left would change the topology, the coarse edges are the few that the handles need, and their geodesics wind
// between the handles, tangled beyond what untangling mends in reasonable time. Such a coarse mesh is traced, and
// each component of it whose geodesics tangle too much is decimated again to twice as many faces.

#include <geotri/decimate.h>
#include <geotri/fine_mesh.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace geotri {

struct BackoffOptions {
    /// Back off from a component while its geodesics have more violations of conditions 2 and 3 (geodesics that
    /// cross, or leave their vertex out of order) than this many per coarse edge on it. On a surface of high genus,
    /// a coarse mesh that the topology stopped far above its target can have well over 0.5 and take minutes to
    /// untangle; at twice as many faces it typically has 0.1-0.2, as most coarse meshes do, and untangles quickly.
    double max_tangled_per_edge = 1.0 / 3.0;
    int max_rounds = 4;  ///< at most this many decimations after the first
    int threads = 0;     ///< for tracing; 0: as many as OpenMP likes (the result is the same for any count)
    /// Called with a line that says what comes next (tracing a level, decimating again), from one thread.
    std::function<void(const std::string& stage)> stage;
};

/// A coarse mesh that was traced to decide whether to back off from it.
struct BackoffLevel {
    std::size_t faces = 0;
    std::size_t edges = 0;
    int tangled = 0;  ///< violations of conditions 2 and 3 of the traced G, all components
};

struct BackoffResult {
    /// The one to keep. After backing off, its target_faces is still the target asked for (not reached), and its
    /// components' target_faces are what each aimed at last.
    DecimateResult decimation;
    std::vector<BackoffLevel> levels;  ///< each level traced, the first (coarsest) first; empty if none was
    bool backed_off = false;           ///< T was decimated again to more faces
};

/// decimate(T, options), and where the topology stops it above its target (not with DecimateOptions::coarsest,
/// which asks for exactly that mesh), traces the coarse mesh in the decimation's class (trace() with its edge
/// paths). Each component of T that the topology stopped above its share, and whose geodesics tangle more than
/// `backoff` allows, is decimated again to twice its faces (DecimateOptions::component_targets; never to as many
/// faces as it has), the others to their shares as before, at most max_rounds times. Where tracing a level fails
/// (trace() throws), that level is kept as it is. Where the progress callback stops a decimation, the last
/// complete level is kept, with `aborted` set. The levels' traced G are not kept: geotri-trace traces the one
/// kept again. Deterministic, as decimate() and trace() are. Throws as decimate() does.
BackoffResult decimate_backing_off(const std::shared_ptr<const FineMesh>& fine, const DecimateOptions& options,
                                   const BackoffOptions& backoff = {});

}  // namespace geotri

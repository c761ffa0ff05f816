#pragma once
// The one-call entry point: a closed triangle mesh in, a valid geodesic triangulation G out, as geotri-decimate,
// geotri-trace and geotri-flip make it.

#include <geotri/decimate.h>
#include <geotri/decimate_backoff.h>
#include <geotri/fine_mesh.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/trace.h>
#include <geotri/untangle_and_flip.h>
#include <geotri/validate.h>

#include <functional>
#include <memory>
#include <string>

namespace geotri {

struct BuildOptions {
    /// What to decimate T to: exactly one of target_faces, target_vertices, ratio and coarsest. The edge paths are
    /// always kept (G is traced in the decimation's classes).
    DecimateOptions decimation;
    /// Where the topology stops decimation above its target with geodesics that tangle, decimate again to more
    /// faces (decimate_backing_off()).
    bool back_off = true;
    UntangleAndFlipOptions flips;  ///< untangling, then geodesic Delaunay flips; its `threads` are set from below
    /// For tracing, untangling and flips; 0: as many as OpenMP likes. The result is the same for any count.
    int threads = 0;
    /// Called with a line that says what comes next, from one thread.
    std::function<void(const std::string& stage)> stage;
};

struct BuildResult {
    GeodesicTriangulation g;
    ValidationReport report;  ///< validate(g), with the overlay
    BackoffResult decimation;
    TraceResult tracing;
    UntangleAndFlipResult flips;
};

/// G of T in one call, with the same result as geotri-decimate --paths, geotri-trace --paths and geotri-flip run
/// one after another on T's file (the same .gtri, byte for byte): decimate T (backing off where the topology stops
/// it with tangled geodesics), trace every coarse edge as an exact geodesic in the decimation's class, untangle,
/// then flip towards geodesic Delaunay. G may still be invalid where untangling gives up: `report` says so.
/// Deterministic, for any thread count. Throws InvalidInput for options out of range, and as decimate(), trace()
/// and untangle_and_flip() do.
BuildResult build_geodesic_triangulation(const std::shared_ptr<const FineMesh>& fine, const BuildOptions& options);

}  // namespace geotri

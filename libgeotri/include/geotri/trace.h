#pragma once
// Tracing: each coarse vertex located on T, then each coarse edge made the exact shortest geodesic between its
// ends (DESIGN.md §3, §4).

#include <geotri/edge_paths_io.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/mesh_io.h>
#include <geotri/validate.h>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

namespace geotri {

struct TraceOptions {
    int threads = 0;  ///< 0: as many as OpenMP likes; the result is the same for any count
    /// Called with (done, total) propagations; may be called from any thread but never concurrently.
    std::function<void(int, int)> progress;
    /// The edge paths of the decimation that made the coarse mesh (geotri-decimate --paths), or null. With them,
    /// every edge is also straightened within its class: into the geodesic homotopic to its path on T with the
    /// coarse vertices taken out (geodesic::straighten_path), which runs the way round that the decimation meant.
    /// When the shortest geodesics do not make G valid, G keeps whichever set does better: the valid one, or the
    /// one with fewer violations (the shortest on a tie).
    const EdgePaths* edge_paths = nullptr;
};

struct TraceResult {
    int propagations = 0;
    double largest_location_move = 0.0;  ///< how far a coarse vertex had to move to land on T
    int largest_move_vertex = -1;        ///< the coarse vertex that moved farthest (-1 when none moved)
    int moved_vertices = 0;              ///< coarse vertices that did not coincide exactly with a vertex of T
    double longest_propagation = 0.0;    ///< the longest edge: the farthest that one propagation had to reach
    std::size_t windows_created = 0;     ///< summed over every propagation (libgeodesic's PropagationStats)
    std::size_t polyline_points = 0;     ///< summed over every edge polyline
    /// With edge paths: edges whose geodesic in the decimation's class is another one than the shortest, edges
    /// whose class runs through another coarse vertex (they keep the shortest), and whether G holds the class
    /// geodesics.
    int class_geodesics_differing = 0;
    int class_geodesics_blocked = 0;
    bool class_geodesics_kept = false;
    /// The full validation of G as returned, when choosing between the two sets made one (callers need not
    /// validate it again).
    std::optional<ValidationReport> report;
    double seconds = 0.0;
};

/// Locates every coarse vertex on T (exact coincidence with a fine vertex, else the closest point of T) and
/// traces every edge: each edge's polyline becomes the exact shortest geodesic between the locations of its ends.
/// Each edge is traced from one of its ends, goal-directed; the result is bit-identical for any thread count.
/// Throws InvalidInput when a coarse component does not lie on one fine component, when two coarse components lie
/// on the same fine component, when a fine component holds no coarse vertex, when a coarse component's genus is not
/// that of its fine component (no G with that connectivity can be valid: the local operations keep it), or when
/// two coarse vertices land on the same point of T; NumericalError if
/// libgeodesic finds no path between two ends on the same component; IOError("NAME: problem") when the edge paths
/// do not fit T or the coarse mesh. Progress goes through options.progress only.
TraceResult trace(GeodesicTriangulation& g, const TraceOptions& options = {});

}  // namespace geotri

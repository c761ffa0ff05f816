#pragma once
// Geodesic Delaunay flips: edge flips that improve the shape of a valid G and keep it valid.

#include <geotri/flip.h>
#include <geotri/geodesic_triangulation.h>

#include <array>
#include <functional>
#include <string>

namespace geotri {

/// When an edge is flipped.
enum class FlipCriterion {
    angle,   ///< when the flip strictly raises the minimum corner angle of the two triangles
    length,  ///< intrinsic Delaunay on geodesic lengths: when the opposite angles by the law of cosines sum to > π
};

/// "angle" or "length".
const char* to_string(FlipCriterion criterion);

struct FlipToDelaunayOptions {
    FlipCriterion criterion = FlipCriterion::angle;
    /// Strict improvement: a flip must raise the minimum corner angle by more than this (criterion angle), or the
    /// opposite angles must sum to more than π plus this (criterion length). Radians.
    double margin = 1e-9;
    int max_passes = 100;  ///< sweeps over the edges; it stops after a sweep without a flip
    /// When the shortest c-d geodesic leaves the two patches, try the shortest path inside them.
    bool region_fallback = true;
    /// For the evaluations of the edges, run in parallel; 0: as many as OpenMP likes. The result is the same for
    /// any count.
    int threads = 0;
    /// Called after each sweep with a line saying where it is.
    std::function<void(const std::string&)> progress;
};

/// Minimum, mean and maximum coarse corner angle, in degrees, over every corner of every face.
struct CornerAngleStats {
    double min_deg = 0.0, mean_deg = 0.0, max_deg = 0.0;
    int corners = 0;
};

/// Every corner of G (corner_angles() of every face). Throws as corner_angle().
CornerAngleStats corner_angle_stats(const GeodesicTriangulation& g);

struct FlipToDelaunayResult {
    int flips = 0;
    int plans = 0;          ///< flips computed (one propagation each)
    int region_flips = 0;   ///< of the flips, those whose new edge is the shortest path inside the patches
    int passes = 0;
    /// Flips that the criterion asked for but plan_flip() refused, by FlipRefusal (index = enum value), with the
    /// shortest geodesic and then with the shortest path inside the patches (the reason counted is the first).
    std::array<int, 5> refused{};
    bool skipped = false;           ///< G was not valid, so nothing was flipped
    bool pass_cap_reached = false;  ///< it stopped at max_passes with flips still happening
    bool reverted = false;          ///< the final check found G invalid after the flips: the G before is kept
    bool valid_after = false;
    CornerAngleStats angles_before, angles_after;
    double seconds = 0.0;
};

/// Flips the edges of a valid G by the criterion, in sweeps, each flip planned with plan_flip()'s local checks,
/// until a sweep flips nothing or max_passes is reached. It terminates because each flip strictly improves a finite
/// order (criterion angle: the sorted vector of all corner angles), and it never makes a valid G invalid: a final
/// validate() with the overlay, and if that fails, G goes back to what it was. An invalid G is left as it is
/// (skipped; untangle() first). Edges are evaluated in parallel but flipped in index order, so the result is the
/// same for any thread count. Preconditions: every edge traced. Throws InvalidInput for a malformed G.
FlipToDelaunayResult flip_to_delaunay(GeodesicTriangulation& g, const FlipToDelaunayOptions& options = {});

}  // namespace geotri

#pragma once
// Refinement of a valid G: longest-edge bisection down to a geodesic edge length or a face count, then
// Delaunay refinement to a minimum corner angle by inserting geodesic circumcentres, moving vertices within their
// stars where that mends a corner. Every step is a split or a move whose local checks keep G valid or refuse it
// (split.h, relocate.h), and flips towards geodesic Delaunay follow each one.

#include <geotri/flip_to_delaunay.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/validate.h>

#include <functional>
#include <string>
#include <vector>

namespace geotri {

struct RefineOptions {
    double max_length = 0.0;  ///< bisect until no edge is longer than this (0: no bound)
    int target_faces = 0;     ///< bisect until G has at least this many faces (0: no target)
    /// Then raise every corner to at least this many degrees (0: none; at most 35). Corners at points of T whose cone
    /// angle is below three times this are exempt: a vertex there must have a smaller corner. Corners above 180
    /// degrees (patches that wrap around a bump of T) are cut in two where no new corner is then below the angle.
    double min_angle_deg = 0.0;
    /// Refine no triangle whose shortest edge is shorter than this, nor make a shorter edge, so that refinement does
    /// not chase the needles of T (0: a tenth of T's mean edge, or a twentieth where that gives up). Near a shorter
    /// edge of the G given (a small feature of T), the bound grows from that edge's length with the distance to it.
    double min_edge_length = 0.0;
    /// At most this many new vertices while raising the angle (0: four times G's faces plus 100, doubled once when
    /// it is reached with fewer than 5% of the faces below the angle). A cap given here is never passed.
    int max_new_vertices = 0;
    /// Never take out or move a vertex of the G given: refinement only adds vertices, and moves those it added.
    bool keep_vertices = false;
    bool flip = true;  ///< flip towards geodesic Delaunay (angle criterion) after every change
    int threads = 0;   ///< 0: as many as OpenMP likes. The result is the same for any count
    /// Called now and then with a line saying where refinement is; never from two threads at once.
    std::function<void(const std::string&)> progress;
};

/// One refinement of the G given. Where raising the minimum angle gives up on some corners below the vertex cap,
/// refine() refines the G given again in other ways, in a fixed order, and returns the best result (see refine()).
struct RefineAttempt {
    /// The shortest edge it refined and made (RefineOptions::min_edge_length; 0: the default, a tenth of T's mean).
    double min_edge_length = 0.0;
    /// Vertices of T whose cone angle differs from 2π by more than this fraction of the minimum angle counted as
    /// curved: a coarse vertex goes onto one inside a circumcircle before the circumcentre, and is never removed.
    double curved_fraction = 0.0;
    bool vertex_moves = true;     ///< it moved vertices within their stars to raise a corner
    int small_corners_left = -1;  ///< its corners left below the angle, not exempt (-1 where it stopped on `error`)
    double min_angle_deg = 0.0;   ///< its smallest corner
    bool kept = false;            ///< its result is the one refine() returns
    std::string error;            ///< where it stopped on numerical trouble: why (its result is not used)
};

struct RefineResult {
    bool valid_before = false, valid_after = false;
    std::vector<Violation> remaining;  ///< the violations left when G is invalid after (it should never be)
    int edge_splits = 0;               ///< bisections, and circumcentres that fell on an edge
    int face_splits = 0;               ///< circumcentres and vertices of T inserted inside a patch, and inside_splits
    int refused_splits = 0;            ///< splits that split_edge() or split_face() refused (G kept as it was)
    int removed_vertices = 0;          ///< vertices taken out, their stars reconnected
    int moved_vertices = 0;            ///< vertices moved within their star, to raise a corner or narrow one
    int moves_onto_saddles = 0;        ///< of those, the moves onto a saddle of T that a geodesic bent at
    int splits_at_saddles = 0;         ///< splits at vertices of T where no circumcentre or split mends a triangle
    int inside_splits = 0;             ///< face splits well inside a patch, where nothing else mends a triangle
    int flips = 0;
    int exempt_corners = 0;            ///< corners below the minimum angle at cone points that force them
    int small_corners_left = 0;        ///< other corners below the minimum angle, where refinement gave up
    int wide_corners_left = 0;         ///< with a minimum angle: corners above 180 degrees left
    bool vertex_cap_reached = false;   ///< stopped at max_new_vertices
    /// The refinements of the G given that ran, in order (one without a minimum angle); exactly one is kept, and
    /// the counts above are its own.
    std::vector<RefineAttempt> attempts;
    double longest_edge = 0.0;         ///< after
    CornerAngleStats angles_before, angles_after;
    double seconds = 0.0;              ///< all attempts together
};

/// Refines G as `options` say. Throws InvalidInput when G is not valid (refinement keeps a valid G valid; make it
/// valid first with flip_to_delaunay()) or when an option is out of range. Deterministic: the same result for any
/// RefineOptions::threads, and the same for a G in memory as for that G written and read back (G is first numbered
/// as reading numbers it: renumbered_as_read()).
///
/// With a minimum angle, where an attempt gives up on some corners below the vertex cap, the G given is refined
/// again: with nearly every vertex of T curved, then (at most 4 corners left) without vertex moves; the same with a
/// twentieth of T's mean edge (where no shortest edge is given); and, at most 4 corners left, with the vertices of T
/// curved by more than a sixth of the angle. Each runs only while the best result so far gives up; the best is
/// the valid one with the fewest corners left below the angle, then the largest smallest corner not exempt.
RefineResult refine(GeodesicTriangulation& g, const RefineOptions& options);

}  // namespace geotri

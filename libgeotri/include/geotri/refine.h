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
    double max_length = 0.0;     ///< bisect until no edge is longer than this (0: no bound)
    int target_faces = 0;        ///< bisect until G has at least this many faces (0: no target)
    /// Then insert circumcentres until every corner angle is at least this, in degrees (0: none; at most 35).
    /// Corners at points of T whose cone angle is below three times this are exempt: a vertex of degree three or
    /// more there must have a smaller corner. Once every other corner is at least this, corners above 180 degrees
    /// (patches that wrap around a bump of T) are cut in two, where that leaves every new corner at least this; where
    /// refinement stops with corners below it (at the default vertex cap, or giving up), those above 180 degrees
    /// are cut at last where every new corner is at least the smallest of the face cut.
    /// Where refinement gives up on some triangles without reaching the vertex cap, it starts again from the G
    /// given with nearly every vertex of T that is not flat treated as curved, and returns the better result.
    double min_angle_deg = 0.0;
    /// Do not refine a triangle whose shortest edge is shorter than this (0: a tenth of the mean edge length of T,
    /// and a twentieth too where that gives up: RefineResult::finer_min_edge_tried), nor make a new edge shorter than
    /// it, so that refinement does not chase a needle of T with ever smaller triangles. Near an edge of the G given
    /// that is shorter (two input vertices close together: a small feature of T), the bound is that edge's length
    /// plus a quarter of the distance to it, so that its triangles are mended too.
    double min_edge_length = 0.0;
    bool flip = true;            ///< flip towards geodesic Delaunay (angle criterion) around every new vertex
    /// While raising the minimum angle, a vertex of the G given (not one that refinement added) at an end of the
    /// worst triangle's shortest edge may be taken out, its star reconnected (reconnect_vertex()), when every
    /// corner around there is then at least the minimum angle: vertices that decimation left close together make
    /// corners that circumcentres mend only with many small triangles. When only triangles that refinement gave up
    /// on are left below the angle, this is done once more with the vertices added so far removable too. Vertices
    /// at curved points of T (whose cone angle differs from 2π by more than a third of the minimum angle, or in a
    /// second attempt (RefineResult::second_attempt) by more than a thousandth of it) are always kept.
    bool remove_vertices = true;
    /// Before a circumcentre, the worst triangle's vertices that are not at curved points of T are tried at the
    /// centroid of their star (relocate_vertex_in_star(), then flips): the move that raises the smallest corner of
    /// the faces it changes the most is kept, when it raises it at all; where a corner above 180 degrees cannot be
    /// cut, a move that narrows it is tried too. Where neither a circumcentre nor a split mends the worst triangle,
    /// a vertex of it may move onto a saddle of T (curved as above) that one of the triangle's geodesics at that
    /// vertex bends at, when every corner that this changes (exempt or not) is then at least half the minimum
    /// angle, before the triangle is given up. With remove_vertices off, the vertices of the G given are not moved.
    bool move_vertices = true;
    /// In the end game of min_angle_deg (at most 4 faces below it, or the last pass of split_inside), where a
    /// triangle would be given up: split it at a saddle of T that one of its geodesics bends at (splitting that
    /// geodesic), or else at the curved vertex of T nearest its circumcentre (splitting the patch that holds it),
    /// with edges of any length: such splits are finitely many, one per vertex of T.
    bool split_at_saddles = true;
    /// Last, where only triangles given up on are left below min_angle_deg (after the removals above), each is tried
    /// again, and from then on a triangle that nothing else mends gets a face split at a point well inside its patch
    /// (walked from a corner along its bisector, as far as the incentre of its intrinsic layout or half as far), or
    /// else inside a neighbour's patch, whose flips may then mend it. Such points are where the new geodesics most
    /// often stay inside the patch: on a very coarse G, or where geodesics bend at saddles of T, those from an edge's
    /// midpoint or a circumcentre leave it. Such a split also cuts a corner above 180 degrees where neither a split
    /// of the opposite edge nor the circumcentre does.
    bool split_inside = true;
    /// A guard on the vertices that each phase may add (0: none for bisection; for the minimum angle, four times
    /// the faces of G, plus 100, doubled once when it is reached with fewer than 5% of the faces below the angle):
    /// where angle refinement cascades instead of converging (as it can on curved meshes at 25-30 degrees), it
    /// stops there and says so. Past the default cap, the corners above 180 degrees left are still cut (see
    /// min_angle_deg); a cap given here is never passed.
    int max_new_vertices = 0;
    /// Threads for the propagations of the flips after each split and of the reconnections that take out a vertex,
    /// or, on a T of under 20000 faces, where those are too short to share, for the attempts that refinement to a
    /// minimum angle may need (RefineResult::second_attempt, without_moves_tried): they then start together, and
    /// those found unneeded stop. 0: as many as OpenMP likes. The result is the same for any count.
    int threads = 0;
    /// Called now and then with a line saying where refinement is; never from two threads at once, but while
    /// attempts run on threads of their own (see `threads`), from theirs.
    std::function<void(const std::string&)> progress;
};

struct RefineResult {
    bool valid_before = false, valid_after = false;
    std::vector<Violation> remaining;  ///< the violations left when G is invalid after (it should never be)
    int edge_splits = 0;               ///< bisections, and circumcentres that fell on an edge
    int face_splits = 0;               ///< circumcentres and vertices of T inserted inside a patch, and inside_splits
    int refused_splits = 0;            ///< splits that split_edge() or split_face() refused (G kept as it was)
    int removed_vertices = 0;          ///< vertices taken out (RefineOptions::remove_vertices)
    int moved_vertices = 0;            ///< vertices moved within their star, to raise a corner or narrow one
    int moves_onto_saddles = 0;        ///< of those, the moves onto a saddle of T that a geodesic bent at
    int splits_at_saddles = 0;         ///< splits at vertices of T (RefineOptions::split_at_saddles)
    int inside_splits = 0;             ///< face splits well inside a patch (RefineOptions::split_inside)
    int flips = 0;
    int exempt_corners = 0;            ///< corners below the minimum angle at cone points that force them
    int small_corners_left = 0;        ///< other corners below the minimum angle, where refinement gave up
    int wide_corners_left = 0;         ///< with a minimum angle: corners above 180 degrees left
    bool vertex_cap_reached = false;   ///< stopped at max_new_vertices
    /// Refinement gave up on some triangles below the minimum angle without reaching the vertex cap, and started
    /// again from the G given with nearly every vertex of T that is not flat treated as curved (a vertex of T
    /// inside a circumcircle goes in before the circumcentre, and is never removed).
    bool second_attempt = false;
    /// The second attempt had fewer corners left (or as many and a larger smallest corner that is not exempt): its
    /// result is the one returned, with its counts.
    bool second_attempt_kept = false;
    /// Refinement with vertex moves (RefineOptions::move_vertices) gave up on a few triangles (at most 4 corners)
    /// without reaching the vertex cap, and refined the G given again without them; where that left fewer corners
    /// below the angle (or as many and a larger smallest corner that is not exempt), its result is the one
    /// returned, with its counts.
    bool without_moves_tried = false, without_moves_kept = false;
    /// Why refining again without moves stopped, where it threw NumericalError: the result with moves is returned.
    std::string without_moves_error;
    /// Why the second attempt stopped, where it threw NumericalError: the first result is returned then.
    std::string second_attempt_error;
    /// With the default min_edge_length, refinement gave up on some triangles below the minimum angle without
    /// reaching the vertex cap, on a T of under 20000 faces, and refined the G given again (all of the above) with
    /// a shortest edge of a twentieth of T's mean edge; where that left fewer corners below the angle (or as many
    /// and a larger smallest corner that is not exempt), its result is the one returned, with its counts.
    bool finer_min_edge_tried = false, finer_min_edge_kept = false;
    /// Why refining again with the shorter edge stopped, where it threw NumericalError: the first result stands.
    std::string finer_min_edge_error;
    /// After all of the above, refinement still gave up on a few triangles (at most 4 corners below the minimum
    /// angle) without reaching the vertex cap, on a T of under 20000 faces, and refined the G given again (with the
    /// shortest edge of the result that stood: a twentieth of T's mean edge where finer_min_edge_kept) counting as
    /// curved the vertices of T whose cone angle differs from 2π by more than a sixth of the minimum angle instead of
    /// a third; where that is better in the same sense, its result is returned.
    /// finer_min_edge_kept then still says whether the shorter edge had done better than the first result.
    bool finer_curved_tried = false, finer_curved_kept = false;
    /// Why refining again with more vertices curved stopped, where it threw NumericalError: what stood before stands.
    std::string finer_curved_error;
    double longest_edge = 0.0;         ///< after
    CornerAngleStats angles_before, angles_after;
    double seconds = 0.0;              ///< both attempts, where there were two
};

/// Refines G as `options` say. Throws InvalidInput when G is not valid (refinement keeps a valid G valid; make it
/// valid first with flip_to_delaunay()) or when an option is out of range. Deterministic: the same result for any
/// RefineOptions::threads, and the same for a G in memory as for that G written and read back (G is first numbered
/// as reading numbers it: renumbered_as_read()).
RefineResult refine(GeodesicTriangulation& g, const RefineOptions& options);

}  // namespace geotri

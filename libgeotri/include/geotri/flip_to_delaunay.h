#pragma once
// Flips that make G valid (untangling) and then well shaped (geodesic Delaunay), as geotri-flip does (issue 4).

#include <geotri/flip.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/propagation_pool.h>
#include <geotri/validate.h>

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace geotri {

/// When improve flips an edge.
enum class FlipCriterion {
    angle,   ///< when the flip strictly raises the minimum corner angle of the two triangles
    length,  ///< intrinsic Delaunay on geodesic lengths: when the opposite angles by the law of cosines sum to > π
};

/// "angle" or "length".
const char* to_string(FlipCriterion criterion);

struct FlipToDelaunayOptions {
    FlipCriterion criterion = FlipCriterion::angle;
    bool untangle = true;
    bool improve = true;
    /// Strict improvement: a flip must raise the minimum corner angle by more than this (criterion angle), or the
    /// opposite angles must sum to more than π plus this (criterion length). Radians.
    double margin = 1e-9;
    int max_improve_passes = 100;    ///< sweeps over every edge; improve stops after a sweep without a flip
    /// Flips, fork splits, collapses and moves: each strictly lowers the violation count, so this is only a guard.
    int max_untangle_operations = 10000;
    /// Untangling, where nothing else helps with at most 16 violations of conditions 1-3 left: 1, also try each
    /// collapse of an edge at a vertex that they name, judged after untangling what it leaves around the vertex
    /// kept; 2, then again with that untangling itself ending with such collapses where it is stuck. 1 made three
    /// more meshes valid at their coarsest (skull_thing74168, anchor_dense, boxpart: 4-17 s each) and 2 femur_cgal
    /// at 320 faces (7 s), but where they mend nothing they cost minutes (gears at its coarsest: 8 s with 0, 144 s
    /// with 1, invalid either way) unless thorough_budget bounds them. 0: neither.
    int thorough = 2;
    /// The work that those collapses may do, in windows of propagation (geodesic::ExactGeodesic::
    /// windows_created_total(), the same on any machine and for any thread count). It is checked between trials:
    /// once the trials so far have spent it, untangling stops with what it has
    /// (FlipToDelaunayResult::thorough_budget_spent), so the trial that crosses it still runs to its end (couplingdown
    /// at its coarsest: 147M). 10^8 is 21-28 s on 2 cores of our development machine, and enough for every mesh that
    /// they mend above (skull_thing74168 needs 72M, the bundled joint 31M, the others 7-13M). The collapse trials of
    /// the untangling inside one trial at level 2 may spend half of it. 0: no bound.
    std::size_t thorough_budget = 100'000'000;
    /// Where untangling is still stuck after all that (or its budget is spent), every edge that a violation names
    /// is split at the middle of its polyline, whatever that does to the count, and untangling goes on: at most
    /// this many rounds. G is then too coarse there, its geodesics winding between handles that its vertices are
    /// too few to separate (stress/cheese.off, genus 133, at 1174 faces: valid after 374 bisections, in 4 minutes).
    /// Where G is left invalid after bisections, untangling starts again from the G given with their vertices kept
    /// from collapses (FlipToDelaunayResult::untangle_kept_bisection_vertices): the rounds, the operations and the
    /// budget above then count once more. 0: never.
    int bisection_rounds = 4;
    /// Improve: when the shortest c-d geodesic leaves the two patches, try the shortest path inside them.
    bool region_fallback = true;
    /// For untangling's trials and improve's evaluations; 0: as many as OpenMP likes. The result is the same for
    /// any count.
    int threads = 0;
    /// A propagation object over g.fine().mesh for the calling thread to reuse (saves its setup, which costs as
    /// much as a short propagation); one is made per call when null, and each other thread makes its own.
    geodesic::ExactGeodesic* propagation = nullptr;
    /// Propagation objects over g.fine().mesh for the other threads of improve's evaluations to reuse across calls
    /// (improve_around() in a loop); each thread makes its own per call when null.
    PropagationPool* propagations = nullptr;
    /// Shortest geodesics found before, for improve's flips to use again (FlipOptions::paths); none when null.
    PathCache* paths = nullptr;
    /// Called after each untangle round and each improve sweep with a line saying where it is.
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
    bool valid_before = false, valid_after = false;
    std::array<int, 4> violations_before{}, violations_after{};  ///< per condition, as validate() counts them
    std::vector<Violation> remaining;  ///< the violations left when G is still invalid

    // Untangling's moves that strictly lowered the violation count, by kind (each kind where the ones before it
    // did not help): flips, fork splits (split_fork(), singly or in chains), splits of an edge where another meets
    // it at a vertex of T (split_edge_at_point()), edge collapses (collapse_edge()) and vertex moves
    // (relocate_vertex()). A single split counts as one move with the flips around its new vertex that follow it;
    // a pair of flips counts as two flips.
    int untangle_flips = 0;
    int untangle_fork_splits = 0;
    int untangle_meeting_splits = 0;
    int untangle_collapses = 0;
    int untangle_relocations = 0;
    /// Edges bisected, not judged by the count, where nothing else lowered it (at most a few rounds).
    int untangle_bisections = 0;
    /// Untangling was left invalid after bisections and started again from the G given, where its collapses (but
    /// those inside the collapses judged after untangling) do not take out the vertices that bisections add; its
    /// result had fewer violations and is the one returned.
    bool untangle_kept_bisection_vertices = false;
    int untangle_rejected = 0;   ///< moves tried that did not lower it (G kept as it was)
    int untangle_refused = 0;    ///< moves not possible there (not flippable, no geodesic, a refused split, ...)
    bool untangle_stuck = false; ///< untangling ended with violations left and no operation that lowers their count
    /// Untangling was stuck with few enough violations left to try its last resorts (FlipToDelaunayOptions::thorough
    /// adds some of them).
    bool last_resorts_tried = false;
    /// Untangling stopped because FlipToDelaunayOptions::thorough_budget was spent.
    bool thorough_budget_spent = false;
    /// The work that the collapses judged after untangling did, in windows of propagation (counted as the budget).
    std::size_t thorough_windows = 0;

    int improve_flips = 0;
    int improve_plans = 0;          ///< flips computed (one propagation each) while improving
    int improve_region_flips = 0;   ///< of improve_flips, those whose new edge is the shortest path inside the patches
    int improve_passes = 0;
    /// Flips that the criterion asked for but plan_flip() refused, by FlipRefusal (index = enum value), with the
    /// shortest geodesic and then with the shortest path inside the patches (the reason counted is the first).
    std::array<int, 5> improve_refused{};
    bool improve_skipped = false;   ///< G was not valid after untangling, so it was not improved
    bool pass_cap_reached = false;  ///< improve stopped at max_improve_passes with flips still happening
    bool improve_reverted = false;  ///< the final check found G invalid after improving: the G before it is kept

    CornerAngleStats angles_before, angles_after;
    double seconds = 0.0;
};

/// Untangles G, then improves it (as options say). Untangle: while G is invalid, flip the edges involved in
/// violations (named by validate(), or at a vertex or face it names); where no flip helps, split the forks at the
/// vertices involved (split_fork(), singly, then as a chain), collapse them into a neighbour (collapse_edge()), or
/// move them to a vertex of T nearby (relocate_vertex()); with a few violations left and nothing else helping, flip
/// two edges of one face together, or move a vertex further; an operation is kept only when it strictly lowers the
/// number of violations of conditions 1-3, or, with none left, that of condition 4; where no such operation is
/// left, the edges that violations name are bisected (bisection_rounds) and it goes on, once more from the start
/// with their vertices kept where that leaves G invalid; it stops when G is valid or nothing is left to try.
/// Trials run in parallel, and the first that helps in a fixed order is kept. Improve (only
/// on a valid G): sweeps over the edges, flipping by the criterion with plan_flip()'s local checks, until a sweep
/// makes no flip or max_improve_passes is reached; it terminates because each flip strictly improves a finite
/// order (criterion angle: the sorted vector of all corner angles), and it never makes a valid G invalid (a final
/// validate() with the overlay; if that fails, G goes back to what it was before improving). Deterministic:
/// improve evaluates edges in parallel but flips in edge index order, and untangle keeps the first helpful trial in
/// order, so the result is the same for any thread count. Preconditions: every edge traced. Throws InvalidInput for
/// a malformed G, and std::logic_error where untangling's count of a trial's violations, made from what the trial
/// changed, is not validate()'s (a broken invariant: it is checked on every trial that untangling keeps).
FlipToDelaunayResult flip_to_delaunay(GeodesicTriangulation& g, const FlipToDelaunayOptions& options = {});

/// Improve only, starting from `edges` and going on with the edges that their flips change, on a G that the caller
/// knows to be valid: no untangling and no validate(), so that it costs what the flips around `edges` cost. For
/// operations that change G locally (refinement). Adds its counts to `result`'s improve fields, and appends every
/// edge that it flips to `flipped` when given (flips keep the edge's handle), so that the caller can tell which
/// faces changed without a pass over G.
void improve_around(GeodesicTriangulation& g, const std::vector<OpenMesh::EdgeHandle>& edges,
                    const FlipToDelaunayOptions& options, FlipToDelaunayResult& result,
                    std::vector<OpenMesh::EdgeHandle>* flipped = nullptr);

}  // namespace geotri

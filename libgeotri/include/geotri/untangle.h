#pragma once
// Untangling: local operations that make an invalid G valid (DESIGN.md §1), each kept only when it strictly lowers
// the number of violations.

#include <geotri/geodesic_triangulation.h>
#include <geotri/validate.h>

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace geotri {

struct UntangleOptions {
    /// Moves that each strictly lower the violation count: a guard only, since the count bounds them.
    int max_operations = 10000;
    /// With at most 16 violations of conditions 1-3 left and nothing else helping: 1 also tries each collapse of an
    /// edge at a vertex that they name, judged after untangling what it leaves around the vertex kept; 2 then lets
    /// that inner untangling end with such collapses too. 0: neither. They can mend a G at its coarsest that nothing
    /// else mends, and can cost minutes where they mend nothing, unless thorough_budget bounds them.
    int thorough = 2;
    /// The work that the last resorts (pairs of flips, moves of a vertex further away, and those collapses) may do
    /// together, in windows of propagation (geodesic::ExactGeodesic::windows_created_total(), the same on any
    /// machine and for any thread count), checked between trials: once spent, untangling goes on without them
    /// (UntangleResult::thorough_budget_spent). 0: no bound.
    std::size_t thorough_budget = 100'000'000;
    /// Where untangling is still stuck, every edge that a violation names is bisected at the middle of its
    /// polyline, whatever that does to the count, and untangling goes on: at most this many rounds. Where G is
    /// left invalid after bisections, untangling starts again from the G given with their vertices kept from
    /// collapses, and the result with fewer violations is kept. 0: never.
    int bisection_rounds = 4;
    /// For the trials, run in parallel; 0: as many as OpenMP likes. The result is the same for any count.
    int threads = 0;
    /// Called after each round with a line saying where it is.
    std::function<void(const std::string&)> progress;
};

struct UntangleResult {
    bool valid_before = false, valid_after = false;
    std::array<int, 4> violations_before{}, violations_after{};  ///< per condition, as validate() counts them
    std::vector<Violation> remaining;  ///< the violations left when G is still invalid

    // The moves kept, by kind (each kind tried where the ones before it did not help): flips, fork splits
    // (split_fork(), singly or in chains), splits of an edge where another meets it at a vertex of T
    // (split_edge_at_point()), edge collapses (collapse_edge()) and vertex moves (relocate_vertex()). A split
    // counts as one move with the flips around its new vertex that follow it; a pair of flips counts as two flips.
    int flips = 0;
    int fork_splits = 0;
    int meeting_splits = 0;
    int collapses = 0;
    int relocations = 0;
    int bisections = 0;  ///< edges bisected, not judged by the count, where nothing else lowered it
    /// The second untangling, with the bisections' vertices kept, did better and is the one returned.
    bool kept_bisection_vertices = false;
    int rejected = 0;   ///< moves tried that did not lower the count (G kept as it was)
    int refused = 0;    ///< moves not possible there (not flippable, no geodesic, a refused split, ...)
    bool stuck = false; ///< it ended with violations left and no move that lowers their count
    bool last_resorts_tried = false;     ///< few enough violations were left to try the last resorts
    bool thorough_budget_spent = false;  ///< the last resorts stopped at UntangleOptions::thorough_budget
    std::size_t thorough_windows = 0;    ///< the work of the last resorts, as the budget counts
    double seconds = 0.0;
};

/// Makes G valid where it can. While G is invalid: flips the edges that violations name (or at a vertex or face
/// they name); where no flip helps, splits the forks at the vertices involved (singly, then as a chain), splits an
/// edge where another meets it at a vertex of T, collapses a vertex into a neighbour, or moves it to a vertex of T
/// nearby; with few violations left, flips two edges of one face together, moves a vertex further, or (thorough)
/// collapses judged after untangling. A move is kept only when it strictly lowers the number of violations of
/// conditions 1-3 or, with none left, of condition 4. Where nothing helps, the edges that violations name are
/// bisected (bisection_rounds). Stops when G is valid or nothing is left to try; a valid G is left as it is.
/// Trials run in parallel and the first that helps, in a fixed order, is kept: the result is the same for any
/// thread count. Preconditions: every edge traced. Throws InvalidInput for a malformed G, and std::logic_error where
/// the count of a trial's violations made from what it changed is not validate()'s (a broken invariant, checked on
/// every trial kept).
UntangleResult untangle(GeodesicTriangulation& g, const UntangleOptions& options = {});

}  // namespace geotri

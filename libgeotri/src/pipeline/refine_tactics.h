#pragma once
// The ways of mending a triangle below the minimum angle that refine() has besides circumcentres and bisection, and
// its other attempts. All are on in refine(); tests turn some off to reach the cases that the others would mend first.

#include <geotri/refine.h>

namespace geotri::detail {

struct RefineTactics {
    /// Before a circumcentre, try the worst triangle's vertices at the centroid of their star, and keep the move that
    /// raises the smallest corner it changes the most; where nothing else mends the triangle, try them on a saddle
    /// of T that one of its geodesics bends at. The attempts without moves (RefineAttempt::vertex_moves) turn it off.
    bool move_vertices = true;
    /// In the end game, split a triangle that would be given up at a saddle of T that one of its geodesics bends at,
    /// or at the curved vertex of T nearest its circumcentre, with edges of any length.
    bool split_at_saddles = true;
    /// Last, where only triangles given up on are left, split each well inside its patch or a neighbour's.
    bool split_inside = true;
    /// Where the first refinement of the G given gives up on some corners, refine it again in the other ways that
    /// refine() lists (RefineResult::attempts).
    bool other_attempts = true;
};

/// refine() with some tactics turned off.
RefineResult refine(GeodesicTriangulation& g, const RefineOptions& options, const RefineTactics& tactics);

}  // namespace geotri::detail

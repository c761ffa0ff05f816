#pragma once
// Straightening a path into a geodesic of the same homotopy class: the shortest path inside a sleeve of faces that
// holds the path (the funnel algorithm on the sleeve unfolded into the plane), with the sleeve moved to the other
// side of every vertex where that path bends by less than π on its far side (Xin and Wang, 2007). Pinned vertices
// are punctures: the sleeve never moves across them, so the class is that of the surface without them.

#include <geodesic/mesh.h>
#include <geodesic/surface_point.h>

#include <vector>

namespace geotri::geodesic {

enum class StraightenStatus {
    geodesic,               ///< a geodesic polyline that passes no pinned vertex
    through_pinned_vertex,  ///< the shortest path of the class runs through a pinned vertex (`vertex`)
    bends_at_boundary,      ///< it bends by too much at a vertex that the sleeve cannot pass: a boundary (`vertex`)
};

struct StraightenResult {
    StraightenStatus status = StraightenStatus::geodesic;
    /// From the first to the last vertex of the input, both included, as a geodesic polyline (DESIGN.md §1); else
    /// the shortest path of the class found, which bends at or touches `vertex`.
    std::vector<SurfacePoint> path;
    double length = 0.0;
    int vertex = -1;  ///< unless geodesic: the pinned or boundary vertex where the path is not straight
    int moves = 0;           ///< times the sleeve was moved to the other side of a vertex
};

/// Shortens `vertices`, a path along edges of the mesh (consecutive vertices share an edge, its two ends differ),
/// to a locally shortest geodesic between its ends that is homotopic to it on the mesh with the `pinned` vertices
/// (nonzero entries, one per vertex; the ends may be pinned) taken out. Steps back (a, b, a) are dropped first.
/// On a boundary vertex the path may bend (bends_at_boundary): the sleeve cannot move across it.
/// Throws InvalidInput when `pinned` has the wrong size, when the path has fewer than two vertices after the steps
/// back are dropped or ends where it starts, when consecutive vertices share no edge, or when an inner vertex is
/// pinned or not manifold; NumericalError if the sleeve keeps moving without the path getting shorter (it never
/// should: every move shortens it).
StraightenResult straighten_path(const Mesh& mesh, const std::vector<int>& vertices,
                                 const std::vector<unsigned char>& pinned);

}  // namespace geotri::geodesic

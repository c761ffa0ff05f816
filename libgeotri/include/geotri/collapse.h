#pragma once
// Edge collapse (DESIGN.md §2, local operations): a coarse vertex removed by merging it into a neighbour, whose
// new edges are retraced as exact geodesics. It either leaves G valid, or is refused with G unchanged.

#include <geotri/geodesic_triangulation.h>

#include <string>

namespace geotri {


struct CollapseOptions {
    /// Refuse the collapse, G unchanged, unless G is valid after it (validate() with the overlay, which costs a
    /// few passes over T). When false, the result is kept whatever it is: for untangling, which judges it on all
    /// of G itself.
    bool check_validity = true;
};

struct CollapseResult {
    bool done = false;
    std::string reason;          ///< one readable line when refused
    OpenMesh::VertexHandle kept; ///< the vertex that remains, after the coarse mesh's garbage collection
    int retraced = 0;            ///< edges given new geodesics
};

/// Collapses the coarse halfedge h = (v, w) onto w: v goes, its edges to vertices other than w and the two
/// vertices opposite h become edges of w, each retraced as the shortest geodesic from w's location. The coarse
/// mesh is garbage-collected afterwards, so other handles may change. Refused when the collapse would change the
/// topology (OpenMesh's link condition) or leave a vertex with fewer than three edges, when a new geodesic cannot be
/// found, and, with options.check_validity, when G is not valid afterwards; refused, G is unchanged. Throws
/// InvalidInput when h is not a halfedge of G.
CollapseResult collapse_edge(GeodesicTriangulation& g, OpenMesh::HalfedgeHandle h, const CollapseOptions& options = {});

}  // namespace geotri

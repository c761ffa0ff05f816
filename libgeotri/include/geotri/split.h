#pragma once
// Edge split and face split (DESIGN.md §2, local operations): a new coarse vertex at a surface point, joined to the
// vertices around it by exact geodesics. Each split either leaves a valid G valid, or is refused with G unchanged
// and the reason given.

#include <geotri/geodesic_triangulation.h>

#include <string>
#include <vector>

namespace geotri {


struct SplitOptions {
    /// When the shortest geodesic from the new vertex leaves the patch that it must run in, try the shortest path
    /// inside that patch (PatchRegion).
    bool region_fallback = true;
    /// false: split_edge() takes the shortest geodesics from the new vertex whatever they do, and checks nothing;
    /// for untangling, which judges the result on all of G.
    bool checked = true;
};

struct SplitResult {
    bool done = false;
    std::string reason;                  ///< one readable line when refused
    OpenMesh::VertexHandle vertex;       ///< the new coarse vertex, when done
    int region_paths = 0;                ///< new geodesics that are the shortest paths inside their patch
};

/// The point at arc-length fraction `fraction` (in [0, 1]) of e's polyline, from from_vertex(halfedge(e, 0)).
/// Throws InvalidInput when e is not an edge or has no polyline, or fraction is outside [0, 1].
SurfacePoint point_along(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e, double fraction);

/// Splits edge e = (a, b), between faces (a, b, c) and (b, a, d), at the point m at arc-length `fraction` of its
/// polyline: a-m and m-b keep the two parts of the old polyline, and m-c and m-d are new geodesics that must run
/// inside the old patches of (a, b, c) and (b, a, d). Refused when m is an end of e, or when a new geodesic cannot
/// be found inside its patch, leaving and reaching its ends strictly inside the corners it splits. Preconditions:
/// G valid around e and every polyline of e's faces traced.
SplitResult split_edge(GeodesicTriangulation& g, OpenMesh::EdgeHandle e, double fraction,
                       const SplitOptions& options = {});

/// split_edge() at point `index` of e's polyline (from from_vertex(halfedge(e, 0))), which must not be an end.
/// Untangling splits an edge where another geodesic meets it, at a vertex of T, with `checked` false.
SplitResult split_edge_at_point(GeodesicTriangulation& g, OpenMesh::EdgeHandle e, std::size_t index,
                                const SplitOptions& options = {});

/// Splits face f = (a, b, c) at p, a point of T strictly inside its patch, with new geodesics p-a, p-b and p-c
/// inside that patch. Refused when p is not strictly inside the patch, or the three geodesics cannot be made so
/// that G stays valid. Preconditions: G valid around f and f's polylines traced.
SplitResult split_face(GeodesicTriangulation& g, OpenMesh::FaceHandle f, const SurfacePoint& p,
                       const SplitOptions& options = {});

/// A fork at coarse vertex a: `count` consecutive edges leaving a (counter-clockwise from `first`) whose geodesics
/// run together from a for their first `common` points, the last of which is where they part (shortest geodesics
/// from one point part only at saddle vertices of T). The corners between them are zero, so G is invalid there;
/// trace() can make such forks, typically on CAD models.
struct Fork {
    OpenMesh::HalfedgeHandle first;
    int count = 0;
    std::size_t common = 0;
};

/// The forks at a: the maximal runs of consecutive edges leaving a whose polylines share their first segment, with
/// two edges or more, and at least two edges of a's fan outside the run (the new vertex is joined to the ends of
/// the edges just before and after the run, which must differ).
std::vector<Fork> find_forks(const GeodesicTriangulation& g, OpenMesh::VertexHandle a);

/// Splits a fork (the inverse of an edge collapse, OpenMesh's vertex_split): a new coarse vertex v at the fork's
/// point takes over the run's edges, whose polylines lose the common part; a-v gets the common part; v is joined
/// to the vertices just before and after the run by shortest geodesics. Not checked: it is for untangling, which
/// judges the result on all of G. Refused when the fork's point is the far end of an edge of the run.
SplitResult split_fork(GeodesicTriangulation& g, const Fork& fork, const SplitOptions& options = {});

}  // namespace geotri

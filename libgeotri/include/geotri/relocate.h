#pragma once
// Vertex relocation: a coarse vertex moved to another point of T, with every edge of it retraced as an exact
// geodesic. It either leaves G valid, or is refused with G unchanged: judged on all of G (relocate_vertex()), or,
// for a move inside the vertex's star, by local checks (relocate_vertex_in_star()).

#include <geotri/geodesic_triangulation.h>

#include <string>
#include <vector>

namespace geotri {

struct RelocateOptions {
    /// Refuse the move, G unchanged, unless G is valid after it (validate() with the overlay). When false, the
    /// result is kept whatever it is: for untangling, which judges it on all of G itself.
    bool check_validity = true;
};

struct RelocateResult {
    bool done = false;
    std::string reason;  ///< one readable line when refused
};

/// Moves coarse vertex v to p, a point of T, and makes each of v's edges the shortest geodesic from p. Refused, G
/// unchanged, when p is where v or another coarse vertex already is, when a geodesic cannot be found, and, with
/// options.check_validity, when G is not valid afterwards. Throws InvalidInput when v is not a vertex of G or p
/// is not a point of T.
RelocateResult relocate_vertex(GeodesicTriangulation& g, OpenMesh::VertexHandle v, const SurfacePoint& p,
                               const RelocateOptions& options = {});

/// Moves coarse vertex v to p, a point of T inside v's star, and makes each of v's edges the shortest geodesic from
/// p, checked locally (no validate()): refused, G unchanged, unless every new geodesic is straight, leaves p in the
/// order of v's edges with a corner between each two, reaches its other end strictly inside the star's corner
/// there, and meets neither the star's outer polylines nor the other new geodesics. For a valid G whose star of v
/// is a disk (its ring vertices distinct), that keeps G valid, at the cost of one propagation from p towards the
/// ring. Throws InvalidInput when v is not a vertex of G or p is not a point of T.
RelocateResult relocate_vertex_in_star(GeodesicTriangulation& g, OpenMesh::VertexHandle v, const SurfacePoint& p);

/// The vertices of T within `rings` edges of v's location (of the fine edge's or face's vertices when it is not at
/// a vertex), nearest rings first and by index within a ring, without v's location itself and without the
/// locations of other coarse vertices: where untangling tries to move v. Throws InvalidInput when v is not a
/// vertex of G.
std::vector<int> nearby_fine_vertices(const GeodesicTriangulation& g, OpenMesh::VertexHandle v, int rings);

}  // namespace geotri

#pragma once
// The flip of a coarse edge (DESIGN.md §2, local operations): edge (a,b) between faces (a,b,c) and (b,a,d) becomes
// (c,d), whose polyline is the exact shortest geodesic from c's location to d's. A flip is refused, with G unchanged
// and the reason given, when the result would not be valid around the edge. Also the coarse corner angles, which
// the flip criteria and the statistics need.

#include <geotri/geodesic_triangulation.h>

#include <array>
#include <string>

namespace geotri {

struct Overlay;

/// The corner angle of face(h) at from_vertex(h): the counter-clockwise angle at that vertex's location from the
/// geodesic of h to the geodesic of the next outgoing halfedge (ccw_rotated_halfedge_handle(h)), in radians, in
/// [0, Θ). This is the corner that geotri::validate() measures for condition 2. Precondition: both edges have
/// polylines of at least two points starting at the vertex's location; throws InvalidInput otherwise.
double corner_angle(const GeodesicTriangulation& g, OpenMesh::HalfedgeHandle h);

/// The three corner angles of coarse face f, at the from-vertices of its halfedges in the order of
/// fh_range(f) (starting at halfedge_handle(f)). Throws as corner_angle().
std::array<double, 3> corner_angles(const GeodesicTriangulation& g, OpenMesh::FaceHandle f);

/// Why a flip was refused.
enum class FlipRefusal {
    none,            ///< not refused
    not_flippable,   ///< a boundary edge, c == d, or c and d already joined by an edge (OpenMesh's is_flip_ok)
    no_path,         ///< libgeodesic found no geodesic from c to d (not on one component), or not one straight
                     ///< within validate()'s tolerance
    leaves_region,   ///< the c-d geodesic meets another polyline or passes through another coarse vertex
    bad_corner,      ///< a corner that the new geodesic creates at c or d would not be positive, or the geodesic
                     ///< does not leave c (or d) inside the old corner there
};

/// "not flippable", "no path", "leaves region", "bad corner" (or "none").
const char* to_string(FlipRefusal refusal);

struct FlipOptions {
    /// Check that the result is valid around the edge (the default, and what keeps a valid G valid). When false,
    /// the flip is done whenever it is topologically possible and a c-d geodesic exists: for callers that judge
    /// the result on all of G themselves (untangling an invalid G).
    bool check_validity = true;
    /// With check_validity: when the shortest c-d geodesic leaves the two patches, try the shortest path inside
    /// them (plan_flip_in_region()).
    bool region_fallback = true;
};

/// A flip computed but not yet done: the new geodesic and the corners it makes.
struct FlipPlan {
    OpenMesh::EdgeHandle edge;
    OpenMesh::VertexHandle a, b, c, d;  ///< the old edge a->b = halfedge_handle(edge, 0); c opposite it, d beyond
    FlipRefusal refusal = FlipRefusal::none;
    std::string reason;                 ///< one readable line when refused
    Polyline path;                      ///< from c's location to d's (when a geodesic was found)
    double length = 0.0;
    bool in_region = false;             ///< the path is the shortest inside the two patches, not on all of T
    /// The six corner angles of the two new faces (a,d,c) and (b,c,d), when refusal is none and check_validity:
    /// at a, d, c of the first (a's is the sum of the two old ones), then at b, c, d of the second.
    std::array<double, 6> corners{};

    bool accepted() const { return refusal == FlipRefusal::none; }
};

/// Computes the flip of e without changing G. Preconditions: e is an edge of g.coarse() and every polyline of the
/// two faces at e has been traced. Throws InvalidInput when e is not a valid edge.
///
/// With options.check_validity, the plan is accepted only when, for a G that was valid, G stays valid: the new
/// geodesic leaves c and reaches d strictly inside the old corners there (each of the four corners it makes is
/// above 1e-9 rad), and it does not meet any of the four other polylines of the two faces, nor the locations of a
/// and b (within the tolerances of validate()). For a valid G this keeps it inside the union of the two patches,
/// which the two new patches then split into two disks. When the shortest geodesic fails these checks and
/// options.region_fallback is set, the plan is plan_flip_in_region()'s if that one is accepted.
FlipPlan plan_flip(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e, const FlipOptions& options = {});

/// The flip of e with the shortest path from c to d inside the union of the two patches of e's faces (libgeodesic
/// on the sub-mesh of `overlay`'s triangles of those patches), then plan_flip()'s checks. The path is accepted only
/// when it stays off the region's boundary except at c and d: it is then straight everywhere, a geodesic of T
/// (if not the shortest one). `overlay` must be build_overlay() of this same G. For a valid G.
FlipPlan plan_flip_in_region(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e, const Overlay& overlay);

/// The same, with the two patches alone cut out of T (PatchRegion): the same path, at a cost that grows with the
/// patches rather than with T.
FlipPlan plan_flip_in_region(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e);

/// Does a flip that plan_flip() accepted on this same, unchanged G: OpenMesh's flip() on the coarse mesh, then the
/// new polyline. Throws InvalidInput when the plan was refused or no longer fits G.
void apply_flip(GeodesicTriangulation& g, const FlipPlan& plan);

/// plan_flip(), then apply_flip() when the plan is accepted. G is unchanged when refused.
FlipPlan flip(GeodesicTriangulation& g, OpenMesh::EdgeHandle e, const FlipOptions& options = {});

}  // namespace geotri

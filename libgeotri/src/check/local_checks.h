#pragma once
// The checks that keep a valid G valid when a local operation adds a geodesic: the new geodesic leaves and reaches
// its end vertices strictly inside the corners it splits (condition 2), and it meets none of the polylines that
// bound the region it must run in (condition 3). For a valid G these two are enough: the region is a disk bounded
// by those polylines, so a geodesic that starts and ends inside it and never meets its boundary stays inside.

#include <geodesic/mesh.h>
#include <geotri/geodesic_triangulation.h>

#include <string>
#include <vector>

namespace geotri::detail {

// New corners must clear validate()'s 1e-12 rad by a wide margin, so that the geodesics they separate stay apart
// by more than validate()'s meeting tolerance along their first segments too.
constexpr double k_min_new_corner = 1e-9;

/// A polyline around the region. `start_tag` says whether its first point is an end of the new geodesic: 0 its
/// start, 1 its end, -1 neither (then the new geodesic must not touch it at all).
struct BoundingPath {
    Polyline path;
    int start_tag = -1;
    std::string name;  ///< for messages: "c-a"
};

/// Empty when `path` (from its start, tag 0, to its end, tag 1) meets none of `around` other than at the ends it
/// shares with them, else one line saying which one it meets and where. Within validate()'s tolerance: points
/// closer than 1e-12 times the local fine edge length meet.
std::string first_meeting(const geodesic::Mesh& mesh, const Polyline& path, const std::vector<BoundingPath>& around);

/// × size(T): how far off straight a polyline point may lie. libgeodesic snaps a crossing within 1e-12·size of a
/// vertex onto it; traced paths on the shared meshes are otherwise straight to 5e-17·size.
constexpr double k_straight_tolerance = 2e-12;

/// Empty when `path` is straight through every interior point (condition 1, as validate() judges it), else one
/// line saying where it bends: "is not straight at point 3 (...): it bends by 7.1e-10 rad, 6.8e-10 allowed".
/// A point may lie within k_straight_tolerance·size(T) of the straight line through its neighbours, unfolded on
/// the side where the angle is π; through a fine vertex, a saddle with at least π on each side is straight too.
std::string straightness_defect(const geodesic::Mesh& mesh, const Polyline& path);

/// A corner at a point of cone angle `theta`, from direction `from` counter-clockwise to `to`, split by `inner`.
struct CornerSplit {
    double before = 0.0;  ///< from `from` to `inner`
    double after = 0.0;   ///< from `inner` to `to`
    /// `inner` lies strictly inside the corner, and both parts exceed k_min_new_corner.
    bool ok = false;
};
CornerSplit split_corner(double from, double inner, double to, double theta);

/// The polar angle, at from_vertex(h)'s location, of the first segment of h's geodesic. Throws InvalidInput when
/// the edge has no polyline of two points or more.
double start_direction(const GeodesicTriangulation& g, OpenMesh::HalfedgeHandle h);

}  // namespace geotri::detail

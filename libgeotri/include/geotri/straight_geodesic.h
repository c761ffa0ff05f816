#pragma once
// Straightest geodesics on the fine mesh T (the discrete exponential map): from a surface point, in the direction of
// a polar angle (tangent_angles.h's convention), for a given length. The ray walks face to face, each next face
// unfolded flat across the edge that it crosses, so the result is straight across every edge it crosses. It never
// continues through a fine vertex: it stops there (or on a mesh boundary) and says so.

#include <geodesic/mesh.h>
#include <geodesic/surface_point.h>

#include <cstddef>
#include <vector>

namespace geotri {

struct StraightGeodesicOptions {
    /// Hard cap on the number of faces the ray may cross; more throws NumericalError. Guards against endless walks
    /// (through runs of zero-area faces, or a huge length); a walk of length L crosses roughly L / (mean edge
    /// length) faces.
    std::size_t max_crossings = 1000000;
};

struct StraightGeodesicResult {
    /// The geodesic polyline (DESIGN.md §1): the start, every edge crossing, and the end, in canonical form
    /// (Mesh::canonical). Just the start for a walk of length 0 (or one refused at once by a boundary).
    std::vector<geodesic::SurfacePoint> path;
    /// path.back().
    geodesic::SurfacePoint end;
    /// Polar angle at `end`, in [0, cone_angle(end)), of the direction the path arrived from: it points back along
    /// the last segment, so that polar_angle(mesh, end, path[path.size() - 2]) is this angle up to rounding and a
    /// straight geodesic traced from `end` in this direction for `length` retraces the path. Where `end` is not a
    /// vertex, the straight continuation is arrival_angle + π (mod 2π). NaN when the path has a single point.
    double arrival_angle = 0.0;
    /// The length actually walked (the sum of the segment lengths): the requested length unless stopped early.
    double length = 0.0;
    /// The ray met a fine vertex (end is that vertex) before walking the requested length.
    bool stopped_at_vertex = false;
    /// The ray left the mesh through a boundary edge (end is on that edge) before walking the requested length.
    bool stopped_at_boundary = false;
};

/// Traces the straightest geodesic from `start` in the direction `polar_angle` (measured as tangent_angles.h's
/// polar_angle() measures, taken modulo cone_angle(start)) for `length`, so that polar_angle(mesh, path[0], path[1])
/// gives back the requested direction.
///
/// - `start` may be a vertex (any cone angle: at a saddle the angle picks the face), an edge point or a face point.
///   A direction along a fine edge walks along that edge.
/// - The ray stops at the first fine vertex that it passes within rounding of (relative 1e-11 of the edge's length),
///   and at a boundary edge; both are reported in the result, never continued. A point of an edge whose other side
///   is missing, with a direction into the missing side, stops at once (a path of one point).
/// - Deterministic: the same input always gives the same path.
///
/// Throws InvalidInput when `start` does not refer to the mesh, when it is a non-manifold vertex, when `polar_angle`
/// is not finite, or when `length` is negative or not finite; NumericalError when the walk crosses more than
/// options.max_crossings faces.
StraightGeodesicResult trace_straight_geodesic(const geodesic::Mesh& mesh, const geodesic::SurfacePoint& start,
                                               double polar_angle, double length,
                                               const StraightGeodesicOptions& options = {});

}  // namespace geotri

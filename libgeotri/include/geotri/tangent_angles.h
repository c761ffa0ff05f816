#pragma once
// Tangent directions at surface points (DESIGN.md §1): polar angles in [0, Θ_p), measured intrinsically and
// counter-clockwise (seen from outside) from a fixed reference direction per point. No normals are involved: every
// angle comes from corner angles of T and from faces laid out flat in the plane.
//
// Reference directions, fixed per point so that any two callers agree:
// - on a vertex v:            along the fine halfedge outgoing(v), as geodesic::Mesh::polar_angle() measures;
// - on an edge {a, b}:        along the edge towards its larger vertex index max(a, b). Polar angle 0 points to
//                             max(a, b), π points to min(a, b); (0, π) lies in the face on the left of the halfedge
//                             min(a, b) -> max(a, b), and (π, 2π) in the other face;
// - inside a face f:          towards the face's first vertex, triangle(f)[0].
// An angle between two directions at the same point is a difference of polar angles (ccw_angle).

#include <geodesic/mesh.h>
#include <geodesic/surface_point.h>

#include <Eigen/Core>

#include <array>
#include <utility>
#include <vector>

namespace geotri {

/// Θ_p: the cone angle of T at a vertex, 2π at an edge or face point. Throws InvalidInput for a point that does not
/// refer to the mesh.
double cone_angle(const geodesic::Mesh& mesh, const geodesic::SurfacePoint& p);

/// A face of T that contains both points (on its boundary or inside), or -1 when there is none. Points on a common
/// edge share two faces; the one returned is then the face on the left of the halfedge min -> max of that edge.
int common_face(const geodesic::Mesh& mesh, const geodesic::SurfacePoint& p, const geodesic::SurfacePoint& q);

/// True when p and q both lie on one fine edge (its vertices included), so that the segment between them runs along
/// that edge.
bool on_common_edge(const geodesic::Mesh& mesh, const geodesic::SurfacePoint& p, const geodesic::SurfacePoint& q);

/// The fine edge that p and q both lie on, as its two vertices in increasing order. Precondition:
/// on_common_edge(mesh, p, q).
std::pair<int, int> common_edge(const geodesic::SurfacePoint& p, const geodesic::SurfacePoint& q);

/// The fine faces that hold p: those around a vertex, the one or two of an edge, or the one it is inside.
std::vector<int> faces_holding(const geodesic::Mesh& mesh, const geodesic::SurfacePoint& p);

/// The position of p, a point of face f (one of its vertices, a point of one of its edges, or a point inside it),
/// in the plane frame of the fine halfedge h of f: tail(h) at (0, 0), head(h) at (length(h), 0), the face at y >= 0.
/// Throws InvalidInput when p does not lie on face(h).
Eigen::Vector2d halfedge_coordinates(const geodesic::Mesh& mesh, int h, const geodesic::SurfacePoint& p);

/// The barycentric coordinates of p in fine face f, in the order of triangle(f), for p on f (one of its vertices, a
/// point of one of its edges, or a point inside it). Throws InvalidInput when p does not lie on f.
std::array<double, 3> barycentric_in(const geodesic::Mesh& mesh, int f, const geodesic::SurfacePoint& p);

/// The polar angle at p, in [0, cone_angle(p)), of the straight segment from p to q. The two points must be
/// distinct and share a face of T, as consecutive points of a geodesic polyline do; a segment along a fine edge or
/// from a vertex across its opposite edge is fine. Throws InvalidInput otherwise.
double polar_angle(const geodesic::Mesh& mesh, const geodesic::SurfacePoint& p, const geodesic::SurfacePoint& q);

/// The polar angle at its start of the first segment of a polyline: polar_angle(mesh, path[0], path[1]).
/// Throws InvalidInput for a polyline of fewer than two points or as polar_angle() does.
double initial_polar_angle(const geodesic::Mesh& mesh, const std::vector<geodesic::SurfacePoint>& path);

/// The counter-clockwise angle from direction `from` to direction `to` at a point of cone angle `theta`, in
/// [0, theta).
double ccw_angle(double from, double to, double theta);

}  // namespace geotri

#pragma once
// What validate() checks for conditions 1-3, one polyline or one coarse vertex at a time, so that untangling can
// count the violations of a trial copy of G from what changed (violation_count.h). The words and the counts are
// those of validate(): validate.cpp uses these too.

#include <geodesic/mesh.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/validate.h>

#include "core/tolerances.h"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace geotri::detail {

/// A point that takes part in condition 3: point `index` of the polyline of coarse edge `feature` (feature < number
/// of edges), or the location of coarse vertex `feature - number of edges` (index 0).
struct Item {
    int feature;
    int index;
};

struct EdgePoint {
    int key;
    double t;
    Item item;
};

struct EdgeInterval {
    int key;
    double t0, t1;
    int feature;
    int segment;
};

struct FaceSegment {
    int face;
    Item end[2];
    Eigen::Vector2d x[2];
    int segment;  ///< -1 for a coarse vertex (a single point)
};

/// A polyline's part in condition 3: its points and segments, each with the fine vertex, edge or face that holds
/// it, as Validator::check_crossings() sorts them. Their coarse edge (feature) is 0, set where they are used: an
/// unchanged polyline may belong to an edge of another index in a changed copy of G.
struct CrossingItems {
    std::vector<std::pair<int, Item>> vertex_items;  ///< a fine vertex, and a point on it
    std::vector<EdgePoint> edge_points;
    std::vector<EdgeInterval> edge_intervals;
    std::vector<FaceSegment> face_segments;
};

/// Coarse vertex v's location in canonical form, as validation reads it. Throws InvalidInput("coarse vertex V:
/// location: ...") when it does not refer to T.
SurfacePoint canonical_location(const geodesic::Mesh& mesh, const SurfacePoint& location, int v);

/// The polyline `raw` of coarse edge e with its points in canonical form, as validation reads it. Throws
/// InvalidInput("coarse edge E: point I: ...") for a point that does not refer to T.
Polyline canonical_polyline(const geodesic::Mesh& mesh, const Polyline& raw, int e);

/// The condition-3 items of a polyline in canonical form whose points are apart and pairwise on a common face.
CrossingItems polyline_crossing_items(const geodesic::Mesh& mesh, const Polyline& path);

/// The condition-3 item of a coarse vertex at `location` (canonical), with feature 0: a point on a fine vertex or
/// edge, or a segment of one point in a fine face.
CrossingItems location_crossing_items(const geodesic::Mesh& mesh, const SurfacePoint& location);

/// Condition 1 on the polyline `path` (canonical points) of a coarse edge from coarse vertex `from` at
/// `from_location` to `to` at `to_location`, with `recorded_length`: empty when it holds, else what is wrong, as
/// validate() words it after the edge's name. `known` is the verdict kept on its shape (PolylineVerdicts), or
/// null. `usable` tells whether the polyline takes part in conditions 2 and 3: it starts and ends at its vertices'
/// locations, and its points are apart and pairwise on a common fine face.
std::string polyline_violation(const geodesic::Mesh& mesh, const Polyline& path, int from,
                               const SurfacePoint& from_location, int to, const SurfacePoint& to_location,
                               const std::string* known, double recorded_length, bool& usable);

/// Condition 2 at a coarse vertex at `location` (canonical), from the polar angles of its geodesics' first
/// segments in the coarse mesh's counter-clockwise order.
struct VertexCorners {
    std::vector<double> corners;  ///< from each geodesic to the next
    double theta = 0.0;           ///< the cone angle at the location
    double sum = 0.0;
    int first_bad = -1;           ///< the first corner that is not positive, or -1
    long winding = 0;             ///< round(sum / theta)
    bool violated() const { return first_bad >= 0 || winding != 1; }
};
VertexCorners vertex_corners(const geodesic::Mesh& mesh, const SurfacePoint& location,
                             const std::vector<double>& polar_angles);

/// A violation of condition 2 at coarse vertex c, whose out halfedges `out` gave corners whose first that is not
/// positive is `first_bad` (VertexCorners), with the coarse elements that validate() names: the edges and face of
/// that corner, else (-1) every edge and face around c. Its `what` is empty.
Violation corner_violation(const CoarseMesh& coarse, int c, const std::vector<OpenMesh::HalfedgeHandle>& out,
                           int first_bad);

/// One side of a meeting of condition 3: coarse edge `index` from coarse vertex `from` to `to`, or coarse vertex
/// `index` (is_vertex; from and to unused).
struct MeetingSide {
    bool is_vertex;
    int index;
    int from, to;
};

/// A violation of condition 3 where a and b meet (a == b: an edge that meets itself), with the coarse elements
/// that validate() names: the edges, and the vertices at their ends or met, sorted. Its `what` is empty.
Violation meeting_violation(const MeetingSide& a, const MeetingSide& b);

}  // namespace geotri::detail

#include "check/local_checks.h"
#include "core/tolerances.h"
#include "core/plane_segments.h"

#include <geodesic/constants.h>
#include <geodesic/errors.h>
#include <geotri/tangent_angles.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace geotri::detail {

using geodesic::Mesh;
using geodesic::PointKind;

namespace {

/// A piece of a polyline inside one fine face, in the frame of the face's first halfedge: a segment, or a single
/// point (a polyline point on a fine vertex, entered in every face around the vertex so that a path that passes
/// near the vertex in any of them is seen).
struct Piece {
    Eigen::Vector2d x0, x1;
    int tag0, tag1;  ///< per end: 0 or 1 when it is that end of the new geodesic, -1 otherwise
    bool point;
    int polyline;    ///< index into the bounding paths, for messages
};

/// The fine faces that hold the straight segment from p to q: one, or the two faces of the fine edge they lie on.
struct SegmentFaces {
    std::array<int, 2> face{-1, -1};
    int count = 0;
};
SegmentFaces faces_of_segment(const Mesh& mesh, const SurfacePoint& p, const SurfacePoint& q) {
    SegmentFaces faces;
    if (on_common_edge(mesh, p, q)) {
        const auto [a, b] = common_edge(p, q);
        for (int h : {mesh.find_halfedge(a, b), mesh.find_halfedge(b, a)})
            if (h >= 0) faces.face[static_cast<std::size_t>(faces.count++)] = Mesh::face_of(h);
        return faces;
    }
    const int f = common_face(mesh, p, q);
    if (f < 0) throw InvalidInput("a polyline has consecutive points on no common fine face");
    faces.face[0] = f;
    faces.count = 1;
    return faces;
}

/// Pieces with the fine face that holds each, in the order they were added until by_face() sorts them by face
/// (stably: within a face, still in that order). A flat list: a map of lists cost a node and a list per face, and
/// every check of a new geodesic makes a few.
struct FacePiece {
    int face;
    Piece piece;
};
using Pieces = std::vector<FacePiece>;

void by_face(Pieces& pieces) {
    std::stable_sort(pieces.begin(), pieces.end(),
                     [](const FacePiece& a, const FacePiece& b) { return a.face < b.face; });
}

/// Whether `sorted` (by_face()) has a piece in face f.
bool has_face(const Pieces& sorted, int f) {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), f,
                                     [](const FacePiece& a, int face) { return a.face < face; });
    return it != sorted.end() && it->face == f;
}

/// Adds the pieces of `line` to `pieces`; `end_tag` holds the tags of its first and last point. With `only`
/// (sorted by face), just the pieces in the faces that it holds pieces in: no others can meet them.
void add_pieces(const Mesh& mesh, const Polyline& line, std::array<int, 2> end_tag, int id, Pieces& pieces,
                const Pieces* only = nullptr) {
    const std::size_t n = line.size();
    auto tag_of = [&](std::size_t i) { return i == 0 ? end_tag[0] : (i + 1 == n ? end_tag[1] : -1); };
    auto wanted = [&](int f) { return !only || has_face(*only, f); };
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const SurfacePoint& p = line[i];
        const SurfacePoint& q = line[i + 1];
        const SegmentFaces faces = faces_of_segment(mesh, p, q);
        for (int k = 0; k < faces.count; ++k) {
            const int f = faces.face[static_cast<std::size_t>(k)];
            if (wanted(f))
                pieces.push_back({f, {halfedge_coordinates(mesh, 3 * f, p), halfedge_coordinates(mesh, 3 * f, q),
                                      tag_of(i), tag_of(i + 1), false, id}});
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        const SurfacePoint& p = line[i];
        if (p.kind != PointKind::vertex) continue;
        for (int h : mesh.outgoing_halfedges(p.vertex)) {
            const int f = Mesh::face_of(h);
            if (!wanted(f)) continue;
            const Eigen::Vector2d x = halfedge_coordinates(mesh, 3 * f, p);
            pieces.push_back({f, {x, x, tag_of(i), tag_of(i), true, id}});
        }
    }
}

/// Whether two pieces in one face meet other than at a common end of the new geodesic.
bool pieces_meet(const Piece& s, const Piece& r, double tolerance) {
    for (int i = 0; i < 2; ++i) {
        const int tag = i == 0 ? s.tag0 : s.tag1;
        if (tag < 0) continue;
        int j = -1;
        if (r.tag0 == tag) j = 0;
        else if (r.tag1 == tag) j = 1;
        if (j < 0) continue;
        if (s.point || r.point) return false;
        // Two geodesics leaving one end overlap when the far end of one lies on the other.
        const Eigen::Vector2d& s_far = i == 0 ? s.x1 : s.x0;
        const Eigen::Vector2d& r_far = j == 0 ? r.x1 : r.x0;
        return point_segment_distance(s_far, r.x0, r.x1) <= tolerance ||
               point_segment_distance(r_far, s.x0, s.x1) <= tolerance;
    }
    return segment_distance(s.x0, s.x1, r.x0, r.x1) <= tolerance;
}

}  // namespace

std::string first_meeting(const Mesh& mesh, const Polyline& path, const std::vector<BoundingPath>& around) {
    Pieces fresh;
    add_pieces(mesh, path, {0, 1}, -1, fresh);
    by_face(fresh);
    Pieces bounding;
    for (std::size_t i = 0; i < around.size(); ++i)
        add_pieces(mesh, around[i].path, {around[i].start_tag, -1}, static_cast<int>(i), bounding, &fresh);
    by_face(bounding);
    // Face by face in increasing order, and in each the pieces in the order they were added.
    auto faces_end = [](const Pieces& pieces, Pieces::const_iterator first) {
        return std::find_if(first, pieces.end(), [&](const FacePiece& p) { return p.face != first->face; });
    };
    auto r_first = bounding.cbegin();
    for (auto s_first = fresh.cbegin(); s_first != fresh.cend();) {
        const auto s_last = faces_end(fresh, s_first);
        const int f = s_first->face;
        while (r_first != bounding.cend() && r_first->face < f) ++r_first;
        if (r_first != bounding.cend() && r_first->face == f) {
            const auto r_last = faces_end(bounding, r_first);
            const double tolerance =
                k_meet_tolerance * std::max({mesh.length(3 * f), mesh.length(3 * f + 1), mesh.length(3 * f + 2)});
            for (auto s = s_first; s != s_last; ++s)
                for (auto r = r_first; r != r_last; ++r)
                    if (pieces_meet(s->piece, r->piece, tolerance))
                        return "the new geodesic meets the polyline " +
                               around[static_cast<std::size_t>(r->piece.polyline)].name + " in fine face " +
                               std::to_string(f);
        }
        s_first = s_last;
    }
    return {};
}

CornerSplit split_corner(double from, double inner, double to, double theta) {
    CornerSplit split;
    split.before = ccw_angle(from, inner, theta);
    split.after = ccw_angle(inner, to, theta);
    const double whole = ccw_angle(from, to, theta);
    split.ok = split.before < whole && split.before > k_min_new_corner && split.after > k_min_new_corner;
    return split;
}

double start_direction(const GeodesicTriangulation& g, OpenMesh::HalfedgeHandle h) {
    const CoarseMesh& coarse = g.coarse();
    const OpenMesh::EdgeHandle e = coarse.edge_handle(h);
    const Polyline& line = g.polyline(e);
    if (line.size() < 2)
        throw InvalidInput("coarse edge " + std::to_string(e.idx()) + " has no polyline of two points or more");
    const std::size_t n = line.size();
    if (h == coarse.halfedge_handle(e, 0)) return polar_angle(g.fine().mesh, line[0], line[1]);
    return polar_angle(g.fine().mesh, line[n - 1], line[n - 2]);
}

std::string straightness_defect(const geodesic::Mesh& mesh, const Polyline& path) {
    // With a bend of β and neighbours at distances a and b, the point is β·ab/(a+b) off the line through them, so
    // the bend may be reach·(1/a + 1/b).
    const double reach = k_straight_tolerance * mesh.size();
    auto format = [](const char* pattern, double x, double y, double z = 0.0) {
        char text[160];
        std::snprintf(text, sizeof text, pattern, x, y, z);
        return std::string(text);
    };
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
        const SurfacePoint& p = path[i];
        const double theta = cone_angle(mesh, p);
        const double left = ccw_angle(polar_angle(mesh, p, path[i - 1]), polar_angle(mesh, p, path[i + 1]), theta);
        const double right = theta - left;
        const double a = (mesh.point(p) - mesh.point(path[i - 1])).norm();
        const double b = (mesh.point(path[i + 1]) - mesh.point(p)).norm();
        const double slack = (a > 0.0 && b > 0.0) ? reach * (1.0 / a + 1.0 / b) : std::numeric_limits<double>::infinity();
        const double bend = std::min(std::abs(left - geodesic::k_pi), std::abs(right - geodesic::k_pi));
        if (bend <= slack) continue;
        if (p.kind == geodesic::PointKind::vertex) {
            // A saddle: at least π on each side. (Straight on one side is a crossing that rounding put on the vertex.)
            if (std::min(left, right) >= geodesic::k_pi - slack) continue;
            return "bends at fine vertex " + std::to_string(p.vertex) + " (point " + std::to_string(i) + "): " +
                   format("angles %.9g° and %.9g° on its sides, cone angle %.9g°", left * 180.0 / geodesic::k_pi,
                          right * 180.0 / geodesic::k_pi, theta * 180.0 / geodesic::k_pi);
        }
        return "is not straight at point " + std::to_string(i) + " (" + geodesic::to_spec(p) + "): " +
               format("it bends by %.2g rad, %.2g allowed", bend, slack);
    }
    return {};
}

}  // namespace geotri::detail

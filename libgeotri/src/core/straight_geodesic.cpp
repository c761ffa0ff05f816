#include <geodesic/constants.h>
#include <geodesic/errors.h>
#include <geotri/straight_geodesic.h>
#include <geotri/tangent_angles.h>

#include "core/plane_segments.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace geotri {

using geodesic::Mesh;
using geodesic::PointKind;
using geodesic::SurfacePoint;

namespace {

using geodesic::k_pi;
using geodesic::k_two_pi;
/// A crossing this close to an end of an edge (as a fraction of its length) is taken as passing through the vertex,
/// and an end this close to an edge or vertex is put on it: unfolding a long walk accumulates rounding of this order
/// far below it, so the same input is decided the same way whatever the order of the operations.
constexpr double k_snap = 1e-11;

using detail::cross;

/// Face face_of(h) laid out in the plane frame of its halfedge h: corner j is tail(edge j), and edge j runs from
/// corner j to corner j+1 (edge 0 is h, edge 1 next(h), edge 2 prev(h)).
struct Frame {
    int h;
    Eigen::Vector2d c[3];

    Frame(const Mesh& mesh, int halfedge)
        : h(halfedge), c{Eigen::Vector2d::Zero(), Eigen::Vector2d(mesh.length(halfedge), 0.0), mesh.apex(halfedge)} {}

    int edge(int j) const {
        switch (j) {
            case 0: return h;
            case 1: return Mesh::next(h);
            default: return Mesh::prev(h);
        }
    }
    int vertex(const Mesh& mesh, int j) const { return mesh.tail(edge(j)); }
};

/// Where a ray leaves the current face: edge k of the frame, at t along it (0 at corner k, 1 at corner k+1).
struct Exit {
    int k;
    double t;
};

/// Which part of the face the ray starts from; it decides which edges it may leave through.
enum class StartOn { interior, edge0, corner0 };

/// Signed side of corner q seen from the ray (x, d): positive on its left.
double side(const Eigen::Vector2d& x, const Eigen::Vector2d& d, const Eigen::Vector2d& q) { return cross(d, q - x); }

/// The parameter where the ray's line crosses the edge from a corner on its right (s_from <= 0) to one on its left.
double crossing(double s_from, double s_to) {
    s_from = std::min(s_from, 0.0);
    s_to = std::max(s_to, 0.0);
    return s_to - s_from > 0.0 ? -s_from / (s_to - s_from) : 0.0;
}

Exit find_exit(const Frame& frame, const Eigen::Vector2d& x, const Eigen::Vector2d& d, StartOn start) {
    const Eigen::Vector2d* c = frame.c;
    switch (start) {
        case StartOn::corner0:
            // From corner 0 into its corner angle: only the opposite edge can be hit.
            return {1, crossing(side(x, d, c[1]), side(x, d, c[2]))};
        case StartOn::edge0: {
            // From edge 0 into the face (d.y >= 0): the apex's side picks the edge.
            const double s0 = side(x, d, c[0]), s1 = side(x, d, c[1]), s2 = side(x, d, c[2]);
            if (s2 > 0.0 || (s2 == 0.0 && s1 < 0.0)) return {1, crossing(s1, s2)};
            if (s2 < 0.0) return {2, crossing(s2, s0)};
            // A zero-area face with the ray along its line: go to the corner ahead.
            return d.x() >= 0.0 ? Exit{1, 0.0} : Exit{2, 1.0};
        }
        case StartOn::interior: {
            const double s[3] = {side(x, d, c[0]), side(x, d, c[1]), side(x, d, c[2])};
            for (int k = 0; k < 3; ++k)
                if (s[k] <= 0.0 && s[(k + 1) % 3] > 0.0) return {k, crossing(s[k], s[(k + 1) % 3])};
            throw NumericalError("straight geodesic: no exit from fine face " + std::to_string(Mesh::face_of(frame.h)) +
                                 " (zero area?)");
        }
    }
    throw NumericalError("straight geodesic: unknown start");
}

/// Rotates a direction from the frame of `frame` to the frame of its edge k (edge k along +x, the face above).
Eigen::Vector2d in_edge_frame(const Frame& frame, int k, const Eigen::Vector2d& w) {
    const Eigen::Vector2d u = (frame.c[(k + 1) % 3] - frame.c[k]).normalized();
    return {u.dot(w), cross(u, w)};
}

double wrap_angle(double angle, double theta) {
    angle = std::fmod(angle, theta);
    if (angle < 0.0) angle += theta;
    if (!(angle < theta) || angle < 0.0) angle = 0.0;
    return angle;
}

SurfacePoint edge_point(const Mesh& mesh, const Frame& frame, int k, double t) {
    const int e = frame.edge(k);
    return mesh.canonical(SurfacePoint::on_edge(mesh.tail(e), mesh.head(e), t));
}

/// The point y of the frame's face as a canonical surface point.
SurfacePoint face_point(const Mesh& mesh, const Frame& frame, const Eigen::Vector2d& y) {
    const Eigen::Vector2d* c = frame.c;
    const double area = cross(c[1] - c[0], c[2] - c[0]);
    const int f = Mesh::face_of(frame.h);
    std::array<double, 3> bary{};
    double sum = 0.0;
    for (int j = 0; j < 3; ++j) {
        const double lambda = std::max(0.0, cross(c[(j + 1) % 3] - y, c[(j + 2) % 3] - y) / area);
        bary[(frame.h % 3 + j) % 3] = lambda;
        sum += lambda;
    }
    for (double& b : bary) b /= sum;
    for (double& b : bary)
        if (b < k_snap) b = 0.0;
    // canonical() divides by the sum again unless it is exactly 1, and that need not settle. The last coordinate
    // that it adds, taken as 1 - (b0 + b1), makes the sum exactly 1 in floating point (the rounding error of that
    // subtraction is at most half an ulp of 1), so the point returned is its own canonical form.
    if (bary[2] > 0.0 && bary[0] > 0.0 && bary[1] > 0.0) bary[2] = 1.0 - (bary[0] + bary[1]);
    return mesh.canonical(SurfacePoint::in_face(f, bary));
}

/// Polar angle at p, a point of the frame's face, of the direction `back` given in the frame.
double polar_angle_in_frame(const Mesh& mesh, const Frame& frame, const SurfacePoint& p, const Eigen::Vector2d& y,
                            const Eigen::Vector2d& back) {
    switch (p.kind) {
        case PointKind::vertex:
            for (int j = 0; j < 3; ++j) {
                if (frame.vertex(mesh, j) != p.vertex) continue;
                const int e = frame.edge(j);
                const Eigen::Vector2d w = in_edge_frame(frame, j, back);
                const double inside = std::clamp(std::atan2(w.y(), w.x()), 0.0, mesh.corner_angle(e));
                return wrap_angle(mesh.polar_angle(e) + inside, mesh.cone_angle(p.vertex));
            }
            break;
        case PointKind::edge:
            for (int k = 0; k < 3; ++k) {
                const int e = frame.edge(k);
                const int a = mesh.tail(e), b = mesh.head(e);
                if (std::min(a, b) != p.edge_v0 || std::max(a, b) != p.edge_v1) continue;
                const Eigen::Vector2d w = in_edge_frame(frame, k, back);
                const double above = std::clamp(std::atan2(w.y(), w.x()), 0.0, k_pi);
                // This face is on the left of min -> max exactly when e runs that way (tangent_angles.h).
                return wrap_angle(a < b ? above : k_pi + above, k_two_pi);
            }
            break;
        case PointKind::face: {
            const int j0 = (3 - frame.h % 3) % 3;  // the corner of triangle(f)[0], the reference direction
            const Eigen::Vector2d r = frame.c[j0] - y;
            return wrap_angle(std::atan2(cross(r, back), r.dot(back)), k_two_pi);
        }
    }
    throw NumericalError("straight geodesic: end point " + geodesic::to_spec(p) + " is not on its last face");
}

}  // namespace

StraightGeodesicResult trace_straight_geodesic(const Mesh& mesh, const SurfacePoint& start, double polar_angle,
                                               double length, const StraightGeodesicOptions& options) {
    const SurfacePoint p = mesh.canonical(start);
    if (!std::isfinite(polar_angle))
        throw InvalidInput("straight geodesic: polar angle " + std::to_string(polar_angle) + " is not finite");
    if (!std::isfinite(length) || length < 0.0)
        throw InvalidInput("straight geodesic: length " + std::to_string(length) + " is not a finite length >= 0");
    if (p.kind == PointKind::vertex) {
        if (mesh.outgoing(p.vertex) < 0)
            throw InvalidInput("straight geodesic: vertex " + std::to_string(p.vertex) + " has no face");
        if (!mesh.is_manifold_vertex(p.vertex))
            throw InvalidInput("straight geodesic: vertex " + std::to_string(p.vertex) +
                               " is not manifold: its polar angles are undefined");
    }

    StraightGeodesicResult result;
    result.path.push_back(p);
    result.end = p;
    result.arrival_angle = std::numeric_limits<double>::quiet_NaN();
    if (length == 0.0) return result;

    // Lay out the first face and the direction in it.
    int h = -1;
    Eigen::Vector2d x = Eigen::Vector2d::Zero(), d = Eigen::Vector2d::UnitX();
    StartOn start_on = StartOn::interior;
    switch (p.kind) {
        case PointKind::vertex: {
            const double theta = wrap_angle(polar_angle, mesh.cone_angle(p.vertex));
            for (int e : mesh.outgoing_halfedges(p.vertex))
                if (mesh.polar_angle(e) <= theta && (h < 0 || mesh.polar_angle(e) > mesh.polar_angle(h))) h = e;
            const double phi = std::clamp(theta - mesh.polar_angle(h), 0.0, mesh.corner_angle(h));
            x = Eigen::Vector2d::Zero();
            d = Eigen::Vector2d(std::cos(phi), std::sin(phi));
            start_on = StartOn::corner0;
            break;
        }
        case PointKind::edge: {
            const double theta = wrap_angle(polar_angle, k_two_pi);
            const int ab = mesh.find_halfedge(p.edge_v0, p.edge_v1), ba = mesh.find_halfedge(p.edge_v1, p.edge_v0);
            double phi;
            if (theta <= k_pi && ab >= 0) {
                h = ab;
                phi = theta;
            } else if (theta > k_pi && ba >= 0) {
                h = ba;
                phi = theta - k_pi;
            } else if ((theta == 0.0 || theta == k_pi) && ba >= 0) {
                h = ba;  // along a boundary edge whose only face is on the other side
                phi = k_pi - theta;
            } else {
                result.stopped_at_boundary = true;
                return result;
            }
            const double s = (h == ab ? p.t : 1.0 - p.t) * mesh.length(h);
            x = Eigen::Vector2d(s, 0.0);
            d = Eigen::Vector2d(std::cos(phi), std::sin(phi));
            start_on = StartOn::edge0;
            break;
        }
        case PointKind::face: {
            h = 3 * p.face;
            x = halfedge_coordinates(mesh, h, p);
            const Eigen::Vector2d r = -x;  // towards triangle(f)[0], the reference direction
            if (!(r.norm() > 0.0))
                throw NumericalError("straight geodesic: face point " + geodesic::to_spec(p) + " is on a vertex");
            const double theta = wrap_angle(polar_angle, k_two_pi);
            const Eigen::Vector2d u = r.normalized();
            d = Eigen::Vector2d(std::cos(theta) * u.x() - std::sin(theta) * u.y(),
                                std::sin(theta) * u.x() + std::cos(theta) * u.y());
            start_on = StartOn::interior;
            break;
        }
    }

    double remaining = length, walked = 0.0;
    std::size_t crossings = 0;
    Frame frame(mesh, h);
    for (;;) {
        const Exit exit = find_exit(frame, x, d, start_on);
        const int k = exit.k, k1 = (k + 1) % 3;
        const Eigen::Vector2d& from = frame.c[k];
        const Eigen::Vector2d& to = frame.c[k1];
        const bool at_from = exit.t <= k_snap, at_to = exit.t >= 1.0 - k_snap;
        const Eigen::Vector2d hit = at_from ? from : at_to ? to : Eigen::Vector2d((1.0 - exit.t) * from + exit.t * to);
        const double dist = std::max(0.0, d.dot(hit - x));
        const double slack = k_snap * (to - from).norm();

        SurfacePoint end;
        Eigen::Vector2d y;
        bool done = true;
        if (remaining < dist - slack) {
            y = x + remaining * d;
            end = face_point(mesh, frame, y);
            walked = length;
        } else {
            // The ray reaches the edge (or its vertex); it stops there unless it can cross to a face beyond.
            const bool reaches_all = remaining <= dist + slack;
            y = hit;
            if (at_from || at_to) {
                end = SurfacePoint::at_vertex(frame.vertex(mesh, at_from ? k : k1));
                result.stopped_at_vertex = !reaches_all;
            } else {
                end = edge_point(mesh, frame, k, exit.t);
                if (!reaches_all) {
                    const int twin = mesh.twin(frame.edge(k));
                    if (twin < 0) {
                        result.stopped_at_boundary = true;
                    } else {
                        // Unfold the next face across the edge: rotate by π about the edge's midpoint.
                        const Eigen::Vector2d w = in_edge_frame(frame, k, d);
                        walked += dist;
                        remaining -= dist;
                        result.path.push_back(end);
                        if (++crossings > options.max_crossings)
                            throw NumericalError("straight geodesic: crossed more than " +
                                                 std::to_string(options.max_crossings) + " fine faces");
                        frame = Frame(mesh, twin);
                        x = Eigen::Vector2d((1.0 - exit.t) * mesh.length(twin), 0.0);
                        d = Eigen::Vector2d(-w.x(), std::max(0.0, -w.y())).normalized();
                        start_on = StartOn::edge0;
                        done = false;
                    }
                }
            }
            if (done) walked = reaches_all ? length : walked + dist;
        }
        if (!done) continue;

        if (end != result.path.back()) result.path.push_back(end);
        result.end = end;
        result.length = walked;
        if (result.path.size() > 1) result.arrival_angle = polar_angle_in_frame(mesh, frame, end, y, -d);
        return result;
    }
}

}  // namespace geotri

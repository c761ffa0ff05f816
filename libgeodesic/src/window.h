#pragma once
// Window arithmetic: private to libgeodesic.
//
// Every halfedge h has a plane frame: tail(h) at (0,0), head(h) at (L,0), and face(h), the face that a window on h
// is about to cross, on the side y >= 0. A window on h is an interval [b0, b1] of the edge on which the distance
// to the nearest source is sigma + |S - x|, for a pseudo-source S unfolded into that frame on the side y <= 0.

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <utility>

namespace geotri::geodesic::detail {

constexpr double k_infinity = std::numeric_limits<double>::infinity();

/// Windows are looked up by id all over memory (edge lists, the queue): one cache line each. Where each stands in
/// the propagation (pending, propagated, merged, retired) is kept apart, in the propagation's window flags.
struct alignas(64) Window {
    // Built in place, field by field, by its constructor: a window assembled on the stack and then copied was
    // loaded back in wider pieces than it was stored in, which stalled every copy.
    Window(double b0_, double b1_, double sx_, double sy_, double sigma_, int halfedge_, int parent_, int origin_,
           int next_on_edge_, int next_pending_)
        : b0(b0_), b1(b1_), sx(sx_), sy(sy_), sigma(sigma_), halfedge(halfedge_), parent(parent_), origin(origin_),
          next_on_edge(next_on_edge_), next_pending(next_pending_) {}

    double b0;
    double b1;
    double sx;
    double sy;
    double sigma;
    int halfedge;
    int parent;        ///< the window this one was propagated from, or -1 if a vertex or a source emitted it
    int origin;        ///< the emitting vertex (>= 0) or -1 - source index; shared by every descendant
    int next_on_edge;  ///< next window on the same halfedge, or -1
    int next_pending = -1;  ///< next window on the same halfedge still to cross its face, or -1

    Eigen::Vector2d source() const { return {sx, sy}; }

    double value_at(double x) const {
        const double dx = x - sx;
        return sigma + std::sqrt(dx * dx + sy * sy);
    }

    double distance_to(const Eigen::Vector2d& p) const { return sigma + (p - source()).norm(); }

    /// The least distance that a window with these values gives anywhere: nothing propagated from it can be nearer.
    static double least_value(double b0, double b1, double sx, double sy, double sigma) {
        if (sx >= b0 && sx <= b1) return sigma + std::abs(sy);  // what the square root gives, exactly, without it
        const double dx = sx < b0 ? b0 - sx : sx - b1;
        return sigma + std::sqrt(dx * dx + sy * sy);
    }

    /// Where the straight line from S to p (p on the face side, y >= 0) crosses the edge line y = 0.
    double crossing_of(const Eigen::Vector2d& p) const {
        if (p.y() <= 0.0) return p.x();
        return sx + (p.x() - sx) * (-sy) / (p.y() - sy);
    }
};

/// The distance that a window gives along its edge line: sigma + sqrt((x - s)^2 + y^2). The windows on the two
/// halfedges of one edge compare in one frame, with s mirrored.
struct EdgeProfile {
    double s;
    double y;
    double sigma;
    double at(double x) const {
        const double dx = x - s;
        return sigma + std::sqrt(dx * dx + y * y);
    }
};

/// A window's values at the ends of its interval, as trimming moves them.
struct EndValues {
    double at_b0;
    double at_b1;
};

/// The points of the open interval (lo, hi) where two profiles may be equal, sorted: at most two, the real roots of
/// the quadratic that squaring the equation gives (squaring may add a root where they differ; callers test the
/// sign between the roots, so an extra root only splits an interval of one sign).
inline int profile_crossings(const EdgeProfile& a, const EdgeProfile& b, double lo, double hi, double roots[2]) {
    // sqrt(u) - sqrt(w) = d with u = (x - a.s)^2 + a.y^2, w = (x - b.s)^2 + b.y^2, d = b.sigma - a.sigma.
    // u - w = alpha x + beta, so (alpha x + beta - d^2)^2 = 4 d^2 w.
    const double d = b.sigma - a.sigma;
    const double d2 = d * d;
    const double alpha = 2.0 * (b.s - a.s);
    const double gamma = a.s * a.s - b.s * b.s + a.y * a.y - b.y * b.y - d2;
    const double qa = alpha * alpha - 4.0 * d2;
    const double qb = 2.0 * alpha * gamma + 8.0 * d2 * b.s;
    const double qc = gamma * gamma - 4.0 * d2 * (b.s * b.s + b.y * b.y);
    double candidates[2];
    int found = 0;
    const double scale = std::abs(alpha * alpha) + 4.0 * d2;
    if (std::abs(qa) <= 1e-12 * scale) {
        if (qb != 0.0) candidates[found++] = -qc / qb;
    } else {
        const double discriminant = qb * qb - 4.0 * qa * qc;
        if (discriminant >= 0.0) {
            // The numerically stable pair of roots.
            const double q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
            if (q != 0.0) candidates[found++] = qc / q;
            candidates[found++] = q / qa;
        } else {
            // Where the quadratic comes nearest to zero. Equal sigmas (every window of one pseudo-source) make it
            // a perfect square, whose double root, where the profiles cross, rounding leaves on either side of a
            // zero discriminant: without this candidate such a crossing went unseen, and a window lost the part
            // where it is the shorter one (1.5e-10 relative on a vertex of cad/turbineblade.ply).
            candidates[found++] = -qb / (2.0 * qa);
        }
    }
    int count = 0;
    for (int i = 0; i < found; ++i)
        if (candidates[i] > lo && candidates[i] < hi) roots[count++] = candidates[i];
    if (count == 2 && roots[0] > roots[1]) std::swap(roots[0], roots[1]);
    return count;
}

inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The coordinates of the point (qx, qy) in the frame whose origin is (px, py) and whose x axis is the unit vector
/// (ex, ey), its y axis that turned by +90°.
struct FramePoint {
    double x;
    double y;
};
inline FramePoint to_frame(double qx, double qy, double px, double py, double ex, double ey) {
    const double rx = qx - px, ry = qy - py;
    return {rx * ex + ry * ey, ex * ry - ey * rx};
}

/// The parameter u at which the ray from the source (sx, sy) through the edge point (x, 0) meets the line
/// (px, py) + u·(ex, ey), with (ex, ey) a unit vector. Not finite when the two are parallel. In scalars: built as
/// 2-vectors, (x, 0) went through memory in two halves and was loaded back whole, a stall at every call.
inline double ray_crossing(double sx, double sy, double x, double px, double py, double ex, double ey) {
    const double dx = x - sx, dy = 0.0 - sy;
    const double ax = sx - px, ay = sy - py;
    return (ax * dy - ay * dx) / (ex * dy - ey * dx);
}

}  // namespace geotri::geodesic::detail

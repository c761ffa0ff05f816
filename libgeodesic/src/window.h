#pragma once
// Window arithmetic: private to libgeodesic.
//
// Every halfedge h has a plane frame: tail(h) at (0,0), head(h) at (L,0), and face(h), the face that a window on h
// is about to cross, on the side y >= 0. A window on h is an interval [b0, b1] of the edge on which the distance
// to the nearest source is sigma + |S - x|, for a pseudo-source S unfolded into that frame on the side y <= 0.

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace geotri::geodesic::detail {

constexpr double k_infinity = std::numeric_limits<double>::infinity();

struct Window {
    double b0;
    double b1;
    double sx;
    double sy;
    double sigma;
    int halfedge;
    int parent;        ///< the window this one was propagated from, or -1 if a vertex or a source emitted it
    int origin;        ///< the emitting vertex (>= 0) or -1 - source index; shared by every descendant
    int next_on_edge;  ///< next window on the same halfedge, or -1

    Eigen::Vector2d source() const { return {sx, sy}; }

    double value_at(double x) const {
        const double dx = x - sx;
        return sigma + std::sqrt(dx * dx + sy * sy);
    }

    double distance_to(const Eigen::Vector2d& p) const { return sigma + (p - source()).norm(); }

    /// The least distance that this window gives anywhere: nothing propagated from it can be nearer.
    double lower_bound() const {
        const double dx = sx < b0 ? b0 - sx : (sx > b1 ? sx - b1 : 0.0);
        return sigma + std::sqrt(dx * dx + sy * sy);
    }

    /// Where the straight line from S to p (p on the face side, y >= 0) crosses the edge line y = 0.
    double crossing_of(const Eigen::Vector2d& p) const {
        if (p.y() <= 0.0) return p.x();
        return sx + (p.x() - sx) * (-sy) / (p.y() - sy);
    }
};

inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The parameter u at which the line through `from` and `through` meets the line P + u·e (e a unit vector).
/// Not finite when the two lines are parallel.
inline double line_crossing(const Eigen::Vector2d& from, const Eigen::Vector2d& through, const Eigen::Vector2d& p,
                            const Eigen::Vector2d& e) {
    const Eigen::Vector2d d = through - from;
    return cross(from - p, d) / cross(e, d);
}

/// Coordinates of q in the frame whose origin is `origin` and whose x axis is the unit vector e (y axis e rotated
/// by +90°).
inline Eigen::Vector2d to_frame(const Eigen::Vector2d& q, const Eigen::Vector2d& origin, const Eigen::Vector2d& e) {
    const Eigen::Vector2d r = q - origin;
    return {r.dot(e), cross(e, r)};
}

}  // namespace geotri::geodesic::detail

#pragma once
// Distances between points and segments in the plane frame of one fine face: how validate() and the local
// operations decide that two polylines meet.

#include <Eigen/Core>

#include <algorithm>

namespace geotri::detail {

inline double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

inline double point_segment_distance(const Eigen::Vector2d& x, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d d = b - a;
    const double dd = d.squaredNorm();
    const double s = dd > 0.0 ? std::clamp((x - a).dot(d) / dd, 0.0, 1.0) : 0.0;
    return (a + s * d - x).norm();
}

/// For segments a and b whose orientation tests say that they cross (a's ends on either side of b's line, with
/// orientations o0 and o1 to b, and b's on either side of a's), whether they do. For segments on one line (the
/// pieces of a bisected geodesic) the signs are rounding noise and can look like a crossing: it is one only where
/// the point where a meets b's line lies on b.
inline bool crossing_confirmed(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                               const Eigen::Vector2d& b1, double o0, double o1) {
    const Eigen::Vector2d at = a0 + (o0 / (o0 - o1)) * (a1 - a0);
    const Eigen::Vector2d d = b1 - b0;
    const double along = (at - b0).dot(d) / d.squaredNorm();
    return along >= 0.0 && along <= 1.0;
}

/// 0 when the segments cross properly, else the smallest distance from an end of one to the other.
inline double segment_distance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                               const Eigen::Vector2d& b1) {
    const double o1 = cross(a1 - a0, b0 - a0), o2 = cross(a1 - a0, b1 - a0);
    const double o3 = cross(b1 - b0, a0 - b0), o4 = cross(b1 - b0, a1 - b0);
    if (((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0)) &&
        crossing_confirmed(a0, a1, b0, b1, o3, o4))
        return 0.0;
    return std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                     point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
}

}  // namespace geotri::detail

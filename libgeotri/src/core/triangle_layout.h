#pragma once
// A triangle laid out in the plane from its three side lengths alone: how flips and refinement read the corners of a
// geodesic triangle's intrinsic layout.

#include <algorithm>
#include <cmath>

namespace geotri::detail {

/// The angle opposite side `opposite` in a triangle with sides `opposite`, `s`, `t` (law of cosines), clamped for
/// side lengths that break the triangle inequality by rounding.
inline double opposite_angle(double opposite, double s, double t) {
    const double cosine = (s * s + t * t - opposite * opposite) / (2.0 * s * t);
    return std::acos(std::clamp(cosine, -1.0, 1.0));
}

}  // namespace geotri::detail

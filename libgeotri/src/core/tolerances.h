#pragma once
// The tolerances of validity (DESIGN.md §1), defined once for validate(), the local checks and the overlay, which
// must all judge alike.

namespace geotri::detail {

/// Two points within this many times the local fine edge length are the same point: geodesics that come this close
/// meet (condition 3), and a point of a fine edge this close to one of its ends is at that vertex of T (the overlay
/// cuts there, condition 4).
constexpr double k_meet_tolerance = 1e-12;

}  // namespace geotri::detail

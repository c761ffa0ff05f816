#pragma once
// The tolerances of validity (DESIGN.md §1), defined once for validate() and for the local checks that must judge
// as it does.

namespace geotri::detail {

/// Two points of condition 3 within this many times the local fine edge length are the same point: geodesics that
/// come this close meet.
constexpr double k_meet_tolerance = 1e-12;

}  // namespace geotri::detail

#pragma once
// The sign of a polynomial over the reference triangle, proven from its Bernstein coefficients (Johnen, Remacle
// and Geuzaine, "Geometrical validity of curvilinear finite elements", JCP 2013): positive where every coefficient
// of a piece is, not positive where a value at a piece's corner is, otherwise the piece is subdivided.

#include <geotri/curved_elements.h>

#include <limits>
#include <vector>

namespace geotri::detail {

/// What the Bernstein coefficients of a polynomial prove about its sign over the reference triangle, with
/// subdivision where they do not decide; and bounds of its minimum and maximum there.
struct SignBounds {
    Certification verdict = Certification::valid;
    double min_lower = std::numeric_limits<double>::infinity();   ///< <= the minimum
    double max_upper = -std::numeric_limits<double>::infinity();  ///< >= the maximum
    double min_value = std::numeric_limits<double>::infinity();   ///< a value taken: >= the minimum
    double max_value = -std::numeric_limits<double>::infinity();  ///< a value taken: <= the maximum
};

/// Positive everywhere when every coefficient of a piece is; not positive when a value at a piece's corner (its
/// corner coefficient, exact) is <= 0; otherwise the piece is split in four, at most `max_depth` times.
SignBounds bound_sign(const std::vector<double>& coefficients, int degree, int max_depth);

}  // namespace geotri::detail

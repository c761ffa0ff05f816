// The root finding behind window trimming (detail::profile_crossings), tested directly: a crossing that it misses
// only shows as a rare distance a hair too long, which the oracles on whole meshes seldom meet.

#include "window.h"

#include <gtest/gtest.h>

#include <cmath>

namespace geotri::geodesic::detail {
namespace {

// Where two profiles with the same sigma are equal: the points of the edge line as far from one source as from the
// other, worked out in long double without squaring anything.
double equal_sigma_crossing(const EdgeProfile& a, const EdgeProfile& b) {
    const long double sa = a.s, ya = a.y, sb = b.s, yb = b.y;
    return static_cast<double>((sa * sa + ya * ya - sb * sb - yb * yb) / (2.0L * (sa - sb)));
}

bool has_root_near(const double* roots, int count, double x, double tolerance) {
    for (int i = 0; i < count; ++i)
        if (std::abs(roots[i] - x) <= tolerance) return true;
    return false;
}

TEST(ProfileCrossings, finds_where_two_unfoldings_of_one_saddle_cross) {
    // Two unfoldings of one saddle (so the same sigma) that met on an edge of cad/turbineblade.ply. The squared
    // equation is then a perfect square, and rounding made its discriminant negative: no crossing was reported, the
    // first window lost all of the overlap, and a vertex behind it got a distance 1.5e-10 (relative) too long.
    const EdgeProfile a{0.96691010889809892, -0.76562039761116574, 29.667346006121598};
    const EdgeProfile b{0.9663720533986182, -0.76629455576008787, 29.667346006121598};
    const double lo = 0.0065253873294068079, hi = 0.0070329461631012556;
    const double crossing = equal_sigma_crossing(a, b);
    ASSERT_GT(crossing, lo);
    ASSERT_LT(crossing, hi);
    ASSERT_GT(a.at(lo), b.at(lo));  // a is the longer one at lo, the shorter one at hi
    ASSERT_LT(a.at(hi), b.at(hi));
    double roots[2];
    const int count = profile_crossings(a, b, lo, hi, roots);
    // A double root found through a square root of a discriminant that rounding left near zero is good to about
    // the square root of the rounding: 1e-6 of the overlap is still a sliver.
    EXPECT_TRUE(has_root_near(roots, count, crossing, 1e-6 * (hi - lo))) << count << " roots";
}

TEST(ProfileCrossings, finds_the_crossing_of_equal_sigma_profiles_whatever_the_rounding) {
    // Pairs of sources ever closer to each other, one moved from the other in every direction, below a unit edge:
    // where a pair crosses inside the edge, the crossing must be among the candidates.
    int checked = 0;
    for (double offset : {1e-2, 1e-4, 1e-6, 1e-8}) {
        for (int k = 0; k < 50; ++k) {
            const double s = 0.1 + 0.016 * k, y = -0.3 - 0.01 * k, sigma = 0.37 * k;
            const EdgeProfile a{s, y, sigma};
            const EdgeProfile b{s + offset * std::cos(k), y + offset * std::sin(k), sigma};
            if (a.s == b.s) continue;
            const double crossing = equal_sigma_crossing(a, b);
            if (!(crossing > 0.0 && crossing < 1.0)) continue;
            double roots[2];
            const int count = profile_crossings(a, b, 0.0, 1.0, roots);
            // Good to about the square root of the rounding (see above), and the crossing itself moves with the
            // rounding of the sources' squares over their distance.
            const double tolerance = 1e-7 + 1e-13 / std::abs(a.s - b.s);
            EXPECT_TRUE(has_root_near(roots, count, crossing, tolerance))
                << "offset " << offset << ", k " << k << ": " << count << " roots";
            ++checked;
        }
    }
    EXPECT_GT(checked, 50);
}

}  // namespace
}  // namespace geotri::geodesic::detail

#pragma once
// The best triangulation of a small polygon by dynamic programming: what small-polygon reconnection does with
// geodesic diagonals, and what refinement's planar estimate of it does with straight ones.

#include <cstddef>
#include <limits>
#include <vector>

namespace geotri::detail {

/// Over the triangulations of a polygon with corners 0..k-1, the one whose smallest value(i, m, j) (i < m < j, a
/// triangle's figure of merit, -infinity when it may not be used) is largest, by dynamic programming over the
/// sub-polygons i..j (O(k³) calls). Returns that smallest value, -infinity when there is no triangulation; apex
/// (k·k) gets, for each sub-polygon i..j, the corner m of its triangle on i-j.
template <class Value>
double best_polygon_triangulation(std::size_t k, Value value, std::vector<std::size_t>& apex) {
    constexpr double none = -std::numeric_limits<double>::infinity();
    std::vector<double> best(k * k, none);
    apex.assign(k * k, 0);
    for (std::size_t i = 0; i + 1 < k; ++i) best[i * k + i + 1] = std::numeric_limits<double>::infinity();
    for (std::size_t span = 2; span < k; ++span)
        for (std::size_t i = 0; i + span < k; ++i) {
            const std::size_t j = i + span;
            for (std::size_t m = i + 1; m < j; ++m) {
                double candidate = std::min(best[i * k + m], best[m * k + j]);
                if (candidate <= best[i * k + j]) continue;  // value() cannot raise it
                candidate = std::min(candidate, value(i, m, j));
                if (candidate > best[i * k + j]) {
                    best[i * k + j] = candidate;
                    apex[i * k + j] = m;
                }
            }
        }
    return best[k - 1];
}

}  // namespace geotri::detail

#include "curved/sign_bounds.h"

#include "curved/bernstein_triangle.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>

namespace geotri::detail {

SignBounds bound_sign(const std::vector<double>& coefficients, int degree, int max_depth) {
    struct Piece {
        std::array<Eigen::Vector2d, 3> corners;
        int depth;
    };
    SignBounds bounds;
    std::vector<Piece> pieces{{{Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(0.0, 1.0)}, 0}};
    while (!pieces.empty()) {
        const Piece piece = pieces.back();
        pieces.pop_back();
        const std::vector<double> c =
            piece.depth == 0 ? coefficients
                             : restrict_to_triangle(coefficients, degree, piece.corners[0], piece.corners[1],
                                                    piece.corners[2]);
        for (const std::size_t corner : {multi_index_position(0, 0), multi_index_position(degree, 0),
                                         multi_index_position(0, degree)}) {
            bounds.min_value = std::min(bounds.min_value, c[corner]);
            bounds.max_value = std::max(bounds.max_value, c[corner]);
        }
        const auto [lowest, highest] = std::minmax_element(c.begin(), c.end());
        bounds.max_upper = std::max(bounds.max_upper, *highest);
        if (bounds.min_value <= 0.0) {
            bounds.verdict = Certification::invalid;
            bounds.min_lower = std::min(bounds.min_lower, *lowest);
            return bounds;
        }
        if (*lowest > 0.0 || piece.depth >= max_depth) {
            if (!(*lowest > 0.0)) bounds.verdict = Certification::undecided;
            bounds.min_lower = std::min(bounds.min_lower, *lowest);
            continue;
        }
        for (const auto& child : split_in_four(piece.corners[0], piece.corners[1], piece.corners[2]))
            pieces.push_back({child, piece.depth + 1});
    }
    return bounds;
}

}  // namespace geotri::detail

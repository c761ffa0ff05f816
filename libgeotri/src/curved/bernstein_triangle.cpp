#include "curved/bernstein_triangle.h"

#include <geodesic/errors.h>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <string>
#include <utility>

namespace geotri::detail {

namespace {

/// The degrees that the tables below serve: elements up to order 8, Jacobians up to degree 14.
constexpr int k_max_degree = 16;

double factorial(int n) {
    double f = 1.0;
    for (int k = 2; k <= n; ++k) f *= k;
    return f;
}

/// n! / (i! j! k!).
double multinomial(int n, const std::array<int, 3>& index) {
    return factorial(n) / (factorial(index[0]) * factorial(index[1]) * factorial(index[2]));
}

/// Barycentric coordinates of (u, v) in the reference triangle.
std::array<double, 3> barycentric(const Eigen::Vector2d& p) { return {1.0 - p.x() - p.y(), p.x(), p.y()}; }

void require_degree(int n, const char* what) {
    if (n < 0 || n > k_max_degree)
        throw InvalidInput(std::string(what) + ": degree " + std::to_string(n) + " is outside [0, " +
                           std::to_string(k_max_degree) + "]");
}

/// The inverse of the matrix of the Bernstein basis of degree n at the equispaced nodes, made once per degree.
const Eigen::MatrixXd& lagrange_to_bernstein(int n) {
    static const std::array<Eigen::MatrixXd, k_max_degree + 1> inverses = [] {
        std::array<Eigen::MatrixXd, k_max_degree + 1> made;
        for (int degree = 0; degree <= k_max_degree; ++degree) {
            const std::vector<std::array<int, 3>> indices = multi_indices(degree);
            const auto size = static_cast<Eigen::Index>(indices.size());
            Eigen::MatrixXd values(size, size);
            for (Eigen::Index row = 0; row < size; ++row) {
                const std::array<double, 3> l =
                    degree == 0 ? std::array<double, 3>{1.0, 0.0, 0.0}
                                : barycentric(node_of(indices[static_cast<std::size_t>(row)], degree));
                for (Eigen::Index column = 0; column < size; ++column) {
                    const std::array<int, 3>& a = indices[static_cast<std::size_t>(column)];
                    double b = multinomial(degree, a);
                    for (int c = 0; c < 3; ++c)
                        for (int p = 0; p < a[static_cast<std::size_t>(c)]; ++p) b *= l[static_cast<std::size_t>(c)];
                    values(row, column) = b;
                }
            }
            made[static_cast<std::size_t>(degree)] = values.fullPivLu().inverse();
        }
        return made;
    }();
    return inverses[static_cast<std::size_t>(n)];
}

/// One step of de Casteljau's algorithm with barycentric weights l: the coefficients `c` of degree m + 1 to `next`
/// of degree m. The buffers are the caller's, so that the steps of a blossom allocate nothing.
template <class Value>
void casteljau_step(const Value* c, int m, const std::array<double, 3>& l, Value* next) {
    for (int s = 0; s <= m; ++s)
        for (int k = 0; k <= s; ++k) {
            const int j = s - k;
            // (i, j, k) of degree m takes (i + 1, j, k), (i, j + 1, k) and (i, j, k + 1) of degree m + 1.
            next[multi_index_position(j, k)] = l[0] * c[multi_index_position(j, k)] +
                                               l[1] * c[multi_index_position(j + 1, k)] +
                                               l[2] * c[multi_index_position(j, k + 1)];
        }
}

/// The weights of the product of two Bernstein polynomials of degree m, for every pair of their multi-indices:
/// B_a B_b = C(m, a) C(m, b) / C(2m, a + b) B_(a + b). Made once per degree.
const std::vector<double>& product_weights(int m) {
    static const std::array<std::vector<double>, k_max_degree / 2 + 1> tables = [] {
        std::array<std::vector<double>, k_max_degree / 2 + 1> made;
        for (int degree = 0; degree <= k_max_degree / 2; ++degree) {
            const std::vector<std::array<int, 3>> lower = multi_indices(degree);
            std::vector<double> weight(lower.size());
            for (std::size_t a = 0; a < lower.size(); ++a) weight[a] = multinomial(degree, lower[a]);
            std::vector<double>& table = made[static_cast<std::size_t>(degree)];
            for (std::size_t a = 0; a < lower.size(); ++a)
                for (std::size_t b = 0; b < lower.size(); ++b) {
                    const std::array<int, 3> sum{lower[a][0] + lower[b][0], lower[a][1] + lower[b][1],
                                                 lower[a][2] + lower[b][2]};
                    table.push_back(weight[a] * weight[b] / multinomial(2 * degree, sum));
                }
        }
        return made;
    }();
    return tables[static_cast<std::size_t>(m)];
}

}  // namespace

std::vector<std::array<int, 3>> multi_indices(int n) {
    std::vector<std::array<int, 3>> indices;
    indices.reserve(coefficient_count(n));
    for (int s = 0; s <= n; ++s)
        for (int k = 0; k <= s; ++k) indices.push_back({n - s, s - k, k});
    return indices;
}

template <class Value>
std::vector<Value> bernstein_from_lagrange(const std::vector<Value>& values, int n) {
    require_degree(n, "bernstein_from_lagrange");
    if (values.size() != coefficient_count(n))
        throw InvalidInput("bernstein_from_lagrange: " + std::to_string(values.size()) + " values for degree " +
                           std::to_string(n));
    const Eigen::MatrixXd& inverse = lagrange_to_bernstein(n);
    std::vector<Value> coefficients(values.size());
    for (std::size_t row = 0; row < values.size(); ++row) {
        Value sum = inverse(static_cast<Eigen::Index>(row), 0) * values[0];
        for (std::size_t column = 1; column < values.size(); ++column)
            sum += inverse(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(column)) * values[column];
        coefficients[row] = sum;
    }
    return coefficients;
}

template <class Value>
std::vector<Value> restrict_to_triangle(const std::vector<Value>& coefficients, int n, const Eigen::Vector2d& a,
                                        const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    require_degree(n, "restrict_to_triangle");
    const std::array<std::array<double, 3>, 3> corners{barycentric(a), barycentric(b), barycentric(c)};
    const std::vector<std::array<int, 3>> indices = multi_indices(n);
    std::vector<Value> restricted;
    restricted.reserve(indices.size());
    std::vector<Value> level(coefficients.size()), next(coefficients.size());
    for (const std::array<int, 3>& index : indices) {
        // The blossom at (a^i, b^j, c^k): de Casteljau with a different argument at each step.
        std::copy(coefficients.begin(), coefficients.end(), level.begin());
        int degree = n;
        for (int corner = 0; corner < 3; ++corner)
            for (int r = 0; r < index[static_cast<std::size_t>(corner)]; ++r) {
                casteljau_step(level.data(), --degree, corners[static_cast<std::size_t>(corner)], next.data());
                std::swap(level, next);
            }
        restricted.push_back(level[0]);
    }
    return restricted;
}

template <class Value>
Value evaluate(const std::vector<Value>& coefficients, int n, const Eigen::Vector2d& point) {
    require_degree(n, "evaluate");
    const std::array<double, 3> l = barycentric(point);
    std::vector<Value> level = coefficients, next(coefficients.size());
    for (int degree = n - 1; degree >= 0; --degree) {
        casteljau_step(level.data(), degree, l, next.data());
        std::swap(level, next);
    }
    return level[0];
}

std::vector<double> jacobian_coefficients(const std::vector<Eigen::Vector3d>& x, int n, const Eigen::Vector3d& normal) {
    if (n < 1 || 2 * (n - 1) > k_max_degree)
        throw InvalidInput("jacobian_coefficients: degree " + std::to_string(n) + " is outside [1, " +
                           std::to_string(k_max_degree / 2 + 1) + "]");
    const int m = n - 1;
    const std::vector<std::array<int, 3>> lower = multi_indices(m);
    std::vector<Eigen::Vector3d> du(lower.size()), dv(lower.size());
    for (std::size_t a = 0; a < lower.size(); ++a) {
        const int j = lower[a][1], k = lower[a][2];
        const Eigen::Vector3d& at_0 = x[multi_index_position(j, k)];
        du[a] = n * (x[multi_index_position(j + 1, k)] - at_0);
        dv[a] = n * (x[multi_index_position(j, k + 1)] - at_0);
    }
    const std::vector<double>& weight = product_weights(m);
    std::vector<double> jacobian(coefficient_count(2 * m), 0.0);
    for (std::size_t a = 0; a < lower.size(); ++a)
        for (std::size_t b = 0; b < lower.size(); ++b)
            jacobian[multi_index_position(lower[a][1] + lower[b][1], lower[a][2] + lower[b][2])] +=
                weight[a * lower.size() + b] * du[a].cross(dv[b]).dot(normal);
    return jacobian;
}

std::array<std::array<Eigen::Vector2d, 3>, 4> split_in_four(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                                             const Eigen::Vector2d& c) {
    const Eigen::Vector2d ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    return {{{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}}};
}

template std::vector<double> bernstein_from_lagrange(const std::vector<double>&, int);
template std::vector<Eigen::Vector3d> bernstein_from_lagrange(const std::vector<Eigen::Vector3d>&, int);
template std::vector<double> restrict_to_triangle(const std::vector<double>&, int, const Eigen::Vector2d&,
                                                  const Eigen::Vector2d&, const Eigen::Vector2d&);
template std::vector<Eigen::Vector3d> restrict_to_triangle(const std::vector<Eigen::Vector3d>&, int,
                                                           const Eigen::Vector2d&, const Eigen::Vector2d&,
                                                           const Eigen::Vector2d&);
template double evaluate(const std::vector<double>&, int, const Eigen::Vector2d&);
template Eigen::Vector3d evaluate(const std::vector<Eigen::Vector3d>&, int, const Eigen::Vector2d&);

}  // namespace geotri::detail

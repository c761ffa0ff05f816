#pragma once
// Polynomials on a triangle in the Bernstein basis: what certifies a curved element. A polynomial of degree n holds
// one coefficient per multi-index (i, j, k), i + j + k = n, and lies in the convex hull of its coefficients over the
// triangle: their minimum and maximum bound it, and subdividing the triangle tightens those bounds.
//
// Barycentric coordinates (l0, l1, l2) of the reference triangle with corners (0,0), (1,0), (0,1): l1 = u, l2 = v.

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <vector>

namespace geotri::detail {

/// The multi-indices (i, j, k) of degree n, in the order that every coefficient vector here uses: by j + k
/// (the distance from corner 0), then by k. Index of (i, j, k): (j + k)(j + k + 1)/2 + k.
std::vector<std::array<int, 3>> multi_indices(int n);

/// The position of (i, j, k) among multi_indices(i + j + k).
inline std::size_t multi_index_position(int j, int k) {
    const int s = j + k;
    return static_cast<std::size_t>(s * (s + 1) / 2 + k);
}

/// The number of coefficients of degree n: (n + 1)(n + 2)/2.
inline std::size_t coefficient_count(int n) { return static_cast<std::size_t>((n + 1) * (n + 2) / 2); }

/// The point (u, v) of multi-index (i, j, k) of degree n: (j/n, k/n), the equispaced Lagrange node.
inline Eigen::Vector2d node_of(const std::array<int, 3>& index, int n) {
    return {static_cast<double>(index[1]) / n, static_cast<double>(index[2]) / n};
}

/// Bernstein coefficients of degree n of the polynomial whose values at the equispaced nodes (node_of(), in the
/// order of multi_indices(n)) are `values`. Exact up to rounding: the matrix of Bernstein values at the nodes is
/// inverted once per degree.
template <class Value>
std::vector<Value> bernstein_from_lagrange(const std::vector<Value>& values, int n);

/// The coefficients of the same polynomial on the triangle with corners a, b, c (points of the reference plane,
/// in that order as its corners 0, 1, 2): the blossom of the polynomial evaluated at (a^i, b^j, c^k). Subdividing
/// a triangle, or restricting a polynomial to any triangle, is this.
template <class Value>
std::vector<Value> restrict_to_triangle(const std::vector<Value>& coefficients, int n, const Eigen::Vector2d& a,
                                        const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// The polynomial's value at (u, v), by de Casteljau.
template <class Value>
Value evaluate(const std::vector<Value>& coefficients, int n, const Eigen::Vector2d& point);

/// The Bernstein coefficients, of degree 2(n - 1), of J(u, v) = (x_u × x_v) · normal, for x of degree n >= 1 with
/// Bernstein coefficients `x` (3D points).
std::vector<double> jacobian_coefficients(const std::vector<Eigen::Vector3d>& x, int n, const Eigen::Vector3d& normal);

/// The four triangles of the midpoint subdivision of the triangle (a, b, c), each with the orientation of the whole.
std::array<std::array<Eigen::Vector2d, 3>, 4> split_in_four(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                                             const Eigen::Vector2d& c);

}  // namespace geotri::detail

#include <geotri/curved_elements.h>

#include "curved/bernstein_triangle.h"

#include <array>
#include <vector>

namespace geotri {

std::vector<Eigen::Vector3d> bezier_control_points(const CurvedMesh& curved) {
    const int p = curved.order;
    const std::vector<std::array<int, 3>> order = gmsh_node_order(p);
    std::vector<Eigen::Vector3d> control(curved.positions.size());
    // The control points of an edge depend on that edge's nodes alone, so both of its elements give them, equal up
    // to rounding; the first element in face order sets them, and the files share them exactly.
    std::vector<char> set(curved.positions.size(), 0);
    std::vector<Eigen::Vector3d> values(order.size());
    for (const CurvedElement& element : curved.elements) {
        for (std::size_t n = 0; n < order.size(); ++n)
            values[detail::multi_index_position(order[n][1], order[n][2])] =
                curved.positions[static_cast<std::size_t>(element.nodes[n])];
        const std::vector<Eigen::Vector3d> coefficients = detail::bernstein_from_lagrange(values, p);
        for (std::size_t n = 0; n < order.size(); ++n) {
            const auto node = static_cast<std::size_t>(element.nodes[n]);
            if (set[node]) continue;
            set[node] = 1;
            control[node] = coefficients[detail::multi_index_position(order[n][1], order[n][2])];
        }
    }
    return control;
}

}  // namespace geotri

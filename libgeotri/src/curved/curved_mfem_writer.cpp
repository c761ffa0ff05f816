#include <geodesic/errors.h>
#include <geotri/curved_mesh_io.h>

#include "io/atomic_file.h"
#include "io/mesh_io_detail.h"

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace geotri {

namespace {

constexpr int k_mfem_triangle = 2;  // MFEM's Geometry::TRIANGLE

/// The nodes of `curved` in the order of MFEM's degrees of freedom for H1 on the mesh as the file states it (see
/// write_mfem()), and the number of vertices. MFEM knows an edge by its two vertices, so two edges of G between the
/// same vertices cannot be written.
std::pair<std::vector<int>, int> mfem_dof_order(const std::string& path, const CurvedMesh& curved) {
    const int p = curved.order;
    int vertices = 0;
    for (const CurvedElement& element : curved.elements)
        for (int s = 0; s < 3; ++s) vertices = std::max(vertices, element.nodes[static_cast<std::size_t>(s)] + 1);
    std::vector<int> order(static_cast<std::size_t>(vertices));
    for (int v = 0; v < vertices; ++v) order[static_cast<std::size_t>(v)] = v;

    // Sides in gmsh's order: side s runs from corner s to corner (s + 1) % 3, its p - 1 inner nodes from corner s
    // at positions 3 + s(p - 1) ...; MFEM's triangle has the same sides in the same directions.
    std::map<std::pair<int, int>, int> edge_first_node;  // by (lower, higher) vertex: the first inner node seen
    for (const CurvedElement& element : curved.elements)
        for (int s = 0; s < 3; ++s) {
            const int a = element.nodes[static_cast<std::size_t>(s)];
            const int b = element.nodes[static_cast<std::size_t>((s + 1) % 3)];
            const auto first = static_cast<std::size_t>(3 + s * (p - 1));
            const auto [at, fresh] = edge_first_node.emplace(std::minmax(a, b), p > 1 ? element.nodes[first] : -1);
            if (p > 1 && !fresh && at->second != element.nodes[first] &&
                at->second != element.nodes[first + static_cast<std::size_t>(p - 2)])
                throw InvalidInput(path + ": G has two edges between vertices " + std::to_string(a) + " and " +
                                   std::to_string(b) + ", which an MFEM mesh cannot hold");
            if (!fresh) continue;
            for (int m = 0; m < p - 1; ++m) {
                const int from_a = element.nodes[first + static_cast<std::size_t>(m)];
                const int from_b = element.nodes[first + static_cast<std::size_t>(p - 2 - m)];
                order.push_back(a < b ? from_a : from_b);
            }
        }

    // Interior nodes: MFEM lists (u, v) = (i/p, j/p) with i running fastest.
    const std::vector<std::array<int, 3>> gmsh = gmsh_node_order(p);
    std::vector<int> at_index(static_cast<std::size_t>((p + 1) * (p + 1)), -1);  // (i, j) -> position in gmsh order
    for (std::size_t n = 0; n < gmsh.size(); ++n)
        at_index[static_cast<std::size_t>(gmsh[n][1] + (p + 1) * gmsh[n][2])] = static_cast<int>(n);
    for (const CurvedElement& element : curved.elements)
        for (int j = 1; j < p; ++j)
            for (int i = 1; i + j < p; ++i)
                order.push_back(
                    element.nodes[static_cast<std::size_t>(at_index[static_cast<std::size_t>(i + (p + 1) * j)])]);
    return {order, vertices};
}

}  // namespace

void write_mfem(const std::string& path, const CurvedMesh& curved) {
    const auto [order, vertices] = mfem_dof_order(path, curved);
    detail::AtomicFile out(path);
    out.write("MFEM mesh v1.0\n\n# a curved surface: element geometry 2 is the triangle\n\ndimension\n2\n\n");
    out.write("elements\n" + std::to_string(curved.elements.size()) + "\n");
    for (const CurvedElement& element : curved.elements) {
        out.write(std::to_string(element.component + 1) + " " + std::to_string(k_mfem_triangle));
        for (int s = 0; s < 3; ++s) {
            out.write(" ");
            out.write_int(element.nodes[static_cast<std::size_t>(s)]);
        }
        out.write("\n");
    }
    out.write("\nboundary\n0\n\nvertices\n" + std::to_string(vertices) + "\n\nnodes\nFiniteElementSpace\n");
    out.write("FiniteElementCollection: H1@U_2D_P" + std::to_string(curved.order) + "\nVDim: 3\nOrdering: 1\n\n");
    std::vector<Eigen::Vector3d> values;
    values.reserve(order.size());
    for (int node : order) values.push_back(curved.positions[static_cast<std::size_t>(node)]);
    detail::write_point_lines(out, "", values);
    out.commit();
}

}  // namespace geotri

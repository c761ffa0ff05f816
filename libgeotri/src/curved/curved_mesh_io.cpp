#include <geodesic/errors.h>
#include <geotri/curved_mesh_io.h>

#include "io/atomic_file.h"
#include "io/mesh_io_detail.h"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace geotri {

namespace {

/// The components that elements lie on, in increasing order.
std::vector<int> components_of(const CurvedMesh& curved) {
    std::vector<int> components;
    for (const CurvedElement& element : curved.elements) components.push_back(element.component);
    std::sort(components.begin(), components.end());
    components.erase(std::unique(components.begin(), components.end()), components.end());
    return components;
}

/// Per node: the component of the first element that uses it (a node is on one component of T).
std::vector<int> node_components(const CurvedMesh& curved) {
    std::vector<int> component(curved.nodes.size(), -1);
    for (const CurvedElement& element : curved.elements)
        for (int node : element.nodes)
            if (component[static_cast<std::size_t>(node)] == -1)
                component[static_cast<std::size_t>(node)] = element.component;
    return component;
}

void write_point(detail::AtomicFile& out, const Eigen::Vector3d& x) {
    out.write_double(x.x());
    out.write(" ");
    out.write_double(x.y());
    out.write(" ");
    out.write_double(x.z());
}

void write_msh41(detail::AtomicFile& out, const CurvedMesh& curved) {
    const std::vector<int> components = components_of(curved);
    const std::vector<int> node_component = node_components(curved);
    out.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    out.write("$PhysicalNames\n" + std::to_string(components.size()) + "\n");
    for (int c : components) out.write("2 " + std::to_string(c + 1) + " \"component " + std::to_string(c + 1) + "\"\n");
    out.write("$EndPhysicalNames\n");
    // Entities: one surface per component, its box from its nodes, its physical group of the same tag.
    out.write("$Entities\n0 0 " + std::to_string(components.size()) + " 0\n");
    for (int c : components) {
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (std::size_t n = 0; n < curved.nodes.size(); ++n)
            if (node_component[n] == c) {
                lo = lo.cwiseMin(curved.positions[n]);
                hi = hi.cwiseMax(curved.positions[n]);
            }
        out.write(std::to_string(c + 1) + " ");
        write_point(out, lo);
        out.write(" ");
        write_point(out, hi);
        out.write(" 1 " + std::to_string(c + 1) + " 0\n");
    }
    out.write("$EndEntities\n");

    const std::size_t nodes = curved.nodes.size();
    out.write("$Nodes\n" + std::to_string(components.size()) + " " + std::to_string(nodes) + " 1 " +
              std::to_string(nodes) + "\n");
    for (int c : components) {
        std::vector<std::size_t> block;
        for (std::size_t n = 0; n < nodes; ++n)
            if (node_component[n] == c) block.push_back(n);
        out.write("2 " + std::to_string(c + 1) + " 0 " + std::to_string(block.size()) + "\n");
        for (std::size_t n : block) {
            out.write_int(static_cast<long long>(n + 1));
            out.write("\n");
        }
        for (std::size_t n : block) {
            write_point(out, curved.positions[n]);
            out.write("\n");
        }
    }
    out.write("$EndNodes\n");

    const int type = gmsh_triangle_type(curved.order);
    out.write("$Elements\n" + std::to_string(components.size()) + " " + std::to_string(curved.elements.size()) +
              " 1 " + std::to_string(curved.elements.size()) + "\n");
    for (int c : components) {
        std::vector<std::size_t> block;
        for (std::size_t e = 0; e < curved.elements.size(); ++e)
            if (curved.elements[e].component == c) block.push_back(e);
        out.write("2 " + std::to_string(c + 1) + " " + std::to_string(type) + " " + std::to_string(block.size()) +
                  "\n");
        for (std::size_t e : block) {
            out.write_int(static_cast<long long>(e + 1));
            for (int node : curved.elements[e].nodes) {
                out.write(" ");
                out.write_int(node + 1);
            }
            out.write("\n");
        }
    }
    out.write("$EndElements\n");
}

void write_msh22(detail::AtomicFile& out, const CurvedMesh& curved) {
    const std::vector<int> components = components_of(curved);
    out.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
    out.write("$PhysicalNames\n" + std::to_string(components.size()) + "\n");
    for (int c : components) out.write("2 " + std::to_string(c + 1) + " \"component " + std::to_string(c + 1) + "\"\n");
    out.write("$EndPhysicalNames\n");
    out.write("$Nodes\n" + std::to_string(curved.nodes.size()) + "\n");
    for (std::size_t n = 0; n < curved.nodes.size(); ++n) {
        out.write_int(static_cast<long long>(n + 1));
        out.write(" ");
        write_point(out, curved.positions[n]);
        out.write("\n");
    }
    out.write("$EndNodes\n");
    const std::string type = std::to_string(gmsh_triangle_type(curved.order));
    out.write("$Elements\n" + std::to_string(curved.elements.size()) + "\n");
    for (std::size_t e = 0; e < curved.elements.size(); ++e) {
        const CurvedElement& element = curved.elements[e];
        // Two tags: the physical group, then the elementary entity, both the component's.
        const std::string tag = std::to_string(element.component + 1);
        out.write(std::to_string(e + 1) + " " + type + " 2 " + tag + " " + tag);
        for (int node : element.nodes) {
            out.write(" ");
            out.write_int(node + 1);
        }
        out.write("\n");
    }
    out.write("$EndElements\n");
}


}  // namespace

int gmsh_triangle_type(int order) {
    static constexpr int types[] = {2, 9, 21, 23, 25, 42, 43, 44};
    if (order < 1 || order > 8)
        throw InvalidInput("gmsh has no Lagrange triangle of order " + std::to_string(order) + " here (1 to 8)");
    return types[order - 1];
}

void write_msh(const std::string& path, const CurvedMesh& curved, MshVersion version) {
    gmsh_triangle_type(curved.order);  // refuse an order that the file cannot hold before anything is written
    detail::AtomicFile out(path);
    if (version == MshVersion::v41) write_msh41(out, curved);
    else write_msh22(out, curved);
    out.commit();
}

void write_curved_mesh(const std::string& path, const CurvedMesh& curved, const CurvedFileOptions& options) {
    const std::string extension = detail::extension_of(path);
    if (extension == ".msh") write_msh(path, curved, options.msh_version);
    else if (extension == ".vtu") write_vtu(path, curved, options.vtu_cells);
    else if (extension == ".mesh") write_mfem(path, curved);
    else
        throw InvalidInput(path + ": cannot write curved elements as '" + extension +
                           "' (expected .msh, .vtu or .mesh)");
}

}  // namespace geotri

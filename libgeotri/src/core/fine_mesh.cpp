#include <geodesic/errors.h>
#include <geotri/fine_mesh.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <string>
#include <utility>

namespace geotri {

namespace {

// FNV-1a over explicit little-endian bytes, so that the value does not depend on the platform.
class Fnv1a {
public:
    void add(std::uint64_t value, int bytes) {
        for (int i = 0; i < bytes; ++i) {
            hash_ ^= (value >> (8 * i)) & 0xffu;
            hash_ *= 0x100000001b3ull;
        }
    }
    std::uint64_t value() const { return hash_; }

private:
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

int find_root(std::vector<int>& parent, int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
}

std::string plural(std::size_t n, const std::string& what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

std::string shortest(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

}  // namespace

std::uint64_t fine_mesh_checksum(const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<std::array<int, 3>>& triangles) {
    Fnv1a hash;
    hash.add(positions.size(), 8);
    hash.add(triangles.size(), 8);
    for (const Eigen::Vector3d& p : positions)
        for (int i = 0; i < 3; ++i) {
            std::uint64_t bits;
            std::memcpy(&bits, &p[i], sizeof bits);
            hash.add(bits, 8);
        }
    for (const auto& t : triangles)
        for (int v : t) hash.add(static_cast<std::uint32_t>(v), 4);
    return hash.value();
}

FineMesh make_fine_mesh(MeshData data, const std::string& name) {
    const std::string prefix = name.empty() ? std::string() : name + ": ";
    if (data.triangles.empty()) throw TopologyError(prefix + "mesh has no faces");
    const std::uint64_t checksum = fine_mesh_checksum(data.positions, data.triangles);
    // Non-finite coordinates are geodesic::Mesh's to refuse (with its own message).
    for (std::size_t v = 0; v < data.positions.size(); ++v)
        for (int i = 0; i < 3; ++i) {
            const double x = data.positions[v][i];
            if (std::isfinite(x) && std::abs(x) > k_max_coordinate)
                throw InvalidInput(prefix + "vertex " + std::to_string(v) + " has a coordinate of " + shortest(x) +
                                   ", beyond +-" + shortest(k_max_coordinate) + " (areas would overflow)");
        }

    // geodesic::Mesh checks indices, finiteness, repeated vertices, edges shared by more than two faces and
    // inconsistent orientation; its messages get the file name in front.
    auto checked_mesh = [&] {
        try {
            return geodesic::Mesh(std::move(data.positions), std::move(data.triangles));
        } catch (const TopologyError& error) {
            throw TopologyError(prefix + error.what());
        } catch (const InvalidInput& error) {
            throw InvalidInput(prefix + error.what());
        }
    };
    FineMesh fine{name, checked_mesh(), checksum, {}, 0, 0, {}};
    const geodesic::Mesh& mesh = fine.mesh;

    if (mesh.num_boundary_halfedges() > 0)
        throw TopologyError(prefix + "mesh is not closed (" + plural(mesh.num_boundary_halfedges(), "boundary edge") +
                            ")");
    std::size_t unused = 0;
    int first_unused = -1;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
        if (mesh.outgoing(v) < 0) {
            if (unused++ == 0) first_unused = v;
            continue;
        }
        if (!mesh.is_manifold_vertex(v))
            throw TopologyError(prefix + "vertex " + std::to_string(v) +
                                " is non-manifold (its faces form more than one fan)");
    }
    if (unused > 0)
        throw TopologyError(prefix + plural(unused, "vertex") + (unused == 1 ? " is" : " are") +
                            " used by no face (the first is vertex " + std::to_string(first_unused) + ")");

    std::vector<int> parent(mesh.num_vertices());
    std::iota(parent.begin(), parent.end(), 0);
    for (const auto& t : mesh.triangles())
        for (int i = 0; i < 2; ++i) {
            const int a = find_root(parent, t[i]), b = find_root(parent, t[i + 1]);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
    fine.component.assign(mesh.num_vertices(), -1);
    std::vector<int> number_of_root(mesh.num_vertices(), -1);
    for (int v = 0; v < mesh.num_vertices(); ++v) {
        int& number = number_of_root[find_root(parent, v)];
        if (number < 0) number = fine.num_components++;
        fine.component[v] = number;
    }
    std::vector<int> vertices(static_cast<std::size_t>(fine.num_components), 0), faces(vertices.size(), 0);
    std::vector<int> first_vertex(vertices.size(), -1);
    std::vector<double> area(vertices.size(), 0.0);
    for (int v = 0; v < mesh.num_vertices(); ++v) {
        const std::size_t c = static_cast<std::size_t>(fine.component[v]);
        if (vertices[c]++ == 0) first_vertex[c] = v;
    }
    for (int f = 0; f < mesh.num_faces(); ++f) {
        const std::size_t c = static_cast<std::size_t>(fine.component[static_cast<std::size_t>(mesh.triangle(f)[0])]);
        ++faces[c];
        const double face_area = mesh.face_area(f);
        if (face_area == 0.0) ++fine.num_zero_area_faces;
        area[c] += face_area;
    }
    // Zero-area faces are allowed, but not a surface without area: it has no geodesics to speak of.
    for (std::size_t c = 0; c < area.size(); ++c) {
        if (area[c] > 0.0) continue;
        const std::string what = area.size() == 1 ? std::string("mesh")
                                                  : "component " + std::to_string(c) + " of " +
                                                        std::to_string(area.size()) + " (from vertex " +
                                                        std::to_string(first_vertex[c]) + ")";
        throw InvalidInput(prefix + what + " has zero area (all " + (area.size() == 1 ? "its " : "") +
                           plural(static_cast<std::size_t>(faces[c]), "face") + " are degenerate)");
    }
    fine.genus.resize(vertices.size());
    for (std::size_t c = 0; c < vertices.size(); ++c) fine.genus[c] = (2 - (vertices[c] - faces[c] / 2)) / 2;
    return fine;
}

}  // namespace geotri

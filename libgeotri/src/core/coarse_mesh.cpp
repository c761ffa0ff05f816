// GCC 12 warns inside OpenMesh's PropertyT<Vec3d>::push_back(), whose default-constructed point is deliberately
// left uninitialised; building a coarse mesh instantiates it here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <geodesic/errors.h>
#include <geotri/fine_mesh.h>
#include <geotri/geodesic_triangulation.h>

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace geotri {

namespace {

using OpenMesh::VertexHandle;

std::uint64_t directed_key(int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

std::string plural(std::size_t n, const std::string& what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

std::array<int, 3> corners_of(const CoarseMesh& coarse, OpenMesh::FaceHandle f) {
    std::array<int, 3> corners{};
    auto fv = coarse.cfv_iter(f);
    for (std::size_t i = 0; i < 3; ++i, ++fv) corners[i] = fv->idx();
    return corners;
}

}  // namespace

CoarseMesh make_coarse_mesh(const MeshData& data, const std::string& name) {
    const std::string prefix = name.empty() ? std::string() : name + ": ";
    const int n = static_cast<int>(data.positions.size());
    if (data.triangles.empty()) throw TopologyError(prefix + "coarse mesh has no faces");
    for (int v = 0; v < n; ++v)
        if (data.positions[static_cast<std::size_t>(v)].cwiseAbs().maxCoeff() > k_max_coordinate)
            throw InvalidInput(prefix + "coarse vertex " + std::to_string(v) + " has a coordinate beyond +-1e+75 "
                                        "(areas would overflow)");
    std::unordered_map<std::uint64_t, int> face_of_halfedge;
    face_of_halfedge.reserve(3 * data.triangles.size());
    for (std::size_t f = 0; f < data.triangles.size(); ++f) {
        const auto& t = data.triangles[f];
        for (int i = 0; i < 3; ++i) {
            if (t[i] < 0 || t[i] >= n)
                throw InvalidInput(prefix + "face " + std::to_string(f) + " refers to vertex " +
                                   std::to_string(t[i]) + ", out of range [0, " + std::to_string(n) + ")");
        }
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
            throw InvalidInput(prefix + "face " + std::to_string(f) + " repeats a vertex");
        for (int i = 0; i < 3; ++i) {
            const int a = t[i], b = t[(i + 1) % 3];
            const auto inserted = face_of_halfedge.emplace(directed_key(a, b), static_cast<int>(f));
            if (!inserted.second)
                throw TopologyError(prefix + "edge " + std::to_string(a) + "-" + std::to_string(b) +
                                    " is used twice in the same direction (faces " +
                                    std::to_string(inserted.first->second) + " and " + std::to_string(f) +
                                    "): non-manifold or inconsistently oriented");
        }
    }
    std::size_t boundary = 0;
    for (const auto& entry : face_of_halfedge) {
        const int a = static_cast<int>(entry.first >> 32), b = static_cast<int>(entry.first & 0xffffffffu);
        if (face_of_halfedge.count(directed_key(b, a)) == 0) ++boundary;
    }
    if (boundary > 0) throw TopologyError(prefix + "coarse mesh is not closed (" + plural(boundary, "boundary edge") + ")");

    // Around each vertex, face (v, a, b) links a to b; the links form one cycle exactly when v is manifold.
    std::vector<int> degree(static_cast<std::size_t>(n), 0);
    for (const auto& t : data.triangles)
        for (int v : t) ++degree[static_cast<std::size_t>(v)];
    for (int v = 0; v < n; ++v)
        if (degree[static_cast<std::size_t>(v)] == 0)
            throw TopologyError(prefix + "coarse vertex " + std::to_string(v) + " is used by no face");
    std::unordered_map<std::uint64_t, int> link;  // (v, a) -> b
    link.reserve(3 * data.triangles.size());
    for (const auto& t : data.triangles)
        for (int i = 0; i < 3; ++i) link.emplace(directed_key(t[i], t[(i + 1) % 3]), t[(i + 2) % 3]);
    std::vector<char> seen(static_cast<std::size_t>(n), 0);
    for (const auto& t : data.triangles)
        for (int i = 0; i < 3; ++i) {
            const int v = t[i];
            if (seen[static_cast<std::size_t>(v)]) continue;
            seen[static_cast<std::size_t>(v)] = 1;
            const int start = t[(i + 1) % 3];
            int a = start, steps = 0;
            do {
                a = link.at(directed_key(v, a));
                ++steps;
            } while (a != start && steps <= degree[static_cast<std::size_t>(v)]);
            if (steps != degree[static_cast<std::size_t>(v)])
                throw TopologyError(prefix + "coarse vertex " + std::to_string(v) +
                                    " is non-manifold (its faces form more than one fan)");
        }

    CoarseMesh coarse;
    coarse.reserve(static_cast<std::size_t>(n), 3 * data.triangles.size() / 2, data.triangles.size());
    for (const Eigen::Vector3d& p : data.positions) coarse.add_vertex(CoarseMesh::Point(p.x(), p.y(), p.z()));
    for (std::size_t f = 0; f < data.triangles.size(); ++f) {
        const auto& t = data.triangles[f];
        const auto face = coarse.add_face(VertexHandle(t[0]), VertexHandle(t[1]), VertexHandle(t[2]));
        if (!face.is_valid()) throw TopologyError(prefix + "face " + std::to_string(f) + " cannot be added");
    }
    return coarse;
}

GeodesicTriangulation renumbered_as_read(const GeodesicTriangulation& g) {
    const CoarseMesh& coarse = g.coarse();
    MeshData faces;  // positions are placeholders, as in a file's faces
    faces.positions.assign(coarse.n_vertices(), Eigen::Vector3d::Zero());
    for (auto f : coarse.faces()) faces.triangles.push_back(corners_of(coarse, f));
    GeodesicTriangulation out(g.shared_fine(), make_coarse_mesh(faces, ""));
    for (auto v : coarse.vertices()) out.set_location(v, g.location(v));
    for (auto e : coarse.edges()) {
        const OpenMesh::HalfedgeHandle h = coarse.halfedge_handle(e, 0);
        if (!g.polyline(e).empty())
            out.set_path(out.coarse().find_halfedge(coarse.from_vertex_handle(h), coarse.to_vertex_handle(h)),
                         g.polyline(e));
    }
    return out;
}

}  // namespace geotri

// Wavefront OBJ: "v x y z" and "f a b c" lines, where each corner is "v", "v/vt", "v/vt/vn" or "v//vn", 1-based,
// or negative to count back from the last vertex read so far. Everything else (vt, vn, groups, materials, lines)
// is ignored.

#include "io/mesh_io_detail.h"

namespace geotri::detail {

MeshData read_obj(const std::string& path, std::string_view bytes) {
    MeshData mesh;
    LineReader lines(bytes);
    std::string_view line;
    auto malformed = [&](const std::string& why) {
        fail(path, "malformed line " + std::to_string(lines.line_number()) + " (" + why + ")");
    };
    // Positive indices may refer to vertices that come later; they are checked once the file is read.
    std::vector<int> face_lines;
    while (lines.next(line)) {
        skip_spaces(line);
        if (line.size() < 2 || !is_space(line[1])) continue;  // vt, vn, #, g, o, usemtl, ... and blank lines
        if (line[0] == 'v') {
            line.remove_prefix(1);
            Eigen::Vector3d p;
            if (!parse_real_token(line, p.x()) || !parse_real_token(line, p.y()) || !parse_real_token(line, p.z())) {
                malformed("expected 'v x y z'");
            }
            mesh.positions.push_back(p);
        } else if (line[0] == 'f') {
            line.remove_prefix(1);
            std::array<int, 3> t{};
            int corners = 0;
            const long long num_vertices = static_cast<long long>(mesh.positions.size());
            for (std::string_view corner = next_token(line); !corner.empty() && corner.front() != '#';
                 corner = next_token(line)) {
                long long index = 0;
                if (!parse_integer(corner, index) || (!corner.empty() && corner.front() != '/') || index == 0) {
                    malformed("expected 'f v1 v2 v3' with 1-based or negative vertex indices");
                }
                if (index < 0) {
                    index += num_vertices;
                    if (index < 0) {
                        fail(path, "face " + std::to_string(mesh.triangles.size()) + " refers to vertex " +
                                       std::to_string(index - num_vertices) + " before the first vertex (line " +
                                       std::to_string(lines.line_number()) + ")");
                    }
                } else {
                    index -= 1;
                }
                if (index > std::numeric_limits<int>::max()) {
                    fail(path, "face " + std::to_string(mesh.triangles.size()) + " refers to vertex " +
                                   std::to_string(index + 1) + ", out of range (line " +
                                   std::to_string(lines.line_number()) + ")");
                }
                if (corners < 3) t[static_cast<std::size_t>(corners)] = static_cast<int>(index);
                ++corners;
            }
            if (corners != 3) {
                fail(path, "face " + std::to_string(mesh.triangles.size()) + " has " + std::to_string(corners) +
                               " vertices (line " + std::to_string(lines.line_number()) +
                               "); only triangles are supported");
            }
            mesh.triangles.push_back(t);
            face_lines.push_back(lines.line_number());
        }
    }
    if (mesh.triangles.empty()) fail(path, "no faces");
    const long long num_vertices = static_cast<long long>(mesh.positions.size());
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        for (const int v : mesh.triangles[f]) {
            if (v >= num_vertices) {
                fail(path, "face " + std::to_string(f) + " refers to vertex " + std::to_string(v + 1LL) +
                               ", out of range (" + std::to_string(num_vertices) + " vertices; line " +
                               std::to_string(face_lines[f]) + ")");
            }
        }
    }
    return mesh;
}

}  // namespace geotri::detail

// OFF: a header line ([ST][C][N]OFF), the counts, one vertex per line, one face per line. Comment lines start
// with '#'. Columns after the coordinates (normals, colours, texture coordinates) and after a face's indices
// (a colour) are ignored.

#include "io/mesh_io_detail.h"

namespace geotri::detail {

namespace {

constexpr long long k_max_index = std::numeric_limits<int>::max();

/// Strips a '#' comment and reports whether anything but blanks is left.
bool has_content(std::string_view& line) {
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    skip_spaces(line);
    return !line.empty();
}

}  // namespace

MeshData read_off(const std::string& path, std::string_view bytes) {
    LineReader lines(bytes);
    std::string_view line;
    auto next_content_line = [&]() {
        while (lines.next(line)) {
            if (has_content(line)) return true;
        }
        return false;
    };
    auto malformed = [&](const std::string& why) {
        fail(path, "malformed line " + std::to_string(lines.line_number()) + " (" + why + ")");
    };

    if (!next_content_line()) fail(path, "empty file (no OFF header)");
    const std::string_view keyword = next_token(line);
    if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") {
        fail(path, "not an OFF file (line " + std::to_string(lines.line_number()) + " does not start with 'OFF')");
    }
    const std::string_view flags = keyword.substr(0, keyword.size() - 3);
    if (flags.find_first_not_of("STCN") != std::string_view::npos) {
        fail(path, "unsupported OFF variant '" + std::string(keyword) + "' (only 3D [ST][C][N]OFF is read)");
    }
    skip_spaces(line);
    if (line.substr(0, 6) == "BINARY") fail(path, "binary OFF is not supported");
    // The counts may follow the keyword on the same line.
    if (line.empty() && !next_content_line()) fail(path, "truncated (no vertex and face counts)");
    long long num_vertices = 0, num_faces = 0;
    if (!parse_integer_token(line, num_vertices) || !parse_integer_token(line, num_faces) || num_vertices < 0 ||
        num_faces < 0) {
        malformed("expected the vertex, face and edge counts");
    }
    if (num_faces == 0) fail(path, "no faces");
    // Every vertex and face takes at least two bytes: a count beyond that is a corrupt header, not a reason to
    // allocate gigabytes.
    if (num_vertices + num_faces > static_cast<long long>(bytes.size()) || num_vertices > k_max_index ||
        num_faces > k_max_index) {
        fail(path, "truncated: the header announces " + std::to_string(num_vertices) + " vertices and " +
                       std::to_string(num_faces) + " faces, more than the file can hold");
    }

    MeshData mesh;
    mesh.positions.resize(static_cast<std::size_t>(num_vertices));
    for (long long v = 0; v < num_vertices; ++v) {
        if (!next_content_line()) {
            fail(path, "truncated: " + std::to_string(num_vertices) + " vertices announced, " + std::to_string(v) +
                           " found");
        }
        Eigen::Vector3d& p = mesh.positions[static_cast<std::size_t>(v)];
        if (!parse_real_token(line, p.x()) || !parse_real_token(line, p.y()) || !parse_real_token(line, p.z())) {
            malformed("expected the 3 coordinates of vertex " + std::to_string(v));
        }
    }
    mesh.triangles.resize(static_cast<std::size_t>(num_faces));
    for (long long f = 0; f < num_faces; ++f) {
        if (!next_content_line()) {
            fail(path, "truncated: " + std::to_string(num_faces) + " faces announced, " + std::to_string(f) +
                           " found");
        }
        long long corners = 0;
        if (!parse_integer_token(line, corners)) malformed("expected the vertex count of face " + std::to_string(f));
        if (corners != 3) {
            fail(path, "face " + std::to_string(f) + " has " + std::to_string(corners) +
                           " vertices (line " + std::to_string(lines.line_number()) + "); only triangles are supported");
        }
        std::array<int, 3>& t = mesh.triangles[static_cast<std::size_t>(f)];
        for (int& v : t) {
            long long index = 0;
            if (!parse_integer_token(line, index)) malformed("expected 3 vertex indices for face " + std::to_string(f));
            if (index < 0 || index >= num_vertices) {
                fail(path, "face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                               ", out of range (" + std::to_string(num_vertices) + " vertices; line " +
                               std::to_string(lines.line_number()) + ")");
            }
            v = static_cast<int>(index);
        }
    }
    // More data than the header announces is a wrong count, whose faces would be left out in silence.
    if (next_content_line())
        fail(path, "line " + std::to_string(lines.line_number()) + " follows the " + std::to_string(num_faces) +
                       " faces that the header announces (is its face count wrong?)");
    return mesh;
}

}  // namespace geotri::detail

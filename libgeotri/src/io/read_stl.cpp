// STL: a soup of triangles, welded here into an indexed mesh by exact position.

#include "io/mesh_io_detail.h"

#include <cmath>
#include <cstring>

namespace geotri::detail {

namespace {

constexpr std::size_t k_header_size = 84;
constexpr std::size_t k_triangle_size = 50;

/// Gives equal positions one index, numbered in order of first occurrence. Positions are equal when their
/// coordinates are equal as numbers (so +0 and -0 weld; the first one's bits are kept).
class Welder {
public:
    /// A closed mesh has about half as many vertices as triangles: sized for that, grown when there are more.
    Welder(MeshData& mesh, std::size_t expected_triangles) : mesh_(mesh) {
        const std::size_t expected_vertices = expected_triangles / 2 + 16;
        std::size_t capacity = 32;
        while (capacity < 2 * expected_vertices) capacity *= 2;
        slots_.assign(capacity, -1);
        mesh_.positions.reserve(expected_vertices);
    }

    int index_of(double x, double y, double z) {
        if (2 * (mesh_.positions.size() + 1) > slots_.size()) grow();
        const Eigen::Vector3d p(x, y, z);
        std::size_t slot = hash(p) & (slots_.size() - 1);
        while (slots_[slot] >= 0) {
            if (mesh_.positions[static_cast<std::size_t>(slots_[slot])] == p) return slots_[slot];
            slot = (slot + 1) & (slots_.size() - 1);
        }
        const int index = static_cast<int>(mesh_.positions.size());
        slots_[slot] = index;
        mesh_.positions.push_back(p);
        return index;
    }

private:
    static std::uint64_t bits(double value) {
        value += 0.0;  // -0 becomes +0
        std::uint64_t b = 0;
        std::memcpy(&b, &value, sizeof b);
        return b;
    }
    static std::size_t hash(const Eigen::Vector3d& p) {
        std::uint64_t h = bits(p.x()) * 0x9E3779B97F4A7C15ull;
        h = (h ^ (h >> 29) ^ bits(p.y())) * 0xBF58476D1CE4E5B9ull;
        h = (h ^ (h >> 32) ^ bits(p.z())) * 0x94D049BB133111EBull;
        return static_cast<std::size_t>(h ^ (h >> 31));
    }
    void grow() {
        slots_.assign(slots_.size() * 2, -1);
        for (std::size_t v = 0; v < mesh_.positions.size(); ++v) {
            std::size_t slot = hash(mesh_.positions[v]) & (slots_.size() - 1);
            while (slots_[slot] >= 0) slot = (slot + 1) & (slots_.size() - 1);
            slots_[slot] = static_cast<int>(v);
        }
    }

    MeshData& mesh_;
    std::vector<int> slots_;
};

std::uint32_t read_u32_le(const char* p) {
    const auto* b = reinterpret_cast<const unsigned char*>(p);
    return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
           static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

float read_f32_le(const char* p) {
    const std::uint32_t b = read_u32_le(p);
    float value = 0.0f;
    std::memcpy(&value, &b, sizeof value);
    return value;
}

std::string finite_check_message(std::size_t triangle) {
    return "non-finite coordinate (NaN or infinity) in triangle " + std::to_string(triangle);
}

MeshData read_binary_stl(const std::string& path, std::string_view bytes, std::size_t count) {
    MeshData mesh;
    mesh.triangles.reserve(count);
    Welder welder(mesh, count);
    const char* record = bytes.data() + k_header_size;
    for (std::size_t t = 0; t < count; ++t, record += k_triangle_size) {
        std::array<int, 3> triangle{};
        for (int corner = 0; corner < 3; ++corner) {
            const char* p = record + 12 + 12 * corner;  // after the normal
            const double x = read_f32_le(p), y = read_f32_le(p + 4), z = read_f32_le(p + 8);
            if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) fail(path, finite_check_message(t));
            triangle[corner] = welder.index_of(x, y, z);
        }
        mesh.triangles.push_back(triangle);
    }
    return mesh;
}

MeshData read_ascii_stl(const std::string& path, std::string_view bytes) {
    MeshData mesh;
    // An ASCII facet takes some 250 bytes.
    Welder welder(mesh, bytes.size() / 250);
    LineReader lines(bytes);
    std::string_view line;
    bool in_solid = false;
    bool in_facet = false;
    bool ended = false;
    int corners = 0;
    std::array<int, 3> triangle{};
    auto malformed = [&](const std::string& why) {
        fail(path, "malformed line " + std::to_string(lines.line_number()) + " (" + why + ")");
    };
    while (lines.next(line)) {
        std::string_view rest = line;
        const std::string_view keyword = next_token(rest);
        if (keyword.empty()) continue;
        if (keyword == "solid") {
            if (in_solid) malformed("'solid' inside a solid");
            in_solid = true;
            ended = false;
        } else if (keyword == "endsolid") {
            if (!in_solid || in_facet) malformed("unexpected 'endsolid'");
            in_solid = false;
            ended = true;
        } else if (keyword == "facet") {
            if (!in_solid || in_facet) malformed("unexpected 'facet'");
            in_facet = true;
            corners = 0;
        } else if (keyword == "outer" || keyword == "endloop") {
            if (!in_facet) malformed("'" + std::string(keyword) + "' outside a facet");
        } else if (keyword == "vertex") {
            if (!in_facet) malformed("'vertex' outside a facet");
            double x = 0, y = 0, z = 0;
            if (!parse_real_token(rest, x) || !parse_real_token(rest, y) || !parse_real_token(rest, z)) {
                malformed("expected 'vertex x y z'");
            }
            if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
                fail(path, finite_check_message(mesh.triangles.size()));
            }
            if (corners == 3) {
                fail(path, "facet " + std::to_string(mesh.triangles.size()) + " has more than 3 vertices (line " +
                               std::to_string(lines.line_number()) + ")");
            }
            triangle[static_cast<std::size_t>(corners++)] = welder.index_of(x, y, z);
        } else if (keyword == "endfacet") {
            if (!in_facet) malformed("unexpected 'endfacet'");
            if (corners != 3) {
                fail(path, "facet " + std::to_string(mesh.triangles.size()) + " has " + std::to_string(corners) +
                               " vertices (line " + std::to_string(lines.line_number()) + ")");
            }
            mesh.triangles.push_back(triangle);
            in_facet = false;
        } else {
            malformed("unknown keyword '" + std::string(keyword.substr(0, 32)) + "'");
        }
    }
    if (!ended || in_solid) fail(path, "truncated ASCII STL (no 'endsolid' at the end)");
    return mesh;
}

bool looks_like_ascii(std::string_view bytes) {
    std::string_view start = bytes;
    skip_spaces(start);
    while (!start.empty() && start.front() == '\n') {
        start.remove_prefix(1);
        skip_spaces(start);
    }
    if (start.substr(0, 5) != "solid") return false;
    // Binary headers may start with "solid" too: an ASCII file has text, with a facet or an end, right after.
    const std::string_view head = start.substr(0, 1024);
    for (const char c : head) {
        if (c == 0 || static_cast<unsigned char>(c) > 126) return false;
    }
    return head.find("facet") != std::string_view::npos || head.find("endsolid") != std::string_view::npos;
}

}  // namespace

MeshData read_stl(const std::string& path, std::string_view bytes) {
    if (bytes.size() >= k_header_size) {
        const std::size_t count = read_u32_le(bytes.data() + 80);
        if (bytes.size() == k_header_size + k_triangle_size * count) {
            if (count == 0) fail(path, "no faces");
            return read_binary_stl(path, bytes, count);
        }
    }
    // An ASCII STL may start with a UTF-8 byte order mark, which some editors write; a binary one whose header
    // starts with those bytes was read above, its size matching its triangle count.
    std::string_view text = bytes;
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    if (looks_like_ascii(text)) return read_ascii_stl(path, text);
    if (bytes.size() < k_header_size) {
        fail(path, "truncated or not an STL file (" + std::to_string(bytes.size()) +
                       " bytes: too short for a binary STL, and no ASCII 'solid' header)");
    }
    const std::size_t count = read_u32_le(bytes.data() + 80);
    const std::size_t expected = k_header_size + k_triangle_size * count;
    if (bytes.size() < expected) {
        fail(path, "truncated binary STL: " + std::to_string(count) + " triangles need " + std::to_string(expected) +
                       " bytes, the file has " + std::to_string(bytes.size()));
    }
    fail(path, "malformed binary STL: " + std::to_string(count) + " triangles need " + std::to_string(expected) +
                   " bytes, the file has " + std::to_string(bytes.size()) + " (trailing data)");
}

}  // namespace geotri::detail

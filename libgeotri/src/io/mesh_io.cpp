#include <geotri/mesh_io.h>

#include "io/atomic_file.h"
#include "io/mesh_io_detail.h"

#include <geodesic/errors.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include <sys/stat.h>

namespace geotri {

namespace detail {

std::string read_file(const std::string& path) {
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) fail(path, std::string("cannot open: ") + std::strerror(errno));
    struct stat info {};
    if (::fstat(::fileno(file.get()), &info) != 0) fail(path, std::string("cannot read: ") + std::strerror(errno));
    if (S_ISDIR(info.st_mode)) fail(path, "cannot read: it is a folder");
    // A device (/dev/zero, a terminal) may never end, and would fill memory; pipes are read as files.
    if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode)) fail(path, "cannot read: it is a device, not a file");
    std::string bytes;
    if (S_ISREG(info.st_mode)) bytes.reserve(static_cast<std::size_t>(info.st_size));
    // Read until the end rather than trusting the size: the file may be a pipe, or change under us.
    char chunk[1 << 16];
    std::size_t n = 0;
    while ((n = std::fread(chunk, 1, sizeof chunk, file.get())) > 0) bytes.append(chunk, n);
    if (std::ferror(file.get())) fail(path, std::string("cannot read: ") + std::strerror(errno));
    return bytes;
}

std::string extension_of(const std::string& path) {
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void check_mesh(const std::string& path, const MeshData& mesh) {
    if (mesh.triangles.empty()) fail(path, "no faces");
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const Eigen::Vector3d& p = mesh.positions[v];
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
            fail(path, "non-finite coordinate (NaN or infinity) at vertex " + std::to_string(v));
        }
    }
    const long long n = static_cast<long long>(mesh.positions.size());
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        for (const int v : mesh.triangles[f]) {
            if (v < 0 || v >= n) {
                fail(path, "face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                               ", out of range (" + std::to_string(n) + " vertices)");
            }
        }
    }
}

void write_point_lines(AtomicFile& out, std::string_view prefix, const std::vector<Eigen::Vector3d>& points) {
    for (const Eigen::Vector3d& p : points) {
        out.write(prefix);
        out.write_double(p.x());
        out.write(" ");
        out.write_double(p.y());
        out.write(" ");
        out.write_double(p.z());
        out.write("\n");
    }
}

}  // namespace detail

MeshData read_mesh(const std::string& path) {
    const std::string ext = detail::extension_of(path);
    MeshData (*reader)(const std::string&, std::string_view) = nullptr;
    if (ext == ".stl") {
        reader = &detail::read_stl;
    } else if (ext == ".off") {
        reader = &detail::read_off;
    } else if (ext == ".obj") {
        reader = &detail::read_obj;
    } else if (ext == ".ply") {
        reader = &detail::read_ply;
    } else {
        detail::fail(path, "unknown mesh format '" + ext + "' (expected .stl, .off, .obj or .ply)");
    }
    const std::string bytes = detail::read_file(path);
    if (bytes.empty()) detail::fail(path, "empty file");
    std::string_view text = bytes;
    // A UTF-8 byte order mark, which some editors put first, is not part of the text formats' first line. (A binary
    // STL's 80-byte header may start with those bytes: read_stl() skips one only where the file is not binary.)
    if (ext != ".stl" && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    MeshData mesh = reader(path, text);
    detail::check_mesh(path, mesh);
    return mesh;
}

namespace {

void check_for_writing(const std::string& path, const MeshData& mesh) {
    const long long n = static_cast<long long>(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        if (!mesh.positions[v].allFinite()) {
            throw InvalidInput(path + ": cannot write a non-finite coordinate (vertex " + std::to_string(v) + ")");
        }
    }
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        for (const int v : mesh.triangles[f]) {
            if (v < 0 || v >= n) {
                throw InvalidInput(path + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                   ", out of range (" + std::to_string(n) + " vertices)");
            }
        }
    }
}

/// The vertex and face lines of OFF and OBJ: "VERTEX_PREFIX x y z" per vertex, then "FACE_PREFIX a b c" per
/// triangle with the vertices counted from `first_index`.
void write_vertex_and_face_lines(detail::AtomicFile& out, const MeshData& mesh, std::string_view vertex_prefix,
                                 std::string_view face_prefix, long long first_index) {
    detail::write_point_lines(out, vertex_prefix, mesh.positions);
    for (const std::array<int, 3>& t : mesh.triangles) {
        out.write(face_prefix);
        for (const int v : t) {
            out.write(" ");
            out.write_int(v + first_index);
        }
        out.write("\n");
    }
}

void write_off(detail::AtomicFile& out, const MeshData& mesh) {
    out.write("OFF\n");
    out.write_int(static_cast<long long>(mesh.positions.size()));
    out.write(" ");
    out.write_int(static_cast<long long>(mesh.triangles.size()));
    out.write(" 0\n");
    write_vertex_and_face_lines(out, mesh, "", "3", 0);
}

void write_obj(detail::AtomicFile& out, const MeshData& mesh) { write_vertex_and_face_lines(out, mesh, "v ", "f", 1); }

template <typename T>
void write_little_endian(detail::AtomicFile& out, T value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (!detail::host_is_little_endian()) {
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    }
    out.write(bytes, sizeof(T));
}

void write_ply(detail::AtomicFile& out, const MeshData& mesh) {
    out.write("ply\nformat binary_little_endian 1.0\ncomment written by geotri\nelement vertex ");
    out.write_int(static_cast<long long>(mesh.positions.size()));
    out.write("\nproperty double x\nproperty double y\nproperty double z\nelement face ");
    out.write_int(static_cast<long long>(mesh.triangles.size()));
    out.write("\nproperty list uchar int vertex_indices\nend_header\n");
    for (const Eigen::Vector3d& p : mesh.positions) {
        write_little_endian(out, p.x());
        write_little_endian(out, p.y());
        write_little_endian(out, p.z());
    }
    for (const std::array<int, 3>& t : mesh.triangles) {
        write_little_endian(out, static_cast<unsigned char>(3));
        for (const int v : t) write_little_endian(out, static_cast<std::int32_t>(v));
    }
}

}  // namespace

void write_mesh(const std::string& path, const MeshData& mesh) {
    const std::string ext = detail::extension_of(path);
    void (*writer)(detail::AtomicFile&, const MeshData&) = nullptr;
    if (ext == ".off") {
        writer = &write_off;
    } else if (ext == ".obj") {
        writer = &write_obj;
    } else if (ext == ".ply") {
        writer = &write_ply;
    } else {
        detail::fail(path, "cannot write mesh format '" + ext + "' (expected .off, .obj or .ply)");
    }
    check_for_writing(path, mesh);
    detail::AtomicFile out(path);
    writer(out, mesh);
    out.commit();
}

FineMesh load_fine_mesh(const std::string& path) { return make_fine_mesh(read_mesh(path), path); }

}  // namespace geotri

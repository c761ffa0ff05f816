// GCC 12 warns inside OpenMesh's PropertyT<Vec3d>::push_back(), whose default-constructed point is deliberately
// left uninitialised; building a coarse mesh instantiates it here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "io/atomic_file.h"
#include "io/text_reader.h"

#include <geodesic/errors.h>
#include <geotri/gtri_io.h>
#include <geotri/mesh_io.h>

#include <array>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace geotri {

namespace fs = std::filesystem;

namespace {

using detail::LineReader;
using detail::parse_count;
using detail::parse_int;
using detail::quoted;
using detail::read_text;
using detail::words;
using geodesic::PointKind;
using geodesic::SurfacePoint;

// ---- Writing ---------------------------------------------------------------------------------------------------

/// Appends the shortest decimal that reads back as exactly `value` (std::to_chars without a precision).
void append_double(std::string& out, double value) {
    char text[32];
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, value);
    out.append(text, static_cast<std::size_t>(r.ptr - text));
}

void append_int(std::string& out, long long value) {
    char text[24];
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, value);
    out.append(text, static_cast<std::size_t>(r.ptr - text));
}

/// The spelling of geodesic::to_spec(), with the shortest exact decimals instead of %.17g.
void append_point(std::string& out, const SurfacePoint& p) {
    switch (p.kind) {
        case PointKind::vertex:
            out += "v:";
            append_int(out, p.vertex);
            break;
        case PointKind::edge:
            out += "e:";
            append_int(out, p.edge_v0);
            out += ',';
            append_int(out, p.edge_v1);
            out += ':';
            append_double(out, p.t);
            break;
        case PointKind::face:
            out += "f:";
            append_int(out, p.face);
            out += ':';
            append_double(out, p.bary[0]);
            out += ',';
            append_double(out, p.bary[1]);
            out += ',';
            append_double(out, p.bary[2]);
            break;
    }
    out += '\n';
}

std::string hex64(std::uint64_t value) {
    char text[20];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

/// T's path relative to the folder of the .gtri file, through canonical paths so that symbolic links and "..".
/// resolve as the operating system will resolve them when the file is read.
std::string relative_fine_path(const std::string& gtri_path, const std::string& fine_path) {
    std::error_code error;
    const fs::path fine = fs::weakly_canonical(fs::absolute(fine_path), error);
    if (error) return fine_path;
    const fs::path folder = fs::weakly_canonical(fs::absolute(gtri_path), error).parent_path();
    if (error) return fs::absolute(fine_path).generic_string();
    const fs::path relative = fine.lexically_relative(folder);
    return relative.empty() ? fine.generic_string() : relative.generic_string();
}

// ---- Reading ---------------------------------------------------------------------------------------------------

/// A decimal number only: from_chars would also take "nan" and "inf", which the format never holds.
bool parse_double(std::string_view text, double& value) {
    if (text.empty() || text.front() == '+') return false;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::general);
    return r.ec == std::errc() && r.ptr == text.data() + text.size() && std::isfinite(value);
}

/// Parses the spelling `v:I`, `e:I,J:T` or `f:I:B0,B1,B2`; returns an empty string or what is wrong.
std::string parse_point(std::string_view text, SurfacePoint& p) {
    if (text.size() < 3 || text[1] != ':') return "expected v:I, e:I,J:T or f:I:B0,B1,B2";
    const char kind = text[0];
    std::string_view rest = text.substr(2);
    auto take = [&rest](char separator, std::string_view& field) {
        const std::size_t at = rest.find(separator);
        if (at == std::string_view::npos) return false;
        field = rest.substr(0, at);
        rest.remove_prefix(at + 1);
        return true;
    };
    auto index = [](std::string_view field, int& value) {
        long long v = 0;
        if (!parse_int(field, v) || v < 0 || v > 2147483647LL) return false;
        value = static_cast<int>(v);
        return true;
    };
    std::string_view a, b;
    switch (kind) {
        case 'v':
            p = SurfacePoint::at_vertex(0);
            if (!index(rest, p.vertex)) return "bad vertex index";
            return {};
        case 'e':
            p = SurfacePoint::on_edge(0, 0, 0.0);
            if (!take(',', a) || !take(':', b)) return "an edge point is e:I,J:T";
            if (!index(a, p.edge_v0) || !index(b, p.edge_v1)) return "bad edge vertex index";
            if (!parse_double(rest, p.t)) return "bad edge parameter (expected a finite number)";
            return {};
        case 'f': {
            p = SurfacePoint::in_face(0, {0.0, 0.0, 0.0});
            std::string_view c;
            if (!take(':', a) || !take(',', b) || !take(',', c)) return "a face point is f:I:B0,B1,B2";
            if (!index(a, p.face)) return "bad face index";
            if (!parse_double(b, p.bary[0]) || !parse_double(c, p.bary[1]) || !parse_double(rest, p.bary[2]))
                return "bad barycentric coordinate (expected a finite number)";
            return {};
        }
        default: return "unknown point kind '" + std::string(1, kind) + "'";
    }
}

/// The point as read, checked against T: it must refer to T and already be in its one representation.
SurfacePoint checked_point(const LineReader& in, int line, const geodesic::Mesh& fine, const SurfacePoint& p) {
    SurfacePoint canonical;
    try {
        canonical = fine.canonical(p);
    } catch (const InvalidInput& e) {
        in.fail_at(line, "surface point " + geodesic::to_spec(p) + " does not refer to the fine mesh: " + e.what());
    }
    if (canonical.kind != p.kind)
        in.fail_at(line, "surface point " + geodesic::to_spec(p) + " is not in its canonical form (" +
                             geodesic::to_spec(canonical) + ")");
    return canonical;
}

struct RawEdge {
    int line = 0;        ///< of its "edge" line
    int from = 0, to = 0;
    std::vector<SurfacePoint> points;
};

struct RawGtri {
    GtriHeader header;
    int fine_line = 0;  ///< of its "fine" line
    std::vector<SurfacePoint> locations;
    std::vector<int> location_lines;
    MeshData faces;  ///< positions are placeholders
    int faces_line = 0;
    std::vector<RawEdge> edges;
    int edges_line = 0;
    std::vector<std::vector<int>> point_lines;  ///< per edge, per point
};

/// The header; `fine_line`, when given, receives the number of the "fine" line.
GtriHeader parse_header(LineReader& in, int* fine_line = nullptr) {
    GtriHeader header;
    std::vector<std::string_view> w = words(in.next("the line 'gtri 1'"));
    if (w.size() != 2 || w[0] != "gtri") in.fail("not a .gtri file (its first line should be 'gtri 1')");
    long long version = 0;
    if (!parse_int(w[1], version)) in.fail("bad version " + quoted(w[1]));
    if (version != k_gtri_version)
        in.fail("unsupported .gtri version " + std::to_string(version) + " (this build reads version " +
                std::to_string(k_gtri_version) + ")");
    header.version = static_cast<int>(version);

    // PATH is the rest of the line after the separators (spaces or tabs) that follow "fine": it may hold spaces.
    const std::string_view line = in.next("the line 'fine PATH'");
    const std::size_t path_start = line.find_first_not_of(" \t", 4);
    if (line.substr(0, 4) != "fine" || line.size() < 5 || (line[4] != ' ' && line[4] != '\t') ||
        path_start == std::string_view::npos)
        in.fail("expected 'fine PATH'");
    header.fine_path = std::string(line.substr(path_start));
    if (fine_line != nullptr) *fine_line = in.line_number();

    w = words(in.next("the line 'fine_checksum HEX'"));
    if (w.size() != 2 || w[0] != "fine_checksum" || w[1].size() != 16 ||
        w[1].find_first_not_of("0123456789abcdef") != std::string_view::npos)
        in.fail("expected 'fine_checksum' and 16 lower-case hexadecimal digits");
    std::from_chars(w[1].data(), w[1].data() + w[1].size(), header.fine_checksum, 16);

    w = words(in.next("the line 'fine_size V F'"));
    if (w.size() != 3 || w[0] != "fine_size") in.fail("expected 'fine_size V F'");
    header.fine_vertices = parse_count(in, w[1], "vertex count");
    header.fine_faces = parse_count(in, w[2], "face count");

    const fs::path fine(header.fine_path);
    header.resolved_fine_path =
        fine.is_absolute() ? header.fine_path : (fs::path(in.path()).parent_path() / fine).generic_string();
    return header;
}

// The fewest bytes that an item can take, its line break included: "v:0", "0 1 2", "edge 0 0 1 0 0".
constexpr std::size_t k_min_point_bytes = 4;
constexpr std::size_t k_min_face_bytes = 6;
constexpr std::size_t k_min_edge_bytes = 15;

/// Refuses, before anything is allocated for them, `count` items that the rest of the file cannot hold: a corrupt
/// count must not cost gigabytes (or end in std::bad_alloc). The bound is a lower one, so no valid file is refused.
void check_room(const LineReader& in, int count, std::size_t min_bytes, const std::string& what,
                const char* one) {
    const std::size_t left = in.bytes_left();
    if (static_cast<unsigned long long>(count) * min_bytes > left)
        in.fail(what + ", but only " + std::to_string(left) + (left == 1 ? " byte follows" : " bytes follow") +
                " (" + one + " takes at least " + std::to_string(min_bytes) + ")");
}

/// "NAME N": the count after the section's name, checked against the bytes that follow (`min_bytes` per item).
int parse_section(LineReader& in, const char* name, std::size_t min_bytes, const char* one) {
    const std::vector<std::string_view> w = words(in.next((std::string("the line '") + name + " N'").c_str()));
    if (w.size() != 2 || w[0] != name) in.fail(std::string("expected '") + name + " N'");
    const int count = parse_count(in, w[1], (std::string(name) + " count").c_str());
    check_room(in, count, min_bytes, std::to_string(count) + " " + name, one);
    return count;
}

RawGtri parse_body(LineReader& in, GtriHeader header) {
    RawGtri raw;
    raw.header = std::move(header);

    const int num_vertices = parse_section(in, "vertices", k_min_point_bytes, "a vertex location");
    raw.locations.resize(static_cast<std::size_t>(num_vertices));
    raw.location_lines.resize(static_cast<std::size_t>(num_vertices));
    for (int v = 0; v < num_vertices; ++v) {
        const std::string_view text = in.next("a vertex location");
        const std::string why = parse_point(text, raw.locations[static_cast<std::size_t>(v)]);
        if (!why.empty()) in.fail("bad location of coarse vertex " + std::to_string(v) + " " + quoted(text) + ": " + why);
        raw.location_lines[static_cast<std::size_t>(v)] = in.line_number();
    }

    const int num_faces = parse_section(in, "faces", k_min_face_bytes, "a face");
    raw.faces_line = in.line_number();
    raw.faces.positions.assign(static_cast<std::size_t>(num_vertices), Eigen::Vector3d::Zero());
    raw.faces.triangles.resize(static_cast<std::size_t>(num_faces));
    for (int f = 0; f < num_faces; ++f) {
        const std::vector<std::string_view> w = words(in.next("a face"));
        if (w.size() != 3) in.fail("a face is three vertex indices");
        for (int i = 0; i < 3; ++i) {
            const int v = parse_count(in, w[static_cast<std::size_t>(i)], "vertex index");
            if (v >= num_vertices)
                in.fail("face " + std::to_string(f) + " refers to coarse vertex " + std::to_string(v) +
                        ", out of range [0, " + std::to_string(num_vertices) + ")");
            raw.faces.triangles[static_cast<std::size_t>(f)][static_cast<std::size_t>(i)] = v;
        }
    }

    const int num_edges = parse_section(in, "edges", k_min_edge_bytes, "an edge block");
    raw.edges_line = in.line_number();
    raw.edges.resize(static_cast<std::size_t>(num_edges));
    raw.point_lines.resize(static_cast<std::size_t>(num_edges));
    for (int e = 0; e < num_edges; ++e) {
        const std::vector<std::string_view> w = words(in.next("an 'edge' line"));
        if (w.size() != 6 || w[0] != "edge") in.fail("expected 'edge INDEX FROM TO POINTS LENGTH'");
        RawEdge& edge = raw.edges[static_cast<std::size_t>(e)];
        edge.line = in.line_number();
        if (parse_count(in, w[1], "edge index") != e)
            in.fail("edge " + quoted(w[1]) + " is out of sequence (expected edge " + std::to_string(e) + ")");
        edge.from = parse_count(in, w[2], "vertex index");
        edge.to = parse_count(in, w[3], "vertex index");
        if (edge.from >= num_vertices || edge.to >= num_vertices)
            in.fail("edge " + std::to_string(e) + " refers to a coarse vertex out of range [0, " +
                    std::to_string(num_vertices) + ")");
        const int count = parse_count(in, w[4], "point count");
        if (count == 1) in.fail("a polyline has no points (not traced) or at least two");
        double length = 0.0;
        if (!parse_double(w[5], length) || length < 0.0) in.fail("bad length " + quoted(w[5]));
        check_room(in, count, k_min_point_bytes,
                   "edge " + std::to_string(e) + " has " + std::to_string(count) + " points", "a point");
        edge.points.resize(static_cast<std::size_t>(count));
        std::vector<int>& lines = raw.point_lines[static_cast<std::size_t>(e)];
        lines.resize(static_cast<std::size_t>(count));
        for (int k = 0; k < count; ++k) {
            const std::string_view text = in.next("a polyline point");
            const std::string why = parse_point(text, edge.points[static_cast<std::size_t>(k)]);
            if (!why.empty())
                in.fail("bad point " + std::to_string(k) + " of edge " + std::to_string(e) + " " + quoted(text) +
                        ": " + why);
            lines[static_cast<std::size_t>(k)] = in.line_number();
        }
    }
    if (words(in.next("the line 'end'")) != std::vector<std::string_view>{"end"})
        in.fail("expected 'end' after the last edge (wrong counts?)");
    if (!in.at_end()) in.fail("unexpected content after 'end'");
    return raw;
}

GeodesicTriangulation build(const LineReader& in, RawGtri raw, std::shared_ptr<const FineMesh> fine,
                            const std::string& fine_name) {
    if (fine->checksum != raw.header.fine_checksum)
        throw InvalidInput(in.path() + ": the fine mesh " + fine_name + " (" + std::to_string(fine->mesh.num_vertices()) +
                           " vertices, " + std::to_string(fine->mesh.num_faces()) + " faces, checksum " +
                           hex64(fine->checksum) + ") is not the one this file was made on (" +
                           std::to_string(raw.header.fine_vertices) + " vertices, " +
                           std::to_string(raw.header.fine_faces) + " faces, checksum " +
                           hex64(raw.header.fine_checksum) + ")");
    CoarseMesh coarse;
    try {
        coarse = make_coarse_mesh(raw.faces, "");
    } catch (const Error& e) {
        in.fail_at(raw.faces_line, std::string("the faces do not make a valid coarse mesh: ") + e.what());
    }
    GeodesicTriangulation g(std::move(fine), std::move(coarse));
    const geodesic::Mesh& mesh = g.fine().mesh;
    for (std::size_t v = 0; v < raw.locations.size(); ++v) {
        const int line = raw.location_lines[v];
        const SurfacePoint p = checked_point(in, line, mesh, raw.locations[v]);
        g.set_location(OpenMesh::VertexHandle(static_cast<int>(v)), p);
    }
    const CoarseMesh& c = g.coarse();
    if (raw.edges.size() != c.n_edges())
        in.fail_at(raw.edges_line, "the file has " + std::to_string(raw.edges.size()) +
                                       " edges but its faces have " + std::to_string(c.n_edges()));
    std::vector<char> seen(c.n_edges(), 0);
    for (std::size_t e = 0; e < raw.edges.size(); ++e) {
        RawEdge& edge = raw.edges[e];
        const OpenMesh::HalfedgeHandle h =
            c.find_halfedge(OpenMesh::VertexHandle(edge.from), OpenMesh::VertexHandle(edge.to));
        if (!h.is_valid())
            in.fail_at(edge.line, "there is no coarse edge " + std::to_string(edge.from) + "-" + std::to_string(edge.to));
        char& once = seen[static_cast<std::size_t>(c.edge_handle(h).idx())];
        if (once) in.fail_at(edge.line, "coarse edge " + std::to_string(edge.from) + "-" + std::to_string(edge.to) +
                                            " is listed twice");
        once = 1;
        for (std::size_t k = 0; k < edge.points.size(); ++k)
            edge.points[k] = checked_point(in, raw.point_lines[e][k], mesh, edge.points[k]);
        if (!edge.points.empty()) g.set_path(h, std::move(edge.points));
    }
    return g;
}

/// f's vertices in the order that write_gtri() writes them.
std::array<int, 3> corners_of(const CoarseMesh& coarse, OpenMesh::FaceHandle f) {
    std::array<int, 3> corners{};
    auto fv = coarse.cfv_iter(f);
    for (std::size_t i = 0; i < 3; ++i, ++fv) corners[i] = fv->idx();
    return corners;
}

RawGtri parse_file(LineReader& in) {
    int fine_line = 0;
    GtriHeader header = parse_header(in, &fine_line);
    RawGtri raw = parse_body(in, std::move(header));
    raw.fine_line = fine_line;
    return raw;
}

}  // namespace

void write_gtri(const std::string& path, const GeodesicTriangulation& g) {
    const FineMesh& fine = g.fine();
    if (fine.path.empty()) throw InvalidInput(path + ": the fine mesh has no file to refer to (FineMesh::path is empty)");
    std::string fine_path = relative_fine_path(path, fine.path);
    if (fine_path.find_first_of("\r\n") != std::string::npos)
        throw InvalidInput(path + ": the fine mesh's path holds a line break");
    // The reader skips the separators after "fine": a relative path that starts with one gets "./" in front.
    if (!fine_path.empty() && (fine_path.front() == ' ' || fine_path.front() == '\t')) fine_path = "./" + fine_path;
    const CoarseMesh& coarse = g.coarse();
    for (auto v : coarse.vertices())
        if (g.location(v).kind == PointKind::vertex && g.location(v).vertex < 0)
            throw InvalidInput(path + ": coarse vertex " + std::to_string(v.idx()) + " has no location on the fine mesh");

    detail::AtomicFile file(path);
    std::string out;
    out.reserve(1 << 16);
    auto flush_if_full = [&] {
        if (out.size() >= (1 << 16) - 256) {
            file.write(out);
            out.clear();
        }
    };
    out += "gtri ";
    append_int(out, k_gtri_version);
    out += "\n# geodesic triangulation (docs/gtri-format.md)\nfine ";
    out += fine_path;
    out += "\nfine_checksum " + hex64(fine.checksum) + "\nfine_size ";
    append_int(out, fine.mesh.num_vertices());
    out += ' ';
    append_int(out, fine.mesh.num_faces());
    out += "\nvertices ";
    append_int(out, static_cast<long long>(coarse.n_vertices()));
    out += '\n';
    for (auto v : coarse.vertices()) {
        append_point(out, g.location(v));
        flush_if_full();
    }
    out += "faces ";
    append_int(out, static_cast<long long>(coarse.n_faces()));
    out += '\n';
    for (auto f : coarse.faces()) {
        const std::array<int, 3> corners = corners_of(coarse, f);
        for (std::size_t i = 0; i < 3; ++i) {
            if (i > 0) out += ' ';
            append_int(out, corners[i]);
        }
        out += '\n';
        flush_if_full();
    }
    out += "edges ";
    append_int(out, static_cast<long long>(coarse.n_edges()));
    out += '\n';
    for (auto e : coarse.edges()) {
        const OpenMesh::HalfedgeHandle h = coarse.halfedge_handle(e, 0);
        const Polyline& polyline = g.polyline(e);
        out += "edge ";
        append_int(out, e.idx());
        out += ' ';
        append_int(out, coarse.from_vertex_handle(h).idx());
        out += ' ';
        append_int(out, coarse.to_vertex_handle(h).idx());
        out += ' ';
        append_int(out, static_cast<long long>(polyline.size()));
        out += ' ';
        append_double(out, g.length(e));
        out += '\n';
        for (const SurfacePoint& p : polyline) {
            append_point(out, p);
            flush_if_full();
        }
    }
    out += "end\n";
    file.write(out);
    file.commit();
}


GtriHeader read_gtri_header(const std::string& path) {
    LineReader in(path, read_text(path));
    return parse_header(in);
}

GeodesicTriangulation read_gtri(const std::string& path, const std::string& fine_override) {
    LineReader in(path, read_text(path));
    RawGtri raw = parse_file(in);
    const std::string fine_path = fine_override.empty() ? raw.header.resolved_fine_path : fine_override;
    std::error_code error;
    if (fine_override.empty()) {
        if (!fs::exists(fine_path, error))
            throw IOError(path + ": its fine mesh " + raw.header.fine_path + " is not at " + fine_path +
                          " (give its path with --fine)");
        if (fs::is_directory(fine_path, error))
            in.fail_at(raw.fine_line, "its fine mesh '" + raw.header.fine_path + "' is a folder" +
                                          (fine_path == raw.header.fine_path ? "" : " (" + fine_path + ")") +
                                          ", not a mesh file");
    } else if (fs::is_directory(fine_path, error)) {
        throw IOError(path + ": its fine mesh " + fine_path + " is a folder, not a mesh file");
    }
    auto fine = std::make_shared<const FineMesh>(load_fine_mesh(fine_path));
    return build(in, std::move(raw), std::move(fine), fine_path);
}

GeodesicTriangulation read_gtri(const std::string& path, std::shared_ptr<const FineMesh> fine) {
    if (!fine) throw InvalidInput(path + ": no fine mesh given");
    LineReader in(path, read_text(path));
    RawGtri raw = parse_file(in);
    const std::string name = fine->path.empty() ? std::string("given") : fine->path;
    return build(in, std::move(raw), std::move(fine), name);
}

}  // namespace geotri

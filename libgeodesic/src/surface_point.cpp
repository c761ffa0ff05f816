#include <geodesic/errors.h>
#include <geodesic/surface_point.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>
#include <vector>

namespace geotri::geodesic {

SurfacePoint SurfacePoint::at_vertex(int v) {
    SurfacePoint p;
    p.kind = PointKind::vertex;
    p.vertex = v;
    return p;
}

SurfacePoint SurfacePoint::on_edge(int v0, int v1, double t) {
    SurfacePoint p;
    p.kind = PointKind::edge;
    p.edge_v0 = v0;
    p.edge_v1 = v1;
    p.t = t;
    return p;
}

SurfacePoint SurfacePoint::in_face(int f, const std::array<double, 3>& bary) {
    SurfacePoint p;
    p.kind = PointKind::face;
    p.face = f;
    p.bary = bary;
    return p;
}

namespace {

std::string exact(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", x);
    return buffer;
}

[[noreturn]] void bad_spec(const std::string& spec, const std::string& why) {
    throw InvalidInput("bad surface point '" + spec + "': " + why +
                       " (expected v:I, e:I,J:T or f:I:B0,B1,B2)");
}

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        std::size_t end = text.find(separator, start);
        parts.push_back(text.substr(start, end - start));
        if (end == std::string::npos) return parts;
        start = end + 1;
    }
}

int parse_index(const std::string& spec, const std::string& text) {
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
        bad_spec(spec, "'" + text + "' is not an index");
    errno = 0;
    long value = std::strtol(text.c_str(), nullptr, 10);
    if (errno != 0 || value > 2147483647L) bad_spec(spec, "index " + text + " is too large");
    return static_cast<int>(value);
}

double parse_number(const std::string& spec, const std::string& text) {
    char* end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value))
        bad_spec(spec, "'" + text + "' is not a finite number");
    return value;
}

}  // namespace

std::string to_spec(const SurfacePoint& p) {
    switch (p.kind) {
        case PointKind::vertex: return "v:" + std::to_string(p.vertex);
        case PointKind::edge:
            return "e:" + std::to_string(p.edge_v0) + "," + std::to_string(p.edge_v1) + ":" + exact(p.t);
        case PointKind::face:
            return "f:" + std::to_string(p.face) + ":" + exact(p.bary[0]) + "," + exact(p.bary[1]) + "," +
                   exact(p.bary[2]);
    }
    return {};
}

std::ostream& operator<<(std::ostream& out, const SurfacePoint& point) { return out << to_spec(point); }

SurfacePoint parse_spec(const std::string& spec) {
    std::vector<std::string> fields = split(spec, ':');
    if (fields.size() < 2) bad_spec(spec, "missing ':'");
    const std::string& kind = fields[0];
    if (kind == "v") {
        if (fields.size() != 2) bad_spec(spec, "a vertex takes one index");
        return SurfacePoint::at_vertex(parse_index(spec, fields[1]));
    }
    if (kind == "e") {
        if (fields.size() != 3) bad_spec(spec, "an edge takes two indices and a parameter");
        std::vector<std::string> ends = split(fields[1], ',');
        if (ends.size() != 2) bad_spec(spec, "an edge takes two vertex indices");
        return SurfacePoint::on_edge(parse_index(spec, ends[0]), parse_index(spec, ends[1]),
                                     parse_number(spec, fields[2]));
    }
    if (kind == "f") {
        if (fields.size() != 3) bad_spec(spec, "a face takes an index and three barycentric coordinates");
        std::vector<std::string> coords = split(fields[2], ',');
        if (coords.size() != 3) bad_spec(spec, "a face point takes three barycentric coordinates");
        return SurfacePoint::in_face(parse_index(spec, fields[1]),
                                     {parse_number(spec, coords[0]), parse_number(spec, coords[1]),
                                      parse_number(spec, coords[2])});
    }
    bad_spec(spec, "unknown kind '" + kind + "'");
}

}  // namespace geotri::geodesic

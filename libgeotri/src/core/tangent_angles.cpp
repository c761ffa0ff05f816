#include <geodesic/constants.h>
#include <geodesic/errors.h>
#include <geotri/tangent_angles.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace geotri {

using geodesic::Mesh;
using geodesic::PointKind;
using geodesic::SurfacePoint;

namespace {

using geodesic::k_pi;
using geodesic::k_two_pi;

/// An edge point with its vertices in increasing order: the point is (1-t)·p(a) + t·p(b).
struct OrderedEdgePoint {
    int a, b;
    double t;
};

OrderedEdgePoint ordered(const SurfacePoint& p) {
    if (p.edge_v0 < p.edge_v1) return {p.edge_v0, p.edge_v1, p.t};
    return {p.edge_v1, p.edge_v0, 1.0 - p.t};
}

bool face_has_vertex(const Mesh& mesh, int f, int v) {
    const auto& t = mesh.triangle(f);
    return t[0] == v || t[1] == v || t[2] == v;
}

bool point_on_face(const Mesh& mesh, int f, const SurfacePoint& p) {
    switch (p.kind) {
        case PointKind::vertex: return face_has_vertex(mesh, f, p.vertex);
        case PointKind::edge: return face_has_vertex(mesh, f, p.edge_v0) && face_has_vertex(mesh, f, p.edge_v1);
        case PointKind::face: return p.face == f;
    }
    return false;
}

std::string describe(const SurfacePoint& p) { return geodesic::to_spec(p); }

/// The halfedge of face f that leaves v.
int halfedge_from(const Mesh& mesh, int f, int v) {
    for (int i = 0; i < 3; ++i)
        if (mesh.tail(3 * f + i) == v) return 3 * f + i;
    return -1;
}

/// Polar angle at v of the direction along the fine edge v -> w (a halfedge in either direction must exist).
double along_edge(const Mesh& mesh, int v, int w) {
    const int h = mesh.find_halfedge(v, w);
    if (h >= 0) return mesh.polar_angle(h);
    // Only w -> v exists (v on a boundary): the direction is the far side of the corner that next(g) opens at v.
    const int g = mesh.find_halfedge(w, v);
    if (g < 0) throw InvalidInput("there is no fine edge (" + std::to_string(v) + "," + std::to_string(w) + ")");
    const int n = Mesh::next(g);
    return mesh.polar_angle(n) + mesh.corner_angle(n);
}

/// Wraps an angle computed as a sum of non-negative parts into [0, theta).
double wrap(double angle, double theta) {
    if (angle >= theta) angle -= theta;
    if (angle < 0.0 || angle >= theta) angle = 0.0;
    return angle;
}

/// The edge {a, b} (a < b) that both points lie on; only called when on_common_edge() holds.
void common_edge(const SurfacePoint& p, const SurfacePoint& q, int& a, int& b) {
    if (p.kind == PointKind::edge) {
        const OrderedEdgePoint e = ordered(p);
        a = e.a;
        b = e.b;
    } else if (q.kind == PointKind::edge) {
        const OrderedEdgePoint e = ordered(q);
        a = e.a;
        b = e.b;
    } else {
        a = std::min(p.vertex, q.vertex);
        b = std::max(p.vertex, q.vertex);
    }
}

/// The parameter along the edge {a, b} (a < b) of a point on it: 0 at a, 1 at b.
double edge_parameter(const SurfacePoint& p, int a) {
    if (p.kind == PointKind::vertex) return p.vertex == a ? 0.0 : 1.0;
    return ordered(p).t;
}

}  // namespace

double cone_angle(const Mesh& mesh, const SurfacePoint& p) {
    if (p.kind == PointKind::vertex) {
        if (p.vertex < 0 || p.vertex >= mesh.num_vertices())
            throw InvalidInput("vertex " + std::to_string(p.vertex) + " is out of range");
        return mesh.cone_angle(p.vertex);
    }
    mesh.point(p);  // checks the indices
    return k_two_pi;
}

bool on_common_edge(const Mesh& mesh, const SurfacePoint& p, const SurfacePoint& q) {
    if (p.kind == PointKind::face || q.kind == PointKind::face) return false;
    if (p.kind == PointKind::vertex && q.kind == PointKind::vertex)
        return p.vertex != q.vertex &&
               (mesh.find_halfedge(p.vertex, q.vertex) >= 0 || mesh.find_halfedge(q.vertex, p.vertex) >= 0);
    if (p.kind == PointKind::vertex) return q.edge_v0 == p.vertex || q.edge_v1 == p.vertex;
    if (q.kind == PointKind::vertex) return p.edge_v0 == q.vertex || p.edge_v1 == q.vertex;
    const OrderedEdgePoint e = ordered(p), f = ordered(q);
    return e.a == f.a && e.b == f.b;
}

int common_face(const Mesh& mesh, const SurfacePoint& p, const SurfacePoint& q) {
    if (on_common_edge(mesh, p, q)) {
        int a, b;
        common_edge(p, q, a, b);
        const int h = mesh.find_halfedge(a, b);
        return Mesh::face_of(h >= 0 ? h : mesh.find_halfedge(b, a));
    }
    switch (p.kind) {
        case PointKind::vertex:
            if (p.vertex < 0 || p.vertex >= mesh.num_vertices()) return -1;
            for (int h : mesh.outgoing_halfedges(p.vertex))
                if (point_on_face(mesh, Mesh::face_of(h), q)) return Mesh::face_of(h);
            return -1;
        case PointKind::edge:
            for (int h : {mesh.find_halfedge(p.edge_v0, p.edge_v1), mesh.find_halfedge(p.edge_v1, p.edge_v0)})
                if (h >= 0 && point_on_face(mesh, Mesh::face_of(h), q)) return Mesh::face_of(h);
            return -1;
        case PointKind::face:
            if (p.face < 0 || p.face >= mesh.num_faces()) return -1;
            return point_on_face(mesh, p.face, q) ? p.face : -1;
    }
    return -1;
}

std::pair<int, int> common_edge(const SurfacePoint& p, const SurfacePoint& q) {
    int a, b;
    if (p.kind == PointKind::edge) {
        a = p.edge_v0;
        b = p.edge_v1;
    } else if (q.kind == PointKind::edge) {
        a = q.edge_v0;
        b = q.edge_v1;
    } else {
        a = p.vertex;
        b = q.vertex;
    }
    return {std::min(a, b), std::max(a, b)};
}

std::vector<int> faces_holding(const Mesh& mesh, const SurfacePoint& p) {
    std::vector<int> faces;
    switch (p.kind) {
    case PointKind::vertex:
        for (int h : mesh.outgoing_halfedges(p.vertex)) faces.push_back(Mesh::face_of(h));
        break;
    case PointKind::edge:
        for (int h : {mesh.find_halfedge(p.edge_v0, p.edge_v1), mesh.find_halfedge(p.edge_v1, p.edge_v0)})
            if (h >= 0) faces.push_back(Mesh::face_of(h));
        break;
    case PointKind::face: faces.push_back(p.face); break;
    }
    return faces;
}

std::array<double, 3> barycentric_in(const Mesh& mesh, int f, const SurfacePoint& p) {
    const std::array<int, 3>& t = mesh.triangle(f);
    std::array<double, 3> b{0.0, 0.0, 0.0};
    auto corner = [&](int v) {
        for (std::size_t i = 0; i < 3; ++i)
            if (t[i] == v) return i;
        throw InvalidInput("a point is not on fine face " + std::to_string(f));
    };
    switch (p.kind) {
    case PointKind::vertex: b[corner(p.vertex)] = 1.0; break;
    case PointKind::edge:
        b[corner(p.edge_v0)] = 1.0 - p.t;
        b[corner(p.edge_v1)] = p.t;
        break;
    case PointKind::face:
        if (p.face != f) throw InvalidInput("a point is not on fine face " + std::to_string(f));
        b = p.bary;
        break;
    }
    return b;
}

Eigen::Vector2d halfedge_coordinates(const Mesh& mesh, int h, const SurfacePoint& p) {
    const int f = Mesh::face_of(h);
    const Eigen::Vector2d corner[3] = {Eigen::Vector2d::Zero(), Eigen::Vector2d(mesh.length(h), 0.0), mesh.apex(h)};
    // corner[k] is the corner at vertex tail(h), head(h), apex, i.e. triangle(f)[(h % 3 + k) % 3].
    auto at = [&](int v) -> Eigen::Vector2d {
        for (int k = 0; k < 3; ++k)
            if (mesh.triangle(f)[(h % 3 + k) % 3] == v) return corner[k];
        throw InvalidInput("surface point " + describe(p) + " is not on fine face " + std::to_string(f));
    };
    switch (p.kind) {
        case PointKind::vertex: return at(p.vertex);
        case PointKind::edge: {
            const Eigen::Vector2d x0 = at(p.edge_v0), x1 = at(p.edge_v1);
            // Written so that a point on an edge through the origin is an exact multiple of the other corner.
            return (1.0 - p.t) * x0 + p.t * x1;
        }
        case PointKind::face: {
            if (p.face != f)
                throw InvalidInput("surface point " + describe(p) + " is not on fine face " + std::to_string(f));
            Eigen::Vector2d x = Eigen::Vector2d::Zero();
            for (int k = 0; k < 3; ++k) x += p.bary[k] * at(mesh.triangle(f)[k]);
            return x;
        }
    }
    throw InvalidInput("unknown surface point kind");
}

double polar_angle(const Mesh& mesh, const SurfacePoint& p, const SurfacePoint& q) {
    if (p == q) throw InvalidInput("no direction from " + describe(p) + " to itself");
    const double theta = cone_angle(mesh, p);
    if (on_common_edge(mesh, p, q)) {
        int a, b;
        common_edge(p, q, a, b);
        if (p.kind == PointKind::vertex) return wrap(along_edge(mesh, p.vertex, p.vertex == a ? b : a), theta);
        const double tp = edge_parameter(p, a), tq = edge_parameter(q, a);
        if (tq == tp) throw InvalidInput("no direction from " + describe(p) + " to " + describe(q) + ": same point");
        return tq > tp ? 0.0 : k_pi;
    }
    const int f = common_face(mesh, p, q);
    if (f < 0)
        throw InvalidInput("surface points " + describe(p) + " and " + describe(q) + " share no fine face");
    switch (p.kind) {
        case PointKind::vertex: {
            // Inside the corner of f at p: counter-clockwise from the direction of the halfedge leaving p.
            const int h = halfedge_from(mesh, f, p.vertex);
            const Eigen::Vector2d x = halfedge_coordinates(mesh, h, q);
            const double inside = std::clamp(std::atan2(x.y(), x.x()), 0.0, mesh.corner_angle(h));
            return wrap(mesh.polar_angle(h) + inside, theta);
        }
        case PointKind::edge: {
            const OrderedEdgePoint e = ordered(p);
            const int h = mesh.find_halfedge(e.a, e.b);
            const bool left = h >= 0 && Mesh::face_of(h) == f;
            // In the frame of the halfedge of f along the edge, the edge is the x axis and the face lies above it.
            const int hf = left ? h : mesh.find_halfedge(e.b, e.a);
            const double x_p = (left ? e.t : 1.0 - e.t) * mesh.length(hf);
            const Eigen::Vector2d x = halfedge_coordinates(mesh, hf, q);
            const double above = std::clamp(std::atan2(x.y(), x.x() - x_p), 0.0, k_pi);
            return wrap(left ? above : k_pi + above, theta);
        }
        case PointKind::face: {
            const Eigen::Vector2d x_p = halfedge_coordinates(mesh, 3 * f, p);
            const Eigen::Vector2d d = halfedge_coordinates(mesh, 3 * f, q) - x_p;
            const Eigen::Vector2d r = -x_p;  // towards triangle(f)[0], the origin of the frame of halfedge 3f
            double angle = std::atan2(r.x() * d.y() - r.y() * d.x(), r.dot(d));
            if (angle < 0.0) angle += k_two_pi;
            return wrap(angle, theta);
        }
    }
    throw InvalidInput("unknown surface point kind");
}

double initial_polar_angle(const Mesh& mesh, const std::vector<SurfacePoint>& path) {
    if (path.size() < 2) throw InvalidInput("a polyline needs two points to have a direction");
    return polar_angle(mesh, path[0], path[1]);
}

double ccw_angle(double from, double to, double theta) {
    double d = to - from;
    if (d < 0.0) d += theta;
    if (d >= theta) d -= theta;
    return d < 0.0 ? 0.0 : d;
}

}  // namespace geotri

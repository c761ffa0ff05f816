#include "oracles.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <sstream>
#include <stdexcept>

namespace geotri::test {

using geodesic::PointKind;
using geodesic::SurfacePoint;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

long long edge_key(int from, int to) { return (static_cast<long long>(from) << 32) | static_cast<unsigned>(to); }

std::string describe(const SurfacePoint& p) {
    std::ostringstream out;
    out.precision(17);
    switch (p.kind) {
        case PointKind::vertex: out << "v:" << p.vertex; break;
        case PointKind::edge: out << "e:" << p.edge_v0 << "," << p.edge_v1 << ":" << p.t; break;
        case PointKind::face:
            out << "f:" << p.face << ":" << p.bary[0] << "," << p.bary[1] << "," << p.bary[2];
            break;
    }
    return out.str();
}

}  // namespace

Eigen::Vector3d point_position(const TriangleMesh& mesh, const SurfacePoint& p) {
    switch (p.kind) {
        case PointKind::vertex: return mesh.positions.at(p.vertex);
        case PointKind::edge:
            return (1.0 - p.t) * mesh.positions.at(p.edge_v0) + p.t * mesh.positions.at(p.edge_v1);
        case PointKind::face: {
            const auto& t = mesh.triangles.at(p.face);
            return p.bary[0] * mesh.positions[t[0]] + p.bary[1] * mesh.positions[t[1]] +
                   p.bary[2] * mesh.positions[t[2]];
        }
    }
    throw std::logic_error("unknown point kind");
}

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

Adjacency::Adjacency(const TriangleMesh& mesh) : mesh_(mesh) {
    const int nv = static_cast<int>(mesh.positions.size());
    const int nf = static_cast<int>(mesh.triangles.size());
    faces_around_.assign(nv, {});
    directed_edges_.reserve(3 * nf);
    for (int f = 0; f < nf; ++f) {
        const auto& t = mesh.triangles[f];
        for (int i = 0; i < 3; ++i) {
            faces_around_[t[i]].push_back(f);
            directed_edges_.emplace_back(edge_key(t[i], t[(i + 1) % 3]), f);
        }
    }
    std::sort(directed_edges_.begin(), directed_edges_.end());
    fan_.assign(nv, {});
    fan_offset_.assign(nv, {});
    cone_angle_.assign(nv, 0.0);
    boundary_.assign(nv, 0);
    single_fan_.assign(nv, 0);
    const auto slot_of = [&](int f, int v) {
        const auto& t = mesh.triangles[f];
        return t[0] == v ? 0 : t[1] == v ? 1 : 2;
    };
    for (int v = 0; v < nv; ++v) {
        const auto& around = faces_around_[v];
        for (int f : around) cone_angle_[v] += corner_angle(f, slot_of(f, v));
        if (around.empty()) continue;
        // Face (v, a, b): the next face counter-clockwise holds v -> b, the previous one holds a -> v.
        int start = around.front();
        for (int f : around) {
            const auto& t = mesh.triangles[f];
            const int a = t[(slot_of(f, v) + 1) % 3];
            if (face_with_directed_edge(a, v) < 0) {
                boundary_[v] = 1;
                start = f;
                break;
            }
        }
        std::vector<int> fan;
        std::vector<double> offset;
        double angle = 0.0;
        int f = start;
        while (f >= 0 && fan.size() <= around.size()) {
            fan.push_back(f);
            offset.push_back(angle);
            const int slot = slot_of(f, v);
            angle += corner_angle(f, slot);
            const int b = mesh.triangles[f][(slot + 2) % 3];
            f = face_with_directed_edge(v, b);
            if (f == start) break;
        }
        single_fan_[v] = fan.size() == around.size();
        fan_[v] = std::move(fan);
        fan_offset_[v] = std::move(offset);
    }
}

int Adjacency::face_with_directed_edge(int from, int to) const {
    const long long key = edge_key(from, to);
    auto it = std::lower_bound(directed_edges_.begin(), directed_edges_.end(), std::make_pair(key, -1));
    return it != directed_edges_.end() && it->first == key ? it->second : -1;
}

bool Adjacency::has_edge(int a, int b) const { return face_with_directed_edge(a, b) >= 0 || face_with_directed_edge(b, a) >= 0; }

double Adjacency::corner_angle(int f, int slot) const {
    const auto& t = mesh_.triangles[f];
    const Eigen::Vector3d& p = mesh_.positions[t[slot]];
    return angle_between(mesh_.positions[t[(slot + 1) % 3]] - p, mesh_.positions[t[(slot + 2) % 3]] - p);
}

std::vector<int> Adjacency::faces_containing(const SurfacePoint& p) const {
    std::vector<int> faces;
    switch (p.kind) {
        case PointKind::vertex:
            if (p.vertex >= 0 && p.vertex < num_vertices()) faces = faces_around_[p.vertex];
            break;
        case PointKind::edge:
            for (int f : {face_with_directed_edge(p.edge_v0, p.edge_v1), face_with_directed_edge(p.edge_v1, p.edge_v0)})
                if (f >= 0) faces.push_back(f);
            break;
        case PointKind::face:
            if (p.face >= 0 && p.face < static_cast<int>(mesh_.triangles.size())) faces.push_back(p.face);
            break;
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
}

double Adjacency::polar_angle(int v, int f, const Eigen::Vector3d& q) const {
    const auto& fan = fan_[v];
    const auto it = std::find(fan.begin(), fan.end(), f);
    if (it == fan.end()) throw std::logic_error("polar_angle: face is not in the vertex's fan");
    const auto& t = mesh_.triangles[f];
    const int slot = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    const Eigen::Vector3d& p = mesh_.positions[v];
    return fan_offset_[v][it - fan.begin()] + angle_between(mesh_.positions[t[(slot + 1) % 3]] - p, q - p);
}

std::vector<double> edge_dijkstra(const TriangleMesh& mesh, const std::vector<std::pair<int, double>>& seeds) {
    const int nv = static_cast<int>(mesh.positions.size());
    std::vector<std::vector<std::pair<int, double>>> graph(nv);
    for (const auto& t : mesh.triangles)
        for (int i = 0; i < 3; ++i) {
            const int a = t[i], b = t[(i + 1) % 3];
            const double length = (mesh.positions[a] - mesh.positions[b]).norm();
            graph[a].emplace_back(b, length);
            graph[b].emplace_back(a, length);
        }
    std::vector<double> dist(nv, inf);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (const auto& [v, d] : seeds)
        if (d < dist[v]) {
            dist[v] = d;
            queue.emplace(d, v);
        }
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > dist[v]) continue;
        for (const auto& [w, length] : graph[v])
            if (d + length < dist[w]) {
                dist[w] = d + length;
                queue.emplace(dist[w], w);
            }
    }
    return dist;
}

std::vector<std::pair<int, double>> dijkstra_seeds(const TriangleMesh& mesh, const SurfacePoint& p) {
    const Eigen::Vector3d x = point_position(mesh, p);
    std::vector<int> vertices;
    switch (p.kind) {
        case PointKind::vertex: vertices = {p.vertex}; break;
        case PointKind::edge: vertices = {p.edge_v0, p.edge_v1}; break;
        case PointKind::face: {
            const auto& t = mesh.triangles.at(p.face);
            vertices = {t[0], t[1], t[2]};
            break;
        }
    }
    std::vector<std::pair<int, double>> seeds;
    for (int v : vertices) seeds.emplace_back(v, p.kind == PointKind::vertex ? 0.0 : (mesh.positions[v] - x).norm());
    return seeds;
}

PathReport check_geodesic_path(const TriangleMesh& mesh, const Adjacency& adjacency,
                               const std::vector<SurfacePoint>& path, double angle_tolerance) {
    PathReport report;
    if (path.empty()) {
        report.problems.push_back("the path is empty");
        return report;
    }
    const double scale = bounding_diagonal(mesh);
    const double tiny = 1e-9 * scale;
    const double at_vertex = 1e-12 * scale;
    const int n = static_cast<int>(path.size());
    std::vector<Eigen::Vector3d> x(n);
    std::vector<std::vector<int>> faces(n);
    for (int i = 0; i < n; ++i) {
        const SurfacePoint& p = path[i];
        faces[i] = adjacency.faces_containing(p);
        if (faces[i].empty()) {
            report.problems.push_back("point " + std::to_string(i) + " (" + describe(p) + ") is not on the mesh");
            return report;
        }
        if (p.kind == PointKind::edge && !(p.t > 0.0 && p.t < 1.0))
            report.problems.push_back("edge point " + std::to_string(i) + " (" + describe(p) + ") has t outside (0, 1)");
        if (p.kind == PointKind::face) {
            if (i != 0 && i != n - 1)
                report.problems.push_back("interior point " + std::to_string(i) + " (" + describe(p) +
                                          ") is a face point, not an edge crossing or a vertex");
            if (!(p.bary[0] > 0.0 && p.bary[1] > 0.0 && p.bary[2] > 0.0) ||
                std::abs(p.bary[0] + p.bary[1] + p.bary[2] - 1.0) > 1e-12)
                report.problems.push_back("face point " + std::to_string(i) + " (" + describe(p) +
                                          ") has barycentric coordinates that are not positive or do not sum to 1");
        }
        x[i] = point_position(mesh, p);
    }
    for (int i = 0; i + 1 < n; ++i) {
        report.length += (x[i + 1] - x[i]).norm();
        std::vector<int> shared;
        std::set_intersection(faces[i].begin(), faces[i].end(), faces[i + 1].begin(), faces[i + 1].end(),
                              std::back_inserter(shared));
        if (shared.empty())
            report.problems.push_back("points " + std::to_string(i) + " (" + describe(path[i]) + ") and " +
                                      std::to_string(i + 1) + " (" + describe(path[i + 1]) + ") share no face");
        if (path[i] == path[i + 1])
            report.problems.push_back("points " + std::to_string(i) + " and " + std::to_string(i + 1) +
                                      " are the same (" + describe(path[i]) + ")");
    }
    if (!report.problems.empty()) return report;

    // The geometry is checked on the path with every interior edge point that lies numerically on a vertex (within
    // 1e-12 of the mesh size) replaced by that vertex, and runs of the same vertex merged: such a point is a vertex
    // passage, and is reported as a representation issue of its own.
    struct Effective {
        SurfacePoint p;
        Eigen::Vector3d x;
        std::vector<int> faces;
        int first;  // index in the path
    };
    std::vector<Effective> eff;
    for (int i = 0; i < n; ++i) {
        SurfacePoint p = path[i];
        if (p.kind == PointKind::edge && i != 0 && i != n - 1) {
            const double d0 = (x[i] - mesh.positions[p.edge_v0]).norm();
            const double d1 = (x[i] - mesh.positions[p.edge_v1]).norm();
            if (std::min(d0, d1) <= at_vertex) {
                const int v = d0 <= d1 ? p.edge_v0 : p.edge_v1;
                std::ostringstream message;
                message.precision(3);
                message << "point " << i << " (" << describe(p) << ") lies " << std::min(d0, d1) << " from vertex " << v
                        << ": a vertex passage given as an edge point";
                report.representation.push_back(message.str());
                p = SurfacePoint::at_vertex(v);
            }
        }
        if (!eff.empty() && eff.back().p == p) continue;
        eff.push_back({p, point_position(mesh, p), adjacency.faces_containing(p), i});
    }

    const auto face_area2 = [&](int f) {
        const auto& t = mesh.triangles[f];
        return (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]).norm();
    };
    const auto degenerate = [&](int f) { return face_area2(f) <= 1e-12 * scale * scale; };
    const auto common = [](const std::vector<int>& a, const std::vector<int>& b) {
        std::vector<int> c;
        std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(c));
        return c;
    };

    for (std::size_t k = 1; k + 1 < eff.size(); ++k) {
        const Effective &prev = eff[k - 1], &here = eff[k], &next = eff[k + 1];
        const SurfacePoint& p = here.p;
        const std::vector<int> shared_prev = common(prev.faces, here.faces), shared_next = common(here.faces, next.faces);
        std::ostringstream where;
        where.precision(17);
        where << "at point " << here.first << " (" << describe(p) << ") between " << describe(prev.p) << " and "
              << describe(next.p) << ": ";
        if (shared_prev.empty() || shared_next.empty()) {
            where << "no face shared with a neighbour once vertex passages are made vertices";
            report.problems.push_back(where.str());
            continue;
        }
        const Eigen::Vector3d to_prev = prev.x - here.x, to_next = next.x - here.x;
        bool any_degenerate = to_prev.norm() <= tiny || to_next.norm() <= tiny;
        for (int f : shared_prev) any_degenerate = any_degenerate || degenerate(f);
        for (int f : shared_next) any_degenerate = any_degenerate || degenerate(f);
        if (any_degenerate) {
            ++report.points_not_checked;
            continue;
        }
        if (p.kind == PointKind::edge) {
            ++report.edge_crossings_checked;
            const std::vector<int> all_three = common(shared_prev, shared_next);
            double sum;
            if (!all_three.empty()) {
                sum = angle_between(to_prev, to_next);  // all three points in one face: straight means angle π
            } else {
                const Eigen::Vector3d along = mesh.positions[p.edge_v1] - mesh.positions[p.edge_v0];
                sum = angle_between(to_prev, along) + angle_between(along, to_next);
            }
            if (std::abs(sum - k_pi) > angle_tolerance) {
                where << "the path is not straight across the edge: angle sum " << sum << ", π + " << (sum - k_pi);
                report.problems.push_back(where.str());
            }
        } else if (p.kind == PointKind::vertex) {
            ++report.vertices_checked;
            const int v = p.vertex;
            if (!adjacency.has_single_fan(v)) {
                ++report.points_not_checked;
                continue;
            }
            const double cone = adjacency.cone_angle(v);
            const double a_prev = adjacency.polar_angle(v, shared_prev.front(), prev.x);
            const double a_next = adjacency.polar_angle(v, shared_next.front(), next.x);
            const double side = std::abs(a_next - a_prev);
            if (adjacency.is_boundary(v)) {
                if (side < k_pi - angle_tolerance) {
                    where << "at boundary vertex " << v << " the path turns by " << side
                          << " < π inside the surface (fan angle " << cone << ")";
                    report.problems.push_back(where.str());
                }
            } else if (cone < 2.0 * k_pi - angle_tolerance) {
                where << "the path passes through vertex " << v << " with cone angle " << cone << " < 2π";
                report.problems.push_back(where.str());
            } else if (side < k_pi - angle_tolerance || cone - side < k_pi - angle_tolerance) {
                where << "at saddle vertex " << v << " (cone angle " << cone << ") the sides are " << side << " and "
                      << cone - side << ", one less than π";
                report.problems.push_back(where.str());
            }
        }
    }
    return report;
}

double box_surface_distance(const Eigen::Vector3d& size, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    // Face 2·axis + side; corners listed counter-clockwise seen from outside.
    struct BoxFace {
        int axis;
        int side;
        std::array<Eigen::Vector3d, 4> corners;
    };
    std::vector<BoxFace> faces;
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // u x w = +axis
            Eigen::Vector3d base = Eigen::Vector3d::Zero();
            base[axis] = side ? size[axis] : 0.0;
            Eigen::Vector3d du = Eigen::Vector3d::Zero(), dw = Eigen::Vector3d::Zero();
            du[u] = size[u];
            dw[w] = size[w];
            BoxFace face{axis, side, {}};
            if (side)
                face.corners = {base, Eigen::Vector3d(base + du), Eigen::Vector3d(base + du + dw), Eigen::Vector3d(base + dw)};
            else
                face.corners = {base, Eigen::Vector3d(base + dw), Eigen::Vector3d(base + du + dw), Eigen::Vector3d(base + du)};
            faces.push_back(face);
        }
    }
    const double scale = size.norm();
    const auto on_face = [&](const Eigen::Vector3d& x, const BoxFace& face) {
        for (int k = 0; k < 3; ++k)
            if (x[k] < -1e-12 * scale || x[k] > size[k] + 1e-12 * scale) return false;
        return std::abs(x[face.axis] - (face.side ? size[face.axis] : 0.0)) <= 1e-12 * scale;
    };
    const auto snapped = [&](Eigen::Vector3d x, const BoxFace& face) {
        x[face.axis] = face.side ? size[face.axis] : 0.0;
        for (int k = 0; k < 3; ++k) x[k] = std::clamp(x[k], 0.0, size[k]);
        return x;
    };
    // Two faces are adjacent when their axes differ; their shared edge is the pair of common corners.
    const auto shared_edge = [&](int a, int b) {
        std::vector<Eigen::Vector3d> common;
        for (const auto& ca : faces[a].corners)
            for (const auto& cb : faces[b].corners)
                if (ca == cb) common.push_back(ca);
        if (common.size() != 2) throw std::logic_error("box faces do not share an edge");
        return std::make_pair(common[0], common[1]);
    };
    // Lays x (a point of the new face) in the plane, given the shared edge s-t in 3D and in 2D, on the side away
    // from `away` (a 2D point of the previous face, off the edge line).
    const auto place = [](const Eigen::Vector3d& x, const Eigen::Vector3d& s, const Eigen::Vector3d& t,
                          const Eigen::Vector2d& s2, const Eigen::Vector2d& t2, const Eigen::Vector2d& away) {
        const Eigen::Vector3d u = (t - s).normalized();
        const double along = (x - s).dot(u);
        const double perp = ((x - s) - along * u).norm();
        const Eigen::Vector2d u2 = (t2 - s2).normalized();
        Eigen::Vector2d n2(-u2.y(), u2.x());
        if (n2.dot(away - s2) > 0.0) n2 = -n2;
        return Eigen::Vector2d(s2 + along * u2 + perp * n2);
    };

    double best = inf;
    for (int start = 0; start < 6; ++start) {
        if (!on_face(p, faces[start])) continue;
        const Eigen::Vector3d ps = snapped(p, faces[start]);
        // 2D frame of the first face.
        const Eigen::Vector3d origin = faces[start].corners[0];
        const Eigen::Vector3d e1 = (faces[start].corners[1] - origin).normalized();
        const Eigen::Vector3d e2 = (faces[start].corners[3] - origin).normalized();
        const auto to2 = [&](const Eigen::Vector3d& x) { return Eigen::Vector2d((x - origin).dot(e1), (x - origin).dot(e2)); };
        const Eigen::Vector2d p2 = to2(ps);

        struct Step {
            int face;
            std::array<Eigen::Vector2d, 4> corners2;
            Eigen::Vector2d edge_s, edge_t;  // the edge crossed to enter this face (unused for the first)
        };
        std::vector<Step> chain;
        Step first{start, {}, {}, {}};
        for (int k = 0; k < 4; ++k) first.corners2[k] = to2(faces[start].corners[k]);
        chain.push_back(first);

        std::function<void()> extend = [&]() {
            const Step last = chain.back();  // a copy: the recursion grows the chain
            const BoxFace& face = faces[last.face];
            if (on_face(q, face)) {
                const Eigen::Vector3d qs = snapped(q, face);
                Eigen::Vector2d q2;
                if (chain.size() == 1) {
                    q2 = to2(qs);
                } else {
                    // q from its offsets to the face's corners 0 and 1 and the face's orientation in the plane.
                    const Eigen::Vector2d c0 = last.corners2[0], c1 = last.corners2[1], c3 = last.corners2[3];
                    const Eigen::Vector3d o = face.corners[0];
                    const Eigen::Vector3d a1 = (face.corners[1] - o).normalized(), a3 = (face.corners[3] - o).normalized();
                    q2 = c0 + (qs - o).dot(a1) * (c1 - c0).normalized() + (qs - o).dot(a3) * (c3 - c0).normalized();
                }
                const Eigen::Vector2d d = q2 - p2;
                bool valid = true;
                double previous = 0.0;
                for (std::size_t k = 1; k < chain.size() && valid; ++k) {
                    const Eigen::Vector2d s = chain[k].edge_s, e = chain[k].edge_t - chain[k].edge_s;
                    const double denom = d.x() * e.y() - d.y() * e.x();
                    if (std::abs(denom) <= 1e-300) {
                        valid = false;
                        break;
                    }
                    const Eigen::Vector2d r = s - p2;
                    const double lambda = (r.x() * e.y() - r.y() * e.x()) / denom;
                    const double mu = (r.x() * d.y() - r.y() * d.x()) / denom;
                    const double eps = 1e-12;
                    valid = lambda >= -eps && lambda <= 1.0 + eps && mu >= -eps && mu <= 1.0 + eps &&
                            lambda >= previous - eps;
                    previous = lambda;
                }
                if (valid) best = std::min(best, d.norm());
            }
            for (int next = 0; next < 6; ++next) {
                if (faces[next].axis == face.axis) continue;
                bool used = false;
                for (const Step& s : chain) used = used || s.face == next;
                if (used) continue;
                const auto [s3, t3] = shared_edge(last.face, next);
                int is = -1, it = -1;
                for (int k = 0; k < 4; ++k) {
                    if (face.corners[k] == s3) is = k;
                    if (face.corners[k] == t3) it = k;
                }
                // A corner of the current face off the shared edge tells which side to avoid.
                int off = 0;
                while (off == is || off == it) ++off;
                Step step{next, {}, last.corners2[is], last.corners2[it]};
                for (int k = 0; k < 4; ++k)
                    step.corners2[k] = place(faces[next].corners[k], s3, t3, step.edge_s, step.edge_t, last.corners2[off]);
                chain.push_back(step);
                extend();
                chain.pop_back();
            }
        };
        extend();
    }
    return best;
}

CellPolygon::CellPolygon(std::vector<std::string> rows) : rows_(std::move(rows)) {
    num_rows_ = static_cast<int>(rows_.size());
    for (const auto& r : rows_) num_cols_ = std::max(num_cols_, static_cast<int>(r.size()));
    for (int y = 0; y <= num_rows_; ++y)
        for (int x = 0; x <= num_cols_; ++x) {
            const int around = filled(x - 1, y - 1) + filled(x, y - 1) + filled(x - 1, y) + filled(x, y);
            if (around == 3) reflex_.emplace_back(x, y);
        }
}

bool CellPolygon::filled(int cx, int cy) const {
    if (cx < 0 || cy < 0 || cx >= num_cols_ || cy >= num_rows_) return false;
    const std::string& r = rows_[num_rows_ - 1 - cy];
    return cx < static_cast<int>(r.size()) && r[cx] == '#';
}

bool CellPolygon::contains(const Eigen::Vector2d& p) const {
    const double eps = 1e-12;
    for (int cx : {static_cast<int>(std::floor(p.x() - eps)), static_cast<int>(std::floor(p.x() + eps))})
        for (int cy : {static_cast<int>(std::floor(p.y() - eps)), static_cast<int>(std::floor(p.y() + eps))})
            if (filled(cx, cy) && p.x() >= cx - eps && p.x() <= cx + 1 + eps && p.y() >= cy - eps &&
                p.y() <= cy + 1 + eps)
                return true;
    return false;
}

bool CellPolygon::segment_inside(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
    if (!contains(a) || !contains(b)) return false;
    // Between two consecutive crossings of grid lines the segment stays in one closed cell (or on one grid line,
    // between the same two cells), so its midpoint decides.
    std::vector<double> ts = {0.0, 1.0};
    for (int axis = 0; axis < 2; ++axis) {
        const double lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
        if (hi - lo <= 0.0) continue;
        for (int k = static_cast<int>(std::ceil(lo)); k <= static_cast<int>(std::floor(hi)); ++k)
            ts.push_back((k - a[axis]) / (b[axis] - a[axis]));
    }
    std::sort(ts.begin(), ts.end());
    for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
        if (ts[i + 1] - ts[i] <= 1e-15) continue;
        const double t = 0.5 * (ts[i] + ts[i + 1]);
        if (!contains(a + t * (b - a))) return false;
    }
    return true;
}

double CellPolygon::shortest_path_length(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
    std::vector<Eigen::Vector2d> nodes = {a, b};
    nodes.insert(nodes.end(), reflex_.begin(), reflex_.end());
    const int n = static_cast<int>(nodes.size());
    std::vector<double> dist(n, inf);
    std::vector<char> done(n, 0);
    dist[0] = 0.0;
    for (int round = 0; round < n; ++round) {
        int u = -1;
        for (int i = 0; i < n; ++i)
            if (!done[i] && (u < 0 || dist[i] < dist[u])) u = i;
        if (u < 0 || dist[u] == inf) break;
        done[u] = 1;
        for (int w = 0; w < n; ++w) {
            if (done[w]) continue;
            if (!segment_inside(nodes[u], nodes[w])) continue;
            dist[w] = std::min(dist[w], dist[u] + (nodes[w] - nodes[u]).norm());
        }
    }
    return dist[1];
}

bool near_relative(double got, double expected, double relative, double floor) {
    if (std::isinf(expected) || std::isinf(got)) return got == expected;
    return std::abs(got - expected) <= relative * std::max(std::abs(expected), floor);
}

}  // namespace geotri::test

namespace geotri::test {

double PointSampler::uniform(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng_() >> 5) * (1.0 / 134217728.0));
}

int PointSampler::vertex(const TriangleMesh& mesh) {
    return static_cast<int>(rng_() % static_cast<unsigned>(mesh.positions.size()));
}

geodesic::SurfacePoint PointSampler::face_point(const TriangleMesh& mesh) {
    const int f = static_cast<int>(rng_() % static_cast<unsigned>(mesh.triangles.size()));
    const double b0 = uniform(0.05, 0.9);
    const double b1 = uniform(0.05, 0.95 - b0);
    return geodesic::SurfacePoint::in_face(f, {b0, b1, 1.0 - b0 - b1});
}

geodesic::SurfacePoint PointSampler::edge_point(const TriangleMesh& mesh) {
    const int f = static_cast<int>(rng_() % static_cast<unsigned>(mesh.triangles.size()));
    const int i = static_cast<int>(rng_() % 3u);
    int v0 = mesh.triangles[f][i], v1 = mesh.triangles[f][(i + 1) % 3];
    double t = uniform(0.1, 0.9);
    if (v0 > v1) {
        std::swap(v0, v1);
        t = 1.0 - t;
    }
    return geodesic::SurfacePoint::on_edge(v0, v1, t);
}

}  // namespace geotri::test

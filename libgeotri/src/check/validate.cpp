#include <geodesic/constants.h>
#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/overlay.h>
#include <geotri/tangent_angles.h>
#include <geotri/validate.h>

#include "check/crossing_items.h"
#include "check/local_checks.h"
#include "check/polyline_verdicts.h"
#include "core/coarse_components.h"
#include "core/plane_segments.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <utility>

namespace geotri {

using geodesic::Mesh;
using geodesic::PointKind;

using detail::CrossingItems;
using detail::EdgeInterval;
using detail::EdgePoint;
using detail::FaceSegment;
using detail::Item;
using detail::k_meet_tolerance;
using detail::point_segment_distance;
using detail::polyline_crossing_items;
using detail::segment_distance;

namespace {

using geodesic::k_pi;
constexpr double k_length_tolerance = 1e-12;    // relative
constexpr double k_min_corner = 1e-12;          // rad
constexpr double k_area_tolerance = 1e-9;       // relative

std::string degrees(double radians) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g°", radians * 180.0 / k_pi);
    return buffer;
}

std::string number(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", x);
    return buffer;
}

/// The key of the fine edge of halfedge h: the smaller of its halfedges (T is closed and manifold: FineMesh).
int edge_key(const Mesh& mesh, int h) {
    const int twin = mesh.twin(h);
    return twin < 0 ? h : std::min(h, twin);
}

/// The key of the fine edge {a, b}.
int edge_key(const Mesh& mesh, int a, int b) {
    const int h = mesh.find_halfedge(a, b);
    return edge_key(mesh, h >= 0 ? h : mesh.find_halfedge(b, a));
}

/// Files p, a point of `item`, under the fine vertex or edge that holds it (nothing for a point inside a face).
void add_point(const Mesh& mesh, const SurfacePoint& p, const Item& item, CrossingItems& out) {
    if (p.kind == PointKind::vertex) {
        out.vertex_items.emplace_back(p.vertex, item);
    } else if (p.kind == PointKind::edge) {
        out.edge_points.push_back({edge_key(mesh, p.edge_v0, p.edge_v1), p.t, item});
    }
}

/// Empty when the consecutive points of `path` are apart and share a fine face, else the first pair that does not.
std::string points_defect(const Mesh& mesh, const Polyline& path) {
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
        if (path[i] == path[i + 1]) return "repeats point " + std::to_string(i);
        if (common_face(mesh, path[i], path[i + 1]) < 0)
            return "has points " + std::to_string(i) + " and " + std::to_string(i + 1) + " on no common fine face";
    }
    return {};
}

}  // namespace

namespace detail {

SurfacePoint canonical_location(const Mesh& mesh, const SurfacePoint& location, int v) {
    try {
        return mesh.canonical(location);
    } catch (const InvalidInput& e) {
        throw InvalidInput("coarse vertex " + std::to_string(v) + ": location: " + e.what());
    }
}

Polyline canonical_polyline(const Mesh& mesh, const Polyline& raw, int e) {
    Polyline path;
    path.reserve(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) {
        try {
            path.push_back(mesh.canonical(raw[i]));
        } catch (const InvalidInput& ex) {
            throw InvalidInput("coarse edge " + std::to_string(e) + ": point " + std::to_string(i) + ": " + ex.what());
        }
    }
    return path;
}

CrossingItems polyline_crossing_items(const Mesh& mesh, const Polyline& path) {
    CrossingItems out;
    const int n = static_cast<int>(path.size());
    for (int i = 0; i < n; ++i) add_point(mesh, path[i], {0, i}, out);
    for (int i = 0; i + 1 < n; ++i) {
        const SurfacePoint& p = path[i];
        const SurfacePoint& q = path[i + 1];
        if (on_common_edge(mesh, p, q)) {
            const auto [a, b] = common_edge(p, q);
            auto param = [a = a](const SurfacePoint& s) {
                return s.kind == PointKind::vertex ? (s.vertex == a ? 0.0 : 1.0) : s.t;
            };
            const double tp = param(p), tq = param(q);
            out.edge_intervals.push_back({edge_key(mesh, a, b), std::min(tp, tq), std::max(tp, tq), 0, i});
        } else {
            const int f = common_face(mesh, p, q);
            out.face_segments.push_back({f,
                                         {Item{0, i}, Item{0, i + 1}},
                                         {halfedge_coordinates(mesh, 3 * f, p), halfedge_coordinates(mesh, 3 * f, q)},
                                         i});
        }
    }
    return out;
}

CrossingItems location_crossing_items(const Mesh& mesh, const SurfacePoint& location) {
    CrossingItems out;
    const Item item{0, 0};
    if (location.kind == PointKind::face) {
        const Eigen::Vector2d x = halfedge_coordinates(mesh, 3 * location.face, location);
        out.face_segments.push_back({location.face, {item, item}, {x, x}, -1});
    } else {
        add_point(mesh, location, item, out);
    }
    return out;
}

std::string polyline_violation(const Mesh& mesh, const Polyline& path, int from, const SurfacePoint& from_location,
                               int to, const SurfacePoint& to_location, const std::string* known,
                               double recorded_length, bool& usable) {
    usable = false;
    if (path.size() < 2) return path.empty() ? "has no polyline" : "has a polyline of one point";
    if (path.front() != from_location) return "does not start at the location of coarse vertex " + std::to_string(from);
    if (path.back() != to_location) return "does not end at the location of coarse vertex " + std::to_string(to);
    // A known verdict is only kept for a polyline whose points are apart and pairwise on a common fine face.
    if (!known) {
        std::string apart = points_defect(mesh, path);
        if (!apart.empty()) return apart;
    }
    usable = true;
    return known ? *known : shape_defect(mesh, path, recorded_length);
}

VertexCorners vertex_corners(const Mesh& mesh, const SurfacePoint& location, const std::vector<double>& polar_angles) {
    VertexCorners out;
    out.theta = cone_angle(mesh, location);
    const std::size_t n = polar_angles.size();
    out.corners.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double corner = ccw_angle(polar_angles[i], polar_angles[(i + 1) % n], out.theta);
        out.corners.push_back(corner);
        out.sum += corner;
        if (corner <= k_min_corner && out.first_bad < 0) out.first_bad = static_cast<int>(i);
    }
    out.winding = std::lround(out.sum / out.theta);
    return out;
}

Violation corner_violation(const CoarseMesh& coarse, int c, const std::vector<OpenMesh::HalfedgeHandle>& out,
                           int first_bad) {
    Violation v;
    v.condition = 2;
    v.coarse_vertices = {c};
    auto name = [&](OpenMesh::HalfedgeHandle h) {
        v.coarse_edges.push_back(coarse.edge_handle(h).idx());
        if (coarse.face_handle(h).is_valid()) v.coarse_faces.push_back(coarse.face_handle(h).idx());
    };
    if (first_bad >= 0) {
        const std::size_t i = static_cast<std::size_t>(first_bad);
        name(out[i]);
        v.coarse_edges.push_back(coarse.edge_handle(out[(i + 1) % out.size()]).idx());
    } else {
        for (OpenMesh::HalfedgeHandle h : out) name(h);
    }
    return v;
}

Violation meeting_violation(const MeetingSide& a, const MeetingSide& b) {
    Violation v;
    v.condition = 3;
    for (const MeetingSide* s : {&a, &b}) {
        if (s->is_vertex) {
            v.coarse_vertices.push_back(s->index);
            continue;
        }
        if (s == &b && !a.is_vertex && a.index == b.index) continue;  // an edge that meets itself
        v.coarse_edges.push_back(s->index);
        v.coarse_vertices.insert(v.coarse_vertices.end(), {s->from, s->to});
    }
    std::sort(v.coarse_edges.begin(), v.coarse_edges.end());
    std::sort(v.coarse_vertices.begin(), v.coarse_vertices.end());
    v.coarse_vertices.erase(std::unique(v.coarse_vertices.begin(), v.coarse_vertices.end()), v.coarse_vertices.end());
    return v;
}

}  // namespace detail

namespace {

class Validator {
public:
    Validator(const GeodesicTriangulation& g, ValidationReport& report,
              const detail::PolylineVerdicts* known = nullptr)
        : g_(g), mesh_(g.fine().mesh), coarse_(g.coarse()), report_(report), known_(known) {}

    void run(const ValidationOptions& options);
    /// Adds condition 4 to a report that run() made without the overlay.
    void add_patches();

private:
    void prepare();
    void check_geodesics();
    void check_polyline(int e);
    void check_corners();
    void check_crossings();
    void check_patches();
    void summarise();

    void add(Violation v) {
        ++report_.violation_count[static_cast<std::size_t>(v.condition - 1)];
        report_.violations.push_back(std::move(v));
    }
    std::string edge_name(int e) const {
        return "coarse edge " + std::to_string(e) + " (" + std::to_string(ends_[e][0]) + "-" +
               std::to_string(ends_[e][1]) + ")";
    }
    int num_edges() const { return static_cast<int>(paths_.size()); }
    bool is_polyline(const Item& i) const { return i.feature < num_edges(); }
    const SurfacePoint& point_of(const Item& i) const {
        return is_polyline(i) ? paths_[i.feature][i.index] : locations_[i.feature - num_edges()];
    }
    /// The coarse vertex at this point when it is an end of its polyline or a coarse vertex, else -1.
    int end_vertex(const Item& i) const {
        if (!is_polyline(i)) return i.feature - num_edges();
        if (i.index == 0) return ends_[i.feature][0];
        if (i.index + 1 == static_cast<int>(paths_[i.feature].size())) return ends_[i.feature][1];
        return -1;
    }
    bool allowed(const Item& a, const Item& b) const;
    void meet(const Item& a, const Item& b, const std::string& where);

    const GeodesicTriangulation& g_;
    const Mesh& mesh_;
    const CoarseMesh& coarse_;
    ValidationReport& report_;
    const detail::PolylineVerdicts* known_;  ///< verdicts of condition 1 already known, or null

    std::vector<Polyline> paths_;                ///< per coarse edge index, in canonical form (empty for a deleted edge)
    std::vector<std::array<int, 2>> ends_;       ///< per coarse edge: from and to vertex of halfedge 0
    std::vector<SurfacePoint> locations_;        ///< per coarse vertex, in canonical form
    std::vector<unsigned char> path_ok_;         ///< per coarse edge: ends match and every segment shares a face
    std::vector<double> corner_angles_;          ///< every coarse corner angle that could be measured

    CrossingItems items_;  ///< condition 3: every point and segment of G, with the fine element that holds it
    std::map<std::pair<int, int>, std::string> meetings_;
};

void Validator::run(const ValidationOptions& options) {
    prepare();
    check_geodesics();
    check_corners();
    check_crossings();
    if (options.overlay) check_patches();
    summarise();
    report_.valid = std::all_of(report_.violation_count.begin(), report_.violation_count.end(),
                                [](int c) { return c == 0; });
}

void Validator::add_patches() {
    check_patches();
    report_.valid = report_.valid && report_.violation_count[3] == 0;
}

void Validator::prepare() {
    locations_.assign(coarse_.n_vertices(), SurfacePoint::at_vertex(-1));
    for (auto v : coarse_.vertices()) locations_[v.idx()] = detail::canonical_location(mesh_, g_.location(v), v.idx());
    paths_.assign(coarse_.n_edges(), Polyline{});
    ends_.assign(coarse_.n_edges(), {-1, -1});
    path_ok_.assign(coarse_.n_edges(), 0);
    for (auto e : coarse_.edges()) {
        const auto h = coarse_.halfedge_handle(e, 0);
        ends_[e.idx()] = {coarse_.from_vertex_handle(h).idx(), coarse_.to_vertex_handle(h).idx()};
        const Polyline* known = known_ ? known_->canonical(g_, e) : nullptr;  // canonicalised with its verdict
        paths_[e.idx()] = known ? *known : detail::canonical_polyline(mesh_, g_.polyline(e), e.idx());
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Condition 1

void Validator::check_geodesics() {
    for (auto e : coarse_.edges()) check_polyline(e.idx());
}

void Validator::check_polyline(int e) {
    const OpenMesh::EdgeHandle handle(e);
    const std::string* known = known_ ? known_->find(g_, handle) : nullptr;
    bool usable = false;
    const auto [from, to] = ends_[e];
    const std::string why = detail::polyline_violation(mesh_, paths_[e], from, locations_[from], to, locations_[to],
                                                       known, g_.length(handle), usable);
    path_ok_[e] = usable ? 1 : 0;
    if (why.empty()) return;
    Violation v;
    v.condition = 1;
    v.what = edge_name(e) + " " + why;
    v.coarse_edges = {e};
    v.coarse_vertices = {ends_[e][0], ends_[e][1]};
    add(std::move(v));
}

// ---------------------------------------------------------------------------------------------------------------
// Condition 2

void Validator::check_corners() {
    for (auto c : coarse_.vertices()) {
        const auto start = coarse_.halfedge_handle(c);
        if (!start.is_valid()) continue;
        std::vector<OpenMesh::HalfedgeHandle> out;
        std::vector<double> angle;
        bool measurable = true;
        auto h = start;
        do {
            const int e = coarse_.edge_handle(h).idx();
            if (!path_ok_[e]) {
                measurable = false;
                break;
            }
            const Polyline& path = paths_[e];
            const bool forward = h == coarse_.halfedge_handle(coarse_.edge_handle(h), 0);
            const SurfacePoint& p = forward ? path[0] : path[path.size() - 1];
            const SurfacePoint& q = forward ? path[1] : path[path.size() - 2];
            out.push_back(h);
            angle.push_back(polar_angle(mesh_, p, q));
            h = coarse_.ccw_rotated_halfedge_handle(h);
        } while (h != start && out.size() <= coarse_.n_halfedges());
        if (!measurable || out.empty()) continue;  // condition 1 already names the broken polyline

        const detail::VertexCorners corners = detail::vertex_corners(mesh_, locations_[c.idx()], angle);
        corner_angles_.insert(corner_angles_.end(), corners.corners.begin(), corners.corners.end());
        if (!corners.violated()) continue;
        const std::size_t n = out.size();
        const double theta = corners.theta, sum = corners.sum;
        const int first_bad = corners.first_bad;
        const long winding = corners.winding;

        Violation v = detail::corner_violation(coarse_, c.idx(), out, first_bad);
        const std::string name = "coarse vertex " + std::to_string(c.idx());
        if (first_bad >= 0) {
            const auto h0 = out[static_cast<std::size_t>(first_bad)];
            const auto h1 = out[(static_cast<std::size_t>(first_bad) + 1) % n];
            v.what = name + ": the corner of coarse face " + std::to_string(coarse_.face_handle(h0).idx()) +
                     " between coarse edges " + std::to_string(coarse_.edge_handle(h0).idx()) + " and " +
                     std::to_string(coarse_.edge_handle(h1).idx()) + " is not positive (geodesics in the wrong " +
                     "order or overlapping)";
            if (winding != 1) v.what += "; they wind " + std::to_string(winding) + " times around it";
        } else {
            v.what = name + ": its geodesics wind " + std::to_string(winding) + " times around it (corner angles " +
                     "sum to " + degrees(sum) + ", cone angle " + degrees(theta) + ")";
        }
        add(std::move(v));
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Condition 3

bool Validator::allowed(const Item& a, const Item& b) const {
    if (a.feature == b.feature && a.index == b.index) return true;
    const bool pa = is_polyline(a), pb = is_polyline(b);
    if (!pa && !pb) return false;  // two coarse vertices at one point
    if (pa && pb && a.feature == b.feature) return std::abs(a.index - b.index) == 1;  // consecutive points
    const int va = end_vertex(a), vb = end_vertex(b);
    return va >= 0 && va == vb;
}

void Validator::meet(const Item& a, const Item& b, const std::string& where) {
    const auto key = std::minmax(a.feature, b.feature);
    meetings_.emplace(std::make_pair(key.first, key.second), where);
}

void Validator::check_crossings() {
    const int ne = num_edges();
    // Bucket every point and segment by the fine vertex, edge or face that holds it.
    for (int e = 0; e < ne; ++e) {
        if (!path_ok_[e]) continue;
        const CrossingItems* items = known_ ? known_->crossing_items(g_, OpenMesh::EdgeHandle(e)) : nullptr;
        CrossingItems own;
        if (!items) {
            own = polyline_crossing_items(mesh_, paths_[e]);
            items = &own;
        }
        for (auto [vertex, item] : items->vertex_items) items_.vertex_items.emplace_back(vertex, Item{e, item.index});
        for (EdgePoint p : items->edge_points) {
            p.item.feature = e;
            items_.edge_points.push_back(p);
        }
        for (EdgeInterval s : items->edge_intervals) {
            s.feature = e;
            items_.edge_intervals.push_back(s);
        }
        for (FaceSegment s : items->face_segments) {
            s.end[0].feature = s.end[1].feature = e;
            items_.face_segments.push_back(s);
        }
    }
    for (auto c : coarse_.vertices()) {
        const int feature = ne + c.idx();
        CrossingItems own = detail::location_crossing_items(mesh_, locations_[c.idx()]);
        for (auto [vertex, item] : own.vertex_items) items_.vertex_items.emplace_back(vertex, Item{feature, 0});
        for (EdgePoint p : own.edge_points) {
            p.item.feature = feature;
            items_.edge_points.push_back(p);
        }
        for (FaceSegment s : own.face_segments) {
            s.end[0].feature = s.end[1].feature = feature;
            items_.face_segments.push_back(s);
        }
    }

    // Points on one fine vertex.
    std::sort(items_.vertex_items.begin(), items_.vertex_items.end(), [](const auto& x, const auto& y) {
        return x.first < y.first || (x.first == y.first && x.second.feature < y.second.feature);
    });
    for (std::size_t i = 0; i < items_.vertex_items.size();) {
        std::size_t j = i;
        while (j < items_.vertex_items.size() && items_.vertex_items[j].first == items_.vertex_items[i].first) ++j;
        for (std::size_t a = i; a < j; ++a)
            for (std::size_t b = a + 1; b < j; ++b)
                if (!allowed(items_.vertex_items[a].second, items_.vertex_items[b].second))
                    meet(items_.vertex_items[a].second, items_.vertex_items[b].second,
                         "at fine vertex " + std::to_string(items_.vertex_items[i].first));
        i = j;
    }

    // Points and segments on one fine edge: coincident points, points inside a segment along the edge, and
    // segments that overlap along it.
    std::sort(items_.edge_points.begin(), items_.edge_points.end(),
              [](const EdgePoint& x, const EdgePoint& y) { return x.key < y.key || (x.key == y.key && x.t < y.t); });
    std::sort(items_.edge_intervals.begin(), items_.edge_intervals.end(),
              [](const EdgeInterval& x, const EdgeInterval& y) { return x.key < y.key || (x.key == y.key && x.t0 < y.t0); });
    auto edge_where = [&](int key) {
        return "on fine edge (" + std::to_string(mesh_.tail(key)) + "," + std::to_string(mesh_.head(key)) + ")";
    };
    // The points at a fine vertex (vertex_items is sorted), for the points on its edges a hair away from it.
    using VertexItem = std::pair<int, Item>;
    auto at_vertex = [&](int vertex) {
        const auto& items = items_.vertex_items;
        const auto first = std::lower_bound(items.begin(), items.end(), vertex,
                                            [](const VertexItem& x, int value) { return x.first < value; });
        const auto last = std::upper_bound(first, items.end(), vertex,
                                           [](int value, const VertexItem& x) { return value < x.first; });
        return std::make_pair(first, last);
    };
    const std::vector<EdgePoint>& points = items_.edge_points;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const EdgePoint& p = points[i];
        for (std::size_t j = i + 1;
             j < points.size() && points[j].key == p.key && points[j].t - p.t <= k_meet_tolerance; ++j) {
            if (!allowed(p.item, points[j].item)) meet(p.item, points[j].item, edge_where(p.key));
        }
        // The points at the edge's ends, where p is a hair away from one (t is 0 at the end of smaller index).
        const int tail = mesh_.tail(p.key), head = mesh_.head(p.key);
        const int a = std::min(tail, head), b = std::max(tail, head);
        const std::pair<int, bool> ends[] = {{a, p.t <= k_meet_tolerance}, {b, 1.0 - p.t <= k_meet_tolerance}};
        for (const auto& [end, near] : ends) {
            if (!near) continue;
            const auto [first, last] = at_vertex(end);
            for (auto v = first; v != last; ++v)
                if (!allowed(v->second, p.item)) meet(v->second, p.item, edge_where(p.key));
        }
    }
    for (std::size_t i = 0; i < items_.edge_intervals.size(); ++i) {
        const EdgeInterval& s = items_.edge_intervals[i];
        const Item item{s.feature, s.segment};
        auto first = std::lower_bound(items_.edge_points.begin(), items_.edge_points.end(), s,
                                      [](const EdgePoint& p, const EdgeInterval& x) {
                                          return p.key < x.key || (p.key == x.key && p.t <= x.t0 + k_meet_tolerance);
                                      });
        for (auto p = first; p != items_.edge_points.end() && p->key == s.key && p->t < s.t1 - k_meet_tolerance; ++p)
            meet(item, p->item, edge_where(s.key));
        for (std::size_t j = i + 1; j < items_.edge_intervals.size() && items_.edge_intervals[j].key == s.key; ++j) {
            const EdgeInterval& r = items_.edge_intervals[j];
            if (std::min(s.t1, r.t1) - std::max(s.t0, r.t0) > k_meet_tolerance)
                meet(item, {r.feature, r.segment}, edge_where(s.key));
        }
    }

    // Segments inside one fine face.
    std::sort(items_.face_segments.begin(), items_.face_segments.end(),
              [](const FaceSegment& x, const FaceSegment& y) { return x.face < y.face; });
    for (std::size_t i = 0; i < items_.face_segments.size();) {
        std::size_t j = i;
        while (j < items_.face_segments.size() && items_.face_segments[j].face == items_.face_segments[i].face) ++j;
        if (j - i > 1) {
            const int f = items_.face_segments[i].face;
            const double tolerance =
                k_meet_tolerance * std::max({mesh_.length(3 * f), mesh_.length(3 * f + 1), mesh_.length(3 * f + 2)});
            const std::string where = "in fine face " + std::to_string(f);
            for (std::size_t a = i; a < j; ++a) {
                for (std::size_t b = a + 1; b < j; ++b) {
                    const FaceSegment& s = items_.face_segments[a];
                    const FaceSegment& r = items_.face_segments[b];
                    if (s.end[0].feature == r.end[0].feature && s.segment >= 0 && std::abs(s.segment - r.segment) <= 1)
                        continue;  // one polyline's consecutive segments
                    int shared_s = -1, shared_r = -1;
                    for (int u = 0; u < 2 && shared_s < 0; ++u)
                        for (int w = 0; w < 2 && shared_s < 0; ++w)
                            if (point_of(s.end[u]) == point_of(r.end[w])) {
                                shared_s = u;
                                shared_r = w;
                            }
                    if (shared_s >= 0) {
                        if (!allowed(s.end[shared_s], r.end[shared_r])) {
                            meet(s.end[shared_s], r.end[shared_r], where);
                        } else if (s.segment >= 0 && r.segment >= 0) {
                            // Two geodesics from a common end overlap when one's far end lies on the other.
                            const Eigen::Vector2d& xs = s.x[1 - shared_s];
                            const Eigen::Vector2d& xr = r.x[1 - shared_r];
                            if (point_segment_distance(xs, r.x[0], r.x[1]) <= tolerance ||
                                point_segment_distance(xr, s.x[0], s.x[1]) <= tolerance)
                                meet(s.end[0], r.end[0], where);
                        }
                        continue;
                    }
                    if (segment_distance(s.x[0], s.x[1], r.x[0], r.x[1]) <= tolerance) meet(s.end[0], r.end[0], where);
                }
            }
        }
        i = j;
    }

    auto side = [&](int feature) {
        return feature < ne ? detail::MeetingSide{false, feature, ends_[feature][0], ends_[feature][1]}
                            : detail::MeetingSide{true, feature - ne, -1, -1};
    };
    for (const auto& [pair, where] : meetings_) {
        const auto [a, b] = pair;
        Violation v = detail::meeting_violation(side(a), side(b));
        if (a < ne && b < ne)
            v.what = a == b ? edge_name(a) + " meets itself " + where
                            : edge_name(a) + " and " + edge_name(b) + " meet " + where;
        else if (a < ne)
            v.what = edge_name(a) + " passes through coarse vertex " + std::to_string(b - ne) + " " + where;
        else
            v.what = "coarse vertices " + std::to_string(a - ne) + " and " + std::to_string(b - ne) +
                     " are at the same point " + where;
        add(std::move(v));
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Condition 4

void Validator::check_patches() {
    report_.overlay_checked = true;
    Overlay overlay;
    try {
        overlay = build_overlay(g_);
    } catch (const Error& e) {
        Violation v;
        v.condition = 4;
        v.what = std::string("the overlay could not be built: ") + e.what();
        add(std::move(v));
        return;
    }
    report_.patch_area = std::accumulate(overlay.patch_area.begin(), overlay.patch_area.end(), 0.0);
    for (int f : overlay.bad_patches) {
        Violation v;
        v.condition = 4;
        v.what = "the patch of coarse face " + std::to_string(f) +
                 " is not a disk bounded by the face's three polylines";
        v.coarse_faces = {f};
        const auto fh = OpenMesh::FaceHandle(f);
        if (f >= 0 && static_cast<std::size_t>(f) < coarse_.n_faces()) {
            for (auto v_ : coarse_.fv_range(fh)) v.coarse_vertices.push_back(v_.idx());
            for (auto e : coarse_.fe_range(fh)) v.coarse_edges.push_back(e.idx());
        }
        add(std::move(v));
    }
    const double fine_area = mesh_.total_area();
    if (!(std::abs(report_.patch_area - fine_area) <= k_area_tolerance * fine_area)) {
        Violation v;
        v.condition = 4;
        v.what = "the patches cover an area of " + number(report_.patch_area) + ", but T's area is " +
                 number(fine_area);
        add(std::move(v));
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Summary

void Validator::summarise() {
    report_.vertices = static_cast<int>(coarse_.n_vertices());
    report_.edges = static_cast<int>(coarse_.n_edges());
    report_.faces = static_cast<int>(coarse_.n_faces());
    report_.fine_area = mesh_.total_area();

    const detail::CoarseComponents components = detail::coarse_components(coarse_);
    report_.components = static_cast<int>(components.genus.size());
    report_.genus = std::accumulate(components.genus.begin(), components.genus.end(), 0);

    if (!corner_angles_.empty()) {
        const auto [lo, hi] = std::minmax_element(corner_angles_.begin(), corner_angles_.end());
        report_.min_corner_angle_deg = *lo * 180.0 / k_pi;
        report_.max_corner_angle_deg = *hi * 180.0 / k_pi;
    }
    double sum = 0.0, lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    int n = 0;
    for (auto e : coarse_.edges()) {
        const double l = g_.length(e);
        sum += l;
        lo = std::min(lo, l);
        hi = std::max(hi, l);
        ++n;
    }
    if (n > 0) {
        report_.min_edge_length = lo;
        report_.max_edge_length = hi;
        report_.mean_edge_length = sum / n;
    }
}

}  // namespace

ValidationReport validate(const GeodesicTriangulation& g, const ValidationOptions& options) {
    ValidationReport report;
    Validator(g, report).run(options);
    return report;
}

ValidationReport validate(const GeodesicTriangulation& g) { return validate(g, ValidationOptions{}); }

void add_overlay_check(const GeodesicTriangulation& g, ValidationReport& report) {
    if (report.overlay_checked) return;
    Validator(g, report).add_patches();
}

namespace detail {

std::string shape_defect(const Mesh& mesh, const Polyline& path, double recorded_length) {
    std::string bend = straightness_defect(mesh, path);
    if (!bend.empty()) return bend;
    const double length = geodesic::path_length(mesh, path);
    if (!(std::abs(recorded_length - length) <= k_length_tolerance * length))
        return "records length " + number(recorded_length) + " but its polyline is " + number(length) + " long";
    return {};
}

PolylineVerdicts::PolylineVerdicts(const GeodesicTriangulation& g, const PolylineVerdicts& earlier) : kept_(g) {
    for (OpenMesh::EdgeHandle e : g.coarse().edges()) earlier.find_or_make(g, e, verdicts_);
}

void PolylineVerdicts::advance(const GeodesicTriangulation& g, const std::vector<int>& edges) {
    auto has = [](const GeodesicTriangulation& in, int e) {
        return static_cast<std::size_t>(e) < in.coarse().n_edges() &&
               !in.coarse().status(OpenMesh::EdgeHandle(e)).deleted();
    };
    // g's verdicts there are found before the old ones go: a polyline may have moved to another of those edges.
    std::unordered_map<const Polyline*, Verdict> added;
    for (int e : edges)
        if (has(g, e)) find_or_make(g, OpenMesh::EdgeHandle(e), added);
    if (kept_)
        for (int e : edges)
            if (has(*kept_, e)) verdicts_.erase(&kept_->polyline(OpenMesh::EdgeHandle(e)));
    for (auto& [raw, verdict] : added) verdicts_[raw] = std::move(verdict);
    kept_ = g;
}

void PolylineVerdicts::find_or_make(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e,
                                    std::unordered_map<const Polyline*, Verdict>& into) const {
    const Polyline& raw = g.polyline(e);
    if (const Verdict* known = verdict(g, e)) {
        into[&raw] = *known;
        return;
    }
    // As Validator::prepare and check_polyline see it: canonical points, apart and on common faces.
    if (raw.size() < 2) return;
    const Mesh& mesh = g.fine().mesh;
    auto path = std::make_shared<Polyline>();
    path->reserve(raw.size());
    for (const SurfacePoint& p : raw) path->push_back(mesh.canonical(p));
    if (!points_defect(mesh, *path).empty()) return;
    auto crossings = std::make_shared<const CrossingItems>(polyline_crossing_items(mesh, *path));
    into[&raw] = {g.length(e), shape_defect(mesh, *path, g.length(e)), std::move(path), std::move(crossings)};
}

const PolylineVerdicts::Verdict* PolylineVerdicts::verdict(const GeodesicTriangulation& g,
                                                           OpenMesh::EdgeHandle e) const {
    const auto it = verdicts_.find(&g.polyline(e));
    if (it == verdicts_.end() || it->second.recorded_length != g.length(e)) return nullptr;
    return &it->second;
}

const std::string* PolylineVerdicts::find(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) const {
    const Verdict* known = verdict(g, e);
    return known ? &known->defect : nullptr;
}

const Polyline* PolylineVerdicts::canonical(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) const {
    const Verdict* known = verdict(g, e);
    return known ? known->canonical.get() : nullptr;
}

std::shared_ptr<const Polyline> PolylineVerdicts::shared_canonical(const GeodesicTriangulation& g,
                                                                   OpenMesh::EdgeHandle e) const {
    const Verdict* known = verdict(g, e);
    return known ? known->canonical : nullptr;
}

const CrossingItems* PolylineVerdicts::crossing_items(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) const {
    const Verdict* known = verdict(g, e);
    return known ? known->crossings.get() : nullptr;
}

ValidationReport validate(const GeodesicTriangulation& g, const ValidationOptions& options,
                          const PolylineVerdicts& known) {
    ValidationReport report;
    Validator(g, report, &known).run(options);
    return report;
}

}  // namespace detail

}  // namespace geotri

#include "check/crossing_items.h"
#include "check/violation_count.h"
#include "core/plane_segments.h"

#include <geodesic/errors.h>
#include <geotri/tangent_angles.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <iterator>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace geotri::detail {

using geodesic::Mesh;
using OpenMesh::EdgeHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

namespace {

// Condition 3 is about features that meet: coarse edge e is feature 2e, coarse vertex c is feature 2c + 1, so that
// an unchanged feature keeps its number in a copy of G with more or fewer edges.
int edge_feature(int e) { return 2 * e; }
int vertex_feature(int c) { return 2 * c + 1; }
bool is_vertex(int feature) { return (feature & 1) != 0; }

/// A point of condition 3: point `index` of a feature's polyline (0 for a coarse vertex), and the coarse vertex at
/// it when it is an end of its polyline or a coarse vertex, else -1.
struct Point {
    int feature;
    int index;
    int end;
};

struct OnVertex {
    int vertex;
    Point point;
};

struct OnEdge {
    int key;
    double t;
    Point point;
};

/// A point on a fine edge within the tolerance of one of its ends.
struct NearVertex {
    int vertex;
    OnEdge at;
};

struct AlongEdge {
    int key;
    double t0, t1;
    int feature;
};

struct InFace {
    int face;
    Point end[2];
    const SurfacePoint* at[2];
    Eigen::Vector2d x[2];
    int segment;  ///< -1 for a coarse vertex
};

/// The items of condition 3 of some features, as validate() files them, each sorted by the fine element that
/// holds it.
struct Buckets {
    std::vector<OnVertex> on_vertex;
    std::vector<OnEdge> on_edge;       ///< by fine edge, then t
    std::vector<NearVertex> near_vertex;
    std::vector<AlongEdge> along_edge;
    std::vector<InFace> in_face;

    static bool before(const OnVertex& a, const OnVertex& b) { return a.vertex < b.vertex; }
    static bool before(const OnEdge& a, const OnEdge& b) { return a.key < b.key || (a.key == b.key && a.t < b.t); }
    static bool before(const NearVertex& a, const NearVertex& b) { return a.vertex < b.vertex; }
    static bool before(const AlongEdge& a, const AlongEdge& b) { return a.key < b.key; }
    static bool before(const InFace& a, const InFace& b) { return a.face < b.face; }

    void sort() {
        sort(on_vertex);
        sort(on_edge);
        sort(near_vertex);
        sort(along_edge);
        sort(in_face);
    }

    /// The items of `kept` but for those of the features that are `gone`, with those of `added` (sorted). Items
    /// that sort alike may come in another order than sort() would give them: nothing that reads them depends on it.
    static Buckets merged(const Buckets& kept, const std::vector<unsigned char>& gone, Buckets added) {
        Buckets out;
        merge(kept.on_vertex, gone, std::move(added.on_vertex), [](const OnVertex& x) { return x.point.feature; },
              out.on_vertex);
        merge(kept.on_edge, gone, std::move(added.on_edge), [](const OnEdge& x) { return x.point.feature; },
              out.on_edge);
        merge(kept.near_vertex, gone, std::move(added.near_vertex),
              [](const NearVertex& x) { return x.at.point.feature; }, out.near_vertex);
        merge(kept.along_edge, gone, std::move(added.along_edge), [](const AlongEdge& x) { return x.feature; },
              out.along_edge);
        merge(kept.in_face, gone, std::move(added.in_face), [](const InFace& x) { return x.end[0].feature; },
              out.in_face);
        return out;
    }

private:
    template <class T>
    static void sort(std::vector<T>& items) {
        std::sort(items.begin(), items.end(), [](const T& a, const T& b) { return before(a, b); });
    }

    template <class T, class Feature>
    static void merge(const std::vector<T>& kept, const std::vector<unsigned char>& gone, std::vector<T> added,
                      Feature feature, std::vector<T>& out) {
        out.reserve(kept.size() + added.size());
        std::copy_if(kept.begin(), kept.end(), std::back_inserter(out),
                     [&](const T& x) { return !gone[static_cast<std::size_t>(feature(x))]; });
        const auto middle = static_cast<std::ptrdiff_t>(out.size());
        out.insert(out.end(), added.begin(), added.end());
        std::inplace_merge(out.begin(), out.begin() + middle, out.end(),
                           [](const T& a, const T& b) { return before(a, b); });
    }
};

/// The items of `sorted` (sorted by `key`) whose key is `value`.
template <class T, class Key>
std::pair<typename std::vector<T>::const_iterator, typename std::vector<T>::const_iterator> group(
    const std::vector<T>& sorted, int value, Key key) {
    const auto first =
        std::lower_bound(sorted.begin(), sorted.end(), value, [&](const T& x, int v) { return key(x) < v; });
    const auto last = std::upper_bound(first, sorted.end(), value, [&](int v, const T& x) { return v < key(x); });
    return {first, last};
}

const auto vertex_of = [](const auto& x) { return x.vertex; };
const auto key_of = [](const auto& x) { return x.key; };
const auto face_of = [](const auto& x) { return x.face; };

/// The points on fine edge `key` from parameter `t` on, in `sorted` (by key, then t).
std::vector<OnEdge>::const_iterator edge_points_from(const std::vector<OnEdge>& sorted, int key, double t) {
    return std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(key, t),
                            [](const OnEdge& p, const std::pair<int, double>& x) {
                                return p.key < x.first || (p.key == x.first && p.t < x.second);
                            });
}

/// Files the condition-3 items of a feature: a polyline of n points `points` from coarse vertex `from` to `to`, or
/// a coarse vertex (n = 1, from = to = the vertex).
void add_items(const Mesh& mesh, const CrossingItems& items, int feature, const SurfacePoint* points, int n,
               int from, int to, Buckets& out) {
    auto point = [&](int index) { return Point{feature, index, index == 0 ? from : index == n - 1 ? to : -1}; };
    for (const auto& [vertex, item] : items.vertex_items) out.on_vertex.push_back({vertex, point(item.index)});
    for (const EdgePoint& p : items.edge_points) {
        const OnEdge at{p.key, p.t, point(p.item.index)};
        out.on_edge.push_back(at);
        // As validate() looks them up: t is 0 at the end of smaller index.
        const int tail = mesh.tail(p.key), head = mesh.head(p.key);
        if (p.t <= k_meet_tolerance) out.near_vertex.push_back({std::min(tail, head), at});
        if (1.0 - p.t <= k_meet_tolerance) out.near_vertex.push_back({std::max(tail, head), at});
    }
    for (const EdgeInterval& s : items.edge_intervals) out.along_edge.push_back({s.key, s.t0, s.t1, feature});
    for (const FaceSegment& s : items.face_segments) {
        InFace f;
        f.face = s.face;
        for (int k = 0; k < 2; ++k) {
            f.end[k] = point(s.end[k].index);
            f.at[k] = &points[s.end[k].index];
            f.x[k] = s.x[k];
        }
        f.segment = s.segment;
        out.in_face.push_back(f);
    }
}

// The tests of Validator::check_crossings(), one pair of items at a time. Each is symmetric, so that a pair meets
// whichever of its items validate() sorted first.

bool allowed(const Point& a, const Point& b) {
    if (a.feature == b.feature && a.index == b.index) return true;
    const bool pa = !is_vertex(a.feature), pb = !is_vertex(b.feature);
    if (!pa && !pb) return false;  // two coarse vertices at one point
    if (pa && pb && a.feature == b.feature) return std::abs(a.index - b.index) == 1;  // consecutive points
    return a.end >= 0 && a.end == b.end;
}

/// Two points on one fine edge at one point (validate() subtracts the smaller parameter from the larger).
bool close(double s, double t) { return std::max(s, t) - std::min(s, t) <= k_meet_tolerance; }

/// A point on a fine edge strictly inside a segment along it.
bool inside(const AlongEdge& s, double t) { return t > s.t0 + k_meet_tolerance && t < s.t1 - k_meet_tolerance; }

bool overlap(const AlongEdge& s, const AlongEdge& r) {
    return std::min(s.t1, r.t1) - std::max(s.t0, r.t0) > k_meet_tolerance;
}

double face_tolerance(const Mesh& mesh, int f) {
    return k_meet_tolerance * std::max({mesh.length(3 * f), mesh.length(3 * f + 1), mesh.length(3 * f + 2)});
}

/// Two segments (or coarse vertices) in one fine face. Where they share both ends, either shared pair decides the
/// same: not allowed, or allowed and then each lies on the other.
bool meet_in_face(const InFace& s, const InFace& r, double tolerance) {
    if (s.end[0].feature == r.end[0].feature && s.segment >= 0 && std::abs(s.segment - r.segment) <= 1)
        return false;  // one polyline's consecutive segments
    for (int u = 0; u < 2; ++u)
        for (int w = 0; w < 2; ++w) {
            if (*s.at[u] != *r.at[w]) continue;
            if (!allowed(s.end[u], r.end[w])) return true;
            if (s.segment < 0 || r.segment < 0) return false;
            // Two geodesics from a common end overlap when one's far end lies on the other.
            return point_segment_distance(s.x[1 - u], r.x[0], r.x[1]) <= tolerance ||
                   point_segment_distance(r.x[1 - w], s.x[0], s.x[1]) <= tolerance;
        }
    return segment_distance(s.x[0], s.x[1], r.x[0], r.x[1]) <= tolerance;
}

/// Pairs of features that meet, each as (smaller, larger); a feature that meets itself is (f, f).
using Meetings = std::vector<std::pair<int, int>>;

void meet(Meetings& out, int a, int b) { out.emplace_back(std::min(a, b), std::max(a, b)); }

/// The meetings among the items of b.
void meetings_within(const Mesh& mesh, const Buckets& b, Meetings& out) {
    for (auto i = b.on_vertex.begin(); i != b.on_vertex.end();) {
        auto j = i;
        while (j != b.on_vertex.end() && j->vertex == i->vertex) ++j;
        for (auto x = i; x != j; ++x)
            for (auto y = x + 1; y != j; ++y)
                if (!allowed(x->point, y->point)) meet(out, x->point.feature, y->point.feature);
        i = j;
    }
    for (auto i = b.on_edge.begin(); i != b.on_edge.end(); ++i)
        for (auto j = i + 1; j != b.on_edge.end() && j->key == i->key && j->t - i->t <= k_meet_tolerance; ++j)
            if (!allowed(i->point, j->point)) meet(out, i->point.feature, j->point.feature);
    for (const NearVertex& p : b.near_vertex) {
        const auto [first, last] = group(b.on_vertex, p.vertex, vertex_of);
        for (auto v = first; v != last; ++v)
            if (!allowed(v->point, p.at.point)) meet(out, v->point.feature, p.at.point.feature);
    }
    for (auto s = b.along_edge.begin(); s != b.along_edge.end(); ++s) {
        const auto end = b.on_edge.end();
        for (auto p = edge_points_from(b.on_edge, s->key, s->t0); p != end && p->key == s->key && p->t < s->t1; ++p)
            if (inside(*s, p->t)) meet(out, s->feature, p->point.feature);
        for (auto r = s + 1; r != b.along_edge.end() && r->key == s->key; ++r)
            if (overlap(*s, *r)) meet(out, s->feature, r->feature);
    }
    for (auto i = b.in_face.begin(); i != b.in_face.end();) {
        auto j = i;
        while (j != b.in_face.end() && j->face == i->face) ++j;
        if (j - i > 1) {
            const double tolerance = face_tolerance(mesh, i->face);
            for (auto x = i; x != j; ++x)
                for (auto y = x + 1; y != j; ++y)
                    if (meet_in_face(*x, *y, tolerance)) meet(out, x->end[0].feature, y->end[0].feature);
        }
        i = j;
    }
}

/// The meetings between the items of x and those of g, but for the features of g that are `gone`.
void meetings_between(const Mesh& mesh, const Buckets& x, const Buckets& g, const std::vector<unsigned char>& gone,
                      Meetings& out) {
    for (const OnVertex& p : x.on_vertex) {
        const auto [first, last] = group(g.on_vertex, p.vertex, vertex_of);
        for (auto q = first; q != last; ++q)
            if (!gone[q->point.feature] && !allowed(p.point, q->point)) meet(out, p.point.feature, q->point.feature);
        const auto [near_first, near_last] = group(g.near_vertex, p.vertex, vertex_of);
        for (auto q = near_first; q != near_last; ++q)
            if (!gone[q->at.point.feature] && !allowed(p.point, q->at.point))
                meet(out, p.point.feature, q->at.point.feature);
    }
    for (const NearVertex& p : x.near_vertex) {
        const auto [first, last] = group(g.on_vertex, p.vertex, vertex_of);
        for (auto q = first; q != last; ++q)
            if (!gone[q->point.feature] && !allowed(q->point, p.at.point))
                meet(out, p.at.point.feature, q->point.feature);
    }
    for (const OnEdge& p : x.on_edge) {
        // Wider than the tolerance, which close() then applies as validate() does.
        for (auto q = edge_points_from(g.on_edge, p.key, p.t - 2.0 * k_meet_tolerance);
             q != g.on_edge.end() && q->key == p.key && q->t <= p.t + 2.0 * k_meet_tolerance; ++q)
            if (!gone[q->point.feature] && close(p.t, q->t) && !allowed(p.point, q->point))
                meet(out, p.point.feature, q->point.feature);
        const auto [first, last] = group(g.along_edge, p.key, key_of);
        for (auto s = first; s != last; ++s)
            if (!gone[s->feature] && inside(*s, p.t)) meet(out, p.point.feature, s->feature);
    }
    for (const AlongEdge& s : x.along_edge) {
        const auto end = g.on_edge.end();
        for (auto p = edge_points_from(g.on_edge, s.key, s.t0); p != end && p->key == s.key && p->t < s.t1; ++p)
            if (!gone[p->point.feature] && inside(s, p->t)) meet(out, s.feature, p->point.feature);
        const auto [first, last] = group(g.along_edge, s.key, key_of);
        for (auto r = first; r != last; ++r)
            if (!gone[r->feature] && overlap(s, *r)) meet(out, s.feature, r->feature);
    }
    for (auto i = x.in_face.begin(); i != x.in_face.end();) {
        auto j = i;
        while (j != x.in_face.end() && j->face == i->face) ++j;
        const auto [first, last] = group(g.in_face, i->face, face_of);
        if (first != last) {
            const double tolerance = face_tolerance(mesh, i->face);
            for (auto s = i; s != j; ++s)
                for (auto r = first; r != last; ++r)
                    if (!gone[r->end[0].feature] && meet_in_face(*s, *r, tolerance))
                        meet(out, s->end[0].feature, r->end[0].feature);
        }
        i = j;
    }
}

/// Condition 2 at a coarse vertex: whether it fails, and where (VertexCorners::first_bad).
struct CornerVerdict {
    bool violated = false;
    int first_bad = -1;
};

struct EdgeState {
    int index = -1;
    bool present = false;             ///< not deleted
    const Polyline* raw = nullptr;    ///< the polyline object, which an operation replaces rather than changes
    double length = 0.0;
    int from = -1, to = -1;           ///< from and to vertex of its first halfedge
    std::shared_ptr<const Polyline> canonical;
    bool usable = false;              ///< takes part in conditions 2 and 3 (polyline_violation())
    bool violated = false;            ///< condition 1
};

struct VertexState {
    int index = -1;
    bool present = false;
    SurfacePoint raw, canonical;
};

/// The out halfedges of v, from its halfedge counter-clockwise, as Validator::check_corners() visits them.
void rotation(const CoarseMesh& coarse, VertexHandle v, std::vector<int>& out) {
    const HalfedgeHandle start = coarse.halfedge_handle(v);
    if (!start.is_valid()) return;
    HalfedgeHandle h = start;
    std::size_t n = 0;
    do {
        out.push_back(h.idx());
        ++n;
        h = coarse.ccw_rotated_halfedge_handle(h);
    } while (h != start && n <= coarse.n_halfedges());
}

}  // namespace

/// What difference() compares of an edge, apart from its state: a trial's every edge is compared, and the states
/// are a cache line each.
struct EdgeIdentity {
    const Polyline* raw;  ///< null where the edge is deleted
    double length;
    int from, to;
};

struct ViolationCount::State {
    State() = default;
    State(const State&) = delete;  // the buckets and `locations` point into its own vectors
    State& operator=(const State&) = delete;

    std::optional<GeodesicTriangulation> g;  ///< keeps g's polylines alive: no new one can take their addresses
    std::vector<EdgeState> edges;            ///< per coarse edge
    std::vector<VertexState> vertices;       ///< per coarse vertex
    std::vector<EdgeIdentity> edge_identities;  ///< per coarse edge, from `edges`
    std::vector<const SurfacePoint*> locations; ///< per coarse vertex: its raw location in `vertices`, or null
    std::vector<CornerVerdict> corners;      ///< condition 2, per coarse vertex
    std::vector<int> rotation_start;         ///< per coarse vertex and one more, into rotation
    std::vector<int> rotation;
    Buckets buckets;                         ///< condition 3's items of every feature
    std::vector<int> meeting_start;          ///< per feature and one more, into meeting_other
    std::vector<int> meeting_other;          ///< the features that each meets (itself included, once)
    std::array<int, 3> violations{};         ///< per condition
};

namespace {

/// What a G differs in from a state, with its violations counted from there.
struct Difference {
    std::vector<int> edge_slot, vertex_slot;  ///< per coarse edge or vertex of G: where in edges or vertices, or -1
    std::vector<EdgeState> edges;             ///< those that differ, or that the state does not have
    std::vector<VertexState> vertices;
    std::vector<unsigned char> gone;          ///< per feature of the state: differs in G, or is not in it
    std::vector<int> gone_list;
    // Where asked for (to make a state of G): the coarse vertices whose condition 2 was checked again, ascending,
    // with their verdicts and rotations (rotation_start: per checked vertex and one more, into rotation).
    std::vector<int> checked;
    std::vector<CornerVerdict> checked_corners;
    std::vector<int> rotation_start, rotation;
    Buckets buckets;                              ///< the items of the features that differ
    Meetings meetings;                            ///< those that involve them, sorted, without repeats
    std::array<int, 3> violations{};
};

/// Per coarse vertex of g: whether its condition 2 may differ from the state's, where `d` holds the vertices and
/// edges that differ. It can only at a vertex that differs, at an end of an edge that differs, and where the
/// rotation of halfedges differs: rotation() walks prev() and opposite() from the vertex's halfedge, so a vertex
/// whose halfedge is the same, and whose every halfedge in the state's rotation has the same prev(), has the same
/// rotation. Walking every vertex's rotation was most of untangling's counting; this is two passes over arrays.
std::vector<unsigned char> corners_that_may_differ(const ViolationCount::State& base, const GeodesicTriangulation& g,
                                                   const Difference& d) {
    const CoarseMesh& coarse = g.coarse();
    const CoarseMesh& before = base.g->coarse();
    const int nv = static_cast<int>(coarse.n_vertices());
    std::vector<unsigned char> may_differ(static_cast<std::size_t>(nv), 0);
    for (int v = 0; v < nv; ++v)
        if (d.vertex_slot[static_cast<std::size_t>(v)] >= 0) may_differ[static_cast<std::size_t>(v)] = 1;
    for (const EdgeState& s : d.edges)
        if (s.present) may_differ[static_cast<std::size_t>(s.from)] = may_differ[static_cast<std::size_t>(s.to)] = 1;
    const int common_nv = std::min(nv, static_cast<int>(before.n_vertices()));
    for (int v = 0; v < common_nv; ++v)
        if (coarse.halfedge_handle(VertexHandle(v)) != before.halfedge_handle(VertexHandle(v)))
            may_differ[static_cast<std::size_t>(v)] = 1;
    const int common_nh = static_cast<int>(std::min(coarse.n_halfedges(), before.n_halfedges()));
    for (int h = 0; h < common_nh; ++h) {
        const HalfedgeHandle handle(h);
        if (coarse.prev_halfedge_handle(handle) == before.prev_halfedge_handle(handle)) continue;
        const int v = before.from_vertex_handle(handle).idx();
        if (v >= 0 && v < nv) may_differ[static_cast<std::size_t>(v)] = 1;
    }
    return may_differ;
}

/// What g differs in from `base`, with g's violations counted from there; `record`: with what it takes to make
/// g's state (make_state()). Against a state of nothing (no g), everything in g differs.
Difference difference(const ViolationCount::State& base, const GeodesicTriangulation& g, const PolylineVerdicts& known,
                      bool record) {
    const bool full = !base.g;
    const Mesh& mesh = g.fine().mesh;
    const CoarseMesh& coarse = g.coarse();
    const int nv = static_cast<int>(coarse.n_vertices()), ne = static_cast<int>(coarse.n_edges());
    const int base_nv = static_cast<int>(base.vertices.size()), base_ne = static_cast<int>(base.edges.size());
    Difference d;
    d.gone.assign(static_cast<std::size_t>(2 * std::max(base_nv, base_ne) + 2), 0);
    auto gone = [&](int feature) {
        if (d.gone[static_cast<std::size_t>(feature)]) return;
        d.gone[static_cast<std::size_t>(feature)] = 1;
        d.gone_list.push_back(feature);
    };

    // Locations, as Validator::prepare() makes them canonical.
    d.vertex_slot.assign(static_cast<std::size_t>(nv), -1);
    // A trial differs from the state in a few elements: those that do not are passed over before anything is made.
    for (int v = 0; v < nv; ++v) {
        const VertexHandle handle(v);
        const bool present = !coarse.status(handle).deleted();
        if (v < base_nv) {
            const SurfacePoint* old = base.locations[static_cast<std::size_t>(v)];
            if (present ? old && *old == g.location(handle) : !old) continue;
            gone(vertex_feature(v));
        }
        VertexState s;
        s.index = v;
        s.present = present;
        if (present) {
            s.raw = g.location(handle);
            s.canonical = canonical_location(mesh, s.raw, v);
        }
        d.vertex_slot[static_cast<std::size_t>(v)] = static_cast<int>(d.vertices.size());
        d.vertices.push_back(s);
    }
    for (int v = nv; v < base_nv; ++v) gone(vertex_feature(v));
    auto vertex = [&](int v) -> const VertexState& {
        const int slot = d.vertex_slot[static_cast<std::size_t>(v)];
        return slot >= 0 ? d.vertices[static_cast<std::size_t>(slot)] : base.vertices[static_cast<std::size_t>(v)];
    };

    // Polylines: those that differ, made canonical as Validator::prepare() does, then condition 1 on them.
    d.edge_slot.assign(static_cast<std::size_t>(ne), -1);
    for (int e = 0; e < ne; ++e) {
        const EdgeHandle handle(e);
        const bool present = !coarse.status(handle).deleted();
        const Polyline* raw = present ? &g.polyline(handle) : nullptr;
        if (e < base_ne) {
            const EdgeIdentity& old = base.edge_identities[static_cast<std::size_t>(e)];
            if (old.raw == raw && (!present || old.length == g.length(handle))) {
                if (!present) continue;
                const HalfedgeHandle h = coarse.halfedge_handle(handle, 0);
                const int from = coarse.from_vertex_handle(h).idx(), to = coarse.to_vertex_handle(h).idx();
                if (old.from == from && old.to == to && d.vertex_slot[static_cast<std::size_t>(from)] < 0 &&
                    d.vertex_slot[static_cast<std::size_t>(to)] < 0)
                    continue;
            }
            gone(edge_feature(e));
        }
        EdgeState s;
        s.index = e;
        s.present = present;
        if (present) {
            const HalfedgeHandle h = coarse.halfedge_handle(handle, 0);
            s.from = coarse.from_vertex_handle(h).idx();
            s.to = coarse.to_vertex_handle(h).idx();
            s.raw = raw;
            s.length = g.length(handle);
            s.canonical = known.shared_canonical(g, handle);
            if (!s.canonical) s.canonical = std::make_shared<const Polyline>(canonical_polyline(mesh, *s.raw, e));
        }
        d.edge_slot[static_cast<std::size_t>(e)] = static_cast<int>(d.edges.size());
        d.edges.push_back(std::move(s));
    }
    for (int e = ne; e < base_ne; ++e) gone(edge_feature(e));
    auto edge = [&](int e) -> const EdgeState& {
        const int slot = d.edge_slot[static_cast<std::size_t>(e)];
        return slot >= 0 ? d.edges[static_cast<std::size_t>(slot)] : base.edges[static_cast<std::size_t>(e)];
    };

    // Condition 1.
    d.violations = base.violations;
    for (int feature : d.gone_list)
        if (!is_vertex(feature) && base.edges[static_cast<std::size_t>(feature / 2)].violated) --d.violations[0];
    for (EdgeState& s : d.edges) {
        if (!s.present) continue;
        const EdgeHandle handle(s.index);
        const std::string why =
            polyline_violation(mesh, *s.canonical, s.from, vertex(s.from).canonical, s.to, vertex(s.to).canonical,
                               known.find(g, handle), s.length, s.usable);
        s.violated = !why.empty();
        if (s.violated) ++d.violations[0];
    }

    // Condition 2, at the vertices whose location, edges around or polylines there differ.
    if (record) d.rotation_start.assign(1, 0);
    const std::vector<unsigned char> may_differ =
        full ? std::vector<unsigned char>() : corners_that_may_differ(base, g, d);
    std::vector<int> around;
    std::vector<double> angles;
    for (int v = 0; v < nv; ++v) {
        if (!full && !may_differ[static_cast<std::size_t>(v)]) continue;
        const bool differs = d.vertex_slot[static_cast<std::size_t>(v)] >= 0;
        const bool was_violated = v < base_nv && base.corners[static_cast<std::size_t>(v)].violated;
        around.clear();
        if (vertex(v).present) rotation(coarse, VertexHandle(v), around);
        if (!differs) {
            const auto first = base.rotation.begin() + base.rotation_start[static_cast<std::size_t>(v)];
            const auto last = base.rotation.begin() + base.rotation_start[static_cast<std::size_t>(v) + 1];
            const bool same = std::equal(around.begin(), around.end(), first, last) &&
                              std::none_of(around.begin(), around.end(), [&](int h) {
                                  const int e = coarse.edge_handle(HalfedgeHandle(h)).idx();
                                  return d.edge_slot[static_cast<std::size_t>(e)] >= 0;
                              });
            if (same) continue;
        }
        if (was_violated) --d.violations[1];
        if (record) {
            d.checked.push_back(v);
            d.checked_corners.push_back({});
            d.rotation.insert(d.rotation.end(), around.begin(), around.end());
            d.rotation_start.push_back(static_cast<int>(d.rotation.size()));
        }
        // As Validator::check_corners(): not measurable where a polyline is unusable (condition 1 names it).
        angles.clear();
        bool measurable = !around.empty();
        for (int index : around) {
            const HalfedgeHandle h(index);
            const EdgeHandle e = coarse.edge_handle(h);
            const EdgeState& s = edge(e.idx());
            if (!s.usable) {
                measurable = false;
                break;
            }
            const Polyline& path = *s.canonical;
            const bool forward = h == coarse.halfedge_handle(e, 0);
            const SurfacePoint& p = forward ? path[0] : path[path.size() - 1];
            const SurfacePoint& q = forward ? path[1] : path[path.size() - 2];
            angles.push_back(polar_angle(mesh, p, q));
        }
        if (!measurable) continue;
        const VertexCorners corners = vertex_corners(mesh, vertex(v).canonical, angles);
        if (corners.violated()) {
            ++d.violations[1];
            if (record) d.checked_corners.back() = {true, corners.first_bad};
        }
    }
    for (int v = nv; v < base_nv; ++v)
        if (base.corners[static_cast<std::size_t>(v)].violated) --d.violations[1];

    // Condition 3: the meetings that involve a feature that differs, in g against the others and among themselves,
    // and in the state those that involve one that is gone.
    for (const EdgeState& s : d.edges) {
        if (!s.present || !s.usable) continue;
        const CrossingItems* items = known.crossing_items(g, EdgeHandle(s.index));
        CrossingItems own;
        if (!items) {
            own = polyline_crossing_items(mesh, *s.canonical);
            items = &own;
        }
        add_items(mesh, *items, edge_feature(s.index), s.canonical->data(), static_cast<int>(s.canonical->size()),
                  s.from, s.to, d.buckets);
    }
    for (const VertexState& s : d.vertices) {
        if (!s.present) continue;
        add_items(mesh, location_crossing_items(mesh, s.canonical), vertex_feature(s.index), &s.canonical, 1, s.index,
                  s.index, d.buckets);
    }
    d.buckets.sort();
    meetings_within(mesh, d.buckets, d.meetings);
    meetings_between(mesh, d.buckets, base.buckets, d.gone, d.meetings);
    std::sort(d.meetings.begin(), d.meetings.end());
    d.meetings.erase(std::unique(d.meetings.begin(), d.meetings.end()), d.meetings.end());
    const int base_features = static_cast<int>(base.meeting_start.size()) - 1;
    for (int f : d.gone_list) {
        if (f >= base_features) continue;
        const auto first = base.meeting_other.begin() + base.meeting_start[static_cast<std::size_t>(f)];
        const auto last = base.meeting_other.begin() + base.meeting_start[static_cast<std::size_t>(f) + 1];
        for (auto other = first; other != last; ++other)
            if (!d.gone[static_cast<std::size_t>(*other)] || *other >= f) --d.violations[2];
    }
    d.violations[2] += static_cast<int>(d.meetings.size());
    return d;
}

}  // namespace

namespace {

/// The state of g, whose difference from `base` is d (recorded): base's where g agrees with it, d's elsewhere.
std::shared_ptr<const ViolationCount::State> make_state(const ViolationCount::State& base,
                                                        const GeodesicTriangulation& g, Difference d) {
    auto state = std::make_shared<ViolationCount::State>();
    state->g.emplace(g);
    const std::size_t ne = g.coarse().n_edges(), nv = g.coarse().n_vertices();
    state->edges.reserve(ne);
    for (std::size_t e = 0; e < ne; ++e) {
        const int slot = d.edge_slot[e];
        state->edges.push_back(slot >= 0 ? std::move(d.edges[static_cast<std::size_t>(slot)]) : base.edges[e]);
        const EdgeState& s = state->edges.back();
        state->edge_identities.push_back({s.present ? s.raw : nullptr, s.length, s.from, s.to});
    }
    state->vertices.reserve(nv);
    for (std::size_t v = 0; v < nv; ++v) {
        const int slot = d.vertex_slot[v];
        state->vertices.push_back(slot >= 0 ? d.vertices[static_cast<std::size_t>(slot)] : base.vertices[v]);
    }
    for (const VertexState& s : state->vertices) state->locations.push_back(s.present ? &s.raw : nullptr);

    // Condition 2: base's rotations and verdicts, but at the vertices checked again.
    state->corners.assign(nv, {});
    state->rotation_start.assign(1, 0);
    std::size_t next = 0;  // into d.checked
    for (std::size_t v = 0; v < nv; ++v) {
        if (next < d.checked.size() && d.checked[next] == static_cast<int>(v)) {
            state->corners[v] = d.checked_corners[next];
            state->rotation.insert(state->rotation.end(), d.rotation.begin() + d.rotation_start[next],
                                   d.rotation.begin() + d.rotation_start[next + 1]);
            ++next;
        } else {  // not checked again: g has it, unchanged, as base
            state->corners[v] = base.corners[v];
            state->rotation.insert(state->rotation.end(), base.rotation.begin() + base.rotation_start[v],
                                   base.rotation.begin() + base.rotation_start[v + 1]);
        }
        state->rotation_start.push_back(static_cast<int>(state->rotation.size()));
    }

    // Condition 3. A coarse vertex's items in a face point at its location, which is now in state->vertices.
    state->buckets = Buckets::merged(base.buckets, d.gone, std::move(d.buckets));
    for (InFace& x : state->buckets.in_face)
        if (is_vertex(x.end[0].feature))
            x.at[0] = x.at[1] = &state->vertices[static_cast<std::size_t>(x.end[0].feature / 2)].canonical;
    Meetings meetings = std::move(d.meetings);
    const std::size_t base_features = base.meeting_start.empty() ? 0 : base.meeting_start.size() - 1;
    for (std::size_t f = 0; f < base_features; ++f) {
        if (d.gone[f]) continue;
        for (int i = base.meeting_start[f]; i < base.meeting_start[f + 1]; ++i) {
            const int other = base.meeting_other[static_cast<std::size_t>(i)];
            if (other >= static_cast<int>(f) && !d.gone[static_cast<std::size_t>(other)])
                meetings.emplace_back(static_cast<int>(f), other);
        }
    }
    if (static_cast<int>(meetings.size()) != d.violations[2])
        throw std::logic_error("ViolationCount: " + std::to_string(meetings.size()) + " meetings kept, " +
                               std::to_string(d.violations[2]) + " counted");
    const std::size_t features = 2 * std::max(ne, nv) + 2;
    state->meeting_start.assign(features + 1, 0);
    for (const auto& [a, b] : meetings) {
        ++state->meeting_start[static_cast<std::size_t>(a) + 1];
        if (b != a) ++state->meeting_start[static_cast<std::size_t>(b) + 1];
    }
    for (std::size_t f = 0; f < features; ++f) state->meeting_start[f + 1] += state->meeting_start[f];
    state->meeting_other.resize(static_cast<std::size_t>(state->meeting_start[features]));
    std::vector<int> slot(state->meeting_start.begin(), state->meeting_start.end() - 1);
    for (const auto& [a, b] : meetings) {
        state->meeting_other[static_cast<std::size_t>(slot[static_cast<std::size_t>(a)]++)] = b;
        if (b != a) state->meeting_other[static_cast<std::size_t>(slot[static_cast<std::size_t>(b)]++)] = a;
    }
    state->violations = d.violations;
    return state;
}

}  // namespace

ViolationCount::ViolationCount(const GeodesicTriangulation& g, const PolylineVerdicts& known) {
    const State nothing;
    g_ = make_state(nothing, g, difference(nothing, g, known, true));
}

ViolationCount::ViolationCount(const ViolationCount& base, const GeodesicTriangulation& trial,
                               const PolylineVerdicts& known)
    : g_(make_state(*base.g_, trial, difference(*base.g_, trial, known, true))) {}

ValidationReport ViolationCount::report() const {
    const State& state = *g_;
    const CoarseMesh& coarse = state.g->coarse();
    ValidationReport report;
    std::copy(state.violations.begin(), state.violations.end(), report.violation_count.begin());
    report.valid = count() == 0;
    for (const EdgeState& s : state.edges) {
        if (!s.present || !s.violated) continue;
        Violation v;
        v.condition = 1;
        v.coarse_edges = {s.index};
        v.coarse_vertices = {s.from, s.to};
        report.violations.push_back(std::move(v));
    }
    std::vector<HalfedgeHandle> out;
    for (std::size_t c = 0; c < state.vertices.size(); ++c) {
        if (!state.corners[c].violated) continue;
        out.clear();
        for (int i = state.rotation_start[c]; i < state.rotation_start[c + 1]; ++i)
            out.emplace_back(state.rotation[static_cast<std::size_t>(i)]);
        report.violations.push_back(corner_violation(coarse, static_cast<int>(c), out, state.corners[c].first_bad));
    }
    auto side = [&](int feature) {
        if (is_vertex(feature)) return MeetingSide{true, feature / 2, -1, -1};
        const EdgeState& s = state.edges[static_cast<std::size_t>(feature / 2)];
        return MeetingSide{false, s.index, s.from, s.to};
    };
    for (std::size_t f = 0; f + 1 < state.meeting_start.size(); ++f)
        for (int i = state.meeting_start[f]; i < state.meeting_start[f + 1]; ++i) {
            const int other = state.meeting_other[static_cast<std::size_t>(i)];
            if (other >= static_cast<int>(f))
                report.violations.push_back(meeting_violation(side(static_cast<int>(f)), side(other)));
        }
    return report;
}

int ViolationCount::count() const { return g_->violations[0] + g_->violations[1] + g_->violations[2]; }

int ViolationCount::count(const GeodesicTriangulation& trial, const PolylineVerdicts& known) const {
    const Difference d = difference(*g_, trial, known, false);
    return d.violations[0] + d.violations[1] + d.violations[2];
}

int ViolationCount::count(const GeodesicTriangulation& trial, const PolylineVerdicts& known, Changed& changed) const {
    const Difference d = difference(*g_, trial, known, false);
    changed = {};
    for (const EdgeState& s : d.edges) changed.edges.push_back(s.index);
    for (const VertexState& s : d.vertices) changed.vertices.push_back(s.index);
    for (int feature : d.gone_list) (is_vertex(feature) ? changed.vertices : changed.edges).push_back(feature / 2);
    for (std::vector<int>* list : {&changed.edges, &changed.vertices}) {
        std::sort(list->begin(), list->end());
        list->erase(std::unique(list->begin(), list->end()), list->end());
    }
    return d.violations[0] + d.violations[1] + d.violations[2];
}

}  // namespace geotri::detail

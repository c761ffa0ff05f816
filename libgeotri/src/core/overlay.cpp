#include <geodesic/constants.h>
#include <geodesic/errors.h>
#include <geotri/overlay.h>
#include <geotri/tangent_angles.h>

#include "core/patch_overlay.h"
#include "core/plane_segments.h"
#include "core/tolerances.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <utility>

namespace geotri {

double Overlay::total_patch_area() const { return std::accumulate(patch_area.begin(), patch_area.end(), 0.0); }

namespace {

using geodesic::Mesh;
using geodesic::PointKind;

using geodesic::k_pi;

std::uint64_t bits_of(double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

std::uint64_t mix(std::uint64_t h, std::uint64_t x) {
    x *= 0x9e3779b97f4a7c15ULL;
    x ^= x >> 29;
    return (h ^ x) * 0xbf58476d1ce4e5b9ULL + 0x94d049bb133111ebULL;
}

std::uint64_t undirected_key(int a, int b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

class DisjointSets {
public:
    explicit DisjointSets(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
    int find(int x) {
        while (parent_[x] != x) {
            parent_[x] = parent_[parent_[x]];
            x = parent_[x];
        }
        return x;
    }
    void unite(int a, int b) {
        a = find(a);
        b = find(b);
        // The smaller root wins, so that roots (and the region numbering built on them) do not depend on order.
        if (a < b) parent_[b] = a;
        else if (b < a) parent_[a] = b;
    }

private:
    std::vector<int> parent_;
};

/// Exact identity of an edge or face point: the fine element and the bit patterns of its parameters.
struct PointKey {
    int kind = 0;
    int element = 0;
    std::uint64_t x = 0, y = 0, z = 0;
    bool operator==(const PointKey& o) const {
        return kind == o.kind && element == o.element && x == o.x && y == o.y && z == o.z;
    }
};
struct PointKeyHash {
    std::size_t operator()(const PointKey& k) const {
        std::uint64_t h = mix(static_cast<std::uint64_t>(k.kind), static_cast<std::uint64_t>(k.element));
        return static_cast<std::size_t>(mix(mix(mix(h, k.x), k.y), k.z));
    }
};

/// One representative halfedge per fine edge, so that both faces of an edge name it the same way.
int edge_representative(const Mesh& mesh, int h) {
    const int t = mesh.twin(h);
    return t >= 0 ? std::min(h, t) : h;
}

/// The overlay's vertices: T's vertices, then every edge and face point that a polyline or a location uses, each
/// created once, so that the two faces of a crossed edge share it and the overlay is watertight.
class PointTable {
public:
    struct EdgeSlot {
        int v0 = -1, v1 = -1;                        // the fine edge, v0 < v1; points are (v0, v1, t)
        std::vector<std::pair<double, int>> points;  // (t, overlay vertex), sorted by t once finish() ran
    };

    /// With `fine_vertices`, out's positions and points start with T's vertices, at their ids; without, they hold
    /// the edge and face points only (whose ids start at T's vertex count all the same), for a caller that does
    /// not want a pass over T.
    PointTable(const Mesh& mesh, Overlay& out, bool fine_vertices = true)
        : mesh_(mesh), out_(out), first_stored_(fine_vertices ? 0 : mesh.num_vertices()) {
        out_.positions.clear();
        out_.points.clear();
        if (!fine_vertices) return;
        out_.positions = mesh.positions();
        out_.points.reserve(mesh.num_vertices());
        for (int v = 0; v < mesh.num_vertices(); ++v) out_.points.push_back(SurfacePoint::at_vertex(v));
    }

    /// The overlay vertex at p, created on first use; -1 when p does not refer to T.
    int id_of(const SurfacePoint& raw) {
        SurfacePoint p;
        try {
            p = mesh_.canonical(raw);
        } catch (const Error&) {
            return -1;
        }
        // A point a hair from an end of its fine edge is at that vertex, as validate() judges where geodesics meet:
        // a geodesic traced through a vertex of T can come as two such points on the edges on either side of it,
        // and the chord between them, of no length once laid out in the face, would meet every chord there.
        if (p.kind == PointKind::edge && p.t <= detail::k_meet_tolerance) return p.edge_v0;
        if (p.kind == PointKind::edge && 1.0 - p.t <= detail::k_meet_tolerance) return p.edge_v1;
        if (p.kind == PointKind::vertex) return p.vertex;
        PointKey key;
        int slot = -1;
        if (p.kind == PointKind::edge) {  // canonical: edge_v0 < edge_v1
            int h = mesh_.find_halfedge(p.edge_v0, p.edge_v1);
            if (h < 0) h = mesh_.find_halfedge(p.edge_v1, p.edge_v0);
            if (h < 0) return -1;
            const int rep = edge_representative(mesh_, h);
            key = {1, rep, bits_of(p.t), 0, 0};
            auto [it, inserted] = slot_of_rep_.emplace(rep, static_cast<int>(edges.size()));
            if (inserted) edges.push_back({p.edge_v0, p.edge_v1, {}});
            slot = it->second;
        } else {
            key = {2, p.face, bits_of(p.bary[0]), bits_of(p.bary[1]), bits_of(p.bary[2])};
        }
        auto [it, inserted] = ids_.emplace(key, first_stored_ + static_cast<int>(out_.positions.size()));
        if (!inserted) return it->second;
        const int id = it->second;
        out_.positions.push_back(mesh_.point(p));
        out_.points.push_back(p);
        slot_of_point_.push_back(slot);
        position_in_slot_.push_back(-1);
        if (slot >= 0) edges[slot].points.emplace_back(p.t, id);
        else face_points.emplace_back(p.face, id);
        return id;
    }

    /// Sorts the points along each edge and the face points by face. Call once every point is in.
    void finish() {
        for (EdgeSlot& e : edges) {
            std::sort(e.points.begin(), e.points.end());
            for (std::size_t i = 0; i < e.points.size(); ++i)
                position_in_slot_[e.points[i].second - mesh_.num_vertices()] = static_cast<int>(i) + 1;
        }
        std::sort(face_points.begin(), face_points.end());
    }

    /// The slot of the fine edge of representative halfedge rep, or -1 when no point lies on it.
    int slot_of_rep(int rep) const {
        auto it = slot_of_rep_.find(rep);
        return it == slot_of_rep_.end() ? -1 : it->second;
    }
    bool is_vertex(int id) const { return id < mesh_.num_vertices(); }
    /// For an edge point: its slot; else -1.
    int slot_of(int id) const { return is_vertex(id) ? -1 : slot_of_point_[id - mesh_.num_vertices()]; }
    /// For an edge point: its index in [v0, points..., v1] of its slot.
    int position_in_slot(int id) const { return position_in_slot_[id - mesh_.num_vertices()]; }
    /// An edge or face point (T's vertices are stored only with `fine_vertices`).
    const SurfacePoint& point(int id) const { return out_.points[static_cast<std::size_t>(id - first_stored_)]; }

    std::vector<EdgeSlot> edges;
    std::vector<std::pair<int, int>> face_points;  // (face, overlay vertex), sorted once finish() ran

private:
    const Mesh& mesh_;
    Overlay& out_;
    std::unordered_map<PointKey, int, PointKeyHash> ids_;
    int first_stored_;  // the id of out's first position
    std::unordered_map<int, int> slot_of_rep_;
    std::vector<int> slot_of_point_;      // per vertex beyond T's
    std::vector<int> position_in_slot_;   // per vertex beyond T's
};

/// A polyline segment through the inside of a fine face.
struct Chord {
    int face;
    int a, b;  // overlay vertices
    int edge;  // coarse edge
};

/// Cuts one fine face along its chords and triangulates the pieces.
///
/// The face is laid out in 2D. Its boundary is the cycle of its corners and of the edge points on its sides, in
/// the exact order of their edge parameters; the chords and the face points inside make a plane graph with it.
/// Each bounded face of that graph is triangulated by ear clipping. Three points on one side of the fine face are
/// collinear by construction, whatever the rounding of their 2D positions says. Whatever the input, this ends:
/// a chord that crosses or overlaps another, or that dangles, is left out (and reported), and ear clipping removes
/// one vertex per step.
class FaceCutter {
public:
    FaceCutter(const Mesh& mesh, const PointTable& table, Overlay& out) : mesh_(mesh), table_(table), out_(out) {}

    void cut(int f, const Chord* chords_begin, const Chord* chords_end, const std::pair<int, int>* inside_begin,
             const std::pair<int, int>* inside_end, std::vector<char>& broken_edge) {
        layout(f, inside_begin, inside_end);
        collect_chords(chords_begin, chords_end, broken_edge);
        prune(broken_edge);
        build_rotations();
        trace_faces(f);
    }

private:
    struct Node {
        int id;
        Eigen::Vector2d pos;
        int mask;   // bit i: on side i (from corner i to corner i+1); 0 inside
        int side;   // the side along which the boundary runs forward from here; -1 inside
        int cycle;  // position on the boundary cycle; -1 inside
    };
    struct LocalChord {
        int a, b, edge;
        bool alive;
    };

    void layout(int f, const std::pair<int, int>* inside_begin, const std::pair<int, int>* inside_end) {
        nodes_.clear();
        const auto& tri = mesh_.triangle(f);
        corner_[0] = Eigen::Vector2d(0.0, 0.0);
        corner_[1] = Eigen::Vector2d(mesh_.length(3 * f), 0.0);
        corner_[2] = mesh_.apex(3 * f);
        for (int i = 0; i < 3; ++i) {
            nodes_.push_back({tri[i], corner_[i], (1 << i) | (1 << ((i + 2) % 3)), i, 0});
            const int slot = table_.slot_of_rep(edge_representative(mesh_, 3 * f + i));
            if (slot < 0) continue;
            const PointTable::EdgeSlot& e = table_.edges[slot];
            const bool forward = tri[i] == e.v0;
            const Eigen::Vector2d& p0 = forward ? corner_[i] : corner_[(i + 1) % 3];
            const Eigen::Vector2d& p1 = forward ? corner_[(i + 1) % 3] : corner_[i];
            const int n = static_cast<int>(e.points.size());
            for (int k = 0; k < n; ++k) {
                const auto& [t, id] = e.points[forward ? k : n - 1 - k];
                nodes_.push_back({id, (1.0 - t) * p0 + t * p1, 1 << i, i, 0});
            }
        }
        boundary_count_ = static_cast<int>(nodes_.size());
        for (int k = 0; k < boundary_count_; ++k) nodes_[k].cycle = k;
        for (auto it = inside_begin; it != inside_end; ++it) {
            const auto& b = table_.point(it->second).bary;
            nodes_.push_back({it->second, b[0] * corner_[0] + b[1] * corner_[1] + b[2] * corner_[2], 0, -1, -1});
        }
    }

    int local_of(int id) const {
        for (int k = 0; k < static_cast<int>(nodes_.size()); ++k)
            if (nodes_[k].id == id) return k;
        return -1;
    }

    /// Twice the signed area of (i, j, k); exactly 0 for three points on one side of the fine face. Three points
    /// of the boundary of a face with area, not all on one side, turn counter-clockwise exactly when they come in
    /// that order along the boundary cycle: that sign is taken, whatever rounding says of points an ulp apart.
    double orient(int i, int j, int k) const {
        if (nodes_[i].mask & nodes_[j].mask & nodes_[k].mask) return 0.0;
        const Eigen::Vector2d u = nodes_[j].pos - nodes_[i].pos;
        const Eigen::Vector2d v = nodes_[k].pos - nodes_[i].pos;
        const double area = u.x() * v.y() - u.y() * v.x();
        const int a = nodes_[i].cycle, b = nodes_[j].cycle, c = nodes_[k].cycle;
        if (a < 0 || b < 0 || c < 0 || !(corner_[2].y() > 0.0)) return area;
        const bool counter_clockwise = (a < b && b < c) || (b < c && c < a) || (c < a && a < b);
        const double magnitude = std::max(std::abs(area), std::numeric_limits<double>::denorm_min());
        return counter_clockwise ? magnitude : -magnitude;
    }

    static int sign(double x) { return (x > 0.0) - (x < 0.0); }

    /// Whether p lies on the closed segment from a to b, given that the three are collinear.
    bool between(int a, int b, int p) const {
        const Eigen::Vector2d d = nodes_[b].pos - nodes_[a].pos;
        const double s = d.dot(nodes_[p].pos - nodes_[a].pos);
        return s >= 0.0 && s <= d.squaredNorm();
    }

    /// Whether two chords meet anywhere but at a common end point (where they may still overlap).
    bool conflict(const LocalChord& c, const LocalChord& d) const {
        int shared = -1, x = -1, y = -1;
        if (c.a == d.a) shared = c.a, x = c.b, y = d.b;
        else if (c.a == d.b) shared = c.a, x = c.b, y = d.a;
        else if (c.b == d.a) shared = c.b, x = c.a, y = d.b;
        else if (c.b == d.b) shared = c.b, x = c.a, y = d.a;
        if (shared >= 0) {
            // From a common end, two chords overlap when they leave in the same direction.
            return orient(shared, x, y) == 0.0 &&
                   (nodes_[x].pos - nodes_[shared].pos).dot(nodes_[y].pos - nodes_[shared].pos) > 0.0;
        }
        if (nodes_[c.a].cycle >= 0 && nodes_[c.b].cycle >= 0 && nodes_[d.a].cycle >= 0 &&
            nodes_[d.b].cycle >= 0) {
            // Chords between boundary points of a convex face cross exactly when their ends interleave.
            int lo = nodes_[c.a].cycle, hi = nodes_[c.b].cycle;
            if (lo > hi) std::swap(lo, hi);
            const bool in0 = nodes_[d.a].cycle > lo && nodes_[d.a].cycle < hi;
            const bool in1 = nodes_[d.b].cycle > lo && nodes_[d.b].cycle < hi;
            return in0 != in1;
        }
        const double c_to_d[2] = {orient(d.a, d.b, c.a), orient(d.a, d.b, c.b)};
        const int o1 = sign(orient(c.a, c.b, d.a)), o2 = sign(orient(c.a, c.b, d.b));
        const int o3 = sign(c_to_d[0]), o4 = sign(c_to_d[1]);
        if (o1 * o2 < 0 && o3 * o4 < 0)
            return detail::crossing_confirmed(nodes_[c.a].pos, nodes_[c.b].pos, nodes_[d.a].pos, nodes_[d.b].pos,
                                              c_to_d[0], c_to_d[1]);
        return (o1 == 0 && between(c.a, c.b, d.a)) || (o2 == 0 && between(c.a, c.b, d.b)) ||
               (o3 == 0 && between(d.a, d.b, c.a)) || (o4 == 0 && between(d.a, d.b, c.b));
    }

    void collect_chords(const Chord* begin, const Chord* end, std::vector<char>& broken_edge) {
        chords_.clear();
        for (const Chord* c = begin; c != end; ++c) {
            const int a = local_of(c->a), b = local_of(c->b);
            if (a < 0 || b < 0 || a == b) {
                broken_edge[c->edge] = 1;
                continue;
            }
            // Along a side of the face: that is the boundary already (the caller sends these elsewhere).
            if (nodes_[a].mask & nodes_[b].mask) continue;
            LocalChord lc{a, b, c->edge, true};
            bool keep = true;
            for (const LocalChord& other : chords_) {
                const bool same = (other.a == a && other.b == b) || (other.a == b && other.b == a);
                if (same || conflict(other, lc)) {
                    broken_edge[other.edge] = 1;
                    broken_edge[c->edge] = 1;
                    keep = false;
                    break;
                }
            }
            if (keep) chords_.push_back(lc);
        }
    }

    /// Leaves out chords that end inside the face at a point of degree one, and chords that are not connected to
    /// the boundary: both are signs of an invalid G, and neither bounds a face of the plane graph.
    void prune(std::vector<char>& broken_edge) {
        const int n = static_cast<int>(nodes_.size());
        degree_.assign(n, 0);
        for (int k = 0; k < boundary_count_; ++k) degree_[k] = 2;
        for (const LocalChord& c : chords_) ++degree_[c.a], ++degree_[c.b];
        for (bool changed = true; changed;) {
            changed = false;
            for (LocalChord& c : chords_) {
                if (!c.alive) continue;
                if ((nodes_[c.a].cycle < 0 && degree_[c.a] <= 1) || (nodes_[c.b].cycle < 0 && degree_[c.b] <= 1)) {
                    c.alive = false;
                    --degree_[c.a], --degree_[c.b];
                    broken_edge[c.edge] = 1;
                    changed = true;
                }
            }
        }
        // Inside points reached from the boundary through live chords.
        reached_.assign(n, 0);
        for (int k = 0; k < boundary_count_; ++k) reached_[k] = 1;
        for (bool changed = true; changed;) {
            changed = false;
            for (const LocalChord& c : chords_) {
                if (c.alive && reached_[c.a] != reached_[c.b]) {
                    reached_[c.a] = reached_[c.b] = 1;
                    changed = true;
                }
            }
        }
        for (LocalChord& c : chords_) {
            if (c.alive && !reached_[c.a]) {
                c.alive = false;
                broken_edge[c.edge] = 1;
            }
        }
    }

    /// The neighbours of every node in counter-clockwise order. On the boundary, the next boundary node comes
    /// first and the previous one last, whatever rounding says about chords nearly along a side, so that the
    /// outer face is exactly the reversed boundary cycle.
    void build_rotations() {
        const int n = static_cast<int>(nodes_.size());
        if (static_cast<int>(rotation_.size()) < n) rotation_.resize(n);
        for (int k = 0; k < n; ++k) rotation_[k].clear();
        std::vector<std::pair<double, int>>& around = scratch_angles_;
        for (int u = 0; u < n; ++u) {
            around.clear();
            for (const LocalChord& c : chords_) {
                if (!c.alive || (c.a != u && c.b != u)) continue;
                const int v = c.a == u ? c.b : c.a;
                const Eigen::Vector2d d = nodes_[v].pos - nodes_[u].pos;
                double angle;
                if (nodes_[u].cycle >= 0) {
                    const int s = nodes_[u].side;
                    const Eigen::Vector2d forward = corner_[(s + 1) % 3] - corner_[s];
                    angle = std::atan2(forward.x() * d.y() - forward.y() * d.x(), forward.dot(d));
                    if (angle < 0.0) angle = angle < -0.5 * k_pi ? k_pi : 0.0;
                } else {
                    angle = std::atan2(d.y(), d.x());
                }
                around.emplace_back(angle, v);
            }
            if (around.empty() && nodes_[u].cycle < 0) continue;
            std::sort(around.begin(), around.end());
            order_boundary_targets(u, around);
            std::vector<int>& rot = rotation_[u];
            if (nodes_[u].cycle >= 0) rot.push_back((u + 1) % boundary_count_);
            for (const auto& [angle, v] : around) rot.push_back(v);
            if (nodes_[u].cycle >= 0) rot.push_back((u + boundary_count_ - 1) % boundary_count_);
        }
    }

    /// Seen from any point of the (convex) fine face, its boundary points come in the order of the boundary cycle.
    /// Two chords to boundary points that nearly coincide (the geodesics of an invalid G that overlap) can have
    /// their angles swapped by rounding, and the faces traced from a wrong rotation overlap: the chords' ends are
    /// put back in cycle order, in the places that they took among the chords to inside points.
    void order_boundary_targets(int u, std::vector<std::pair<double, int>>& around) {
        std::vector<int>& slots = scratch_slots_;
        std::vector<int>& targets = scratch_targets_;
        slots.clear();
        targets.clear();
        for (int k = 0; k < static_cast<int>(around.size()); ++k) {
            if (nodes_[around[k].second].cycle < 0) continue;
            slots.push_back(k);
            targets.push_back(around[k].second);
        }
        const int m = static_cast<int>(targets.size());
        if (m < 2) return;
        // From a boundary point the order starts after it; from an inside point it is cyclic, and the rotation of
        // it that agrees best with the angles is taken.
        const int start = nodes_[u].cycle >= 0 ? nodes_[u].cycle + 1 : 0;
        auto offset = [&](int v) { return (nodes_[v].cycle - start + boundary_count_) % boundary_count_; };
        std::vector<int> by_cycle(targets);
        std::sort(by_cycle.begin(), by_cycle.end(), [&](int a, int b) { return offset(a) < offset(b); });
        int shift = 0;
        if (nodes_[u].cycle < 0) {
            int best_agree = -1;
            for (int r = 0; r < m; ++r) {
                int agree = 0;
                for (int k = 0; k < m; ++k) agree += by_cycle[(k + r) % m] == targets[k];
                if (agree > best_agree) best_agree = agree, shift = r;
            }
        }
        for (int k = 0; k < m; ++k) around[slots[k]].second = by_cycle[(k + shift) % m];
    }

    int index_in_rotation(int u, int v) const {
        const std::vector<int>& rot = rotation_[u];
        for (int k = 0; k < static_cast<int>(rot.size()); ++k)
            if (rot[k] == v) return k;
        return -1;
    }

    void trace_faces(int f) {
        const int n = static_cast<int>(nodes_.size());
        offset_.assign(n + 1, 0);
        for (int u = 0; u < n; ++u) offset_[u + 1] = offset_[u] + static_cast<int>(rotation_[u].size());
        const int total = offset_[n];
        used_.assign(total, 0);
        // The outer face: the boundary cycle run backwards.
        for (int u = 0; u < boundary_count_; ++u) used_[offset_[u + 1] - 1] = 1;
        for (int u = 0; u < n; ++u) {
            for (int k = 0; k < static_cast<int>(rotation_[u].size()); ++k) {
                if (used_[offset_[u] + k]) continue;
                polygon_.clear();
                int x = u, i = k;
                bool closed = false;
                for (int steps = 0; steps <= total; ++steps) {
                    if (used_[offset_[x] + i]) {
                        closed = x == u && i == k;
                        break;
                    }
                    used_[offset_[x] + i] = 1;
                    polygon_.push_back(x);
                    const int y = rotation_[x][i];
                    const int j = index_in_rotation(y, x);
                    if (j < 0) break;
                    const int deg = static_cast<int>(rotation_[y].size());
                    x = y;
                    i = (j + deg - 1) % deg;
                }
                if (closed && polygon_.size() >= 3) triangulate(f);
            }
        }
    }

    void emit(int f, int a, int b, int c) {
        out_.triangles.push_back({nodes_[a].id, nodes_[b].id, nodes_[c].id});
        out_.fine_face.push_back(f);
    }

    /// Ear clipping of polygon_ (counter-clockwise, possibly touching itself at a vertex): the strictly convex
    /// ear of best shape with no other vertex in it; when there is none (degenerate input), the corner of largest
    /// signed area, so that each step removes a vertex and the loop ends.
    void triangulate(int f) {
        std::vector<int>& poly = polygon_;
        while (poly.size() > 3) {
            const int n = static_cast<int>(poly.size());
            int best = -1;
            bool best_is_ear = false;
            double best_quality = -std::numeric_limits<double>::infinity();
            for (int i = 0; i < n; ++i) {
                const int a = poly[(i + n - 1) % n], b = poly[i], c = poly[(i + 1) % n];
                if (nodes_[a].id == nodes_[c].id) continue;
                const double o = orient(a, b, c);
                const double scale = (nodes_[b].pos - nodes_[a].pos).squaredNorm() +
                                      (nodes_[c].pos - nodes_[b].pos).squaredNorm() +
                                      (nodes_[a].pos - nodes_[c].pos).squaredNorm();
                const double quality = scale > 0.0 ? o / scale : o;
                bool ear = o > 0.0;
                for (int j = 0; ear && j < n; ++j) {
                    const int p = poly[j];
                    const int id = nodes_[p].id;
                    if (id == nodes_[a].id || id == nodes_[b].id || id == nodes_[c].id) continue;
                    if (orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0) ear = false;
                }
                if ((ear && !best_is_ear) || (ear == best_is_ear && quality > best_quality)) {
                    best = i;
                    best_is_ear = ear;
                    best_quality = quality;
                }
            }
            if (best < 0) return;  // only pinched corners left: nothing sensible to cut
            emit(f, poly[(best + n - 1) % n], poly[best], poly[(best + 1) % n]);
            poly.erase(poly.begin() + best);
        }
        if (nodes_[poly[0]].id != nodes_[poly[2]].id) emit(f, poly[0], poly[1], poly[2]);
    }

    const Mesh& mesh_;
    const PointTable& table_;
    Overlay& out_;
    Eigen::Vector2d corner_[3];
    std::vector<Node> nodes_;
    int boundary_count_ = 0;
    std::vector<LocalChord> chords_;
    std::vector<int> degree_;
    std::vector<char> reached_;
    std::vector<std::vector<int>> rotation_;
    std::vector<std::pair<double, int>> scratch_angles_;
    std::vector<int> scratch_slots_;
    std::vector<int> scratch_targets_;
    std::vector<int> offset_;
    std::vector<char> used_;
    std::vector<int> polygon_;
};

/// The fine faces that contain both points (at most a handful; sorted).
void common_faces(const Mesh& mesh, const PointTable& table, int a, int b, std::vector<int>& out) {
    auto faces_of = [&](int id, std::vector<int>& faces) {
        faces.clear();
        if (table.is_vertex(id)) {
            for (int h : mesh.outgoing_halfedges(id)) faces.push_back(Mesh::face_of(h));
        } else if (table.slot_of(id) >= 0) {
            const auto& e = table.edges[table.slot_of(id)];
            for (int h : {mesh.find_halfedge(e.v0, e.v1), mesh.find_halfedge(e.v1, e.v0)})
                if (h >= 0) faces.push_back(Mesh::face_of(h));
        } else {
            faces.push_back(table.point(id).face);
        }
        std::sort(faces.begin(), faces.end());
    };
    static thread_local std::vector<int> fa, fb;
    faces_of(a, fa);
    faces_of(b, fb);
    out.clear();
    std::set_intersection(fa.begin(), fa.end(), fb.begin(), fb.end(), std::back_inserter(out));
}

/// When a and b lie on one fine edge (its ends or points on it), the overlay vertices from a to b along it,
/// both included; else empty.
std::vector<int> along_edge(const Mesh& mesh, const PointTable& table, int a, int b) {
    int v0 = -1, v1 = -1, slot = -1;
    const bool va = table.is_vertex(a), vb = table.is_vertex(b);
    if (va && vb) {
        if (mesh.find_halfedge(a, b) < 0 && mesh.find_halfedge(b, a) < 0) return {};
        v0 = std::min(a, b);
        v1 = std::max(a, b);
        int h = mesh.find_halfedge(v0, v1);
        if (h < 0) h = mesh.find_halfedge(v1, v0);
        slot = table.slot_of_rep(edge_representative(mesh, h));
    } else {
        const int sa = table.slot_of(a), sb = table.slot_of(b);
        slot = sa >= 0 ? sa : sb;
        if (slot < 0) return {};
        if ((!va && sa != slot) || (!vb && sb != slot)) return {};
        v0 = table.edges[slot].v0;
        v1 = table.edges[slot].v1;
        if ((va && a != v0 && a != v1) || (vb && b != v0 && b != v1)) return {};
    }
    const int count = slot >= 0 ? static_cast<int>(table.edges[slot].points.size()) : 0;
    auto position = [&](int id) { return id == v0 ? 0 : id == v1 ? count + 1 : table.position_in_slot(id); };
    auto vertex_at = [&](int k) { return k == 0 ? v0 : k == count + 1 ? v1 : table.edges[slot].points[k - 1].second; };
    const int pa = position(a), pb = position(b);
    std::vector<int> run;
    const int step = pa < pb ? 1 : -1;
    for (int k = pa;; k += step) {
        run.push_back(vertex_at(k));
        if (k == pb) break;
    }
    return run;
}

/// The cut along some polylines of G: each one's overlay vertices along the cut (its chain, oriented like the
/// polyline), its segments through fine faces (chords, sorted by face), and which polyline owns each cut edge.
struct Cuts {
    std::vector<std::vector<int>> chain;                // per coarse edge
    std::vector<Chord> chords;
    std::unordered_map<std::uint64_t, int> cut_owner;  // undirected overlay edge -> coarse edge
};

/// Cuts along the polylines of `edges`, whose points are `ids` (per coarse edge) in `table`. Each segment runs
/// along a fine edge (the cut follows the edge's pieces) or through one fine face (a chord of that face). Marks in
/// `broken` the polylines that cannot be cut: consecutive points on no common fine face, or overlapping another.
Cuts cut_along(const Mesh& mesh, const PointTable& table, const std::vector<std::vector<int>>& ids,
               const std::vector<int>& edges, std::vector<char>& broken) {
    Cuts cuts;
    cuts.chain.resize(ids.size());
    auto mark_cut = [&](int a, int b, int edge) {
        auto [it, inserted] = cuts.cut_owner.emplace(undirected_key(a, b), edge);
        if (!inserted && it->second != edge) broken[it->second] = broken[edge] = 1;  // overlapping polylines
    };
    std::vector<int> faces;
    for (int e : edges) {
        const std::vector<int>& line_ids = ids[e];
        if (line_ids.size() < 2) continue;
        std::vector<int>& c = cuts.chain[e];
        c.push_back(line_ids[0]);
        for (std::size_t k = 0; k + 1 < line_ids.size(); ++k) {
            const int a = line_ids[k], b = line_ids[k + 1];
            if (a == b) continue;
            const std::vector<int> run = along_edge(mesh, table, a, b);
            if (!run.empty()) {
                for (std::size_t r = 0; r + 1 < run.size(); ++r) {
                    mark_cut(run[r], run[r + 1], e);
                    c.push_back(run[r + 1]);
                }
                continue;
            }
            common_faces(mesh, table, a, b, faces);
            if (faces.empty()) broken[e] = 1;
            else cuts.chords.push_back({faces[0], a, b, e});
            mark_cut(a, b, e);
            c.push_back(b);
        }
    }
    std::stable_sort(cuts.chords.begin(), cuts.chords.end(),
                     [](const Chord& x, const Chord& y) { return x.face < y.face; });
    return cuts;
}

/// The overlay vertices of each polyline of `edges` (per coarse edge; empty, and the edge marked in `broken`, for a
/// polyline that does not refer to T or has fewer than two points).
std::vector<std::vector<int>> polyline_ids(const GeodesicTriangulation& g, const std::vector<int>& edges,
                                           PointTable& table, std::vector<char>& broken) {
    std::vector<std::vector<int>> ids(g.coarse().n_edges());
    for (int e : edges) {
        std::vector<int>& line_ids = ids[e];
        for (const SurfacePoint& p : g.polyline(OpenMesh::EdgeHandle(e))) {
            const int id = table.id_of(p);
            if (id < 0) {
                line_ids.clear();
                break;
            }
            line_ids.push_back(id);
        }
        if (line_ids.size() < 2) broken[e] = 1;
    }
    return ids;
}

/// The fine faces that the cut touches: those of its chords, of its face points and on both sides of every fine
/// edge with a point on it. Sorted, without repeats.
std::vector<int> touched_faces(const Mesh& mesh, const Cuts& cuts, const PointTable& table) {
    std::vector<int> touched;
    for (const Chord& c : cuts.chords) touched.push_back(c.face);
    for (const auto& [f, id] : table.face_points) touched.push_back(f);
    for (const auto& e : table.edges)
        for (int h : {mesh.find_halfedge(e.v0, e.v1), mesh.find_halfedge(e.v1, e.v0)})
            if (h >= 0) touched.push_back(Mesh::face_of(h));
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    return touched;
}

/// Cuts fine face f along its chords and around its face points. Faces must come in increasing order: the
/// cursors walk the chords and the face points (both sorted by face) once.
void cut_face(FaceCutter& cutter, int f, const Cuts& cuts, const PointTable& table, std::size_t& next_chord,
              std::size_t& next_inside, std::vector<char>& broken) {
    while (next_chord < cuts.chords.size() && cuts.chords[next_chord].face < f) ++next_chord;
    std::size_t chord_end = next_chord;
    while (chord_end < cuts.chords.size() && cuts.chords[chord_end].face == f) ++chord_end;
    while (next_inside < table.face_points.size() && table.face_points[next_inside].first < f) ++next_inside;
    std::size_t inside_end = next_inside;
    while (inside_end < table.face_points.size() && table.face_points[inside_end].first == f) ++inside_end;
    cutter.cut(f, cuts.chords.data() + next_chord, cuts.chords.data() + chord_end,
               table.face_points.data() + next_inside, table.face_points.data() + inside_end, broken);
    next_chord = chord_end;
    next_inside = inside_end;
}

/// Topology of each region, as a surface of its own (cut open along the polylines).
struct RegionShape {
    int triangles = 0;
    int boundary_edges = 0;
    int vertices = 0;   // classes of corners glued across uncut edges
    int loops = 0;
    bool simple = true;  // every boundary vertex has one boundary edge out, and no overlay vertex repeats
    double area = 0.0;
    bool disk() const {
        const int twice_edges = 3 * triangles + boundary_edges;
        if (twice_edges % 2) return false;
        return simple && loops == 1 && vertices - twice_edges / 2 + triangles == 1;
    }
};

}  // namespace

Overlay build_overlay(const GeodesicTriangulation& g) {
    const Mesh& mesh = g.fine().mesh;
    const CoarseMesh& coarse = g.coarse();
    const int num_coarse_edges = static_cast<int>(coarse.n_edges());
    const int num_coarse_faces = static_cast<int>(coarse.n_faces());
    Overlay out;
    PointTable table(mesh, out);

    // 1. Every point of every polyline, and every location, becomes an overlay vertex.
    std::vector<char> broken(num_coarse_edges, 0);
    std::vector<int> location_id(coarse.n_vertices(), -1);
    for (auto v : coarse.vertices()) location_id[v.idx()] = table.id_of(g.location(v));
    std::vector<int> all_edges(num_coarse_edges);
    std::iota(all_edges.begin(), all_edges.end(), 0);
    const std::vector<std::vector<int>> ids = polyline_ids(g, all_edges, table, broken);
    table.finish();

    // 2. The chain of each polyline along the cut, and its chords through fine faces.
    Cuts cuts = cut_along(mesh, table, ids, all_edges, broken);
    const std::vector<std::vector<int>>& chain = cuts.chain;
    const std::vector<Chord>& chords = cuts.chords;
    const std::unordered_map<std::uint64_t, int>& cut_owner = cuts.cut_owner;

    // 3. Triangulate: untouched fine faces as they are, the others cut along their chords.
    const int nf = mesh.num_faces();
    std::vector<char> touched(nf, 0);
    for (int f : touched_faces(mesh, cuts, table)) touched[f] = 1;
    out.triangles.reserve(nf + 4 * chords.size());
    out.fine_face.reserve(out.triangles.capacity());
    FaceCutter cutter(mesh, table, out);
    std::size_t next_chord = 0, next_inside = 0;
    for (int f = 0; f < nf; ++f) {
        if (touched[f]) {
            cut_face(cutter, f, cuts, table, next_chord, next_inside, broken);
        } else {
            out.triangles.push_back(mesh.triangle(f));
            out.fine_face.push_back(f);
        }
    }

    // 4. Halfedges of the overlay, by tail vertex, to find a directed edge and its twin.
    const int nt = static_cast<int>(out.triangles.size());
    const int nv = static_cast<int>(out.positions.size());
    std::vector<int> first(nv + 1, 0);
    for (const auto& t : out.triangles)
        for (int v : t) ++first[v + 1];
    for (int v = 0; v < nv; ++v) first[v + 1] += first[v];
    std::vector<std::pair<int, int>> leaving(first[nv]);  // (head, halfedge 3·t + k)
    {
        std::vector<int> fill(first.begin(), first.end() - 1);
        for (int t = 0; t < nt; ++t)
            for (int k = 0; k < 3; ++k)
                leaving[fill[out.triangles[t][k]]++] = {out.triangles[t][(k + 1) % 3], 3 * t + k};
    }
    auto find_halfedge = [&](int a, int b) {
        for (int i = first[a]; i < first[a + 1]; ++i)
            if (leaving[i].first == b) return leaving[i].second;
        return -1;
    };
    auto tail = [&](int h) { return out.triangles[h / 3][h % 3]; };
    auto head = [&](int h) { return out.triangles[h / 3][(h % 3 + 1) % 3]; };

    // 5. Regions: triangles joined across uncut edges; corners joined likewise, for the regions' own topology.
    // Only an edge between two vertices of the cut can be cut: most edges are then told apart without a lookup.
    std::vector<char> on_cut(nv, 0);
    for (const auto& [key, edge] : cut_owner) {
        on_cut[static_cast<std::size_t>(key >> 32)] = 1;
        on_cut[static_cast<std::size_t>(key & 0xffffffffu)] = 1;
    }
    DisjointSets triangle_sets(nt), corner_sets(3 * nt);
    std::vector<char> boundary_halfedge(3 * nt, 0);
    std::vector<int> twin(3 * nt, -1);
    for (int h = 0; h < 3 * nt; ++h) {
        const int a = tail(h), b = head(h);
        const int t = find_halfedge(b, a);
        twin[h] = t;
        const bool cut = t < 0 || (on_cut[a] && on_cut[b] && cut_owner.count(undirected_key(a, b)) != 0);
        if (cut) {
            boundary_halfedge[h] = 1;
            continue;
        }
        if (h > t) continue;
        triangle_sets.unite(h / 3, t / 3);
        corner_sets.unite(h, 3 * (t / 3) + (t % 3 + 1) % 3);  // both corners at a
        corner_sets.unite(3 * (h / 3) + (h % 3 + 1) % 3, t);  // both corners at b
    }
    std::vector<int> region(nt);
    std::vector<int> region_of_root(nt, -1);
    int num_regions = 0;
    for (int t = 0; t < nt; ++t) {
        const int root = triangle_sets.find(t);
        if (region_of_root[root] < 0) region_of_root[root] = num_regions++;
        region[t] = region_of_root[root];
    }
    out.num_regions = num_regions;

    std::vector<RegionShape> shape(num_regions);
    {
        std::vector<char> class_seen(3 * nt, 0);
        std::vector<int> out_edge(3 * nt, -1);  // per corner class: its boundary halfedge, if one
        std::vector<int> stamp(nv, -1);
        for (int t = 0; t < nt; ++t) {
            RegionShape& s = shape[region[t]];
            ++s.triangles;
            const auto& tri = out.triangles[t];
            s.area += 0.5 * (out.positions[tri[1]] - out.positions[tri[0]])
                                .cross(out.positions[tri[2]] - out.positions[tri[0]])
                                .norm();
            for (int k = 0; k < 3; ++k) {
                const int h = 3 * t + k;
                const int cls = corner_sets.find(h);
                if (!class_seen[cls]) {
                    class_seen[cls] = 1;
                    ++s.vertices;
                }
                if (!boundary_halfedge[h]) continue;
                ++s.boundary_edges;
                if (out_edge[cls] >= 0) s.simple = false;
                out_edge[cls] = h;
                if (stamp[tail(h)] == region[t]) s.simple = false;
                stamp[tail(h)] = region[t];
            }
        }
        std::vector<char> visited(3 * nt, 0);
        for (int h = 0; h < 3 * nt; ++h) {
            if (!boundary_halfedge[h] || visited[h]) continue;
            RegionShape& s = shape[region[h / 3]];
            ++s.loops;
            for (int x = h, steps = 0; x >= 0 && !visited[x] && steps < 3 * nt; ++steps) {
                visited[x] = 1;
                x = out_edge[corner_sets.find(3 * (x / 3) + (x % 3 + 1) % 3)];
            }
        }
    }

    // 6. Claims: the region on the left of each path of each coarse face.
    std::vector<char> bad(num_coarse_faces, 0);
    std::vector<std::vector<int>> claims(num_coarse_faces);
    std::vector<int> path_edges(num_coarse_faces, 0);
    for (auto f : coarse.faces()) {
        const int fi = f.idx();
        for (auto h : coarse.fh_range(f)) {
            const int e = coarse.edge_handle(h).idx();
            const std::vector<int>& c = chain[e];
            if (broken[e] || c.size() < 2) {
                bad[fi] = 1;
                continue;
            }
            const bool forward = h == coarse.halfedge_handle(coarse.edge_handle(h), 0);
            const int from = location_id[coarse.from_vertex_handle(h).idx()];
            const int to = location_id[coarse.to_vertex_handle(h).idx()];
            if ((forward ? c.front() : c.back()) != from || (forward ? c.back() : c.front()) != to || from < 0)
                bad[fi] = 1;
            for (std::size_t k = 0; k + 1 < c.size(); ++k) {
                const int a = forward ? c[k] : c[c.size() - 1 - k];
                const int b = forward ? c[k + 1] : c[c.size() - 2 - k];
                const int he = find_halfedge(a, b);
                ++path_edges[fi];
                if (he < 0) {
                    bad[fi] = 1;
                    continue;
                }
                claims[fi].push_back(region[he / 3]);
            }
        }
        std::sort(claims[fi].begin(), claims[fi].end());
        claims[fi].erase(std::unique(claims[fi].begin(), claims[fi].end()), claims[fi].end());
    }
    std::vector<int> owner(num_regions, -1), claimers(num_regions, 0);
    for (int fi = 0; fi < num_coarse_faces; ++fi) {
        for (int r : claims[fi]) {
            ++claimers[r];
            if (owner[r] < 0) owner[r] = fi;
        }
    }
    out.patch_area.assign(num_coarse_faces, 0.0);
    for (int r = 0; r < num_regions; ++r) {
        if (owner[r] >= 0) {
            out.patch_area[owner[r]] += shape[r].area;
        } else {
            ++out.unclaimed_regions;
            out.unclaimed_area += shape[r].area;
        }
    }
    for (auto f : coarse.faces()) {
        const int fi = f.idx();
        if (claims[fi].size() != 1) {
            bad[fi] = 1;
            continue;
        }
        const int r = claims[fi][0];
        if (claimers[r] != 1 || !shape[r].disk() || shape[r].boundary_edges != path_edges[fi]) bad[fi] = 1;
    }
    for (int fi = 0; fi < num_coarse_faces; ++fi)
        if (bad[fi]) out.bad_patches.push_back(fi);
    for (int e = 0; e < num_coarse_edges; ++e)
        if (broken[e]) out.broken_edges.push_back(e);

    out.patch.resize(nt);
    for (int t = 0; t < nt; ++t) out.patch[t] = owner[region[t]];

    // 7. Greedy colouring of the patches in face order, over the adjacency that the overlay shows.
    std::vector<std::pair<int, int>> adjacent;
    for (int h = 0; h < 3 * nt; ++h) {
        if (!boundary_halfedge[h] || twin[h] < 0) continue;
        const int a = out.patch[h / 3], b = out.patch[twin[h] / 3];
        if (a >= 0 && b >= 0 && a != b) adjacent.emplace_back(a, b);
    }
    std::sort(adjacent.begin(), adjacent.end());
    adjacent.erase(std::unique(adjacent.begin(), adjacent.end()), adjacent.end());
    std::vector<int> patch_colour(num_coarse_faces, -1);
    std::vector<char> taken;
    std::size_t a_begin = 0;
    for (int fi = 0; fi < num_coarse_faces; ++fi) {
        std::size_t a_end = a_begin;
        while (a_end < adjacent.size() && adjacent[a_end].first == fi) ++a_end;
        taken.assign(a_end - a_begin + 1, 0);
        for (std::size_t i = a_begin; i < a_end; ++i) {
            const int c = patch_colour[adjacent[i].second];
            if (c >= 0 && c < static_cast<int>(taken.size())) taken[c] = 1;
        }
        int c = 0;
        while (taken[c]) ++c;
        patch_colour[fi] = c;
        out.num_colours = std::max(out.num_colours, c + 1);
        a_begin = a_end;
    }
    out.colour.resize(nt);
    for (int t = 0; t < nt; ++t) out.colour[t] = out.patch[t] >= 0 ? patch_colour[out.patch[t]] : -1;
    return out;
}

}  // namespace geotri

namespace geotri::detail {

Overlay build_patch_overlay(const GeodesicTriangulation& g, std::vector<int> coarse_faces) {
    std::sort(coarse_faces.begin(), coarse_faces.end());
    coarse_faces.erase(std::unique(coarse_faces.begin(), coarse_faces.end()), coarse_faces.end());
    const Mesh& mesh = g.fine().mesh;
    const CoarseMesh& coarse = g.coarse();
    const int num_fine_vertices = mesh.num_vertices();
    std::vector<int> edges;
    for (int f : coarse_faces) {
        if (f < 0 || f >= static_cast<int>(coarse.n_faces()) || coarse.status(OpenMesh::FaceHandle(f)).deleted())
            throw InvalidInput("build_patch_overlay: " + std::to_string(f) + " is not a face of the coarse mesh");
        for (auto e : coarse.fe_range(OpenMesh::FaceHandle(f))) edges.push_back(e.idx());
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    auto not_a_disk = [](int f, const std::string& why) {
        return InvalidInput("the patch of coarse face " + std::to_string(f) + " is not a disk (" + why + ")");
    };

    // 1-2. The points of the faces' polylines and locations, and the cut along those polylines only.
    Overlay cut;  // the edge and face points, and every triangle made; ids as the table numbers them
    PointTable table(mesh, cut, false);
    // Every coarse vertex's location, as in the overlay of all of G: a patch must not hold any but its corners.
    std::vector<int> location_id(coarse.n_vertices(), -1);
    for (auto v : coarse.vertices()) location_id[v.idx()] = table.id_of(g.location(v));
    std::vector<char> broken(coarse.n_edges(), 0);
    const std::vector<std::vector<int>> ids = polyline_ids(g, edges, table, broken);
    table.finish();
    const Cuts cuts = cut_along(mesh, table, ids, edges, broken);

    // 3. The fine faces that the cut touches, cut into triangles; the others are added whole as the flood
    // reaches them.
    const std::vector<int> touched = touched_faces(mesh, cuts, table);
    FaceCutter cutter(mesh, table, cut);
    std::size_t next_chord = 0, next_inside = 0;
    for (int f : touched) cut_face(cutter, f, cuts, table, next_chord, next_inside, broken);
    for (int e : edges)
        if (broken[e]) throw InvalidInput("coarse edge " + std::to_string(e) + ": its polyline cannot be cut");

    // 4. Each face's patch: a flood from the triangles on the left of its paths across uncut edges.
    std::unordered_map<std::uint64_t, int> triangle_of;  // directed edge -> the triangle on its left
    auto directed = [](int a, int b) {
        return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
    };
    std::vector<int> patch;
    auto add_triangle = [&](int t) {
        const auto& tri = cut.triangles[static_cast<std::size_t>(t)];
        for (int k = 0; k < 3; ++k) triangle_of[directed(tri[k], tri[(k + 1) % 3])] = t;
        patch.push_back(-1);
    };
    for (int t = 0; t < static_cast<int>(cut.triangles.size()); ++t) add_triangle(t);
    // The triangle on the left of a -> b, or -1. One that the cut did not touch is a whole fine face (a and b are
    // then T's vertices), added when it is first asked for.
    auto triangle_left_of = [&](int a, int b) {
        const auto it = triangle_of.find(directed(a, b));
        if (it != triangle_of.end()) return it->second;
        const int h = a < num_fine_vertices && b < num_fine_vertices ? mesh.find_halfedge(a, b) : -1;
        if (h < 0 || std::binary_search(touched.begin(), touched.end(), Mesh::face_of(h))) return -1;
        const int t = static_cast<int>(cut.triangles.size());
        cut.triangles.push_back(mesh.triangle(Mesh::face_of(h)));
        cut.fine_face.push_back(Mesh::face_of(h));
        add_triangle(t);
        return t;
    };
    // Whether a point of fine face `face` (barycentric `b`) lies in triangle t, a piece of that face.
    auto holds = [&](int t, int face, const std::array<double, 3>& b) {
        Eigen::Matrix3d corners;
        for (int i = 0; i < 3; ++i) {
            const int v = cut.triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(i)];
            const SurfacePoint corner = v < num_fine_vertices ? SurfacePoint::at_vertex(v) : table.point(v);
            const std::array<double, 3> c = barycentric_in(mesh, face, corner);
            corners.col(i) = Eigen::Vector3d(c[0], c[1], c[2]);
        }
        const Eigen::FullPivLU<Eigen::Matrix3d> lu(corners);
        return lu.isInvertible() && lu.solve(Eigen::Vector3d(b[0], b[1], b[2])).minCoeff() >= -1e-12;
    };
    for (int f : coarse_faces) {
        std::vector<int> seeds;
        std::vector<std::uint64_t> own;  // this face's cut edges
        for (auto h : coarse.fh_range(OpenMesh::FaceHandle(f))) {
            const std::vector<int>& c = cuts.chain[static_cast<std::size_t>(coarse.edge_handle(h).idx())];
            const bool forward = h == coarse.halfedge_handle(coarse.edge_handle(h), 0);
            const int from = location_id[coarse.from_vertex_handle(h).idx()];
            if (c.size() < 2 || (forward ? c.front() : c.back()) != from || from < 0)
                throw not_a_disk(f, "a path does not start at its vertex");
            for (std::size_t k = 0; k + 1 < c.size(); ++k) {
                const int a = forward ? c[k] : c[c.size() - 1 - k];
                const int b = forward ? c[k + 1] : c[c.size() - 2 - k];
                own.push_back(undirected_key(a, b));
                const int t = triangle_left_of(a, b);
                if (t < 0) throw not_a_disk(f, "nothing on the left of a path");
                seeds.push_back(t);
            }
        }
        std::sort(own.begin(), own.end());
        // From one seed: a patch is one piece across edges, and must reach every other seed.
        std::vector<int> stack{seeds.front()}, region;
        if (patch[static_cast<std::size_t>(seeds.front())] >= 0) throw not_a_disk(f, "it runs into another patch");
        patch[static_cast<std::size_t>(seeds.front())] = f;
        std::size_t boundary = 0;
        std::vector<int> vertices;
        while (!stack.empty()) {
            const int t = stack.back();
            stack.pop_back();
            region.push_back(t);
            const std::array<int, 3> tri = cut.triangles[static_cast<std::size_t>(t)];
            for (int k = 0; k < 3; ++k) {
                const int a = tri[k], b = tri[(k + 1) % 3];
                vertices.push_back(a);
                if (cuts.cut_owner.count(undirected_key(a, b))) {
                    if (!std::binary_search(own.begin(), own.end(), undirected_key(a, b)))
                        throw not_a_disk(f, "another path runs inside it");
                    ++boundary;
                    continue;
                }
                const int next = triangle_left_of(b, a);
                if (next < 0) throw not_a_disk(f, "it reaches a border of T");
                int& owner = patch[static_cast<std::size_t>(next)];
                if (owner == f) continue;
                if (owner >= 0) throw not_a_disk(f, "it runs into another patch");
                owner = f;
                stack.push_back(next);
            }
        }
        for (int t : seeds)
            if (patch[static_cast<std::size_t>(t)] != f) throw not_a_disk(f, "its paths bound more than one piece");
        // Connected, bounded by its paths, each met once from inside, and of Euler characteristic 1: a disk.
        const std::size_t triangles = region.size();
        std::sort(vertices.begin(), vertices.end());
        vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
        if (boundary != own.size() || (3 * triangles + boundary) % 2 != 0 ||
            vertices.size() + triangles != (3 * triangles + boundary) / 2 + 1)
            throw not_a_disk(f, "its triangles do not make a disk bounded by its paths");
        // No other coarse vertex: at a vertex or on an edge of T it is a corner of the triangles; inside a fine face
        // it may be a point that no cut reaches, inside a triangle.
        std::vector<int> corners;
        for (auto v : coarse.fv_range(OpenMesh::FaceHandle(f))) corners.push_back(location_id[v.idx()]);
        for (auto v : coarse.vertices()) {
            const int id = location_id[v.idx()];
            if (std::find(corners.begin(), corners.end(), id) != corners.end()) continue;
            bool inside = std::binary_search(vertices.begin(), vertices.end(), id);
            if (!inside && id >= num_fine_vertices && table.point(id).kind == PointKind::face) {
                const SurfacePoint& p = table.point(id);
                for (int t : region)
                    if (cut.fine_face[static_cast<std::size_t>(t)] == p.face && holds(t, p.face, p.bary)) inside = true;
            }
            if (inside) throw not_a_disk(f, "coarse vertex " + std::to_string(v.idx()) + " lies in it");
        }
    }

    // 5. The patches' triangles in fine face order (the cut ones in the order the cutter made them), renumbered.
    std::vector<int> order;
    for (int t = 0; t < static_cast<int>(patch.size()); ++t)
        if (patch[static_cast<std::size_t>(t)] >= 0) order.push_back(t);
    std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
        return cut.fine_face[static_cast<std::size_t>(x)] < cut.fine_face[static_cast<std::size_t>(y)];
    });
    Overlay out;
    std::unordered_map<int, int> renumbered;
    for (int t : order) {
        std::array<int, 3> tri = cut.triangles[static_cast<std::size_t>(t)];
        for (int& v : tri) {
            const auto [it, inserted] = renumbered.emplace(v, static_cast<int>(out.positions.size()));
            if (inserted && v < num_fine_vertices) {
                out.positions.push_back(mesh.position(v));
                out.points.push_back(SurfacePoint::at_vertex(v));
            } else if (inserted) {
                out.positions.push_back(cut.positions[static_cast<std::size_t>(v - num_fine_vertices)]);
                out.points.push_back(cut.points[static_cast<std::size_t>(v - num_fine_vertices)]);
            }
            v = it->second;
        }
        out.triangles.push_back(tri);
        out.fine_face.push_back(cut.fine_face[static_cast<std::size_t>(t)]);
        out.patch.push_back(patch[static_cast<std::size_t>(t)]);
    }
    return out;
}

}  // namespace geotri::detail

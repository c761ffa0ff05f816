#include <geodesic/constants.h>
#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geodesic/straighten_path.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace geotri::geodesic {

namespace {

using Eigen::Vector2d;

// A bend with this little less than π on its far side is rounding, not a shorter way round.
constexpr double k_angle_slack = 1e-12;
// Passes in a row that move the sleeve without shortening the path, before giving up: every move should shorten it.
constexpr int k_max_idle_passes = 8;

double cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
// Positive when c lies to the left of the line from a to b.
double orient(const Vector2d& a, const Vector2d& b, const Vector2d& c) { return cross(b - a, c - a); }
double angle_between(const Vector2d& u, const Vector2d& v) { return std::atan2(std::abs(cross(u, v)), u.dot(v)); }

bool face_has(const Mesh& mesh, int f, int v) {
    const auto& t = mesh.triangle(f);
    return t[0] == v || t[1] == v || t[2] == v;
}

// The halfedge of face f that leaves v (v is a corner of f).
int leaving(const Mesh& mesh, int f, int v) {
    const auto& t = mesh.triangle(f);
    return 3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
}

// The faces met turning counter-clockwise around v from its edge to a to its edge to b: the face on the left of
// (v, a) first, the face on the right of (v, b) last. Nothing when a boundary is in the way.
std::optional<std::vector<int>> ccw_fan(const Mesh& mesh, int v, int a, int b) {
    std::vector<int> faces;
    int h = mesh.find_halfedge(v, a);
    while (h >= 0 && faces.size() <= std::size_t(mesh.num_faces())) {
        faces.push_back(Mesh::face_of(h));
        if (mesh.tail(Mesh::prev(h)) == b) return faces;
        h = mesh.twin(Mesh::prev(h));
    }
    return std::nullopt;
}

double corner_sum(const Mesh& mesh, const std::vector<int>& faces, int v) {
    double sum = 0.0;
    for (const int f : faces) sum += mesh.corner_angle(leaving(mesh, f, v));
    return sum;
}

// Appends x to `items` unless it repeats the last one, and drops a step straight back (…, a, b, a → …, a): going
// into a face or to a vertex and back again changes no class.
void append_reduced(std::vector<int>& items, int x) {
    if (!items.empty() && items.back() == x) return;
    if (items.size() >= 2 && items[items.size() - 2] == x) {
        items.pop_back();
        return;
    }
    items.push_back(x);
}

// A sequence of faces, each sharing an edge with the next, with the path's start in the first and its end in the
// last. Appending keeps it reduced: no face twice in a row, and no step into a face and straight back (f, g, f),
// which only goes back and forth across one edge.
class Sleeve {
public:
    Sleeve(const Mesh& mesh, int start, int end) : mesh_(mesh), start_(start), end_(end) {}

    void append(int f) { append_reduced(faces_, f); }

    // Leaves out the faces around the ends that the path need not cross: turning around an end is free.
    void trim_ends() {
        std::size_t first = 0;
        while (first + 1 < faces_.size() && face_has(mesh_, faces_[first + 1], start_)) ++first;
        faces_.erase(faces_.begin(), faces_.begin() + std::ptrdiff_t(first));
        while (faces_.size() >= 2 && face_has(mesh_, faces_[faces_.size() - 2], end_)) faces_.pop_back();
    }

    /// A run of faces [first, last] to be replaced by `faces`.
    struct Replacement {
        std::size_t first, last;
        std::vector<int> faces;
    };

    // Makes the replacements (disjoint, in decreasing order of position), then reduces again.
    void replace(const std::vector<Replacement>& replacements) {
        std::vector<int> old;
        old.swap(faces_);
        std::size_t i = 0;
        for (auto r = replacements.rbegin(); r != replacements.rend(); ++r) {
            for (; i < r->first; ++i) append(old[i]);
            for (const int f : r->faces) append(f);
            i = r->last + 1;
        }
        for (; i < old.size(); ++i) append(old[i]);
    }

    const std::vector<int>& faces() const { return faces_; }
    int start() const { return start_; }
    int end() const { return end_; }

private:
    const Mesh& mesh_;
    int start_, end_;
    std::vector<int> faces_;
};

// An edge between two consecutive faces of the sleeve, as seen going along it, laid out in the plane; the first
// and last portals are the path's ends, on both sides.
struct Portal {
    int left, right;
    Vector2d left_xy, right_xy;
};

std::vector<Portal> unfold(const Mesh& mesh, const Sleeve& sleeve) {
    const std::vector<int>& faces = sleeve.faces();
    std::vector<Portal> portals;
    portals.reserve(faces.size() + 2);
    // Corners of the current face in the plane, in the face's vertex order.
    std::array<Vector2d, 3> xy;
    const int h0 = 3 * faces[0];
    xy[0] = Vector2d(0.0, 0.0);
    xy[1] = Vector2d(mesh.length(h0), 0.0);
    xy[2] = mesh.apex(h0);
    auto corner_xy = [&](int f, int v) { return xy[std::size_t(leaving(mesh, f, v) % 3)]; };
    portals.push_back({sleeve.start(), sleeve.start(), corner_xy(faces[0], sleeve.start()),
                       corner_xy(faces[0], sleeve.start())});
    for (std::size_t i = 1; i < faces.size(); ++i) {
        int h = -1;
        for (int k = 0; k < 3; ++k) {
            const int twin = mesh.twin(3 * faces[i - 1] + k);
            if (twin >= 0 && Mesh::face_of(twin) == faces[i]) h = 3 * faces[i - 1] + k;
        }
        if (h < 0) throw NumericalError("straighten_path: consecutive sleeve faces share no edge");
        // Crossing h from its left (the face behind) to its right: its head is on the left of the way ahead.
        const Vector2d a = xy[std::size_t(Mesh::next(h) % 3)];
        const Vector2d b = xy[std::size_t(h % 3)];
        portals.push_back({mesh.head(h), mesh.tail(h), a, b});
        const int g = mesh.twin(h);  // from head(h) to tail(h), in the face ahead
        const Vector2d along = b - a;
        const Vector2d across(-along.y(), along.x());
        const Vector2d apex = mesh.apex(g) / mesh.length(g);
        xy[std::size_t(g % 3)] = a;
        xy[std::size_t(Mesh::next(g) % 3)] = b;
        xy[std::size_t(Mesh::prev(g) % 3)] = a + apex.x() * along + apex.y() * across;
    }
    portals.push_back({sleeve.end(), sleeve.end(), corner_xy(faces.back(), sleeve.end()),
                       corner_xy(faces.back(), sleeve.end())});
    return portals;
}

// Where the shortest path through the portals bends: its ends and the portal endpoints that it wraps around.
struct Bend {
    int vertex;
    std::size_t portal;
    Vector2d xy;
};

// The same corner of the unfolded sleeve. A vertex that the sleeve passes twice has two places in the plane; within
// one pass its place is copied from face to face, so equal places mean the same pass.
bool same_place(int vertex, const Vector2d& xy, const Bend& bend) { return vertex == bend.vertex && xy == bend.xy; }

// The funnel algorithm: the shortest path from the first portal to the last that crosses every portal in order.
std::vector<Bend> funnel(const std::vector<Portal>& portals) {
    std::vector<Bend> bends{{portals[0].left, 0, portals[0].left_xy}};
    Bend apex = bends[0], left = apex, right = apex;
    // The funnel side `side` becomes the apex; returns the portal to go on after. A side still at the apex (a portal
    // through the apex's vertex) only moves the apex along, without a new bend.
    auto wrap_around = [&](const Bend& side) {
        if (!same_place(side.vertex, side.xy, apex)) bends.push_back(side);
        apex = side;
        left = right = apex;
        return apex.portal;
    };
    for (std::size_t i = 1; i < portals.size(); ++i) {
        const Portal& p = portals[i];
        if (orient(apex.xy, right.xy, p.right_xy) >= 0.0) {  // narrows the funnel on the right
            if (same_place(right.vertex, right.xy, apex) || orient(apex.xy, left.xy, p.right_xy) < 0.0) {
                right = {p.right, i, p.right_xy};
            } else {  // crosses the left side: the path wraps around the left one
                i = wrap_around(left);
                continue;
            }
        }
        if (orient(apex.xy, left.xy, p.left_xy) <= 0.0) {  // narrows the funnel on the left
            if (same_place(left.vertex, left.xy, apex) || orient(apex.xy, right.xy, p.left_xy) > 0.0) {
                left = {p.left, i, p.left_xy};
            } else {  // crosses the right side
                i = wrap_around(right);
                continue;
            }
        }
    }
    const Portal& last = portals.back();
    if (bends.back().portal != portals.size() - 1)  // the end can become the apex on the last portal
        bends.push_back({last.left, portals.size() - 1, last.left_xy});
    return bends;
}

// The faces of the sleeve around a bend's vertex: [first, last], with the bend's portal between two of them.
std::pair<std::size_t, std::size_t> run_around(const Mesh& mesh, const std::vector<int>& faces, const Bend& bend) {
    std::size_t a = bend.portal - 1, b = bend.portal;
    while (a > 0 && face_has(mesh, faces[a - 1], bend.vertex)) --a;
    while (b + 1 < faces.size() && face_has(mesh, faces[b + 1], bend.vertex)) ++b;
    return {a, b};
}

// The other corner of face f at v than the one across the edge that f shares with `inner`, laid out with the face.
int outer_neighbour(const Mesh& mesh, int f, int v, int inner) {
    const int h = leaving(mesh, f, v);
    const int twin = mesh.twin(Mesh::prev(h));
    return (twin >= 0 && Mesh::face_of(twin) == inner) ? mesh.head(h) : mesh.tail(Mesh::prev(h));
}

// Whether the sleeve turns counter-clockwise around v from face fa to the next face, fa_next.
bool turns_ccw(const Mesh& mesh, int fa, int fa_next, int v) {
    const int twin = mesh.twin(Mesh::prev(leaving(mesh, fa, v)));
    return twin >= 0 && Mesh::face_of(twin) == fa_next;
}

// The faces around v from fa to the first fb (both included), turning counter-clockwise or clockwise; nothing when
// a boundary is in the way.
std::optional<std::vector<int>> fan_between(const Mesh& mesh, int fa, int fb, int v, bool ccw) {
    std::vector<int> run{fa};
    int h = leaving(mesh, fa, v);
    while (Mesh::face_of(h) != fb) {
        if (ccw) {
            h = mesh.twin(Mesh::prev(h));
        } else {
            if (mesh.twin(h) < 0) return std::nullopt;
            h = Mesh::next(mesh.twin(h));
        }
        if (h < 0 || run.size() > std::size_t(mesh.num_faces())) return std::nullopt;
        run.push_back(Mesh::face_of(h));
    }
    return run;
}

struct Layout {
    std::vector<Portal> portals;
    std::vector<Bend> bends;
};

// Where a bend needs a move that cannot be made.
struct Stuck {
    int pinned = -1;    // a pinned vertex
    int boundary = -1;  // a boundary vertex, or one whose faces around do not close
};

// Moves the sleeve to the far side of every vertex where that side is shorter; where runs of faces around two
// bends overlap, only the later one moves. Returns the moves made, and in `stuck` the bends that need one that
// cannot be made.
int move_bends(const Mesh& mesh, Sleeve& sleeve, const Layout& layout, const std::vector<unsigned char>& pinned,
               Stuck& stuck) {
    const std::vector<int>& faces = sleeve.faces();
    std::vector<Sleeve::Replacement> replacements;
    std::size_t limit = faces.size();  // runs must end before this (below the last one moved)
    for (std::size_t k = layout.bends.size() - 1; k-- > 1;) {
        const Bend& bend = layout.bends[k];
        const auto [a, b] = run_around(mesh, faces, bend);
        const int w = bend.vertex;
        // The angle on the sleeve's side: the run's corners at w, less what lies outside the two segments.
        const Vector2d to_prev = layout.bends[k - 1].xy - bend.xy;
        const Vector2d to_next = layout.bends[k + 1].xy - bend.xy;
        auto outer_direction = [&](std::size_t i, std::size_t inner) {
            const int o = outer_neighbour(mesh, faces[i], w, faces[inner]);
            const std::vector<Portal>& p = layout.portals;
            // Face i's corners are portal endpoints of the portal before or after it.
            for (const std::size_t j : {i, i + 1})
                if (j < p.size()) {
                    if (p[j].left == o) return Vector2d(p[j].left_xy - bend.xy);
                    if (p[j].right == o) return Vector2d(p[j].right_xy - bend.xy);
                }
            throw NumericalError("straighten_path: a face of the sleeve lost its layout");
        };
        double sleeve_side = 0.0;
        for (std::size_t i = a; i <= b; ++i) sleeve_side += mesh.corner_angle(leaving(mesh, faces[i], w));
        sleeve_side -= angle_between(outer_direction(a, a + 1), to_prev);
        sleeve_side -= angle_between(outer_direction(b, b - 1), to_next);
        if (mesh.cone_angle(w) - sleeve_side >= k_pi - k_angle_slack) continue;
        if (pinned[std::size_t(w)]) {
            stuck.pinned = w;
            continue;
        }
        if (mesh.is_boundary_vertex(w)) {
            stuck.boundary = w;
            continue;
        }
        if (b >= limit) continue;
        // A run that turns more than once around w (its faces again) unwinds; any other goes round the other way.
        const bool ccw = turns_ccw(mesh, faces[a], faces[a + 1], w);
        auto run = fan_between(mesh, faces[a], faces[b], w, ccw);
        if (run && run->size() >= b - a + 1) run = fan_between(mesh, faces[a], faces[b], w, !ccw);
        if (!run) {
            stuck.boundary = w;
            continue;
        }
        replacements.push_back({a, b, std::move(*run)});
        limit = a;
    }
    sleeve.replace(replacements);
    sleeve.trim_ends();
    return int(replacements.size());
}

// The polyline of the straight segments between the bends, with a point where each crosses a portal.
std::vector<SurfacePoint> polyline(const Mesh& mesh, const Layout& layout) {
    std::vector<SurfacePoint> path;
    auto add = [&](const SurfacePoint& p) {
        const SurfacePoint c = mesh.canonical(p);
        if (path.empty() || path.back() != c) path.push_back(c);
    };
    for (std::size_t k = 0; k + 1 < layout.bends.size(); ++k) {
        const Bend& from = layout.bends[k];
        const Bend& to = layout.bends[k + 1];
        add(SurfacePoint::at_vertex(from.vertex));
        for (std::size_t i = from.portal + 1; i < to.portal; ++i) {
            const Portal& p = layout.portals[i];
            if (same_place(p.left, p.left_xy, from) || same_place(p.right, p.right_xy, from) ||
                same_place(p.left, p.left_xy, to) || same_place(p.right, p.right_xy, to))
                continue;  // the segment meets this portal at its end
            const double r = orient(from.xy, to.xy, p.right_xy);
            const double l = orient(from.xy, to.xy, p.left_xy);
            const double t = (r - l) != 0.0 ? std::clamp(r / (r - l), 0.0, 1.0) : 0.5;
            add(SurfacePoint::on_edge(p.right, p.left, t));
        }
    }
    add(SurfacePoint::at_vertex(layout.bends.back().vertex));
    return path;
}

}  // namespace

StraightenResult straighten_path(const Mesh& mesh, const std::vector<int>& vertices,
                                 const std::vector<unsigned char>& pinned) {
    if (pinned.size() != std::size_t(mesh.num_vertices()))
        throw InvalidInput("straighten_path: " + std::to_string(pinned.size()) + " pinned flags for " +
                           std::to_string(mesh.num_vertices()) + " vertices");
    std::vector<int> path;
    for (const int v : vertices) {
        if (v < 0 || v >= mesh.num_vertices())
            throw InvalidInput("straighten_path: vertex " + std::to_string(v) + " is out of range");
        append_reduced(path, v);
    }
    if (path.size() < 2 || path.front() == path.back())
        throw InvalidInput("straighten_path: the path needs two different ends");
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
        if (mesh.find_halfedge(path[i], path[i + 1]) < 0 && mesh.find_halfedge(path[i + 1], path[i]) < 0)
            throw InvalidInput("straighten_path: vertices " + std::to_string(path[i]) + " and " +
                               std::to_string(path[i + 1]) + " share no edge");

    StraightenResult result;
    if (path.size() == 2) {  // one edge is straight
        result.path = {SurfacePoint::at_vertex(path[0]), SurfacePoint::at_vertex(path[1])};
        result.length = path_length(mesh, result.path);
        return result;
    }

    // The first sleeve: around each inner vertex, the fan on the side of the smaller angle.
    Sleeve sleeve(mesh, path.front(), path.back());
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
        const int v = path[i];
        if (pinned[std::size_t(v)])
            throw InvalidInput("straighten_path: inner vertex " + std::to_string(v) + " is pinned");
        if (!mesh.is_manifold_vertex(v))
            throw InvalidInput("straighten_path: inner vertex " + std::to_string(v) + " is not manifold");
        std::optional<std::vector<int>> ccw = ccw_fan(mesh, v, path[i - 1], path[i + 1]);
        std::optional<std::vector<int>> cw = ccw_fan(mesh, v, path[i + 1], path[i - 1]);
        if (cw) std::reverse(cw->begin(), cw->end());
        if (!ccw && !cw)
            throw InvalidInput("straighten_path: the path cannot pass boundary vertex " + std::to_string(v));
        const bool take_ccw = ccw && (!cw || corner_sum(mesh, *ccw, v) <= corner_sum(mesh, *cw, v));
        for (const int f : take_ccw ? *ccw : *cw) sleeve.append(f);
    }
    sleeve.trim_ends();

    Layout layout;
    double length = std::numeric_limits<double>::infinity();
    for (int idle = 0;;) {
        layout.portals = unfold(mesh, sleeve);
        layout.bends = funnel(layout.portals);
        double now = 0.0;
        for (std::size_t k = 0; k + 1 < layout.bends.size(); ++k)
            now += (layout.bends[k + 1].xy - layout.bends[k].xy).norm();
        idle = now < length ? 0 : idle + 1;
        if (idle == k_max_idle_passes) throw NumericalError("straighten_path: the sleeve did not settle");
        length = std::min(length, now);
        Stuck stuck;
        const int moves = move_bends(mesh, sleeve, layout, pinned, stuck);
        result.moves += moves;
        if (moves > 0) continue;
        if (stuck.pinned >= 0) {
            result.status = StraightenStatus::through_pinned_vertex;
            result.vertex = stuck.pinned;
        } else if (stuck.boundary >= 0) {
            result.status = StraightenStatus::bends_at_boundary;
            result.vertex = stuck.boundary;
        }
        break;
    }
    result.path = polyline(mesh, layout);
    for (std::size_t i = 1; i + 1 < result.path.size(); ++i) {
        const SurfacePoint& p = result.path[i];
        if (p.kind == PointKind::vertex && pinned[std::size_t(p.vertex)]) {
            result.status = StraightenStatus::through_pinned_vertex;
            result.vertex = p.vertex;
            break;
        }
    }
    result.length = path_length(mesh, result.path);
    return result;
}

}  // namespace geotri::geodesic

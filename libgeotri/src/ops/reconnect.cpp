#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/flip.h>
#include <geotri/overlay.h>
#include <geotri/reconnect.h>
#include <geotri/tangent_angles.h>
#include <geotri/validate.h>

#include "check/local_checks.h"
#include "core/parallel_propagations.h"
#include "core/patch_region.h"
#include "core/polygon_triangulation.h"
#include "ops/with_workspace.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace geotri {

using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

namespace {

constexpr double k_none = -std::numeric_limits<double>::infinity();

/// The polygon around a set of coarse faces: its corners counter-clockwise (the faces on the left of its sides),
/// with side i running from corner i to corner i+1.
struct Polygon {
    std::vector<VertexHandle> corners;
    std::vector<HalfedgeHandle> sides;
    std::vector<VertexHandle> inside;  ///< the vertices of the faces that are not corners
};

/// The polygon around `faces`, or why they do not make a disk bounded by one simple polygon.
std::string find_polygon(const CoarseMesh& coarse, const std::set<FaceHandle>& faces, Polygon& polygon) {
    std::map<VertexHandle, HalfedgeHandle> side_from;  // boundary halfedge by its start
    std::set<VertexHandle> vertices;
    std::set<EdgeHandle> edges;
    for (FaceHandle f : faces)
        for (HalfedgeHandle h : coarse.fh_range(f)) {
            vertices.insert(coarse.from_vertex_handle(h));
            edges.insert(coarse.edge_handle(h));
            const FaceHandle other = coarse.opposite_face_handle(h);
            if (other.is_valid() && faces.count(other)) continue;
            if (!side_from.emplace(coarse.from_vertex_handle(h), h).second)
                return "coarse vertex " + std::to_string(coarse.from_vertex_handle(h).idx()) +
                       " is twice a corner of the polygon";
        }
    if (side_from.empty()) return "the faces have no boundary (they are a whole component)";
    // Connected through their edges (a closed component of genus one beside a disk would pass the test below).
    std::set<FaceHandle> reached{*faces.begin()};
    std::vector<FaceHandle> stack{*faces.begin()};
    while (!stack.empty()) {
        const FaceHandle f = stack.back();
        stack.pop_back();
        for (FaceHandle n : coarse.ff_range(f))
            if (faces.count(n) && reached.insert(n).second) stack.push_back(n);
    }
    if (reached.size() != faces.size()) return "the faces are not connected through their edges";
    if (static_cast<long>(vertices.size()) - static_cast<long>(edges.size()) + static_cast<long>(faces.size()) != 1)
        return "the faces do not make a topological disk";
    HalfedgeHandle h = side_from.begin()->second;  // the corner of lowest index first: deterministic
    do {
        polygon.corners.push_back(coarse.from_vertex_handle(h));
        polygon.sides.push_back(h);
        const auto next = side_from.find(coarse.to_vertex_handle(h));
        if (next == side_from.end()) return "the polygon around the faces is not closed";
        h = next->second;
    } while (h != polygon.sides.front() && polygon.sides.size() <= side_from.size());
    if (polygon.sides.size() != side_from.size()) return "the faces are bounded by more than one polygon";
    for (VertexHandle v : vertices)
        if (!side_from.count(v)) polygon.inside.push_back(v);
    return {};
}

/// A candidate diagonal: its geodesic, when usable.
struct Diagonal {
    Polyline path;
    bool usable = false;
};

class Reconnection {
public:
    Reconnection(const GeodesicTriangulation& g, const Polygon& polygon, const std::set<FaceHandle>& faces)
        : g_(g), polygon_(polygon), faces_(faces), k_(polygon.corners.size()), position_(k_ * k_, k_none),
          diagonals_(k_ * k_) {}

    /// Fills the angular positions of the sides and of every usable diagonal at each corner. Each diagonal is the
    /// shortest geodesic on T when that one stays inside the polygon (it leaves and reaches its ends inside the
    /// polygon's corners and meets no side), else, with `region_fallback`, the shortest path inside the faces'
    /// patches (cut out of `overlay`, or of T alone when it is null). Empty, or why not.
    std::string measure(geodesic::ExactGeodesic& propagation, int threads, PropagationPool* pool,
                        bool region_fallback, const Overlay* overlay) {
        const CoarseMesh& coarse = g_.coarse();
        // At corner i, positions count counter-clockwise from side i (to corner i+1) up to the reversed side i-1
        // (to corner i-1): the polygon's inner angle there.
        from_.resize(k_);
        for (std::size_t i = 0; i < k_; ++i) {
            const std::size_t before = (i + k_ - 1) % k_;
            from_[i] = detail::start_direction(g_, polygon_.sides[i]);
            const double to = detail::start_direction(g_, coarse.opposite_halfedge_handle(polygon_.sides[before]));
            position(i, (i + 1) % k_) = 0.0;
            position(i, before) = ccw_angle(from_[i], to, cone(i));
        }
        // One propagation per corner, to the corners after it, in parallel: each writes only its own diagonals.
        std::vector<std::vector<std::size_t>> leaving(k_);  // per corner: the ends of its diagonals that leave
        detail::for_each_with_propagation(
            g_.fine().mesh, k_, threads,
            [&](std::size_t i, geodesic::ExactGeodesic& mine) { leaving[i] = measure_from(i, mine); }, &propagation,
            pool);
        std::vector<std::pair<std::size_t, std::size_t>> outside;  // diagonals whose shortest geodesic leaves
        for (std::size_t i = 0; i < k_; ++i)
            for (std::size_t j : leaving[i]) outside.emplace_back(i, j);
        if (outside.empty() || !region_fallback) return {};
        std::vector<int> patches;
        for (FaceHandle f : faces_) patches.push_back(f.idx());
        std::optional<PatchRegion> region;
        try {
            if (overlay) region.emplace(g_, *overlay, patches);
            else region.emplace(g_, patches);
        } catch (const InvalidInput& e) {
            return e.what();
        }
        for (std::size_t n = 0; n < outside.size();) {  // one propagation per corner
            const std::size_t i = outside[n].first;
            std::vector<std::size_t> ends;
            std::vector<SurfacePoint> targets;
            for (; n < outside.size() && outside[n].first == i; ++n) {
                ends.push_back(outside[n].second);
                targets.push_back(g_.location(polygon_.corners[outside[n].second]));
            }
            const std::vector<PatchRegion::Path> paths =
                region->shortest_paths(g_.location(polygon_.corners[i]), targets);
            for (std::size_t m = 0; m < ends.size(); ++m) use(i, ends[m], paths[m].polyline, false);
        }
        return {};
    }

    /// The shortest geodesics from corner i to the corners after it that a diagonal may join; returns the ends of
    /// those that leave the polygon.
    std::vector<std::size_t> measure_from(std::size_t i, geodesic::ExactGeodesic& propagation) {
        const CoarseMesh& coarse = g_.coarse();
        std::vector<std::size_t> ends, leaving;
        geodesic::PropagationOptions options;
        for (std::size_t j = i + 2; j < k_; ++j) {
            if (i == 0 && j == k_ - 1) continue;  // a side
            const HalfedgeHandle existing = coarse.find_halfedge(polygon_.corners[i], polygon_.corners[j]);
            if (existing.is_valid() && !interior(coarse.edge_handle(existing))) continue;  // would double an edge
            ends.push_back(j);
            options.stop_points.push_back(g_.location(polygon_.corners[j]));
        }
        if (ends.empty()) return leaving;
        options.goal_directed = true;
        propagation.propagate({g_.location(polygon_.corners[i])}, options);
        for (std::size_t j : ends)
            if (!use(i, j, propagation.shortest_path(g_.location(polygon_.corners[j])), true)) leaving.push_back(j);
        return leaving;
    }

    /// Whether the chosen diagonals meet nowhere but at shared ends; empty, or where two of them meet.
    std::string chosen_diagonals_meet() const {
        std::vector<std::pair<std::size_t, std::size_t>> chosen;
        for (const std::array<std::size_t, 3>& t : triangles())
            for (std::size_t n = 0; n < 3; ++n) {
                const std::size_t i = std::min(t[n], t[(n + 1) % 3]), j = std::max(t[n], t[(n + 1) % 3]);
                if (!is_side(i, j) && std::find(chosen.begin(), chosen.end(), std::make_pair(i, j)) == chosen.end())
                    chosen.emplace_back(i, j);
            }
        for (std::size_t x = 0; x < chosen.size(); ++x)
            for (std::size_t y = x + 1; y < chosen.size(); ++y) {
                const auto [i, j] = chosen[x];
                const auto [p, q] = chosen[y];
                Polyline other = diagonal(p, q).path;  // from p to q
                int tag = -1;
                if (p == j || q == j) tag = 1;
                if (p == i || q == i) tag = 0;
                if ((tag == 0 && q == i) || (tag == 1 && q == j)) std::reverse(other.begin(), other.end());
                const std::string meeting =
                    detail::first_meeting(g_.fine().mesh, diagonal(i, j).path, {{other, tag, "a diagonal"}});
                if (!meeting.empty()) return meeting;
            }
        return {};
    }

    /// The triangulation that maximises the smallest corner (dynamic programming over the sub-polygons i..j);
    /// returns that corner, k_none when there is none with every corner above detail::k_min_new_corner.
    double best_triangulation() {
        const double best = detail::best_polygon_triangulation(
            k_, [this](std::size_t i, std::size_t m, std::size_t j) { return smallest_corner(i, m, j); }, apex_);
        return best > detail::k_min_new_corner ? best : k_none;
    }

    /// The triangles of the best triangulation as corner indices (i, m, j), each after the two it rests on, so
    /// that adding them in this order fills the polygon from its sides inwards.
    std::vector<std::array<std::size_t, 3>> triangles() const {
        std::vector<std::array<std::size_t, 3>> out;
        std::function<void(std::size_t, std::size_t)> add = [&](std::size_t i, std::size_t j) {
            if (j < i + 2) return;
            const std::size_t m = apex_[i * k_ + j];
            add(i, m);
            add(m, j);
            out.push_back({i, m, j});
        };
        add(0, k_ - 1);
        return out;
    }

    const Diagonal& diagonal(std::size_t i, std::size_t j) const { return diagonals_[std::min(i, j) * k_ + std::max(i, j)]; }
    bool is_side(std::size_t i, std::size_t j) const { return j == i + 1 || i == j + 1 || (std::min(i, j) == 0 && std::max(i, j) == k_ - 1); }

private:
    /// Records `path` (from corner i to corner j) as the diagonal i-j when it is straight and leaves and reaches
    /// its ends strictly inside the polygon's corners, and, when `check_sides`, meets no side of the polygon but at
    /// its ends (a path inside the patches cannot). Returns whether it did.
    bool use(std::size_t i, std::size_t j, const Polyline& path, bool check_sides) {
        const geodesic::Mesh& mesh = g_.fine().mesh;
        if (path.size() < 2 || !detail::straightness_defect(mesh, path).empty()) return false;
        const double at_i = ccw_angle(from_[i], polar_angle(mesh, path[0], path[1]), cone(i));
        const double at_j = ccw_angle(from_[j], polar_angle(mesh, path.back(), path[path.size() - 2]), cone(j));
        if (!strictly_inside(i, at_i) || !strictly_inside(j, at_j)) return false;
        if (check_sides) {
            std::vector<detail::BoundingPath> sides;
            for (std::size_t s = 0; s < k_; ++s) {
                const std::size_t t = (s + 1) % k_;
                Polyline side = g_.path(polygon_.sides[s]);  // from corner s to corner t
                int tag = -1;
                if (s == i || t == i) tag = 0;
                if (s == j || t == j) tag = 1;
                if ((tag == 0 && t == i) || (tag == 1 && t == j)) std::reverse(side.begin(), side.end());
                sides.push_back({std::move(side), tag, "a side"});
            }
            if (!detail::first_meeting(mesh, path, sides).empty()) return false;
        }
        position(i, j) = at_i;
        position(j, i) = at_j;
        diagonals_[i * k_ + j] = {path, true};
        return true;
    }

    double cone(std::size_t i) const { return cone_angle(g_.fine().mesh, g_.location(polygon_.corners[i])); }
    double& position(std::size_t i, std::size_t j) { return position_[i * k_ + j]; }
    bool strictly_inside(std::size_t i, double at) const {
        return at > detail::k_min_new_corner && at < position_[i * k_ + (i + k_ - 1) % k_] - detail::k_min_new_corner;
    }
    bool interior(EdgeHandle e) const {
        const CoarseMesh& coarse = g_.coarse();
        const FaceHandle f0 = coarse.face_handle(coarse.halfedge_handle(e, 0));
        const FaceHandle f1 = coarse.face_handle(coarse.halfedge_handle(e, 1));
        return f0.is_valid() && f1.is_valid() && faces_.count(f0) && faces_.count(f1);
    }
    bool joined(std::size_t i, std::size_t j) const { return is_side(i, j) || diagonal(i, j).usable; }

    /// The smallest corner of triangle (i, m, j), i < m < j; k_none when an edge of it is not usable.
    double smallest_corner(std::size_t i, std::size_t m, std::size_t j) const {
        if (!joined(i, m) || !joined(m, j) || !joined(i, j)) return k_none;
        // The corner at a between its edges to b and then c (counter-clockwise) is the difference of positions.
        auto corner = [this](std::size_t a, std::size_t b, std::size_t c) {
            return position_[a * k_ + c] - position_[a * k_ + b];
        };
        return std::min({corner(i, m, j), corner(m, j, i), corner(j, i, m)});
    }

    const GeodesicTriangulation& g_;
    const Polygon& polygon_;
    const std::set<FaceHandle>& faces_;
    std::size_t k_;
    std::vector<double> from_;      ///< per corner: the polar angle of its side to the next corner
    std::vector<double> position_;  ///< k×k: polar position at corner i of the edge to corner j; k_none if unusable
    std::vector<Diagonal> diagonals_;  ///< k×k, at [min·k + max]
    std::vector<std::size_t> apex_;  ///< of the best triangulation (detail::best_polygon_triangulation())
};

double smallest_corner_of(const GeodesicTriangulation& g, const std::set<FaceHandle>& faces) {
    double smallest = std::numeric_limits<double>::infinity();
    for (FaceHandle f : faces)
        for (double a : corner_angles(g, f)) smallest = std::min(smallest, a);
    return smallest;
}

}  // namespace

ReconnectResult reconnect_polygon(GeodesicTriangulation& g, const std::vector<FaceHandle>& face_list,
                                  const ReconnectOptions& options) {
    return reconnect_polygon(g, face_list, options, Workspace{});
}

ReconnectResult reconnect_polygon(GeodesicTriangulation& g, const std::vector<FaceHandle>& face_list,
                                  const ReconnectOptions& options, const Workspace& workspace) {
    CoarseMesh& coarse = g.coarse();
    std::set<FaceHandle> faces;
    for (FaceHandle f : face_list) {
        if (!f.is_valid() || static_cast<std::size_t>(f.idx()) >= coarse.n_faces() || coarse.status(f).deleted())
            throw InvalidInput("reconnect_polygon: not a face of the coarse mesh");
        faces.insert(f);
    }
    ReconnectResult result;
    auto refuse = [&result](const std::string& why) {
        result.reason = "reconnecting the polygon: " + why;
        return result;
    };
    if (faces.empty()) return refuse("no faces");
    Polygon polygon;
    if (const std::string why = find_polygon(coarse, faces, polygon); !why.empty()) return refuse(why);
    result.corners = static_cast<int>(polygon.corners.size());
    if (result.corners > options.max_corners)
        return refuse("it has " + std::to_string(result.corners) + " corners, more than " +
                      std::to_string(options.max_corners));
    result.min_corner_before = smallest_corner_of(g, faces);

    std::unique_ptr<geodesic::ExactGeodesic> own;
    geodesic::ExactGeodesic* propagation = workspace.propagation;
    if (!propagation) {
        own = std::make_unique<geodesic::ExactGeodesic>(g.fine().mesh);
        propagation = own.get();
    }
    Reconnection reconnection(g, polygon, faces);
    if (const std::string why = reconnection.measure(*propagation, options.threads, workspace.propagations,
                                                        options.region_fallback, workspace.overlay);
        !why.empty())
        return refuse(why);
    const double best = reconnection.best_triangulation();
    if (best == k_none) return refuse("no triangulation of it with geodesic diagonals has positive corners");
    result.min_corner_after = best;
    if (options.required_gain >= 0.0 && best <= result.min_corner_before + options.required_gain)
        return refuse("no triangulation of it raises the smallest corner");
    if (const std::string meeting = reconnection.chosen_diagonals_meet(); !meeting.empty())
        return refuse("two of its best diagonals meet: " + meeting);

    GeodesicTriangulation before = g;  // restored when refused from here on
    auto restore = [&](const std::string& why) {
        g = std::move(before);
        result.corners_after.clear();
        return refuse(why);
    };
    for (FaceHandle f : faces) coarse.delete_face(f, true);  // inside vertices and edges go with their last face
    for (const std::array<std::size_t, 3>& t : reconnection.triangles()) {
        const FaceHandle f = coarse.add_face(polygon.corners[t[0]], polygon.corners[t[1]], polygon.corners[t[2]]);
        if (!f.is_valid()) return restore("the coarse mesh refused a new triangle");
        for (std::size_t n = 0; n < 3; ++n) {
            const std::size_t i = t[n], j = t[(n + 1) % 3];
            if (reconnection.is_side(i, j)) continue;
            const HalfedgeHandle h = coarse.find_halfedge(polygon.corners[std::min(i, j)], polygon.corners[std::max(i, j)]);
            if (g.polyline(coarse.edge_handle(h)).empty()) {
                g.set_path(h, reconnection.diagonal(i, j).path);
                ++result.diagonals;
            }
        }
    }
    for (VertexHandle v : polygon.corners)
        if (coarse.valence(v) < 3)
            return restore("coarse vertex " + std::to_string(v.idx()) + " would have fewer than three edges");
    result.removed_vertices = static_cast<int>(polygon.inside.size());
    result.corners_after = polygon.corners;
    std::vector<VertexHandle*> vertex_handles;
    for (VertexHandle& v : result.corners_after) vertex_handles.push_back(&v);
    std::vector<HalfedgeHandle*> no_halfedges;
    std::vector<FaceHandle*> no_faces;
    coarse.garbage_collection(vertex_handles, no_halfedges, no_faces);
    if (options.check_validity) {
        const ValidationReport report = validate(g);
        if (!report.valid) return restore("the result is not valid (" + report.violations.front().what + ")");
    }
    result.done = true;
    return result;
}

ReconnectResult reconnect_vertex(GeodesicTriangulation& g, VertexHandle v, const ReconnectOptions& options) {
    return reconnect_vertex(g, v, options, Workspace{});
}

ReconnectResult reconnect_vertex(GeodesicTriangulation& g, VertexHandle v, const ReconnectOptions& options,
                                 const Workspace& workspace) {
    const CoarseMesh& coarse = g.coarse();
    if (!v.is_valid() || static_cast<std::size_t>(v.idx()) >= coarse.n_vertices() || coarse.status(v).deleted())
        throw InvalidInput("reconnect_vertex: not a vertex of the coarse mesh");
    std::vector<FaceHandle> faces;
    for (FaceHandle f : coarse.vf_range(v)) faces.push_back(f);
    return reconnect_polygon(g, faces, options, workspace);
}

}  // namespace geotri

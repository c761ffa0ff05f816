#include <geodesic/constants.h>
#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/flip.h>
#include <geotri/reconnect.h>
#include <geotri/refine.h>
#include <geotri/relocate.h>
#include <geotri/split.h>
#include <geotri/straight_geodesic.h>
#include <geotri/tangent_angles.h>

#include "check/local_checks.h"
#include "core/parallel_propagations.h"
#include "core/patch_location.h"
#include "core/path_cache.h"
#include "core/plane_segments.h"
#include "core/polygon_triangulation.h"
#include "core/propagation_pool.h"
#include "core/thread_count.h"
#include "core/triangle_layout.h"
#include "ops/with_workspace.h"
#include "pipeline/flip_to_delaunay_detail.h"
#include "pipeline/refine_tactics.h"
#include "pipeline/speculative_attempts.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <queue>
#include <set>

namespace geotri {

using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

namespace {

using geodesic::k_pi;
constexpr double k_max_min_angle_deg = 35.0;
// A vertex of T whose cone angle differs from 2π by more than this fraction of the minimum angle counts as curved:
// refinement puts a coarse vertex on it when a circumcircle holds it. Triangles around it cannot be flat, and
// circumcentres laid out as if they were chase it with ever smaller triangles. Gently curved vertices (scanned
// surfaces have them everywhere) are left alone: snapping to them would itself make short edges.
constexpr double k_curved_fraction = 1.0 / 3.0;
// Where refinement gives up on some triangles without reaching its vertex cap, it starts again from the G given with
// every vertex of T that is curved by more than this fraction of the minimum angle counted as curved: nearly every
// vertex that is not flat, as in intrinsic Delaunay refinement, where all vertices of T are vertices of the
// triangulation and its triangles are flat inside. Near curved vertices, that is what reaches the angle where the
// first attempt gives up (armadillo_cgal, brain_conte69 and triceratops at 25 degrees, horse at 30). As the only
// strategy (with a ten-thousandth or a tenth of the angle) it reached 30 degrees on fewer meshes, with more faces.
constexpr double k_second_curved_fraction = 1e-3;
// A corner above this (radians) belongs to a patch that wraps around a bump of T (its corners sum to far more than
// π): no use for an element. Once the minimum angle is reached, refinement cuts such corners in two.
constexpr double k_max_corner = k_pi;
// Where the default vertex cap is reached with fewer than this fraction of the faces below the minimum angle,
// refinement is nearly done rather than cascading, and it gets a second budget as large: at 30 degrees footbones
// then reaches the angle, and horse, triceratops and brain_mni end with 2-8 corners left instead of 42-137
// (armadillo at 25 degrees: 5 instead of 80); the scans that cascade reach the cap with 10-15% of their faces
// below it, and stop there.
constexpr double k_nearly_done = 0.05;
// A vertex is moved (Refiner::move_a_vertex_of) only where that raises the smallest corner around it by more than
// this (radians): moves that gain less cost a propagation each for nearly nothing.
constexpr double k_min_move_gain = 1e-3;
// Where vertex moves leave at most this many corners below the angle, refinement also tries without them (refine());
// with at most this many faces below it, refinement is in its end game (Refiner::split_at_saddle()).
constexpr int k_few_corners_left = 4;
// At most this many moves per vertex that the cap lets refinement add: each move raises the smallest corner of the
// faces it changes, but positions are not finitely many, so that alone does not bound them.
constexpr int k_moves_per_new_vertex = 2;
// A circumcentre farther than this times the triangle's longest edge is not inserted.
constexpr double k_max_radius_ratio = 4.0;
// How many fine faces the search for a curved vertex near a circumcentre may look at.
constexpr std::size_t k_max_search_faces = 2000;
// Below this many faces of T, the flips and reconnections after each split run on one thread: geotri-refine at 25
// degrees on two threads took femur_cgal (7.8k faces) 3.2 -> 3.6 s, and sped up from about 20k faces
// (lucy_100k 4.2 -> 3.4 s, turbineblade 3.4 -> 2.6 s).
constexpr int k_min_faces_for_threads = 20000;
// Below this many faces of T, the geodesics of the flips are not kept for flips evaluated again (Refiner::paths_).
constexpr int k_min_faces_for_path_cache = 20000;
// The shortest edge that refinement refines and makes, unless the caller gives one: this fraction of T's mean edge.
constexpr double k_min_edge_fraction = 0.1;
// Near an edge of the G given shorter than that (a small feature of the input), the shortest edge there grows with
// the distance from it, at this rate (Refiner::min_edge_of()). With a rate of 1, on gears (whose G has an edge of a
// thousandth of T's mean edge, at a spike of T) faces with corners of 16-24 degrees were left too small to refine
// near it: at 25 degrees 13 corners were left (16.7 degrees), at 30 degrees 6 (27.1). With a quarter, 1 (23.2
// degrees, in a face whose corners sum to 93: a geodesic of it bends at a saddle of T), and at 30 degrees none. The
// results swing with the rate (at 25 and 30 degrees: a tenth 1 and 3 corners left, 13.1 degrees; a half 1 and 2,
// 27.1; three quarters 1 and 9, 25.3); no other G of the 320-face sweep changes with it.
constexpr double k_feature_grading = 0.25;
// The shortest edge of the attempts that refine() makes where the others give up, as a fraction of T's mean edge.
constexpr double k_finer_min_edge_fraction = 0.05;
// The curved fraction (k_curved_fraction) of the last attempts that refine() makes, where a few corners are left.
constexpr double k_finer_curved_fraction = 1.0 / 6.0;

/// The mean length of T's edges.
double mean_edge_length(const geodesic::Mesh& mesh) {
    double sum = 0.0;
    for (int h = 0; h < mesh.num_halfedges(); ++h) sum += mesh.length(h);
    return sum / mesh.num_halfedges();
}

std::array<HalfedgeHandle, 3> halfedges_of(const CoarseMesh& coarse, FaceHandle f) {
    const HalfedgeHandle h0 = coarse.halfedge_handle(f), h1 = coarse.next_halfedge_handle(h0);
    return {h0, h1, coarse.next_halfedge_handle(h1)};
}

std::array<int, 3> vertices_of(const CoarseMesh& coarse, FaceHandle f) {
    const auto h = halfedges_of(coarse, f);
    return {coarse.from_vertex_handle(h[0]).idx(), coarse.from_vertex_handle(h[1]).idx(),
            coarse.from_vertex_handle(h[2]).idx()};
}

/// The edges opposite v in its star: those that a new vertex's flips start from.
std::vector<EdgeHandle> link_edges(const CoarseMesh& coarse, VertexHandle v) {
    std::vector<EdgeHandle> edges;
    for (HalfedgeHandle h : coarse.voh_range(v))
        if (!coarse.is_boundary(h)) edges.push_back(coarse.edge_handle(coarse.next_halfedge_handle(h)));
    return edges;
}

/// Whether the segment between corners p and q of the planar polygon `points` (counter-clockwise) runs inside it:
/// it meets no other corner and no side, and its midpoint is inside.
bool inside_diagonal(const std::vector<Eigen::Vector2d>& points, std::size_t p, std::size_t q) {
    const std::size_t k = points.size();
    const Eigen::Vector2d a = points[p], b = points[q];
    for (std::size_t r = 0; r < k; ++r) {
        const std::size_t s = (r + 1) % k;
        if (r != p && r != q) {
            const double t = (points[r] - a).dot(b - a) / (b - a).squaredNorm();
            if (t > 0.0 && t < 1.0 && std::abs(detail::cross(b - a, points[r] - a)) <= 1e-12 * (b - a).squaredNorm())
                return false;
        }
        if (r == p || r == q || s == p || s == q) continue;
        const Eigen::Vector2d c = points[r], d = points[s];
        if (detail::cross(b - a, c - a) * detail::cross(b - a, d - a) < 0.0 &&
            detail::cross(d - c, a - c) * detail::cross(d - c, b - c) < 0.0)
            return false;
    }
    const Eigen::Vector2d mid = 0.5 * (a + b);
    bool inside = false;
    for (std::size_t r = 0; r < k; ++r) {
        const Eigen::Vector2d c = points[r], d = points[(r + 1) % k];
        if ((c.y() > mid.y()) != (d.y() > mid.y()) &&
            mid.x() < c.x() + (mid.y() - c.y()) / (d.y() - c.y()) * (d.x() - c.x()))
            inside = !inside;
    }
    return inside;
}

/// An estimate, without a single geodesic, of the smallest corner that reconnect_vertex(v) can reach: v's star
/// laid out in the plane around v (its edges' lengths, its corners at v scaled to sum to 2π), and that polygon
/// triangulated by straight diagonals as well as possible (the dynamic programming of reconnect_polygon()). Exact
/// for a flat star. Refinement skips the removals whose estimate is below the minimum angle: each would cost a
/// propagation per corner of the star, and few of them reach it (measured on ten meshes at 25 and 30 degrees, a
/// slack of 1 or 3 degrees let more through for the same results).
double planar_removal_estimate(const GeodesicTriangulation& g, VertexHandle v) {
    const CoarseMesh& coarse = g.coarse();
    std::vector<double> lengths, corners;
    double total = 0.0;
    for (HalfedgeHandle h : coarse.voh_ccw_range(v)) {
        lengths.push_back(g.length(coarse.edge_handle(h)));
        corners.push_back(corner_angle(g, h));
        total += corners.back();
    }
    const std::size_t k = lengths.size();
    std::vector<Eigen::Vector2d> points;
    double direction = 0.0;
    for (std::size_t i = 0; i < k; ++i) {
        points.emplace_back(lengths[i] * std::cos(direction), lengths[i] * std::sin(direction));
        direction += corners[i] * 2.0 * k_pi / total;
    }
    auto angle = [&](std::size_t at, std::size_t p, std::size_t q) {  // counter-clockwise; negative when reflex
        const Eigen::Vector2d a = points[p] - points[at], b = points[q] - points[at];
        return std::atan2(detail::cross(a, b), a.dot(b));
    };
    auto usable = [&](std::size_t i, std::size_t j) {
        return j == i + 1 || (i == 0 && j == k - 1) || inside_diagonal(points, i, j);
    };
    std::vector<std::size_t> apex;
    return detail::best_polygon_triangulation(
        k,
        [&](std::size_t i, std::size_t m, std::size_t j) {
            if (!usable(i, m) || !usable(m, j) || !usable(i, j)) return -std::numeric_limits<double>::infinity();
            return std::min({angle(i, m, j), angle(m, j, i), angle(j, i, m)});
        },
        apex);
}

/// A move onto a saddle (Refiner::move_a_vertex_of()) must leave every corner that it changes at least this many
/// times the minimum angle. Measured at 30 degrees at 320 faces: with no such floor, the smallest corner left on
/// femur_cgal, gears and skull_thing74168 fell (21.8 -> 9.7, 12.6 -> 9.4, 17.8 -> 13.6 degrees); with the whole
/// angle as the floor, lucy_100k and man were left with 292 and 60 corners below it (4 and 15 with half of it).
constexpr double k_saddle_move_floor = 0.5;

/// Corners at points of T whose cone angle is below this many times the minimum angle are exempt: a vertex of
/// degree three or more there must have a smaller corner.
constexpr double k_exempt_cone_factor = 3.0;

/// G's smallest corner at a point of T whose cone angle is at least `exempt_below` (0: every corner), or infinity.
double smallest_corner_of(const GeodesicTriangulation& g, double exempt_below = 0.0) {
    double smallest = std::numeric_limits<double>::infinity();
    for (FaceHandle f : g.coarse().faces())
        for (HalfedgeHandle h : halfedges_of(g.coarse(), f))
            if (exempt_below <= 0.0 ||
                cone_angle(g.fine().mesh, g.location(g.coarse().from_vertex_handle(h))) >= exempt_below)
                smallest = std::min(smallest, corner_angle(g, h));
    return smallest;
}

/// Whether refinement result `a` (G `ga`) is better than `b` (G `gb`): fewer corners left below the angle, or as
/// many and a larger smallest corner at a point of T whose cone angle is at least `exempt_below`.
bool better_result(const RefineResult& a, const GeodesicTriangulation& ga, const RefineResult& b,
                   const GeodesicTriangulation& gb, double exempt_below) {
    return a.small_corners_left < b.small_corners_left ||
           (a.small_corners_left == b.small_corners_left &&
            smallest_corner_of(ga, exempt_below) > smallest_corner_of(gb, exempt_below));
}

/// Storage for trial copies of G, kept between trials.
struct TrialSlot {
    std::optional<GeodesicTriangulation> g;
    long copy_of = -1;  ///< the Refiner::g_version_ of the G that `g` still equals, or -1
};

class Refiner {
public:
    /// `curved_fraction`: a vertex of T whose cone angle differs from 2π by more than this fraction of the minimum
    /// angle counts as curved.
    /// `stop_if_cancelled`, when given, is called after every step, and may throw to end refinement there.
    Refiner(GeodesicTriangulation& g, const RefineOptions& options, const detail::RefineTactics& tactics,
            RefineResult& result, double curved_fraction, std::function<void()> stop_if_cancelled = {})
        : g_(g), options_(options), tactics_(tactics), result_(result), propagation_(g.fine().mesh),
          pool_(g.fine().mesh),
          stop_if_cancelled_(std::move(stop_if_cancelled)) {
        const geodesic::Mesh& mesh = g.fine().mesh;
        min_edge_ = options.min_edge_length > 0.0 ? options.min_edge_length
                                                   : k_min_edge_fraction * mean_edge_length(mesh);
        // Bisection stops by itself (every split halves an edge); only an explicit cap bounds it.
        budget_ = options.max_new_vertices > 0 ? options.max_new_vertices : std::numeric_limits<int>::max();
        min_angle_ = options.min_angle_deg * k_pi / 180.0;
        curved_ = curved_fraction * min_angle_;
        // The flips after a split evaluate a handful of edges, in parallel with the pool's objects (a team whose
        // threads made their own at every call took as much wall time as one thread); on a small T their
        // propagations are too short for a team to pay. Without the region fallback: with it (cheap since the
        // patches are cut out alone), triceratops reaches 25 degrees, but lucy_100k, man and armadillo end lower
        // (5.0 -> 0.3, 4.3 -> 0.9, 7.2 -> 5.5 degrees).
        flip_options_.threads = mesh.num_faces() < k_min_faces_for_threads ? 1 : options.threads;
        flip_options_.region_fallback = false;
        flip_workspace_.propagation = &propagation_;
        flip_workspace_.propagations = &pool_;
        // Refinement evaluates flips on the same pairs of vertices again and again (a third of them on lucy_100k
        // at 25 degrees): their geodesics are kept, on a T large enough for a propagation to cost more than keeping
        // its path (lucy_100k at 25 degrees 7.1 -> 6.2 s; femur_cgal, 7.8k faces, at 30 degrees 3.4 -> 3.7 s).
        if (mesh.num_faces() >= k_min_faces_for_path_cache) flip_workspace_.paths = &paths_;
        for (VertexHandle v : g.coarse().vertices()) {
            if (g.location(v).kind == geodesic::PointKind::vertex) coarse_at_fine_vertex_.insert(g.location(v).vertex);
            given_.push_back(g.location(v));
            input_.push_back(g.location(v));
        }
        for (EdgeHandle e : g.coarse().edges())
            if (g.length(e) < min_edge_) {
                const HalfedgeHandle h = g.coarse().halfedge_handle(e, 0);
                short_given_edges_.push_back({{mesh.point(g.location(g.coarse().from_vertex_handle(h))),
                                               mesh.point(g.location(g.coarse().to_vertex_handle(h)))},
                                              g.length(e)});
            }
    }

    void bisect() {
        // The longest edge not refused, the lowest index among equally long ones (what a pass over G found at every
        // split, which made bisecting to 20000 faces quadratic): a heap of (length, edge), where an entry whose
        // length is no longer its edge's is stale, and a split gives the edges that it and its flips changed new
        // ones (split_edges_).
        struct Entry {
            double length;
            int edge;
            bool operator<(const Entry& other) const {
                return length < other.length || (length == other.length && edge > other.edge);
            }
        };
        std::priority_queue<Entry> longest_first;
        for (EdgeHandle e : g_.coarse().edges()) longest_first.push({g_.length(e), e.idx()});
        std::vector<char> refused;  // per edge (splits add edges, and keep the others' indices)
        while (!cap_reached()) {
            const CoarseMesh& coarse = g_.coarse();
            refused.resize(coarse.n_edges(), 0);
            auto stale = [&](const Entry& x) {
                const EdgeHandle e(x.edge);
                return refused[static_cast<std::size_t>(x.edge)] || coarse.status(e).deleted() ||
                       g_.length(e) != x.length;
            };
            while (!longest_first.empty() && stale(longest_first.top())) longest_first.pop();
            if (longest_first.empty()) break;
            const EdgeHandle longest(longest_first.top().edge);
            const bool too_long = options_.max_length > 0.0 && g_.length(longest) > options_.max_length;
            const bool too_few = options_.target_faces > 0 && static_cast<int>(coarse.n_faces()) < options_.target_faces;
            if (!too_long && !too_few) break;
            if (!split_edge_somewhere(longest, min_edge_)) refused[static_cast<std::size_t>(longest.idx())] = 1;
            else
                for (EdgeHandle e : split_edges_) longest_first.push({g_.length(e), e.idx()});
            progress("bisection");
        }
    }

    void raise_min_angle() {
        if (!(min_angle_ > 0.0)) return;
        new_vertices_ = 0;
        budget_ = options_.max_new_vertices > 0 ? options_.max_new_vertices
                                                : 4 * static_cast<int>(g_.coarse().n_faces()) + 100;
        // Raising the minimum angle must never lower it: no split may make a corner below the smallest one now.
        keep_above_ = smallest_corner_of(g_);
        std::set<std::array<int, 3>> given_up;
        FacesByCorner faces(*this);
        bool extended = options_.max_new_vertices > 0;  // a cap that the caller gave is never extended
        bool all_removable = false;
        const MoveGoal saddle_move{false, k_saddle_move_floor * min_angle_, true};
        while (true) {
            const CoarseMesh& coarse = g_.coarse();
            faces.update();
            auto not_given_up = [&](int f) { return !given_up.count(vertices_of(coarse, FaceHandle(f))); };
            const FaceHandle worst = faces.first_below(not_given_up), widest = faces.first_wide(not_given_up);
            // Nearly done at the default cap (k_nearly_done): once more as many.
            if (!extended && new_vertices_ >= budget_ &&
                static_cast<double>(faces.count_below(not_given_up)) <
                    k_nearly_done * static_cast<double>(coarse.n_faces())) {
                extended = true;
                budget_ *= 2;
            }
            if (cap_reached()) break;
            if (!worst.is_valid() && !widest.is_valid()) {
                // A face below the angle with an edge shorter than refinement refines (min_edge_of(), often an edge
                // that a flip made) was left as it was: gears and skull_thing74168 at 25 degrees had 28 of 36 and 30
                // of 32 such faces left. Once nothing else is left to mend, each gets a removal or a vertex move,
                // which make no triangle: skull_thing74168 then reaches the angle (from 6.1 degrees), as cheese does.
                if (const FaceHandle tiny = faces.first_tiny(not_given_up); tiny.is_valid()) {
                    if (remove_a_vertex_of(tiny)) {
                        given_up.clear();  // the coarse mesh was renumbered
                        continue;
                    }
                    if (!(tactics_.move_vertices && may_move() && move_a_vertex_of(tiny, &given_up, MoveGoal{})))
                        given_up.insert(vertices_of(coarse, tiny));
                    progress("small triangles");
                    continue;
                }
                // A vertex that refinement inserted can stand in the way of a face given up, where only a removal
                // mends it (boxpart at 30 degrees): once, the vertices inserted so far become removable too, and
                // the faces given up are tried again.
                // Then, once, the faces given up are tried again with splits inside their patches or their
                // neighbours' (split_inside_or_around()).
                if (given_up.empty() || inside_splits_) break;
                if (all_removable) {
                    inside_splits_ = tactics_.split_inside;
                    if (!inside_splits_) break;
                    given_up.clear();
                    continue;
                }
                all_removable = true;
                given_.clear();
                for (VertexHandle v : coarse.vertices()) given_.push_back(g_.location(v));
                given_up.clear();
                continue;
            }
            if (!worst.is_valid()) {
                // No triangle is left below the angle but those given up: then the corners above k_max_corner.
                if (!mend_wide_corners(widest, min_angle_, &given_up)) given_up.insert(vertices_of(coarse, widest));
                progress("corners above 180 degrees");
                continue;
            }
            // A removal comes first: where decimation left two vertices close together, circumcentres would
            // cascade into ever smaller triangles between them.
            if (remove_a_vertex_of(worst)) {
                given_up.clear();  // the coarse mesh was renumbered
                continue;
            }
            if (tactics_.move_vertices && may_move() && move_a_vertex_of(worst, &given_up, MoveGoal{})) continue;
            // Where neither a circumcentre nor a split mends the worst triangle, one of its vertices may move onto
            // a saddle of T that its geodesics bend at, before the triangle is given up.
            // In the end game (at most k_few_corners_left faces below the angle, or the last resort's pass) the
            // triangle may be split at a saddle of T that its geodesics bend at, or at a curved vertex of T in its
            // circumcircle (split_at_saddle()).
            if (!refine_face(worst) &&
                !(tactics_.move_vertices && may_move() && move_a_vertex_of(worst, &given_up, saddle_move)) &&
                !((faces.size_below() <= k_few_corners_left || inside_splits_) && split_at_saddle(worst)))
                given_up.insert(vertices_of(coarse, worst));
            progress("angle refinement");
        }
        mend_wide_corners_left();
    }

    /// Counts the corners left below the minimum angle (exempt ones, and the others) and above k_max_corner.
    void count_corners_left() {
        if (!(min_angle_ > 0.0)) return;
        for (FaceHandle f : g_.coarse().faces())
            for (HalfedgeHandle h : halfedges_of(g_.coarse(), f)) {
                const double corner = corner_angle(g_, h);
                result_.wide_corners_left += corner > k_max_corner;
                if (corner >= min_angle_) continue;
                if (exempt(g_.coarse().from_vertex_handle(h))) ++result_.exempt_corners;
                else ++result_.small_corners_left;
            }
    }

private:
    bool cap_reached() {
        if (new_vertices_ < budget_) return false;
        result_.vertex_cap_reached = true;
        return true;
    }

    /// Every loop of refinement comes here once per step.
    void progress(const char* stage) {
        if (stop_if_cancelled_) stop_if_cancelled_();
        if (options_.progress && new_vertices_ % 50 == 0)
            options_.progress(std::string(stage) + ": " + std::to_string(g_.coarse().n_faces()) + " faces");
    }

    bool exempt(VertexHandle v) const {
        return cone_angle(g_.fine().mesh, g_.location(v)) < k_exempt_cone_factor * min_angle_;
    }

    /// f's smallest corner that is not exempt (or infinity) and its largest corner, in one pass over its corners;
    /// infinity and 0 for a face too small to refine.
    struct CornerRange {
        double smallest = std::numeric_limits<double>::infinity();
        double largest = 0.0;
        double tiny_smallest = std::numeric_limits<double>::infinity();  ///< the smallest, for a face too small
    };
    CornerRange corner_range(FaceHandle f) const {
        CornerRange range;
        double shortest = std::numeric_limits<double>::infinity();
        for (HalfedgeHandle h : halfedges_of(g_.coarse(), f)) {
            shortest = std::min(shortest, g_.length(g_.coarse().edge_handle(h)));
            const double corner = corner_angle(g_, h);
            if (!exempt(g_.coarse().from_vertex_handle(h))) range.smallest = std::min(range.smallest, corner);
            range.largest = std::max(range.largest, corner);
        }
        if (shortest < min_edge_of(f)) {
            CornerRange tiny;
            tiny.tiny_smallest = range.smallest;
            return tiny;
        }
        return range;
    }

    /// The smallest corner of f that is not exempt, or infinity; infinity too for a face too small to refine.
    double smallest_corner(FaceHandle f) const { return corner_range(f).smallest; }

    /// The faces below the minimum angle by their smallest corner that is not exempt, and those with a corner above
    /// k_max_corner by their largest, each then by index: the worst and the widest, which raise_min_angle() takes
    /// next, found without measuring every face of G at every step (which made refinement quadratic in G's size).
    /// Kept up to date from the faces that the steps change (Refiner::changed_faces_).
    class FacesByCorner {
    public:
        explicit FacesByCorner(Refiner& refiner) : refiner_(refiner) { refiner_.renumbered_ = true; }

        /// Takes in the changes since the last call.
        void update() {
            if (refiner_.renumbered_) {
                below_.clear();
                wide_.clear();
                tiny_.clear();
                ranges_.assign(refiner_.g_.coarse().n_faces(), CornerRange{});
                for (FaceHandle f : refiner_.g_.coarse().faces()) measure(f.idx());
            } else {
                for (int f : refiner_.changed_faces_) measure(f);
            }
            refiner_.renumbered_ = false;
            refiner_.changed_faces_.clear();
        }

        /// The first face below the angle for which `take(face index)` holds, or an invalid handle.
        template <class Take>
        FaceHandle first_below(Take take) const { return first_in(below_, take); }
        /// The first face with a corner above k_max_corner for which `take(face index)` holds, or an invalid handle.
        template <class Take>
        FaceHandle first_wide(Take take) const { return first_in(wide_, take); }
        /// The first face below the angle but too small to refine (corner_range()) for which `take` holds.
        template <class Take>
        FaceHandle first_tiny(Take take) const { return first_in(tiny_, take); }
        /// How many faces are below the angle (not counting those too small to refine).
        std::size_t size_below() const { return below_.size(); }
        template <class Take>
        std::size_t count_below(Take take) const {
            return static_cast<std::size_t>(
                std::count_if(below_.begin(), below_.end(), [&](const auto& entry) { return take(entry.second); }));
        }

    private:
        template <class Take>
        static FaceHandle first_in(const std::set<std::pair<double, int>>& faces, Take take) {
            for (const auto& [corner, f] : faces)
                if (take(f)) return FaceHandle(f);
            return FaceHandle();
        }

        void measure(int f) {
            const std::size_t i = static_cast<std::size_t>(f);
            if (i >= ranges_.size()) ranges_.resize(i + 1);
            below_.erase({ranges_[i].smallest, f});
            wide_.erase({-ranges_[i].largest, f});
            tiny_.erase({ranges_[i].tiny_smallest, f});
            ranges_[i] = refiner_.corner_range(FaceHandle(f));
            if (ranges_[i].smallest < refiner_.min_angle_) below_.emplace(ranges_[i].smallest, f);
            if (ranges_[i].tiny_smallest < refiner_.min_angle_) tiny_.emplace(ranges_[i].tiny_smallest, f);
            if (ranges_[i].largest > k_max_corner) wide_.emplace(-ranges_[i].largest, f);
        }

        Refiner& refiner_;
        std::vector<CornerRange> ranges_;       ///< per face, as last measured
        std::set<std::pair<double, int>> below_;  ///< (smallest corner, face)
        std::set<std::pair<double, int>> wide_;   ///< (minus the largest corner, face)
        std::set<std::pair<double, int>> tiny_;   ///< (smallest corner, face) of those too small to refine
    };

    /// Cuts f's corners above k_max_corner in two: splits the edge opposite each, the widest first, else inserts f's
    /// circumcentre, else splits f well inside its patch (split_inside(), from the widest corner first: a patch that
    /// wraps around a bump of T often holds no circumcentre, and the geodesics from the far edge leave it); only
    /// where every corner that changes is at least `bar` (and the smallest corner when refinement began). Before the
    /// vertex cap, the bar is the minimum angle, so that mending them never makes work for the minimum angle nor
    /// lowers it (with half of it as the bar for the new vertex's corners, triceratops ended at 7.4 degrees instead
    /// of 11.0). The splits inside took the corners above 180 degrees left on the 320-face sweep at 30 degrees from
    /// 40 to 25 (man 5 -> 0, lucy_100k 6 -> 2, footbones 2 -> 0), with the same angles; tried only in the last
    /// resort's pass (split_inside_or_around()), they left 26.
    bool mend_wide_corners(FaceHandle f, double bar, std::set<std::array<int, 3>>* given_up = nullptr) {
        std::vector<std::pair<double, HalfedgeHandle>> wide;
        for (HalfedgeHandle h : halfedges_of(g_.coarse(), f)) {
            const double corner = corner_angle(g_, h);
            if (corner > k_max_corner) wide.emplace_back(corner, h);
        }
        std::sort(wide.begin(), wide.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
        const double floor = std::max(keep_above_, bar), min_length = min_edge_of(f);
        for (const auto& corner : wide) {
            const EdgeHandle opposite = g_.coarse().edge_handle(g_.coarse().next_halfedge_handle(corner.second));
            for (double fraction : {0.5, 0.4, 0.6}) {
                auto split = [&](GeodesicTriangulation& trial) {
                    return split_edge(trial, opposite, fraction, split_options(true), propagation_only(propagation_));
                };
                if (try_split(split, floor, min_length, result_.edge_splits, floor) == Tried::kept) return true;
            }
        }
        const std::optional<Centre> centre = circumcentre(f);
        if (centre && insert_in_one_of(centre_patches(f, *centre), centre->point, floor, min_length, floor))
            return true;
        if (tactics_.split_inside && split_inside(f, floor, min_length)) {
            ++result_.inside_splits;
            return true;
        }
        // Else a vertex of f moved, where that narrows the widest corner of the faces it changes and keeps their
        // corners at least the floor (or what they were): the moves that raise the minimum angle may open such
        // corners, and the splits above then be refused (the lumbar spine at 25 degrees).
        return tactics_.move_vertices && may_move() && move_a_vertex_of(f, given_up, MoveGoal{true, floor});
    }

    /// Where refinement stops with triangles below the minimum angle (at the vertex cap, or given up), the corners
    /// above k_max_corner that wait for the angle are cut at last, each face tried once, with the bar lowered to the
    /// face's own smallest corner, so that no triangle comes out worse than the one it cuts (gears, lucy_100k, man
    /// and skull_thing74168 at 25 degrees: 56 such corners left -> 32). Without the cap, faces whose corners are all
    /// at least the angle were tried already, with the same bar. A cap that the caller gave is kept to the letter.
    void mend_wide_corners_left() {
        const bool capped = new_vertices_ >= budget_;
        if (!(min_angle_ > 0.0) || (capped && options_.max_new_vertices > 0)) return;
        auto candidate = [&](const CornerRange& range) {
            return range.largest > k_max_corner && (capped || range.smallest < min_angle_);
        };
        int wide = 0;
        for (FaceHandle f : g_.coarse().faces()) wide += candidate(corner_range(f));
        std::set<std::array<int, 3>> tried;
        // Cutting a corner can widen another through the flips that follow: a bound on the tries, not only the set.
        for (int tries = 0; tries < 2 * wide; ++tries) {
            if (options_.max_new_vertices > 0 && cap_reached()) return;
            FaceHandle widest;
            CornerRange widest_range;
            for (FaceHandle f : g_.coarse().faces()) {
                const CornerRange range = corner_range(f);
                if (candidate(range) && range.largest > widest_range.largest &&
                    !tried.count(vertices_of(g_.coarse(), f))) {
                    widest = f;
                    widest_range = range;
                }
            }
            if (!widest.is_valid()) return;
            tried.insert(vertices_of(g_.coarse(), widest));
            mend_wide_corners(widest, std::min(min_angle_, widest_range.smallest));
            progress("corners above 180 degrees left");
        }
    }

    /// The shortest edge that refinement refines in f and makes there: min_edge_, or less near an edge of the G given
    /// that is shorter, the length of that edge plus k_feature_grading times f's distance to it (as a local feature
    /// size grows away from a feature). Such an edge joins two input vertices that are close together (two corners
    /// of a small chamfer of a CAD part): a feature of the input, whose triangles refinement must mend at its scale
    /// (skipping them left corners of 11 degrees on cad/joint.off), with triangles that grow away from it.
    double min_edge_of(FaceHandle f) const {
        double min_length = min_edge_;
        for (const ShortEdge& edge : short_given_edges_)
            for (VertexHandle v : g_.coarse().fv_range(f)) {
                const Eigen::Vector3d x = g_.fine().mesh.point(g_.location(v));
                const double distance = std::min((x - edge.ends[0]).norm(), (x - edge.ends[1]).norm());
                min_length = std::min(min_length, edge.length + k_feature_grading * distance);
            }
        return min_length;
    }

    static SplitOptions split_options(bool region_fallback) {
        SplitOptions options;
        options.region_fallback = region_fallback;
        return options;
    }

    /// A copy of G to try an operation on, in the storage of `slot` where it has some: copying G into new storage
    /// for every split and move tried was a third of refinement on a G of thousands of faces (cheese at 25
    /// degrees: PropertyT::clone(), malloc() and free()). Not copied at all where the slot still holds this G
    /// (untouched(), replace_g()). The slot counts as changed from here on.
    GeodesicTriangulation& trial_copy(TrialSlot& slot) const {
        if (!slot.g) slot.g.emplace(g_);
        else if (slot.copy_of != g_version_) *slot.g = g_;
        slot.copy_of = -1;
        return *slot.g;
    }
    /// The operation tried on the slot's copy refused before it changed anything: the copy is still G.
    void untouched(TrialSlot& slot) const { slot.copy_of = g_version_; }

    /// G becomes `next`, a changed copy whose faces that differ from G's are `changed` (indices), or, where `next`
    /// was renumbered (a removal collects its garbage), any of them. Copied into G's storage (the coarse mesh stays
    /// the same object), and `next` keeps its own for another trial: `from`, its slot where it has one, then holds
    /// this G.
    void replace_g(const GeodesicTriangulation& next, const std::vector<int>* changed, TrialSlot* from = nullptr) {
        g_ = next;
        ++g_version_;
        if (from) from->copy_of = g_version_;
        if (!changed) renumbered_ = true;
        else if (!renumbered_) changed_faces_.insert(changed_faces_.end(), changed->begin(), changed->end());
    }

    /// Does `split` (one of split_edge() or split_face() on the G it is given) on a copy of G, then the flips around
    /// the new vertex, and keeps the result when the corners of the faces at the new vertex are no smaller than
    /// `floor` (radians) and its edges no shorter than `min_length`, the shortest edge that refinement still
    /// refines there (min_edge_of()), and every corner that the split and its flips change is no smaller than
    /// keep_above_ and `changed_floor`. A split that makes a worse corner than the one it mends is what lets
    /// refinement chase its own tail; one that puts the new vertex next to another makes triangles too small to
    /// mend. Says whether G changed, or else whether the split itself was refused or made and then refused.
    enum class Tried { kept, refused_split, refused_shape };
    template <class Split>
    Tried try_split(Split split, double floor, double min_length, int& counter, double changed_floor = 0.0) {
        GeodesicTriangulation& trial = trial_copy(split_trial_);
        const SplitResult done = split(trial);
        if (!done.done) {
            untouched(split_trial_);  // split_edge() and split_face() refuse before they change G
            ++result_.refused_splits;
            return Tried::refused_split;
        }
        FlipToDelaunayResult flips;
        std::vector<EdgeHandle> flipped;
        if (options_.flip)
            detail::improve_around(trial, link_edges(trial.coarse(), done.vertex), flip_options_, flip_workspace_, flips,
                                   &flipped);
        const std::vector<int> changed = changed_faces(trial, done.vertex, flipped);
        // The flips after the split can reach beyond the new vertex's faces: the smallest corner of all of G must
        // stay above keep_above_ too.
        double shortest_new = std::numeric_limits<double>::infinity();
        for (HalfedgeHandle h : trial.coarse().voh_range(done.vertex))
            shortest_new = std::min(shortest_new, trial.length(trial.coarse().edge_handle(h)));
        const double changed_bar = std::max(keep_above_, changed_floor);
        if (shortest_new < min_length || smallest_corner_around(trial, done.vertex) < floor ||
            (changed_bar > 0.0 && corners_in(trial, changed).smallest < changed_bar)) {
            ++result_.refused_splits;
            return Tried::refused_shape;
        }
        replace_g(trial, &changed, &split_trial_);
        split_vertex_ = done.vertex;
        split_edges_ = flipped;
        for (HalfedgeHandle h : g_.coarse().voh_range(done.vertex)) split_edges_.push_back(g_.coarse().edge_handle(h));
        ++counter;
        ++new_vertices_;
        result_.flips += flips.flips;
        return Tried::kept;
    }

    /// Whether face f of `trial` (a changed copy of G) is one that G does not have: its index is new or now holds
    /// other vertices. A face with the same vertices has the same edges (flips never double an edge), so the same
    /// corners; measuring only the others saves most of the corner angles on a large G.
    bool is_changed(const GeodesicTriangulation& trial, FaceHandle f) const {
        const CoarseMesh& before = g_.coarse();
        return static_cast<std::size_t>(f.idx()) >= before.n_faces() || before.status(f).deleted() ||
               vertices_of(before, f) != vertices_of(trial.coarse(), f);
    }

    /// The changed faces (is_changed()) of `trial`, G split at `vertex` and then flipped at `flipped`: only faces
    /// that meet the new vertex or a flipped edge can be (flips keep the handles of their edge's two faces), so
    /// they are found without a pass over G, whose cost grew with G at every step.
    std::vector<int> changed_faces(const GeodesicTriangulation& trial, VertexHandle vertex,
                                   const std::vector<EdgeHandle>& flipped) const {
        std::vector<int> faces = faces_at(trial, vertex, flipped);
        faces.erase(std::remove_if(faces.begin(), faces.end(),
                                   [&](int f) { return !is_changed(trial, FaceHandle(f)); }),
                    faces.end());
        return faces;
    }

    /// The faces of `trial` at `vertex` and at the edges of `flipped` (indices, sorted, each once).
    static std::vector<int> faces_at(const GeodesicTriangulation& trial, VertexHandle vertex,
                                     const std::vector<EdgeHandle>& flipped) {
        const CoarseMesh& coarse = trial.coarse();
        std::vector<int> faces;
        for (FaceHandle f : coarse.vf_range(vertex)) faces.push_back(f.idx());
        for (EdgeHandle e : flipped)
            for (int side = 0; side < 2; ++side) {
                const FaceHandle f = coarse.face_handle(coarse.halfedge_handle(e, side));
                if (f.is_valid()) faces.push_back(f.idx());
            }
        std::sort(faces.begin(), faces.end());
        faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
        return faces;
    }

    /// The smallest and the largest corner of `faces` (indices) in `trial`, exempt or not (infinity and 0 for none).
    static CornerRange corners_in(const GeodesicTriangulation& trial, const std::vector<int>& faces) {
        CornerRange range;
        for (int f : faces)
            for (HalfedgeHandle h : halfedges_of(trial.coarse(), FaceHandle(f))) {
                const double corner = corner_angle(trial, h);
                range.smallest = std::min(range.smallest, corner);
                range.largest = std::max(range.largest, corner);
            }
        return range;
    }

    /// The smallest corner of the changed faces of `trial`, found by a pass over all of it: for a removal, whose
    /// garbage collection renumbers G.
    double smallest_changed_corner(const GeodesicTriangulation& trial) const {
        std::vector<int> faces;
        for (FaceHandle f : trial.coarse().faces())
            if (is_changed(trial, f)) faces.push_back(f.idx());
        return corners_in(trial, faces).smallest;
    }

    static double smallest_corner_around(const GeodesicTriangulation& g, VertexHandle v) {
        double smallest = std::numeric_limits<double>::infinity();
        for (FaceHandle f : g.coarse().vf_range(v))
            for (HalfedgeHandle h : halfedges_of(g.coarse(), f)) smallest = std::min(smallest, corner_angle(g, h));
        return smallest;
    }

    /// Half the smallest corner of the faces at e: no edge split may make a corner below it (as longest-edge
    /// bisection guarantees).
    double floor_at(EdgeHandle e) const {
        double smallest = std::numeric_limits<double>::infinity();
        for (int side = 0; side < 2; ++side) {
            const FaceHandle f = g_.coarse().face_handle(g_.coarse().halfedge_handle(e, side));
            if (!f.is_valid()) continue;
            for (HalfedgeHandle h : halfedges_of(g_.coarse(), f)) smallest = std::min(smallest, corner_angle(g_, h));
        }
        return 0.5 * smallest;
    }

    /// Splits e at its midpoint (or, when that is refused, at 0.4 or 0.6 of it), making no edge shorter than
    /// `min_length`; false when every one is refused. `unsplit`, when given, gets the fractions where the split
    /// itself was refused.
    bool split_edge_somewhere(EdgeHandle e, double min_length, bool region_fallback = true,
                              std::vector<std::pair<EdgeHandle, double>>* unsplit = nullptr) {
        for (double fraction : {0.5, 0.4, 0.6}) {
            const Tried tried = split_edge_at(e, fraction, min_length, region_fallback);
            if (tried == Tried::kept) return true;
            if (tried == Tried::refused_split && unsplit) unsplit->emplace_back(e, fraction);
        }
        return false;
    }

    /// One try of split_edge_somewhere(): e split at `fraction`.
    Tried split_edge_at(EdgeHandle e, double fraction, double min_length, bool region_fallback) {
        auto split = [&](GeodesicTriangulation& trial) {
            return split_edge(trial, e, fraction, split_options(region_fallback), propagation_only(propagation_));
        };
        return try_split(split, std::max(floor_at(e), keep_above_), min_length, result_.edge_splits);
    }

    /// The circumcentre of f, found on T by walking straight from a corner of f in the direction that the
    /// triangle's intrinsic layout (its three geodesic lengths) gives, scaled to the corner's true angle.
    struct Centre {
        SurfacePoint point;
        double radius;
        HalfedgeHandle corner;    ///< the walk started at this halfedge's from-vertex, inside f's corner there
        double layout_direction;  ///< the walk's direction in f's intrinsic layout, from the corner's first side
    };
    std::optional<Centre> circumcentre(FaceHandle f) const {
        const CoarseMesh& coarse = g_.coarse();
        const auto h = halfedges_of(coarse, f);
        std::array<double, 3> length{};
        for (std::size_t i = 0; i < 3; ++i) length[i] = g_.length(coarse.edge_handle(h[i]));
        // From the corner where the circumcentre's direction lies deepest inside the corner.
        int best = -1;
        double best_margin = 0.0, best_direction = 0.0, best_radius = 0.0, best_phi = 0.0;
        for (std::size_t i = 0; i < 3; ++i) {
            const double ab = length[i], bc = length[(i + 1) % 3], ca = length[(i + 2) % 3];
            const double layout_angle = detail::opposite_angle(bc, ab, ca);
            const double cx = ca * std::cos(layout_angle), cy = ca * std::sin(layout_angle);
            if (!(cy > 0.0)) continue;
            const double ux = 0.5 * ab, uy = (ca * ca - ab * cx) / (2.0 * cy);
            const double phi = std::atan2(uy, ux);
            const double margin = std::min(phi, layout_angle - phi);
            if (margin > best_margin) {
                const double corner = corner_angle(g_, h[i]);
                best = static_cast<int>(i);
                best_margin = margin;
                best_direction = detail::start_direction(g_, h[i]) + phi * corner / layout_angle;
                best_radius = std::hypot(ux, uy);
                best_phi = phi;
            }
        }
        // A nearly flat triangle's circumcentre is far away and of no use: its longest edge is split instead.
        if (best < 0 || best_radius > k_max_radius_ratio * *std::max_element(length.begin(), length.end()))
            return std::nullopt;
        const SurfacePoint& start = g_.location(coarse.from_vertex_handle(h[static_cast<std::size_t>(best)]));
        const double theta = cone_angle(g_.fine().mesh, start);
        const StraightGeodesicResult walk =
            trace_straight_geodesic(g_.fine().mesh, start, std::fmod(best_direction, theta), best_radius);
        if (walk.stopped_at_boundary) return std::nullopt;
        return Centre{walk.end, best_radius, h[static_cast<std::size_t>(best)], best_phi};
    }

    /// Takes out a vertex of the G given at an end of f's shortest edge (of the two, the one whose removal gives
    /// the higher smallest corner), reconnecting its star, when after the flips around it every corner of the
    /// polygon's vertices is at least the minimum angle, above what it was, and G's smallest corner stays above
    /// keep_above_. Removals mend only; each removes a vertex of the G given, so there are finitely many.
    bool remove_a_vertex_of(FaceHandle f) {
        if (options_.keep_vertices) return false;
        const CoarseMesh& coarse = g_.coarse();
        HalfedgeHandle shortest;
        for (HalfedgeHandle h : halfedges_of(coarse, f))
            if (!shortest.is_valid() || g_.length(coarse.edge_handle(h)) < g_.length(coarse.edge_handle(shortest)))
                shortest = h;
        std::optional<GeodesicTriangulation> best;
        double best_corner = -1.0;
        int best_flips = 0;
        for (VertexHandle v : {coarse.from_vertex_handle(shortest), coarse.to_vertex_handle(shortest)}) {
            if (std::find(given_.begin(), given_.end(), g_.location(v)) == given_.end() || curved(v)) continue;
            // A star tried before without success, and not changed since, fails again.
            if (!failed_stars_.insert(star_key(v)).second) continue;
            if (planar_removal_estimate(g_, v) < min_angle_) continue;
            ReconnectOptions options;
            options.check_validity = false;  // the local checks keep a valid G valid
            options.required_gain = flip_options_.margin;
            // The pool's objects, as for the flips: a team whose other thread made its own propagation object over
            // T at every removal tried (a pass over the mesh) took as much wall time as one thread.
            Workspace workspace = propagation_only(propagation_);
            workspace.propagations = &pool_;
            options.threads = flip_options_.threads;
            options.region_fallback = false;
            GeodesicTriangulation trial = g_;
            const ReconnectResult done = reconnect_vertex(trial, v, options, workspace);
            if (!done.done) continue;
            FlipToDelaunayResult flips;
            if (options_.flip) {
                // The polygon's sides and diagonals: the edges whose faces changed.
                std::vector<EdgeHandle> edges;
                for (VertexHandle c : done.corners_after)
                    for (HalfedgeHandle h : trial.coarse().voh_range(c))
                        if (c < trial.coarse().to_vertex_handle(h) &&
                            std::find(done.corners_after.begin(), done.corners_after.end(),
                                      trial.coarse().to_vertex_handle(h)) != done.corners_after.end())
                            edges.push_back(trial.coarse().edge_handle(h));
                detail::improve_around(trial, edges, flip_options_, flip_workspace_, flips);
            }
            double smallest = std::numeric_limits<double>::infinity();
            for (VertexHandle c : done.corners_after) smallest = std::min(smallest, smallest_corner_around(trial, c));
            if (smallest <= done.min_corner_before || smallest < min_angle_ || smallest <= best_corner ||
                smallest_changed_corner(trial) < keep_above_)
                continue;
            best.emplace(std::move(trial));
            best_corner = smallest;
            best_flips = flips.flips;
        }
        if (!best) return false;
        replace_g(*best, nullptr);
        ++result_.removed_vertices;
        result_.flips += best_flips;
        return true;
    }

    /// What a move must do: raise the smallest corner of the faces it changes by more than k_min_move_gain, to
    /// at least `floor`, or, with `narrow`, lower their widest corner by as much, keeping their corners at least
    /// `floor` (or what they were). Either way no corner may fall below keep_above_. Exempt corners count too.
    struct MoveGoal {
        bool narrow = false;
        double floor = 0.0;
        bool onto_saddles = false;  ///< onto the saddles of T that f's geodesics bend at, not to star centroids
    };
    struct MoveCandidate {
        VertexHandle vertex;
        std::optional<SurfacePoint> target;  ///< where to move it; none: the centroid of its star
        std::vector<double> key;  ///< star_key() before the move, with the target
        TrialSlot* slot = nullptr;               ///< the storage of its trial copy of G
        GeodesicTriangulation* moved = nullptr;  ///< the trial, set where the move is one to keep
        std::vector<int> changed;  ///< the faces that the move and its flips changed
        double score = 0.0;        ///< the higher the better: their smallest corner after, or minus the widest
        int flips = 0;
        bool numerical_trouble = false;  ///< not cached as failed: it says nothing about the star
    };

    /// Moves a vertex of f to the centroid of its star (star_centroid()), or with goal.onto_saddles onto a saddle
    /// that a geodesic of f bends at (saddles_on_edges_of()), then flips around it: of f's candidates, the move
    /// that meets `goal` and raises the smallest corner of the faces that it and its flips change the most (or,
    /// to narrow, lowers their widest the most). On a bumpy T, circumcentres cascade into ever smaller
    /// triangles whose corners the bumps distort; moving a vertex mends a corner without making a triangle.
    /// Vertices at curved points of T stay, and so do those of the G given with RefineOptions::keep_vertices.
    /// Each move that raises the minimum angle raises the smallest corner of the faces it changes and leaves
    /// the others as they are. The candidates are tried in parallel (each with its flips on one thread; a lone one
    /// with its flips on all), and the choice does not depend on the thread count. The faces that the move changes
    /// leave `given_up` (when given).
    bool move_a_vertex_of(FaceHandle f, std::set<std::array<int, 3>>* given_up, const MoveGoal& goal) {
        std::vector<MoveCandidate> candidates;
        for (VertexHandle v : g_.coarse().fv_range(f)) {
            if (curved(v) || (options_.keep_vertices &&
                              std::find(input_.begin(), input_.end(), g_.location(v)) != input_.end()))
                continue;
            // A star whose move failed before, and that has not changed since, fails again.
            const std::vector<double> star = star_key(v);
            auto add = [&](const std::optional<SurfacePoint>& target) {
                std::vector<double> key = star;
                if (target) {
                    key.push_back(-1.0);  // no star key is one field longer than a multiple of a location's
                    append_key(key, *target);
                }
                if (goal.narrow || !failed_moves_.count(key))
                    candidates.push_back({v, target, std::move(key), nullptr, nullptr, {}, 0.0, 0, false});
            };
            if (!goal.onto_saddles) add(std::nullopt);
            else
                for (int saddle : saddles_on_edges_of(f, v)) add(SurfacePoint::at_vertex(saddle));
        }
        if (move_trials_.size() < candidates.size()) move_trials_.resize(candidates.size());
        for (std::size_t k = 0; k < candidates.size(); ++k) candidates[k].slot = &move_trials_[k];
        // A lone candidate would leave every thread but one idle: its flips then run on all of them instead.
        auto try_one = [&](std::size_t k, geodesic::ExactGeodesic& propagation) {
            try_move(candidates[k], propagation, goal);
        };
        if (candidates.size() == 1) try_move(candidates[0], propagation_, goal, true);
        else
            detail::for_each_with_propagation(g_.fine().mesh, candidates.size(), flip_options_.threads, try_one,
                                              &propagation_, &pool_);
        MoveCandidate* best = nullptr;
        for (MoveCandidate& c : candidates) {
            if (!c.moved && !goal.narrow && !c.numerical_trouble) failed_moves_.insert(c.key);
            else if (c.moved && (!best || c.score > best->score)) best = &c;
        }
        if (!best) return false;
        // The triangles given up that the move changed, or that had the moved vertex, are others now.
        if (given_up) {
            for (int x : best->changed) given_up->erase(vertices_of(best->moved->coarse(), FaceHandle(x)));
            const int moved = best->vertex.idx();
            for (auto it = given_up->begin(); it != given_up->end();)
                it = std::find(it->begin(), it->end(), moved) != it->end() ? given_up->erase(it) : std::next(it);
        }
        const SurfacePoint& from = g_.location(best->vertex);
        if (from.kind == geodesic::PointKind::vertex) coarse_at_fine_vertex_.erase(from.vertex);
        const SurfacePoint& to = best->moved->location(best->vertex);
        if (to.kind == geodesic::PointKind::vertex) coarse_at_fine_vertex_.insert(to.vertex);
        replace_g(*best->moved, &best->changed, best->slot);
        if (best->target) {
            ++result_.moves_onto_saddles;
            add_short_edges_at(best->vertex);
        }
        ++result_.moved_vertices;
        result_.flips += best->flips;
        return true;
    }

    bool may_move() const { return result_.moved_vertices / k_moves_per_new_vertex < budget_; }

    /// One move of move_a_vertex_of(), on a copy of G, with `propagation` for its geodesics and flips (`alone`:
    /// the flips on the threads of flip_options_, `propagation` being propagation_). A move only tries to do better:
    /// one that meets numerical trouble is not made.
    void try_move(MoveCandidate& c, geodesic::ExactGeodesic& propagation, const MoveGoal& goal,
                  bool alone = false) const {
        try {
            try_move_or_throw(c, propagation, goal, alone);
        } catch (const NumericalError&) {
            c.moved = nullptr;
            c.numerical_trouble = true;
        }
    }
    void try_move_or_throw(MoveCandidate& c, geodesic::ExactGeodesic& propagation, const MoveGoal& goal,
                           bool alone) const {
        const std::optional<SurfacePoint> target = c.target ? c.target : star_centroid(c.vertex);
        if (!target) return;
        GeodesicTriangulation& trial = trial_copy(*c.slot);
        if (!relocate_vertex_in_star(trial, c.vertex, *target, propagation_only(propagation)).done) {
            untouched(*c.slot);  // relocate_vertex_in_star() refuses before it changes G
            return;
        }
        const CoarseMesh& coarse = trial.coarse();
        FlipToDelaunayResult flips;
        std::vector<EdgeHandle> flipped;
        if (options_.flip) {
            std::vector<EdgeHandle> edges = link_edges(coarse, c.vertex);
            for (HalfedgeHandle h : coarse.voh_range(c.vertex)) edges.push_back(coarse.edge_handle(h));
            FlipToDelaunayOptions around = flip_options_;
            Workspace around_workspace = flip_workspace_;
            if (!alone) {  // one thread of a parallel loop over the candidates
                around.threads = 1;
                around_workspace.propagation = &propagation;
                around_workspace.propagations = nullptr;
            }
            detail::improve_around(trial, edges, around, around_workspace, flips, &flipped);
        }
        // Every face at the vertex changed (its corners did, though not its vertices), and those of the flipped
        // edges.
        std::vector<int> changed = faces_at(trial, c.vertex, flipped);
        const CornerRange after = corners_in(trial, changed), before = corners_in(g_, changed);
        if (after.smallest < keep_above_) return;
        if (goal.narrow) {
            if (!(after.largest < before.largest - k_min_move_gain) ||
                after.smallest < std::min(goal.floor, before.smallest))
                return;
            c.score = -after.largest;
        } else {
            if (!(after.smallest - before.smallest > k_min_move_gain) || after.smallest < goal.floor) return;
            c.score = after.smallest;
        }
        c.moved = &trial;
        c.changed = std::move(changed);
        c.flips = flips.flips;
    }

    /// Where smoothing moves v: the centroid of v's star laid out in the plane around v (its edges' lengths, its
    /// corners at v scaled to sum to 2π), found on T by walking straight from v; none when the layout folds over.
    std::optional<SurfacePoint> star_centroid(VertexHandle v) const {
        const geodesic::Mesh& mesh = g_.fine().mesh;
        const double theta = cone_angle(mesh, g_.location(v));
        std::vector<Eigen::Vector2d> ring;
        double first = 0.0;
        for (HalfedgeHandle h : g_.coarse().voh_ccw_range(v)) {
            const double direction = detail::start_direction(g_, h);
            if (ring.empty()) first = direction;
            const double angle = ccw_angle(first, direction, theta) * 2.0 * k_pi / theta;
            const double length = g_.length(g_.coarse().edge_handle(h));
            ring.emplace_back(length * std::cos(angle), length * std::sin(angle));
        }
        Eigen::Vector2d weighted(0.0, 0.0);
        double area = 0.0;
        for (std::size_t i = 0; i < ring.size(); ++i) {
            const Eigen::Vector2d& p = ring[i];
            const Eigen::Vector2d& q = ring[(i + 1) % ring.size()];
            const double twice = detail::cross(p, q);
            if (!(twice > 0.0)) return std::nullopt;
            weighted += twice * (p + q) / 3.0;
            area += twice;
        }
        const Eigen::Vector2d centroid = weighted / area;
        const double distance = centroid.norm();
        if (!(distance > 0.0)) return std::nullopt;
        double direction = std::atan2(centroid.y(), centroid.x());
        if (direction < 0.0) direction += 2.0 * k_pi;
        const StraightGeodesicResult walk = trace_straight_geodesic(
            mesh, g_.location(v), std::fmod(first + direction * theta / (2.0 * k_pi), theta), distance);
        if (walk.stopped_at_boundary) return std::nullopt;
        return walk.end;
    }

    /// v's star as the locations of v and of its ring, counter-clockwise: a key that survives renumbering.
    std::vector<double> star_key(VertexHandle v) const {
        std::vector<double> key;
        append_key(key, g_.location(v));
        for (VertexHandle u : g_.coarse().vv_ccw_range(v)) append_key(key, g_.location(u));
        return key;
    }
    static void append_key(std::vector<double>& key, const SurfacePoint& p) {
        const std::array<double, 9> fields{static_cast<double>(p.kind), static_cast<double>(p.vertex),
                                           static_cast<double>(p.edge_v0), static_cast<double>(p.edge_v1), p.t,
                                           static_cast<double>(p.face), p.bary[0], p.bary[1], p.bary[2]};
        for (double x : fields) key.push_back(x);
    }

    /// The saddles of T, curved as refinement counts it (curved()), that the geodesics of f's two edges at its
    /// vertex v (of all three where v is invalid) pass through, each once, in the order met: a shortest geodesic
    /// passes through no vertex of positive curvature, and bends only at a saddle, whose curvature the two faces
    /// beside it then share, so that their corners sum to well below π (on femur_cgal, to 86 degrees) and no split
    /// of theirs can mend them. Moved onto the saddle, v takes that curvature as its own. (No coarse vertex is on a
    /// geodesic of a valid G.)
    std::vector<int> saddles_on_edges_of(FaceHandle f, VertexHandle v = VertexHandle()) const {
        const geodesic::Mesh& mesh = g_.fine().mesh;
        const CoarseMesh& coarse = g_.coarse();
        std::vector<int> found;
        for (HalfedgeHandle h : halfedges_of(coarse, f)) {
            if (v.is_valid() && coarse.from_vertex_handle(h) != v && coarse.to_vertex_handle(h) != v) continue;
            const Polyline& line = g_.polyline(coarse.edge_handle(h));
            for (std::size_t i = 1; i + 1 < line.size(); ++i) {
                const SurfacePoint& p = line[i];
                if (p.kind == geodesic::PointKind::vertex && mesh.cone_angle(p.vertex) - 2.0 * k_pi > curved_ &&
                    std::find(found.begin(), found.end(), p.vertex) == found.end())
                    found.push_back(p.vertex);
            }
        }
        return found;
    }

    /// Whether v's location on T is a curved point (see k_curved_fraction): a feature that refinement keeps.
    bool curved(VertexHandle v) const {
        return std::abs(cone_angle(g_.fine().mesh, g_.location(v)) - 2.0 * k_pi) > curved_;
    }

    /// Inserts f's circumcentre (in the patch that centre_patches() finds holding it), or else splits f's edges,
    /// longest first.
    bool refine_face(FaceHandle f) {
        const CoarseMesh& coarse = g_.coarse();
        const auto h = halfedges_of(coarse, f);
        const double min_length = min_edge_of(f);
        if (const std::optional<Centre> centre = circumcentre(f)) {
            const std::vector<FaceHandle> around = with_neighbours(f);
            // A curved vertex of T inside the circumcircle goes in first: between curved vertices of T that are
            // not coarse vertices, circumcentres can chase each other down to ever smaller triangles.
            const double floor = std::max(0.5 * smallest_corner(f), keep_above_);
            if (const std::optional<int> cone = curved_vertex_near(centre->point, centre->radius)) {
                if (insert_in_one_of(around, SurfacePoint::at_vertex(*cone), floor, min_length)) return true;
            }
            if (insert_in_one_of(centre_patches(f, *centre), centre->point, floor, min_length)) return true;
        }
        std::array<EdgeHandle, 3> edges{coarse.edge_handle(h[0]), coarse.edge_handle(h[1]), coarse.edge_handle(h[2])};
        std::stable_sort(edges.begin(), edges.end(),
                         [&](EdgeHandle a, EdgeHandle b) { return g_.length(a) > g_.length(b); });
        std::vector<std::pair<EdgeHandle, double>> unsplit;
        for (EdgeHandle e : edges)
            if (split_edge_somewhere(e, min_length, false, &unsplit)) return true;
        // Again with geodesics inside the patches where the shortest ones left them. A split that was made and
        // then refused for its shape used no such fallback: it would be refused again, so it is not tried.
        for (const auto& [e, fraction] : unsplit)
            if (split_edge_at(e, fraction, min_length, true) == Tried::kept) return true;
        return inside_splits_ && split_inside_or_around(f);
    }

    /// raise_min_angle()'s last resort, for a face f that nothing else mends: a face split well inside f's patch
    /// (split_inside()), else inside a neighbour's. A split inside f cuts its smallest corner; one inside a neighbour
    /// leaves it, for the flips after it to mend. Each try's floor is half the smallest corner of the face split, but
    /// never above f's smallest (G's smallest does not fall): the neighbours of a face with a corner of 3 degrees, on
    /// a G of 4 faces, are wide patches that no split cuts evenly.
    bool split_inside_or_around(FaceHandle f) {
        const double worst = smallest_corner(f);
        for (FaceHandle x : with_neighbours(f))
            if (split_inside(x, std::max(std::min(0.5 * smallest_corner(x), worst), keep_above_), min_edge_of(x))) {
                ++result_.inside_splits;
                return true;
            }
        return false;
    }

    /// A face split of f at a point well inside its patch: walked straight from a corner along its bisector, as far
    /// as the incentre of f's intrinsic layout or half as far, the widest corner first. Where a patch is large (the
    /// coarsest G that decimation gives has 4 faces on a sphere-like T) or a geodesic of it bends at a saddle of T,
    /// the geodesics from a point on an edge or a circumcentre to the far corners leave the patch, and those splits
    /// are refused; geodesics from a point deep inside it leave it less often.
    bool split_inside(FaceHandle f, double floor, double min_length) {
        const CoarseMesh& coarse = g_.coarse();
        const auto h = halfedges_of(coarse, f);
        std::array<double, 3> length{}, corner{};
        for (std::size_t i = 0; i < 3; ++i) {
            length[i] = g_.length(coarse.edge_handle(h[i]));
            corner[i] = corner_angle(g_, h[i]);
        }
        const double half_perimeter = 0.5 * (length[0] + length[1] + length[2]);
        std::array<std::size_t, 3> order{0, 1, 2};
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t a, std::size_t b) { return corner[a] > corner[b]; });
        for (std::size_t i : order) {
            // The corner at h[i]'s from-vertex lies between h[i] and the edge before it; h[i]'s next is opposite.
            const double ab = length[i], ca = length[(i + 2) % 3], bc = length[(i + 1) % 3];
            const double layout_angle = detail::opposite_angle(bc, ab, ca);
            // The incentre lies inside the layout, no farther from the corner than its longer side.
            const double to_incentre =
                std::min((half_perimeter - bc) / std::cos(0.5 * layout_angle), std::max(ab, ca));
            if (!(to_incentre > 0.0)) continue;
            const SurfacePoint& start = g_.location(coarse.from_vertex_handle(h[i]));
            const double theta = cone_angle(g_.fine().mesh, start);
            const double direction = std::fmod(detail::start_direction(g_, h[i]) + 0.5 * corner[i], theta);
            for (double fraction : {1.0, 0.5}) {
                const StraightGeodesicResult walk =
                    trace_straight_geodesic(g_.fine().mesh, start, direction, fraction * to_incentre);
                if (walk.stopped_at_boundary) continue;
                if (insert_in_one_of({f}, walk.end, floor, min_length)) return true;
            }
        }
        return false;
    }

    /// In the end game, where refine_face() and the moves give up on f: a split at a saddle of T that f's geodesics
    /// bend at, or else at the curved vertex of T nearest f's circumcentre (in its circumcircle). A saddle on a
    /// geodesic of f takes its curvature out of the corners of f and of the face beside it, and one inside f's patch
    /// out of f's, so that their corners sum to far below pi (93 degrees on man and gears) and no other split mends
    /// them; a coarse vertex on the saddle takes that curvature as its own. Such a vertex can sit closer to a coarse
    /// vertex than refinement's shortest edge: on cheese, a face of T a thirtieth of its mean edge across holds a
    /// saddle of 494 degrees next to a cone of 294 degrees with a coarse vertex on it; on man, saddles of 419 and 447
    /// degrees lie 0.07 of T's mean edge apart. So the split may make edges of any length (such splits are finitely
    /// many: one per vertex of T), and its edges shorter than min_edge_ become features that the triangles around
    /// them are mended at the scale of (min_edge_of()). Tried wherever a face would be given up, such splits took
    /// cheese to 25 degrees but left man at 30 degrees with 77 corners at 1.8 degrees instead of 15 at 18.1,
    /// cascading next to the short edges: hence the end game only (and the last resort's pass, split_inside).
    bool split_at_saddle(FaceHandle f) {
        if (!tactics_.split_at_saddles) return false;
        std::vector<int> cones = saddles_on_edges_of(f);
        if (const std::optional<Centre> centre = circumcentre(f))
            if (const std::optional<int> near = curved_vertex_near(centre->point, centre->radius))
                if (std::find(cones.begin(), cones.end(), *near) == cones.end()) cones.push_back(*near);
        for (int cone : cones)
            if (split_at_vertex_of_t(f, cone)) {
                ++result_.splits_at_saddles;
                add_short_edges_at(split_vertex_);
                return true;
            }
        return false;
    }

    /// split_at_saddle()'s split at vertex `cone` of T: of the geodesic of an edge at one of f's corners that
    /// passes through it (no two geodesics of a valid G meet, so there is at most one), else of the patch of f or
    /// of a neighbour that holds it. A geodesic bent at a saddle has no better place to split, and its split may
    /// make corners as small as keep_above_ (7 degrees on man at 30 degrees, next to a saddle of 472, where f's
    /// smallest was 22.7) for the triangles around it to mend; a face split must keep half of f's smallest, as
    /// refine_face()'s do: the curved vertex nearest the circumcentre may be a cone of positive curvature (350
    /// degrees on man's coarsest G), and with keep_above_ as the floor its split made corners of 2.9 degrees there,
    /// from which refinement cascaded to the vertex cap.
    bool split_at_vertex_of_t(FaceHandle f, int cone) {
        const CoarseMesh& coarse = g_.coarse();
        for (VertexHandle v : coarse.fv_range(f))
            for (HalfedgeHandle h : coarse.voh_range(v)) {
                const EdgeHandle e = coarse.edge_handle(h);
                const Polyline& line = g_.polyline(e);
                for (std::size_t i = 1; i + 1 < line.size(); ++i) {
                    if (line[i].kind != geodesic::PointKind::vertex || line[i].vertex != cone) continue;
                    auto split = [&](GeodesicTriangulation& trial) {
                        return split_edge_at_point(trial, e, i, split_options(false), propagation_only(propagation_));
                    };
                    if (try_split(split, keep_above_, 0.0, result_.edge_splits) != Tried::kept) return false;
                    coarse_at_fine_vertex_.insert(cone);  // as insert_in_one_of() records it for a face split
                    return true;
                }
            }
        return insert_in_one_of(with_neighbours(f), SurfacePoint::at_vertex(cone),
                                std::max(0.5 * smallest_corner(f), keep_above_), 0.0);
    }

    /// The edges shorter than min_edge_ at coarse vertex v, which a split or a move onto a saddle just put there, as
    /// features of the input (short_given_edges_); every face is measured again, as min_edge_of() changed around them.
    void add_short_edges_at(VertexHandle v) {
        const CoarseMesh& coarse = g_.coarse();
        const geodesic::Mesh& mesh = g_.fine().mesh;
        for (HalfedgeHandle h : coarse.voh_range(v)) {
            const EdgeHandle e = coarse.edge_handle(h);
            if (!(g_.length(e) < min_edge_)) continue;
            short_given_edges_.push_back(
                {{mesh.point(g_.location(v)), mesh.point(g_.location(coarse.to_vertex_handle(h)))}, g_.length(e)});
            renumbered_ = true;
        }
    }

    /// The coarse face where a straight walk of `distance` from corner `corner` ends, `direction` radians from the
    /// corner's first side, walked across the intrinsic layouts of the coarse triangles (their geodesic lengths
    /// only) unfolded one after the other; invalid when the walk leaves through a boundary or goes on too long.
    /// A guess of the patch that holds the walk's end on T: the layouts ignore the curvature inside the patches.
    FaceHandle layout_walk(HalfedgeHandle corner, double direction, double distance) const {
        const CoarseMesh& coarse = g_.coarse();
        auto third = [&](HalfedgeHandle e, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
            // The corner opposite e = (a, b) in e's face, on the left of a -> b.
            const double ab = (b - a).norm(), bc = g_.length(coarse.edge_handle(coarse.next_halfedge_handle(e))),
                         ca = g_.length(coarse.edge_handle(coarse.prev_halfedge_handle(e)));
            const double x = (ab * ab + ca * ca - bc * bc) / (2.0 * ab), y = std::sqrt(std::max(0.0, ca * ca - x * x));
            const Eigen::Vector2d u = (b - a) / ab;
            return Eigen::Vector2d(a + x * u + y * Eigen::Vector2d(-u.y(), u.x()));
        };
        const Eigen::Vector2d origin(0.0, 0.0), end(distance * std::cos(direction), distance * std::sin(direction));
        HalfedgeHandle entry = corner;  // a halfedge of the current face; in the first face, the corner's first side
        Eigen::Vector2d a = origin, b(g_.length(coarse.edge_handle(corner)), 0.0);
        for (int step = 0; step < 64; ++step) {
            const Eigen::Vector2d c = third(entry, a, b);
            // Leaves through b -> c or c -> a (never back through the entry side), at the first crossing.
            HalfedgeHandle exit;
            Eigen::Vector2d exit_from, exit_to;
            double first = 1.0;
            const std::array<std::pair<Eigen::Vector2d, Eigen::Vector2d>, 2> sides{{{b, c}, {c, a}}};
            for (std::size_t k = 0; k < 2; ++k) {
                const auto& [p, q] = sides[k];
                const Eigen::Vector2d d = end - origin, e = q - p;
                const double denominator = detail::cross(d, e);
                if (denominator == 0.0) continue;
                const double along = detail::cross(p - origin, e) / denominator;  // on the walk
                const double at = detail::cross(p - origin, d) / denominator;     // on the side
                if (along > 1e-12 && along < first && at >= 0.0 && at <= 1.0) {
                    first = along;
                    exit = k == 0 ? coarse.next_halfedge_handle(entry) : coarse.prev_halfedge_handle(entry);
                    exit_from = p;
                    exit_to = q;
                }
            }
            if (!exit.is_valid()) return coarse.face_handle(entry);
            entry = coarse.opposite_halfedge_handle(exit);
            if (coarse.is_boundary(entry)) return FaceHandle();
            a = exit_to;
            b = exit_from;
        }
        return FaceHandle();
    }

    /// `faces`, then f and its neighbours that it does not hold yet (nothing for an invalid f).
    std::vector<FaceHandle> with_neighbours(FaceHandle f, std::vector<FaceHandle> faces = {}) const {
        if (!f.is_valid()) return faces;
        const CoarseMesh& coarse = g_.coarse();
        auto add = [&faces](FaceHandle x) {
            if (x.is_valid() && std::find(faces.begin(), faces.end(), x) == faces.end()) faces.push_back(x);
        };
        add(f);
        for (HalfedgeHandle h : coarse.fh_range(f)) add(coarse.face_handle(coarse.opposite_halfedge_handle(h)));
        return faces;
    }

    /// The faces whose patches may hold f's circumcentre, the likeliest first: where layout_walk() ends and its
    /// neighbours, then f and its neighbours.
    std::vector<FaceHandle> centre_patches(FaceHandle f, const Centre& centre) const {
        return with_neighbours(f, with_neighbours(layout_walk(centre.corner, centre.layout_direction, centre.radius)));
    }

    /// Splits the first of `faces` whose patch holds p strictly inside, with no new corner below `floor` and no new
    /// edge shorter than `min_length` (try_split(), with `changed_floor`); false when none does.
    bool insert_in_one_of(const std::vector<FaceHandle>& faces, const SurfacePoint& p, double floor,
                          double min_length, double changed_floor = 0.0) {
        // A try in a patch that does not hold p costs a propagation before it is refused: rays from p rule them
        // out first where they can (on lucy_100k at 25 degrees, two tries in three were such).
        std::vector<FaceHandle> candidates = faces;
        if (const std::optional<FaceHandle> holder = detail::patch_holding(g_, faces, p))
            candidates = holder->is_valid() ? std::vector<FaceHandle>{*holder} : std::vector<FaceHandle>{};
        const SplitOptions options = split_options(false);
        Workspace workspace = propagation_only(propagation_);
        for (std::size_t i = 0; i < candidates.size(); ++i) {
            auto split = [&](GeodesicTriangulation& trial) {
                return split_face(trial, candidates[i], p, options, workspace);
            };
            const Tried tried = try_split(split, floor, min_length, result_.face_splits, changed_floor);
            if (tried == Tried::kept) {
                if (p.kind == geodesic::PointKind::vertex) coarse_at_fine_vertex_.insert(p.vertex);
                return true;
            }
            // The split was made, so p is strictly inside this patch and in no other.
            if (tried == Tried::refused_shape) return false;
            // When the first patch tried does not hold p, one propagation from p towards the corners of all the
            // others serves the tries left: a try in a patch that does not hold p is refused as soon as its first
            // geodesic arrives outside the patch's corner.
            if (i == 0 && candidates.size() > 1) {
                geodesic::PropagationOptions towards;
                for (std::size_t j = 1; j < candidates.size(); ++j)
                    for (VertexHandle v : g_.coarse().fv_range(candidates[j]))
                        if (std::find(towards.stop_points.begin(), towards.stop_points.end(), g_.location(v)) ==
                            towards.stop_points.end())
                            towards.stop_points.push_back(g_.location(v));
                towards.goal_directed = true;
                propagation_.propagate({g_.fine().mesh.canonical(p)}, towards);
                workspace.propagated = true;
            }
        }
        return false;
    }

    /// The curved vertex of T nearest to p within Euclidean distance `radius`, that no coarse
    /// vertex sits on yet. A search over the fine faces near p.
    std::optional<int> curved_vertex_near(const SurfacePoint& p, double radius) const {
        const geodesic::Mesh& mesh = g_.fine().mesh;
        const Eigen::Vector3d x = mesh.point(p);
        std::vector<int> stack;
        // Faces seen are stamped with this search's number: a set of them cost a node allocation per face.
        if (face_stamp_.empty()) face_stamp_.assign(static_cast<std::size_t>(mesh.num_faces()), 0);
        if (++search_number_ == 0) {  // wrapped around: no stamp may look like this search's
            std::fill(face_stamp_.begin(), face_stamp_.end(), 0u);
            search_number_ = 1;
        }
        const unsigned stamp = search_number_;
        std::size_t seen = 0;
        auto visit = [&](int f) {
            if (face_stamp_[static_cast<std::size_t>(f)] == stamp) return;
            face_stamp_[static_cast<std::size_t>(f)] = stamp;
            ++seen;
            double nearest = std::numeric_limits<double>::infinity(), longest = 0.0;
            for (int i = 0; i < 3; ++i) {
                nearest = std::min(nearest, (mesh.position(mesh.triangle(f)[i]) - x).norm());
                longest = std::max(longest, mesh.length(3 * f + i));
            }
            if (nearest <= radius + longest) stack.push_back(f);
        };
        for (int f : faces_holding(mesh, p)) visit(f);
        std::optional<int> best;
        double best_distance = radius;
        while (!stack.empty() && seen < k_max_search_faces) {
            const int f = stack.back();
            stack.pop_back();
            for (int i = 0; i < 3; ++i) {
                const int v = mesh.triangle(f)[i];
                const double d = (mesh.position(v) - x).norm();
                if (d < best_distance && std::abs(mesh.cone_angle(v) - 2.0 * k_pi) > curved_ &&
                    !coarse_at_fine_vertex_.count(v)) {
                    best = v;
                    best_distance = d;
                }
                const int twin = mesh.twin(3 * f + i);
                if (twin >= 0) visit(geodesic::Mesh::face_of(twin));
            }
        }
        return best;
    }

    GeodesicTriangulation& g_;
    const RefineOptions& options_;
    const detail::RefineTactics tactics_;
    RefineResult& result_;
    geodesic::ExactGeodesic propagation_;
    PropagationPool pool_;  ///< for the other threads of the flips' and reconnections' parallel loops
    PathCache paths_;       ///< the flips' geodesics, for flips evaluated again
    FlipToDelaunayOptions flip_options_;
    Workspace flip_workspace_;  ///< the flips' propagation objects and, on a large T, their path cache
    std::function<void()> stop_if_cancelled_;
    std::set<int> coarse_at_fine_vertex_;  ///< the vertices of T that coarse vertices sit on
    std::vector<SurfacePoint> given_;       ///< the locations of the vertices that removals may take out
    std::vector<SurfacePoint> input_;       ///< the locations of the vertices of the G given
    struct ShortEdge {
        std::array<Eigen::Vector3d, 2> ends;
        double length;
    };
    /// The edges of the G given shorter than min_edge_, and those of splits and moves at saddles (add_short_edges_at())
    std::vector<ShortEdge> short_given_edges_;
    std::set<std::vector<double>> failed_stars_;  ///< star_key() of the removals tried without success
    std::set<std::vector<double>> failed_moves_;  ///< star_key() of the moves tried without success
    mutable std::vector<unsigned> face_stamp_;  ///< per face of T: the last curved_vertex_near() that saw it
    mutable unsigned search_number_ = 0;
    TrialSlot split_trial_;                ///< storage for the splits' trial copies of G
    std::vector<TrialSlot> move_trials_;  ///< and for those of the moves tried together
    long g_version_ = 0;                  ///< how many times replace_g() changed G
    std::vector<EdgeHandle> split_edges_;  ///< the edges that the last split kept and its flips made or changed
    VertexHandle split_vertex_;            ///< the new vertex of the last split kept
    double min_edge_ = 0.0, min_angle_ = 0.0, curved_ = 0.0;
    bool inside_splits_ = false;  ///< refine_face() tries split_inside_or_around() too (the last resort)
    double keep_above_ = 0.0;  ///< while raising the minimum angle: the smallest corner when it began (radians)
    int budget_ = 0, new_vertices_ = 0;
    /// The faces of G that changed since raise_min_angle() last looked (indices), or, when renumbered_, any.
    std::vector<int> changed_faces_;
    bool renumbered_ = true;  // nothing is recorded until raise_min_angle() looks
};

/// One refinement of the G given: its result, and what it did.
struct Attempt {
    std::optional<GeodesicTriangulation> g;
    RefineResult result;
};

/// The refinements of the G given with one shortest edge: with the vertices of T curved by more than
/// `curved_fraction` of the angle counted as curved, then with nearly every vertex of T that is not flat
/// (k_second_curved_fraction); with vertex moves, then, where the tactics move vertices, both again without. refine()
/// knows which it needs only from the results of those before, so on `threads` > 1 they all start at once
/// (SpeculativeAttempts), and each one's progress is reported while refine() waits for it.
class AttemptGroup {
public:
    AttemptGroup(const GeodesicTriangulation& given, const RefineResult& given_result, const RefineOptions& options,
                 const detail::RefineTactics& tactics, double min_edge_length, double curved_fraction, int threads)
        : given_(given), given_result_(given_result), options_(options), tactics_(tactics),
          variants_(variants_of(min_edge_length, curved_fraction, tactics.move_vertices)),
          runner_(variants_.size(), threads, [this](std::size_t k) { run(k); }) {}

    std::size_t size() const { return variants_.size(); }
    /// How attempt k refines: its shortest edge, its curved fraction, and whether it moves vertices.
    const RefineAttempt& variant(std::size_t k) const { return variants_[k]; }
    /// Attempt k, once finished; rethrows what it threw.
    const Attempt& get(std::size_t k) {
        runner_.wait(k);
        return results_[k];
    }
    /// Attempt k is not needed.
    void cancel(std::size_t k) { runner_.cancel(k); }
    /// Whether attempt k turns off the vertex moves that the tactics allow.
    bool without_moves(std::size_t k) const { return !variants_[k].vertex_moves && tactics_.move_vertices; }

private:
    static std::vector<RefineAttempt> variants_of(double min_edge_length, double curved_fraction, bool moves) {
        std::vector<RefineAttempt> all;
        for (bool with_moves : moves ? std::vector<bool>{true, false} : std::vector<bool>{false}) {
            for (double curved : {curved_fraction, k_second_curved_fraction}) {
                RefineAttempt v;
                v.min_edge_length = min_edge_length;
                v.curved_fraction = curved;
                v.vertex_moves = with_moves;
                all.push_back(v);
            }
        }
        return all;
    }

    void run(std::size_t k) {
        RefineOptions options = options_;
        options.min_edge_length = variants_[k].min_edge_length;
        if (options_.progress)
            options.progress = [this, k](const std::string& line) {
                if (!runner_.waited_for(k)) return;
                std::lock_guard<std::mutex> lock(progress_mutex_);
                options_.progress(line);
            };
        detail::RefineTactics tactics = tactics_;
        tactics.move_vertices = variants_[k].vertex_moves;
        Attempt& attempt = results_[k];
        attempt.g.emplace(given_);
        attempt.result = given_result_;
        Refiner refiner(*attempt.g, options, tactics, attempt.result, variants_[k].curved_fraction,
                        [this, k] { runner_.stop_if_cancelled(k); });
        refiner.bisect();
        refiner.raise_min_angle();
        refiner.count_corners_left();
    }

    // Made before runner_, whose threads read them at once.
    const GeodesicTriangulation& given_;
    const RefineResult& given_result_;
    const RefineOptions& options_;  // the caller's, with its progress, which refine() reports to too
    const detail::RefineTactics tactics_;
    const std::vector<RefineAttempt> variants_;
    std::vector<Attempt> results_ = std::vector<Attempt>(variants_.size());
    std::mutex progress_mutex_;
    detail::SpeculativeAttempts runner_;  // last: its threads start as it is made, and use all of the above
};

/// What an attempt after the first does otherwise, for the progress line that announces it.
std::string how_it_differs(const RefineAttempt& attempt, const RefineAttempt& first) {
    std::vector<std::string> parts;
    if (attempt.min_edge_length != first.min_edge_length) parts.push_back("a shorter shortest edge");
    if (attempt.curved_fraction == k_second_curved_fraction) parts.push_back("nearly every vertex of T curved");
    else if (attempt.curved_fraction != first.curved_fraction) parts.push_back("more vertices of T curved");
    if (attempt.vertex_moves != first.vertex_moves) parts.push_back("without vertex moves");
    std::string text;
    for (std::size_t i = 0; i < parts.size(); ++i)
        text += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
    return text;
}

}  // namespace

namespace detail {

RefineResult refine(GeodesicTriangulation& g, const RefineOptions& options, const RefineTactics& tactics) {
    const auto start = std::chrono::steady_clock::now();
    if (!(options.max_length >= 0.0) || !std::isfinite(options.max_length))
        throw InvalidInput("refine: the maximum length must be a finite number >= 0");
    if (options.target_faces < 0) throw InvalidInput("refine: the face count must be >= 0");
    if (!(options.min_angle_deg >= 0.0 && options.min_angle_deg <= k_max_min_angle_deg))
        throw InvalidInput("refine: the minimum angle must be in [0, 35] degrees");
    if (!(options.min_edge_length >= 0.0) || !std::isfinite(options.min_edge_length))
        throw InvalidInput("refine: the minimum edge length must be a finite number >= 0");
    RefineResult given_result;
    const ValidationReport before = validate(g);
    given_result.valid_before = before.valid;
    if (!before.valid)
        throw InvalidInput("refine: G is not valid (" + std::to_string(before.violations.size()) +
                           " violations); make it valid first (geotri-flip)");
    given_result.angles_before = corner_angle_stats(g);
    // Refinement's choices follow the numbering of G's edges and halfedges, which flips change: numbered as reading
    // its file numbers it, a G flipped in memory refines as geotri-refine refines geotri-flip's output.
    const GeodesicTriangulation given = renumbered_as_read(g);
    const double exempt_below = k_exempt_cone_factor * options.min_angle_deg * k_pi / 180.0;

    // Which triangles refinement gives up on follows its choices all along the way, which the shortest edge, the
    // vertices of T counted as curved and the vertex moves steer, and no choice is best everywhere. So where the
    // best result so far gives up on some corners below the vertex cap, the G given is refined again, in groups of
    // one shortest edge each (AttemptGroup), and the best result is kept:
    // - with the options' shortest edge and the vertices of T curved by more than k_curved_fraction of the angle;
    // - where no shortest edge is given, with k_finer_min_edge_fraction of T's mean edge;
    // - with the shortest edge of the best so far and k_finer_curved_fraction, where at most k_few_corners_left
    //   corners are left.
    // Within each, with nearly every vertex of T curved too (armadillo_cgal, brain_conte69 and triceratops at 25
    // degrees, horse at 30), and without vertex moves where at most k_few_corners_left corners are left: the ways out
    // that refinement has where it is stuck were made for circumcentres alone, and moves can stand in their way
    // (footbones at 30 degrees). Where more are left, circumcentres alone left more still on every mesh measured,
    // and a sixth of the angle in every attempt left far more corners (gears 308 instead of 6 at 30 degrees), so
    // those run only near the end. The shorter edge takes femur_cgal at 30 degrees from 21.8 to 28.4 degrees, and
    // the sixth with it to 30.0; man at 30 degrees comes out better with the tenth.
    std::vector<RefineAttempt> attempts;
    std::size_t kept = 0;
    RefineResult counts;
    ValidationReport after;
    auto gives_up = [&](bool few_left) {
        return tactics.other_attempts && options.min_angle_deg > 0.0 && after.valid && counts.small_corners_left > 0 &&
               !counts.vertex_cap_reached && (!few_left || counts.small_corners_left <= k_few_corners_left);
    };
    // Attempts run ahead of time on threads of their own where the propagations are too short to share
    // (k_min_faces_for_threads); either way, the same attempts run and give the same results.
    const int threads = options.min_angle_deg > 0.0 && g.fine().mesh.num_faces() < k_min_faces_for_threads
                            ? detail::team_size(options.threads)
                            : 1;
    enum class Group { given_edge, shorter_edge, more_curved };
    for (Group group : {Group::given_edge, Group::shorter_edge, Group::more_curved}) {
        double min_edge = options.min_edge_length, curved = k_curved_fraction;
        if (group == Group::shorter_edge) {
            if (options.min_edge_length > 0.0 || !gives_up(false)) continue;
            min_edge = k_finer_min_edge_fraction * mean_edge_length(g.fine().mesh);
        } else if (group == Group::more_curved) {
            if (!gives_up(true)) continue;
            min_edge = attempts[kept].min_edge_length;
            curved = k_finer_curved_fraction;
        }
        AttemptGroup runs(given, given_result, options, tactics, min_edge, curved, threads);
        for (std::size_t k = 0; k < runs.size(); ++k) {
            RefineAttempt record = runs.variant(k);
            const bool first = attempts.empty();
            if (!first && !gives_up(runs.without_moves(k) || group == Group::more_curved)) {
                runs.cancel(k);
                continue;
            }
            if (!first && options.progress)
                options.progress("gave up on " + std::to_string(counts.small_corners_left) +
                                 (counts.small_corners_left == 1 ? " corner" : " corners") +
                                 ": refining again with " + how_it_differs(record, attempts.front()));
            const Attempt* done = nullptr;
            if (first) {
                done = &runs.get(k);  // its numerical trouble is refine()'s
            } else {
                try {
                    done = &runs.get(k);
                } catch (const NumericalError& trouble) {
                    // Another attempt only tries to do better: where it meets numerical trouble, the best stands.
                    record.error = trouble.what();
                }
            }
            if (done) {
                record.small_corners_left = done->result.small_corners_left;
                record.min_angle_deg = corner_angle_stats(*done->g).min_deg;
                if (first) {
                    g = *done->g;
                    counts = done->result;
                    after = validate(g);
                } else if (better_result(done->result, *done->g, counts, g, exempt_below)) {
                    // Only a valid result can be better: the local checks may have let an invalid one through.
                    ValidationReport report = validate(*done->g);
                    if (report.valid) {
                        g = *done->g;
                        counts = done->result;
                        after = std::move(report);
                        kept = attempts.size();
                    }
                }
            }
            attempts.push_back(record);
        }
    }
    attempts[kept].kept = true;
    RefineResult result = counts;
    result.attempts = std::move(attempts);
    result.valid_after = after.valid;
    if (!after.valid) result.remaining = after.violations;
    result.angles_after = corner_angle_stats(g);
    for (EdgeHandle e : g.coarse().edges()) result.longest_edge = std::max(result.longest_edge, g.length(e));
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace detail

RefineResult refine(GeodesicTriangulation& g, const RefineOptions& options) {
    return detail::refine(g, options, detail::RefineTactics{});
}

}  // namespace geotri

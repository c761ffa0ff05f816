#include "event_queue.h"
#include "window.h"

#include <geodesic/constants.h>
#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <string>
#include <utility>

namespace geotri::geodesic {

using detail::k_infinity;
using detail::Window;
using detail::EdgeProfile;
using detail::profile_crossings;
using Vec2 = Eigen::Vector2d;

namespace {

// A window that ends within this fraction of an edge's length from a vertex also gives that vertex its distance;
// the apex of the face that it crosses, within this fraction of the edge's length plus its source's distance, since
// that ray is computed from the source. The ray to the vertex then misses the window by at most that much, which
// changes the length only to second order (~1e-18 relative). It closes the gaps that rounding leaves where a ray
// runs exactly through a vertex.
constexpr double k_cover = 1e-12;
// A window is dropped only when a vertex beats it by more than this relative margin, so that ties are kept.
constexpr double k_margin = 1e-12;
// Cone angles within this of 2π count as flat: geodesics pass straight through, no pseudo-source is needed, and the
// rounding gaps left behind are closed by k_cover.
constexpr double k_flat = 1e-13;
// How far a saddle's emission reaches beyond its exact shadow (radians), to cover rounding at the shadow's rims.
// A path can bend by this much less than π at the saddle, so it must stay far below what a straightness check
// allows; rays just outside the shadow are carried by the windows that pass beside the saddle anyway.
constexpr double k_shadow_slack = 1e-12;
// A path's edge crossing this close to a vertex (relative to the mesh size) is reported as that vertex.
constexpr double k_vertex_snap = 1e-12;

enum class Via : std::uint8_t { none, source, vertex, window };

constexpr unsigned char k_pending = 0;
constexpr unsigned char k_propagated = 1;
constexpr unsigned char k_merged = 2;
// Windows of the same ray family (same pseudo-source, unfolded to the same place up to this relative rounding) that
// touch on an edge are propagated as one.
constexpr double k_same_source = 1e-13;
constexpr int k_merge_lookahead = 4;

// Windows compared with each other on an edge: the most recent ones, which are those the wavefront brings together.
constexpr int k_compare_lookahead = 4;
// No window further down its edge's list than this is ever read again while the propagation runs.
constexpr int k_list_reach = std::max(k_merge_lookahead, k_compare_lookahead);
// Without keep_windows, the windows that no longer count are freed once there are at least this many windows.
constexpr std::size_t k_min_windows_to_free = 1 << 16;
// first_window of a halfedge whose edge the wavefront has passed (close_passed_edges): no window comes there again.
constexpr int k_closed = -2;
// How far beyond the longest path through an end vertex, relative to the key, an edge is closed: far more than the
// rounding by which later keys can fall below the last (wavefront_has_passed), and far less than the windows
// dropped there exceed that path by (2.6e-3 relative at the least, on boxes, cylinders and grids).
constexpr double k_close_margin = 1e-8;

/// A hint to start loading memory that will soon be read; no effect on results.
inline void prefetch(const void* address) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(address);
#else
    (void)address;
#endif
}

/// std::fmod(x, cone) (up to the sign of a zero), without its cost where |x| < 2 cone, as angles around a vertex
/// nearly always are: there one subtraction or addition is exact (Sterbenz), and std::fmod took 2% of the
/// instructions on a noisy sphere, whose saddles emit often.
inline double angle_remainder(double x, double cone) {
    if (x >= cone && x < 2.0 * cone) return x - cone;
    if (x <= -cone && x > -2.0 * cone) return x + cone;
    if (x > -cone && x < cone) return x;
    return std::fmod(x, cone);
}

/// How a vertex got its distance: from a source directly, along an edge from another vertex, or through a window.
struct Predecessor {
    Via via = Via::none;
    int id = -1;
};

}  // namespace

class ExactGeodesic::Impl {
public:
    explicit Impl(const Mesh& mesh);

    void propagate(const std::vector<SurfacePoint>& sources, const PropagationOptions& options);
    double vertex_distance(int v) const;
    int num_vertices() const { return mesh_.num_vertices(); }
    double distance(const SurfacePoint& p) const;
    std::vector<SurfacePoint> shortest_path(const SurfacePoint& target) const;

    double settled_radius_ = k_infinity;
    PropagationStats stats_;
    std::size_t windows_created_before_ = 0;  ///< by the propagations before the current one

private:
    /// The best known way to reach a point: its distance and what gives it.
    struct Best {
        double distance = k_infinity;
        Via via = Via::none;
        int id = -1;    // source index, vertex, or window
        Vec2 position;  // for a window: the point in the window's frame
    };

    struct StopPoint {
        SurfacePoint point;
        double window_estimate = k_infinity;  // best distance through windows, kept up to date as they arrive
        double source_distance = k_infinity;  // straight from a source in one of its faces
        std::vector<std::pair<int, double>> corners;  // the vertices of its faces, with their straight distances
        bool settled = false;
    };

    void reset();
    void relax_vertex(int v, double distance, Predecessor predecessor);
    void add_window(int h, double b0, double b1, double sx, double sy, double sigma, int parent, int origin);
    void retire_beyond_reach(int h);
    bool wavefront_has_passed(int h) const;
    void close_edge(int h);
    void close_passed_edges();
    void free_retired_windows();
    bool trim_by_end_vertices(Window& w, detail::EndValues& ends) const;
    struct ComparedWindows;
    void collect_compared(int list, int self, double length, bool mirrored, ComparedWindows& out) const;
    bool trim_by_other_windows(Window& w, detail::EndValues& ends) const;
    struct FaceCrossing;
    FaceCrossing face_crossing(int h) const;
    void propagate_window(int popped, bool may_merge, const FaceCrossing& face);
    int merge_with_siblings(int id);
    int piece_covering(int id, double x) const;
    void emit_from_vertex(int v);
    double incoming_polar_angle(int v) const;
    void seed_from_point(const SurfacePoint& p, int source_index);
    bool all_stops_settled(double key);
    void watch_stop_point(int index);

    Vec2 corner_position(int h, int vertex) const;
    Vec2 layout(int h, const SurfacePoint& p) const;
    std::vector<int> faces_around(const SurfacePoint& p) const;
    bool source_touches_face(int source_index, int f) const;
    Best best_way_to(const SurfacePoint& p) const;
    double window_value_at(const Window& w, const Vec2& p) const;
    SurfacePoint point_on_halfedge(int h, double x) const;
    class Scratch;
    void propagate_towards(const std::vector<SurfacePoint>& sources, const SurfacePoint& target,
                           double max_distance = k_infinity);
    std::vector<SurfacePoint> path_through_pseudo_sources(int v) const;

    void push_queue(double key, int item);
    void push_vertex(int v);
    double estimate_left(const Eigen::Vector3d& x) const;
    double estimate_left(const Window& w) const;
    double vertex_key(int v) const;
    bool is_settled_stop(const SurfacePoint& p) const;

    const Mesh& mesh_;
    std::vector<unsigned char> pseudo_source_;  // vertices that emit windows: saddles, boundary, zero-length edges

    // State of one propagation; reset through the touched lists so that the cost follows the explored region.
    std::vector<double> distance_;
    std::vector<Predecessor> predecessor_;  // its window ids go stale as windows are freed without keep_windows
    // Per vertex, without keep_windows: where its shortest path comes in, taken when it gets its distance, since the
    // window that gave it may be freed before the vertex emits. (With them, it is taken when the vertex emits: many
    // vertices are reached again, or never emit in a propagation that stops early.)
    std::vector<double> incoming_angle_;
    // Per vertex, without keep_windows: the pseudo-source its shortest path comes straight from (a vertex, or -1 -
    // source index), so that a path is found again leg by leg, each leg by a propagation from it alone.
    std::vector<int> origin_;
    std::vector<int> touched_vertices_;
    // Per halfedge, side by side: a window that is added reads and writes all of it, for a halfedge that the
    // wavefront reaches far from where it was.
    struct HalfedgeState {
        double queued_key = k_infinity;  // the key of its queue entry; infinity when not queued
        int first_window = -1;           // its list of windows, newest first
        int first_pending = -1;          // its windows that have not crossed its face yet
    };
    std::vector<HalfedgeState> halfedge_state_;
    // Per halfedge: a stop point lies in its face. A bit apart rather than a byte in HalfedgeState, whose padding
    // took it from 16 to 24 bytes: 100 MB more per propagation object on a T of 4M faces.
    std::vector<bool> watched_;
    std::vector<int> touched_halfedges_;
    std::vector<Window> windows_;
    /// Per window, side by side with windows_: where it stands. Apart from the windows, so that the passes that
    /// free windows read 2 bytes of each, not its cache line (the whole storage, 8 MB on a sphere of 100k faces).
    struct WindowFlags {
        unsigned char state = k_pending;  ///< pending, propagated or merged
        bool retired = false;             ///< pushed beyond the recent windows of its edge that are ever compared again
    };
    std::vector<WindowFlags> window_flags_;
    std::vector<int> merged_pieces_;           // for merged windows: a count, then the ids of the pieces
    std::vector<int> merge_scratch_;
    /// Copies of the windows that trim_by_other_windows compares a window crossing its face with: the first
    /// k_compare_lookahead of a list of its edge but itself, in the frame of its halfedge. Within a batch they
    /// change only while the batch's first windows cross, or when a merge adds a window to the list, and the batch
    /// loop copies them again then (collect_compared): walking both lists for every window read up to 8 windows,
    /// most of which do not overlap it.
    struct ComparedWindows {
        struct Entry {
            EdgeProfile profile;
            double o0, o1;
        };
        Entry entries[k_compare_lookahead];
        int count = 0;
        double lo = k_infinity, hi = -k_infinity;  // the hull of their intervals
    };
    ComparedWindows own_compared_, twin_compared_;
    /// What every window of a halfedge's batch needs of the face that it crosses, in the halfedge's frame, and of
    /// the frames of the two edges beyond: the same for the whole batch, whose divisions cost as much as a window's
    /// own did.
    struct FaceCrossing {
        double length, ax, ay;  // the halfedge's length and the apex
        int apex_vertex;
        struct Side {
            int child = -1;       // the halfedge beyond, whose face a child window crosses next; -1 if none
            double length = 0.0;  // its length
            double ex = 0.0, ey = 0.0;  // its direction, a unit vector in the halfedge's frame
        };
        Side left, right;  // beyond the edges tail→apex (origin at the tail) and apex→head (origin at the apex)
    };
    bool keep_windows_ = true;
    std::size_t windows_to_free_at_ = k_min_windows_to_free;  // without keep_windows: free once there are this many
    int lowest_retired_ = std::numeric_limits<int>::max();  // the first window retired since the last pass
    std::vector<int> moved_to_;  // scratch of free_retired_windows()
    // Without keep_windows: the halfedges whose lists or pending windows the passes that free windows must renumber,
    // that is, every one with windows but those of closed edges with none pending.
    std::vector<int> open_halfedges_;
    bool closes_edges_ = false;  // close_passed_edges() runs: without keep_windows or goals
    double popped_key_ = 0.0;    // the key of the latest queue entry popped; no later window is nearer
    // Without keep_windows: the propagation that the queries run again, kept between them so that each costs what
    // it explores, not the mesh's size. A query takes it; one that comes meanwhile (from another thread) makes its
    // own.
    mutable std::unique_ptr<Impl> scratch_;
    mutable std::mutex scratch_mutex_;
    // Items: a halfedge (>= 0) whose pending windows cross its face together, or -1 - v, a vertex that emits.
    detail::EventQueue queue_;
    std::vector<SurfacePoint> sources_;
    std::vector<StopPoint> stops_;
    std::vector<std::pair<int, int>> watches_;  // (halfedge, stop index), sorted
    double max_distance_ = k_infinity;
    std::vector<Eigen::Vector3d> goals_;  // goal-directed: the stop points' positions; empty otherwise
    std::vector<unsigned char> goal_settled_;  // per goal: its stop point is settled, so it no longer draws the search
};

ExactGeodesic::Impl::Impl(const Mesh& mesh) : mesh_(mesh) {
    const int nv = mesh.num_vertices();
    pseudo_source_.assign(nv, 0);
    for (int v = 0; v < nv; ++v) {
        bool emits = mesh.is_boundary_vertex(v) || mesh.cone_angle(v) > k_two_pi + k_flat;
        for (int h : mesh.outgoing_halfedges(v))
            if (mesh.length(h) == 0.0) emits = true;
        pseudo_source_[v] = emits;
    }
    distance_.assign(nv, k_infinity);
    queue_.resize(nv, mesh.num_halfedges());
    predecessor_.assign(nv, Predecessor{});
    incoming_angle_.assign(nv, std::numeric_limits<double>::quiet_NaN());
    origin_.assign(nv, -1);
    halfedge_state_.assign(mesh.num_halfedges(), HalfedgeState{});
    watched_.assign(mesh.num_halfedges(), false);
}

void ExactGeodesic::Impl::reset() {
    for (int v : touched_vertices_) {
        distance_[v] = k_infinity;
        predecessor_[v] = Predecessor{};
    }
    for (int h : touched_halfedges_) {
        halfedge_state_[h].first_window = -1;
        halfedge_state_[h].first_pending = -1;
        halfedge_state_[h].queued_key = k_infinity;
    }
    for (const auto& watch : watches_) watched_[watch.first] = false;
    touched_vertices_.clear();
    touched_halfedges_.clear();
    open_halfedges_.clear();
    popped_key_ = 0.0;
    windows_.clear();
    window_flags_.clear();
    windows_to_free_at_ = k_min_windows_to_free;
    lowest_retired_ = std::numeric_limits<int>::max();
    merged_pieces_.clear();
    queue_.clear();
    sources_.clear();
    stops_.clear();
    watches_.clear();
    goals_.clear();
    windows_created_before_ += stats_.windows_created;
    stats_ = PropagationStats{};
    settled_radius_ = k_infinity;
}

void ExactGeodesic::Impl::push_queue(double key, int item) {
    queue_.set(key, item);
    ++stats_.queue_pushes;
    stats_.peak_queue_size = std::max(stats_.peak_queue_size, queue_.size());
}

void ExactGeodesic::Impl::relax_vertex(int v, double distance, Predecessor predecessor) {
    if (!(distance < distance_[v])) return;
    if (distance_[v] == k_infinity) touched_vertices_.push_back(v);
    distance_[v] = distance;
    predecessor_[v] = predecessor;
    if (!keep_windows_) {
        switch (predecessor.via) {
            case Via::window: origin_[v] = windows_[predecessor.id].origin; break;
            case Via::vertex: origin_[v] = predecessor.id; break;
            case Via::source: origin_[v] = -1 - predecessor.id; break;
            case Via::none: break;
        }
    }
    if (pseudo_source_[v] && distance <= max_distance_) {
        if (!keep_windows_) incoming_angle_[v] = incoming_polar_angle(v);
        push_vertex(v);
    }
}

void ExactGeodesic::Impl::push_vertex(int v) {
    push_queue(vertex_key(v), -1 - v);
}

// Only the goals whose stop points are not settled count: the search then heads for those (a face split's three
// corners: the search stops spreading towards the nearest once it is settled). A key made before a goal was settled
// is smaller than it would be now, so every queued key stays a lower bound of any path through its item to any stop
// point not yet settled, which is all that the stop test needs.
double ExactGeodesic::Impl::estimate_left(const Eigen::Vector3d& x) const {
    if (goals_.empty()) return 0.0;
    // The square root of the least square: the same as the least square root, for one square root.
    double nearest = k_infinity;
    for (std::size_t i = 0; i < goals_.size(); ++i)
        if (!goal_settled_[i]) nearest = std::min(nearest, (goals_[i] - x).squaredNorm());
    return std::sqrt(nearest);
}

double ExactGeodesic::Impl::estimate_left(const Window& w) const {
    // The least straight-line distance from the window's part of its edge to a goal: with the window's least
    // distance, a lower bound of any path through it to a goal, since a path is never shorter than a straight line.
    if (goals_.empty()) return 0.0;
    const int h = w.halfedge;
    const double length = mesh_.length(h);
    const Eigen::Vector3d& tail = mesh_.position(mesh_.tail(h));
    const Eigen::Vector3d along = (mesh_.position(mesh_.head(h)) - tail) / length;
    double nearest = k_infinity;
    for (std::size_t i = 0; i < goals_.size(); ++i) {
        if (goal_settled_[i]) continue;
        const Eigen::Vector3d& goal = goals_[i];
        const double x = std::clamp((goal - tail).dot(along), w.b0, w.b1);
        nearest = std::min(nearest, (goal - (tail + x * along)).squaredNorm());
    }
    return std::sqrt(nearest);
}

double ExactGeodesic::Impl::vertex_key(int v) const { return distance_[v] + estimate_left(mesh_.position(v)); }

namespace {

// Where, on an edge whose end vertex sits at the origin with distance d, the path through that vertex stops beating
// the window by `slack`: the x >= 0 with sigma + |S - x| = d + slack + x. Only called when such an x exists in the
// window; NaN if rounding says otherwise.
double vertex_takeover(double sx, double sy, double sigma, double d, double slack) {
    const double k = d + slack - sigma;
    const double denominator = 2.0 * (sx + k);
    const double x = (sx * sx + sy * sy - k * k) / denominator;
    return denominator > 0.0 && k + x >= 0.0 ? x : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

// Sets `ends` to w's values at its ends as trimmed, but where w.sy == 0, which trim_by_other_windows leaves alone.
bool ExactGeodesic::Impl::trim_by_end_vertices(Window& w, detail::EndValues& ends) const {
    // |S - x| - |tail - x| never increases as x moves away from the tail, so the part where the tail's path beats
    // the window is an interval that starts at the tail; likewise for the head. Such a part cannot be on any
    // shortest path (the vertex's path is shorter, or, for a convex vertex, shorter still around it), so it goes.
    // A source on the edge line (across a zero-area face) sends its rays into the face through the one point
    // x = sx: trimming could only cut that point off by rounding.
    if (w.sy == 0.0) return true;
    const int h = w.halfedge;
    const double length = mesh_.length(h);
    const double slack = k_margin * (w.sigma + w.source().norm() + length);
    const double d_tail = distance_[mesh_.tail(h)];
    const double d_head = distance_[mesh_.head(h)];
    // The window's values at its ends, each computed once (square roots are not cheap) and again if the end moves;
    // trim_by_other_windows needs them too.
    ends = {w.value_at(w.b0), w.value_at(w.b1)};
    if (d_tail < k_infinity) {
        if (ends.at_b1 > d_tail + w.b1 + slack) return false;
        if (ends.at_b0 > d_tail + w.b0 + slack) {
            const double x = vertex_takeover(w.sx, w.sy, w.sigma, d_tail, slack);
            if (x > w.b0 && x < w.b1) {
                w.b0 = x;
                ends.at_b0 = w.value_at(x);
            }
        }
    }
    if (d_head < k_infinity) {
        if (ends.at_b0 > d_head + (length - w.b0) + slack) return false;
        if (ends.at_b1 > d_head + (length - w.b1) + slack) {
            const double y = vertex_takeover(length - w.sx, w.sy, w.sigma, d_head, slack);
            if (length - y > w.b0 && length - y < w.b1) {
                w.b1 = length - y;
                ends.at_b1 = w.value_at(w.b1);
            }
        }
    }
    return w.b0 < w.b1;
}

namespace {

// Cuts from the ends of the nonempty [w.b0, w.b1] the runs where `other` (a real path length to the edge's points,
// defined on [o0, o1]) beats w by more than `slack`. Only the ends can go: a window stays one interval, and only an
// end where `other` is already shorter: that test is cheap, the crossings are not. Returns false when nothing is
// left; otherwise `ends` holds w's values at its ends, as it did on entry.
bool trim_ends_against(Window& w, detail::EndValues& ends, const EdgeProfile& other, double o0, double o1,
                       double slack) {
    // Without branches, most of whose outcomes the processor could not predict: both values are computed, the one
    // not needed too. Where an end lies in [o0, o1], the intervals overlap, since w's is not empty.
    const bool from_start = (o0 <= w.b0) & (w.b0 < o1) & (ends.at_b0 > other.at(w.b0) + slack);
    const bool from_end = (o0 < w.b1) & (w.b1 <= o1) & (ends.at_b1 > other.at(w.b1) + slack);
    if (!(from_start | from_end)) return true;
    const EdgeProfile mine{w.sx, w.sy, w.sigma};
    const double lo = std::max(w.b0, o0), hi = std::min(w.b1, o1);
    double cuts[4] = {lo, 0.0, 0.0, 0.0};
    const int roots = profile_crossings(mine, other, lo, hi, cuts + 1);
    cuts[roots + 1] = hi;
    // Between crossings one profile stays below the other; three samples guard against a crossing that rounding hid.
    auto worse = [&](double a, double b) {
        for (double f : {0.25, 0.5, 0.75}) {
            const double x = a + f * (b - a);
            if (!(mine.at(x) > other.at(x) + slack)) return false;
        }
        return true;
    };
    double b0 = w.b0, b1 = w.b1;
    if (from_start)
        for (int i = 0; i <= roots && worse(cuts[i], cuts[i + 1]); ++i) b0 = cuts[i + 1];
    if (from_end)
        for (int i = roots; i >= 0 && worse(cuts[i], cuts[i + 1]); --i) b1 = cuts[i];
    if (!(b0 < b1)) return false;
    if (b0 != w.b0) ends.at_b0 = mine.at(b0);
    if (b1 != w.b1) ends.at_b1 = mine.at(b1);
    w.b0 = b0;
    w.b1 = b1;
    return true;
}

}  // namespace

void ExactGeodesic::Impl::collect_compared(int list, int self, double length, bool mirrored,
                                           ComparedWindows& out) const {
    out.count = 0;
    out.lo = k_infinity;
    out.hi = -k_infinity;
    if (list < 0) return;
    int looked = 0;
    for (int id = halfedge_state_[list].first_window; id >= 0 && looked < k_compare_lookahead;
         id = windows_[id].next_on_edge) {
        ++looked;  // the window itself counts: no window beyond the reach is read
        if (id == self) continue;
        const Window& other = windows_[id];
        ComparedWindows::Entry& entry = out.entries[out.count++];
        entry.profile = {mirrored ? length - other.sx : other.sx, other.sy, other.sigma};
        entry.o0 = mirrored ? length - other.b1 : other.b0;
        entry.o1 = mirrored ? length - other.b0 : other.b1;
        out.lo = std::min(out.lo, entry.o0);
        out.hi = std::max(out.hi, entry.o1);
    }
}

bool ExactGeodesic::Impl::trim_by_other_windows(Window& w, detail::EndValues& ends) const {
    // Where another window on the same edge (either side) is shorter than w, no shortest path goes through w there:
    // it could take the other window's path to the same point instead. The other window keeps its part, so coverage
    // is never lost; both must differ by more than `slack`, so that two tied windows never remove each other.
    // (Testing the paths through the apexes of the edge's two faces as well cut almost nothing: 8k windows of 1.9M
    // on the bunny, for 27% more instructions.)
    // The windows compared are those that the batch loop has copied for w (own_compared_, twin_compared_).
    if (w.sy == 0.0) return true;  // see trim_by_end_vertices
    const double scale = w.sigma + std::abs(w.sx) + std::abs(w.sy) + mesh_.length(w.halfedge);
    for (const ComparedWindows* compared : {&own_compared_, &twin_compared_}) {
        // Trimming only shrinks w, so a window whose interval misses the hull's misses every one of them.
        if (!(std::max(w.b0, compared->lo) < std::min(w.b1, compared->hi))) continue;
        for (int i = 0; i < compared->count; ++i) {
            const ComparedWindows::Entry& other = compared->entries[i];
            if (!trim_ends_against(w, ends, other.profile, other.o0, other.o1,
                                   k_margin * (scale + other.profile.sigma)))
                return false;
        }
    }
    return true;
}

void ExactGeodesic::Impl::add_window(int h, double b0, double b1, double sx, double sy, double sigma, int parent,
                                     int origin) {
    const double length = mesh_.length(h);
    if (length <= 0.0) return;
    b0 = std::max(b0, 0.0);
    b1 = std::min(b1, length);
    if (!(b0 < b1)) return;
    if (max_distance_ < k_infinity && Window::least_value(b0, b1, sx, sy, sigma) > max_distance_) return;
    const int next_on_edge = halfedge_state_[h].first_window;
    if (next_on_edge == k_closed) {  // nowhere shorter than a path through an end vertex (close_passed_edges)
        ++stats_.windows_not_made;
        return;
    }
    // A window is trimmed only when it is about to cross its face (propagate_window), once: by then the distances
    // of its end vertices and the windows it meets on its edge are nearer their last. Trimming when it was added
    // as well gave up to 30% fewer windows but cost more than it saved (bench/README.md: the 100k icosphere 1.23 ->
    // 0.82 s with the changes that came with it).
    const int id = static_cast<int>(windows_.size());
    const Window& w = windows_.emplace_back(b0, b1, sx, sy, sigma, h, parent, origin, next_on_edge,
                                            halfedge_state_[h].first_pending);
    window_flags_.emplace_back();
    if (next_on_edge < 0) {
        touched_halfedges_.push_back(h);
        if (!keep_windows_) open_halfedges_.push_back(h);
    }
    halfedge_state_[h].first_window = id;
    halfedge_state_[h].first_pending = id;
    ++stats_.windows_created;
    const double tolerance = k_cover * length;
    if (b0 <= tolerance) relax_vertex(mesh_.tail(h), w.value_at(0.0), {Via::window, id});
    if (b1 >= length - tolerance) relax_vertex(mesh_.head(h), w.value_at(length), {Via::window, id});
    if (watched_[h]) {
        auto range = std::equal_range(watches_.begin(), watches_.end(), std::make_pair(h, -1),
                                      [](const auto& a, const auto& b) { return a.first < b.first; });
        for (auto it = range.first; it != range.second; ++it) {
            StopPoint& stop = stops_[it->second];
            stop.window_estimate = std::min(stop.window_estimate, window_value_at(w, layout(h, stop.point)));
        }
    }
    // The estimate adds to the bound: where the bound alone is no lower than the halfedge's queued key, so is the
    // key, and the estimate (a loop over the goals) is not needed.
    const double bound = Window::least_value(b0, b1, sx, sy, sigma);
    if (!(bound < halfedge_state_[h].queued_key)) return;
    const double key = bound + estimate_left(w);
    if (key < halfedge_state_[h].queued_key) {
        halfedge_state_[h].queued_key = key;
        push_queue(key, h);
    }
}

void ExactGeodesic::Impl::retire_beyond_reach(int h) {
    // After a halfedge's windows have crossed: the windows of its list beyond its k_list_reach newest are never read
    // again. Lists only grow at the front, so those beyond the first window retired before are retired already;
    // each window is marked once, and the walk reads what trimming has just read (a walk at every new window
    // read three windows that had left the cache: 6% of the time).
    int id = halfedge_state_[h].first_window;
    for (int i = 0; i < k_list_reach && id >= 0; ++i) id = windows_[id].next_on_edge;
    for (; id >= 0 && !window_flags_[id].retired; id = windows_[id].next_on_edge) {
        window_flags_[id].retired = true;
        lowest_retired_ = std::min(lowest_retired_, id);
    }
}

bool ExactGeodesic::Impl::wavefront_has_passed(int h) const {
    // Every point x of the edge has a path through an end vertex of length at most U = (d_tail + d_head + L) / 2,
    // the most that min(d_tail + x, d_head + L - x) reaches. Once both distances are final (at most the popped key,
    // which no later window goes below) and the popped key is beyond U, every window still to come, or still to
    // cross, is longer everywhere on the edge than such a path: trim_by_end_vertices would remove it whole, since
    // the margins here exceed its slack (k_margin times at most the window's value plus twice L) and its cover of
    // the end vertices (k_cover L). The key is such a bound only up to rounding: a window that ends within k_cover
    // of a vertex gives it a distance below its own least value by up to k_cover times its edge, and a saddle there
    // emits from that distance (keys fell by up to 2.3e-10 relative on a box of 1e5 by 1 by 1), hence k_close_margin.
    const double d_tail = distance_[mesh_.tail(h)];
    const double d_head = distance_[mesh_.head(h)];
    if (!(d_tail <= popped_key_ && d_head <= popped_key_)) return false;
    const double length = mesh_.length(h);
    const double through_end = 0.5 * (d_tail + d_head + length);
    return popped_key_ * (1.0 - k_close_margin) > through_end + 8.0 * (k_margin + k_cover) * length;
}

void ExactGeodesic::Impl::close_edge(int h) {
    // Its windows are read again only to trim windows that come to the edge later, and none is kept from now on:
    // free_retired_windows() frees them all once they have crossed. They may lie anywhere in the storage, so the
    // pass reads it all, in order, which costs less than walking the edge's list to mark them (a cache miss each).
    for (int side : {h, mesh_.twin(h)}) {
        if (side < 0) continue;
        if (halfedge_state_[side].first_window == -1) touched_halfedges_.push_back(side);  // for reset()
        halfedge_state_[side].first_window = k_closed;
    }
    lowest_retired_ = 0;
}

void ExactGeodesic::Impl::close_passed_edges() {
    // Without this, every edge behind the wavefront kept its k_list_reach newest windows to the end: storage that
    // grew with the area swept (2.5 windows a halfedge, 60 MB on a sphere of 100k faces), not with the wavefront.
    for (int h : open_halfedges_)
        if (halfedge_state_[h].first_window != k_closed && wavefront_has_passed(h)) close_edge(h);
}

void ExactGeodesic::Impl::free_retired_windows() {
    // A retired window that has crossed its face is read again only by the queries after the propagation, which
    // keep_windows = false gives up. The others move down, in order, since the comparisons of trim_by_other_windows
    // go by the order of the ids. Below the first window retired since the last pass, none moves; and since lists
    // link each window to older ones, none of those links changes either.
    if (closes_edges_) close_passed_edges();
    const int size = static_cast<int>(windows_.size());
    const int start = std::min(lowest_retired_, size);
    lowest_retired_ = std::numeric_limits<int>::max();
    moved_to_.assign(size - start, -1);
    int kept = start;
    for (int id = start; id < size; ++id) {
        const WindowFlags flags = window_flags_[id];
        if (flags.retired && flags.state != k_pending) continue;  // most are: their windows are not read
        const Window& w = windows_[id];
        const bool freed = flags.retired || halfedge_state_[w.halfedge].first_window == k_closed;
        if (freed && flags.state != k_pending) continue;
        if (freed) lowest_retired_ = std::min(lowest_retired_, kept);  // to be freed once it has crossed
        moved_to_[id - start] = kept;
        if (kept != id) {
            windows_[kept] = w;
            window_flags_[kept] = flags;
        }
        ++kept;
    }
    if (kept < size) {
        windows_.erase(windows_.begin() + kept, windows_.end());
        window_flags_.resize(kept);
        stats_.windows_freed += static_cast<std::size_t>(size - kept);
        auto moved = [&](int id) { return id < start ? id : moved_to_[id - start]; };
        for (int id = start; id < kept; ++id) {
            windows_[id].next_on_edge = moved(windows_[id].next_on_edge);  // -1 past the reach: never walked
            windows_[id].next_pending = moved(windows_[id].next_pending);
        }
        for (int h : open_halfedges_) {
            HalfedgeState& state = halfedge_state_[h];
            if (state.first_window >= 0) state.first_window = moved(state.first_window);
            state.first_pending = moved(state.first_pending);
        }
    }
    // A closed edge's halfedge needs renumbering only while windows of it are still to cross.
    auto done = [this](int h) {
        return halfedge_state_[h].first_window == k_closed && halfedge_state_[h].first_pending < 0;
    };
    open_halfedges_.erase(std::remove_if(open_halfedges_.begin(), open_halfedges_.end(), done), open_halfedges_.end());
    // Free again when at least half as many windows have come as are left now, so that the work of freeing stays
    // proportional to the windows made; the storage grows by half when that does not fit, and not at every pass,
    // since a new block is copied into and its pages are first touched, which costs more than the pass itself.
    const std::size_t wanted = std::max(k_min_windows_to_free, windows_.size() + windows_.size() / 2);
    const std::size_t room = wanted + wanted / 16;  // for the batch that crosses the threshold
    if (room > windows_.capacity()) {
        windows_.reserve(std::max(room, windows_.capacity() + windows_.capacity() / 2));
        window_flags_.reserve(windows_.capacity());
    }
    windows_to_free_at_ = windows_.capacity() - windows_.capacity() / 17;
}

int ExactGeodesic::Impl::merge_with_siblings(int id) {
    // The same ray family reaches an edge in fragments, one per path of faces. Merging the pending fragments
    // before crossing the face keeps the window count near one per family and edge.
    // The window's values one at a time: trimming has just stored some of them (see propagate_window).
    const Window& w = windows_[id];
    const double sx = w.sx, sy = w.sy, sigma = w.sigma;
    const int h = w.halfedge, origin = w.origin, parent = w.parent;
    const double length = mesh_.length(h);
    const double source_tolerance = k_same_source * (length + std::sqrt(sx * sx + sy * sy) + sigma);
    const double gap_tolerance = k_cover * length;
    double b0 = w.b0, b1 = w.b1;
    std::vector<int>& pieces = merge_scratch_;
    pieces.assign(1, id);
    // Fragments of one family arrive close together in time, so they sit near the front of the edge's list;
    // a bounded look keeps the cost constant on edges that many families cross.
    int looked = 0;
    for (int s = halfedge_state_[h].first_window; s >= 0 && looked < k_merge_lookahead;
         s = windows_[s].next_on_edge) {
        ++looked;
        if (window_flags_[s].state != k_pending || s == id) continue;
        const Window& other = windows_[s];
        if (other.origin != origin || std::abs(other.sigma - sigma) > source_tolerance) continue;
        // Most windows of one origin are other unfoldings of it, far apart: a square root is spared for those.
        const double apart_x = other.sx - sx, apart_y = other.sy - sy;
        if (std::max(std::abs(apart_x), std::abs(apart_y)) > 2.0 * source_tolerance ||
            std::sqrt(apart_x * apart_x + apart_y * apart_y) > source_tolerance)
            continue;
        if (other.b0 > b1 + gap_tolerance || other.b1 < b0 - gap_tolerance) continue;
        window_flags_[s].state = k_merged;
        pieces.push_back(s);
        b0 = std::min(b0, other.b0);
        b1 = std::max(b1, other.b1);
    }
    if (pieces.size() == 1) return id;
    const int merged = static_cast<int>(windows_.size());
    // It is the newest window of its edge and never pending: it crosses now, in place of its pieces.
    Window& m = windows_.emplace_back(b0, b1, sx, sy, sigma, h, parent, origin, halfedge_state_[h].first_window, -1);
    window_flags_.push_back({k_propagated, false});
    if (keep_windows_) {  // the pieces, for tracing paths back through them
        m.parent = -2 - static_cast<int>(merged_pieces_.size());
        merged_pieces_.push_back(static_cast<int>(pieces.size()));
        merged_pieces_.insert(merged_pieces_.end(), pieces.begin(), pieces.end());
    }
    halfedge_state_[h].first_window = merged;
    stats_.windows_merged += pieces.size() - 1;
    return merged;
}

int ExactGeodesic::Impl::piece_covering(int id, double x) const {
    const int offset = -2 - windows_[id].parent;
    const int count = merged_pieces_[offset];
    int best = merged_pieces_[offset + 1];
    double best_gap = k_infinity;
    for (int i = 0; i < count; ++i) {
        const int piece = merged_pieces_[offset + 1 + i];
        const Window& p = windows_[piece];
        const double gap = std::max({p.b0 - x, x - p.b1, 0.0});
        if (gap < best_gap) {
            best_gap = gap;
            best = piece;
        }
    }
    return best;
}

ExactGeodesic::Impl::FaceCrossing ExactGeodesic::Impl::face_crossing(int h) const {
    FaceCrossing face;
    face.length = mesh_.length(h);
    face.ax = mesh_.apex(h).x();
    face.ay = mesh_.apex(h).y();
    face.apex_vertex = mesh_.tail(Mesh::prev(h));
    const double apex_norm = mesh_.length(Mesh::prev(h));  // the length of the apex vector, and of the edge
    const int left = mesh_.twin(Mesh::prev(h));
    if (left >= 0 && apex_norm > 0.0) face.left = {left, apex_norm, face.ax / apex_norm, face.ay / apex_norm};
    const double along_norm = mesh_.length(Mesh::next(h));
    const int right = mesh_.twin(Mesh::next(h));
    if (right >= 0 && along_norm > 0.0)
        face.right = {right, along_norm, (face.length - face.ax) / along_norm, (0.0 - face.ay) / along_norm};
    return face;
}

void ExactGeodesic::Impl::propagate_window(int popped, bool may_merge, const FaceCrossing& face) {
    if (window_flags_[popped].state != k_pending) return;  // merged into another window
    window_flags_[popped].state = k_propagated;
    detail::EndValues ends;
    if (!trim_by_end_vertices(windows_[popped], ends) || !trim_by_other_windows(windows_[popped], ends)) {
        ++stats_.windows_pruned;
        return;
    }
    const int id = may_merge ? merge_with_siblings(popped) : popped;
    // Copies, since adding children may reallocate windows_; and one value at a time, since trimming has just
    // stored some of them and a copy of the whole window, loaded in wider pieces, would wait for those stores.
    const Window& crossing = windows_[id];
    const double b0 = crossing.b0, b1 = crossing.b1, sx = crossing.sx, sy = crossing.sy, sigma = crossing.sigma;
    const int origin = crossing.origin;
    ++stats_.windows_propagated;
    // A source beyond the edge line sends no ray into the face. One on the line (a vertex emitting across a
    // zero-area face) sends rays along the edge, which reached the end vertices when the window was added, and,
    // when it lies inside the window, rays into the whole face too: the general case below covers those.
    if (sy > 0.0 || (sy == 0.0 && !(sx >= b0 && sx <= b1))) return;

    // In scalars, as the frames' points are: 2-vectors built here went through memory and stalled when loaded back.
    const double length = face.length, ax = face.ax, ay = face.ay;

    // The ray from S through the apex crosses the edge at x_apex: rays left of it reach the edge tail→apex, rays
    // right of it the edge apex→head.
    const double x_apex = sx + (ax - sx) * (-sy) / (ay - sy);
    // x_apex carries the rounding of S, which was unfolded from face to face: it is relative to S's distance, not
    // to the edge. Where the ray runs exactly through an end vertex and on along an edge, as on a thin cylinder
    // whose rows of needles line up with a far source, it misses [b0, b1] by more than k_cover times a short edge
    // (1.3e-14 on an edge of 8.7e-3 with S 4.7 away), and so does the ray beyond that vertex: neither window gave
    // the apex a distance.
    const double tolerance = k_cover * (length + std::abs(sx) + std::abs(sy));
    if (x_apex >= b0 - tolerance && x_apex <= b1 + tolerance) {
        const double dx = ax - sx, dy = ay - sy;
        relax_vertex(face.apex_vertex, sigma + std::sqrt(dx * dx + dy * dy), {Via::window, id});
    }

    if (b0 < x_apex && face.left.child >= 0) {  // child on the edge tail→apex, seen from the neighbour across it
        const FaceCrossing::Side& left = face.left;  // the child's frame: origin at the tail, x along the edge
        const double hi = std::min(b1, x_apex);
        double u0 = b0 == 0.0 ? 0.0 : detail::ray_crossing(sx, sy, b0, 0.0, 0.0, left.ex, left.ey);
        double u1 = hi == x_apex ? left.length : detail::ray_crossing(sx, sy, hi, 0.0, 0.0, left.ex, left.ey);
        if (!std::isfinite(u0)) u0 = 0.0;
        if (!std::isfinite(u1)) u1 = left.length;
        const detail::FramePoint source = detail::to_frame(sx, sy, 0.0, 0.0, left.ex, left.ey);
        add_window(left.child, u0, u1, source.x, source.y, sigma, id, origin);
    }
    if (x_apex < b1 && face.right.child >= 0) {  // child on the edge apex→head
        const FaceCrossing::Side& right = face.right;  // the child's frame: origin at the apex, x towards the head
        const double lo = std::max(b0, x_apex);
        double v0 = lo == x_apex ? 0.0 : detail::ray_crossing(sx, sy, lo, ax, ay, right.ex, right.ey);
        double v1 = b1 == length ? right.length : detail::ray_crossing(sx, sy, b1, ax, ay, right.ex, right.ey);
        if (!std::isfinite(v0)) v0 = 0.0;
        if (!std::isfinite(v1)) v1 = right.length;
        const detail::FramePoint source = detail::to_frame(sx, sy, ax, ay, right.ex, right.ey);
        add_window(right.child, v0, v1, source.x, source.y, sigma, id, origin);
    }
}

double ExactGeodesic::Impl::incoming_polar_angle(int v) const {
    constexpr double unknown = std::numeric_limits<double>::quiet_NaN();
    if (!mesh_.is_manifold_vertex(v) || mesh_.is_boundary_vertex(v)) return unknown;
    const Predecessor predecessor = predecessor_[v];
    if (predecessor.via == Via::vertex) {
        const int h = mesh_.find_halfedge(v, predecessor.id);
        return h >= 0 ? mesh_.polar_angle(h) : unknown;
    }
    if (predecessor.via != Via::window) return unknown;
    // The direction from v back towards the window's pseudo-source, in v's polar angles. The frame of the window's
    // halfedge keeps orientation, so counter-clockwise there is counter-clockwise on the surface.
    const Window& w = windows_[predecessor.id];
    const int h = w.halfedge;
    const Vec2 source = w.source();
    auto angle_from = [](const Vec2& from, const Vec2& to) {
        return std::atan2(detail::cross(from, to), from.dot(to));
    };
    double angle;
    if (v == mesh_.tail(h)) {  // clockwise from the direction of h
        angle = mesh_.polar_angle(h) - std::clamp(-angle_from(Vec2(1.0, 0.0), source), 0.0, k_pi);
    } else if (v == mesh_.head(h)) {  // counter-clockwise beyond the direction head -> tail
        const int n = Mesh::next(h);
        angle = mesh_.polar_angle(n) + mesh_.corner_angle(n) +
                std::clamp(angle_from(Vec2(-1.0, 0.0), source - Vec2(mesh_.length(h), 0.0)), 0.0, k_pi);
    } else {  // v is the apex: inside its corner, counter-clockwise from the direction apex -> tail
        const int p = Mesh::prev(h);
        const Vec2 apex = mesh_.apex(h);
        angle = mesh_.polar_angle(p) + std::clamp(angle_from(-apex, source - apex), 0.0, mesh_.corner_angle(p));
    }
    const double cone = mesh_.cone_angle(v);
    angle = angle_remainder(angle, cone);
    return angle < 0.0 ? angle + cone : angle;
}

void ExactGeodesic::Impl::emit_from_vertex(int v) {
    ++stats_.vertex_emissions;
    const double d = distance_[v];
    // A geodesic through v leaves it at least π away from where it came in, on both sides (MMP): emit only into
    // that shadow, widened by k_shadow_slack to cover rounding at its rims. Sources and boundary vertices emit all
    // around.
    const double incoming = keep_windows_ ? incoming_polar_angle(v) : incoming_angle_[v];
    const double cone = mesh_.cone_angle(v);
    const bool everywhere = std::isnan(incoming);
    const double shadow_start = incoming + k_pi - k_shadow_slack;
    const double shadow_length = cone - 2.0 * k_pi + 2.0 * k_shadow_slack;
    if (!everywhere && shadow_length <= 0.0) return;

    // Along an edge too, only inside the shadow: outside it the path along the edge bends at v by less than π,
    // so it is not a geodesic, and the geodesic that passes beside v (which windows carry) is shorter, if only by
    // rounding; taking the edge would leave a polyline that is not straight.
    auto in_shadow = [&](double angle) {
        if (everywhere) return true;
        double offset = angle_remainder(angle - shadow_start, cone);
        if (offset < 0.0) offset += cone;
        return offset <= shadow_length;
    };
    for (int h : mesh_.outgoing_halfedges(v)) {
        if (in_shadow(mesh_.polar_angle(h))) relax_vertex(mesh_.head(h), d + mesh_.length(h), {Via::vertex, v});
        if (in_shadow(mesh_.polar_angle(h) + mesh_.corner_angle(h)))
            relax_vertex(mesh_.tail(Mesh::prev(h)), d + mesh_.length(Mesh::prev(h)), {Via::vertex, v});
        const int opposite = Mesh::next(h);
        const int beyond = mesh_.twin(opposite);
        if (beyond < 0) continue;
        const double corner = mesh_.corner_angle(h);
        double a0 = 0.0, a1 = corner;  // the part of the corner to emit into, counter-clockwise from h
        if (!everywhere) {
            // Intersect [polar(h), polar(h) + corner] with the shadow, which may wrap around the cone angle.
            double start = angle_remainder(shadow_start - mesh_.polar_angle(h), cone);
            if (start < 0.0) start += cone;
            if (start > corner && start + shadow_length < cone) continue;
            if (start <= corner) {
                a0 = start;
                a1 = std::min(corner, start + shadow_length);
            } else {
                a0 = 0.0;
                a1 = std::min(corner, start + shadow_length - cone);
            }
            if (start <= corner && start + shadow_length > cone) a0 = 0.0;  // the shadow also wraps into it
            if (!(a0 < a1)) continue;
        }
        // The opposite edge's frame: tail(opposite) = head(h) at the origin, v at its apex. Angles turn from the
        // direction v -> origin towards v -> (L, 0).
        const double length = mesh_.length(opposite);
        const Vec2 apex = mesh_.apex(opposite);
        const double scale = mesh_.length(beyond) / length;
        if (apex.y() == 0.0) {
            // A zero-area face with v inside its opposite edge: every direction of v's corner (π) leaves through
            // that edge at v's own position, so v emits from that point into the face beyond, all of it (more
            // than the shadow is only more work, never wrong).
            if (apex.x() > 0.0 && apex.x() < length)
                add_window(beyond, 0.0, mesh_.length(beyond), length - apex.x(), 0.0, d, -1, v);
            continue;
        }
        auto hit = [&](double angle) {
            const Vec2 toward = -apex;
            const double c = std::cos(angle), s = std::sin(angle);
            const Vec2 direction(c * toward.x() - s * toward.y(), s * toward.x() + c * toward.y());
            const double x = apex.x() + direction.x() * (-apex.y()) / direction.y();
            return std::isfinite(x) && direction.y() < 0.0 ? std::clamp(x, 0.0, length) : length;
        };
        const double x0 = a0 == 0.0 ? 0.0 : hit(a0);
        const double x1 = a1 == corner ? length : hit(a1);
        add_window(beyond, (length - x1) * scale, (length - x0) * scale, length - apex.x(), -apex.y(), d, -1, v);
    }
}

void ExactGeodesic::Impl::seed_from_point(const SurfacePoint& p, int source_index) {
    const Eigen::Vector3d position = mesh_.point(p);
    for (int f : faces_around(p)) {
        for (int i = 0; i < 3; ++i) {
            const int h = 3 * f + i;
            relax_vertex(mesh_.tail(h), (mesh_.position(mesh_.tail(h)) - position).norm(),
                         {Via::source, source_index});
            const int beyond = mesh_.twin(h);
            if (beyond < 0) continue;
            const bool own_edge = p.kind == PointKind::edge &&
                                  ((mesh_.tail(h) == p.edge_v0 && mesh_.head(h) == p.edge_v1) ||
                                   (mesh_.tail(h) == p.edge_v1 && mesh_.head(h) == p.edge_v0));
            if (own_edge) continue;
            const Vec2 s = layout(h, p);
            add_window(beyond, 0.0, mesh_.length(beyond), mesh_.length(h) - s.x(), -s.y(), 0.0, -1, -1 - source_index);
        }
    }
}

Vec2 ExactGeodesic::Impl::corner_position(int h, int vertex) const {
    if (vertex == mesh_.tail(h)) return Vec2::Zero();
    if (vertex == mesh_.head(h)) return Vec2(mesh_.length(h), 0.0);
    return mesh_.apex(h);
}

Vec2 ExactGeodesic::Impl::layout(int h, const SurfacePoint& p) const {
    switch (p.kind) {
        case PointKind::vertex: return corner_position(h, p.vertex);
        case PointKind::edge: return (1.0 - p.t) * corner_position(h, p.edge_v0) + p.t * corner_position(h, p.edge_v1);
        case PointKind::face: {
            const int i = h % 3;
            return p.bary[(i + 1) % 3] * Vec2(mesh_.length(h), 0.0) + p.bary[(i + 2) % 3] * mesh_.apex(h);
        }
    }
    return Vec2::Zero();
}

std::vector<int> ExactGeodesic::Impl::faces_around(const SurfacePoint& p) const {
    std::vector<int> faces;
    switch (p.kind) {
        case PointKind::vertex:
            for (int h : mesh_.outgoing_halfedges(p.vertex)) faces.push_back(Mesh::face_of(h));
            break;
        case PointKind::edge:
            for (int h : {mesh_.find_halfedge(p.edge_v0, p.edge_v1), mesh_.find_halfedge(p.edge_v1, p.edge_v0)})
                if (h >= 0) faces.push_back(Mesh::face_of(h));
            break;
        case PointKind::face: faces.push_back(p.face); break;
    }
    return faces;
}

bool ExactGeodesic::Impl::source_touches_face(int source_index, int f) const {
    const SurfacePoint& s = sources_[source_index];
    const auto& t = mesh_.triangle(f);
    auto in_face = [&](int v) { return v == t[0] || v == t[1] || v == t[2]; };
    switch (s.kind) {
        case PointKind::vertex: return in_face(s.vertex);
        case PointKind::edge: return in_face(s.edge_v0) && in_face(s.edge_v1);
        case PointKind::face: return s.face == f;
    }
    return false;
}

double ExactGeodesic::Impl::window_value_at(const Window& w, const Vec2& p) const {
    const double x = w.crossing_of(p);
    const double tolerance = k_cover * mesh_.length(w.halfedge);
    if (!(x >= w.b0 - tolerance && x <= w.b1 + tolerance)) return k_infinity;
    return w.distance_to(p);
}

ExactGeodesic::Impl::Best ExactGeodesic::Impl::best_way_to(const SurfacePoint& p) const {
    Best best;
    if (p.kind == PointKind::vertex) {
        best.distance = distance_[p.vertex];
        best.via = Via::vertex;
        best.id = p.vertex;
        return best;
    }
    const Eigen::Vector3d position = mesh_.point(p);
    for (int f : faces_around(p)) {
        for (int i = 0; i < 3; ++i) {
            const int h = 3 * f + i;
            const int v = mesh_.tail(h);
            const double through_vertex = distance_[v] + (mesh_.position(v) - position).norm();
            if (through_vertex < best.distance) best = Best{through_vertex, Via::vertex, v, Vec2::Zero()};
            const Vec2 q = layout(h, p);
            for (int id = halfedge_state_[h].first_window; id >= 0; id = windows_[id].next_on_edge) {
                const double d = window_value_at(windows_[id], q);
                if (d < best.distance) best = Best{d, Via::window, id, q};
            }
        }
        for (int s = 0; s < static_cast<int>(sources_.size()); ++s) {
            if (!source_touches_face(s, f)) continue;
            const double d = (mesh_.point(sources_[s]) - position).norm();
            if (d < best.distance) best = Best{d, Via::source, s, Vec2::Zero()};
        }
    }
    return best;
}

void ExactGeodesic::Impl::watch_stop_point(int index) {
    StopPoint& stop = stops_[index];
    const SurfacePoint& p = stop.point;
    if (p.kind == PointKind::vertex) return;  // its distance is always current
    // What all_stops_settled() needs besides the windows, worked out once rather than at every pop.
    const Eigen::Vector3d position = mesh_.point(p);
    for (int f : faces_around(p)) {
        for (int i = 0; i < 3; ++i) {
            watches_.emplace_back(3 * f + i, index);
            watched_[3 * f + i] = true;
            const int v = mesh_.triangle(f)[i];
            stop.corners.emplace_back(v, (mesh_.position(v) - position).norm());
        }
        for (int s = 0; s < static_cast<int>(sources_.size()); ++s)
            if (source_touches_face(s, f))
                stop.source_distance = std::min(stop.source_distance, (mesh_.point(sources_[s]) - position).norm());
    }
}

bool ExactGeodesic::Impl::all_stops_settled(double key) {
    // Every pending window gives at least `key`, so a stop point whose best distance is within it is final.
    bool all = true;
    for (StopPoint& stop : stops_) {
        if (stop.settled) continue;
        double estimate;
        if (stop.point.kind == PointKind::vertex) {
            estimate = distance_[stop.point.vertex];
        } else {
            estimate = std::min(stop.window_estimate, stop.source_distance);
            for (const auto& [v, straight] : stop.corners) estimate = std::min(estimate, distance_[v] + straight);
        }
        stop.settled = estimate <= key;
        if (stop.settled && !goals_.empty()) goal_settled_[static_cast<std::size_t>(&stop - stops_.data())] = 1;
        all = all && stop.settled;
    }
    return all;
}

void ExactGeodesic::Impl::propagate(const std::vector<SurfacePoint>& sources, const PropagationOptions& options) {
    if (sources.empty()) throw InvalidInput("propagation needs at least one source");
    if (!(options.max_distance >= 0.0)) throw InvalidInput("max_distance must be non-negative");
    std::vector<SurfacePoint> canonical_sources;
    for (const SurfacePoint& s : sources) canonical_sources.push_back(mesh_.canonical(s));
    std::vector<SurfacePoint> stop_points;
    for (const SurfacePoint& s : options.stop_points) stop_points.push_back(mesh_.canonical(s));

    reset();
    // Storage that kept every window of an earlier propagation would make this one free nothing for long.
    if (keep_windows_ && !options.keep_windows) {
        windows_ = std::vector<Window>();
        window_flags_ = std::vector<WindowFlags>();
        merged_pieces_ = std::vector<int>();
    }
    sources_ = std::move(canonical_sources);
    max_distance_ = options.max_distance;
    keep_windows_ = options.keep_windows;
    for (const SurfacePoint& p : stop_points) stops_.emplace_back().point = p;
    for (int i = 0; i < static_cast<int>(stops_.size()); ++i) watch_stop_point(i);
    std::sort(watches_.begin(), watches_.end());
    if (options.goal_directed && !std::isfinite(max_distance_))
        for (const StopPoint& stop : stops_) goals_.push_back(mesh_.point(stop.point));
    goal_settled_.assign(goals_.size(), 0);
    // A goal-directed key adds the distance left to a goal, so it bounds no window's distance: closing edges needs
    // keys that do. (A stop point's estimate loses nothing: a window not made is longer than its corners' paths.)
    closes_edges_ = !keep_windows_ && goals_.empty();

    for (int k = 0; k < static_cast<int>(sources_.size()); ++k) {
        const SurfacePoint& s = sources_[k];
        if (s.kind == PointKind::vertex) {
            relax_vertex(s.vertex, 0.0, {Via::source, k});
            if (!pseudo_source_[s.vertex]) push_vertex(s.vertex);
        } else {
            seed_from_point(s, k);
        }
    }

    while (!queue_.empty()) {
        if (!keep_windows_ && windows_.size() >= windows_to_free_at_) free_retired_windows();
        const auto [key, item] = queue_.pop();
        popped_key_ = key;
        ++stats_.queue_pops;
        // The windows of the next halfedge to pop have waited since they were made, so they are out of cache:
        // fetch the first while this item is processed.
        // Its face's records too, which its first window reads at once.
        if (!queue_.empty() && queue_.top_item() >= 0) {
            const int top = queue_.top_item();
            prefetch(&mesh_.apex(Mesh::prev(top)));
            prefetch(&mesh_.apex(Mesh::next(top)));
            if (halfedge_state_[top].first_pending >= 0) prefetch(&windows_[halfedge_state_[top].first_pending]);
        }
        if (goals_.empty() && key > max_distance_) {  // a goal-directed key bounds more than the distance
            stats_.stopped_early = true;
            break;
        }
        if (!stops_.empty() && all_stops_settled(key)) {
            stats_.stopped_early = true;
            settled_radius_ = goals_.empty() ? key : 0.0;
            break;
        }
        if (item >= 0) {
            // All the pending windows of the halfedge cross its face now, not only the nearest (the batching of
            // VTP, Qin et al. 2016). The queue's least key is still a lower bound of every pending window, so the
            // stop tests above stay exact; and the windows of one face and of the edges around it are processed
            // while they are in cache, with one queue entry for several windows.
            const int h = item;
            halfedge_state_[h].queued_key = k_infinity;
            int id = halfedge_state_[h].first_pending;
            halfedge_state_[h].first_pending = -1;
            // While they cross, the halfedge's list starts with the windows merged meanwhile, then this batch,
            // newest first: nothing else comes to it. So the only windows that one can merge with, the pending
            // ones among the k_merge_lookahead first of the list, are those after it in the batch, and there are
            // none from the list's k_merge_lookahead - 1st place on; most windows of a batch are there (the search
            // took 11% of the instructions on a noisy sphere, for 1 merge in 1000 windows).
            int place = 0;  // in the halfedge's list
            // The halfedges that the batch's children go to, read first by the first child, which otherwise waited.
            // (A halfedge's record, its length among them, lies in one cache line with its apex.)
            for (int side : {Mesh::prev(h), Mesh::next(h)}) {
                const int child = mesh_.twin(side);
                if (child < 0) continue;
                prefetch(&mesh_.apex(child));
                prefetch(&halfedge_state_[child]);
            }
            const FaceCrossing face = face_crossing(h);
            const double length = face.length;
            // Nothing comes to the twin's list meanwhile. The halfedge's own list changes at its front only: its
            // first windows are trimmed as they cross, and a merged window goes before them. So from the place
            // after the first k_compare_lookahead on, the windows compared stay the same until a merge.
            collect_compared(mesh_.twin(h), -1, length, true, twin_compared_);
            int compared_front = -1;
            while (id >= 0) {
                const int next = windows_[id].next_pending;
                const int first = halfedge_state_[h].first_window;
                if (place <= k_compare_lookahead || first != compared_front) {
                    collect_compared(h, id, length, false, own_compared_);
                    compared_front = first;
                }
                propagate_window(id, next >= 0 && place + 1 < k_merge_lookahead, face);
                place += halfedge_state_[h].first_window == first ? 1 : 2;  // a merged window came first
                id = next;
            }
            if (!keep_windows_) retire_beyond_reach(h);
        } else {
            emit_from_vertex(-1 - item);
        }
    }
    if (!stats_.stopped_early && !stops_.empty()) all_stops_settled(k_infinity);
    if (std::isfinite(max_distance_)) settled_radius_ = std::min(settled_radius_, max_distance_);
    stats_.window_bytes = windows_.capacity() * sizeof(Window) + window_flags_.capacity() * sizeof(WindowFlags) +
                          merged_pieces_.capacity() * sizeof(int);
    if (!keep_windows_) {  // nothing reads them any more; the storage stays for the next propagation
        windows_.clear();
        window_flags_.clear();
    }
}

bool ExactGeodesic::Impl::is_settled_stop(const SurfacePoint& p) const {
    return std::any_of(stops_.begin(), stops_.end(),
                       [&p](const StopPoint& stop) { return stop.settled && stop.point == p; });
}

double ExactGeodesic::Impl::vertex_distance(int v) const {
    const double d = distance_[v];
    return d <= settled_radius_ || is_settled_stop(SurfacePoint::at_vertex(v)) ? d : k_infinity;
}

/// The owner's scratch propagation for the length of one query, or a new one when another query holds it.
class ExactGeodesic::Impl::Scratch {
public:
    explicit Scratch(const Impl& owner) : owner_(owner) {
        {
            std::lock_guard<std::mutex> lock(owner.scratch_mutex_);
            impl_ = std::move(owner.scratch_);
        }
        if (!impl_) impl_ = std::make_unique<Impl>(owner.mesh_);
    }
    ~Scratch() {
        impl_->windows_ = std::vector<Window>();  // memory for the wavefront only, between queries too
        impl_->window_flags_ = std::vector<WindowFlags>();
        std::lock_guard<std::mutex> lock(owner_.scratch_mutex_);
        if (!owner_.scratch_) owner_.scratch_ = std::move(impl_);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    Impl* operator->() const { return impl_.get(); }

private:
    const Impl& owner_;
    std::unique_ptr<Impl> impl_;
};

void ExactGeodesic::Impl::propagate_towards(const std::vector<SurfacePoint>& sources, const SurfacePoint& target,
                                            double max_distance) {
    // Without keep_windows the windows are gone: a propagation that stops at the target, its only goal, finds them
    // again, exactly, over a region that grows with the target's distance from `sources`, not with the mesh.
    PropagationOptions options;
    options.max_distance = max_distance;
    options.stop_points = {target};
    options.goal_directed = true;
    propagate(sources, options);
}

std::vector<SurfacePoint> ExactGeodesic::Impl::path_through_pseudo_sources(int v) const {
    // A vertex's shortest path comes straight (through no vertex) from its pseudo-source o, and o's from its own, back
    // to a source. The shortest path from o to v alone is as long as that leg (a shorter one would make v nearer),
    // so each leg is found by a propagation from its pseudo-source only, which ends near it on most real meshes.
    std::vector<int> chain{v};
    while (origin_[chain.back()] >= 0) {
        chain.push_back(origin_[chain.back()]);
        if (chain.size() > touched_vertices_.size() + 1)
            throw NumericalError("shortest path could not be traced back to a source");
    }
    const SurfacePoint& source = sources_[-1 - origin_[chain.back()]];
    const Scratch scratch(*this);
    std::vector<SurfacePoint> path{source};
    for (std::size_t i = chain.size(); i-- > 0;) {
        const SurfacePoint from = path.back(), to = SurfacePoint::at_vertex(chain[i]);
        if (from == to) continue;  // v is the source
        scratch->propagate_towards({from}, to);
        const std::vector<SurfacePoint> leg = scratch->shortest_path(to);
        if (leg.empty()) throw NumericalError("shortest path could not be traced back to a source");
        path.insert(path.end(), leg.begin() + 1, leg.end());
    }
    return path;
}

double ExactGeodesic::Impl::distance(const SurfacePoint& raw) const {
    const SurfacePoint p = mesh_.canonical(raw);
    double d;
    if (keep_windows_ || p.kind == PointKind::vertex) {
        d = best_way_to(p).distance;
    } else {
        const Scratch scratch(*this);
        scratch->propagate_towards(sources_, p, max_distance_);
        d = scratch->best_way_to(p).distance;
    }
    return d <= settled_radius_ || is_settled_stop(p) ? d : k_infinity;
}

SurfacePoint ExactGeodesic::Impl::point_on_halfedge(int h, double x) const {
    // A crossing that rounding leaves a hair away from a vertex is a passage through that vertex (DESIGN.md §1:
    // a point has one representation). Moving it there changes the path length only to second order.
    const double length = mesh_.length(h);
    const double snap = k_vertex_snap * mesh_.size();
    if (x <= snap) return SurfacePoint::at_vertex(mesh_.tail(h));
    if (x >= length - snap) return SurfacePoint::at_vertex(mesh_.head(h));
    const int tail = mesh_.tail(h), head = mesh_.head(h);
    return tail < head ? SurfacePoint::on_edge(tail, head, x / length)
                       : SurfacePoint::on_edge(head, tail, (length - x) / length);
}

std::vector<SurfacePoint> ExactGeodesic::Impl::shortest_path(const SurfacePoint& raw_target) const {
    const SurfacePoint target = mesh_.canonical(raw_target);
    if (!keep_windows_ && target.kind == PointKind::vertex) {
        const double d = vertex_distance(target.vertex);
        return std::isfinite(d) ? path_through_pseudo_sources(target.vertex) : std::vector<SurfacePoint>{};
    }
    if (!keep_windows_) {
        const Scratch scratch(*this);
        scratch->propagate_towards(sources_, target, max_distance_);
        const double d = scratch->best_way_to(target).distance;
        return d <= settled_radius_ || is_settled_stop(target) ? scratch->shortest_path(target)
                                                               : std::vector<SurfacePoint>{};
    }
    const Best best = best_way_to(target);
    if (!std::isfinite(best.distance) || !(best.distance <= settled_radius_ || is_settled_stop(target)))
        return {};  // unreached

    std::vector<SurfacePoint> path{target};
    auto append = [&](const SurfacePoint& p) {
        if (path.back() != p) path.push_back(p);
    };

    // Walk back from the target: through windows (straight across the faces they crossed) and vertices (to
    // whatever gave them their distance), until a source is reached.
    Via via = best.via;
    int id = best.id;
    Vec2 position = best.position;
    const std::size_t step_limit = 4 * (windows_.size() + touched_vertices_.size()) + 16;
    for (std::size_t step = 0; step < step_limit; ++step) {
        if (via == Via::source) {
            append(sources_[id]);
            std::reverse(path.begin(), path.end());
            return path;
        }
        if (via == Via::vertex) {
            append(SurfacePoint::at_vertex(id));
            const Predecessor predecessor = predecessor_[id];
            if (predecessor.via == Via::window) {
                const int h = windows_[predecessor.id].halfedge;
                position = corner_position(h, id);
            }
            via = predecessor.via;
            id = predecessor.id;
            if (via == Via::none) break;
            continue;
        }
        // via == Via::window: `position` is in the frame of the window's halfedge, on the face side.
        if (windows_[id].parent <= -2) id = piece_covering(id, windows_[id].crossing_of(position));
        const Window& w = windows_[id];
        const int h = w.halfedge;
        // A vertex within k_cover of the window's end took its distance from the straight ray to it, which may
        // cross the edge just outside [b0, b1]: follow that ray, or the path would get a hair-long kink there.
        const double slack = k_cover * mesh_.length(h);
        const double x = std::clamp(std::clamp(w.crossing_of(position), w.b0 - slack, w.b1 + slack), 0.0,
                                    mesh_.length(h));
        append(point_on_halfedge(h, x));
        if (w.parent < 0) {
            via = w.origin >= 0 ? Via::vertex : Via::source;
            id = w.origin >= 0 ? w.origin : -1 - w.origin;
            continue;
        }
        // Carry the crossing into the parent's frame: h is the twin of one of the other edges of its face.
        const Window& parent = windows_[w.parent];
        const int hp = parent.halfedge;
        const double fraction = x / mesh_.length(h);
        const Vec2 apex = mesh_.apex(hp);
        if (mesh_.twin(h) == Mesh::prev(hp)) {
            position = fraction * apex;
        } else {
            position = apex + fraction * (Vec2(mesh_.length(hp), 0.0) - apex);
        }
        id = w.parent;
    }
    throw NumericalError("shortest path could not be traced back to a source");
}

// ---------------------------------------------------------------------------------------------------------------

ExactGeodesic::ExactGeodesic(const Mesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
ExactGeodesic::~ExactGeodesic() = default;
ExactGeodesic::ExactGeodesic(ExactGeodesic&&) noexcept = default;
ExactGeodesic& ExactGeodesic::operator=(ExactGeodesic&&) noexcept = default;

void ExactGeodesic::propagate(const std::vector<SurfacePoint>& sources, const PropagationOptions& options) {
    impl_->propagate(sources, options);
}

double ExactGeodesic::distance(int vertex) const { return impl_->vertex_distance(vertex); }

double ExactGeodesic::distance(const SurfacePoint& point) const { return impl_->distance(point); }

std::vector<double> ExactGeodesic::vertex_distances() const {
    std::vector<double> result(impl_->num_vertices());
    for (int v = 0; v < static_cast<int>(result.size()); ++v) result[v] = impl_->vertex_distance(v);
    return result;
}

std::vector<SurfacePoint> ExactGeodesic::shortest_path(const SurfacePoint& target) const {
    return impl_->shortest_path(target);
}

double ExactGeodesic::settled_radius() const { return impl_->settled_radius_; }

const PropagationStats& ExactGeodesic::stats() const { return impl_->stats_; }

std::size_t ExactGeodesic::windows_created_total() const {
    return impl_->windows_created_before_ + impl_->stats_.windows_created;
}

double path_length(const Mesh& mesh, const std::vector<SurfacePoint>& path) {
    double length = 0.0;
    for (std::size_t i = 1; i < path.size(); ++i) length += (mesh.point(path[i]) - mesh.point(path[i - 1])).norm();
    return length;
}

}  // namespace geotri::geodesic

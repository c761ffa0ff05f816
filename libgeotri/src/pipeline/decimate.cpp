// GCC 12 warns inside OpenMesh's PropertyT<Vec3d>::push_back(), whose default-constructed vector is deliberately
// left uninitialised; adding vertices to an OpenMesh mesh instantiates it here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "pipeline/collapse_paths.h"

#include <geodesic/errors.h>
#include <geotri/decimate.h>
#include <geotri/geodesic_triangulation.h>

#include <Eigen/Geometry>
#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <OpenMesh/Tools/Decimater/Observer.hh>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <numeric>
#include <queue>
#include <string>
#include <tuple>
#include <utility>

namespace geotri {

namespace {

using Vec3 = CoarseMesh::Point;

// A symmetric 4x4 quadric (Garland and Heckbert), as its 10 distinct entries.
struct Quadric {
    double a[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};  // xx xy xz xw yy yz yw zz zw ww

    void add_plane(const Vec3& n, double d, double weight) {
        const double p[4] = {n[0], n[1], n[2], d};
        int k = 0;
        for (int i = 0; i < 4; ++i)
            for (int j = i; j < 4; ++j) a[k++] += weight * p[i] * p[j];
    }
    Quadric& operator+=(const Quadric& q) {
        for (int i = 0; i < 10; ++i) a[i] += q.a[i];
        return *this;
    }
    double operator()(const Vec3& p) const {
        const double x = p[0], y = p[1], z = p[2];
        return a[0] * x * x + 2 * a[1] * x * y + 2 * a[2] * x * z + 2 * a[3] * x + a[4] * y * y + 2 * a[5] * y * z +
               2 * a[6] * y + a[7] * z * z + 2 * a[8] * z + a[9];
    }
};

// Limits that a collapse must respect; relaxed round by round when the target is not reached.
struct CollapseLimits {
    double min_cos_normal_turn;  // cosine of the largest turn of a triangle's normal in one collapse
    double min_quality;          // a new triangle below this quality must not be worse than the worst removed one
};

// From strict to the hard limits that every collapse keeps: no triangle turns over, none gets zero area, and no
// needle gets worse.
constexpr CollapseLimits k_rounds[] = {{0.5, 0.1}, {0.0, 0.01}, {0.0, 0.0}};

// What the collapse module shares with the drivers and between the rounds of one component.
struct ComponentState {
    OpenMesh::VPropHandleT<Quadric> quadric;
    OpenMesh::VPropHandleT<int> fine_index;
    CollapseLimits limits = k_rounds[0];
    double error_scale = 1.0;  // makes the quadric error scale-free, so that it fits a float priority
    double volume = 0.0;       // six times the component's signed volume now; collapses never change its sign
    bool edge_paths = true;  // DecimateOptions::edge_paths
    OpenMesh::EPropHandleT<detail::CollapsePaths::Ref> path;  // what each edge is on T
    detail::CollapsePaths paths;
};

// Most that a new triangle may fold against the unchanged triangle across its far edge: cos(177.4°). Normal checks
// against the triangle's own old normal miss folds where the old triangle was a needle with a meaningless normal.
constexpr double k_min_cos_fold = -0.999;

// 1 for an equilateral triangle, 0 for a degenerate one: 4·sqrt(3)·area / (sum of squared edge lengths).
double triangle_quality(double cross_norm, const Vec3& a, const Vec3& b, const Vec3& c) {
    const double sum = (b - a).sqrnorm() + (c - b).sqrnorm() + (a - c).sqrnorm();
    return sum > 0.0 ? 2.0 * std::sqrt(3.0) * cross_norm / sum : 0.0;
}

// The priority module of every decimater here: the quadric error of the collapse, or ILLEGAL_COLLAPSE when a
// triangle around v0 would turn over, lose all its area, or become a needle worse than the worst one removed.
template <class MeshT>
class ModCoarseT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
    DECIMATING_MODULE(ModCoarseT, MeshT, CoarseQuadric);

    explicit ModCoarseT(MeshT& mesh) : Base(mesh, false) {}

    void set_state(ComponentState* state) { state_ = state; }

    float collapse_priority(const CollapseInfo& ci) override {
        if (!shape_ok(ci)) return float(Base::ILLEGAL_COLLAPSE);
        return error(ci);
    }

    // The quadric error of the collapse, scaled to be free of the mesh's size.
    float error(const CollapseInfo& ci) {
        MeshT& mesh = Base::mesh();
        Quadric q = mesh.property(state_->quadric, ci.v0);
        q += mesh.property(state_->quadric, ci.v1);
        const double e = std::max(0.0, q(ci.p1) * state_->error_scale);
        return float(std::min(e, double(FLT_MAX) / 2));
    }

    // Whether no triangle around v0 turns over, loses all its area, or becomes a needle worse than the limits allow.
    bool shape_ok(const CollapseInfo& ci) {
        MeshT& mesh = Base::mesh();
        double worst_old = std::numeric_limits<double>::infinity();
        double worst_new = std::numeric_limits<double>::infinity();
        for (const auto h : mesh.voh_range(ci.v0)) {
            if (mesh.is_boundary(h)) continue;
            const auto ab = mesh.next_halfedge_handle(h);
            const auto a = mesh.to_vertex_handle(h);
            const auto b = mesh.to_vertex_handle(ab);
            const Vec3& pa = mesh.point(a);
            const Vec3& pb = mesh.point(b);
            const Vec3 n_old = OpenMesh::cross(pa - ci.p0, pb - ci.p0);
            const double old_norm = n_old.norm();
            worst_old = std::min(worst_old, triangle_quality(old_norm, ci.p0, pa, pb));
            if (a == ci.v1 || b == ci.v1) continue;  // fl or fr: removed by the collapse
            const Vec3 n_new = OpenMesh::cross(pa - ci.p1, pb - ci.p1);
            const double new_norm = n_new.norm();
            if (!(new_norm > 0.0)) return false;
            // A degenerate old triangle has no normal to compare with.
            if (old_norm > 0.0 && OpenMesh::dot(n_old, n_new) <= state_->limits.min_cos_normal_turn * old_norm * new_norm)
                return false;
            // Folds against the three neighbours after the collapse: across a-b an unchanged triangle; across b-v1
            // and v1-a either another new triangle, or, where the collapse removes the triangle there, the unchanged
            // one beyond it.
            if (folds(n_new, new_norm, unchanged_normal(mesh.opposite_halfedge_handle(ab)))) return false;
            const auto next_in_ring = mesh.opposite_halfedge_handle(mesh.next_halfedge_handle(ab));  // v0 -> b
            const auto c = mesh.to_vertex_handle(mesh.next_halfedge_handle(next_in_ring));
            const Vec3 n_next = c == ci.v1 ? unchanged_normal(mesh.opposite_halfedge_handle(
                                                 mesh.next_halfedge_handle(next_in_ring)))
                                           : OpenMesh::cross(pb - ci.p1, mesh.point(c) - ci.p1);
            if (folds(n_new, new_norm, n_next)) return false;
            const auto previous_in_ring = mesh.opposite_halfedge_handle(h);  // a -> v0
            const auto after = mesh.next_halfedge_handle(previous_in_ring);  // v0 -> x
            if (mesh.to_vertex_handle(after) == ci.v1 &&
                folds(n_new, new_norm,
                      unchanged_normal(mesh.opposite_halfedge_handle(mesh.next_halfedge_handle(after)))))
                return false;
            worst_new = std::min(worst_new, triangle_quality(new_norm, ci.p1, pa, pb));
        }
        if (!(worst_new > 0.0 && worst_new >= std::min(state_->limits.min_quality, worst_old))) return false;
        // The component must not turn inside out: the signed volume keeps its sign.
        const double volume = state_->volume + volume_change(ci);
        return state_->volume > 0.0 ? volume > 0.0 : state_->volume < 0.0 ? volume < 0.0 : true;
    }

    // The normal of the triangle of halfedge h, which the collapse leaves unchanged.
    Vec3 unchanged_normal(typename MeshT::HalfedgeHandle h) {
        MeshT& mesh = Base::mesh();
        if (mesh.is_boundary(h)) return Vec3(0, 0, 0);
        const Vec3& p = mesh.point(mesh.from_vertex_handle(h));
        const Vec3& q = mesh.point(mesh.to_vertex_handle(h));
        const Vec3& r = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
        return OpenMesh::cross(q - p, r - p);
    }

    static bool folds(const Vec3& n, double n_norm, const Vec3& m) {
        return OpenMesh::dot(n, m) < k_min_cos_fold * n_norm * m.norm();
    }

    // Six times the change of the enclosed signed volume. With p1 as the origin the new triangles, which all contain
    // v1, contribute nothing, so the change is minus what the triangles around v0 contribute now.
    double volume_change(const CollapseInfo& ci) {
        MeshT& mesh = Base::mesh();
        const Vec3 d0 = ci.p0 - ci.p1;
        double change = 0.0;
        for (const auto h : mesh.voh_range(ci.v0)) {
            if (mesh.is_boundary(h)) continue;
            const Vec3 da = mesh.point(mesh.to_vertex_handle(h)) - ci.p1;
            const Vec3 db = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - ci.p1;
            change -= OpenMesh::dot(d0, OpenMesh::cross(da, db));
        }
        return change;
    }

    void preprocess_collapse(const CollapseInfo& ci) override {
        state_->volume += volume_change(ci);
        if (state_->edge_paths) drag_paths(ci);
    }

    void postprocess_collapse(const CollapseInfo& ci) override {
        MeshT& mesh = Base::mesh();
        mesh.property(state_->quadric, ci.v1) += mesh.property(state_->quadric, ci.v0);
    }

private:
    // Every edge (v0, w) becomes the path from v1 to v0 and on to w. The edges from v0 to the two apexes merge into
    // those from v1, which keep their paths: both get them, whichever of the two OpenMesh keeps.
    void drag_paths(const CollapseInfo& ci) {
        MeshT& mesh = Base::mesh();
        auto fine = [&](OpenMesh::VertexHandle v) { return mesh.property(state_->fine_index, v); };
        auto path = [&](OpenMesh::HalfedgeHandle h) -> detail::CollapsePaths::Ref& {
            return mesh.property(state_->path, mesh.edge_handle(h));
        };
        const detail::CollapsePaths::Ref to_v0 =
            state_->paths.oriented(path(ci.v0v1), fine(ci.v1), fine(ci.v0));
        for (const auto h : mesh.voh_range(ci.v0)) {
            const auto w = mesh.to_vertex_handle(h);
            if (w == ci.v1) continue;
            if (w == ci.vl || w == ci.vr)
                path(h) = path(mesh.find_halfedge(ci.v1, w));
            else
                path(h) = state_->paths.join(to_v0, state_->paths.oriented(path(h), fine(ci.v0), fine(w)));
        }
    }

    ComponentState* state_ = nullptr;
};

using CoarseModule = ModCoarseT<CoarseMesh>;

// Progress of all components together, and the request to stop.
class ProgressSink {
public:
    ProgressSink(const DecimateOptions& options, std::size_t fine_faces, std::size_t target_faces)
        : callback_(options.progress), fine_faces_(fine_faces), target_faces_(target_faces) {}

    // Records `removed` more faces gone; returns false once the callback has asked to stop.
    bool report(std::size_t removed) {
        const std::size_t total = removed_.fetch_add(removed) + removed;
        if (callback_ && !stop_.load()) {
            std::lock_guard<std::mutex> lock(mutex_);
            DecimateProgress progress{fine_faces_, target_faces_, fine_faces_ - std::min(total, fine_faces_)};
            if (!callback_(progress)) stop_.store(true);
        }
        return !stop_.load();
    }
    bool stopped() const { return stop_.load(); }

private:
    std::function<bool(const DecimateProgress&)> callback_;
    std::size_t fine_faces_;
    std::size_t target_faces_;
    std::atomic<std::size_t> removed_{0};
    std::atomic<bool> stop_{false};
    std::mutex mutex_;
};

constexpr std::size_t k_report_interval = 4096;  // collapses between progress reports

class SinkObserver : public OpenMesh::Decimater::Observer {
public:
    explicit SinkObserver(ProgressSink& sink) : Observer(k_report_interval), sink_(sink) {}
    void notify(std::size_t) override { go_on_ = sink_.report(2 * k_report_interval); }
    bool abort() const override { return !go_on_; }

private:
    ProgressSink& sink_;
    bool go_on_ = true;
};

// A small, portable generator (SplitMix64): the same draws on every platform, unlike rand().
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    std::uint64_t operator()() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }

private:
    std::uint64_t state_;
};

// Collapses on OpenMesh's decimater framework (its CollapseInfo, modules and collapse()), with two drivers of our
// own. OpenMesh's is_collapse_ok() builds and drops a named vertex property on every call, which made it the largest
// cost of a decimation; on a closed manifold mesh the link condition that it checks reduces to "v0 and v1 have exactly
// the two common neighbours vl and vr", which a stamp per vertex tests in one pass over both one-rings.
class CollapseDriver : public OpenMesh::Decimater::BaseDecimaterT<CoarseMesh> {
public:
    using Base = OpenMesh::Decimater::BaseDecimaterT<CoarseMesh>;
    CollapseDriver(CoarseMesh& mesh, ComponentState& state) : Base(mesh), mesh_(mesh) {
        add(module_handle_);
        module_ = &module(module_handle_);
        module_->set_state(&state);
        initialize();
        mesh_.add_property(stamp_);
        for (const auto vh : mesh_.vertices()) mesh_.property(stamp_, vh) = 0;
    }
    ~CollapseDriver() { mesh_.remove_property(stamp_); }

    // The multiple-choice scheme of OpenMesh's McDecimaterT: the cheapest of `samples` random halfedges, drawn from a
    // seeded generator (McDecimaterT uses the global rand()), with garbage collection whenever half of the halfedges
    // are deleted, so that the draws keep hitting live ones as the mesh shrinks. Stops at `target_faces` faces, or
    // when no legal collapse turns up in many draws in a row. Returns the faces left.
    std::size_t decimate_multiple_choice(std::size_t faces, std::size_t target_faces, int samples, SplitMix64& random,
                                         ProgressSink& sink) {
        constexpr int k_give_up = 64;
        int misses = 0;
        std::size_t since_report = 0;
        while (faces > target_faces && misses < k_give_up) {
            if (6 * faces < mesh_.n_halfedges()) mesh_.garbage_collection();
            const std::uint64_t n = mesh_.n_halfedges();
            OpenMesh::HalfedgeHandle best;
            float best_priority = FLT_MAX;
            for (int i = 0; i < samples; ++i) {
                const OpenMesh::HalfedgeHandle h(int(random() % n));
                if (mesh_.status(h).deleted()) continue;
                // The error is cheap: the checks run only for a collapse that would be the best so far.
                const CollapseInfo ci(mesh_, h);
                const float priority = module_->error(ci);
                if (priority >= best_priority || !link_condition(ci) || !module_->shape_ok(ci)) continue;
                best_priority = priority;
                best = h;
            }
            if (!best.is_valid()) {
                ++misses;
                continue;
            }
            misses = 0;
            collapse(best);
            faces -= 2;
            if (++since_report == k_report_interval) {
                since_report = 0;
                if (!sink.report(2 * k_report_interval)) break;
            }
        }
        return faces;
    }

    // Always the cheapest legal collapse, as OpenMesh's DecimaterT does, from a heap with lazy deletion. Expects a
    // garbage-collected mesh. Returns the faces left.
    std::size_t decimate_priority_queue(std::size_t faces, std::size_t target_faces, ProgressSink& sink) {
        if (faces <= target_faces) return faces;
        mesh_.add_property(target_);
        mesh_.add_property(version_);
        for (const auto vh : mesh_.vertices()) {
            mesh_.property(version_, vh) = 0;
            push_vertex(vh);
        }
        std::size_t since_report = 0;
        std::vector<OpenMesh::VertexHandle> ring;
        while (faces > target_faces && !heap_.empty()) {
            const Entry entry = heap_.top();
            heap_.pop();
            const OpenMesh::VertexHandle vh(entry.vertex);
            if (mesh_.status(vh).deleted() || mesh_.property(version_, vh) != entry.version) continue;
            const OpenMesh::HalfedgeHandle h = mesh_.property(target_, vh);
            // The link condition depends on the two-ring, which the updates below do not cover: check again.
            const CollapseInfo ci(mesh_, h);
            if (!link_condition(ci) || !module_->shape_ok(ci)) {
                push_vertex(vh);
                continue;
            }
            ring.clear();
            for (const auto w : mesh_.vv_range(vh)) ring.push_back(w);
            collapse(h);
            faces -= 2;
            for (const auto w : ring) push_vertex(w);
            if (++since_report == k_report_interval) {
                since_report = 0;
                if (!sink.report(2 * k_report_interval)) break;
            }
        }
        heap_ = {};
        mesh_.remove_property(target_);
        mesh_.remove_property(version_);
        return faces;
    }

private:
    struct Entry {
        float priority;
        int vertex;
        unsigned version;
        bool operator<(const Entry& other) const {
            // std::priority_queue puts the largest first; ties go to the lower vertex, for a result that does not
            // depend on the heap's internals.
            if (priority != other.priority) return priority > other.priority;
            return vertex > other.vertex;
        }
    };

    bool link_condition(const CollapseInfo& ci) {
        if (!ci.vl.is_valid() || !ci.vr.is_valid() || ci.vl == ci.vr) return false;
        const unsigned stamp = ++stamp_counter_;
        int valence0 = 0, valence1 = 0, common = 0;
        for (const auto w : mesh_.vv_range(ci.v0)) {
            mesh_.property(stamp_, w) = stamp;
            ++valence0;
        }
        for (const auto w : mesh_.vv_range(ci.v1)) {
            if (mesh_.property(stamp_, w) == stamp) ++common;
            ++valence1;
        }
        if (common != 2) return false;
        // A tetrahedron: the link condition holds for its edges, but a collapse would leave two faces glued together.
        return !(valence0 == 3 && valence1 == 3 && mesh_.valence(ci.vl) == 3 && mesh_.valence(ci.vr) == 3);
    }

    void collapse(OpenMesh::HalfedgeHandle h) {
        CollapseInfo ci(mesh_, h);
        preprocess_collapse(ci);
        mesh_.collapse(h);
        postprocess_collapse(ci);
    }

    void push_vertex(OpenMesh::VertexHandle vh) {
        unsigned& version = mesh_.property(version_, vh);
        ++version;
        float best_priority = FLT_MAX;
        OpenMesh::HalfedgeHandle best;
        for (const auto h : mesh_.voh_range(vh)) {
            const CollapseInfo ci(mesh_, h);
            const float priority = module_->error(ci);
            if (priority >= best_priority || !link_condition(ci) || !module_->shape_ok(ci)) continue;
            best_priority = priority;
            best = h;
        }
        if (!best.is_valid()) return;
        mesh_.property(target_, vh) = best;
        heap_.push({best_priority, vh.idx(), version});
    }

    CoarseMesh& mesh_;
    OpenMesh::Decimater::ModHandleT<CoarseModule> module_handle_;
    CoarseModule* module_ = nullptr;
    OpenMesh::VPropHandleT<unsigned> stamp_;
    OpenMesh::VPropHandleT<OpenMesh::HalfedgeHandle> target_;
    OpenMesh::VPropHandleT<unsigned> version_;
    unsigned stamp_counter_ = 0;
    std::priority_queue<Entry> heap_;
};

struct ComponentInput {
    std::vector<int> vertices;  // fine indices, ascending
    std::vector<int> faces;     // fine faces
    double area = 0.0;
};

// Splits `target` faces between components: at least min_faces each, at most what each has, the rest in proportion
// to area, always an even count (a closed triangle mesh has an even number of faces).
std::vector<int> split_target(std::size_t target, const std::vector<DecimateComponent>& components,
                              const std::vector<double>& areas) {
    const std::size_t n = components.size();
    std::vector<int> result(n);
    std::size_t floor_sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        result[i] = components[i].min_faces;
        floor_sum += std::size_t(result[i]);
    }
    if (target <= floor_sum) return result;
    auto share = [&](double s, std::size_t i) {
        return std::clamp(s * areas[i], double(components[i].min_faces), double(components[i].fine_faces));
    };
    auto total = [&](double s) {
        double sum = 0.0;
        for (std::size_t i = 0; i < n; ++i) sum += share(s, i);
        return sum;
    };
    const double total_area = std::accumulate(areas.begin(), areas.end(), 0.0);
    double lo = 0.0, hi = total_area > 0.0 ? double(target) / total_area : 0.0;
    if (hi > 0.0) {
        while (total(hi) < double(target) && hi < 1e300) hi *= 2;
        for (int iteration = 0; iteration < 200; ++iteration) {
            const double mid = 0.5 * (lo + hi);
            (total(mid) < double(target) ? lo : hi) = mid;
        }
    }
    std::vector<std::pair<double, std::size_t>> remainders;
    std::size_t sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double exact = share(lo, i);
        result[i] = std::max(components[i].min_faces, 2 * int(std::floor(exact / 2)));
        sum += std::size_t(result[i]);
        remainders.push_back({exact - result[i], i});
    }
    std::stable_sort(remainders.begin(), remainders.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& [remainder, i] : remainders) {
        if (sum + 2 > target) break;
        if (result[i] + 2 <= components[i].fine_faces) {
            result[i] += 2;
            sum += 2;
        }
    }
    return result;
}

// Builds the component as an OpenMesh mesh, decimates it to `target_faces`, and returns its coarse vertices (fine
// indices), its triangles (fine indices) and, when asked, the path of each of its edges (fine indices).
void decimate_component(const FineMesh& fine, const ComponentInput& input, int target_faces,
                        const DecimateOptions& options, ProgressSink& sink, std::vector<int>& coarse_vertices,
                        std::vector<std::array<int, 3>>& coarse_triangles,
                        std::vector<std::vector<int>>& edge_paths) {
    CoarseMesh mesh;
    ComponentState state;
    mesh.add_property(state.quadric);
    mesh.add_property(state.fine_index);
    mesh.add_property(state.path);
    state.edge_paths = options.edge_paths;
    mesh.reserve(input.vertices.size(), 3 * input.faces.size() / 2, input.faces.size());
    std::vector<OpenMesh::VertexHandle> handle;
    handle.reserve(input.vertices.size());
    // A sorted vertex list maps fine to local indices by binary search, without a table the size of T per component.
    auto local_of = [&](int v) {
        return handle[std::size_t(std::lower_bound(input.vertices.begin(), input.vertices.end(), v) -
                                  input.vertices.begin())];
    };
    Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const int v : input.vertices) {
        const Eigen::Vector3d& p = fine.mesh.position(v);
        const Vec3 point(p.x(), p.y(), p.z());
        const OpenMesh::VertexHandle vh = mesh.add_vertex(point);
        mesh.property(state.fine_index, vh) = v;
        handle.push_back(vh);
        lo.minimize(point);
        hi.maximize(point);
    }
    for (const int f : input.faces) {
        const auto& t = fine.mesh.triangle(f);
        if (!mesh.add_face(local_of(t[0]), local_of(t[1]), local_of(t[2])).is_valid())
            throw TopologyError(fine.path + ": face " + std::to_string(f) + " cannot be added to the coarse mesh");
    }

    for (const auto eh : mesh.edges()) mesh.property(state.path, eh) = detail::CollapsePaths::k_single_edge;

    // Quadrics of the face planes, weighted by area.
    const double diagonal = (hi - lo).norm();
    state.error_scale = diagonal > 0.0 ? 1.0 / (diagonal * diagonal * diagonal * diagonal) : 1.0;
    for (const auto vh : mesh.vertices()) mesh.property(state.quadric, vh) = Quadric();
    for (const auto fh : mesh.faces()) {
        auto fv = mesh.cfv_iter(fh);
        const Vec3& a = mesh.point(*fv);
        const Vec3& b = mesh.point(*++fv);
        const Vec3& c = mesh.point(*++fv);
        Vec3 n = OpenMesh::cross(b - a, c - a);
        const double norm = n.norm();
        if (!(norm > 0.0)) continue;
        n /= norm;
        Quadric q;
        q.add_plane(n, -OpenMesh::dot(n, a), 0.5 * norm);
        for (const auto vh : mesh.fv_range(fh)) mesh.property(state.quadric, vh) += q;
    }

    state.volume = 0.0;
    for (const int f : input.faces) {
        const auto& t = fine.mesh.triangle(f);
        const Eigen::Vector3d& a = fine.mesh.position(t[0]);
        const Eigen::Vector3d& origin = fine.mesh.position(input.vertices.front());
        state.volume += (fine.mesh.position(t[1]) - a).cross(fine.mesh.position(t[2]) - a).dot(a - origin);
    }

    std::size_t faces = input.faces.size();
    const std::size_t target = std::size_t(target_faces);
    SplitMix64 random(options.seed ^ (0x6a09e667f3bcc909ull * (std::uint64_t(input.vertices.front()) + 1)));
    for (const CollapseLimits& limits : k_rounds) {
        if (faces <= target || sink.stopped()) break;
        state.limits = limits;
        if (options.strategy == DecimateStrategy::multiple_choice) {
            CollapseDriver driver(mesh, state);
            const std::size_t handover = std::max<std::size_t>(20000, 8 * target);
            if (faces > handover)
                faces = driver.decimate_multiple_choice(faces, handover, std::max(1, options.samples), random, sink);
            if (sink.stopped()) break;
            mesh.garbage_collection();
            faces = driver.decimate_priority_queue(faces, target, sink);
            mesh.garbage_collection();
        } else {
            mesh.garbage_collection();
            OpenMesh::Decimater::DecimaterT<CoarseMesh> decimater(mesh);
            OpenMesh::Decimater::ModHandleT<CoarseModule> module;
            decimater.add(module);
            decimater.module(module).set_state(&state);
            decimater.initialize();
            SinkObserver observer(sink);
            decimater.set_observer(&observer);
            decimater.decimate_to_faces(0, target);
            decimater.set_observer(nullptr);
            mesh.garbage_collection();
            faces = mesh.n_faces();
        }
    }
    mesh.garbage_collection();

    coarse_vertices.clear();
    for (const auto vh : mesh.vertices()) coarse_vertices.push_back(mesh.property(state.fine_index, vh));
    coarse_triangles.clear();
    for (const auto fh : mesh.faces()) {
        std::array<int, 3> t{};
        int i = 0;
        for (const auto vh : mesh.fv_range(fh)) t[std::size_t(i++)] = mesh.property(state.fine_index, vh);
        coarse_triangles.push_back(t);
    }
    edge_paths.clear();
    if (!state.edge_paths) return;
    for (const auto eh : mesh.edges()) {
        const auto h = mesh.halfedge_handle(eh, 0);
        edge_paths.push_back(state.paths.vertices(mesh.property(state.path, eh),
                                                  mesh.property(state.fine_index, mesh.from_vertex_handle(h)),
                                                  mesh.property(state.fine_index, mesh.to_vertex_handle(h))));
    }
}

}  // namespace

int min_faces_of_genus(int genus) {
    if (genus < 0) throw InvalidInput("min_faces_of_genus: negative genus " + std::to_string(genus));
    // Fewest vertices (Heawood's bound, reached by Jungerman and Ringel for every genus but 2, which needs 10).
    int vertices = 4;
    if (genus == 2) {
        vertices = 10;
    } else if (genus > 0) {
        vertices = int(std::ceil((7.0 + std::sqrt(1.0 + 48.0 * genus)) / 2.0 - 1e-9));
    }
    // V - F/2 = 2 - 2g for a closed triangulated surface.
    return 2 * (vertices - 2 + 2 * genus);
}

DecimateResult decimate(const FineMesh& fine, const DecimateOptions& options) {
    const int targets = (options.target_faces > 0) + (options.target_vertices > 0) + (options.ratio != 0.0) +
                        (options.coarsest ? 1 : 0);
    if (targets != 1)
        throw InvalidInput("decimate: set exactly one of target_faces, target_vertices, ratio and coarsest (" +
                           std::to_string(targets) + " set)");
    if (options.ratio != 0.0 && !(options.ratio > 0.0 && options.ratio <= 1.0))
        throw InvalidInput("decimate: ratio must be in (0, 1], not " + std::to_string(options.ratio));

    const geodesic::Mesh& mesh = fine.mesh;
    const std::size_t n_components = std::size_t(fine.num_components);
    std::vector<ComponentInput> inputs(n_components);
    for (int v = 0; v < mesh.num_vertices(); ++v) inputs[std::size_t(fine.component[std::size_t(v)])].vertices.push_back(v);
    for (int f = 0; f < mesh.num_faces(); ++f) {
        ComponentInput& input = inputs[std::size_t(fine.component[std::size_t(mesh.triangle(f)[0])])];
        input.faces.push_back(f);
        input.area += mesh.face_area(f);
    }

    DecimateResult result;
    result.components.resize(n_components);
    std::vector<double> areas(n_components);
    int euler_sum = 0;
    std::size_t min_sum = 0;
    for (std::size_t c = 0; c < n_components; ++c) {
        DecimateComponent& info = result.components[c];
        info.fine_vertices = int(inputs[c].vertices.size());
        info.fine_faces = int(inputs[c].faces.size());
        info.genus = fine.genus[c];
        info.euler_characteristic = 2 - 2 * info.genus;
        info.min_faces = std::min(info.fine_faces, min_faces_of_genus(std::max(0, info.genus)));
        areas[c] = inputs[c].area;
        euler_sum += info.euler_characteristic;
        min_sum += std::size_t(info.min_faces);
    }

    std::size_t target = 0;
    if (options.coarsest) {
        target = min_sum;
    } else if (options.target_faces > 0) {
        target = options.target_faces;
    } else if (options.target_vertices > 0) {
        // V = F/2 + χ per closed component.
        const long long faces = 2 * (static_cast<long long>(options.target_vertices) - euler_sum);
        target = std::size_t(std::max(0LL, faces));
    } else {
        target = std::size_t(std::floor(options.ratio * double(mesh.num_faces())));
    }
    std::vector<int> shares;
    if (options.component_targets.empty()) {
        shares = split_target(target, result.components, areas);
    } else {
        if (options.component_targets.size() != n_components)
            throw InvalidInput("decimate: " + std::to_string(options.component_targets.size()) +
                               " component targets for " + std::to_string(n_components) + " components");
        target = 0;
        for (std::size_t c = 0; c < n_components; ++c) {
            const DecimateComponent& info = result.components[c];
            shares.push_back(std::clamp(options.component_targets[c], info.min_faces, info.fine_faces));
            target += std::size_t(shares.back());
        }
    }
    result.target_faces = target;

    ProgressSink sink(options, std::size_t(mesh.num_faces()), target);
    std::vector<std::vector<int>> coarse_vertices(n_components);
    std::vector<std::vector<std::array<int, 3>>> coarse_triangles(n_components);
    std::vector<std::vector<std::vector<int>>> edge_paths(n_components);
    // Largest first, so that dynamic scheduling balances the threads.
    std::vector<std::size_t> order(n_components);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return inputs[a].faces.size() > inputs[b].faces.size(); });
    std::exception_ptr error;
    std::mutex error_mutex;
#pragma omp parallel for schedule(dynamic, 1)
    for (std::ptrdiff_t k = 0; k < std::ptrdiff_t(n_components); ++k) {
        const std::size_t c = order[std::size_t(k)];
        try {
            result.components[c].target_faces = shares[c];
            decimate_component(fine, inputs[c], shares[c], options, sink, coarse_vertices[c], coarse_triangles[c],
                               edge_paths[c]);
        } catch (...) {
            std::lock_guard<std::mutex> lock(error_mutex);
            if (!error) error = std::current_exception();
        }
    }
    if (error) std::rethrow_exception(error);

    // Coarse vertices in the order of their fine indices.
    std::vector<int> coarse_index(std::size_t(mesh.num_vertices()), -1);
    for (std::size_t c = 0; c < n_components; ++c) {
        result.components[c].vertices = int(coarse_vertices[c].size());
        result.components[c].faces = int(coarse_triangles[c].size());
        for (const int v : coarse_vertices[c]) coarse_index[std::size_t(v)] = 0;
    }
    for (int v = 0; v < mesh.num_vertices(); ++v) {
        if (coarse_index[std::size_t(v)] < 0) continue;
        coarse_index[std::size_t(v)] = int(result.fine_vertex.size());
        result.fine_vertex.push_back(v);
        result.coarse.positions.push_back(mesh.position(v));
    }
    for (std::size_t c = 0; c < n_components; ++c)
        for (const auto& t : coarse_triangles[c])
            result.coarse.triangles.push_back({coarse_index[std::size_t(t[0])], coarse_index[std::size_t(t[1])],
                                               coarse_index[std::size_t(t[2])]});
    for (std::size_t c = 0; c < n_components; ++c)
        for (std::vector<int>& path : edge_paths[c]) {
            if (path.front() > path.back()) std::reverse(path.begin(), path.end());
            result.edges.push_back({coarse_index[std::size_t(path.front())], coarse_index[std::size_t(path.back())],
                                    std::move(path)});
        }
    std::sort(result.edges.begin(), result.edges.end(),
              [](const DecimatedEdge& x, const DecimatedEdge& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });

    result.aborted = sink.stopped();
    result.target_reached = options.target_vertices > 0 && options.component_targets.empty()
                                ? result.coarse.positions.size() <= options.target_vertices
                                : result.coarse.triangles.size() <= target;
    return result;
}

EdgePaths make_edge_paths(const FineMesh& fine, const DecimateResult& decimation) {
    if (2 * decimation.edges.size() != 3 * decimation.coarse.triangles.size())
        throw InvalidInput("make_edge_paths: the decimation kept no edge paths (DecimateOptions::edge_paths is off)");
    EdgePaths paths;
    paths.name = "the decimation's edge paths";
    paths.fine_checksum = fine.checksum;
    paths.fine_vertices = fine.mesh.num_vertices();
    paths.coarse_vertices = static_cast<int>(decimation.coarse.positions.size());
    paths.edges = decimation.edges;
    return paths;
}

}  // namespace geotri

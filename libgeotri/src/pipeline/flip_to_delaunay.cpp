#include <geodesic/constants.h>
#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/flip_to_delaunay.h>

#include "core/parallel_propagations.h"
#include "core/triangle_layout.h"
#include "ops/with_workspace.h"
#include "pipeline/flip_to_delaunay_detail.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace geotri {

using geodesic::k_pi;
using OpenMesh::EdgeHandle;
using OpenMesh::HalfedgeHandle;

namespace {

/// What one edge's evaluation found: a flip to do, or a refusal to count.
struct Evaluation {
    bool flip = false;
    bool planned = false;      ///< plan_flip() was called
    bool wants_region = false; ///< the criterion asks for the flip, but the shortest geodesic leaves the patches
    double before = 0.0;       ///< the criterion's figure for the edge as it is (minimum angle, or opposite sum)
    FlipPlan plan;
    FlipRefusal refused = FlipRefusal::none;
};

/// Improve, in sweeps. Each sweep evaluates (in parallel: G is only read) every edge whose two faces changed since
/// its last evaluation; when it found no ordinary flip, it evaluates the flips whose shortest geodesic left the two
/// patches once more with the shortest path inside them (the two patches cut out of T alone); it does the flips it
/// found in edge index order, skipping those whose faces an earlier flip of the same sweep changed (they are
/// evaluated again in the next sweep). The result does not depend on the thread count.
class Improver {
public:
    /// Starts with every edge to evaluate, or only `edges` when given.
    /// Every edge flipped is appended to `flipped` when given.
    Improver(GeodesicTriangulation& g, const FlipToDelaunayOptions& options, const Workspace& workspace,
             FlipToDelaunayResult& result, const std::vector<EdgeHandle>* edges = nullptr,
             std::vector<EdgeHandle>* flipped = nullptr)
        : g_(g), options_(options), workspace_(workspace), result_(result), flipped_(flipped) {
        const int n = static_cast<int>(g.coarse().n_edges());
        if (!edges) {
            for (int e = 0; e < n; ++e) dirty_.push_back(e);
            return;
        }
        for (EdgeHandle e : *edges) {
            if (e.idx() < 0 || e.idx() >= n) throw std::out_of_range("improve: not an edge of the coarse mesh");
            dirty_.push_back(e.idx());
        }
    }

    /// Sweeps until one makes no flip or max_passes is reached; counts into the result.
    void run() {
        int flips = 0, passes = 0;
        do {
            flips = sweep();
            ++passes;
            ++result_.passes;
            result_.flips += flips;
            if (options_.progress)
                options_.progress("improve sweep " + std::to_string(result_.passes) + ": " +
                                  std::to_string(flips) + " flips");
        } while (flips > 0 && passes < options_.max_passes);
        if (flips > 0) result_.pass_cap_reached = true;
    }

    /// One sweep; returns the number of flips.
    int sweep() {
        const CoarseMesh& coarse = g_.coarse();
        // The dirty edges in increasing order, each once.
        std::vector<int> edges;
        edges.swap(dirty_);
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        edges.erase(std::remove_if(edges.begin(), edges.end(),
                                   [&](int i) {
                                       const EdgeHandle e(i);
                                       return coarse.status(e).deleted() || coarse.is_boundary(e) ||
                                              !coarse.is_flip_ok(e);
                                   }),
                    edges.end());
        std::vector<Evaluation> found(edges.size());
        for_each_parallel(edges.size(), [&](std::size_t k, geodesic::ExactGeodesic& propagation) {
            found[k] = evaluate(EdgeHandle(edges[k]), propagation);
        });
        std::vector<std::size_t> again;
        for (std::size_t k = 0; k < found.size(); ++k)
            if (found[k].wants_region) again.push_back(k);
        // While ordinary flips go on, the flips that want the region fallback wait for a sweep without them
        // (evaluated again then): ordinary flips first. This once let one overlay of all of T serve them all; each
        // now cuts its two patches alone out of T, but trying them at once ends lower after flipping on footbones
        // (2.9 -> 1.9 degrees), u (2.2 -> 0.1) and bunny_closed_cgal (5.4 -> 4.6).
        const bool ordinary = std::any_of(found.begin(), found.end(), [](const Evaluation& x) { return x.flip; });
        if (ordinary) {
            for (std::size_t k : again) {
                found[k].refused = FlipRefusal::none;  // counted when it is evaluated again
                dirty_.push_back(edges[k]);
            }
        } else if (!again.empty()) {
            for_each_parallel(again.size(), [&](std::size_t i, geodesic::ExactGeodesic&) {
                Evaluation& x = found[again[i]];
                FlipPlan inside = plan_flip_in_region(g_, EdgeHandle(edges[again[i]]));
                if (!inside.accepted()) return;
                x.plan = std::move(inside);
                x.refused = FlipRefusal::none;
                x.flip = better(x.before, x.plan);
            });
        }

        // The edges whose faces this sweep's flips changed, sorted: a handful, where a flag per edge of G cost a pass
        // over G at every sweep around every vertex that refinement inserts.
        std::vector<int> touched;
        auto was_touched = [&](int x) { return std::binary_search(touched.begin(), touched.end(), x); };
        int flips = 0;
        for (std::size_t k = 0; k < found.size(); ++k) {
            if (found[k].planned) ++result_.plans;
            if (found[k].refused != FlipRefusal::none)
                ++result_.refused[static_cast<std::size_t>(found[k].refused)];
            if (!found[k].flip) continue;
            const std::array<int, 5> quad = quad_edges(EdgeHandle(edges[k]));
            // An earlier flip of this sweep changed e's faces, or made the edge c-d that this flip would make (two
            // quads can share their opposite vertices): evaluate e again in the next sweep.
            if (std::any_of(quad.begin(), quad.end(), was_touched) || !coarse.is_flip_ok(EdgeHandle(edges[k]))) {
                dirty_.push_back(edges[k]);
                continue;
            }
            apply_flip(g_, found[k].plan);
            if (flipped_) flipped_->push_back(EdgeHandle(edges[k]));
            ++flips;
            if (found[k].plan.in_region) ++result_.region_flips;
            for (int x : quad) {
                if (!was_touched(x)) touched.insert(std::lower_bound(touched.begin(), touched.end(), x), x);
                dirty_.push_back(x);
            }
        }
        return flips;
    }

private:
    template <class Work>
    void for_each_parallel(std::size_t n, Work work) const {
        detail::for_each_with_propagation(g_.fine().mesh, n, options_.threads, work, workspace_.propagation,
                                          workspace_.propagations);
    }

    /// e and the four other edges of its two faces: the edges whose faces a flip of e changes.
    std::array<int, 5> quad_edges(EdgeHandle e) const {
        const CoarseMesh& coarse = g_.coarse();
        const HalfedgeHandle ab = coarse.halfedge_handle(e, 0), ba = coarse.halfedge_handle(e, 1);
        return {e.idx(), coarse.edge_handle(coarse.next_halfedge_handle(ab)).idx(),
                coarse.edge_handle(coarse.prev_halfedge_handle(ab)).idx(),
                coarse.edge_handle(coarse.next_halfedge_handle(ba)).idx(),
                coarse.edge_handle(coarse.prev_halfedge_handle(ba)).idx()};
    }

    /// Whether the accepted plan is a strict improvement on `before` by the criterion.
    bool better(double before, const FlipPlan& plan) const {
        if (options_.criterion == FlipCriterion::angle)
            return *std::min_element(plan.corners.begin(), plan.corners.end()) > before + options_.margin;
        // The new edge must be more Delaunay than the old one, so that it is never flipped straight back.
        const CoarseMesh& coarse = g_.coarse();
        const HalfedgeHandle ab = coarse.halfedge_handle(plan.edge, 0), ba = coarse.halfedge_handle(plan.edge, 1);
        const double l_bc = g_.length(coarse.edge_handle(coarse.next_halfedge_handle(ab)));
        const double l_ca = g_.length(coarse.edge_handle(coarse.prev_halfedge_handle(ab)));
        const double l_ad = g_.length(coarse.edge_handle(coarse.next_halfedge_handle(ba)));
        const double l_db = g_.length(coarse.edge_handle(coarse.prev_halfedge_handle(ba)));
        return detail::opposite_angle(plan.length, l_ad, l_ca) + detail::opposite_angle(plan.length, l_bc, l_db) <
               before;
    }

    Evaluation evaluate(EdgeHandle e, geodesic::ExactGeodesic& propagation) const {
        const CoarseMesh& coarse = g_.coarse();
        const HalfedgeHandle ab = coarse.halfedge_handle(e, 0), ba = coarse.halfedge_handle(e, 1);
        const HalfedgeHandle bc = coarse.next_halfedge_handle(ab), ca = coarse.next_halfedge_handle(bc);
        const HalfedgeHandle ad = coarse.next_halfedge_handle(ba), db = coarse.next_halfedge_handle(ad);
        Evaluation result;
        if (options_.criterion == FlipCriterion::angle) {
            const double at_a = corner_angle(g_, ab), at_b = corner_angle(g_, bc), at_c = corner_angle(g_, ca);
            const double at_b2 = corner_angle(g_, ba), at_a2 = corner_angle(g_, ad), at_d = corner_angle(g_, db);
            result.before = std::min({at_a, at_b, at_c, at_b2, at_a2, at_d});
            // No flip can beat this: the corners at a and b merge, and those at c and d are split in two.
            const double bound = std::min({at_a + at_a2, at_b + at_b2, 0.5 * at_c, 0.5 * at_d});
            if (!(bound > result.before + options_.margin)) return result;
        } else {
            const double l_ab = g_.length(e), l_bc = g_.length(coarse.edge_handle(bc));
            const double l_ca = g_.length(coarse.edge_handle(ca)), l_ad = g_.length(coarse.edge_handle(ad));
            const double l_db = g_.length(coarse.edge_handle(db));
            result.before = detail::opposite_angle(l_ab, l_bc, l_ca) + detail::opposite_angle(l_ab, l_ad, l_db);
            if (!(result.before > k_pi + options_.margin)) return result;
        }
        FlipOptions flip_options;
        flip_options.region_fallback = false;  // done for all such edges after the ordinary flips (sweep())
        Workspace with_paths;
        with_paths.propagation = &propagation;
        with_paths.paths = workspace_.paths;
        result.plan = plan_flip(g_, e, flip_options, with_paths);
        result.planned = true;
        if (!result.plan.accepted()) {
            result.refused = result.plan.refusal;
            result.wants_region = options_.region_fallback && (result.refused == FlipRefusal::bad_corner ||
                                                               result.refused == FlipRefusal::leaves_region);
            return result;
        }
        result.flip = better(result.before, result.plan);
        return result;
    }

    GeodesicTriangulation& g_;
    const FlipToDelaunayOptions& options_;
    const Workspace& workspace_;
    FlipToDelaunayResult& result_;
    std::vector<int> dirty_;  ///< the edges whose faces changed since they were last evaluated (repeats allowed)
    std::vector<EdgeHandle>* flipped_;  ///< where the flipped edges go, or null
};

}  // namespace

const char* to_string(FlipCriterion criterion) { return criterion == FlipCriterion::angle ? "angle" : "length"; }

CornerAngleStats corner_angle_stats(const GeodesicTriangulation& g) {
    CornerAngleStats stats;
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0, sum = 0.0;
    for (OpenMesh::FaceHandle f : g.coarse().faces()) {
        for (double angle : corner_angles(g, f)) {
            lo = std::min(lo, angle);
            hi = std::max(hi, angle);
            sum += angle;
            ++stats.corners;
        }
    }
    if (stats.corners > 0) {
        stats.min_deg = lo * geodesic::k_degrees_per_radian;
        stats.max_deg = hi * geodesic::k_degrees_per_radian;
        stats.mean_deg = sum / stats.corners * geodesic::k_degrees_per_radian;
    }
    return stats;
}

FlipToDelaunayResult flip_to_delaunay(GeodesicTriangulation& g, const FlipToDelaunayOptions& options) {
    ValidationReport report = validate(g);
    return detail::flip_to_delaunay_validated(g, options, report);
}

namespace detail {

FlipToDelaunayResult flip_to_delaunay_validated(GeodesicTriangulation& g, const FlipToDelaunayOptions& options,
                                                ValidationReport& report) {
    const auto start = std::chrono::steady_clock::now();
    FlipToDelaunayResult result;
    result.angles_before = corner_angle_stats(g);
    if (!report.valid) {
        result.skipped = true;
    } else {
        const GeodesicTriangulation before = g;
        Improver(g, options, Workspace{}, result).run();
        if (result.flips > 0) {
            report = validate(g);
            if (!report.valid) {
                g = before;
                report = validate(g);
                result.reverted = true;
            }
        }
    }
    result.valid_after = report.valid;
    result.angles_after = corner_angle_stats(g);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

void improve_around(GeodesicTriangulation& g, const std::vector<EdgeHandle>& edges,
                    const FlipToDelaunayOptions& options, const Workspace& workspace, FlipToDelaunayResult& result,
                    std::vector<EdgeHandle>* flipped) {
    for (EdgeHandle e : edges)
        if (!e.is_valid() || static_cast<std::size_t>(e.idx()) >= g.coarse().n_edges())
            throw InvalidInput("improve_around: not an edge of the coarse mesh");
    Improver(g, options, workspace, result, &edges, flipped).run();
}

}  // namespace detail

}  // namespace geotri

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/collapse.h>
#include <geotri/relocate.h>
#include <geotri/split.h>
#include <geotri/untangle.h>

#include "check/polyline_verdicts.h"
#include "check/violation_count.h"
#include "core/thread_count.h"
#include "ops/with_workspace.h"
#include "pipeline/stale_trials.h"
#include "pipeline/untangle_detail.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace geotri {

using OpenMesh::EdgeHandle;
using OpenMesh::HalfedgeHandle;

namespace {

int total(const ValidationReport& r) { return static_cast<int>(r.violations.size()); }

/// `indices`, each below n, in increasing order and each once. Through a mark per index rather than by sorting:
/// the violations of a G of genus 1409 name a hundred thousand edges, over and over, in every round.
std::vector<int> sorted_once(const std::vector<int>& indices, std::size_t n) {
    std::vector<unsigned char> named(n, 0);
    for (int i : indices) named[static_cast<std::size_t>(i)] = 1;
    std::vector<int> out;
    for (std::size_t i = 0; i < n; ++i)
        if (named[i]) out.push_back(static_cast<int>(i));
    return out;
}

/// The coarse edges that a flip might mend: those that the violations name, and those at the vertices and faces
/// that they name. Sorted, so that untangling is deterministic.
std::vector<int> candidate_edges(const CoarseMesh& coarse, const ValidationReport& report) {
    std::vector<int> edges;
    for (const Violation& v : report.violations) {
        edges.insert(edges.end(), v.coarse_edges.begin(), v.coarse_edges.end());
        for (int c : v.coarse_vertices)
            for (EdgeHandle e : coarse.ve_range(OpenMesh::VertexHandle(c))) edges.push_back(e.idx());
        for (int f : v.coarse_faces)
            for (EdgeHandle e : coarse.fe_range(OpenMesh::FaceHandle(f))) edges.push_back(e.idx());
    }
    return sorted_once(edges, coarse.n_edges());
}

/// How far untangling moves a coarse vertex: to the vertices of T within this many edges of it.
constexpr int k_relocation_rings = 2;
/// How far untangling moves a vertex when nothing nearer helps: on a torus decimated to its coarsest (rotor,
/// eight), the vertex that winds twice needs a move of 3-6 fine edges.
constexpr int k_wide_relocation_rings = 6;
/// The last resorts of untangling (pairs of flips, wider moves) are tried only when at most this many violations
/// of conditions 1-3 are left: there are many of them, and where hundreds of violations are stuck (cheese) they
/// cost minutes and leave it invalid all the same.
constexpr int k_max_last_resort_violations = 16;

/// Rounds of fork splits in one chain (try_fork_chain in untangle()): chains seen on real meshes take three.
constexpr int k_max_fork_chain_rounds = 8;

/// Violations of conditions 1-3 (the cheap ones, without the overlay).
int cheap_count(const ValidationReport& r) { return r.violation_count[0] + r.violation_count[1] + r.violation_count[2]; }

/// The coarse vertices that a fork split might mend: those that the violations name, and the ends of the edges
/// that they name. Sorted, so that untangling is deterministic.
std::vector<int> candidate_vertices(const CoarseMesh& coarse, const ValidationReport& report) {
    std::vector<int> vertices;
    for (const Violation& v : report.violations) {
        vertices.insert(vertices.end(), v.coarse_vertices.begin(), v.coarse_vertices.end());
        for (int e : v.coarse_edges)
            for (int side = 0; side < 2; ++side)
                vertices.push_back(coarse.to_vertex_handle(coarse.halfedge_handle(EdgeHandle(e), side)).idx());
    }
    return sorted_once(vertices, coarse.n_vertices());
}

/// Counts the violations of conditions 1-3 of a trial copy of G (ViolationCount, from what the trial changed).
using CountViolations = std::function<int(const GeodesicTriangulation&)>;

/// At most this many operations settle a split's new vertex (settle_around()).
constexpr int k_max_settle_steps = 8;

/// Settles the new vertex v of `split`, which untangling tries on g: while one of these lowers G's violations of
/// conditions 1-3, does the first that does (v's split and these are one untangling move), at most
/// k_max_settle_steps times:
/// a flip of an edge of the stars or links of v and the vertices added here, or a fork split at them or at their
/// neighbours. A split's new geodesics often run through a vertex of G or along one of its geodesics, which such
/// an operation then mends, and the split lowers the count only with it: on femur_cgal, a fork split at coarse
/// vertex 6 takes the count from 9 to 12 and a flip after it to 7; on 42400-IDGH, one at coarse vertex 48 leaves
/// it at 6 with a new fork at a neighbour, whose split takes it to 4.
/// Returns the untangling moves made: 0 when the split was not done, else 1.
int settle_around(GeodesicTriangulation& g, const SplitResult& split, geodesic::ExactGeodesic& propagation,
                  const CountViolations& count_violations) {
    if (!split.done) return 0;
    const CoarseMesh& coarse = g.coarse();
    std::vector<OpenMesh::VertexHandle> added{split.vertex};
    int count = count_violations(g);
    // Does `operation` on a copy of G and keeps it when it lowers the count. The copy is made in the storage of the
    // one before: a new copy for each step tried, and its destruction, were most of untangling a sponge of genus
    // 1409 once fork splits were all that was left to try.
    std::optional<GeodesicTriangulation> copy;
    auto keep_if_lower = [&](const std::function<bool(GeodesicTriangulation&)>& operation) {
        if (copy) copy->assign(g);
        else copy.emplace(g);
        int after = 0;
        try {
            if (!operation(*copy)) return false;
            after = count_violations(*copy);
        } catch (const InvalidInput&) {
            return false;  // G is unfit for it around there (it is not valid): this step fails, not the split
        }
        if (after >= count) return false;
        g.assign(*copy);
        count = after;
        return true;
    };
    for (int step = 0; step < k_max_settle_steps && count > 0; ++step) {
        std::set<int> edges, vertices;
        for (OpenMesh::VertexHandle a : added) {
            vertices.insert(a.idx());
            for (HalfedgeHandle h : coarse.voh_range(a)) {
                edges.insert(coarse.edge_handle(h).idx());
                edges.insert(coarse.edge_handle(coarse.next_halfedge_handle(h)).idx());
                vertices.insert(coarse.to_vertex_handle(h).idx());
            }
        }
        bool kept = false;
        for (auto it = edges.begin(); it != edges.end() && !kept; ++it) {
            const EdgeHandle e(*it);
            if (coarse.is_boundary(e) || !coarse.is_flip_ok(e)) continue;
            kept = keep_if_lower([&](GeodesicTriangulation& trial) {
                FlipOptions unchecked;
                unchecked.check_validity = false;
                return flip(trial, e, unchecked, propagation_only(propagation)).accepted();
            });
        }
        for (auto it = vertices.begin(); it != vertices.end() && !kept; ++it)
            for (const Fork& fork : find_forks(g, OpenMesh::VertexHandle(*it))) {
                OpenMesh::VertexHandle split_vertex;
                kept = keep_if_lower([&](GeodesicTriangulation& trial) {
                    const SplitResult split = split_fork(trial, fork, {}, propagation_only(propagation));
                    split_vertex = split.vertex;
                    return split.done;
                });
                if (kept) {
                    added.push_back(split_vertex);
                    break;
                }
            }
        if (!kept) break;
    }
    return 1;
}

/// The places where the violations of condition 3 say that two geodesics meet at a vertex of T that is inside
/// both: each of the two edges with the index of that vertex in its polyline. Sorted, without repeats.
std::vector<std::pair<EdgeHandle, std::size_t>> meetings_at_fine_vertices(const GeodesicTriangulation& g,
                                                                          const ValidationReport& report) {
    auto inner_vertices = [&](EdgeHandle e) {
        std::vector<std::pair<int, std::size_t>> found;  // fine vertex, index
        const Polyline& line = g.polyline(e);
        for (std::size_t i = 1; i + 1 < line.size(); ++i)
            if (line[i].kind == geodesic::PointKind::vertex) found.emplace_back(line[i].vertex, i);
        std::sort(found.begin(), found.end());
        return found;
    };
    std::set<std::pair<int, std::size_t>> places;
    for (const Violation& v : report.violations) {
        if (v.condition != 3 || v.coarse_edges.size() != 2 || v.coarse_edges[0] == v.coarse_edges[1]) continue;
        const EdgeHandle e(v.coarse_edges[0]), f(v.coarse_edges[1]);
        const auto in_e = inner_vertices(e), in_f = inner_vertices(f);
        for (const auto& [vertex, i] : in_e)
            for (const auto& [other, j] : in_f)
                if (vertex == other) {
                    places.emplace(e.idx(), i);
                    places.emplace(f.idx(), j);
                }
    }
    std::vector<std::pair<EdgeHandle, std::size_t>> out;
    for (const auto& [e, i] : places) out.emplace_back(EdgeHandle(e), i);
    return out;
}

/// Throws std::logic_error unless `counted`, the violations of conditions 1-3 of a G that ViolationCount found, are
/// those of `report`, validate()'s on that G.
void check_count(int counted, const ValidationReport& report, const char* what) {
    if (counted != cheap_count(report))
        throw std::logic_error(std::string("untangling: ") + what + ": " + std::to_string(counted) +
                               " violations counted from what changed, " + std::to_string(cheap_count(report)) +
                               " by validate()");
}

/// Untangling's judge: `trial` is better when it has fewer violations of conditions 1-3 than `report`, or none
/// (as `report`) and fewer of condition 4. Conditions 1-3 are counted first, without the overlay, which costs most,
/// and from what trial changed (`count`, made from the G that trial was copied from, with its verdicts `known`);
/// the overlay is built only for a trial without such violations. That is enough while there are some: an
/// embedding of the coarse graph that keeps its rotation system (conditions 1-3) cuts T into disks by Euler's
/// formula, so condition 4 fails alone only by rounding. `cheap` is trial's count of conditions 1-3; `after` its
/// report, with condition 4, when it was needed (no violations of conditions 1-3); `changed`, where it differs from
/// the G that `count` counts.
bool lowers_violations(const GeodesicTriangulation& trial, const ValidationReport& report,
                       const detail::PolylineVerdicts& known, const detail::ViolationCount& count, int& cheap,
                       std::optional<ValidationReport>& after, detail::ViolationCount::Changed& changed) {
    ValidationOptions no_overlay;
    no_overlay.overlay = false;
    cheap = count.count(trial, known, changed);
#ifndef NDEBUG
    check_count(cheap, detail::validate(trial, no_overlay, known), "a trial");
#endif
    if (cheap > 0) return cheap < cheap_count(report);
    after = detail::validate(trial, no_overlay, known);
    check_count(cheap, *after, "a trial without violations");
    add_overlay_check(trial, *after);
    return cheap_count(report) > 0 || total(*after) < total(report);
}

/// `report` without its condition 4, as validate() without the overlay gives it: while conditions 1-3 fail,
/// untangling neither counts nor looks at condition 4.
ValidationReport without_condition_4(ValidationReport report) {
    report.violations.erase(std::remove_if(report.violations.begin(), report.violations.end(),
                                           [](const Violation& v) { return v.condition == 4; }),
                            report.violations.end());
    report.violation_count[3] = 0;
    report.overlay_checked = false;
    return report;
}

/// `report` with only the violations that name a coarse vertex at one of the locations `focus`.
ValidationReport violations_naming(const GeodesicTriangulation& g, ValidationReport report,
                                   const std::vector<SurfacePoint>& focus) {
    auto elsewhere = [&](const Violation& v) {
        return std::none_of(v.coarse_vertices.begin(), v.coarse_vertices.end(), [&](int c) {
            return std::find(focus.begin(), focus.end(), g.location(OpenMesh::VertexHandle(c))) != focus.end();
        });
    };
    report.violations.erase(std::remove_if(report.violations.begin(), report.violations.end(), elsewhere),
                            report.violations.end());
    return report;
}

/// collapse_edge(g, h) without its validity check: untangling judges the result on all of G.
CollapseResult collapse_unchecked(GeodesicTriangulation& g, HalfedgeHandle h, geodesic::ExactGeodesic& propagation) {
    CollapseOptions unchecked;
    unchecked.check_validity = false;
    return collapse_edge(g, h, unchecked, propagation_only(propagation));
}

/// One untangling move: `run` does it on a copy of G with the propagation object of its thread, and returns how
/// many operations it did (0: not possible there); a move of several steps can judge them with the count it is
/// given. `key` names it by kind and coarse vertices.
struct Move {
    std::function<int(GeodesicTriangulation&, geodesic::ExactGeodesic&, const CountViolations&)> run;
    std::array<int, 3> key;
};

/// The kinds of untangling moves, for their keys.
enum MoveKind : int {
    k_flip,
    k_fork_split,
    k_fork_chain,
    k_meeting_split,
    k_collapse,
    k_relocate,
    k_flip_pair,
    k_collapse_and_untangle,
    k_collapse_and_untangle_nested
};

/// Work that a kind of move may do, in windows of propagation (UntangleOptions::thorough_budget).
struct WorkBudget {
    std::size_t limit = 0;  ///< 0: no bound
    std::size_t spent = 0;
    bool spent_all() const { return limit > 0 && spent >= limit; }
};

/// Tries untangling moves on copies of G and keeps the first that lowers the violation count.
class Untangler {
public:
    /// `skip_known_failures`: flips and vertex moves known to fail again are not tried (StaleTrials). Not inside a
    /// trial that a budget of work may bound: a move not tried spends no work, and the budget would run out
    /// elsewhere than where the trial's caller counted it.
    Untangler(GeodesicTriangulation& g, ValidationReport& report, const UntangleOptions& options,
              geodesic::ExactGeodesic* propagation, UntangleResult& result, bool skip_known_failures)
        : g_(g), report_(report), result_(result), skip_known_failures_(skip_known_failures),
          given_propagation_(propagation), verdicts_(g, {}) {
        recount();
        threads_ = detail::team_size(options.threads);
        propagations_.resize(static_cast<std::size_t>(threads_));
        trial_storage_.resize(static_cast<std::size_t>(threads_));
    }

    /// Tries `moves` and keeps the first that is possible and lowers the count: G and report become its, and
    /// `kept` grows by its operations. Moves that were tried before without success go last, in their order: a
    /// move that helps is then found sooner, and none is left out. The moves run in parallel, each thread taking
    /// the next one as soon as it is free, but their outcomes are read in order, as if they had run one after
    /// another: moves after the kept one are dropped uncounted, so that G and every count are the same for any
    /// thread count. A move that throws InvalidInput found G unfit for it around there (untangling works on an
    /// invalid G): it counts as not possible. With a `budget`, each move tried spends the work of its
    /// propagations, and none after the one that spends the rest is read.
    bool keep_first_better(std::vector<Move> moves, int& kept, WorkBudget* budget = nullptr) {
        std::stable_partition(moves.begin(), moves.end(), [&](const Move& m) { return !failed_.count(m.key); });
        struct Trial {
            std::optional<GeodesicTriangulation> g;  ///< kept only where it is better
            std::optional<ValidationReport> report;
            int cheap = 0;  ///< violations of conditions 1-3
            int operations = 0;
            std::size_t work = 0;  ///< windows that the move's propagations made
            bool better = false;
            detail::ViolationCount::Changed changed;  ///< where it differs from G, once judged
            std::vector<int> faces;  ///< a flip or move that failed: the fine faces that its judgement read
            std::exception_ptr error;
        };
        // While conditions 1-3 fail, a flip or a vertex move that failed before is known to fail again where
        // nothing that it read has changed (StaleTrials): conditions 1-3 are counted from what a trial changes,
        // and a trial is better when that count drops. Both are one operation whose geodesics depend only on the
        // locations of their ends. With no such violations left, condition 4 decides, which all of G takes part in.
        const bool known_failures = skip_known_failures_ && cheap_count(report_) > 0;
        const CountViolations count_trial = [this](const GeodesicTriangulation& trial) {
            return count_->count(trial, verdicts_);
        };
        const std::size_t n = moves.size();
        std::vector<Trial> trials(n);
        // No trial after `last` is read: the first found better or failing, or the one whose work, added to the
        // work of every trial before it, spends the budget. Batches of one trial per thread left threads idle
        // while the slowest of a batch ran (femur_cgal's nested collapses: 0 and 5.7M windows in one batch).
        std::mutex progress;
        std::size_t last = n;
        std::size_t finished_before = 0;  ///< every trial before it has finished
        std::vector<char> finished(n, 0);
        WorkBudget read = budget ? *budget : WorkBudget{};  ///< the budget as the trials read so far spent it
#ifdef _OPENMP
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1)
#endif
        for (long i = 0; i < static_cast<long>(n); ++i) {
            const auto k = static_cast<std::size_t>(i);
            {
                std::lock_guard<std::mutex> lock(progress);
                if (k > last) continue;
            }
            Trial& t = trials[k];
            const bool local_move = known_failures && (moves[k].key[0] == k_flip || moves[k].key[0] == k_relocate);
            if (const std::optional<int> known = local_move ? stale_.known_failure(moves[k].key) : std::nullopt) {
                t.operations = *known;  // it failed before, and nothing that it read has changed since
            } else {
                try {
                    GeodesicTriangulation& trial = trial_copy();
                    geodesic::ExactGeodesic& p = propagation();
                    const std::size_t work_before = p.windows_created_total();
                    try {
                        t.operations = moves[k].run(trial, p, count_trial);
                    } catch (const InvalidInput&) {
                        t.operations = 0;
                    }
                    t.work = p.windows_created_total() - work_before;
                    t.better = t.operations > 0 &&
                               lowers_violations(trial, report_, verdicts_, *count_, t.cheap, t.report, t.changed);
                    if (t.better) t.g.emplace(std::move(trial));  // takes the coarse mesh along
                    else if (local_move && t.operations > 0)
                        t.faces = detail::StaleTrials::changed_faces(g_, trial, t.changed.edges, t.changed.vertices);
                } catch (...) {
                    t.error = std::current_exception();
                }
            }
            std::lock_guard<std::mutex> lock(progress);
            finished[k] = 1;
            if (t.better || t.error) last = std::min(last, k);
            if (k > last) t.g.reset();  // a better one comes before it: only memory now
            for (; finished_before < n && finished[finished_before]; ++finished_before) {
                read.spent += trials[finished_before].work;
                if (read.spent_all()) last = std::min(last, finished_before);
            }
        }
        for (std::size_t i = 0; i < n && i <= last; ++i) {
            Trial& t = trials[i];
            if (t.error) std::rethrow_exception(t.error);
            if (budget) budget->spent += t.work;
            if (t.better) {
                adopt(*t.g, t.report, t.cheap, t.changed);
                kept += t.operations;
                // A collapse renumbers the coarse vertices, and with them the keys.
                const int kind = moves[i].key[0];
                if (kind == k_collapse || kind == k_collapse_and_untangle || kind == k_collapse_and_untangle_nested)
                    forget_failures();
                return true;
            }
            ++(t.operations == 0 ? result_.refused : result_.rejected);
            failed_.insert(moves[i].key);
            if (!t.faces.empty()) stale_.failed(moves[i].key, std::move(t.faces), t.operations);
            if (budget && budget->spent_all() && i + 1 < n) {
                result_.thorough_budget_spent = true;
                return false;  // the moves after it are dropped uncounted, as after a kept one
            }
        }
        return false;
    }

    /// Makes the report validate()'s, with its words and, where conditions 1-3 hold, condition 4: the counts and
    /// what each violation names are those already.
    void exact() {
        if (!report_exact_) {
            ValidationOptions no_overlay;
            no_overlay.overlay = false;
            report_ = detail::validate(g_, no_overlay, verdicts_);
            check_count(count_->count(), report_, "the G kept");
            report_exact_ = true;
        }
        add_overlay_check(g_, report_);
    }

    /// Makes `next` G, whatever its violations: a step that is not judged by them (bisect_tangled_edges()).
    void replace(GeodesicTriangulation next) {
        g_ = std::move(next);
        verdicts_ = detail::PolylineVerdicts(g_, verdicts_);
        ValidationOptions no_overlay;
        no_overlay.overlay = false;
        report_ = detail::validate(g_, no_overlay, verdicts_);
        // Without violations of conditions 1-3 that report says valid; the overlay decides condition 4, as for a
        // trial (lowers_violations()), so that untangling goes on with what is left of it.
        if (cheap_count(report_) == 0) add_overlay_check(g_, report_);
        report_exact_ = true;
        recount();
        forget_failures();
    }

private:
    /// The coarse elements were renumbered: the keys name others now.
    void forget_failures() {
        failed_.clear();
        stale_.clear();
    }

    /// Keeps what it takes to count the violations of trial copies of G from what they change.
    void recount() {
        count_.emplace(g_, verdicts_);
        check_count(count_->count(), report_, "G");
    }

    /// G becomes `trial`, a kept trial with `cheap` violations of conditions 1-3 that differs from G where
    /// `changed` says; report_ becomes its `report` where lowers_violations() made one, else the count's (exact()
    /// adds the words). The count and the verdicts are made from G's and what the trial changed: untangling a
    /// genus-293 grate keeps 598 trials, and validating and counting each in full was two thirds of its time.
    /// Where it throws, G is as it was.
    void adopt(GeodesicTriangulation& trial, std::optional<ValidationReport>& report, int cheap,
               const detail::ViolationCount::Changed& changed) {
        detail::ViolationCount count(*count_, trial, verdicts_);
        if (count.count() != cheap)
            throw std::logic_error("untangling: a kept trial: " + std::to_string(cheap) + " violations counted, " +
                                   std::to_string(count.count()) + " by its own count");
        const bool exact = report.has_value();
        if (exact) check_count(count.count(), *report, "G");
        else report = count.report();
#ifndef NDEBUG
        {
            ValidationOptions no_overlay;
            no_overlay.overlay = false;
            check_count(cheap, detail::validate(trial, no_overlay, verdicts_), "a kept trial");
        }
#endif
        verdicts_.advance(trial, changed.edges);
        stale_.changed(detail::StaleTrials::changed_faces(g_, trial, changed.edges, changed.vertices));
        g_ = std::move(trial);
        report_ = std::move(*report);
        report_exact_ = exact;
        count_ = std::move(count);
    }

    /// A copy of G for the calling thread's next trial, in the storage of its last one where that was not kept
    /// (a kept trial takes its coarse mesh along, and the next copy is a new one): a copy of G into new storage for
    /// every trial was an eighth of untangling cheese (PropertyT::clone() and clear()).
    GeodesicTriangulation& trial_copy() {
        std::size_t k = 0;
#ifdef _OPENMP
        k = static_cast<std::size_t>(omp_get_thread_num());
#endif
        std::optional<GeodesicTriangulation>& storage = trial_storage_[k];
        if (storage) *storage = g_;
        else storage.emplace(g_);
        return *storage;
    }

    /// The calling thread's propagation object, made on first use.
    geodesic::ExactGeodesic& propagation() {
        std::size_t k = 0;
#ifdef _OPENMP
        k = static_cast<std::size_t>(omp_get_thread_num());
#endif
        if (k == 0 && given_propagation_) return *given_propagation_;
        if (!propagations_[k]) propagations_[k] = std::make_unique<geodesic::ExactGeodesic>(g_.fine().mesh);
        return *propagations_[k];
    }

    GeodesicTriangulation& g_;
    ValidationReport& report_;
    UntangleResult& result_;
    const bool skip_known_failures_;
    int threads_ = 1;
    geodesic::ExactGeodesic* given_propagation_;  ///< the calling thread's, when its caller gave one
    std::vector<std::unique_ptr<geodesic::ExactGeodesic>> propagations_;  ///< one per thread without a given one
    std::vector<std::optional<GeodesicTriangulation>> trial_storage_;      ///< one per thread (trial_copy())
    std::unordered_set<std::array<int, 3>, detail::MoveKeyHash> failed_;  ///< keys of the moves tried without success
    detail::StaleTrials stale_;            ///< the flips among them that are known to fail again
    bool report_exact_ = true;             ///< report_ is validate()'s, not the count's (exact())
    detail::PolylineVerdicts verdicts_;    ///< condition 1 on G's polylines, for judging the trials
    std::optional<detail::ViolationCount> count_;  ///< G's violations of conditions 1-3, to count the trials'
};

/// Untangles by single flips, where no flip helps by fork splits, then by edge collapses, then by moving vertices,
/// and with a few violations left by pairs of flips and longer moves and (UntangleOptions::thorough, within
/// its budget of work) collapses judged after untangling, while they strictly lower the number of violations (see
/// lowers_violations()), which bounds their number; where none of them helps, by bisecting the edges that the
/// violations name (a bounded number of rounds, not judged; `keep_bisection_vertices`: collapses do not take the new
/// vertices out). With a `focus`, moves are sought only for the violations that name a coarse vertex at one of its
/// locations, no plain collapses are tried, of the last resorts only the collapses judged after untangling, and only
/// where `options.thorough` asks for them, and nothing is bisected.
/// `report` is validate(g) on entry and on exit.
void untangle_in_place(GeodesicTriangulation& g, const UntangleOptions& options,
                       geodesic::ExactGeodesic* calling_propagation,
                       UntangleResult& result, ValidationReport& report,
                       const std::vector<SurfacePoint>* focus = nullptr, bool keep_bisection_vertices = false) {
    if (cheap_count(report) > 0) report = without_condition_4(std::move(report));
    // A focus is given only to the untangling inside a trial, which a budget of work may bound.
    Untangler untangler(g, report, options, calling_propagation, result, focus == nullptr);
    // The violations that moves are sought for: all (`report`, not copied: there may be thousands), or with a focus
    // those that name a coarse vertex there (`focused`).
    ValidationReport focused;
    const ValidationReport* named = &report;
    auto try_flips = [&] {
        std::vector<Move> moves;
        for (int index : candidate_edges(g.coarse(), *named)) {
            const EdgeHandle e(index);
            if (g.coarse().is_boundary(e) || !g.coarse().is_flip_ok(e)) continue;
            const int a = g.coarse().to_vertex_handle(g.coarse().halfedge_handle(e, 0)).idx();
            const int b = g.coarse().to_vertex_handle(g.coarse().halfedge_handle(e, 1)).idx();
            auto run = [e](GeodesicTriangulation& trial, geodesic::ExactGeodesic& propagation, const CountViolations&) {
                FlipOptions unchecked;
                unchecked.check_validity = false;
                return flip(trial, e, unchecked, propagation_only(propagation)).accepted() ? 1 : 0;
            };
            moves.push_back({run, {k_flip, std::min(a, b), std::max(a, b)}});
        }
        return untangler.keep_first_better(moves, result.flips);
    };
    auto try_fork_splits = [&] {
        std::vector<Move> moves;
        for (int index : candidate_vertices(g.coarse(), *named))
            for (const Fork& fork : find_forks(g, OpenMesh::VertexHandle(index))) {
                auto run = [fork](GeodesicTriangulation& trial, geodesic::ExactGeodesic& propagation,
                                                 const CountViolations& count) {
                    const SplitResult split = split_fork(trial, fork, {}, propagation_only(propagation));
                    return settle_around(trial, split, propagation, count);
                };
                moves.push_back({run, {k_fork_split, index, g.coarse().to_vertex_handle(fork.first).idx()}});
            }
        return untangler.keep_first_better(moves, result.fork_splits);
    };
    // Forks come in chains where many geodesics pass through the same saddles of T: a fork split's new edges fork
    // again at the next vertex, and no single split lowers the count. The chain splits a fork at every vertex that
    // the violations name, round after round while there are any, and is judged as one move.
    auto try_fork_chain = [&] {
        const ValidationReport& start = *named;
        auto chain = [&start](GeodesicTriangulation& trial, geodesic::ExactGeodesic& propagation,
                                             const CountViolations&) {
            ValidationOptions cheap;
            cheap.overlay = false;
            ValidationReport current = start;
            int splits = 0;
            for (int round = 0; round < k_max_fork_chain_rounds; ++round) {
                int done = 0;
                for (int index : candidate_vertices(trial.coarse(), current)) {
                    const std::vector<Fork> forks = find_forks(trial, OpenMesh::VertexHandle(index));
                    if (!forks.empty() && split_fork(trial, forks.front(), {}, propagation_only(propagation)).done) ++done;
                }
                if (done == 0) break;
                splits += done;
                current = validate(trial, cheap);
            }
            return splits > 1 ? splits : 0;  // one split alone was tried already
        };
        // Its key changes with the number of violations, so that it is tried again first once they have changed.
        return untangler.keep_first_better({{chain, {k_fork_chain, total(report), 0}}}, result.fork_splits);
    };
    // Shortest geodesics from different vertices meet at saddle vertices of T, and where several pass through one,
    // no flip parts them: a coarse vertex there, splitting one of them, settled (settle_around()), may.
    auto try_meeting_splits = [&] {
        std::vector<Move> moves;
        for (const auto& [e, index] : meetings_at_fine_vertices(g, *named)) {
            auto run = [e = e, index = index](GeodesicTriangulation& trial,
                                                            geodesic::ExactGeodesic& propagation,
                                                            const CountViolations& count) {
                SplitOptions unchecked;
                unchecked.checked = false;
                const SplitResult split =
                    split_edge_at_point(trial, e, index, unchecked, propagation_only(propagation));
                return settle_around(trial, split, propagation, count);
            };
            moves.push_back({run, {k_meeting_split, e.idx(), static_cast<int>(index)}});
        }
        return untangler.keep_first_better(moves, result.meeting_splits);
    };
    // The vertices that bisections added; with keep_bisection_vertices, collapses do not take them out again.
    std::vector<SurfacePoint> bisection_vertices;
    auto added_by_bisection = [&](int index) {
        if (!keep_bisection_vertices) return false;
        const SurfacePoint& p = g.location(OpenMesh::VertexHandle(index));
        return std::find(bisection_vertices.begin(), bisection_vertices.end(), p) != bisection_vertices.end();
    };
    // A collapse removes a coarse vertex whose edges no flip or split could straighten out: its neighbours are
    // joined to the vertex it merges into by new shortest geodesics.
    auto try_collapses = [&] {
        std::vector<Move> moves;
        for (int index : candidate_vertices(g.coarse(), *named))
            for (HalfedgeHandle h : g.coarse().voh_ccw_range(OpenMesh::VertexHandle(index)))
            {
                if (added_by_bisection(index)) continue;
                auto run = [h](GeodesicTriangulation& trial, geodesic::ExactGeodesic& propagation,
                               const CountViolations&) {
                    return collapse_unchecked(trial, h, propagation).done ? 1 : 0;
                };
                moves.push_back({run, {k_collapse, index, g.coarse().to_vertex_handle(h).idx()}});
            }
        return untangler.keep_first_better(moves, result.collapses);
    };
    // The last resorts search wider than the moves before them, and where they mend nothing they cost the more the
    // finer T is around G's vertices: on a CAD part whose flat faces are fans of needles, six rings of T around a
    // vertex hold a thousand vertices of T, and moving 20 vertices to each of them cost z_bottom_cover at 320
    // faces 2.0G windows (146 s) that mended nothing, where the bisections after them did in 0.7 s. So all of them
    // together, in the order tried, make at most options.thorough_budget windows of propagation.
    WorkBudget budget{options.thorough_budget};
    // Whether some of the budget is left; says so in the result where none is.
    auto budget_left = [&] {
        if (!budget.spent_all()) return true;
        result.thorough_budget_spent = true;
        return false;
    };
    // A coarse vertex on the wrong side of a thin wall or a small handle has geodesics that wind around it twice,
    // whatever its edges: moved a little, to a vertex of T nearby, its new geodesics may wind once.
    // `rings` fine edges away at most, and more than `inner`: nearby_fine_vertices() lists the nearest rings first.
    // `last_resort`: the moves spend the last resorts' budget.
    auto try_relocations = [&](int rings, int inner, bool last_resort) {
        if (last_resort && !budget_left()) return false;
        std::vector<Move> moves;
        for (int index : candidate_vertices(g.coarse(), *named)) {
            const OpenMesh::VertexHandle v(index);
            const std::vector<int> nearby = nearby_fine_vertices(g, v, rings);
            const std::size_t tried = inner > 0 ? nearby_fine_vertices(g, v, inner).size() : 0;
            for (auto it = nearby.begin() + static_cast<std::ptrdiff_t>(tried); it != nearby.end(); ++it) {
                const int to = *it;
                auto run = [v, to](GeodesicTriangulation& trial, geodesic::ExactGeodesic& propagation,
                                   const CountViolations&) {
                    RelocateOptions unchecked;
                    unchecked.check_validity = false;
                    return relocate_vertex(trial, v, SurfacePoint::at_vertex(to), unchecked,
                                           propagation_only(propagation))
                                   .done
                               ? 1
                               : 0;
                };
                moves.push_back({run, {k_relocate, index, to}});
            }
        }
        return untangler.keep_first_better(moves, result.relocations, last_resort ? &budget : nullptr);
    };
    // Two tangled faces side by side can need two flips where either alone changes nothing that is counted (the
    // other face still tangles the same geodesics): the second flip is of an edge of a face of the first edge.
    auto try_flip_pairs = [&] {
        if (!budget_left()) return false;
        std::vector<Move> moves;
        const CoarseMesh& coarse = g.coarse();
        for (int index : candidate_edges(coarse, *named)) {
            const EdgeHandle first(index);
            if (coarse.is_boundary(first) || !coarse.is_flip_ok(first)) continue;
            for (int side = 0; side < 2; ++side)
                for (EdgeHandle second : coarse.fe_range(coarse.face_handle(coarse.halfedge_handle(first, side)))) {
                    if (second == first || coarse.is_boundary(second)) continue;
                    auto run = [first, second](GeodesicTriangulation& trial, geodesic::ExactGeodesic& propagation,
                                               const CountViolations&) {
                        FlipOptions unchecked;
                        unchecked.check_validity = false;
                        const Workspace workspace = propagation_only(propagation);
                        if (!flip(trial, first, unchecked, workspace).accepted()) return 0;
                        return flip(trial, second, unchecked, workspace).accepted() ? 2 : 0;
                    };
                    moves.push_back({run, {k_flip_pair, first.idx(), second.idx()}});
                }
        }
        return untangler.keep_first_better(moves, result.flips, &budget);
    };
    // A collapse that raises the count can still be the way out (skull_thing74168, anchor_dense and boxpart at
    // their coarsest): each is judged after untangling what it leaves, with moves sought only for the violations
    // around the vertex kept, and without the other last resorts; `nested`, that untangling may itself end with
    // such collapses (femur_cgal at 320 faces). Each trial untangles, so that they cost the more the longer G's
    // geodesics are (gears at its coarsest: 3-35M windows each).
    auto try_collapse_and_untangle = [&](bool nested) {
        if (!budget_left()) return false;
        std::vector<Move> moves;
        for (int index : candidate_vertices(g.coarse(), *named))
            for (HalfedgeHandle h : g.coarse().voh_ccw_range(OpenMesh::VertexHandle(index))) {
                if (added_by_bisection(index)) continue;
                auto run = [h, nested, &options](GeodesicTriangulation& trial, geodesic::ExactGeodesic& propagation,
                                                 const CountViolations&) {
                    const CollapseResult done = collapse_unchecked(trial, h, propagation);
                    if (!done.done) return 0;
                    std::vector<SurfacePoint> around{trial.location(done.kept)};
                    for (OpenMesh::VertexHandle u : trial.coarse().vv_range(done.kept))
                        around.push_back(trial.location(u));
                    UntangleOptions inner = options;
                    inner.threads = 1;  // the trials run in parallel already
                    inner.progress = nullptr;
                    inner.thorough = nested ? 1 : 0;
                    // Half the budget, and never 0 where there is one: 0 would lift it.
                    inner.thorough_budget =
                        options.thorough_budget > 0 ? std::max<std::size_t>(1, options.thorough_budget / 2) : 0;
                    UntangleResult inner_result;
                    ValidationReport inner_report = validate(trial);
                    untangle_in_place(trial, inner, &propagation, inner_result, inner_report, &around);
                    return 1;  // one collapse, with the moves that follow it
                };
                const int kind = nested ? k_collapse_and_untangle_nested : k_collapse_and_untangle;
                moves.push_back({run, {kind, index, g.coarse().to_vertex_handle(h).idx()}});
            }
        return untangler.keep_first_better(moves, result.collapses, &budget);
    };
    // Only where nothing above helps and few violations are left; with a focus, only the collapses judged after
    // untangling, and only where asked for.
    auto try_last_resorts = [&] {
        if (focus) return options.thorough >= 1 && try_collapse_and_untangle(false);
        if (cheap_count(report) > k_max_last_resort_violations) return false;
        result.last_resorts_tried = true;
        return try_flip_pairs() || try_relocations(k_wide_relocation_rings, k_relocation_rings, true) ||
               (options.thorough >= 1 && try_collapse_and_untangle(false)) ||
               (options.thorough >= 2 && try_collapse_and_untangle(true));
    };
    // Where no move lowers the count, G is too coarse there: its geodesics wind around handles and between holes
    // of T that its vertices are too few to separate (stress/cheese.off, genus 133, at 1174 faces; the same mesh
    // decimated to 2400 faces untangles). Bisecting every edge that a violation names, at the middle of its
    // polyline, halves those geodesics; the count may rise, and untangling goes on from there. A bounded number
    // of rounds keeps it finite.
    int bisection_rounds = 0;
    auto bisect_tangled_edges = [&] {
        if (focus || bisection_rounds >= options.bisection_rounds) return false;
        std::set<std::pair<int, int>> ends;  // by their end vertices: splits renumber nothing but add edges
        const CoarseMesh& coarse = g.coarse();
        for (const Violation& v : report.violations)
            for (int index : v.coarse_edges) {
                const HalfedgeHandle h = coarse.halfedge_handle(EdgeHandle(index), 0);
                ends.insert({coarse.from_vertex_handle(h).idx(), coarse.to_vertex_handle(h).idx()});
            }
        GeodesicTriangulation next = g;
        int splits = 0;
        geodesic::ExactGeodesic propagation(g.fine().mesh);
        SplitOptions unchecked;
        unchecked.checked = false;
        for (const auto& [a, b] : ends) {
            const HalfedgeHandle h =
                next.coarse().find_halfedge(OpenMesh::VertexHandle(a), OpenMesh::VertexHandle(b));
            if (!h.is_valid()) continue;
            GeodesicTriangulation split_g = next;  // a split that throws may have changed what it was given
            try {
                const SplitResult split = split_edge(split_g, split_g.coarse().edge_handle(h), 0.5, unchecked,
                                                      propagation_only(propagation));
                if (!split.done) continue;
                bisection_vertices.push_back(split_g.location(split.vertex));
                next = std::move(split_g);
                ++splits;
            } catch (const InvalidInput&) {
                // G is unfit for it around there: that edge stays
            }
        }
        if (splits == 0) return false;
        ++bisection_rounds;
        result.bisections += splits;
        untangler.replace(std::move(next));
        return true;
    };
    int round = 0;
    while (!report.valid && result.flips + result.fork_splits + result.meeting_splits +
                                    result.collapses + result.relocations <
                                options.max_operations) {
        ++round;
        if (focus) {
            focused = violations_naming(g, report, *focus);
            named = &focused;
        }
        if (focus && named->violations.empty()) {  // what is left is elsewhere
            result.stuck = true;
            break;
        }
        // With a focus, G is a collapse's trial: no plain collapses then. They were most of what the trials cost
        // (femur_cgal: 59M windows, 22 s; without them 13M, 6.7 s) and mended nothing more; nesting collapses is
        // what level 2 does.
        if (!try_flips() && !try_fork_splits() && !try_fork_chain() && !try_meeting_splits() &&
            (focus || !try_collapses()) && !try_relocations(k_relocation_rings, 0, false) && !try_last_resorts() &&
            !bisect_tangled_edges()) {
            result.stuck = true;
            break;
        }
        if (options.progress)
            options.progress("untangle round " + std::to_string(round) + ": " + std::to_string(total(report)) +
                             " violations left");
    }
    result.thorough_windows = budget.spent;
    untangler.exact();
}

}  // namespace

UntangleResult untangle(GeodesicTriangulation& g, const UntangleOptions& options) {
    ValidationReport report = validate(g);
    return detail::untangle_validated(g, options, report);
}

namespace detail {

UntangleResult untangle_validated(GeodesicTriangulation& g, const UntangleOptions& options, ValidationReport& report) {
    const auto start = std::chrono::steady_clock::now();
    UntangleResult result;
    result.valid_before = report.valid;
    result.violations_before = report.violation_count;
    if (!report.valid) {
        const GeodesicTriangulation given = g;
        const UntangleResult given_result = result;
        const ValidationReport given_report = report;
        untangle_in_place(g, options, nullptr, result, report);
        // The collapses after a round of bisections can take its vertices out again and leave G as tangled as it
        // was (fertility at its coarsest); anchor and 42400-IDGH at theirs need some taken out. So where G is left
        // invalid after bisections, untangling starts again from the G given with those vertices kept, and the
        // result with fewer violations is kept (the first where they tie).
        if (!report.valid && result.bisections > 0) {
            if (options.progress) options.progress("untangling again, keeping the vertices that bisections add");
            GeodesicTriangulation again = given;
            UntangleResult again_result = given_result;
            ValidationReport again_report = given_report;
            try {
                untangle_in_place(again, options, nullptr, again_result, again_report, nullptr, true);
                again_result.kept_bisection_vertices = true;
                if (total(again_report) < total(report)) {
                    g = std::move(again);
                    result = again_result;
                    report = std::move(again_report);
                }
            } catch (const NumericalError&) {
                // The second untangling only tries to do better: where it meets numerical trouble, the first stands.
            }
        }
    }
    result.valid_after = report.valid;
    result.violations_after = report.violation_count;
    if (!report.valid) result.remaining = report.violations;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace detail

}  // namespace geotri

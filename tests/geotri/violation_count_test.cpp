// Untangling's judge (libgeotri/src/check/violation_count.h): the violations of conditions 1-3 of a trial copy of G,
// counted from what the trial changed, against validate() on the whole copy. Random operations of every kind that
// untangling tries, and hand-made changes that break the conditions in other ways (polylines reversed, erased or
// moved to another edge, vertices moved without their edges, two vertices at one point), on G that random walks
// tangle further, over procedural meshes and a bundled real mesh.

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/collapse.h>
#include <geotri/fine_mesh.h>
#include <geotri/flip.h>
#include <geotri/relocate.h>
#include <geotri/split.h>
#include <geotri/trace.h>
#include <geotri/validate.h>

#include <geotri_test/fine_mesh.h>
#include <geotri_test/g_checks.h>
#include <geotri_test/procedural_meshes.h>

#include "ops/with_workspace.h"

#include "check/polyline_verdicts.h"  // libgeotri/src: untangling's verdicts kept between validations
#include "check/violation_count.h"    // libgeotri/src: untangling's count of violations from what a trial changed
#include "pipeline/stale_trials.h"       // libgeotri/src: the fine faces that a trial's count reads

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <iostream>
#include <iterator>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace geotri {
namespace {

using geodesic::SurfacePoint;
using OpenMesh::EdgeHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;
using test::decimated_coarse;
using test::fine_of;

/// Violations of conditions 1-3, as validate() without the overlay names them: the oracle.
int validated(const GeodesicTriangulation& g) {
    const ValidationReport r = validate(g, ValidationOptions{false});
    return r.violation_count[0] + r.violation_count[1] + r.violation_count[2];
}

/// The violations of a report, each as its condition and the coarse elements that it names, sorted: what
/// untangling reads of them.
std::vector<std::string> named(const ValidationReport& report) {
    std::vector<std::string> out;
    for (const Violation& v : report.violations) {
        std::string line = "condition " + std::to_string(v.condition);
        for (const auto& [what, list] : {std::make_pair("vertices", &v.coarse_vertices),
                                         std::make_pair("edges", &v.coarse_edges),
                                         std::make_pair("faces", &v.coarse_faces)}) {
            line += std::string("; ") + what;
            for (int i : *list) line += " " + std::to_string(i);
        }
        out.push_back(line);
    }
    std::sort(out.begin(), out.end());
    return out;
}

int uniform(std::mt19937& random, int n) { return std::uniform_int_distribution<int>(0, n - 1)(random); }

/// A random fine vertex near v's location: one of nearby_fine_vertices(), else any.
int nearby_vertex(const GeodesicTriangulation& g, VertexHandle v, std::mt19937& random) {
    const std::vector<int> near = nearby_fine_vertices(g, v, 2);
    if (!near.empty()) return near[static_cast<std::size_t>(uniform(random, static_cast<int>(near.size())))];
    return uniform(random, g.fine().mesh.num_vertices());
}

/// One random change of g, of the kinds that untangling makes or of kinds that break G otherwise, at edge `at_edge`
/// or vertex `at_vertex` where given, else at random ones; returns its name, or "" when it was not possible there.
std::string random_change(GeodesicTriangulation& g, std::mt19937& random, geodesic::ExactGeodesic& propagation,
                          EdgeHandle at_edge = EdgeHandle(), VertexHandle at_vertex = VertexHandle()) {
    CoarseMesh& coarse = g.coarse();
    const EdgeHandle e = at_edge.is_valid() ? at_edge : EdgeHandle(uniform(random, static_cast<int>(coarse.n_edges())));
    const VertexHandle v =
        at_vertex.is_valid() ? at_vertex : VertexHandle(uniform(random, static_cast<int>(coarse.n_vertices())));
    try {
        switch (uniform(random, 12)) {
        case 0:
        case 1: {
            FlipOptions unchecked;
            unchecked.check_validity = false;
            return flip(g, e, unchecked, propagation_only(propagation)).accepted() ? "flip" : "";
        }
        case 2: {
            const std::vector<Fork> forks = find_forks(g, v);
            if (forks.empty()) return "";
            return split_fork(g, forks.front(), {}, propagation_only(propagation)).done ? "fork split" : "";
        }
        case 3: {
            CollapseOptions unchecked;
            unchecked.check_validity = false;
            return collapse_edge(g, coarse.halfedge_handle(e, uniform(random, 2)), unchecked, propagation_only(propagation)).done
                       ? "collapse"
                       : "";
        }
        case 4: {
            RelocateOptions unchecked;
            unchecked.check_validity = false;
            return relocate_vertex(g, v, SurfacePoint::at_vertex(nearby_vertex(g, v, random)), unchecked,
                                   propagation_only(propagation))
                           .done
                       ? "move"
                       : "";
        }
        case 5: {
            // Into a fine face, whose edges then cross the faces around it.
            RelocateOptions unchecked;
            unchecked.check_validity = false;
            const int f = uniform(random, g.fine().mesh.num_faces());
            return relocate_vertex(g, v, SurfacePoint::in_face(f, {0.2, 0.3, 0.5}), unchecked, propagation_only(propagation))
                           .done
                       ? "move into a face"
                       : "";
        }
        case 6: {
            // Its edges stay where they were: condition 1 names them, and they drop out of conditions 2 and 3.
            g.set_location(v, SurfacePoint::at_vertex(nearby_vertex(g, v, random)));
            return "location moved";
        }
        case 7: {
            const VertexHandle w(uniform(random, static_cast<int>(coarse.n_vertices())));
            g.set_location(v, g.location(w));
            return "two vertices at one point";
        }
        case 8: {
            // On a fine edge, a hair (1e-13 of it, within validate()'s tolerance) from another vertex's location
            // (a fine vertex here), or from a fine vertex.
            const VertexHandle w(uniform(random, static_cast<int>(coarse.n_vertices())));
            const geodesic::Mesh& mesh = g.fine().mesh;
            const int a = g.location(w).kind == geodesic::PointKind::vertex ? g.location(w).vertex
                                                                            : uniform(random, mesh.num_vertices());
            const int b = mesh.head(mesh.outgoing(a));
            g.set_location(v, SurfacePoint::on_edge(a, b, uniform(random, 2) == 0 ? 1e-13 : 0.0));
            return "a hair from another vertex";
        }
        case 9: {
            // There, back and there again: it meets itself all along (and is not straight).
            const Polyline& path = g.polyline(e);
            if (path.size() < 2) return "";
            Polyline doubled = path;
            doubled.insert(doubled.end(), path.rbegin() + 1, path.rend());
            doubled.insert(doubled.end(), path.begin() + 1, path.end());
            g.set_polyline(e, doubled);
            return "polyline doubled back";
        }
        case 10: {
            Polyline reversed = g.polyline(e);
            std::reverse(reversed.begin(), reversed.end());
            g.set_polyline(e, reversed);
            return "polyline reversed";
        }
        default: {
            if (uniform(random, 2) == 0) {
                g.set_polyline(e, {});
                return "polyline erased";
            }
            g.set_polyline(e, g.polyline(EdgeHandle(uniform(random, static_cast<int>(coarse.n_edges())))));
            return "another edge's polyline";
        }
        }
    } catch (const InvalidInput&) {
        return "";  // as untangling: G unfit for the operation around there
    }
}

/// `trials` trial copies of g, each changed by one to three random changes, counted from what changed and by
/// validate(). One trial in `keep_every` becomes G (whatever its count), so that G wanders and tangles, and its
/// count is made from the one before and what changed, as untangling makes it; its report must name what
/// validate() names. Returns the number of trials whose count went down, for the caller to see that
/// both ways were exercised.
int check_random_trials(GeodesicTriangulation g, int trials, int keep_every, unsigned seed, const std::string& name) {
    std::mt19937 random(seed);
    geodesic::ExactGeodesic propagation(g.fine().mesh);
    detail::PolylineVerdicts verdicts(g, {});
    detail::ViolationCount count(g, verdicts);
    int g_count = validated(g);
    EXPECT_EQ(count.count(), g_count) << name;
    int lower = 0, higher = 0, kept = 0;
    for (int k = 0; k < trials; ++k) {
        GeodesicTriangulation trial = g;
        std::string changes;
        const int n = 1 + uniform(random, 3);
        for (int i = 0; i < n; ++i) {
            const std::string change = random_change(trial, random, propagation);
            if (!change.empty()) changes += (changes.empty() ? "" : ", ") + change;
        }
        const int expected = validated(trial);
        detail::ViolationCount::Changed changed;
        const int counted = count.count(trial, verdicts, changed);
        EXPECT_EQ(count.count(trial, verdicts), counted);
        EXPECT_EQ(counted, expected) << name << ", trial " << k << " (" << changes << "): G has " << g_count;
        if (counted != expected) return lower;  // one failure tells it; what follows would only repeat it
        (expected < g_count ? lower : higher) += 1;
        if (uniform(random, keep_every) == 0) {
            // Made from what changed, as untangling keeps a trial: the trials after it are counted from there.
            count = detail::ViolationCount(count, trial, verdicts);
            verdicts.advance(trial, changed.edges);
            g = trial;
            g_count = expected;
            EXPECT_EQ(count.count(), g_count) << name << ", kept trial " << k << " (" << changes << ")";
            const std::vector<std::string> oracle = named(validate(g, ValidationOptions{false}));
            EXPECT_EQ(named(count.report()), oracle) << name << ", kept trial " << k << " (" << changes << ")";
            EXPECT_EQ(named(detail::validate(g, ValidationOptions{false}, verdicts)), oracle)
                << name << ", kept trial " << k << " (" << changes << "): with the verdicts advanced";
            ++kept;
        }
    }
    std::cout << "[ count    ] " << name << ": " << trials << " trials (" << lower << " lower, " << higher
              << " not), " << kept << " kept; G ends with " << g.coarse().n_faces() << " faces and " << g_count
              << " violations\n";
    EXPECT_GT(higher, 0) << name;
    return lower;
}

TEST(ViolationCount, trials_on_a_perturbed_sphere_count_as_validate) {
    const auto fine = fine_of(test::perturbed_sphere(10, 0.05, 7));
    GeodesicTriangulation g(fine, decimated_coarse(*fine, 40));
    trace(g);
    EXPECT_GT(check_random_trials(g, 400, 8, 1, "perturbed sphere"), 0);
}

TEST(ViolationCount, trials_on_a_torus_count_as_validate) {
    // Genus 1: geodesics that wind around the handle, vertices whose edges wind more than once.
    const auto fine = fine_of(test::torus(1.0, 0.35, 48, 18));
    GeodesicTriangulation g(fine, decimated_coarse(*fine, 60));
    trace(g);
    EXPECT_GT(check_random_trials(g, 400, 8, 2, "torus"), 0);
}

/// The bundled anchor at 320 faces, traced: trace leaves forks and crossings that untangling starts from.
GeodesicTriangulation traced_anchor() {
    return test::traced(std::string(GEOTRI_TEST_DATA) + "/cad/anchor.off", 320);
}

TEST(ViolationCount, trials_on_a_tangled_real_mesh_count_as_validate) {
    GeodesicTriangulation g = traced_anchor();
    EXPECT_GT(validated(g), 0);
    EXPECT_GT(check_random_trials(g, 300, 10, 3, "anchor"), 0);
}

/// A move that untangling may skip where it failed before (StaleTrials): its name, the coarse vertices that it acts
/// at, and the move itself, to be done on G or a copy changed elsewhere (false: not possible there).
struct LocalMove {
    std::string name;
    std::vector<VertexHandle> at;
    std::function<bool(GeodesicTriangulation&)> run;
};

/// What StaleTrials relies on: a trial's change of the count depends only on what lies on the fine faces that it
/// reads (StaleTrials::changed_faces()). A move drawn by `draw` is tried on G, and again on G changed nearby (at an
/// edge or vertex within two rings of where it acts) by a random change of any kind that keeps the numbering (not a
/// collapse); where the two touch no common fine face, the move must be possible on both and change the count by
/// as much. Oracle: validate(). Returns the moves compared; `after_a_count_change`, those where the change
/// elsewhere changed G's count.
int compare_after_changes_elsewhere(const GeodesicTriangulation& g, std::mt19937& random,
                                    const std::function<LocalMove(std::mt19937&)>& draw, int& after_a_count_change) {
    const int g_count = validated(g);
    geodesic::ExactGeodesic propagation(g.fine().mesh);
    int compared = 0;
    after_a_count_change = 0;
    for (int k = 0; k < 2000 && compared < 100; ++k) {
        const LocalMove move = draw(random);
        GeodesicTriangulation moved = g;
        if (!move.run(moved)) continue;
        // The vertices within two rings of where it acts, and their edges.
        std::set<int> near_vertices, near_edges;
        for (VertexHandle c : move.at)
            for (VertexHandle n : g.coarse().vv_range(c)) {
                near_vertices.insert(n.idx());
                for (HalfedgeHandle h : g.coarse().voh_range(n)) {
                    near_vertices.insert(g.coarse().to_vertex_handle(h).idx());
                    near_edges.insert(g.coarse().edge_handle(h).idx());
                }
            }
        auto any_of_set = [&](const std::set<int>& from) {
            return *std::next(from.begin(), uniform(random, static_cast<int>(from.size())));
        };
        // Drawn one after the other: the order of a call's arguments is the compiler's.
        const EdgeHandle near_edge(any_of_set(near_edges));
        const VertexHandle near_vertex(any_of_set(near_vertices));
        GeodesicTriangulation elsewhere = g;
        const std::string change = random_change(elsewhere, random, propagation, near_edge, near_vertex);
        if (change.empty() || change == "collapse") continue;
        const std::vector<int> read = detail::StaleTrials::changed_faces(g, moved);
        const std::vector<int> other = detail::StaleTrials::changed_faces(g, elsewhere);
        std::vector<int> common;
        std::set_intersection(read.begin(), read.end(), other.begin(), other.end(), std::back_inserter(common));
        if (!common.empty()) continue;
        GeodesicTriangulation both = elsewhere;
        EXPECT_TRUE(move.run(both)) << "trial " << k << ": " << move.name << " after " << change;
        const int elsewhere_count = validated(elsewhere);
        EXPECT_EQ(validated(both) - elsewhere_count, validated(moved) - g_count)
            << "trial " << k << ": " << move.name << " after " << change;
        after_a_count_change += elsewhere_count != g_count;
        ++compared;
    }
    return compared;
}

TEST(ViolationCount, a_flip_changes_the_count_alike_after_a_change_on_other_fine_faces) {
    const GeodesicTriangulation g = traced_anchor();
    EXPECT_GT(validated(g), 0);
    std::mt19937 random(11);
    geodesic::ExactGeodesic propagation(g.fine().mesh);
    auto draw = [&](std::mt19937& r) {
        const EdgeHandle e(uniform(r, static_cast<int>(g.coarse().n_edges())));
        std::vector<VertexHandle> quad;
        for (int side = 0; side < 2; ++side)
            for (VertexHandle c : g.coarse().fv_range(g.coarse().face_handle(g.coarse().halfedge_handle(e, side))))
                quad.push_back(c);
        return LocalMove{"flip of coarse edge " + std::to_string(e.idx()), quad, [&, e](GeodesicTriangulation& t) {
                             FlipOptions unchecked;
                             unchecked.check_validity = false;
                             return flip(t, e, unchecked, propagation_only(propagation)).accepted();
                         }};
    };
    int changed_count = 0;
    const int compared = compare_after_changes_elsewhere(g, random, draw, changed_count);
    std::cout << "[ locality ] anchor: " << compared << " flips compared, " << changed_count
              << " after a change that changed G's count\n";
    EXPECT_GE(compared, 50);
    EXPECT_GT(changed_count, 0);  // the changes elsewhere did change what is counted
}

TEST(ViolationCount, a_vertex_move_changes_the_count_alike_after_a_change_on_other_fine_faces) {
    // Untangling's moves of a vertex to a vertex of T nearby, within two rings or further.
    const GeodesicTriangulation g = traced_anchor();
    std::mt19937 random(12);
    geodesic::ExactGeodesic propagation(g.fine().mesh);
    auto draw = [&](std::mt19937& r) {
        const VertexHandle v(uniform(r, static_cast<int>(g.coarse().n_vertices())));
        const std::vector<int> near = nearby_fine_vertices(g, v, 1 + uniform(r, 6));
        const int to = near.empty() ? g.fine().mesh.num_vertices() : near[static_cast<std::size_t>(
                                                                          uniform(r, static_cast<int>(near.size())))];
        std::vector<VertexHandle> star{v};  // its edges change, and with them the faces around them
        for (VertexHandle u : g.coarse().vv_range(v)) star.push_back(u);
        return LocalMove{"move of coarse vertex " + std::to_string(v.idx()) + " to vertex " + std::to_string(to) +
                             " of T",
                         star, [&, v, to](GeodesicTriangulation& t) {
                             if (to >= t.fine().mesh.num_vertices()) return false;
                             RelocateOptions unchecked;
                             unchecked.check_validity = false;
                             return relocate_vertex(t, v, SurfacePoint::at_vertex(to), unchecked,
                                                    propagation_only(propagation))
                                 .done;
                         }};
    };
    int changed_count = 0;
    const int compared = compare_after_changes_elsewhere(g, random, draw, changed_count);
    std::cout << "[ locality ] anchor: " << compared << " vertex moves compared, " << changed_count
              << " after a change that changed G's count\n";
    EXPECT_GE(compared, 50);
    EXPECT_GT(changed_count, 0);
}

TEST(ViolationCount, an_unchanged_copy_counts_as_g) {
    const auto fine = fine_of(test::perturbed_sphere(8, 0.05, 3));
    GeodesicTriangulation g(fine, decimated_coarse(*fine, 30));
    trace(g);
    // Tangled by hand: two polylines swapped, one vertex on another.
    const Polyline first = g.polyline(EdgeHandle(0));
    g.set_polyline(EdgeHandle(0), g.polyline(EdgeHandle(1)));
    g.set_polyline(EdgeHandle(1), first);
    g.set_location(VertexHandle(0), g.location(VertexHandle(5)));
    const detail::PolylineVerdicts verdicts(g, {});
    const detail::ViolationCount count(g, verdicts);
    EXPECT_GT(validated(g), 0);
    EXPECT_EQ(count.count(), validated(g));
    const GeodesicTriangulation copy = g;
    EXPECT_EQ(count.count(copy, verdicts), validated(g));
    EXPECT_EQ(count.count(copy, detail::PolylineVerdicts{}), validated(g));
}

}  // namespace
}  // namespace geotri

// Untangling's memory of the flips and vertex moves that failed (libgeotri/src/pipeline/stale_trials.h): a failure
// stays known until a change touches one of the fine faces that its trial read. Whether that is enough, that such a
// move changes the count alike wherever G changed elsewhere, is checked against validate() in
// violation_count_test.cpp.

#include <geodesic/exact_geodesic.h>
#include <geotri/flip.h>
#include <geotri/trace.h>

#include <geotri_test/fine_mesh.h>
#include <geotri_test/g_checks.h>
#include <geotri_test/procedural_meshes.h>

#include "ops/with_workspace.h"

#include "pipeline/stale_trials.h"  // libgeotri/src

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <vector>

namespace geotri {
namespace {

using OpenMesh::EdgeHandle;

/// g with edge e flipped (unchecked, as untangling tries it); asserts that the flip was possible.
GeodesicTriangulation flipped(const GeodesicTriangulation& g, EdgeHandle e, geodesic::ExactGeodesic& propagation) {
    GeodesicTriangulation trial = g;
    FlipOptions unchecked;
    unchecked.check_validity = false;
    EXPECT_TRUE(flip(trial, e, unchecked, propagation_only(propagation)).accepted()) << "coarse edge " << e.idx();
    return trial;
}

TEST(StaleTrials, a_failure_is_known_until_a_change_touches_its_faces) {
    const auto fine = test::fine_of(test::perturbed_sphere(12, 0.05, 5));
    GeodesicTriangulation g(fine, test::decimated_coarse(*fine, 60));
    trace(g);
    geodesic::ExactGeodesic propagation(g.fine().mesh);
    const EdgeHandle first(0);
    const std::vector<int> read = detail::StaleTrials::changed_faces(g, flipped(g, first, propagation));
    ASSERT_FALSE(read.empty());
    EXPECT_TRUE(std::is_sorted(read.begin(), read.end()));
    EXPECT_TRUE(detail::StaleTrials::changed_faces(g, g).empty());  // an unchanged copy changes nothing

    // An edge whose flip touches none of those faces, and one whose flip touches some.
    EdgeHandle apart, close;
    for (EdgeHandle e : g.coarse().edges()) {
        if (e == first || !g.coarse().is_flip_ok(e)) continue;
        const std::vector<int> other = detail::StaleTrials::changed_faces(g, flipped(g, e, propagation));
        std::vector<int> common;
        std::set_intersection(read.begin(), read.end(), other.begin(), other.end(), std::back_inserter(common));
        (common.empty() ? apart : close) = e;
        if (apart.is_valid() && close.is_valid()) break;
    }
    ASSERT_TRUE(apart.is_valid() && close.is_valid());

    detail::StaleTrials stale;
    const std::array<int, 3> key{0, 1, 2};
    EXPECT_FALSE(stale.known_failure(key));
    stale.failed(key, read, 1);
    ASSERT_TRUE(stale.known_failure(key));
    EXPECT_EQ(*stale.known_failure(key), 1);
    stale.changed(detail::StaleTrials::changed_faces(g, flipped(g, apart, propagation)));
    EXPECT_TRUE(stale.known_failure(key)) << "a change elsewhere";
    stale.changed(detail::StaleTrials::changed_faces(g, flipped(g, close, propagation)));
    EXPECT_FALSE(stale.known_failure(key)) << "a change on a face that it read";

    // Known again once it fails on the G changed there; forgotten when the elements are renumbered.
    stale.failed(key, read, 1);
    EXPECT_TRUE(stale.known_failure(key));
    stale.clear();
    EXPECT_FALSE(stale.known_failure(key));
}

}  // namespace
}  // namespace geotri

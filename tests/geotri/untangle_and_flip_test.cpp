// untangle(), flip_to_delaunay() and their composition untangle_and_flip(): each does its own part only, and the
// composition is the two one after the other. On bundled meshes traced as the pipeline traces them.

#include <geotri/flip_to_delaunay.h>
#include <geotri/untangle.h>
#include <geotri/untangle_and_flip.h>
#include <geotri/validate.h>
#include <geotri_test/g_checks.h>

#include <gtest/gtest.h>

#include <string>

namespace geotri {
namespace {

using test::expect_same_polylines;

/// The bundled anchor (genus 4, with needle triangles) at 320 faces, traced in the decimation's classes: its
/// geodesics cross, so G is invalid until untangled.
GeodesicTriangulation tangled_anchor() {
    return test::traced_in_classes(std::string(GEOTRI_TEST_DATA) + "/cad/anchor.off", "anchor", false);
}

TEST(Untangle, leaves_a_valid_g_as_it_is) {
    GeodesicTriangulation g = test::unit_cube_g();
    const GeodesicTriangulation given = g;
    const UntangleResult r = untangle(g);
    EXPECT_TRUE(r.valid_before);
    EXPECT_TRUE(r.valid_after);
    EXPECT_EQ(r.flips + r.fork_splits + r.meeting_splits + r.collapses + r.relocations + r.bisections, 0);
    expect_same_polylines(g, given, "the cube untangled");
}

TEST(Untangle, makes_the_tangled_anchor_valid_and_leaves_the_delaunay_flips_to_flip_to_delaunay) {
    GeodesicTriangulation g = tangled_anchor();
    const UntangleResult r = untangle(g);
    EXPECT_FALSE(r.valid_before);
    EXPECT_GT(r.flips + r.fork_splits + r.meeting_splits + r.collapses + r.relocations, 0);
    const ValidationReport check = validate(g);
    EXPECT_TRUE(r.valid_after) << test::describe(check);
    EXPECT_EQ(check.violation_count, r.violations_after);
    // Untangling alone stops as soon as G is valid: a sweep of Delaunay flips still finds work.
    GeodesicTriangulation flipped = g;
    EXPECT_GT(flip_to_delaunay(flipped).flips, 0);
}

TEST(FlipToDelaunay, leaves_an_invalid_g_as_it_is) {
    GeodesicTriangulation g = tangled_anchor();
    const GeodesicTriangulation given = g;
    const FlipToDelaunayResult r = flip_to_delaunay(g);
    EXPECT_TRUE(r.skipped);
    EXPECT_FALSE(r.valid_after);
    EXPECT_EQ(r.flips, 0);
    expect_same_polylines(g, given, "an invalid G given to flip_to_delaunay()");
}

TEST(UntangleAndFlip, is_untangle_then_flip_to_delaunay) {
    const GeodesicTriangulation traced = tangled_anchor();
    GeodesicTriangulation composed = traced;
    const UntangleAndFlipResult r = untangle_and_flip(composed);

    GeodesicTriangulation apart = traced;
    const UntangleResult untangled = untangle(apart);
    const FlipToDelaunayResult flipped = flip_to_delaunay(apart);

    expect_same_polylines(composed, apart, "untangle_and_flip() against untangle(), then flip_to_delaunay()");
    EXPECT_FALSE(r.untangling.valid_before);
    EXPECT_EQ(r.untangling.violations_before, untangled.violations_before);
    EXPECT_EQ(r.untangling.flips, untangled.flips);
    EXPECT_EQ(r.untangling.fork_splits, untangled.fork_splits);
    EXPECT_EQ(r.untangling.collapses, untangled.collapses);
    EXPECT_EQ(r.flipping.flips, flipped.flips);
    EXPECT_EQ(r.flipping.passes, flipped.passes);
    EXPECT_TRUE(r.valid_after);
    EXPECT_EQ(r.valid_after, flipped.valid_after);
    EXPECT_EQ(r.violations_after, validate(composed).violation_count);
    EXPECT_GE(r.angles_after.min_deg, flipped.angles_before.min_deg);
}

TEST(UntangleAndFlip, does_only_the_steps_asked_for) {
    const GeodesicTriangulation traced = tangled_anchor();
    UntangleAndFlipOptions neither;
    neither.untangle = false;
    neither.flip = false;
    GeodesicTriangulation g = traced;
    const UntangleAndFlipResult r = untangle_and_flip(g, neither);
    EXPECT_FALSE(r.valid_after);
    EXPECT_EQ(r.untangling.violations_before, r.violations_after);
    expect_same_polylines(g, traced, "neither step");

    UntangleAndFlipOptions flip_only;
    flip_only.untangle = false;
    const UntangleAndFlipResult skipped = untangle_and_flip(g, flip_only);
    EXPECT_TRUE(skipped.flipping.skipped);
    expect_same_polylines(g, traced, "flips only, on an invalid G");
}

}  // namespace
}  // namespace geotri

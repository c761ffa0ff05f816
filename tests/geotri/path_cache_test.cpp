// The kept shortest geodesics of flips: a flip planned with a cache gives the path that planning without
// one gives, the second time from the cache; and a full cache starts again empty.

#include <geotri/flip.h>
#include <geotri_test/g_checks.h>

#include "core/path_cache.h"
#include "ops/with_workspace.h"

#include <gtest/gtest.h>

namespace geotri {
namespace {

using geodesic::SurfacePoint;
using OpenMesh::EdgeHandle;

TEST(PathCache, flips_planned_with_the_cache_give_the_paths_planned_without_it) {
    const GeodesicTriangulation g = test::unit_cube_g();
    PathCache cache;
    Workspace cached;
    cached.paths = &cache;
    int planned = 0;
    for (EdgeHandle e : g.coarse().edges()) {
        const FlipPlan plain = plan_flip(g, e);
        const FlipPlan first = plan_flip(g, e, {}, cached);
        ASSERT_TRUE(cache.find(g.location(first.c), g.location(first.d)).has_value()) << "edge " << e.idx();
        const FlipPlan again = plan_flip(g, e, {}, cached);  // from the cache
        EXPECT_EQ(first.path, plain.path) << "edge " << e.idx();
        EXPECT_EQ(again.path, plain.path) << "edge " << e.idx();
        EXPECT_EQ(again.refusal, plain.refusal) << "edge " << e.idx();
        EXPECT_EQ(again.length, plain.length) << "edge " << e.idx();
        planned += !plain.path.empty();
    }
    EXPECT_GT(planned, 0);
}

TEST(PathCache, a_full_cache_starts_again_empty) {
    PathCache cache(2);
    const SurfacePoint a = SurfacePoint::at_vertex(0), b = SurfacePoint::at_vertex(1), c = SurfacePoint::at_vertex(2);
    cache.keep(a, b, {a, b});
    cache.keep(b, c, {b, c});
    EXPECT_EQ(cache.find(a, b), (std::vector<SurfacePoint>{a, b}));
    EXPECT_FALSE(cache.find(b, a).has_value());  // paths are kept one way
    cache.keep(a, c, {a, c});  // the third: the two before go
    EXPECT_FALSE(cache.find(a, b).has_value());
    EXPECT_FALSE(cache.find(b, c).has_value());
    EXPECT_EQ(cache.find(a, c), (std::vector<SurfacePoint>{a, c}));
}

}  // namespace
}  // namespace geotri

// decimate_backing_off(): where the target is reached, or the coarsest mesh is asked for, it is decimate() itself;
// where the topology stops decimation, each level is traced and its tangles counted as trace() and validate() count
// them independently of it, the levels double, and the mesh kept is the one that decimate() gives for its face
// count. On stress/cheese.off (shared data, genus 133) it backs off to a level that the limit accepts.

#include <geotri/decimate.h>
#include <geotri/decimate_backoff.h>
#include <geotri/edge_paths_io.h>
#include <geotri/fine_mesh.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/mesh_io.h>
#include <geotri/trace.h>
#include <geotri/validate.h>
#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace geotri {
namespace {

std::shared_ptr<const FineMesh> bundled_bob() {  // genus 1, 500 faces: a target of 4 faces stops at 18
    return std::make_shared<const FineMesh>(load_fine_mesh(std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply"));
}

// `second` moved by `shift` and added to `first` as a component of its own; its vertices come after first's.
MeshData side_by_side(MeshData first, const MeshData& second, const Eigen::Vector3d& shift) {
    const int offset = static_cast<int>(first.positions.size());
    for (const Eigen::Vector3d& p : second.positions) first.positions.push_back(p + shift);
    for (const auto& t : second.triangles) first.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    return first;
}

DecimateOptions faces_target(std::size_t faces) {
    DecimateOptions options;
    options.target_faces = faces;
    return options;
}

// Violations of conditions 2 and 3 of the decimation's coarse mesh traced in its class, counted here on a fully
// validated G.
int tangles_of(const std::shared_ptr<const FineMesh>& fine, const DecimateResult& decimation) {
    GeodesicTriangulation g(fine, make_coarse_mesh(decimation.coarse, "level"));
    const EdgePaths paths = make_edge_paths(*fine, decimation);
    TraceOptions options;
    options.edge_paths = &paths;
    trace(g, options);
    const ValidationReport report = validate(g);
    return report.violation_count[1] + report.violation_count[2];
}

TEST(DecimateBackoff, a_reached_target_is_decimate_itself) {
    const auto fine = std::make_shared<const FineMesh>(
        make_fine_mesh(MeshData{test::icosphere(3).positions, test::icosphere(3).triangles}, "icosphere"));
    const BackoffResult result = decimate_backing_off(fine, faces_target(60));
    EXPECT_TRUE(result.levels.empty());
    EXPECT_FALSE(result.backed_off);
    EXPECT_TRUE(result.decimation.target_reached);
    EXPECT_EQ(result.decimation.coarse.triangles, decimate(*fine, faces_target(60)).coarse.triangles);
}

TEST(DecimateBackoff, the_coarsest_asked_for_is_kept_however_tangled) {
    const auto fine = bundled_bob();
    DecimateOptions coarsest;
    coarsest.coarsest = true;
    BackoffOptions always;
    always.max_tangled_per_edge = -1.0;  // every level is too tangled
    const BackoffResult result = decimate_backing_off(fine, coarsest, always);
    EXPECT_TRUE(result.levels.empty());
    EXPECT_EQ(result.decimation.coarse.triangles, decimate(*fine, coarsest).coarse.triangles);
}

TEST(DecimateBackoff, a_level_tangled_within_the_limit_is_kept_and_counted) {
    const auto fine = bundled_bob();
    const BackoffResult result = decimate_backing_off(fine, faces_target(4));
    ASSERT_EQ(result.levels.size(), 1u);
    EXPECT_FALSE(result.backed_off);
    const DecimateResult plain = decimate(*fine, faces_target(4));
    EXPECT_FALSE(plain.target_reached);
    EXPECT_EQ(result.decimation.coarse.triangles, plain.coarse.triangles);
    EXPECT_EQ(result.levels[0].faces, plain.coarse.triangles.size());
    EXPECT_EQ(result.levels[0].edges, plain.edges.size());
    EXPECT_EQ(result.levels[0].tangled, tangles_of(fine, plain));
    EXPECT_GT(result.levels[0].tangled, 0);  // bob's coarsest geodesics do tangle: the count means something
    EXPECT_LE(3 * result.levels[0].tangled, static_cast<int>(result.levels[0].edges));
}

TEST(DecimateBackoff, too_tangled_levels_double_within_the_rounds_and_the_fine_mesh) {
    const auto fine = bundled_bob();
    BackoffOptions always;
    always.max_tangled_per_edge = -1.0;
    DecimateOptions options = faces_target(4);
    options.edge_paths = false;
    const BackoffResult four_rounds = decimate_backing_off(fine, options, always);
    EXPECT_TRUE(four_rounds.backed_off);
    ASSERT_EQ(four_rounds.levels.size(), 5u);  // 18, 36, 72, 144, 288
    for (std::size_t i = 1; i < four_rounds.levels.size(); ++i)
        EXPECT_EQ(four_rounds.levels[i].faces, 2 * four_rounds.levels[i - 1].faces);
    const DecimateResult& kept = four_rounds.decimation;
    const DecimateResult direct = decimate(*fine, faces_target(four_rounds.levels.back().faces));
    EXPECT_EQ(kept.coarse.triangles.size(), four_rounds.levels.back().faces);
    EXPECT_EQ(kept.coarse.triangles, direct.coarse.triangles);
    EXPECT_FALSE(kept.target_reached);  // the target asked for is still 4 faces
    EXPECT_EQ(kept.target_faces, 4u);
    EXPECT_TRUE(kept.edges.empty());  // not asked for
    // Asked for, the edge paths are those of the mesh kept.
    options.edge_paths = true;
    const BackoffResult with_paths = decimate_backing_off(fine, options, always);
    ASSERT_EQ(with_paths.decimation.edges.size(), direct.edges.size());
    for (std::size_t i = 0; i < direct.edges.size(); ++i)
        EXPECT_EQ(with_paths.decimation.edges[i].fine_path, direct.edges[i].fine_path);

    always.max_rounds = 10;  // 576 would be more faces than bob has
    options.edge_paths = false;
    const BackoffResult ten_rounds = decimate_backing_off(fine, options, always);
    EXPECT_EQ(ten_rounds.levels.size(), 5u);
    EXPECT_EQ(ten_rounds.decimation.coarse.triangles, kept.coarse.triangles);
}

// Two components: bob, which the topology stops at 18 faces, and a sphere, which reaches its share of 4. Only bob
// backs off; the sphere is decimated as before at every level.
TEST(DecimateBackoff, only_the_component_that_the_topology_stopped_backs_off) {
    const MeshData bob = read_mesh(std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply");
    const test::TriangleMesh sphere = test::icosphere(2);
    const int offset = static_cast<int>(bob.positions.size());
    const auto fine = std::make_shared<const FineMesh>(make_fine_mesh(
        side_by_side(bob, {sphere.positions, sphere.triangles}, Eigen::Vector3d(5.0, 0.0, 0.0)), "bob and a sphere"));
    ASSERT_EQ(fine->num_components, 2);
    const int bob_component = fine->component[0], sphere_component = 1 - bob_component;
    BackoffOptions always;
    always.max_tangled_per_edge = -1.0;
    always.max_rounds = 2;
    const BackoffResult result = decimate_backing_off(fine, faces_target(4), always);
    ASSERT_EQ(result.levels.size(), 3u);
    const DecimateComponent& bob_kept = result.decimation.components[static_cast<std::size_t>(bob_component)];
    const DecimateComponent& sphere_kept = result.decimation.components[static_cast<std::size_t>(sphere_component)];
    EXPECT_EQ(bob_kept.faces, 72);  // 18, 36, 72
    EXPECT_EQ(sphere_kept.faces, 4);
    EXPECT_EQ(result.levels.back().faces, 76u);
    // The sphere's coarse vertices are those of the first decimation, before any back-off.
    auto sphere_vertices = [&](const DecimateResult& decimation) {
        std::vector<int> vertices;
        for (int v : decimation.fine_vertex)
            if (v >= offset) vertices.push_back(v);
        return vertices;
    };
    EXPECT_EQ(sphere_vertices(result.decimation), sphere_vertices(decimate(*fine, faces_target(4))));
}

// The tangles are counted per component: knot1 (0.60 violations per edge at its coarsest) backs off, anchor (0.12)
// next to it does not, though the two together have less than one per three edges.
TEST(DecimateBackoff, tangles_are_counted_per_component) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at " << test::configured_shared_data_dir();
    const MeshData knot = read_mesh(test::shared_mesh("classic/knot1.off").path);
    const MeshData anchor = read_mesh(std::string(GEOTRI_TEST_DATA) + "/cad/anchor.off");
    const auto fine = std::make_shared<const FineMesh>(
        make_fine_mesh(side_by_side(knot, anchor, Eigen::Vector3d(1000.0, 0.0, 0.0)), "knot and anchor"));
    ASSERT_EQ(fine->num_components, 2);
    const std::size_t knot_component = static_cast<std::size_t>(fine->component[0]);
    const DecimateResult first = decimate(*fine, faces_target(4));
    const BackoffResult result = decimate_backing_off(fine, faces_target(4));
    ASSERT_GE(result.levels.size(), 2u);
    EXPECT_LE(3 * result.levels.front().tangled, static_cast<int>(result.levels.front().edges));  // all together
    EXPECT_EQ(result.decimation.components[knot_component].faces, 2 * first.components[knot_component].faces);
    EXPECT_EQ(result.decimation.components[1 - knot_component].faces, first.components[1 - knot_component].faces);
}

TEST(DecimateBackoff, cheese_backs_off_from_the_coarsest_mesh_to_one_that_untangles) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at " << test::configured_shared_data_dir();
    const auto fine = std::make_shared<const FineMesh>(load_fine_mesh(test::shared_mesh("stress/cheese.off").path));
    const BackoffResult result = decimate_backing_off(fine, faces_target(320));
    EXPECT_TRUE(result.backed_off);
    ASSERT_EQ(result.levels.size(), 2u);
    const BackoffLevel& stopped = result.levels.front();
    const BackoffLevel& kept = result.levels.back();
    EXPECT_GT(3 * stopped.tangled, static_cast<int>(stopped.edges));  // 1141 for 1761 edges at 1174 faces
    EXPECT_LE(3 * kept.tangled, static_cast<int>(kept.edges));         // 363 for 3522 at 2348
    EXPECT_EQ(kept.faces, 2 * stopped.faces);
    EXPECT_EQ(result.decimation.coarse.triangles.size(), kept.faces);
    EXPECT_EQ(kept.tangled, tangles_of(fine, result.decimation));
}

}  // namespace
}  // namespace geotri

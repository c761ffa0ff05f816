// decimate(): the target is reached, every component keeps its Euler characteristic, the coarse mesh is closed,
// manifold and oriented, its vertices are fine vertices bit for bit, and no coarse face is degenerate or turned over.
// The oracles share no code with the decimation: union-find components and V - E + F counted here, make_fine_mesh for
// the topology checks, bit patterns compared directly, and outward normals on convex surfaces.

#include <geodesic/errors.h>
#include <geotri/decimate.h>
#include <geotri/fine_mesh.h>
#include <geotri/mesh_io.h>
#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <numeric>
#include <set>
#include <utility>

namespace geotri {

namespace test {
void PrintTo(const SharedMesh& mesh, std::ostream* out) { *out << mesh.relative_path; }
}  // namespace test

namespace {

FineMesh fine_of(const test::TriangleMesh& mesh, const std::string& name = "procedural") {
    return make_fine_mesh(MeshData{mesh.positions, mesh.triangles}, name);
}

int find_root(std::vector<int>& parent, int v) {
    while (parent[std::size_t(v)] != v) v = parent[std::size_t(v)] = parent[std::size_t(parent[std::size_t(v)])];
    return v;
}

// Per component (numbered by its smallest vertex): vertices, undirected edges and faces.
struct Counts {
    int vertices = 0, edges = 0, faces = 0;
    int euler() const { return vertices - edges + faces; }
};

std::map<int, Counts> count_components(const MeshData& mesh, std::vector<int>* root_of = nullptr) {
    std::vector<int> parent(mesh.positions.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (const auto& t : mesh.triangles)
        for (int i = 0; i < 2; ++i) {
            const int a = find_root(parent, t[std::size_t(i)]), b = find_root(parent, t[std::size_t(i) + 1]);
            if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
        }
    std::map<int, Counts> counts;
    for (int v = 0; v < int(mesh.positions.size()); ++v) ++counts[find_root(parent, v)].vertices;
    std::set<std::pair<int, int>> edges;
    for (const auto& t : mesh.triangles) {
        const int root = find_root(parent, t[0]);
        ++counts[root].faces;
        for (int i = 0; i < 3; ++i) {
            const int a = t[std::size_t(i)], b = t[std::size_t((i + 1) % 3)];
            if (edges.insert({std::min(a, b), std::max(a, b)}).second) ++counts[root].edges;
        }
    }
    if (root_of) {
        root_of->resize(mesh.positions.size());
        for (int v = 0; v < int(mesh.positions.size()); ++v) (*root_of)[std::size_t(v)] = find_root(parent, v);
    }
    return counts;
}

std::array<std::uint64_t, 3> bits_of(const Eigen::Vector3d& p) {
    std::array<std::uint64_t, 3> bits{};
    for (int i = 0; i < 3; ++i) std::memcpy(&bits[std::size_t(i)], &p[i], sizeof(double));
    return bits;
}

Eigen::Vector3d normal_of(const MeshData& mesh, const std::array<int, 3>& t) {
    const Eigen::Vector3d& a = mesh.positions[std::size_t(t[0])];
    return (mesh.positions[std::size_t(t[1])] - a).cross(mesh.positions[std::size_t(t[2])] - a);
}

double quality_of(const MeshData& mesh, const std::array<int, 3>& t) {
    const Eigen::Vector3d& a = mesh.positions[std::size_t(t[0])];
    const Eigen::Vector3d& b = mesh.positions[std::size_t(t[1])];
    const Eigen::Vector3d& c = mesh.positions[std::size_t(t[2])];
    const double sum = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    return 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / sum;
}

// Six times the signed volume enclosed by the triangles of one component.
double signed_volume6(const MeshData& mesh, const std::vector<int>& root_of, int root) {
    double volume = 0.0;
    for (const auto& t : mesh.triangles)
        if (root_of[std::size_t(t[0])] == root)
            volume += mesh.positions[std::size_t(t[0])].dot(
                mesh.positions[std::size_t(t[1])].cross(mesh.positions[std::size_t(t[2])]));
    return volume;
}

// Everything that must hold for any decimation of `fine`.
void expect_valid_decimation(const FineMesh& fine, const DecimateResult& result) {
    const MeshData& coarse = result.coarse;
    ASSERT_FALSE(coarse.triangles.empty());

    // Closed, manifold, oriented, no unused vertex: checked by the fine mesh loader.
    int coarse_components = -1;
    ASSERT_NO_THROW(coarse_components = make_fine_mesh(coarse, "coarse").num_components);
    EXPECT_EQ(coarse_components, fine.num_components);

    // Every coarse vertex is a fine vertex, bit for bit, found by its bits alone.
    std::map<std::array<std::uint64_t, 3>, int> fine_by_bits;
    for (int v = 0; v < fine.mesh.num_vertices(); ++v) fine_by_bits.emplace(bits_of(fine.mesh.position(v)), v);
    ASSERT_EQ(result.fine_vertex.size(), coarse.positions.size());
    for (std::size_t i = 0; i < coarse.positions.size(); ++i) {
        const auto found = fine_by_bits.find(bits_of(coarse.positions[i]));
        ASSERT_NE(found, fine_by_bits.end()) << "coarse vertex " << i << " is not a fine vertex";
        EXPECT_EQ(bits_of(fine.mesh.position(result.fine_vertex[i])), bits_of(coarse.positions[i]));
        if (i > 0) {
            EXPECT_LT(result.fine_vertex[i - 1], result.fine_vertex[i]);
        }
    }

    // Per component: the same Euler characteristic as the fine component it came from.
    std::vector<int> fine_root, coarse_root;
    const std::map<int, Counts> fine_counts = count_components(
        MeshData{fine.mesh.positions(), fine.mesh.triangles()}, &fine_root);
    const std::map<int, Counts> coarse_counts = count_components(coarse, &coarse_root);
    ASSERT_EQ(coarse_counts.size(), fine_counts.size());
    std::set<int> fine_roots_seen;
    for (const auto& [root, counts] : coarse_counts) {
        const int fine_root_of_it = fine_root[std::size_t(result.fine_vertex[std::size_t(root)])];
        EXPECT_TRUE(fine_roots_seen.insert(fine_root_of_it).second) << "two coarse components in one fine one";
        EXPECT_EQ(counts.euler(), fine_counts.at(fine_root_of_it).euler())
            << "coarse component of vertex " << root << " changed its Euler characteristic";
        // The signed volume keeps its sign: a component does not turn inside out.
        const double fine_volume =
            signed_volume6(MeshData{fine.mesh.positions(), fine.mesh.triangles()}, fine_root, fine_root_of_it);
        const double coarse_volume = signed_volume6(coarse, coarse_root, root);
        EXPECT_GT(fine_volume * coarse_volume, 0.0) << "component of coarse vertex " << root;
    }

    // No zero-area face, and no coarse edge folded back on itself (adjacent normals opposite).
    std::map<std::pair<int, int>, int> face_of_directed;
    for (int f = 0; f < int(coarse.triangles.size()); ++f) {
        const auto& t = coarse.triangles[std::size_t(f)];
        EXPECT_GT(quality_of(coarse, t), 0.0) << "coarse face " << f << " has zero area";
        for (int i = 0; i < 3; ++i) face_of_directed[{t[std::size_t(i)], t[std::size_t((i + 1) % 3)]}] = f;
    }
    for (const auto& [edge, f] : face_of_directed) {
        const int g = face_of_directed.at({edge.second, edge.first});
        const Eigen::Vector3d n = normal_of(coarse, coarse.triangles[std::size_t(f)]).normalized();
        const Eigen::Vector3d m = normal_of(coarse, coarse.triangles[std::size_t(g)]).normalized();
        EXPECT_GT(n.dot(m), -1.0 + 1e-9) << "coarse faces " << f << " and " << g << " are folded onto each other";
    }

    // The reported counts are the mesh's.
    int vertices = 0, faces = 0;
    for (const DecimateComponent& c : result.components) {
        vertices += c.vertices;
        faces += c.faces;
        EXPECT_GE(c.faces, c.min_faces);
        EXPECT_EQ(c.faces, 2 * (c.vertices - c.euler_characteristic));
    }
    EXPECT_EQ(std::size_t(vertices), coarse.positions.size());
    EXPECT_EQ(std::size_t(faces), coarse.triangles.size());

    // Every coarse edge, once and in order, with a path along fine edges between its ends' fine vertices that
    // passes no other coarse vertex.
    std::set<std::pair<int, int>> coarse_edges, fine_edges;
    for (const auto& [edge, f] : face_of_directed)
        if (edge.first < edge.second) coarse_edges.insert(edge);
    for (const auto& t : fine.mesh.triangles())
        for (int i = 0; i < 3; ++i)
            fine_edges.insert(std::minmax(t[std::size_t(i)], t[std::size_t((i + 1) % 3)]));
    const std::set<int> coarse_fine(result.fine_vertex.begin(), result.fine_vertex.end());
    ASSERT_EQ(result.edges.size(), coarse_edges.size());
    auto expected = coarse_edges.begin();
    for (const DecimatedEdge& e : result.edges) {
        const std::string name = "edge (" + std::to_string(e.a) + ", " + std::to_string(e.b) + ")";
        EXPECT_EQ(std::make_pair(e.a, e.b), *expected++);
        ASSERT_GE(e.fine_path.size(), 2u) << name;
        EXPECT_EQ(e.fine_path.front(), result.fine_vertex[std::size_t(e.a)]) << name;
        EXPECT_EQ(e.fine_path.back(), result.fine_vertex[std::size_t(e.b)]) << name;
        for (std::size_t i = 0; i + 1 < e.fine_path.size(); ++i)
            EXPECT_TRUE(fine_edges.count(std::minmax(e.fine_path[i], e.fine_path[i + 1]))) << name << ", step " << i;
        for (std::size_t i = 1; i + 1 < e.fine_path.size(); ++i)
            EXPECT_FALSE(coarse_fine.count(e.fine_path[i])) << name << " passes a coarse vertex at step " << i;
    }
}

// On a sphere centred at the origin every face of a coarse mesh whose vertices are on the sphere points outwards.
void expect_outward_on_sphere(const MeshData& coarse) {
    for (std::size_t f = 0; f < coarse.triangles.size(); ++f) {
        const auto& t = coarse.triangles[f];
        const Eigen::Vector3d centroid = (coarse.positions[std::size_t(t[0])] + coarse.positions[std::size_t(t[1])] +
                                          coarse.positions[std::size_t(t[2])]) /
                                         3.0;
        EXPECT_GT(normal_of(coarse, t).dot(centroid), 0.0) << "coarse face " << f << " is turned over";
    }
}

DecimateOptions faces_target(std::size_t faces) {
    DecimateOptions options;
    options.target_faces = faces;
    return options;
}

TEST(Decimate, sphere_to_320_faces_keeps_topology_and_exact_vertices) {
    const FineMesh fine = fine_of(test::icosphere(4));  // 5120 faces
    for (const DecimateStrategy strategy : {DecimateStrategy::multiple_choice, DecimateStrategy::priority_queue}) {
        DecimateOptions options = faces_target(320);
        options.strategy = strategy;
        const DecimateResult result = decimate(fine, options);
        EXPECT_TRUE(result.target_reached);
        EXPECT_EQ(result.coarse.triangles.size(), 320u);
        EXPECT_EQ(result.coarse.positions.size(), 162u);
        expect_valid_decimation(fine, result);
        expect_outward_on_sphere(result.coarse);
    }
}

TEST(Decimate, large_sphere_uses_both_stages_and_stays_valid) {
    // 81920 faces: more than the multiple-choice stage's hand-over size, so both stages run.
    const FineMesh fine = fine_of(test::perturbed_sphere(64, 0.02, 3));
    const DecimateResult result = decimate(fine, faces_target(500));
    EXPECT_TRUE(result.target_reached);
    EXPECT_EQ(result.coarse.triangles.size(), 500u);
    expect_valid_decimation(fine, result);
}

TEST(Decimate, coarsest_sphere_is_a_tetrahedron) {
    const FineMesh fine = fine_of(test::icosphere(3));
    DecimateOptions options;
    options.coarsest = true;
    const DecimateResult result = decimate(fine, options);
    EXPECT_EQ(result.coarse.positions.size(), 4u);
    EXPECT_EQ(result.coarse.triangles.size(), 4u);
    EXPECT_TRUE(result.target_reached);
    EXPECT_EQ(result.target_faces, 4u);
    // (Not necessarily outward from the sphere's centre: a tetrahedron need not contain it. The signed volume's sign
    // is checked above.)
    expect_valid_decimation(fine, result);
}

TEST(Decimate, coarsest_cube_is_a_tetrahedron) {
    const FineMesh fine = fine_of(test::cube(6, 2.0, true, 5));
    DecimateOptions options;
    options.coarsest = true;
    const DecimateResult result = decimate(fine, options);
    EXPECT_EQ(result.coarse.triangles.size(), 4u);
    expect_valid_decimation(fine, result);
}

TEST(Decimate, coarsest_torus_keeps_genus_one) {
    const FineMesh fine = fine_of(test::torus(2.0, 0.7, 40, 16));
    DecimateOptions options;
    options.coarsest = true;
    const DecimateResult result = decimate(fine, options);
    ASSERT_EQ(result.components.size(), 1u);
    EXPECT_EQ(result.components[0].genus, 1);
    EXPECT_EQ(result.components[0].min_faces, 14);
    expect_valid_decimation(fine, result);
    // The link condition stops a little above the 7-vertex torus; anything far above it is a failure to decimate.
    EXPECT_LE(result.coarse.positions.size(), 12u);
    std::printf("coarsest torus: %zu vertices, %zu faces\n", result.coarse.positions.size(),
                result.coarse.triangles.size());
}

TEST(Decimate, two_components_share_the_target_by_area) {
    // A sphere of radius 1 and one of radius 2: areas 1 : 4.
    const test::TriangleMesh small = test::icosphere(3, 1.0), large = test::icosphere(3, 2.0);
    const FineMesh fine = fine_of(test::disjoint_union(small, large, {10, 0, 0}));
    const DecimateResult result = decimate(fine, faces_target(200));
    EXPECT_TRUE(result.target_reached);
    EXPECT_LE(result.coarse.triangles.size(), 200u);
    EXPECT_GE(result.coarse.triangles.size(), 198u);
    ASSERT_EQ(result.components.size(), 2u);
    EXPECT_EQ(result.components[0].target_faces + result.components[1].target_faces, 200);
    // 200 faces split 1 : 4 is 40 : 160, in even counts.
    EXPECT_NEAR(result.components[0].target_faces, 40, 2);
    EXPECT_NEAR(result.components[1].target_faces, 160, 2);
    expect_valid_decimation(fine, result);
}

TEST(Decimate, each_component_gets_at_least_its_minimum) {
    // A tiny sphere next to a large torus: area alone would give the sphere less than a tetrahedron.
    const FineMesh fine =
        fine_of(test::disjoint_union(test::icosphere(2, 0.01), test::torus(3.0, 1.0, 30, 12), {20, 0, 0}));
    const DecimateResult result = decimate(fine, faces_target(60));
    ASSERT_EQ(result.components.size(), 2u);
    EXPECT_EQ(result.components[0].target_faces, 4);
    EXPECT_EQ(result.components[0].faces, 4);
    EXPECT_EQ(result.components[1].genus, 1);
    EXPECT_LE(result.coarse.triangles.size(), 60u);
    expect_valid_decimation(fine, result);
}

TEST(Decimate, target_below_the_topology_gives_the_minimum_and_says_so) {
    const FineMesh fine = fine_of(test::torus(2.0, 0.7, 30, 12));
    const DecimateResult result = decimate(fine, faces_target(6));
    EXPECT_FALSE(result.target_reached);
    EXPECT_GE(result.coarse.triangles.size(), 14u);
    expect_valid_decimation(fine, result);
}

TEST(Decimate, vertex_target_and_ratio) {
    const FineMesh fine = fine_of(test::icosphere(4));  // 2562 vertices, 5120 faces
    DecimateOptions by_vertices;
    by_vertices.target_vertices = 100;
    const DecimateResult a = decimate(fine, by_vertices);
    EXPECT_TRUE(a.target_reached);
    EXPECT_EQ(a.coarse.positions.size(), 100u);  // a sphere's V = F/2 + 2, so 100 vertices is reachable exactly
    expect_valid_decimation(fine, a);

    DecimateOptions by_ratio;
    by_ratio.ratio = 0.25;
    const DecimateResult b = decimate(fine, by_ratio);
    EXPECT_TRUE(b.target_reached);
    EXPECT_EQ(b.coarse.triangles.size(), 1280u);
    expect_valid_decimation(fine, b);
}

TEST(Decimate, target_above_the_mesh_keeps_it_whole) {
    const FineMesh fine = fine_of(test::icosphere(1));
    const DecimateResult result = decimate(fine, faces_target(1000));
    EXPECT_TRUE(result.target_reached);
    EXPECT_EQ(result.coarse.triangles.size(), 80u);
    EXPECT_EQ(result.coarse.triangles, fine.mesh.triangles());
}

TEST(Decimate, needs_exactly_one_target) {
    const FineMesh fine = fine_of(test::icosphere(1));
    EXPECT_THROW(decimate(fine, DecimateOptions{}), InvalidInput);
    DecimateOptions two = faces_target(20);
    two.coarsest = true;
    EXPECT_THROW(decimate(fine, two), InvalidInput);
    DecimateOptions bad_ratio;
    bad_ratio.ratio = 1.5;
    EXPECT_THROW(decimate(fine, bad_ratio), InvalidInput);
    bad_ratio.ratio = -0.5;
    EXPECT_THROW(decimate(fine, bad_ratio), InvalidInput);
}

TEST(Decimate, same_input_gives_the_same_result) {
    const FineMesh fine = fine_of(test::perturbed_sphere(40, 0.05, 7));
    const DecimateResult a = decimate(fine, faces_target(300));
    const DecimateResult b = decimate(fine, faces_target(300));
    EXPECT_EQ(a.fine_vertex, b.fine_vertex);
    EXPECT_EQ(a.coarse.triangles, b.coarse.triangles);
}

TEST(Decimate, progress_is_reported_and_can_stop_the_work) {
    const FineMesh fine = fine_of(test::perturbed_sphere(64, 0.02, 3));  // 81920 faces
    int calls = 0;
    std::size_t last = fine.mesh.num_faces() + 1;
    DecimateOptions options = faces_target(100);
    options.progress = [&](const DecimateProgress& p) {
        ++calls;
        EXPECT_EQ(p.fine_faces, std::size_t(fine.mesh.num_faces()));
        EXPECT_EQ(p.target_faces, 100u);
        EXPECT_LT(p.current_faces, last);
        last = p.current_faces;
        return calls < 3;
    };
    const DecimateResult result = decimate(fine, options);
    EXPECT_EQ(calls, 3);
    EXPECT_TRUE(result.aborted);
    EXPECT_FALSE(result.target_reached);
    // Stopped at a consistent state: still a valid decimation.
    expect_valid_decimation(fine, result);
}

TEST(Decimate, edge_paths_can_be_left_out) {
    const FineMesh fine = fine_of(test::icosphere(3));
    DecimateOptions options = faces_target(60);
    const DecimateResult with = decimate(fine, options);
    options.edge_paths = false;
    const DecimateResult without = decimate(fine, options);
    EXPECT_EQ(with.coarse.triangles, without.coarse.triangles);  // the same collapses
    EXPECT_EQ(2 * with.edges.size(), 3 * with.coarse.triangles.size());
    EXPECT_TRUE(without.edges.empty());
}

TEST(Decimate, component_targets_replace_the_shares) {
    const test::TriangleMesh a = test::icosphere(3), b = test::icosphere(3);
    MeshData both{a.positions, a.triangles};
    const int offset = static_cast<int>(a.positions.size());
    for (const Eigen::Vector3d& p : b.positions) both.positions.push_back(p + Eigen::Vector3d(3.0, 0.0, 0.0));
    for (const auto& t : b.triangles) both.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    const FineMesh fine = make_fine_mesh(both, "two spheres");
    DecimateOptions options = faces_target(100);
    options.component_targets = {40, 200};
    const DecimateResult result = decimate(fine, options);
    EXPECT_EQ(result.target_faces, 240u);
    EXPECT_TRUE(result.target_reached);
    EXPECT_EQ(result.components[0].faces + result.components[1].faces, 240);
    EXPECT_EQ(result.components[static_cast<std::size_t>(fine.component[0])].faces, 40);
    expect_valid_decimation(fine, result);
    options.component_targets = {40};
    EXPECT_THROW(decimate(fine, options), InvalidInput);
}

TEST(Decimate, min_faces_of_genus) {
    EXPECT_EQ(min_faces_of_genus(0), 4);
    EXPECT_EQ(min_faces_of_genus(1), 14);   // the 7-vertex torus
    EXPECT_EQ(min_faces_of_genus(2), 24);   // 10 vertices
    EXPECT_EQ(min_faces_of_genus(3), 28);   // 10 vertices: V - F/2 = -4
    EXPECT_THROW(min_faces_of_genus(-1), InvalidInput);
}

// Every shared real mesh: to 320 faces and to the coarsest.
class DecimateRealMesh : public testing::TestWithParam<test::SharedMesh> {};

TEST_P(DecimateRealMesh, to_320_faces_and_coarsest) {
    const test::SharedMesh& shared = GetParam();
    if (shared.path.empty())
        GTEST_SKIP() << "the shared real meshes are missing: GEOTRI_SHARED_DATA ('"
                     << test::configured_shared_data_dir()
                     << "') is not a folder; configure with -DGEOTRI_SHARED_DATA=<folder> to run these tests";
    if (!shared.closed_as_stored) {
        EXPECT_THROW(load_fine_mesh(shared.path), TopologyError);
        return;
    }
    const FineMesh fine = load_fine_mesh(shared.path);
    const DecimateResult to_320 = decimate(fine, faces_target(320));
    expect_valid_decimation(fine, to_320);
    std::size_t min_faces = 0;
    for (const DecimateComponent& c : to_320.components) min_faces += std::size_t(c.min_faces);
    // Where the topology allows 320 faces, the decimation may still stop above: when no collapse is left that keeps
    // every triangle within the hard limits of decimate.h (the lattices and struts of hard/: diamond_lattice stops
    // at 382 faces, where its genus needs 216). The log says so; the bound below holds either way.
    if (min_faces <= 320 && std::size_t(fine.mesh.num_faces()) > 320 && !to_320.target_reached)
        std::cout << "[ decimate ] " << shared.relative_path << ": no legal collapse left at "
                  << to_320.coarse.triangles.size() << " faces (the topology needs " << min_faces << ")\n";
    EXPECT_LE(to_320.coarse.triangles.size(), std::max<std::size_t>(320, 4 * min_faces));

    DecimateOptions coarsest;
    coarsest.coarsest = true;
    const DecimateResult result = decimate(fine, coarsest);
    expect_valid_decimation(fine, result);
    EXPECT_LE(result.coarse.triangles.size(), to_320.coarse.triangles.size());
    for (const DecimateComponent& c : result.components)
        if (c.genus == 0) {
            EXPECT_LE(c.faces, 8) << "a sphere-like component stopped at " << c.faces << " faces";
        }
}

std::vector<test::SharedMesh> shared_or_placeholder() {
    std::vector<test::SharedMesh> meshes = test::shared_meshes();
    if (meshes.empty()) meshes.push_back(test::SharedMesh{"missing", "", true, "missing"});
    return meshes;
}

INSTANTIATE_TEST_SUITE_P(Shared, DecimateRealMesh, testing::ValuesIn(shared_or_placeholder()),
                         [](const testing::TestParamInfo<test::SharedMesh>& info) { return info.param.test_name; });

}  // namespace
}  // namespace geotri

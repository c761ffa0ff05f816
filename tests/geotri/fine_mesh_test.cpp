// load_fine_mesh and make_fine_mesh: what they accept, what they refuse and with which message, the components they
// count and the checksum. Meshes are written out by hand here, so that every expected count is known.

#include <geodesic/errors.h>
#include <geotri/fine_mesh.h>
#include <geotri/mesh_io.h>
#include <geotri_test/procedural_meshes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>

namespace geotri {
namespace {

MeshData tetrahedron(const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
    MeshData m;
    m.positions = {offset + Eigen::Vector3d(0, 0, 0), offset + Eigen::Vector3d(1, 0, 0),
                   offset + Eigen::Vector3d(0, 1, 0), offset + Eigen::Vector3d(0, 0, 1)};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    return m;
}

MeshData from_test_mesh(const test::TriangleMesh& mesh) { return MeshData{mesh.positions, mesh.triangles}; }

// The message of the exception that `make` throws as E, or a failure.
template <typename E, typename F>
std::string message_of(F make) {
    try {
        make();
    } catch (const E& error) {
        return error.what();
    } catch (const std::exception& error) {
        return std::string("wrong exception type: ") + error.what();
    }
    return "no exception";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class TempFile {
public:
    explicit TempFile(const std::string& suffix) {
        char name[] = "/tmp/geotri_fine_mesh_test_XXXXXX";
        const int fd = mkstemp(name);
        if (fd >= 0) close(fd);
        base_ = name;
        path_ = base_ + suffix;
    }
    ~TempFile() {
        std::remove(path_.c_str());
        std::remove(base_.c_str());
    }
    const std::string& path() const { return path_; }
    void write(const std::string& text) const { std::ofstream(path_) << text; }

private:
    std::string base_, path_;
};

TEST(FineMesh, tetrahedron_is_accepted_with_one_component) {
    const FineMesh fine = make_fine_mesh(tetrahedron(), "tet");
    EXPECT_EQ(fine.mesh.num_vertices(), 4);
    EXPECT_EQ(fine.mesh.num_faces(), 4);
    EXPECT_EQ(fine.num_components, 1);
    EXPECT_EQ(fine.num_zero_area_faces, 0);
    EXPECT_EQ(fine.path, "tet");
    for (const int c : fine.component) EXPECT_EQ(c, 0);
    EXPECT_EQ(fine.genus, std::vector<int>{0});
}

TEST(FineMesh, torus_and_sphere_are_two_components_numbered_by_first_vertex) {
    const test::TriangleMesh a = test::torus(2.0, 0.5, 12, 6);
    const test::TriangleMesh b = test::icosphere(1);
    const FineMesh fine = make_fine_mesh(from_test_mesh(test::disjoint_union(a, b, {10, 0, 0})), "");
    ASSERT_EQ(fine.num_components, 2);
    for (int v = 0; v < fine.mesh.num_vertices(); ++v)
        EXPECT_EQ(fine.component[std::size_t(v)], v < int(a.positions.size()) ? 0 : 1) << "vertex " << v;
    EXPECT_EQ(fine.genus, (std::vector<int>{1, 0}));  // the torus's handle, the sphere's none
}

// The genus of each component, of the bundled real meshes whose genus their README gives.
TEST(FineMesh, genus_of_the_bundled_meshes) {
    const std::string data = GEOTRI_TEST_DATA;
    EXPECT_EQ(load_fine_mesh(data + "/classic/bob_small.ply").genus, std::vector<int>{1});
    EXPECT_EQ(load_fine_mesh(data + "/cad/tripod.off").genus, std::vector<int>{0});
    EXPECT_EQ(load_fine_mesh(data + "/cad/joint.off").genus, std::vector<int>{2});
    EXPECT_EQ(load_fine_mesh(data + "/cad/anchor.off").genus, std::vector<int>{4});
}

TEST(FineMesh, three_components_counted) {
    MeshData m = tetrahedron();
    for (int k = 1; k < 3; ++k) {
        const MeshData t = tetrahedron(Eigen::Vector3d(3.0 * k, 0, 0));
        const int base = int(m.positions.size());
        m.positions.insert(m.positions.end(), t.positions.begin(), t.positions.end());
        for (auto tri : t.triangles) m.triangles.push_back({tri[0] + base, tri[1] + base, tri[2] + base});
    }
    // Interleave the components' faces: the count must not depend on the face order.
    std::swap(m.triangles[1], m.triangles[9]);
    EXPECT_EQ(make_fine_mesh(m, "").num_components, 3);
}

TEST(FineMesh, open_mesh_reports_its_boundary_edges) {
    MeshData m = tetrahedron();
    m.triangles.pop_back();  // removes a face: its three edges become boundary edges
    const std::string message = message_of<TopologyError>([&] { make_fine_mesh(m, "open.off"); });
    EXPECT_EQ(message, "open.off: mesh is not closed (3 boundary edges)");
}

TEST(FineMesh, open_grid_reports_every_boundary_edge) {
    const test::TriangleMesh grid = test::flat_grid(4, 3, 4.0, 3.0);
    const std::string message = message_of<TopologyError>([&] { make_fine_mesh(from_test_mesh(grid), "grid"); });
    // The boundary of a 4 x 3 grid has 2·(4 + 3) unit edges.
    EXPECT_EQ(message, "grid: mesh is not closed (14 boundary edges)");
}

TEST(FineMesh, non_manifold_edge_is_refused) {
    // Two tetrahedra glued along the edge 0-1: four faces on that edge.
    MeshData m = tetrahedron();
    m.positions.push_back({0, -1, 0});
    m.positions.push_back({0, 0, -1});
    m.triangles.push_back({0, 4, 1});
    m.triangles.push_back({0, 1, 5});
    m.triangles.push_back({1, 4, 5});
    m.triangles.push_back({0, 5, 4});
    const std::string message = message_of<TopologyError>([&] { make_fine_mesh(m, "fin"); });
    EXPECT_TRUE(contains(message, "fin: ")) << message;
    EXPECT_TRUE(contains(message, "non-manifold")) << message;
    EXPECT_TRUE(contains(message, "0") && contains(message, "1")) << message;
}

TEST(FineMesh, non_manifold_vertex_is_refused_and_named) {
    // Two tetrahedra that share only vertex 0: closed, every edge has two faces, but vertex 0 has two fans.
    MeshData m = tetrahedron();
    m.positions.push_back({-1, 0, 0});
    m.positions.push_back({0, -1, 0});
    m.positions.push_back({0, 0, -1});
    m.triangles.push_back({0, 4, 5});
    m.triangles.push_back({0, 5, 6});
    m.triangles.push_back({0, 6, 4});
    m.triangles.push_back({4, 6, 5});
    const std::string message = message_of<TopologyError>([&] { make_fine_mesh(m, "bowtie"); });
    EXPECT_TRUE(contains(message, "bowtie: vertex 0 is non-manifold")) << message;
}

TEST(FineMesh, inconsistent_orientation_is_refused) {
    MeshData m = tetrahedron();
    std::swap(m.triangles[2][0], m.triangles[2][1]);
    const std::string message = message_of<TopologyError>([&] { make_fine_mesh(m, "flip"); });
    EXPECT_TRUE(contains(message, "flip: ")) << message;
    EXPECT_TRUE(contains(message, "inconsistently oriented")) << message;
}

TEST(FineMesh, unused_vertex_is_refused_and_named) {
    MeshData m = tetrahedron();
    m.positions.insert(m.positions.begin() + 2, Eigen::Vector3d(5, 5, 5));
    for (auto& t : m.triangles)
        for (int& v : t)
            if (v >= 2) ++v;
    const std::string message = message_of<TopologyError>([&] { make_fine_mesh(m, "extra"); });
    EXPECT_EQ(message, "extra: 1 vertex is used by no face (the first is vertex 2)");
}

TEST(FineMesh, nan_coordinate_is_refused) {
    MeshData m = tetrahedron();
    m.positions[3].y() = std::numeric_limits<double>::quiet_NaN();
    const std::string message = message_of<InvalidInput>([&] { make_fine_mesh(m, "nan"); });
    EXPECT_TRUE(contains(message, "nan: vertex 3")) << message;
}

TEST(FineMesh, infinite_coordinate_is_refused) {
    MeshData m = tetrahedron();
    m.positions[1].x() = std::numeric_limits<double>::infinity();
    const std::string message = message_of<InvalidInput>([&] { make_fine_mesh(m, "inf"); });
    EXPECT_TRUE(contains(message, "inf: vertex 1")) << message;
}

TEST(FineMesh, empty_mesh_is_refused) {
    EXPECT_EQ(message_of<TopologyError>([&] { make_fine_mesh(MeshData{}, "empty"); }), "empty: mesh has no faces");
}

TEST(FineMesh, zero_area_faces_are_counted_not_refused) {
    // The tetrahedron's connectivity, with all four vertices in the plane z = 0 and vertex 3 on the segment 1-2.
    MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    const FineMesh fine = make_fine_mesh(m, "flat");
    EXPECT_EQ(fine.num_zero_area_faces, 1);  // face (1, 2, 3): 3 lies on the segment 1-2
}

TEST(FineMesh, mesh_at_one_point_is_refused) {
    // Closed and oriented, but every vertex at the origin: every face, and so the surface, has zero area.
    TempFile file(".off");
    file.write("OFF\n4 4 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    EXPECT_EQ(message_of<InvalidInput>([&] { load_fine_mesh(file.path()); }),
              file.path() + ": mesh has zero area (all its 4 faces are degenerate)");
}

TEST(FineMesh, collinear_mesh_is_refused) {
    // All four vertices on a line: no face has area, though no two vertices coincide.
    MeshData m = tetrahedron();
    m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    EXPECT_EQ(message_of<InvalidInput>([&] { make_fine_mesh(m, "line"); }),
              "line: mesh has zero area (all its 4 faces are degenerate)");
}

TEST(FineMesh, zero_area_component_is_refused_and_named) {
    // A good tetrahedron, then one whose vertices all lie at (5, 5, 5).
    MeshData m = tetrahedron();
    const MeshData t = tetrahedron();
    for (int i = 0; i < 4; ++i) m.positions.push_back({5, 5, 5});
    for (auto tri : t.triangles) m.triangles.push_back({tri[0] + 4, tri[1] + 4, tri[2] + 4});
    EXPECT_EQ(message_of<InvalidInput>([&] { make_fine_mesh(m, "two"); }),
              "two: component 1 of 2 (from vertex 4) has zero area (all 4 faces are degenerate)");
}

TEST(FineMesh, huge_coordinate_is_refused) {
    MeshData m = tetrahedron();
    m.positions[2].z() = -1e200;
    EXPECT_EQ(message_of<InvalidInput>([&] { make_fine_mesh(m, "huge"); }),
              "huge: vertex 2 has a coordinate of -1e+200, beyond +-1e+75 (areas would overflow)");
    // Just beyond the bound: at 1e80 the areas (from squared edge lengths squared) would be infinite.
    m.positions = tetrahedron().positions;
    for (Eigen::Vector3d& p : m.positions) p *= 1e80;
    EXPECT_TRUE(contains(message_of<InvalidInput>([&] { make_fine_mesh(m, "large"); }), "beyond +-1e+75"));
}

TEST(FineMesh, very_small_and_very_large_scales_are_accepted) {
    // (Below a scale of about 1e-77, a face's area, a product of two lengths, underflows to zero in double: such a
    // mesh is refused as one of zero area.)
    for (const double scale : {1e-60, 1e-30, 1e30, 1e70}) {
        MeshData m = tetrahedron();
        for (Eigen::Vector3d& p : m.positions) p *= scale;
        try {
            const FineMesh fine = make_fine_mesh(m, "scaled");
            EXPECT_GT(fine.mesh.total_area(), 0.0) << scale;
            EXPECT_EQ(fine.num_zero_area_faces, 0) << scale;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "scale " << scale << ": " << e.what();
        }
    }
}

TEST(FineMesh, checksum_is_stable_and_sees_one_bit) {
    const MeshData m = tetrahedron();
    const std::uint64_t a = make_fine_mesh(m, "a").checksum;
    EXPECT_EQ(a, make_fine_mesh(m, "b").checksum);
    EXPECT_EQ(a, fine_mesh_checksum(m.positions, m.triangles));
    for (int v = 0; v < 4; ++v)
        for (int i = 0; i < 3; ++i) {
            MeshData changed = m;
            std::uint64_t bits;
            std::memcpy(&bits, &changed.positions[std::size_t(v)][i], sizeof bits);
            bits ^= 1u;  // the lowest mantissa bit
            std::memcpy(&changed.positions[std::size_t(v)][i], &bits, sizeof bits);
            EXPECT_NE(a, make_fine_mesh(changed, "").checksum) << "vertex " << v << " coordinate " << i;
        }
    MeshData renumbered = m;
    std::swap(renumbered.triangles[0], renumbered.triangles[1]);
    EXPECT_NE(a, make_fine_mesh(renumbered, "").checksum) << "face order is part of the mesh as loaded";
}

TEST(FineMesh, load_reads_exactly_and_prefixes_the_path) {
    TempFile file(".off");
    file.write("OFF\n4 4 0\n0.1 0 0\n1 0.30000000000000004 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
    const FineMesh fine = load_fine_mesh(file.path());
    EXPECT_EQ(fine.path, file.path());
    EXPECT_EQ(fine.mesh.position(0).x(), 0.1);
    EXPECT_EQ(fine.mesh.position(1).y(), 0.30000000000000004);
    EXPECT_EQ(fine.checksum, fine_mesh_checksum(fine.mesh.positions(), fine.mesh.triangles()));
}

TEST(FineMesh, load_of_open_file_names_the_file) {
    TempFile file(".off");
    file.write("OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n");
    EXPECT_EQ(message_of<TopologyError>([&] { load_fine_mesh(file.path()); }),
              file.path() + ": mesh is not closed (3 boundary edges)");
}

TEST(FineMesh, load_of_empty_file_is_an_io_error_naming_the_file) {
    TempFile file(".ply");
    file.write("");
    const std::string message = message_of<IOError>([&] { load_fine_mesh(file.path()); });
    EXPECT_EQ(message.rfind(file.path() + ": ", 0), 0u) << message;
}

}  // namespace
}  // namespace geotri

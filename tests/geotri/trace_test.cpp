// trace(): coarse vertices located on T, every edge the exact shortest geodesic between its ends (checked against
// fresh full propagations), identical output for any thread count, and bad inputs refused.

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/decimate.h>
#include <geotri/edge_paths_io.h>
#include <geotri/gtri_io.h>
#include <geotri/mesh_io.h>
#include <geotri/trace.h>
#include <geotri/validate.h>
#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using geotri::GeodesicTriangulation;
using geotri::geodesic::PointKind;
using geotri::geodesic::SurfacePoint;
using OpenMesh::VertexHandle;

namespace {

std::shared_ptr<const geotri::FineMesh> fine_of(const geotri::test::TriangleMesh& mesh, const std::string& name) {
    return std::make_shared<const geotri::FineMesh>(geotri::make_fine_mesh({mesh.positions, mesh.triangles}, name));
}

/// The four fine vertices nearest to the directions of a regular tetrahedron (around `centre`), faces outward.
geotri::MeshData tetrahedron_on(const geotri::geodesic::Mesh& fine, const Eigen::Vector3d& centre = {0, 0, 0},
                                int first = 0, int last = -1) {
    if (last < 0) last = fine.num_vertices();
    const Eigen::Vector3d directions[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    geotri::MeshData coarse;
    for (const Eigen::Vector3d& d : directions) {
        int best = first;
        for (int v = first; v < last; ++v)
            if ((fine.position(v) - centre).normalized().dot(d.normalized()) >
                (fine.position(best) - centre).normalized().dot(d.normalized()))
                best = v;
        coarse.positions.push_back(fine.position(best));
    }
    coarse.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    for (auto& t : coarse.triangles) {
        const Eigen::Vector3d a = coarse.positions[t[0]] - centre;
        const Eigen::Vector3d n = (coarse.positions[t[1]] - coarse.positions[t[0]])
                                      .cross(coarse.positions[t[2]] - coarse.positions[t[0]]);
        if (n.dot(a + coarse.positions[t[1]] + coarse.positions[t[2]] - 2 * centre) < 0) std::swap(t[1], t[2]);
    }
    return coarse;
}

/// A coarse torus on the fine torus(…, n_major, n_minor): every `step_major`-th ring, every `step_minor`-th vertex.
geotri::MeshData coarse_torus(const geotri::geodesic::Mesh& fine, int n_major, int n_minor, int step_major,
                              int step_minor) {
    const int cm = n_major / step_major, cn = n_minor / step_minor;
    geotri::MeshData coarse;
    for (int i = 0; i < cm; ++i)
        for (int j = 0; j < cn; ++j) coarse.positions.push_back(fine.position(i * step_major * n_minor + j * step_minor));
    auto at = [&](int i, int j) { return (i % cm) * cn + (j % cn); };
    for (int i = 0; i < cm; ++i)
        for (int j = 0; j < cn; ++j) {
            coarse.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            coarse.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return coarse;
}

/// Every polyline runs exactly from its first end's location to its second's, and its length is the exact distance
/// between them from a fresh full propagation (an independent run with no stop points, from the edge's other end
/// when `from_other_end`). Checks the edges around `sources` (all vertices when empty).
void expect_edges_are_shortest_geodesics(const GeodesicTriangulation& g, std::vector<int> sources = {}) {
    const geotri::CoarseMesh& c = g.coarse();
    if (sources.empty())
        for (auto v : c.vertices()) sources.push_back(v.idx());
    geotri::geodesic::ExactGeodesic fresh(g.fine().mesh);
    for (const int s : sources) {
        const VertexHandle v(s);
        fresh.propagate({g.location(v)});
        for (auto h : c.voh_range(v)) {
            const geotri::Polyline path = g.path(h);
            const std::string what = "edge " + std::to_string(c.edge_handle(h).idx()) + " from coarse vertex " +
                                     std::to_string(s) + " to " + std::to_string(c.to_vertex_handle(h).idx());
            ASSERT_GE(path.size(), 2u) << what;
            EXPECT_EQ(path.front(), g.location(v)) << what;
            EXPECT_EQ(path.back(), g.location(c.to_vertex_handle(h))) << what;
            const double exact = fresh.distance(g.location(c.to_vertex_handle(h)));
            const double length = g.length(c.edge_handle(h));
            EXPECT_NEAR(length, exact, 1e-12 * exact) << what;
            EXPECT_EQ(length, geotri::geodesic::path_length(g.fine().mesh, g.polyline(c.edge_handle(h)))) << what;
        }
    }
}

std::string gtri_text(const GeodesicTriangulation& g, const fs::path& path) {
    geotri::write_gtri(path.string(), g);
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

class Trace : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        // The process id keeps two runs of the suite (two build folders) out of each other's way.
        dir_ = fs::temp_directory_path() /
               ("geotri_trace_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    /// T written to a file and loaded from it, so that G can be written as .gtri.
    std::shared_ptr<const geotri::FineMesh> fine_file(const geotri::test::TriangleMesh& mesh, const std::string& name) {
        const std::string path = (dir_ / name).string();
        geotri::write_mesh(path, {mesh.positions, mesh.triangles});
        return std::make_shared<const geotri::FineMesh>(geotri::load_fine_mesh(path));
    }

    fs::path dir_;
};

// ---- Procedural meshes -----------------------------------------------------------------------------------------

TEST_F(Trace, tetrahedron_on_icosphere_gives_shortest_geodesics) {
    const auto fine = fine_of(geotri::test::icosphere(3), "icosphere");
    GeodesicTriangulation g(fine, geotri::make_coarse_mesh(tetrahedron_on(fine->mesh), "tetrahedron"));
    const geotri::TraceResult r = geotri::trace(g);
    EXPECT_EQ(r.largest_location_move, 0.0);
    EXPECT_EQ(r.moved_vertices, 0);
    EXPECT_EQ(r.propagations, 6);  // one per edge
    for (auto v : g.coarse().vertices()) {
        ASSERT_EQ(g.location(v).kind, PointKind::vertex);
        const auto& p = g.coarse().point(v);
        EXPECT_EQ(fine->mesh.position(g.location(v).vertex), Eigen::Vector3d(p[0], p[1], p[2]));
    }
    expect_edges_are_shortest_geodesics(g);
}

TEST_F(Trace, coarse_torus_gives_shortest_geodesics) {
    const auto fine = fine_of(geotri::test::torus(3.0, 1.0, 48, 24), "torus");
    GeodesicTriangulation g(fine, geotri::make_coarse_mesh(coarse_torus(fine->mesh, 48, 24, 8, 6), "coarse torus"));
    const geotri::TraceResult r = geotri::trace(g);
    EXPECT_EQ(r.propagations, static_cast<int>(g.coarse().n_edges()));
    expect_edges_are_shortest_geodesics(g);
}

// Copies share their polylines (they are replaced, never changed in place): a copy changed afterwards must leave
// the original as it was.
TEST_F(Trace, a_copy_of_g_changes_independently_of_the_original) {
    const auto fine = fine_of(geotri::test::torus(3.0, 1.0, 48, 24), "torus");
    GeodesicTriangulation g(fine, geotri::make_coarse_mesh(coarse_torus(fine->mesh, 48, 24, 8, 6), "coarse torus"));
    geotri::trace(g);
    const OpenMesh::EdgeHandle e(0);
    const geotri::Polyline before = g.polyline(e);
    const double length_before = g.length(e);
    GeodesicTriangulation copy = g;
    EXPECT_EQ(&copy.polyline(e), &g.polyline(e)) << "the copy should share the polyline, not copy it";
    geotri::Polyline reversed = before;
    std::reverse(reversed.begin(), reversed.end());
    copy.set_path(copy.coarse().halfedge_handle(e, 1), reversed);  // the same path along the other halfedge
    copy.set_polyline(OpenMesh::EdgeHandle(1), {before.front(), before.front()});
    EXPECT_EQ(g.polyline(e), before);
    EXPECT_EQ(g.length(e), length_before);
    EXPECT_NE(g.polyline(OpenMesh::EdgeHandle(1)), copy.polyline(OpenMesh::EdgeHandle(1)));
    EXPECT_EQ(copy.polyline(e), before);
    EXPECT_NE(&copy.polyline(e), &g.polyline(e));
}

// Assignment copies into the coarse mesh that G has (callers hold references to it), in its storage; it copies
// everything that a copy does: connectivity, status flags, points, locations, polylines (shared) and lengths, and
// properties that a caller added. Construction by move takes the coarse mesh itself.
TEST_F(Trace, assignment_copies_everything_into_the_coarse_mesh_that_g_has) {
    const auto fine = fine_file(geotri::test::torus(3.0, 1.0, 48, 24), "torus.off");
    GeodesicTriangulation g(fine, geotri::make_coarse_mesh(coarse_torus(fine->mesh, 48, 24, 8, 6), "coarse torus"));
    geotri::trace(g);
    g.coarse().status(OpenMesh::FaceHandle(3)).set_tagged(true);
    GeodesicTriangulation other(fine,
                                geotri::make_coarse_mesh(coarse_torus(fine->mesh, 48, 24, 12, 8), "finer torus"));
    geotri::trace(other);
    const geotri::CoarseMesh* storage = &other.coarse();
    OpenMesh::VPropHandleT<geotri::SurfacePoint> location;
    ASSERT_TRUE(other.coarse().get_property_handle(location, "geotri:location"));
    const auto* location_storage = &other.coarse().property(location);
    other = g;
    EXPECT_EQ(&other.coarse(), storage);
    EXPECT_EQ(&other.coarse().property(location), location_storage);  // assigned in place, not cloned
    EXPECT_EQ(other.coarse().n_faces(), g.coarse().n_faces());
    EXPECT_TRUE(other.coarse().status(OpenMesh::FaceHandle(3)).tagged());
    EXPECT_FALSE(other.coarse().status(OpenMesh::FaceHandle(4)).tagged());
    EXPECT_EQ(&other.polyline(OpenMesh::EdgeHandle(0)), &g.polyline(OpenMesh::EdgeHandle(0)));
    const std::string g_text = gtri_text(g, dir_ / "g.gtri");
    EXPECT_EQ(gtri_text(other, dir_ / "other.gtri"), g_text);
    other.set_polyline(OpenMesh::EdgeHandle(0), {g.polyline(OpenMesh::EdgeHandle(0)).front()});
    EXPECT_NE(other.polyline(OpenMesh::EdgeHandle(0)), g.polyline(OpenMesh::EdgeHandle(0)));

    // By move: into the same coarse mesh too.
    GeodesicTriangulation source = g;
    other = std::move(source);
    EXPECT_EQ(&other.coarse(), storage);
    EXPECT_EQ(gtri_text(other, dir_ / "other.gtri"), g_text);
    // Constructed by move: the coarse mesh itself, no copy.
    GeodesicTriangulation taken(std::move(other));
    EXPECT_EQ(&taken.coarse(), storage);

    // A property that a caller added goes with the copy.
    OpenMesh::VPropHandleT<int> mark;
    g.coarse().add_property(mark, "test:mark");
    for (auto v : g.coarse().vertices()) g.coarse().property(mark, v) = v.idx() * 7;
    taken = g;
    OpenMesh::VPropHandleT<int> copied;
    ASSERT_TRUE(taken.coarse().get_property_handle(copied, "test:mark"));
    for (auto v : g.coarse().vertices()) EXPECT_EQ(taken.coarse().property(copied, v), v.idx() * 7);
    EXPECT_EQ(gtri_text(taken, dir_ / "other.gtri"), g_text);
    // Again, with the property on both: still copied.
    for (auto v : g.coarse().vertices()) g.coarse().property(mark, v) = v.idx() * 11;
    taken = g;
    ASSERT_TRUE(taken.coarse().get_property_handle(copied, "test:mark"));
    for (auto v : g.coarse().vertices()) EXPECT_EQ(taken.coarse().property(copied, v), v.idx() * 11);

    // Into a G moved from, by copy and by move: it gets a coarse mesh again.
    GeodesicTriangulation emptied(std::move(taken));
    taken = g;
    EXPECT_EQ(gtri_text(taken, dir_ / "other.gtri"), g_text);
    GeodesicTriangulation emptied_again(std::move(taken));
    GeodesicTriangulation source_again = g;
    const geotri::CoarseMesh* source_storage = &source_again.coarse();
    taken = std::move(source_again);
    EXPECT_EQ(&taken.coarse(), source_storage);  // taken over, not copied
    EXPECT_EQ(gtri_text(taken, dir_ / "other.gtri"), g_text);
}

TEST_F(Trace, output_is_identical_for_any_thread_count) {
    const auto fine = fine_file(geotri::test::torus(3.0, 1.0, 48, 24), "torus.off");
    const geotri::CoarseMesh coarse = geotri::make_coarse_mesh(coarse_torus(fine->mesh, 48, 24, 6, 4), "coarse");
    std::vector<std::string> files;
    for (const int threads : {1, 2, 4}) {
        GeodesicTriangulation g(fine, coarse);
        geotri::TraceOptions options;
        options.threads = threads;
        geotri::trace(g, options);
        files.push_back(gtri_text(g, dir_ / ("t" + std::to_string(threads) + ".gtri")));
    }
    EXPECT_EQ(files[0], files[1]);
    EXPECT_EQ(files[0], files[2]);
}

TEST_F(Trace, vertices_off_the_surface_move_to_the_closest_point) {
    const auto fine = fine_of(geotri::test::icosphere(2), "icosphere");
    const geotri::geodesic::Mesh& m = fine->mesh;
    geotri::MeshData coarse = tetrahedron_on(m);
    // 0: radially outside a fine vertex, whose closest point on this convex polyhedron is that vertex.
    // 1: outside the centroid of a face, along its normal: the closest point is that centroid.
    // 2: inside the sphere, at an arbitrary point. 3: stays on a fine vertex.
    const Eigen::Vector3d vertex0 = coarse.positions[0];
    coarse.positions[0] = 1.2 * vertex0;
    int face = 0;
    for (int f = 0; f < m.num_faces(); ++f) {
        const auto& t = m.triangle(f);
        const Eigen::Vector3d centroid = (m.position(t[0]) + m.position(t[1]) + m.position(t[2])) / 3.0;
        if (centroid.normalized().dot(coarse.positions[1].normalized()) >
            ((m.position(m.triangle(face)[0]) + m.position(m.triangle(face)[1]) + m.position(m.triangle(face)[2])) / 3.0)
                .normalized()
                .dot(coarse.positions[1].normalized()))
            face = f;
    }
    const auto& t = m.triangle(face);
    const Eigen::Vector3d centroid = (m.position(t[0]) + m.position(t[1]) + m.position(t[2])) / 3.0;
    const Eigen::Vector3d normal = (m.position(t[1]) - m.position(t[0])).cross(m.position(t[2]) - m.position(t[0])).normalized();
    coarse.positions[1] = centroid + 0.05 * normal;
    coarse.positions[2] = 0.8 * coarse.positions[2] + Eigen::Vector3d(0.01, 0.02, -0.03);
    const std::vector<Eigen::Vector3d> wanted = coarse.positions;

    GeodesicTriangulation g(fine, geotri::make_coarse_mesh(coarse, "tetrahedron"));
    const geotri::TraceResult r = geotri::trace(g);
    EXPECT_EQ(r.moved_vertices, 3);

    const SurfacePoint& l0 = g.location(VertexHandle(0));
    ASSERT_EQ(l0.kind, PointKind::vertex);
    EXPECT_EQ(m.position(l0.vertex), vertex0);
    const SurfacePoint& l1 = g.location(VertexHandle(1));
    ASSERT_EQ(l1.kind, PointKind::face);
    EXPECT_EQ(l1.face, face);
    for (double b : l1.bary) EXPECT_NEAR(b, 1.0 / 3.0, 1e-12);
    EXPECT_EQ(g.location(VertexHandle(3)).kind, PointKind::vertex);

    // Oracle for "closest": no point of a dense barycentric sampling of any face is nearer than the location.
    double largest = 0.0;
    for (int v = 0; v < 3; ++v) {
        const Eigen::Vector3d located = m.point(g.location(VertexHandle(v)));
        const double d = (located - wanted[static_cast<std::size_t>(v)]).norm();
        largest = std::max(largest, d);
        const auto& p = g.coarse().point(VertexHandle(v));
        EXPECT_EQ(Eigen::Vector3d(p[0], p[1], p[2]), located) << "the coarse point follows its location";
        constexpr int k = 12;
        for (int f = 0; f < m.num_faces(); ++f) {
            const auto& ft = m.triangle(f);
            for (int i = 0; i <= k; ++i)
                for (int j = 0; i + j <= k; ++j) {
                    const Eigen::Vector3d q = (i * m.position(ft[0]) + j * m.position(ft[1]) +
                                               (k - i - j) * m.position(ft[2])) / k;
                    ASSERT_GE((q - wanted[static_cast<std::size_t>(v)]).norm(), d - 1e-12)
                        << "coarse vertex " << v << ": face " << f << " has a nearer point";
                }
        }
    }
    EXPECT_NEAR(r.largest_location_move, largest, 1e-15);
    EXPECT_GE(r.largest_move_vertex, 0);
    EXPECT_LE(r.largest_move_vertex, 2);
    expect_edges_are_shortest_geodesics(g);
}

TEST_F(Trace, two_components_each_get_their_own) {
    const auto a = geotri::test::icosphere(2);
    const auto union_mesh = geotri::test::disjoint_union(a, a, {5, 0, 0});
    const auto fine = fine_of(union_mesh, "two spheres");
    const int n = static_cast<int>(a.positions.size());
    geotri::MeshData first = tetrahedron_on(fine->mesh, {0, 0, 0}, 0, n);
    const geotri::MeshData second = tetrahedron_on(fine->mesh, {5, 0, 0}, n, 2 * n);
    for (const auto& p : second.positions) first.positions.push_back(p);
    for (const auto& t : second.triangles) first.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
    GeodesicTriangulation g(fine, geotri::make_coarse_mesh(first, "two tetrahedra"));
    geotri::trace(g);
    expect_edges_are_shortest_geodesics(g);

    // Both tetrahedra on the first sphere: refused.
    geotri::MeshData same = tetrahedron_on(fine->mesh, {0, 0, 0}, 0, n);
    geotri::MeshData rotated = same;
    for (auto& p : rotated.positions) p = Eigen::Vector3d(-p.x(), -p.y(), p.z());
    for (const auto& p : rotated.positions) same.positions.push_back(p);
    for (const auto& t : rotated.triangles) same.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
    GeodesicTriangulation both_on_one(fine, geotri::make_coarse_mesh(same, "coarse"));
    try {
        geotri::trace(both_on_one);
        ADD_FAILURE() << "no error";
    } catch (const geotri::InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("same component of the fine mesh"), std::string::npos) << e.what();
    }

    // One tetrahedron with a vertex on each sphere: refused.
    geotri::MeshData straddling = tetrahedron_on(fine->mesh, {0, 0, 0}, 0, n);
    straddling.positions[3] = second.positions[3];
    GeodesicTriangulation across(fine, geotri::make_coarse_mesh(straddling, "coarse"));
    try {
        geotri::trace(across);
        ADD_FAILURE() << "no error";
    } catch (const geotri::InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("different components of the fine mesh"), std::string::npos) << e.what();
    }
}

// Flips, splits and collapses keep the coarse topology, so a coarse mesh of another genus than T, or one that leaves
// a component of T bare, could never give a valid G: trace refuses it and says why.
TEST_F(Trace, a_coarse_mesh_of_another_genus_or_leaving_a_component_bare_is_refused) {
    const auto torus = fine_of(geotri::test::torus(3.0, 1.0, 24, 12), "torus");
    GeodesicTriangulation sphere_on_torus(torus, geotri::make_coarse_mesh(tetrahedron_on(torus->mesh), "tetrahedron"));
    try {
        geotri::trace(sphere_on_torus);
        ADD_FAILURE() << "no error";
    } catch (const geotri::InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("genus 0 but the fine mesh has genus 1"), std::string::npos) << e.what();
    }

    const auto a = geotri::test::icosphere(2);
    const auto two_spheres = fine_of(geotri::test::disjoint_union(a, a, {5, 0, 0}), "two spheres");
    const int n = static_cast<int>(a.positions.size());
    GeodesicTriangulation one_bare(two_spheres,
                                   geotri::make_coarse_mesh(tetrahedron_on(two_spheres->mesh, {0, 0, 0}, 0, n), "one"));
    try {
        geotri::trace(one_bare);
        ADD_FAILURE() << "no error";
    } catch (const geotri::InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("no coarse vertex lies on component 1"), std::string::npos) << e.what();
    }
}

TEST_F(Trace, two_vertices_on_one_point_are_refused) {
    const auto fine = fine_of(geotri::test::icosphere(2), "icosphere");
    geotri::MeshData coarse = tetrahedron_on(fine->mesh);
    coarse.positions[3] = coarse.positions[2];
    GeodesicTriangulation g(fine, geotri::make_coarse_mesh(coarse, "coarse"));
    EXPECT_THROW(geotri::trace(g), geotri::InvalidInput);
}

TEST_F(Trace, progress_is_reported_and_its_exceptions_come_out) {
    const auto fine = fine_of(geotri::test::torus(3.0, 1.0, 24, 12), "torus");
    const geotri::CoarseMesh coarse = geotri::make_coarse_mesh(coarse_torus(fine->mesh, 24, 12, 4, 3), "coarse");
    GeodesicTriangulation g(fine, coarse);
    std::vector<std::pair<int, int>> calls;
    geotri::TraceOptions options;
    options.threads = 2;
    options.progress = [&calls](int done, int total) { calls.emplace_back(done, total); };
    const geotri::TraceResult r = geotri::trace(g, options);
    ASSERT_EQ(calls.size(), static_cast<std::size_t>(r.propagations));
    for (std::size_t i = 0; i < calls.size(); ++i) {
        EXPECT_EQ(calls[i].first, static_cast<int>(i) + 1);
        EXPECT_EQ(calls[i].second, r.propagations);
    }
    GeodesicTriangulation h(fine, coarse);
    options.progress = [](int done, int) {
        if (done == 2) throw std::runtime_error("stop here");
    };
    EXPECT_THROW(geotri::trace(h, options), std::runtime_error);
}

TEST(CoarseMesh, broken_coarse_meshes_are_refused) {
    geotri::MeshData tetra;
    tetra.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    EXPECT_EQ(geotri::make_coarse_mesh(tetra, "tetra").n_edges(), 6u);

    geotri::MeshData open = tetra;
    open.triangles.pop_back();
    EXPECT_THROW(geotri::make_coarse_mesh(open, "open"), geotri::TopologyError);
    geotri::MeshData flipped = tetra;
    std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
    EXPECT_THROW(geotri::make_coarse_mesh(flipped, "flipped"), geotri::TopologyError);
    geotri::MeshData out_of_range = tetra;
    out_of_range.triangles[0][0] = 4;
    EXPECT_THROW(geotri::make_coarse_mesh(out_of_range, "range"), geotri::InvalidInput);
    geotri::MeshData isolated = tetra;
    isolated.positions.emplace_back(5, 5, 5);
    EXPECT_THROW(geotri::make_coarse_mesh(isolated, "isolated"), geotri::TopologyError);
    // Two tetrahedra sharing vertex 0: closed and edge-manifold, but vertex 0 has two fans.
    geotri::MeshData pinched = tetra;
    for (int i = 0; i < 3; ++i) pinched.positions.emplace_back(-1.0 - i, -1, -1);
    pinched.triangles.push_back({0, 5, 4});
    pinched.triangles.push_back({0, 4, 6});
    pinched.triangles.push_back({0, 6, 5});
    pinched.triangles.push_back({4, 5, 6});
    try {
        geotri::make_coarse_mesh(pinched, "pinched");
        ADD_FAILURE() << "no error";
    } catch (const geotri::TopologyError& e) {
        EXPECT_NE(std::string(e.what()).find("pinched: coarse vertex 0 is non-manifold"), std::string::npos) << e.what();
    }
}

// ---- Real meshes -----------------------------------------------------------------------------------------------

/// Decimates `path` to about `faces` faces, traces with 1 and 2 threads, and checks the edges around a sample of the
/// coarse vertices (a full propagation each) and the thread-count independence.
void trace_real_mesh(const fs::path& dir, const std::string& path, std::size_t faces, int sampled_sources) {
    auto fine = std::make_shared<const geotri::FineMesh>(geotri::load_fine_mesh(path));
    geotri::DecimateOptions options;
    options.target_faces = faces;
    const geotri::DecimateResult decimated = geotri::decimate(*fine, options);
    const geotri::CoarseMesh coarse = geotri::make_coarse_mesh(decimated.coarse, "decimated");
    std::string first_file;
    for (const int threads : {1, 2}) {
        GeodesicTriangulation g(fine, coarse);
        geotri::TraceOptions trace_options;
        trace_options.threads = threads;
        const geotri::TraceResult r = geotri::trace(g, trace_options);
        EXPECT_EQ(r.moved_vertices, 0);
        std::cout << "[ trace    ] " << path << ": " << coarse.n_faces() << " coarse faces, " << r.propagations
                  << " propagations, " << r.seconds << " s on " << threads << " thread(s)\n";
        const std::string text = gtri_text(g, dir / ("t" + std::to_string(threads) + ".gtri"));
        if (threads == 1) {
            first_file = text;
            std::vector<int> sources;
            const int n = static_cast<int>(coarse.n_vertices());
            for (int i = 0; i < std::min(n, sampled_sources); ++i) sources.push_back(i * n / std::min(n, sampled_sources));
            expect_edges_are_shortest_geodesics(g, sources);
        } else {
            EXPECT_EQ(text, first_file) << "2 threads differ from 1";
        }
    }
}

TEST_F(Trace, bundled_bob) {
    trace_real_mesh(dir_, std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply", 60, 1000);
}

TEST_F(Trace, shared_vertebra) {
    if (geotri::test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at " << geotri::test::configured_shared_data_dir()
                     << " (set GEOTRI_SHARED_DATA)";
    trace_real_mesh(dir_, geotri::test::shared_mesh("anatomy/lumbar_vertebra_mean_2nd.ply").path, 320, 8);
}

// The bundled vertebra (examples/data), whose shortest geodesics cross at 320 faces and at the coarsest: with the
// decimation's edge paths, every edge keeps the class that the decimation gave it, and G is valid.
TEST_F(Trace, edge_paths_keep_the_decimated_triangulation) {
    auto fine = std::make_shared<const geotri::FineMesh>(
        geotri::load_fine_mesh(std::string(GEOTRI_TEST_DATA) + "/../../examples/data/lumbar_vertebra.ply"));
    for (const std::size_t faces : {std::size_t(320), std::size_t(0)}) {
        geotri::DecimateOptions options;
        options.target_faces = faces;
        options.coarsest = faces == 0;
        const geotri::DecimateResult decimated = geotri::decimate(*fine, options);
        const geotri::EdgePaths paths = geotri::make_edge_paths(*fine, decimated);
        const std::string name = faces ? "320 faces" : "coarsest";

        GeodesicTriangulation shortest(fine, geotri::make_coarse_mesh(decimated.coarse, "coarse"));
        geotri::trace(shortest);
        EXPECT_FALSE(geotri::validate(shortest).valid) << name << ": the case needs crossing shortest geodesics";

        GeodesicTriangulation g(fine, geotri::make_coarse_mesh(decimated.coarse, "coarse"));
        geotri::TraceOptions with_paths;
        with_paths.edge_paths = &paths;
        const geotri::TraceResult result = geotri::trace(g, with_paths);
        EXPECT_TRUE(result.class_geodesics_kept) << name;
        EXPECT_GT(result.class_geodesics_differing, 0) << name;
        const geotri::ValidationReport report = geotri::validate(g);
        EXPECT_TRUE(report.valid) << name << ": " << report.violation_count[0] << ", " << report.violation_count[1]
                                  << ", " << report.violation_count[2] << ", " << report.violation_count[3];
        ASSERT_TRUE(result.report.has_value()) << name;  // the check that chose the set, of G as returned
        EXPECT_EQ(result.report->valid, report.valid) << name;
        EXPECT_EQ(result.report->violation_count, report.violation_count) << name;
        // The class geodesics are longer than the shortest ones where they differ, never shorter.
        int longer = 0;
        for (const auto e : g.coarse().edges()) {
            EXPECT_GE(g.length(e), shortest.length(e) * (1 - 1e-12)) << name << ", edge " << e.idx();
            longer += g.length(e) > shortest.length(e) * (1 + 1e-9);
        }
        EXPECT_EQ(longer, result.class_geodesics_differing) << name;
    }
}

TEST_F(Trace, edge_paths_of_another_mesh_are_refused) {
    const auto fine = fine_file(geotri::test::icosphere(3), "sphere.off");
    geotri::DecimateOptions options;
    options.target_faces = 40;
    const geotri::DecimateResult decimated = geotri::decimate(*fine, options);
    geotri::EdgePaths paths = geotri::make_edge_paths(*fine, decimated);
    paths.name = "sphere.paths";
    geotri::TraceOptions with_paths;
    with_paths.edge_paths = &paths;
    auto trace_with = [&](const geotri::MeshData& coarse) {
        GeodesicTriangulation g(fine, geotri::make_coarse_mesh(coarse, "coarse"));
        geotri::trace(g, with_paths);
    };
    EXPECT_NO_THROW(trace_with(decimated.coarse));

    options.target_faces = 60;  // another coarse mesh
    EXPECT_THROW(trace_with(geotri::decimate(*fine, options).coarse), geotri::IOError);
    geotri::EdgePaths other_fine = paths;
    other_fine.fine_checksum ^= 1;
    with_paths.edge_paths = &other_fine;
    EXPECT_THROW(trace_with(decimated.coarse), geotri::IOError);
    geotri::EdgePaths broken = paths;
    broken.edges[0].fine_path.insert(broken.edges[0].fine_path.begin() + 1, broken.edges[5].fine_path.back());
    with_paths.edge_paths = &broken;
    try {
        trace_with(decimated.coarse);
        ADD_FAILURE() << "a path that jumps between fine vertices was accepted";
    } catch (const geotri::IOError& e) {
        const std::string expected = "sphere.paths: the path of coarse edge (" + std::to_string(broken.edges[0].a) +
                                     ", " + std::to_string(broken.edges[0].b) + ")";
        EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << e.what();
    }
}

TEST_F(Trace, edge_paths_files_read_back_and_bad_ones_are_refused) {
    const auto fine = fine_file(geotri::test::icosphere(2), "sphere.off");
    geotri::DecimateOptions options;
    options.coarsest = true;
    const geotri::EdgePaths paths = geotri::make_edge_paths(*fine, geotri::decimate(*fine, options));
    const std::string file = (dir_ / "sphere.paths").string();
    geotri::write_edge_paths(file, paths);
    const geotri::EdgePaths read = geotri::read_edge_paths(file);
    EXPECT_EQ(read.name, file);
    EXPECT_EQ(read.fine_checksum, paths.fine_checksum);
    EXPECT_EQ(read.fine_vertices, paths.fine_vertices);
    EXPECT_EQ(read.coarse_vertices, paths.coarse_vertices);
    ASSERT_EQ(read.edges.size(), paths.edges.size());
    for (std::size_t i = 0; i < paths.edges.size(); ++i) {
        EXPECT_EQ(read.edges[i].a, paths.edges[i].a);
        EXPECT_EQ(read.edges[i].b, paths.edges[i].b);
        EXPECT_EQ(read.edges[i].fine_path, paths.edges[i].fine_path);
    }

    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    const std::string whole = text.str();
    auto refused = [&](const std::string& content, const std::string& message) {
        const std::string bad = (dir_ / "bad.paths").string();
        std::ofstream(bad) << content;
        try {
            geotri::read_edge_paths(bad);
            ADD_FAILURE() << "accepted: " << message;
        } catch (const geotri::IOError& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).rfind(bad, 0), 0u) << e.what();
        }
    };
    refused(whole.substr(0, whole.find('\n', whole.size() / 2) + 1), "truncated");
    refused("geotri-edge-paths 2\n", "version 2 is not supported");
    refused("OFF\n", "not an edge paths file");
    refused(whole + "0 1 2 0 1\n", "unexpected content");
    refused("geotri-edge-paths 1\nfine 10 0123456789abcdef\ncoarse 4 2000000000\n", "truncated");  // no huge reserve
    std::string out_of_range = whole;
    out_of_range.replace(out_of_range.rfind(' ') + 1, std::string::npos, "99999999\n");
    refused(out_of_range, "out of range");
}

TEST_F(Trace, shared_spine_four_components) {
    if (geotri::test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at " << geotri::test::configured_shared_data_dir()
                     << " (set GEOTRI_SHARED_DATA)";
    trace_real_mesh(dir_, geotri::test::shared_mesh("anatomy/lumbar_spine_L2-L5_mean.ply").path, 1232, 4);
}

}  // namespace

// .gtri read/write: exact round trips, the fine mesh found through its relative path or refused when it changed,
// and every kind of corrupt file turned into an IOError that names the file and the line.

#include <geodesic/errors.h>
#include <geotri/gtri_io.h>
#include <geotri/mesh_io.h>
#include <geotri/trace.h>
#include <geotri_test/procedural_meshes.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using geotri::GeodesicTriangulation;
using geotri::geodesic::SurfacePoint;
using OpenMesh::EdgeHandle;
using OpenMesh::VertexHandle;

namespace {

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void spit(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
}

/// Replaces the first occurrence of `from` (which must occur) by `to`.
std::string replace_first(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the file";
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

/// The line number (from 1) of the first line that starts with `prefix`.
int line_of(const std::string& text, const std::string& prefix) {
    std::istringstream in(text);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
        if (line.rfind(prefix, 0) == 0) return n;
    ADD_FAILURE() << "no line starts with '" << prefix << "'";
    return -1;
}

/// The four fine vertices nearest to the directions of a regular tetrahedron, with outward-oriented faces.
geotri::MeshData tetrahedron_on(const geotri::geodesic::Mesh& fine) {
    const Eigen::Vector3d directions[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    geotri::MeshData coarse;
    for (const Eigen::Vector3d& d : directions) {
        int best = 0;
        for (int v = 1; v < fine.num_vertices(); ++v)
            if (fine.position(v).normalized().dot(d.normalized()) > fine.position(best).normalized().dot(d.normalized()))
                best = v;
        coarse.positions.push_back(fine.position(best));
    }
    coarse.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    for (auto& t : coarse.triangles) {
        const Eigen::Vector3d& a = coarse.positions[t[0]];
        const Eigen::Vector3d n = (coarse.positions[t[1]] - a).cross(coarse.positions[t[2]] - a);
        if (n.dot(a + coarse.positions[t[1]] + coarse.positions[t[2]]) < 0) std::swap(t[1], t[2]);
    }
    return coarse;
}

class GtriIO : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("geotri_gtri_io_" + std::string(info->name()) + "_" +
                                            std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "meshes");
        fs::create_directories(dir_ / "out");
        const geotri::test::TriangleMesh sphere = geotri::test::icosphere(3);
        fine_path_ = (dir_ / "meshes" / "sphere.off").string();
        geotri::write_mesh(fine_path_, {sphere.positions, sphere.triangles});
        fine_ = std::make_shared<const geotri::FineMesh>(geotri::load_fine_mesh(fine_path_));
    }
    void TearDown() override { fs::remove_all(dir_); }

    /// A traced tetrahedron on the sphere; with `off_surface`, the coarse vertices are pushed off T first, so that
    /// their locations become face and edge points.
    GeodesicTriangulation traced(bool off_surface = false) const {
        geotri::MeshData coarse = tetrahedron_on(fine_->mesh);
        if (off_surface) {
            coarse.positions[0] *= 1.05;
            coarse.positions[1] = 0.97 * (0.5 * (fine_->mesh.position(fine_->mesh.triangle(7)[0]) +
                                                 fine_->mesh.position(fine_->mesh.triangle(7)[1])));
            coarse.positions[2] = (fine_->mesh.position(fine_->mesh.triangle(100)[0]) +
                                   fine_->mesh.position(fine_->mesh.triangle(100)[1]) +
                                   fine_->mesh.position(fine_->mesh.triangle(100)[2])) / 3.0 * 1.01;
        }
        GeodesicTriangulation g(fine_, geotri::make_coarse_mesh(coarse, "tetrahedron"));
        geotri::trace(g);
        return g;
    }

    /// Expects read_gtri to throw IOError whose message starts with the path and holds `fragment`.
    void expect_io_error(const std::string& text, const std::string& fragment, const std::string& why) {
        const std::string path = (dir_ / "out" / "bad.gtri").string();
        spit(path, text);
        try {
            geotri::read_gtri(path);
            ADD_FAILURE() << why << ": no error";
        } catch (const geotri::IOError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << why << ": " << message;
            EXPECT_NE(message.find(fragment), std::string::npos) << why << ": '" << message << "' lacks '" << fragment << "'";
        } catch (const std::exception& e) {
            ADD_FAILURE() << why << ": not an IOError: " << e.what();
        }
    }

    fs::path dir_;
    std::string fine_path_;
    std::shared_ptr<const geotri::FineMesh> fine_;
};

void expect_identical(const GeodesicTriangulation& a, const GeodesicTriangulation& b) {
    const geotri::CoarseMesh &ca = a.coarse(), &cb = b.coarse();
    ASSERT_EQ(ca.n_vertices(), cb.n_vertices());
    ASSERT_EQ(ca.n_edges(), cb.n_edges());
    ASSERT_EQ(ca.n_faces(), cb.n_faces());
    EXPECT_EQ(a.fine().checksum, b.fine().checksum);
    for (auto v : ca.vertices()) {
        EXPECT_EQ(a.location(v), b.location(v)) << "vertex " << v.idx() << ": " << to_spec(a.location(v)) << " vs "
                                                << to_spec(b.location(v));
        EXPECT_EQ(ca.point(v), cb.point(v)) << "vertex " << v.idx();
    }
    for (auto f : ca.faces()) {
        auto ia = ca.cfv_iter(f);
        auto ib = cb.cfv_iter(OpenMesh::FaceHandle(f.idx()));
        for (int i = 0; i < 3; ++i, ++ia, ++ib) EXPECT_EQ(ia->idx(), ib->idx()) << "face " << f.idx();
    }
    for (auto e : ca.edges()) {
        const EdgeHandle eb(e.idx());
        EXPECT_EQ(ca.from_vertex_handle(ca.halfedge_handle(e, 0)).idx(),
                  cb.from_vertex_handle(cb.halfedge_handle(eb, 0)).idx());
        EXPECT_EQ(a.polyline(e), b.polyline(eb)) << "edge " << e.idx();
        EXPECT_EQ(a.length(e), b.length(eb)) << "edge " << e.idx();
    }
}

// ---- Round trips -----------------------------------------------------------------------------------------------

TEST_F(GtriIO, round_trip_is_exact) {
    const GeodesicTriangulation g = traced();
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, g);
    const GeodesicTriangulation back = geotri::read_gtri(path);
    expect_identical(g, back);
    // Written again, it is the same file byte for byte.
    const std::string again = (dir_ / "out" / "again.gtri").string();
    geotri::write_gtri(again, back);
    EXPECT_EQ(slurp(path), slurp(again));
    // Nothing but the two files: no temporary file is left behind.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "out"), fs::directory_iterator()), 2);
}

TEST_F(GtriIO, round_trip_keeps_face_and_edge_locations_exactly) {
    const GeodesicTriangulation g = traced(true);
    int kinds[3] = {0, 0, 0};
    for (auto v : g.coarse().vertices()) ++kinds[static_cast<int>(g.location(v).kind)];
    EXPECT_GE(kinds[static_cast<int>(geotri::geodesic::PointKind::face)], 1);
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, g);
    expect_identical(g, geotri::read_gtri(path, fine_));
}

TEST_F(GtriIO, round_trip_of_arbitrary_points_and_an_untraced_edge) {
    // Locations and polylines that no trace made: awkward doubles must still come back bit for bit.
    GeodesicTriangulation g(fine_, geotri::make_coarse_mesh(tetrahedron_on(fine_->mesh), "tetrahedron"));
    const auto& t = fine_->mesh.triangle(11);
    const double third = 1.0 / 3.0;
    g.set_location(VertexHandle(0), SurfacePoint::in_face(11, {third, third, 1.0 - 2.0 * third}));
    g.set_location(VertexHandle(1), SurfacePoint::on_edge(t[0], t[1], 0.1));
    g.set_location(VertexHandle(2), SurfacePoint::on_edge(t[1], t[2], 1e-300));
    g.set_location(VertexHandle(3), SurfacePoint::at_vertex(t[2]));
    g.set_polyline(EdgeHandle(0), {SurfacePoint::on_edge(t[0], t[1], 0.30000000000000004),
                                   SurfacePoint::on_edge(t[1], t[2], 0.7071067811865476),
                                   SurfacePoint::at_vertex(t[2])});
    g.set_polyline(EdgeHandle(1), {SurfacePoint::at_vertex(t[0]), SurfacePoint::at_vertex(t[1])});
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, g);
    const GeodesicTriangulation back = geotri::read_gtri(path);
    expect_identical(g, back);
    EXPECT_TRUE(back.polyline(EdgeHandle(2)).empty());
}

TEST_F(GtriIO, file_is_readable_text) {
    const GeodesicTriangulation g = traced();
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, g);
    const std::string text = slurp(path);
    EXPECT_EQ(text.rfind("gtri 1\n", 0), 0u);
    EXPECT_NE(text.find("\nfine ../meshes/sphere.off\n"), std::string::npos);
    EXPECT_NE(text.find("\nvertices 4\n"), std::string::npos);
    EXPECT_NE(text.find("\nfaces 4\n"), std::string::npos);
    EXPECT_NE(text.find("\nedges 6\n"), std::string::npos);
    EXPECT_EQ(text.substr(text.size() - 4), "end\n");
    const geotri::GtriHeader header = geotri::read_gtri_header(path);
    EXPECT_EQ(header.version, 1);
    EXPECT_EQ(header.fine_checksum, fine_->checksum);
    EXPECT_EQ(header.fine_vertices, fine_->mesh.num_vertices());
    EXPECT_TRUE(fs::equivalent(header.resolved_fine_path, fine_path_));
}

// ---- The fine mesh ---------------------------------------------------------------------------------------------

TEST_F(GtriIO, moved_fine_mesh_is_found_through_the_relative_path) {
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, traced());
    const fs::path moved = dir_.string() + "_moved";
    fs::remove_all(moved);
    fs::rename(dir_, moved);
    fs::create_directories(dir_);  // so that TearDown has something to remove
    try {
        const GeodesicTriangulation back = geotri::read_gtri((moved / "out" / "g.gtri").string());
        EXPECT_EQ(back.fine().checksum, fine_->checksum);
        EXPECT_TRUE(fs::equivalent(back.fine().path, moved / "meshes" / "sphere.off"));
    } catch (const std::exception& e) {
        ADD_FAILURE() << e.what();
    }
    fs::remove_all(moved);
}

TEST_F(GtriIO, missing_fine_mesh_is_an_io_error_and_override_finds_it) {
    const std::string path = (dir_ / "out" / "g.gtri").string();
    const GeodesicTriangulation g = traced();
    geotri::write_gtri(path, g);
    fs::rename(fine_path_, dir_ / "elsewhere.off");
    try {
        geotri::read_gtri(path);
        ADD_FAILURE() << "no error";
    } catch (const geotri::IOError& e) {
        EXPECT_NE(std::string(e.what()).find("../meshes/sphere.off"), std::string::npos) << e.what();
    }
    expect_identical(g, geotri::read_gtri(path, (dir_ / "elsewhere.off").string()));
}

TEST_F(GtriIO, changed_fine_mesh_is_refused) {
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, traced());
    geotri::MeshData changed = geotri::read_mesh(fine_path_);
    changed.positions[5].x() = std::nextafter(changed.positions[5].x(), 10.0);  // one ulp
    geotri::write_mesh(fine_path_, changed);
    EXPECT_THROW(geotri::read_gtri(path), geotri::InvalidInput);
    const std::string other = (dir_ / "other.off").string();
    geotri::write_mesh(other, changed);
    EXPECT_THROW(geotri::read_gtri(path, other), geotri::InvalidInput);
    auto changed_fine = std::make_shared<const geotri::FineMesh>(geotri::make_fine_mesh(changed, "changed"));
    EXPECT_THROW(geotri::read_gtri(path, changed_fine), geotri::InvalidInput);
}

// ---- Writing ---------------------------------------------------------------------------------------------------

TEST_F(GtriIO, write_failure_leaves_nothing) {
    const GeodesicTriangulation g = traced();
    EXPECT_THROW(geotri::write_gtri((dir_ / "missing" / "g.gtri").string(), g), geotri::IOError);
    EXPECT_FALSE(fs::exists(dir_ / "missing"));
    // A fine mesh without a file cannot be referred to.
    auto anonymous = std::make_shared<const geotri::FineMesh>(
        geotri::make_fine_mesh(geotri::read_mesh(fine_path_), ""));
    GeodesicTriangulation h(anonymous, g.coarse());
    EXPECT_THROW(geotri::write_gtri((dir_ / "out" / "h.gtri").string(), h), geotri::InvalidInput);
    EXPECT_TRUE(fs::is_empty(dir_ / "out"));
}

// ---- Corrupt files ---------------------------------------------------------------------------------------------

TEST_F(GtriIO, truncation_anywhere_is_an_io_error) {
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, traced());
    const std::string text = slurp(path);
    ASSERT_GT(text.size(), 200u);
    // Every cut in the header and the first blocks, then every third one, but not the one that drops only the final
    // line break (which a reader must tolerate).
    for (std::size_t size = 0; size + 1 < text.size(); size += size < 600 ? 1 : 3) {
        spit(path, text.substr(0, size));
        try {
            geotri::read_gtri(path);
            ADD_FAILURE() << "truncated to " << size << " bytes: no error";
        } catch (const geotri::IOError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << "truncated to " << size << " bytes: not an IOError: " << e.what();
        }
    }
    spit(path, text.substr(0, text.size() - 1));
    EXPECT_NO_THROW(geotri::read_gtri(path));
}

TEST_F(GtriIO, corrupt_files_are_io_errors_naming_the_line) {
    const std::string path = (dir_ / "out" / "g.gtri").string();
    const GeodesicTriangulation g = traced();
    geotri::write_gtri(path, g);
    const std::string text = slurp(path);
    const int n_fine = fine_->mesh.num_vertices();

    expect_io_error("", "empty", "empty file");
    expect_io_error("hello\n", "line 1: not a .gtri file", "wrong magic");
    expect_io_error(replace_first(text, "gtri 1\n", "gtri 2\n"), "line 1: unsupported .gtri version 2", "version");
    expect_io_error(replace_first(text, "fine_checksum ", "fine_checksum x"), "line 4:", "bad checksum line");
    expect_io_error(replace_first(text, "vertices 4\n", "vertices 5\n"), "", "one vertex too many");
    expect_io_error(replace_first(text, "vertices 4\n", "vertices 3\n"), "line " + std::to_string(line_of(text, "vertices") + 4),
                    "one vertex too few");
    expect_io_error(replace_first(text, "faces 4\n", "faces 3\n"), "", "one face too few");
    expect_io_error(replace_first(text, "faces 4\n", "faces 5\n"), "", "one face too many");
    expect_io_error(replace_first(text, "edges 6\n", "edges 5\n"), "", "one edge too few");
    expect_io_error(replace_first(text, "edges 6\n", "edges 7\n"), "", "one edge too many");
    expect_io_error(replace_first(text, "vertices 4\n", "vertices -4\n"), "bad vertices count", "negative count");
    expect_io_error(replace_first(text, "vertices 4\n", "vertices 99999999999\n"), "bad vertices count", "huge count");

    // The first face line, with an index out of range or repeated.
    const int faces_line = line_of(text, "faces");
    std::istringstream lines(text);
    std::vector<std::string> all;
    for (std::string l; std::getline(lines, l);) all.push_back(l);
    auto with_line = [&](int number, const std::string& content) {
        std::vector<std::string> copy = all;
        copy[static_cast<std::size_t>(number - 1)] = content;
        std::string out;
        for (const std::string& l : copy) out += l + "\n";
        return out;
    };
    expect_io_error(with_line(faces_line + 1, "0 1 4"), "line " + std::to_string(faces_line + 1) + ": face 0 refers to coarse vertex 4",
                    "face index out of range");
    expect_io_error(with_line(faces_line + 1, "0 1 1"), "repeats a vertex", "repeated face index");
    expect_io_error(with_line(faces_line + 1, "0 1"), "three vertex indices", "short face");
    expect_io_error(with_line(faces_line + 1, "0 1 2.5"), "bad vertex index", "non-integer index");

    // Vertex locations.
    const int first_location = line_of(text, "vertices") + 1;
    const std::string at = "line " + std::to_string(first_location) + ": ";
    expect_io_error(with_line(first_location, "v:" + std::to_string(n_fine)), at + "surface point v:", "vertex out of T");
    expect_io_error(with_line(first_location, "x:3"), at + "bad location", "unknown kind");
    expect_io_error(with_line(first_location, "v:-1"), at + "bad location", "negative vertex");
    expect_io_error(with_line(first_location, "e:0,1"), at + "bad location", "edge point without parameter");
    expect_io_error(with_line(first_location, "e:0,1:nan"), at + "bad location", "NaN");
    expect_io_error(with_line(first_location, "e:0,1:inf"), at + "bad location", "infinity");
    expect_io_error(with_line(first_location, "f:3:0.5,0.5"), at + "bad location", "face point with two coordinates");
    expect_io_error(with_line(first_location, "f:3:nan,0.5,0.5"), at + "bad location", "NaN coordinate");
    expect_io_error(with_line(first_location, "f:" + std::to_string(fine_->mesh.num_faces()) + ":0.2,0.3,0.5"),
                    at + "surface point f:", "face out of range");
    const auto& t0 = fine_->mesh.triangle(0);
    const std::string edge0 = std::to_string(t0[0]) + "," + std::to_string(t0[1]);
    expect_io_error(with_line(first_location, "e:" + edge0 + ":1.5"), at + "surface point e:", "parameter out of [0, 1]");
    expect_io_error(with_line(first_location, "e:" + edge0 + ":0"), at + "surface point e:" + edge0 + ":0 is not in its canonical form",
                    "vertex spelled as an edge point");
    expect_io_error(with_line(first_location, "e:0,999:0.5"), at + "surface point e:", "no such edge of T");

    // Edge blocks.
    const int first_edge = line_of(text, "edge ");
    std::istringstream edge_words(all[static_cast<std::size_t>(first_edge - 1)]);
    std::string word, from, to, count, length;
    edge_words >> word >> word >> from >> to >> count >> length;
    const std::string edge_at = "line " + std::to_string(first_edge) + ": ";
    expect_io_error(with_line(first_edge, "edge 0 " + from + " " + to + " " + count + " nan"), edge_at + "bad length", "NaN length");
    expect_io_error(with_line(first_edge, "edge 1 " + from + " " + to + " " + count + " " + length), edge_at + "edge '1' is out of sequence",
                    "edge index out of sequence");
    expect_io_error(with_line(first_edge, "edge 0 " + from + " 9 " + count + " " + length), edge_at, "edge end out of range");
    expect_io_error(with_line(first_edge, "edge 0 " + from + " " + from + " " + count + " " + length),
                    edge_at + "there is no coarse edge", "edge that is not a coarse edge");
    expect_io_error(with_line(first_edge, "edge 0 " + from + " " + to + " " + std::to_string(std::stoi(count) + 1) + " " + length),
                    "", "one point too many");
    expect_io_error(with_line(first_edge, "edge 0 " + from + " " + to + " 1 " + length), edge_at + "a polyline has no points (not traced) or at least two", "one point");
    expect_io_error(with_line(first_edge + 1, "e:0,1:0.5:7"), "line " + std::to_string(first_edge + 1) + ": bad point 0 of edge 0",
                    "bad polyline point");
    expect_io_error(with_line(first_edge + 1, std::string("v:1\0", 4)), "NUL", "NUL byte");

    // Trailing garbage, and a duplicated edge block.
    expect_io_error(text + "edge 6 0 1 0 0\n", "unexpected content after 'end'", "content after end");
    expect_io_error(replace_first(text, "end\n", "fin\n"), "expected 'end'", "no end");
}

TEST_F(GtriIO, counts_beyond_the_file_are_refused_before_allocating) {
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, traced());
    const std::string text = slurp(path);
    // The bytes after a line that starts with `prefix`: what a count on that line is checked against.
    auto bytes_after = [&](const std::string& prefix) {
        const std::size_t at = text.find("\n" + prefix);
        EXPECT_NE(at, std::string::npos) << prefix;
        return std::to_string(text.size() - (text.find('\n', at + 1) + 1));
    };
    // Each of these once took gigabytes or ended in std::bad_alloc ("out of memory", with no file or line).
    const std::string vertices_at = "line " + std::to_string(line_of(text, "vertices")) + ": ";
    expect_io_error(replace_first(text, "vertices 4\n", "vertices 100000000\n"),
                    vertices_at + "100000000 vertices, but only " + bytes_after("vertices") + " bytes follow",
                    "vertex count beyond the file");
    expect_io_error(replace_first(text, "vertices 4\n", "vertices 2000000000\n"), vertices_at + "2000000000 vertices",
                    "vertex count near INT_MAX");
    expect_io_error(replace_first(text, "faces 4\n", "faces 2000000000\n"),
                    "line " + std::to_string(line_of(text, "faces")) + ": 2000000000 faces, but only " +
                        bytes_after("faces") + " bytes follow",
                    "face count beyond the file");
    expect_io_error(replace_first(text, "edges 6\n", "edges 2147483647\n"),
                    "line " + std::to_string(line_of(text, "edges")) + ": 2147483647 edges, but only " +
                        bytes_after("edges") + " bytes follow",
                    "edge count beyond the file");
    // An edge block's point count K.
    const int first_edge = line_of(text, "edge ");
    std::istringstream edge_words(text.substr(text.find("\nedge ") + 1));
    std::string word, from, to, count, length;
    edge_words >> word >> word >> from >> to >> count >> length;
    const std::string edge_line = "edge 0 " + from + " " + to + " " + count + " " + length + "\n";
    expect_io_error(replace_first(text, edge_line, "edge 0 " + from + " " + to + " 2147483647 " + length + "\n"),
                    "line " + std::to_string(first_edge) + ": edge 0 has 2147483647 points, but only " +
                        bytes_after("edge ") + " bytes follow",
                    "point count beyond the file");
}

TEST_F(GtriIO, shortest_possible_items_are_not_refused_by_the_count_checks) {
    // Every item as short as the format allows ("v:0", "0 1 2", "edge 0 0 1 0 0"), and no final line break: the
    // bounds on the counts must stay below what a real file takes.
    GeodesicTriangulation g(fine_, geotri::make_coarse_mesh(tetrahedron_on(fine_->mesh), "tetrahedron"));
    for (int v = 0; v < 4; ++v) g.set_location(VertexHandle(v), SurfacePoint::at_vertex(v));
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, g);
    std::string text = slurp(path);
    ASSERT_NE(text.find("\nv:0\nv:1\nv:2\nv:3\nfaces 4\n"), std::string::npos) << text;
    ASSERT_NE(text.find(" 0 0\nend\n"), std::string::npos) << text;
    text.pop_back();
    spit(path, text);
    const GeodesicTriangulation back = geotri::read_gtri(path);
    EXPECT_EQ(back.coarse().n_edges(), 6u);
    EXPECT_EQ(back.location(VertexHandle(3)), SurfacePoint::at_vertex(3));
}

TEST_F(GtriIO, fine_path_may_follow_tabs_and_spaces) {
    const std::string path = (dir_ / "out" / "g.gtri").string();
    const GeodesicTriangulation g = traced();
    geotri::write_gtri(path, g);
    const std::string text = slurp(path);
    for (const std::string separator : {"\t", " \t ", "   "}) {
        spit(path, replace_first(text, "fine ../", "fine" + separator + "../"));
        try {
            expect_identical(g, geotri::read_gtri(path));
        } catch (const std::exception& e) {
            ADD_FAILURE() << "separator '" << separator << "': " << e.what();
        }
        EXPECT_EQ(geotri::read_gtri_header(path).fine_path, "../meshes/sphere.off");
    }
    const int fine_line = line_of(text, "fine ");
    const std::string at = "line " + std::to_string(fine_line) + ": expected 'fine PATH'";
    expect_io_error(replace_first(text, "fine ../meshes/sphere.off\n", "fine\t\n"), at, "only a tab after 'fine'");
    expect_io_error(replace_first(text, "fine ../meshes/sphere.off\n", "fine\n"), at, "no path");
    expect_io_error(replace_first(text, "fine ../", "fineX ../"), at, "no separator after 'fine'");
}

TEST_F(GtriIO, fine_path_with_a_leading_space_round_trips) {
    // The reader skips the separators after "fine", so the writer spells such a path "./ sphere.off".
    const std::string spaced = (dir_ / "out" / " sphere.off").string();
    fs::copy_file(fine_path_, spaced);
    auto fine = std::make_shared<const geotri::FineMesh>(geotri::load_fine_mesh(spaced));
    GeodesicTriangulation g(fine, geotri::make_coarse_mesh(tetrahedron_on(fine->mesh), "tetrahedron"));
    geotri::trace(g);
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, g);
    EXPECT_NE(slurp(path).find("\nfine ./ sphere.off\n"), std::string::npos);
    const GeodesicTriangulation back = geotri::read_gtri(path);
    expect_identical(g, back);
    EXPECT_TRUE(fs::equivalent(back.fine().path, spaced));
}

TEST_F(GtriIO, a_device_is_refused_not_read_until_memory_runs_out) {
    const fs::path zero = dir_ / "zero.gtri";
    fs::create_symlink("/dev/zero", zero);
    try {
        geotri::read_gtri(zero.string());
        ADD_FAILURE() << "no error";
    } catch (const geotri::IOError& e) {
        EXPECT_EQ(std::string(e.what()), zero.string() + ": cannot read: it is a device, not a file");
    }
}

TEST_F(GtriIO, fine_path_that_is_a_folder_names_the_gtri_file) {
    const std::string path = (dir_ / "out" / "g.gtri").string();
    geotri::write_gtri(path, traced());
    const std::string text = slurp(path);
    const std::string at = "line " + std::to_string(line_of(text, "fine ")) + ": its fine mesh ";
    expect_io_error(replace_first(text, "fine ../meshes/sphere.off\n", "fine .\n"), at + "'.' is a folder",
                    "the .gtri file's own folder");
    expect_io_error(replace_first(text, "fine ../meshes/sphere.off\n", "fine ../meshes\n"),
                    at + "'../meshes' is a folder", "another folder");
    // The same through an override.
    try {
        geotri::read_gtri(path, (dir_ / "meshes").string());
        ADD_FAILURE() << "a folder as the override: no error";
    } catch (const geotri::IOError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
        EXPECT_NE(message.find("is a folder"), std::string::npos) << message;
    }
}

TEST_F(GtriIO, comments_blank_lines_and_crlf_are_accepted) {
    const std::string path = (dir_ / "out" / "g.gtri").string();
    const GeodesicTriangulation g = traced();
    geotri::write_gtri(path, g);
    std::string text = replace_first(slurp(path), "faces ", "\n# a comment\n\nfaces ");
    std::string crlf;
    for (const char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    spit(path, crlf);
    expect_identical(g, geotri::read_gtri(path));
}

}  // namespace

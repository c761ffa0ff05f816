// read_mesh / write_mesh: exactness in every format, the format variants, every kind of broken input, and every
// real mesh of the shared data set against OpenMesh's own reader.

#include <geodesic/errors.h>
#include <geotri/mesh_io.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;
using geotri::MeshData;

namespace {

// ---- Fixtures -------------------------------------------------------------------------------------------------

/// A fresh folder per test, removed afterwards.
class MeshIO : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("geotri_mesh_io_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::string write_bytes(const std::string& name, const std::string& bytes) const {
        const std::string p = path(name);
        std::ofstream(p, std::ios::binary) << bytes;
        return p;
    }

    fs::path dir_;
};

/// A tetrahedron with coordinates that no decimal or float32 writer would keep by accident.
MeshData awkward_tetrahedron() {
    MeshData mesh;
    mesh.positions = {
        {0.1, 1.0 / 3.0, 1e-300},
        {-0.0, 2.0 / 3.0, -1e300},
        {5e-324, 0.30000000000000004, std::nextafter(1.0, 2.0)},
        {-123456789.123456789, 2.2250738585072014e-308, 1.7976931348623157e308},
    };
    mesh.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{1, 2, 3}}, {{0, 3, 2}}};
    return mesh;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_identical(const MeshData& expected, const MeshData& actual) {
    ASSERT_EQ(expected.positions.size(), actual.positions.size());
    ASSERT_EQ(expected.triangles.size(), actual.triangles.size());
    for (std::size_t v = 0; v < expected.positions.size(); ++v) {
        for (int i = 0; i < 3; ++i) {
            EXPECT_TRUE(same_bits(expected.positions[v][i], actual.positions[v][i]))
                << "vertex " << v << " axis " << i << ": wrote " << expected.positions[v][i] << ", read "
                << actual.positions[v][i];
        }
    }
    for (std::size_t f = 0; f < expected.triangles.size(); ++f) EXPECT_EQ(expected.triangles[f], actual.triangles[f]);
}

/// Expects read_mesh(path) to throw IOError with a message that starts with the path and contains `words`.
void expect_read_error(const std::string& path, const std::string& words) {
    try {
        geotri::read_mesh(path);
        ADD_FAILURE() << "no error reading " << path;
    } catch (const geotri::IOError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << "message does not start with the path: " << message;
        EXPECT_NE(message.find(words), std::string::npos) << "expected '" << words << "' in: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "message is not one line: " << message;
    }
}

// ---- Binary STL and PLY builders ------------------------------------------------------------------------------

template <typename T>
void append(std::string& bytes, T value, bool big_endian = false) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (big_endian) {
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    bytes.append(raw, sizeof(T));
}

/// A binary STL of the triangles, the 80-byte header starting with `header`.
std::string binary_stl(const std::vector<std::array<std::array<float, 3>, 3>>& triangles,
                       const std::string& header = "binary test") {
    std::string bytes = header;
    bytes.resize(80, ' ');
    append<std::uint32_t>(bytes, static_cast<std::uint32_t>(triangles.size()));
    for (const auto& t : triangles) {
        for (int i = 0; i < 3; ++i) append<float>(bytes, 0.0f);
        for (const auto& p : t) {
            for (const float x : p) append<float>(bytes, x);
        }
        append<std::uint16_t>(bytes, 0);
    }
    return bytes;
}

std::string ascii_stl(const std::vector<std::array<std::array<float, 3>, 3>>& triangles) {
    std::ostringstream out;
    out.precision(17);
    out << "solid test\n";
    for (const auto& t : triangles) {
        out << "  facet normal 0 0 0\n    outer loop\n";
        for (const auto& p : t) out << "      vertex " << double(p[0]) << ' ' << double(p[1]) << ' ' << double(p[2]) << '\n';
        out << "    endloop\n  endfacet\n";
    }
    out << "endsolid test\n";
    return out.str();
}

/// A closed soup: the 4 faces of a tetrahedron, each with its own copy of its corners.
std::vector<std::array<std::array<float, 3>, 3>> tetrahedron_soup() {
    const std::array<float, 3> a{0.1f, 0.2f, 0.3f}, b{1.5f, -0.0f, 1e-30f}, c{0.0f, 1.0f, 1.0f / 3.0f},
        d{-7.25f, 3.0f, 16777217.0f};
    return {{{a, c, b}}, {{a, b, d}}, {{b, c, d}}, {{a, d, c}}};
}

// ---- Exactness ------------------------------------------------------------------------------------------------

TEST_F(MeshIO, every_format_reads_back_bit_identical) {
    const MeshData mesh = awkward_tetrahedron();
    for (const std::string ext : {".off", ".obj", ".ply", ".OFF"}) {
        SCOPED_TRACE(ext);
        const std::string p = path("awkward" + ext);
        geotri::write_mesh(p, mesh);
        expect_identical(mesh, geotri::read_mesh(p));
    }
}

TEST_F(MeshIO, write_leaves_no_temporary_file_and_replaces_the_old_one) {
    const std::string p = path("mesh.off");
    write_bytes("mesh.off", "old content");
    geotri::write_mesh(p, awkward_tetrahedron());
    expect_identical(awkward_tetrahedron(), geotri::read_mesh(p));
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++files;
    EXPECT_EQ(files, 1u);
}

TEST_F(MeshIO, failed_write_leaves_nothing_behind) {
    MeshData bad = awkward_tetrahedron();
    bad.triangles.push_back({{0, 1, 7}});
    EXPECT_THROW(geotri::write_mesh(path("bad.off"), bad), geotri::InvalidInput);
    EXPECT_THROW(geotri::write_mesh(path("mesh.stl"), awkward_tetrahedron()), geotri::IOError);
    EXPECT_THROW(geotri::write_mesh(path("missing_folder/mesh.off"), awkward_tetrahedron()), geotri::IOError);
    EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(MeshIO, decimals_read_as_the_nearest_double) {
    const std::string p = write_bytes("decimal.off",
                                      "OFF\n4 1 0\n"
                                      "0.1 0.2 0.3\n"
                                      "+1e-320 -4.9406564584124654e-324 1e-400\n"
                                      "0.10000000000000000555 1.7976931348623158e308 2.2250738585072011e-308\n"
                                      "9007199254740993 -0 .5\n"
                                      "3 0 1 2\n");
    const MeshData mesh = geotri::read_mesh(p);
    EXPECT_TRUE(same_bits(mesh.positions[0].x(), 0.1));
    EXPECT_TRUE(same_bits(mesh.positions[0].y(), 0.2));
    EXPECT_TRUE(same_bits(mesh.positions[0].z(), 0.3));
    EXPECT_TRUE(same_bits(mesh.positions[1].x(), 1e-320));
    EXPECT_TRUE(same_bits(mesh.positions[1].y(), -std::numeric_limits<double>::denorm_min()));
    EXPECT_TRUE(same_bits(mesh.positions[1].z(), 0.0));
    EXPECT_TRUE(same_bits(mesh.positions[2].x(), 0.1));
    EXPECT_TRUE(same_bits(mesh.positions[2].y(), std::numeric_limits<double>::max()));
    EXPECT_TRUE(same_bits(mesh.positions[2].z(), 2.2250738585072009e-308));
    EXPECT_TRUE(same_bits(mesh.positions[3].x(), 9007199254740992.0));  // ties to even
    EXPECT_TRUE(same_bits(mesh.positions[3].y(), -0.0));
    EXPECT_TRUE(same_bits(mesh.positions[3].z(), 0.5));
}

// ---- STL ------------------------------------------------------------------------------------------------------

TEST_F(MeshIO, stl_binary_and_ascii_weld_to_the_same_mesh) {
    const auto soup = tetrahedron_soup();
    const MeshData binary = geotri::read_mesh(write_bytes("binary.stl", binary_stl(soup)));
    const MeshData ascii = geotri::read_mesh(write_bytes("ascii.stl", ascii_stl(soup)));
    ASSERT_EQ(binary.positions.size(), 4u);
    ASSERT_EQ(binary.triangles.size(), 4u);
    expect_identical(binary, ascii);
    // First-occurrence order: the corners of the first facet come first.
    EXPECT_EQ(binary.triangles[0], (std::array<int, 3>{0, 1, 2}));
    EXPECT_EQ(binary.triangles[1], (std::array<int, 3>{0, 2, 3}));
    EXPECT_TRUE(same_bits(binary.positions[0].x(), double(0.1f)));
    EXPECT_TRUE(same_bits(binary.positions[3].z(), double(16777217.0f)));
}

TEST_F(MeshIO, stl_binary_whose_header_starts_with_solid) {
    const auto soup = tetrahedron_soup();
    const MeshData mesh = geotri::read_mesh(write_bytes("solid.stl", binary_stl(soup, "solid from a careless exporter")));
    EXPECT_EQ(mesh.positions.size(), 4u);
    EXPECT_EQ(mesh.triangles.size(), 4u);
}

TEST_F(MeshIO, stl_welds_only_equal_positions) {
    auto soup = tetrahedron_soup();
    soup[3][1][0] = std::nextafter(soup[3][1][0], 0.0f);  // one corner moved by one ulp: a vertex of its own
    soup[2][0][1] = 0.0f;                                  // +0 welds with -0, which came first
    const MeshData mesh = geotri::read_mesh(write_bytes("weld.stl", binary_stl(soup)));
    EXPECT_EQ(mesh.positions.size(), 5u);
    EXPECT_TRUE(std::signbit(mesh.positions[2].y()));
}

TEST_F(MeshIO, stl_broken_inputs) {
    const std::string whole = binary_stl(tetrahedron_soup());
    expect_read_error(write_bytes("truncated.stl", whole.substr(0, whole.size() - 7)), "truncated");
    expect_read_error(write_bytes("short.stl", whole.substr(0, 40)), "truncated");
    expect_read_error(write_bytes("zero.stl", binary_stl({})), "no faces");
    auto soup = tetrahedron_soup();
    soup[1][2][1] = std::numeric_limits<float>::quiet_NaN();
    expect_read_error(write_bytes("nan.stl", binary_stl(soup)), "NaN");
    const std::string ascii = ascii_stl(tetrahedron_soup());
    expect_read_error(write_bytes("cut.stl", ascii.substr(0, ascii.size() / 2)), "truncated");
    std::string four = ascii;
    four.insert(four.find("    endloop"), "      vertex 1 2 3\n");
    expect_read_error(write_bytes("quad.stl", four), "has more than 3 vertices");
    std::string inf = ascii;
    inf.replace(inf.find("vertex ") + 7, 1, "inf ");
    expect_read_error(write_bytes("inf.stl", inf), "non-finite");
    expect_read_error(write_bytes("garbage.stl", "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 1 2\n"),
                      "malformed line 4");
}

// ---- OFF ------------------------------------------------------------------------------------------------------

TEST_F(MeshIO, off_with_comments_colours_and_counts_on_the_header_line) {
    const MeshData mesh = geotri::read_mesh(write_bytes("coloured.off",
                                                         "# a comment before the header\n"
                                                         "COFF 4 2 0\n"
                                                         "\n"
                                                         "0 0 0 255 0 0 255\n"
                                                         "# a comment between vertices\n"
                                                         "1 0 0 0 255 0 255\r\n"
                                                         "0 1 0 0 0 255 255  # trailing comment\n"
                                                         "1 1 0.5 1 1 1 1\n"
                                                         "3 0 1 2 0.5 0.5 0.5\n"
                                                         "3\t1 3 2\n"));
    ASSERT_EQ(mesh.positions.size(), 4u);
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.positions[3], Eigen::Vector3d(1, 1, 0.5));
    EXPECT_EQ(mesh.triangles[1], (std::array<int, 3>{1, 3, 2}));
}

TEST_F(MeshIO, off_broken_inputs) {
    expect_read_error(write_bytes("empty.off", ""), "empty");
    expect_read_error(write_bytes("blank.off", "\n  \n# nothing\n"), "empty");
    expect_read_error(write_bytes("header.off", "PLY\n3 1 0\n"), "not an OFF file");
    expect_read_error(write_bytes("truncated.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n"), "truncated");
    expect_read_error(write_bytes("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), "at vertex 1");
    expect_read_error(write_bytes("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 -inf 0\n3 0 1 2\n"), "at vertex 2");
    expect_read_error(write_bytes("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                      "face 0 refers to vertex 3, out of range");
    expect_read_error(write_bytes("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), "out of range");
    expect_read_error(write_bytes("quad.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n4 0 1 3 2\n"),
                      "face 1 has 4 vertices");
    expect_read_error(write_bytes("letters.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"), "malformed line 4");
    expect_read_error(write_bytes("nofaces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"), "no faces");
    expect_read_error(write_bytes("huge.off", "OFF\n3000000000 1 0\n0 0 0\n"), "truncated");
    // A face count one short would drop a face in silence.
    expect_read_error(write_bytes("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n"),
                      "line 7 follows the 1 faces that the header announces");
    expect_read_error(write_bytes("junk.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\ngarbage 1 2 3\n"),
                      "line 7 follows");
}

TEST_F(MeshIO, obj_index_at_the_end_of_int_is_named_as_written) {
    // 2147483648 is the last index that fits an int once made 0-based: its message must not wrap around.
    expect_read_error(write_bytes("big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2147483648\n"),
                      "face 0 refers to vertex 2147483648, out of range (3 vertices; line 4)");
}

TEST_F(MeshIO, a_utf8_byte_order_mark_is_skipped_in_text_formats) {
    const std::string bom = "\xEF\xBB\xBF";
    const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# trailing comment\n";
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                            "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const std::string stl = ascii_stl(tetrahedron_soup());
    for (const auto& [name, text] :
         {std::pair{"t.off", off}, std::pair{"t.obj", obj}, std::pair{"t.ply", ply}, std::pair{"t.stl", stl}}) {
        const MeshData plain = geotri::read_mesh(write_bytes(std::string("plain_") + name, text));
        const MeshData marked = geotri::read_mesh(write_bytes(std::string("bom_") + name, bom + text));
        EXPECT_EQ(marked.positions, plain.positions) << name;
        EXPECT_EQ(marked.triangles, plain.triangles) << name;
        EXPECT_GE(plain.positions.size(), 3u) << name;
    }
}

// ---- OBJ ------------------------------------------------------------------------------------------------------

TEST_F(MeshIO, obj_with_texture_normals_and_negative_indices) {
    const MeshData mesh = geotri::read_mesh(write_bytes("variants.obj",
                                                         "# comment\n"
                                                         "mtllib missing.mtl\n"
                                                         "o thing\n"
                                                         "v 0 0 0\n"
                                                         "v 1 0 0 1.0\n"
                                                         "vt 0.5 0.5\n"
                                                         "vn 0 0 1\n"
                                                         "v 0 1 0 0.2 0.3 0.4\n"
                                                         "g group\n"
                                                         "usemtl stuff\n"
                                                         "s off\n"
                                                         "f 1/1/1 2/1/1 3/1/1\n"
                                                         "v 1 1 0.1\n"
                                                         "f 2//1 -1//1 -2//1 # comment\n"
                                                         "f\t-3/1 -4/1 -1/1\r\n"
                                                         "l 1 2\n"));
    ASSERT_EQ(mesh.positions.size(), 4u);
    ASSERT_EQ(mesh.triangles.size(), 3u);
    EXPECT_TRUE(same_bits(mesh.positions[3].z(), 0.1));
    EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{0, 1, 2}));
    EXPECT_EQ(mesh.triangles[1], (std::array<int, 3>{1, 3, 2}));
    EXPECT_EQ(mesh.triangles[2], (std::array<int, 3>{1, 0, 3}));
}

TEST_F(MeshIO, obj_broken_inputs) {
    expect_read_error(write_bytes("empty.obj", ""), "empty");
    expect_read_error(write_bytes("nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "no faces");
    expect_read_error(write_bytes("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
                      "face 0 refers to vertex 4, out of range");
    expect_read_error(write_bytes("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), "malformed line 4");
    expect_read_error(write_bytes("before.obj", "v 0 0 0\nv 1 0 0\nf 1 2 -3\nv 0 1 0\n"), "before the first vertex");
    expect_read_error(write_bytes("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 1 2 4 3\n"),
                      "face 1 has 4 vertices");
    expect_read_error(write_bytes("nan.obj", "v 0 0 0\nv 1 NaN 0\nv 0 1 0\nf 1 2 3\n"), "at vertex 1");
    expect_read_error(write_bytes("short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n"), "malformed line 2");
}

// ---- PLY ------------------------------------------------------------------------------------------------------

struct PlyLayout {
    std::string format;     // ascii, binary_little_endian, binary_big_endian
    std::string coord;      // float, double, int, short, ...
    std::string count;      // list count type
    std::string index;      // list index type
};

/// A PLY of the tetrahedron with integer-valued or float-exact coordinates, plus distracting extra properties
/// and elements. Coordinates are written in the given type; 0.1f shows how ASCII floats are read.
std::string make_ply(const PlyLayout& layout, const std::vector<std::array<double, 3>>& points,
                     const std::vector<std::array<int, 3>>& faces) {
    const bool ascii = layout.format == "ascii";
    const bool big = layout.format == "binary_big_endian";
    std::ostringstream header;
    header << "ply\nformat " << layout.format << " 1.0\ncomment test\nobj_info nothing\n"
           << "element vertex " << points.size() << "\nproperty uchar flags\nproperty " << layout.coord
           << " x\nproperty " << layout.coord << " y\nproperty list uchar float texture\nproperty " << layout.coord
           << " z\nproperty double quality\n"
           << "element face " << faces.size() << "\nproperty int material\nproperty list " << layout.count << ' '
           << layout.index << " vertex_indices\nproperty float weight\n"
           << "element camera 1\nproperty float view\nproperty list int short pixels\nend_header\n";
    std::string bytes = header.str();
    auto put = [&](const std::string& type, double value) {
        if (ascii) {
            std::ostringstream text;
            text.precision(17);
            text << value << ' ';
            bytes += text.str();
        } else if (type == "float") {
            append<float>(bytes, static_cast<float>(value), big);
        } else if (type == "double") {
            append<double>(bytes, value, big);
        } else if (type == "int") {
            append<std::int32_t>(bytes, static_cast<std::int32_t>(value), big);
        } else if (type == "uint") {
            append<std::uint32_t>(bytes, static_cast<std::uint32_t>(value), big);
        } else if (type == "short") {
            append<std::int16_t>(bytes, static_cast<std::int16_t>(value), big);
        } else if (type == "ushort") {
            append<std::uint16_t>(bytes, static_cast<std::uint16_t>(value), big);
        } else if (type == "char") {
            append<std::int8_t>(bytes, static_cast<std::int8_t>(value), big);
        } else if (type == "uchar") {
            append<std::uint8_t>(bytes, static_cast<std::uint8_t>(value), big);
        } else {
            throw std::logic_error("no such type " + type);
        }
    };
    auto end_line = [&] {
        if (ascii) bytes += "\n";
    };
    for (const auto& p : points) {
        put("uchar", 7);
        put(layout.coord, p[0]);
        put(layout.coord, p[1]);
        put("uchar", 2);
        put("float", 0.5);
        put("float", 0.25);
        put(layout.coord, p[2]);
        put("double", -1.0);
        end_line();
    }
    for (const auto& f : faces) {
        put("int", 42);
        put(layout.count, static_cast<double>(f.size()));
        for (const int v : f) put(layout.index, v);
        put("float", 1.5);
        end_line();
    }
    put("float", 3.0);
    put("int", 2);
    put("short", 10);
    put("short", 11);
    end_line();
    return bytes;
}

const std::vector<std::array<int, 3>> k_tetrahedron_faces{{{0, 2, 1}}, {{0, 1, 3}}, {{1, 2, 3}}, {{0, 3, 2}}};
const std::vector<std::array<double, 3>> k_integer_points{{{0, 0, 0}}, {{100, -3, 7}}, {{-20, 50, 1}}, {{5, 6, -128}}};

TEST_F(MeshIO, ply_every_encoding_and_type) {
    const std::vector<std::array<double, 3>> real_points{
        {{0.1f, 1.0f / 3.0f, -0.0f}}, {{1e30f, 1e-30f, 2.5f}}, {{-1, 2, 3}}, {{16777217.0f, 0.5f, 0.75f}}};
    const std::vector<std::array<double, 3>> double_points{
        {{0.1, 1.0 / 3.0, 1e-300}}, {{5e-324, -0.0, 2.5}}, {{-1, 2, 3}}, {{1.7976931348623157e308, 0.5, 0.75}}};
    int n = 0;
    for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
        for (const std::string coord : {"float", "double", "int", "short", "char", "uchar", "ushort", "uint"}) {
            for (const std::string count : {"uchar", "int", "ushort"}) {
                for (const std::string index : {"int", "uint", "uchar", "short"}) {
                    const auto& points = coord == "float"    ? real_points
                                         : coord == "double" ? double_points
                                                             : k_integer_points;
                    // Unsigned types take the absolute values.
                    std::vector<std::array<double, 3>> used = points;
                    if (coord == "uchar" || coord == "ushort" || coord == "uint") {
                        for (auto& p : used) {
                            for (double& x : p) x = std::fabs(x);
                        }
                    }
                    SCOPED_TRACE(format + " " + coord + " list " + count + " " + index);
                    const std::string file = path("t" + std::to_string(n++) + ".ply");
                    write_bytes(file.substr(file.find_last_of('/') + 1),
                                make_ply({format, coord, count, index}, used, k_tetrahedron_faces));
                    const MeshData mesh = geotri::read_mesh(file);
                    ASSERT_EQ(mesh.positions.size(), 4u);
                    ASSERT_EQ(mesh.triangles.size(), 4u);
                    for (std::size_t v = 0; v < 4; ++v) {
                        for (int i = 0; i < 3; ++i) {
                            EXPECT_TRUE(same_bits(mesh.positions[v][i], used[v][static_cast<std::size_t>(i)]))
                                << "vertex " << v << " axis " << i << " read " << mesh.positions[v][i];
                        }
                    }
                    for (std::size_t f = 0; f < 4; ++f) EXPECT_EQ(mesh.triangles[f], k_tetrahedron_faces[f]);
                }
            }
        }
    }
}

TEST_F(MeshIO, ply_ascii_float_reads_as_the_float_it_stands_for) {
    const std::string p = write_bytes("float.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float32 x\nproperty float32 y\n"
                                      "property float64 z\nelement face 1\nproperty list uint8 int32 vertex_index\n"
                                      "end_header\n0.1 0.100000001 0.1\n1 0 0\n0 1 0\n3 0 1 2\n");
    const MeshData mesh = geotri::read_mesh(p);
    EXPECT_TRUE(same_bits(mesh.positions[0].x(), double(0.1f)));
    EXPECT_TRUE(same_bits(mesh.positions[0].y(), double(0.1f)));
    EXPECT_TRUE(same_bits(mesh.positions[0].z(), 0.1));
}

TEST_F(MeshIO, ply_header_with_crlf_line_ends) {
    std::string bytes = make_ply({"binary_little_endian", "double", "uchar", "int"}, k_integer_points, k_tetrahedron_faces);
    std::string header = bytes.substr(0, bytes.find("end_header\n") + 11);
    const std::string body = bytes.substr(header.size());
    std::string crlf;
    for (const char c : header) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    const MeshData mesh = geotri::read_mesh(write_bytes("crlf.ply", crlf + body));
    EXPECT_EQ(mesh.positions[1], Eigen::Vector3d(100, -3, 7));
}

TEST_F(MeshIO, ply_broken_inputs) {
    const std::string good =
        make_ply({"binary_little_endian", "float", "uchar", "int"}, k_integer_points, k_tetrahedron_faces);
    const std::size_t data = good.find("end_header\n") + 11;
    expect_read_error(write_bytes("empty.ply", ""), "empty");
    expect_read_error(write_bytes("cut_header.ply", good.substr(0, data - 5)), "no 'end_header'");
    expect_read_error(write_bytes("cut_vertices.ply", good.substr(0, data + 30)), "truncated");
    expect_read_error(write_bytes("cut_faces.ply", good.substr(0, data + 4 * 22 + 10)), "truncated");
    expect_read_error(write_bytes("cut_tail.ply", good.substr(0, good.size() - 1)), "truncated");
    // An ASCII file with more than its header announces (a face count one short would drop a face in silence).
    const std::string ascii = make_ply({"ascii", "float", "uchar", "int"}, k_integer_points, k_tetrahedron_faces);
    expect_read_error(write_bytes("extra.ply", ascii + "3 0 1 2\n"), "data follows the elements");
    EXPECT_NO_THROW(geotri::read_mesh(write_bytes("blank_tail.ply", ascii + "\n  \r\n")));
    expect_read_error(write_bytes("not.ply", "PLY\n"), "not a PLY file");
    expect_read_error(write_bytes("format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"), "unknown format");
    expect_read_error(write_bytes("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n"),
                      "unknown property type");
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    expect_read_error(write_bytes("nan.ply", header + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), "at vertex 1");
    expect_read_error(write_bytes("inf.ply", header + "0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n"), "at vertex 2");
    expect_read_error(write_bytes("index.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                      "face 0 refers to vertex 3, out of range");
    expect_read_error(write_bytes("quad.ply", header + "0 0 0\n1 0 0\n0 1 0\n4 0 1 2 0\n"), "face 0 has 4 vertices");
    expect_read_error(write_bytes("letters.ply", header + "0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n"), "malformed line 12");
    expect_read_error(write_bytes("ascii_cut.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"), "truncated");
    expect_read_error(write_bytes("noxyz.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                  "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0\n"),
                      "lacks an x, y or z");
    expect_read_error(write_bytes("nofaces.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                  "property float z\nend_header\n0 0 0\n"),
                      "no faces");
    expect_read_error(write_bytes("strips.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                  "property float z\nelement tristrips 1\nproperty list int int vertex_indices\n"
                                  "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                      "no faces");
    expect_read_error(write_bytes("huge.ply",
                                  "ply\nformat binary_little_endian 1.0\nelement vertex 400000000\nproperty float x\n"
                                  "property float y\nproperty float z\nend_header\n"),
                      "truncated");
    expect_read_error(write_bytes("too_many.ply",
                                  "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                                  "property float y\nproperty float z\nend_header\n"),
                      "too many vertices");
}

// ---- Files and extensions -------------------------------------------------------------------------------------

TEST_F(MeshIO, unknown_extension_and_missing_file) {
    expect_read_error(write_bytes("mesh.xyz", "0 0 0\n"), "unknown mesh format");
    expect_read_error(write_bytes("mesh", "OFF\n"), "unknown mesh format");
    expect_read_error(path("missing.off"), "cannot open");
    expect_read_error(dir_.string() + "/", "unknown mesh format");
    fs::create_directories(dir_ / "folder.off");
    expect_read_error(path("folder.off"), "folder");
    // A device never ends: it is refused, not read until memory runs out.
    const fs::path zero = dir_ / "zero.stl";
    fs::create_symlink("/dev/zero", zero);
    expect_read_error(zero.string(), "it is a device, not a file");
}

// ---- Real meshes ----------------------------------------------------------------------------------------------

/// OpenMesh writes warnings about what it skips to its own streams.
void silence_openmesh() {
    omerr().disable();
    omout().disable();
    omlog().disable();
}

TEST(MeshIOShared, every_shared_mesh_matches_openmesh_counts) {
    silence_openmesh();
    const fs::path root = GEOTRI_SHARED_DATA;
    if (!fs::is_directory(root)) GTEST_SKIP() << "shared test meshes not found in " << root << " (GEOTRI_SHARED_DATA)";
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".stl" || ext == ".off" || ext == ".obj" || ext == ".ply")) {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty()) << "no meshes in " << root;
    std::size_t compared = 0;
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.string());
        MeshData mesh;
        ASSERT_NO_THROW(mesh = geotri::read_mesh(file.string()));
        EXPECT_GT(mesh.triangles.size(), 0u);

        OpenMesh::TriMesh_ArrayKernelT<> reference;
        OpenMesh::IO::Options options;
        const bool loaded = OpenMesh::IO::read_mesh(reference, file.string(), options);
        if (!loaded) {
            std::printf("[   INFO   ] %s: OpenMesh cannot read it; counts not compared\n", file.filename().c_str());
            continue;
        }
        // OpenMesh drops faces that would make its halfedge mesh non-manifold; only compare where it kept them all.
        if (reference.n_faces() != mesh.triangles.size()) {
            std::printf("[   INFO   ] %s: OpenMesh kept %zu of %zu faces; counts not compared\n",
                        file.filename().c_str(), reference.n_faces(), mesh.triangles.size());
            continue;
        }
        EXPECT_EQ(reference.n_vertices(), mesh.positions.size());
        ++compared;
    }
    std::printf("[   INFO   ] %zu of %zu meshes compared with OpenMesh\n", compared, files.size());
    EXPECT_GT(compared, files.size() / 2) << "OpenMesh agreed on too few files";
}

TEST(MeshIOShared, float32_meshes_match_openmesh_coordinates) {
    // Binary STL and binary float PLY hold float32 values: OpenMesh's float reading is exact for them, so the
    // coordinates must match bit for bit (and the order of vertices too).
    const fs::path root = GEOTRI_SHARED_DATA;
    if (!fs::is_directory(root)) GTEST_SKIP() << "shared test meshes not found in " << root << " (GEOTRI_SHARED_DATA)";
    silence_openmesh();
    for (const char* name : {"classic/bob_small.ply", "anatomy/femur_thing157696.stl", "cad/turbineblade.ply"}) {
        const fs::path file = root / name;
        if (!fs::exists(file)) continue;
        SCOPED_TRACE(file.string());
        const MeshData mesh = geotri::read_mesh(file.string());
        OpenMesh::TriMesh_ArrayKernelT<> reference;
        ASSERT_TRUE(OpenMesh::IO::read_mesh(reference, file.string()));
        ASSERT_EQ(reference.n_vertices(), mesh.positions.size());
        for (const auto vh : reference.vertices()) {
            const auto& p = reference.point(vh);
            const Eigen::Vector3d& q = mesh.positions[static_cast<std::size_t>(vh.idx())];
            ASSERT_TRUE(double(p[0]) == q.x() && double(p[1]) == q.y() && double(p[2]) == q.z())
                << "vertex " << vh.idx();
        }
    }
}

}  // namespace

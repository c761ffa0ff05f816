// build_geodesic_triangulation(): the same G as geotri-decimate --paths, geotri-trace --paths and geotri-flip give
// through their files, byte for byte, here made by the same library calls with the same files between them. (The
// install test runs the installed tools themselves against examples/embed.)

#include <geotri/geotri.h>
#include <geotri_test/g_checks.h>

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

namespace geotri {
namespace {

namespace fs = std::filesystem;

std::string bytes_of(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class BuildGeodesicTriangulation : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("geotri_build_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    /// G of `mesh` at `faces` faces as the three tools make it, each reading what the one before wrote.
    std::string through_files(const std::shared_ptr<const FineMesh>& fine, std::size_t faces) const {
        DecimateOptions decimate_options;  // geotri-decimate --faces N --paths P
        decimate_options.target_faces = faces;
        const BackoffResult decimated = decimate_backing_off(fine, decimate_options);
        const std::string coarse_path = (dir_ / "coarse.off").string(), paths_path = (dir_ / "coarse.paths").string();
        write_mesh(coarse_path, decimated.decimation.coarse);
        write_edge_paths(paths_path, make_edge_paths(*fine, decimated.decimation));

        GeodesicTriangulation traced(fine, make_coarse_mesh(read_mesh(coarse_path), coarse_path));  // geotri-trace
        const EdgePaths paths = read_edge_paths(paths_path);
        TraceOptions trace_options;
        trace_options.edge_paths = &paths;
        trace(traced, trace_options);
        const fs::path traced_path = dir_ / "traced.gtri";
        write_gtri(traced_path.string(), traced);

        GeodesicTriangulation g = read_gtri(traced_path.string(), fine);  // geotri-flip
        untangle_and_flip(g);
        const fs::path out = dir_ / "piped.gtri";
        write_gtri(out.string(), g);
        return bytes_of(out);
    }

    std::string written(const GeodesicTriangulation& g) const {
        const fs::path out = dir_ / "built.gtri";
        write_gtri(out.string(), g);
        return bytes_of(out);
    }

    fs::path dir_;
};

TEST_F(BuildGeodesicTriangulation, gives_the_gtri_of_decimate_trace_and_flip_through_their_files) {
    // bob is valid once traced; anchor's geodesics cross at 320 faces, so untangling has work to do.
    for (const auto& [mesh, faces] : {std::pair<std::string, std::size_t>{"classic/bob_small.ply", 100},
                                      std::pair<std::string, std::size_t>{"cad/anchor.off", 320}}) {
        SCOPED_TRACE(mesh);
        const auto fine =
            std::make_shared<const FineMesh>(load_fine_mesh(std::string(GEOTRI_TEST_DATA) + "/" + mesh));
        BuildOptions options;
        options.decimation.target_faces = faces;
        const BuildResult built = build_geodesic_triangulation(fine, options);
        EXPECT_EQ(written(built.g), through_files(fine, faces));

        const ValidationReport check = validate(built.g);
        EXPECT_TRUE(built.report.valid) << test::describe(built.report);
        EXPECT_EQ(built.report.violation_count, check.violation_count);
        EXPECT_EQ(built.report.faces, static_cast<int>(built.g.coarse().n_faces()));
        EXPECT_EQ(built.flips.valid_after, check.valid);

        // The same bytes for any thread count.
        for (int threads : {1, 3}) {
            options.threads = threads;
            EXPECT_EQ(written(build_geodesic_triangulation(fine, options).g), written(built.g))
                << threads << " threads";
        }
    }
}

TEST_F(BuildGeodesicTriangulation, refuses_a_missing_mesh_and_a_target_out_of_range) {
    BuildOptions options;
    options.decimation.target_faces = 100;
    EXPECT_THROW(build_geodesic_triangulation(nullptr, options), InvalidInput);
    const auto fine =
        std::make_shared<const FineMesh>(load_fine_mesh(std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply"));
    BuildOptions no_target;
    EXPECT_THROW(build_geodesic_triangulation(fine, no_target), InvalidInput);
}

}  // namespace
}  // namespace geotri

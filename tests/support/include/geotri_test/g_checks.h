#pragma once
// Checks and hand-made triangulations shared by the libgeotri tests of operations on G. Header-only, like
// fine_mesh.h: geotri_test_support links only libgeodesic, so a test that includes this header links libgeotri.

#include <geotri/decimate.h>
#include <geotri/decimate_backoff.h>
#include <geotri/edge_paths_io.h>
#include <geotri/fine_mesh.h>
#include <geotri/trace.h>
#include <geotri/validate.h>
#include <geotri_test/fine_mesh.h>
#include <geotri_test/procedural_meshes.h>

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace geotri::test {

/// One line per violation, for failure messages.
inline std::string describe(const ValidationReport& r) {
    std::string s;
    for (const Violation& v : r.violations) s += "  [" + std::to_string(v.condition) + "] " + v.what + "\n";
    return s;
}

/// Valid with the overlay, and the patch areas sum to the area of T within 1e-9 relative.
inline void expect_valid_with_area(const GeodesicTriangulation& g) {
    const ValidationReport r = validate(g);
    EXPECT_TRUE(r.valid) << describe(r);
    EXPECT_TRUE(r.overlay_checked);
    EXPECT_NEAR(r.patch_area, r.fine_area, 1e-9 * r.fine_area);
}

/// The same coarse mesh with the same polyline on every edge: what untangling or refining gives for any thread count.
inline void expect_same_polylines(const GeodesicTriangulation& a, const GeodesicTriangulation& b,
                                  const std::string& what) {
    ASSERT_EQ(a.coarse().n_vertices(), b.coarse().n_vertices()) << what;
    ASSERT_EQ(a.coarse().n_edges(), b.coarse().n_edges()) << what;
    for (auto e : a.coarse().edges()) EXPECT_EQ(a.polyline(e), b.polyline(e)) << what << ", edge " << e.idx();
}

/// The unit cube (each side a 4 x 4 grid of squares) with G made of the cube's eight corners (corner k at
/// (k & 1, k >> 1 & 1, k >> 2 & 1)) and one diagonal per side, traced. It is valid.
inline GeodesicTriangulation unit_cube_g() {
    auto fine = fine_of(cube(4));
    MeshData data;
    for (int k = 0; k < 8; ++k)
        data.positions.push_back(
            fine->mesh.position(nearest_vertex(fine->mesh, Eigen::Vector3d(k & 1, k >> 1 & 1, k >> 2 & 1))));
    // Oriented outwards: counter-clockwise seen from outside.
    data.triangles = {{0, 3, 1}, {0, 2, 3}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                      {2, 7, 3}, {2, 6, 7}, {0, 6, 2}, {0, 4, 6}, {1, 3, 7}, {1, 7, 5}};
    GeodesicTriangulation g(fine, make_coarse_mesh(data, "cube"));
    trace(g);
    return g;
}

/// The coarse mesh of decimate() to at most `target_faces` faces.
inline CoarseMesh decimated_coarse(const FineMesh& fine, std::size_t target_faces) {
    DecimateOptions options;
    options.target_faces = target_faces;
    return make_coarse_mesh(decimate(fine, options).coarse, "decimated");
}

/// The mesh at `path`, decimated to at most `target_faces` faces (decimated_coarse()) and traced.
inline GeodesicTriangulation traced(const std::string& path, std::size_t target_faces) {
    auto fine = std::make_shared<const FineMesh>(load_fine_mesh(path));
    GeodesicTriangulation g(fine, decimated_coarse(*fine, target_faces));
    trace(g);
    return g;
}

/// The mesh at `path`, decimated to its coarsest or to 320 faces (backing off where the topology stops it above
/// them with geodesics that tangle, as geotri-decimate does) and traced in the decimation's classes, as the
/// pipeline does.
inline GeodesicTriangulation traced_in_classes(const std::string& path, const std::string& name, bool coarsest) {
    auto fine = std::make_shared<const FineMesh>(load_fine_mesh(path));
    DecimateOptions options;
    if (coarsest)
        options.coarsest = true;
    else
        options.target_faces = 320;
    const DecimateResult decimated = decimate_backing_off(fine, options).decimation;
    const EdgePaths paths = make_edge_paths(*fine, decimated);
    GeodesicTriangulation traced(fine, make_coarse_mesh(decimated.coarse, name));
    TraceOptions trace_options;
    trace_options.edge_paths = &paths;
    trace(traced, trace_options);
    return traced;
}

}  // namespace geotri::test

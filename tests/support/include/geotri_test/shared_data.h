#pragma once
// Where the shared real meshes are (GEOTRI_SHARED_DATA, a CMake cache variable), and which of them the tests use.

#include <string>
#include <vector>

namespace geotri::test {

/// The folder configured at build time (GEOTRI_SHARED_DATA), whether or not it exists.
std::string configured_shared_data_dir();

/// The folder of the shared real meshes (the compile definition GEOTRI_SHARED_DATA), or "" if it does not exist.
std::string shared_data_dir();

struct SharedMesh {
    std::string relative_path;  ///< e.g. "classic/bunny_closed_cgal.off"
    std::string path;           ///< shared_data_dir() + "/" + relative_path
    /// False for the one mesh that is not a closed, consistently oriented surface as stored (stress/boeing.off:
    /// an OFF soup with duplicated vertices, open unless welded and not consistently oriented once welded).
    bool closed_as_stored = true;
    /// A name made of [A-Za-z0-9_] only, for parameterised test names.
    std::string test_name;
};

/// Every .off, .obj, .ply and .stl file under anatomy/, classic/, cad/, stress/ and hard/ of shared_data_dir(), sorted
/// by relative path; empty if the folder is missing.
std::vector<SharedMesh> shared_meshes();

/// The shared mesh with this relative path; throws std::runtime_error if the folder or the file is missing.
SharedMesh shared_mesh(const std::string& relative_path);

}  // namespace geotri::test

#include <geotri_test/shared_data.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#ifndef GEOTRI_SHARED_DATA
#define GEOTRI_SHARED_DATA ""
#endif

namespace geotri::test {

namespace fs = std::filesystem;

std::string configured_shared_data_dir() { return GEOTRI_SHARED_DATA; }

std::string shared_data_dir() {
    const std::string dir = configured_shared_data_dir();
    std::error_code error;
    if (dir.empty() || !fs::is_directory(dir, error)) return {};
    return dir;
}

namespace {

std::string test_name_of(const std::string& relative_path) {
    std::string name = relative_path;
    for (char& c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))) c = '_';
    return name;
}

}  // namespace

std::vector<SharedMesh> shared_meshes() {
    std::vector<SharedMesh> meshes;
    const std::string dir = shared_data_dir();
    if (dir.empty()) return meshes;
    for (const char* folder : {"anatomy", "classic", "cad", "stress", "hard"}) {
        std::error_code error;
        const fs::path sub = fs::path(dir) / folder;
        if (!fs::is_directory(sub, error)) continue;
        for (const auto& entry : fs::directory_iterator(sub, error)) {
            if (!entry.is_regular_file()) continue;
            std::string ext = entry.path().extension().string();
            std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
            if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl") continue;
            SharedMesh mesh;
            mesh.relative_path = std::string(folder) + "/" + entry.path().filename().string();
            mesh.path = (fs::path(dir) / mesh.relative_path).string();
            mesh.closed_as_stored = mesh.relative_path != "stress/boeing.off";
            mesh.test_name = test_name_of(mesh.relative_path);
            meshes.push_back(std::move(mesh));
        }
    }
    std::sort(meshes.begin(), meshes.end(),
              [](const SharedMesh& a, const SharedMesh& b) { return a.relative_path < b.relative_path; });
    return meshes;
}

SharedMesh shared_mesh(const std::string& relative_path) {
    for (auto& mesh : shared_meshes())
        if (mesh.relative_path == relative_path) return mesh;
    throw std::runtime_error("shared mesh " + relative_path + " not found under '" + shared_data_dir() + "'");
}

}  // namespace geotri::test

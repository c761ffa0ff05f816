#pragma once
// The fine mesh T of a procedural mesh, for the libgeotri tests. Header-only: geotri_test_support links only
// libgeodesic, so a test that includes this header links libgeotri itself.

#include <geotri/fine_mesh.h>
#include <geotri/mesh_io.h>
#include <geotri_test/procedural_meshes.h>

#include <memory>
#include <string>

namespace geotri::test {

/// make_fine_mesh() of the mesh's arrays, shared as G holds it; `name` prefixes the messages.
inline std::shared_ptr<const FineMesh> fine_of(const TriangleMesh& mesh, const std::string& name = "procedural") {
    return std::make_shared<const FineMesh>(make_fine_mesh(MeshData{mesh.positions, mesh.triangles}, name));
}

}  // namespace geotri::test

// geotri-bench-subdivide: a closed triangle mesh Loop-subdivided N times (OpenMesh's subdivider), written as binary
// PLY: the large inputs of bench/large_pipeline.py, made from a shared mesh rather than bundled.
//
//   geotri-bench-subdivide IN OUT.ply [N]     (N: 2 by default; each time multiplies the faces by 4)

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3 || argc > 4) {
        std::fprintf(stderr, "usage: %s IN OUT.ply [N]\n", argv[0]);
        return 2;
    }
    const std::string in = argv[1], out = argv[2];
    const int times = argc == 4 ? std::atoi(argv[3]) : 2;
    if (times < 0) {
        std::fprintf(stderr, "%s: N must be >= 0\n", argv[0]);
        return 2;
    }
    omerr().disable();  // OpenMesh's notes on PLY header lines it skips (obj_info, comments)
    Mesh mesh;
    if (!OpenMesh::IO::read_mesh(mesh, in)) {
        std::fprintf(stderr, "%s: %s: cannot read the mesh\n", argv[0], in.c_str());
        return 1;
    }
    for (const auto& e : mesh.edges())
        if (mesh.is_boundary(e)) {
            std::fprintf(stderr, "%s: %s: the mesh is not closed (welded STL soups are not: use PLY, OFF or OBJ)\n",
                         argv[0], in.c_str());
            return 1;
        }
    OpenMesh::Subdivider::Uniform::LoopT<Mesh> loop;
    loop.attach(mesh);
    loop(static_cast<std::size_t>(times));
    loop.detach();
    if (!OpenMesh::IO::write_mesh(mesh, out, OpenMesh::IO::Options::Binary)) {
        std::fprintf(stderr, "%s: %s: cannot write the mesh\n", argv[0], out.c_str());
        return 1;
    }
    std::printf("%zu vertices, %zu faces\n", mesh.n_vertices(), mesh.n_faces());
    return 0;
}

// geodesic::Mesh's adjacency: twins, boundary halfedges and the topology errors, against a map of directed edges
// built here from the triangles alone.

#include <geodesic/errors.h>
#include <geodesic/mesh.h>
#include <geotri_test/procedural_meshes.h>

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace geotri::geodesic {
namespace {

/// The halfedges of each directed edge (from, to), in index order: halfedge 3f + i runs from corner i of face f.
std::map<std::pair<int, int>, std::vector<int>> directed_edges(const std::vector<std::array<int, 3>>& triangles) {
    std::map<std::pair<int, int>, std::vector<int>> edges;
    for (int f = 0; f < static_cast<int>(triangles.size()); ++f)
        for (int i = 0; i < 3; ++i) edges[{triangles[f][i], triangles[f][(i + 1) % 3]}].push_back(3 * f + i);
    return edges;
}

/// Checks every halfedge's twin and the boundary count against directed_edges().
void expect_adjacency_of(const test::TriangleMesh& arrays, const char* name) {
    const Mesh mesh = arrays.to_mesh();
    const auto edges = directed_edges(arrays.triangles);
    int boundary = 0;
    for (const auto& [edge, halfedges] : edges) {
        ASSERT_EQ(halfedges.size(), 1u) << name;
        const int h = halfedges.front();
        EXPECT_EQ(mesh.tail(h), edge.first) << name;
        EXPECT_EQ(mesh.head(h), edge.second) << name;
        const auto reverse = edges.find({edge.second, edge.first});
        if (reverse == edges.end()) {
            EXPECT_EQ(mesh.twin(h), -1) << name << ": halfedge " << h;
            ++boundary;
        } else {
            EXPECT_EQ(mesh.twin(h), reverse->second.front()) << name << ": halfedge " << h;
        }
    }
    EXPECT_EQ(mesh.num_boundary_halfedges(), boundary) << name;
}

std::string topology_error_of(std::vector<Eigen::Vector3d> positions, std::vector<std::array<int, 3>> triangles) {
    try {
        Mesh mesh(std::move(positions), std::move(triangles));
    } catch (const TopologyError& error) {
        return error.what();
    }
    return "no error";
}

TEST(MeshAdjacency, twins_of_closed_and_open_meshes_are_the_reversed_directed_edges) {
    expect_adjacency_of(test::icosphere(3), "icosphere");
    expect_adjacency_of(test::torus(2.0, 0.5, 24, 12), "torus");
    expect_adjacency_of(test::flat_grid(7, 5, 1.0, 1.0), "open grid");
    expect_adjacency_of(test::disjoint_union(test::cube(3), test::icosphere(1), {3.0, 0.0, 0.0}), "two components");
}

TEST(MeshAdjacency, an_edge_of_three_faces_is_named_the_smallest_first) {
    // A fan of three triangles around edge (1,2) and of three around edge (0,1): the second is reported, its vertex
    // pair being the smaller.
    const std::vector<Eigen::Vector3d> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                                                    {1, 1, 1}, {0, -1, 0}, {0, 0, -1}};
    const std::vector<std::array<int, 3>> triangles = {{1, 2, 3}, {2, 1, 4}, {1, 2, 5}, {0, 1, 3}, {1, 0, 6}, {0, 1, 5}};
    EXPECT_EQ(topology_error_of(positions, triangles), "edge (0,1) is shared by 3 faces (non-manifold)");
}

TEST(MeshAdjacency, two_faces_that_run_an_edge_the_same_way_are_named) {
    const std::vector<Eigen::Vector3d> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    // The tetrahedron with face 2 turned over: it runs edges (0,3), (3,2) and (2,0) as faces 0, 1 and 3 do.
    const std::vector<std::array<int, 3>> triangles = {{0, 2, 1}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    EXPECT_EQ(topology_error_of(positions, triangles), "faces 0 and 2 are inconsistently oriented at edge (0,2)");
}

}  // namespace
}  // namespace geotri::geodesic

#pragma once
// Procedural meshes for the tests and the benchmarks. Every generator is deterministic: a seed, never the clock.
// Faces are oriented counter-clockwise seen from outside (closed meshes) or from +z (flat meshes).

#include <geodesic/mesh.h>

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace geotri::test {

/// A mesh as plain arrays, before geodesic::Mesh builds its adjacency.
struct TriangleMesh {
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::array<int, 3>> triangles;

    /// geodesic::Mesh of a copy of the arrays.
    geodesic::Mesh to_mesh() const;
};

/// The square [0, width] x [0, height] in the plane z = 0, as an nx x ny grid of quads, each split along a random
/// diagonal. Interior vertices are moved by up to `perturbation` (a fraction of the cell size, at most 0.25) in x
/// and y, so that distances are not grid-aligned; boundary vertices stay on the boundary.
TriangleMesh flat_grid(int nx, int ny, double width, double height, double perturbation = 0.0, unsigned seed = 1);

/// A flat polygon made of unit cells: `rows[i][j] == '#'` fills the cell [j, j+1] x [R-1-i, R-i] (R = rows.size(),
/// so the first row is the top). Cells that touch only at a corner are not allowed. Each cell is split into
/// `subdivisions` x `subdivisions` quads with random diagonals; vertices inside the polygon are perturbed as in
/// flat_grid, vertices on its boundary are not (so the polygon is exactly the union of the cells).
TriangleMesh flat_cell_polygon(const std::vector<std::string>& rows, int subdivisions, double perturbation = 0.0,
                               unsigned seed = 1);

/// Cell masks for flat_cell_polygon: an L, a U, a comb with three teeth, an S (a path around four reflex corners),
/// and a 3 x 3 square with the middle cell removed (a polygon with a hole).
std::vector<std::string> l_shape_cells();
std::vector<std::string> u_shape_cells();
std::vector<std::string> comb_cells();
std::vector<std::string> s_shape_cells();
std::vector<std::string> square_with_hole_cells();

/// The closed surface of the box [0,a] x [0,b] x [0,c]; the faces orthogonal to x, y, z are split into na, nb, nc
/// parts along x, y, z. Vertex (i, j, k) of the lattice sits at (a·i/na, b·j/nb, c·k/nc), exactly at a, b, c on the
/// far faces. Quads are split
/// along one diagonal, or along a random one when `irregular_diagonals` is set.
TriangleMesh box(double a, double b, double c, int na, int nb, int nc, bool irregular_diagonals = false,
                 unsigned seed = 1);

/// The closed surface of the cube [0, size]^3 with every face split into n x n quads (see box()).
TriangleMesh cube(int n, double size = 1.0, bool irregular_diagonals = false, unsigned seed = 1);

/// A closed capped prism approximating a cylinder of axis z: the cross-section is the regular polygon with `sides`
/// corners (radius `radius`, corner 0 on the +x axis), each polygon side split into `side_subdivisions` columns,
/// the mantle into `rows` rows between z = 0 and z = height, each mantle quad into two triangles, and each cap
/// fan-triangulated around a centre vertex. Vertices: the mantle lattice row by row (row 0 at z = 0, each row
/// sides·side_subdivisions vertices, counter-clockwise from corner 0), then the bottom centre, then the top centre.
TriangleMesh capped_cylinder(double radius, double height, int sides, int rows, int side_subdivisions = 1);

/// An icosahedron whose faces are split into frequency^2 triangles, with vertices projected onto the sphere of
/// radius `radius` centred at the origin (20·frequency^2 faces).
TriangleMesh geodesic_sphere(int frequency, double radius = 1.0);

/// The icosphere of the given subdivision level: geodesic_sphere(2^level) (20·4^level faces).
TriangleMesh icosphere(int level, double radius = 1.0);

/// A torus around the z axis (major radius R, minor radius r) with n_major x n_minor quads, each split in two.
TriangleMesh torus(double major_radius, double minor_radius, int n_major, int n_minor);

/// geodesic_sphere(frequency) with every vertex moved radially by a random factor in [1 - amplitude, 1 + amplitude].
TriangleMesh perturbed_sphere(int frequency, double amplitude, unsigned seed = 1);

/// Both meshes in one, b's vertices moved by `offset` and renumbered after a's.
TriangleMesh disjoint_union(const TriangleMesh& a, const TriangleMesh& b, const Eigen::Vector3d& offset);

/// Axis-aligned bounding box diagonal length.
double bounding_diagonal(const TriangleMesh& mesh);

/// The vertex of `mesh` nearest to `x` (the lowest index among equally near ones).
int nearest_vertex(const geodesic::Mesh& mesh, const Eigen::Vector3d& x);

}  // namespace geotri::test

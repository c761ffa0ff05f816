#pragma once
// Oracles for the libgeodesic tests. They share no code with libgeodesic: positions of surface points, adjacency,
// corner angles, unfoldings, Dijkstra and the polygon shortest paths are all computed here from the raw arrays.

#include <geodesic/surface_point.h>
#include <geotri_test/procedural_meshes.h>

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace geotri::test {

constexpr double k_pi = 3.14159265358979323846;

/// The 3D position of a surface point, from the arrays alone.
Eigen::Vector3d point_position(const TriangleMesh& mesh, const geodesic::SurfacePoint& p);

/// The angle between two 3D vectors in [0, π], accurate near 0 and π (atan2, not acos).
double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// Adjacency and intrinsic angles computed independently of geodesic::Mesh.
class Adjacency {
public:
    explicit Adjacency(const TriangleMesh& mesh);

    /// Faces that contain the point (its face; both faces of its edge; the faces around its vertex), sorted.
    std::vector<int> faces_containing(const geodesic::SurfacePoint& p) const;
    /// The face with the directed edge from -> to, or -1.
    int face_with_directed_edge(int from, int to) const;
    bool has_edge(int a, int b) const;

    /// Corner angle of face f at its vertex slot i.
    double corner_angle(int f, int slot) const;
    /// Sum of the corner angles around v.
    double cone_angle(int v) const { return cone_angle_[v]; }
    bool is_boundary(int v) const { return boundary_[v] != 0; }
    /// Whether the faces around v form one fan (always true on a vertex-manifold mesh).
    bool has_single_fan(int v) const { return single_fan_[v] != 0; }
    /// Polar angle at v, counter-clockwise from the first edge of v's fan, of the direction towards q, a point of
    /// face f (f contains v). On a boundary vertex the fan starts at the boundary, so that the angle lies in
    /// [0, cone_angle(v)].
    double polar_angle(int v, int f, const Eigen::Vector3d& q) const;

    int num_vertices() const { return static_cast<int>(faces_around_.size()); }

private:
    const TriangleMesh& mesh_;
    std::vector<std::vector<int>> faces_around_;
    std::vector<std::pair<long long, int>> directed_edges_;  // sorted (key(from, to), face)
    std::vector<std::vector<int>> fan_;                      // ordered faces around v
    std::vector<std::vector<double>> fan_offset_;            // polar angle at which each fan face starts
    std::vector<double> cone_angle_;
    std::vector<unsigned char> boundary_;
    std::vector<unsigned char> single_fan_;
};

/// Distances along the edges of the mesh from several seeds (vertex, initial distance). +inf where unreachable.
std::vector<double> edge_dijkstra(const TriangleMesh& mesh, const std::vector<std::pair<int, double>>& seeds);

/// Seeds for edge_dijkstra that start at a surface point: the vertices of its simplex, at straight distances.
std::vector<std::pair<int, double>> dijkstra_seeds(const TriangleMesh& mesh, const geodesic::SurfacePoint& p);

/// What check_geodesic_path found.
struct PathReport {
    double length = 0.0;                ///< sum of the 3D segment lengths, computed here
    std::vector<std::string> problems;  ///< empty when the path is a valid geodesic polyline
    /// Interior edge points that lie on a vertex to 1e-12 of the mesh size: vertex passages that DESIGN.md §1 wants
    /// as vertex points. The geometry is checked with them replaced by their vertex.
    std::vector<std::string> representation;
    int edge_crossings_checked = 0;
    int vertices_checked = 0;
    int points_not_checked = 0;         ///< interior points next to a degenerate segment or face
};

/// Checks a path against DESIGN.md §1: interior points are edge or vertex points, consecutive points share a face,
/// no point repeats the previous one,
/// the path is straight across every edge once the two faces are unfolded (angle sum π), and passes only through
/// vertices with cone angle >= 2π (or boundary vertices) with at least π on each side. Angles to `angle_tolerance`.
PathReport check_geodesic_path(const TriangleMesh& mesh, const Adjacency& adjacency,
                               const std::vector<geodesic::SurfacePoint>& path, double angle_tolerance);

/// Shortest distance on the surface of the box [0,a] x [0,b] x [0,c] between two points of its surface, by
/// enumerating every sequence of distinct faces from a face of p to a face of q, unfolding it, and keeping the
/// straight segments that cross every shared edge in order. The minimum over these real paths is the distance,
/// because a shortest path on a convex polyhedron crosses each face at most once.
double box_surface_distance(const Eigen::Vector3d& size, const Eigen::Vector3d& p, const Eigen::Vector3d& q);

/// A polygon made of unit cells (the masks of flat_cell_polygon), and its exact shortest paths: Dijkstra on the
/// visibility graph of the reflex corners and the two end points.
class CellPolygon {
public:
    explicit CellPolygon(std::vector<std::string> rows);

    bool filled(int cx, int cy) const;
    /// Whether the closed polygon contains p (to 1e-12).
    bool contains(const Eigen::Vector2d& p) const;
    /// Whether the whole segment lies in the closed polygon.
    bool segment_inside(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
    const std::vector<Eigen::Vector2d>& reflex_corners() const { return reflex_; }
    /// Length of the shortest path from a to b inside the closed polygon.
    double shortest_path_length(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

private:
    std::vector<std::string> rows_;
    int num_rows_ = 0;
    int num_cols_ = 0;
    std::vector<Eigen::Vector2d> reflex_;
};

/// |got - expected| <= relative · max(|expected|, floor). Both infinite counts as equal.
bool near_relative(double got, double expected, double relative, double floor);

}  // namespace geotri::test

#include <random>

namespace geotri::test {

/// Random surface points with a fixed seed, for the sweeps.
class PointSampler {
public:
    explicit PointSampler(unsigned seed) : rng_(seed) {}
    /// A uniform number in [lo, hi).
    double uniform(double lo, double hi);
    int vertex(const TriangleMesh& mesh);
    /// A point inside a random face, barycentric coordinates in [0.05, 0.9].
    geodesic::SurfacePoint face_point(const TriangleMesh& mesh);
    /// A point on a random edge, t in [0.1, 0.9], with edge_v0 < edge_v1.
    geodesic::SurfacePoint edge_point(const TriangleMesh& mesh);

private:
    std::mt19937 rng_;
};

}  // namespace geotri::test

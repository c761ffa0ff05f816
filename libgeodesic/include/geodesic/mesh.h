#pragma once
// An immutable triangle mesh for exact geodesics: positions, triangles, halfedge adjacency, corner angles.

#include <geodesic/surface_point.h>

#include <Eigen/Core>
#include <array>
#include <vector>

namespace geotri::geodesic {

/// Halfedge h = 3·f + i of face f runs from triangle(f)[i] to triangle(f)[(i+1) % 3]; the face lies on its left.
/// The mesh may have boundaries, several components, saddle vertices and zero-area faces.
class Mesh {
public:
    /// Builds the adjacency and the per-corner geometry.
    /// Throws InvalidInput for an index out of range, a face that repeats a vertex, or a non-finite coordinate;
    /// TopologyError for an edge shared by more than two faces or used twice in the same direction.
    Mesh(std::vector<Eigen::Vector3d> positions, std::vector<std::array<int, 3>> triangles);

    int num_vertices() const { return static_cast<int>(positions_.size()); }
    int num_faces() const { return static_cast<int>(triangles_.size()); }
    int num_halfedges() const { return 3 * num_faces(); }

    const Eigen::Vector3d& position(int v) const { return positions_[v]; }
    const std::array<int, 3>& triangle(int f) const { return triangles_[f]; }
    const std::vector<Eigen::Vector3d>& positions() const { return positions_; }
    const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }

    // Halfedge navigation.
    static int face_of(int h) { return h / 3; }
    // One unsigned remainder and a select: these are on the hot path of every propagation.
    static int next(int h) { return static_cast<unsigned>(h) % 3u == 2u ? h - 2 : h + 1; }
    static int prev(int h) { return static_cast<unsigned>(h) % 3u == 0u ? h + 2 : h - 1; }
    int tail(int h) const { return halfedges_[h].tail; }
    int head(int h) const { return halfedges_[next(h)].tail; }
    /// The opposite halfedge in the neighbouring face, or -1 on a boundary.
    int twin(int h) const { return halfedges_[h].twin; }
    /// One halfedge leaving v (the first of its fan when v is on a boundary), or -1 for an isolated vertex.
    int outgoing(int v) const { return outgoing_[v]; }
    /// Every halfedge leaving v, in no particular order (also at a non-manifold vertex).
    struct HalfedgeRange {
        const int* first;
        const int* last;
        const int* begin() const { return first; }
        const int* end() const { return last; }
    };
    HalfedgeRange outgoing_halfedges(int v) const {
        return {outgoing_list_.data() + outgoing_offset_[v], outgoing_list_.data() + outgoing_offset_[v + 1]};
    }
    /// The halfedge from `from` to `to`, or -1 if there is none.
    int find_halfedge(int from, int to) const;

    double length(int h) const { return halfedges_[h].length; }
    /// Corner angle of face(h) at tail(h).
    double corner_angle(int h) const { return corner_angle_[h]; }
    /// The vertex opposite h, laid out in h's plane frame: tail(h) at (0,0), head(h) at (length(h),0), the face
    /// on the side y >= 0 (y == 0 for a zero-area face). Any face can be unfolded from these.
    const Eigen::Vector2d& apex(int h) const { return halfedges_[h].apex; }
    /// Sum of the corner angles around v: > 2π at a saddle, < 2π at a convex vertex.
    double cone_angle(int v) const { return cone_angle_[v]; }
    bool is_boundary_vertex(int v) const { return boundary_vertex_[v] != 0; }
    /// True when the faces around v form one fan (closed or, on a boundary, open).
    bool is_manifold_vertex(int v) const { return manifold_vertex_[v] != 0; }
    /// Polar angle in [0, cone_angle(tail(h))) of the direction of h at its tail, measured intrinsically and
    /// counter-clockwise from outgoing(tail(h)) (DESIGN.md §1). NaN at a non-manifold vertex.
    double polar_angle(int h) const { return polar_angle_[h]; }
    int num_boundary_halfedges() const { return num_boundary_halfedges_; }
    double face_area(int f) const;
    /// The sum of the face areas (computed once: validation asks for it on every check).
    double total_area() const { return total_area_; }
    /// Diagonal of the bounding box: the scale for tolerances that must not depend on units.
    double size() const { return size_; }

    /// The 3D position of a surface point. Throws InvalidInput if the point does not refer to this mesh.
    Eigen::Vector3d point(const SurfacePoint& p) const;

    /// The one representation of p (see SurfacePoint), after checking that it refers to this mesh: indices in
    /// range, an edge that exists, finite parameters in [0, 1] (barycentric coordinates may be off by rounding:
    /// they are clamped to be non-negative and normalised). Throws InvalidInput otherwise.
    SurfacePoint canonical(const SurfacePoint& p) const;

private:
    std::vector<Eigen::Vector3d> positions_;
    std::vector<std::array<int, 3>> triangles_;
    /// What crossing a face reads of its halfedges, side by side: the three of a face fill two cache lines.
    struct alignas(32) HalfedgeRecord {
        Eigen::Vector2d apex;
        double length = 0.0;
        int twin = -1;
        int tail = -1;
    };
    std::vector<HalfedgeRecord> halfedges_;
    std::vector<int> outgoing_;
    std::vector<int> outgoing_offset_;  // CSR: the halfedges leaving v are outgoing_list_[offset[v] .. offset[v+1])
    std::vector<int> outgoing_list_;
    std::vector<int> outgoing_head_;    // head of outgoing_list_[i], side by side for find_halfedge()
    std::vector<double> corner_angle_;
    std::vector<double> cone_angle_;
    std::vector<unsigned char> boundary_vertex_;
    std::vector<unsigned char> manifold_vertex_;
    std::vector<double> polar_angle_;
    int num_boundary_halfedges_ = 0;
    double size_ = 0.0;
    double total_area_ = 0.0;
};

}  // namespace geotri::geodesic

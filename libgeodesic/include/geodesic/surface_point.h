#pragma once
// A point of a triangle mesh's surface: on a vertex, on an edge, or inside a face (DESIGN.md §1).

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>

namespace geotri::geodesic {

enum class PointKind : std::uint8_t { vertex, edge, face };

/// One struct for the three kinds of surface point. Only the fields of its kind are meaningful.
/// - vertex: `vertex`.
/// - edge:   `edge_v0`, `edge_v1`, `t`; the point is (1-t)·p(v0) + t·p(v1), 0 < t < 1.
/// - face:   `face`, `bary`; barycentric coordinates in the face's vertex order, all positive, summing to 1.
/// Mesh::canonical() turns any well-formed point into its one representation (a point at t = 0 becomes a vertex
/// point, a face point with a zero coordinate becomes an edge point, edge points have edge_v0 < edge_v1).
struct SurfacePoint {
    PointKind kind = PointKind::vertex;
    int vertex = -1;
    int edge_v0 = -1;
    int edge_v1 = -1;
    double t = 0.0;
    int face = -1;
    std::array<double, 3> bary{0.0, 0.0, 0.0};

    static SurfacePoint at_vertex(int v);
    static SurfacePoint on_edge(int v0, int v1, double t);
    static SurfacePoint in_face(int f, const std::array<double, 3>& bary);

    /// Exact equality of kind and of the kind's fields.
    bool operator==(const SurfacePoint& other) const {
        if (kind != other.kind) return false;
        switch (kind) {
            case PointKind::vertex: return vertex == other.vertex;
            case PointKind::edge: return edge_v0 == other.edge_v0 && edge_v1 == other.edge_v1 && t == other.t;
            case PointKind::face: return face == other.face && bary == other.bary;
        }
        return false;
    }
    bool operator!=(const SurfacePoint& other) const { return !(*this == other); }
};

/// The command-line spelling: `v:I`, `e:I,J:T` or `f:I:B0,B1,B2`, with every double printed so it reads back exactly.
std::string to_spec(const SurfacePoint& point);

/// Writes to_spec(point) (so that a test that compares points or polylines names them when it fails).
std::ostream& operator<<(std::ostream& out, const SurfacePoint& point);

/// Parses the spelling of to_spec(). Throws InvalidInput with a message naming the problem.
SurfacePoint parse_spec(const std::string& spec);

}  // namespace geotri::geodesic

#include <geodesic/errors.h>
#include <geodesic/mesh.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

namespace geotri::geodesic {

namespace {

std::string edge_name(int a, int b) { return "(" + std::to_string(a) + "," + std::to_string(b) + ")"; }

// Angle between u and v, robust for needles and zero-area faces (atan2 instead of acos).
double angle_between(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    return std::atan2(u.cross(v).norm(), u.dot(v));
}

// Edge points name their edge with the smaller vertex first (SurfacePoint). Reversing costs a rounding of 1 - t
// for t < 1/2; producers that know the distance from either end (path tracing) build the ordered form directly.
// A reversed t that rounds to an end is that vertex.
SurfacePoint ordered_edge_point(int v0, int v1, double t) {
    if (v0 > v1) {
        std::swap(v0, v1);
        t = 1.0 - t;
    }
    if (t == 0.0) return SurfacePoint::at_vertex(v0);
    if (t == 1.0) return SurfacePoint::at_vertex(v1);
    return SurfacePoint::on_edge(v0, v1, t);
}

}  // namespace

Mesh::Mesh(std::vector<Eigen::Vector3d> positions, std::vector<std::array<int, 3>> triangles)
    : positions_(std::move(positions)), triangles_(std::move(triangles)) {
    const int nv = num_vertices();
    const int nf = num_faces();
    Eigen::AlignedBox3d box;
    for (int v = 0; v < nv; ++v) {
        if (!positions_[v].allFinite())
            throw InvalidInput("vertex " + std::to_string(v) + " has a non-finite coordinate");
        box.extend(positions_[v]);
    }
    size_ = nv > 0 ? box.diagonal().norm() : 0.0;
    for (int f = 0; f < nf; ++f) {
        const auto& t = triangles_[f];
        for (int i = 0; i < 3; ++i) {
            if (t[i] < 0 || t[i] >= nv)
                throw InvalidInput("face " + std::to_string(f) + " refers to vertex " + std::to_string(t[i]) +
                                   ", out of range [0, " + std::to_string(nv) + ")");
        }
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            throw InvalidInput("face " + std::to_string(f) + " repeats a vertex");
    }

    const int nh = 3 * nf;
    halfedges_.resize(nh);
    for (int h = 0; h < nh; ++h) halfedges_[h].tail = triangles_[h / 3][h % 3];

    // Outgoing halfedges per vertex (CSR, each vertex's in halfedge order), and their heads.
    outgoing_offset_.assign(nv + 1, 0);
    for (int h = 0; h < nh; ++h) ++outgoing_offset_[tail(h) + 1];
    for (int v = 0; v < nv; ++v) outgoing_offset_[v + 1] += outgoing_offset_[v];
    outgoing_list_.resize(nh);
    {
        std::vector<int> fill(outgoing_offset_.begin(), outgoing_offset_.end() - 1);
        for (int h = 0; h < nh; ++h) outgoing_list_[fill[tail(h)]++] = h;
        outgoing_head_.resize(nh);
        for (int i = 0; i < nh; ++i) outgoing_head_[i] = head(outgoing_list_[i]);
    }

    // Twins: the halfedges of edge {a, b} are those from a to b and from b to a, found in the two vertices' lists
    // (a few each) rather than by sorting all halfedges by edge, which took most of the time of loading a large T.
    // Where an edge has more than two halfedges, or two in the same direction, the edge with the smallest
    // (smaller vertex, larger vertex) is the one reported, its halfedges in index order.
    std::uint64_t worst_key = std::numeric_limits<std::uint64_t>::max();
    int worst_first = -1, worst_second = -1, worst_count = 0;
    for (int h = 0; h < nh; ++h) {
        if (halfedges_[h].twin >= 0) continue;  // paired from its twin, which came first
        const int a = tail(h), b = head(h);
        int count = 0, first = -1, second = -1, reverse = -1;
        auto visit = [&](int from, int to, bool same_direction) {
            for (int i = outgoing_offset_[from]; i < outgoing_offset_[from + 1]; ++i) {
                if (outgoing_head_[i] != to) continue;
                const int g = outgoing_list_[i];
                ++count;
                if (!same_direction) reverse = g;
                if (first < 0 || g < first) {
                    second = first;
                    first = g;
                } else if (second < 0 || g < second) {
                    second = g;
                }
            }
        };
        visit(a, b, true);
        visit(b, a, false);
        if (count == 2 && reverse >= 0) {
            halfedges_[h].twin = reverse;
            halfedges_[reverse].twin = h;
        } else if (count == 1) {
            ++num_boundary_halfedges_;
        } else if (h == first) {  // each bad edge once
            const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
            const std::uint64_t key = lo << 32 | hi;
            if (key < worst_key) {
                worst_key = key;
                worst_first = first;
                worst_second = second;
                worst_count = count;
            }
        }
    }
    if (worst_first >= 0) {
        const int h = worst_first, g = worst_second;
        if (worst_count > 2)
            throw TopologyError("edge " + edge_name(tail(h), head(h)) + " is shared by " + std::to_string(worst_count) +
                                " faces (non-manifold)");
        throw TopologyError("faces " + std::to_string(face_of(h)) + " and " + std::to_string(face_of(g)) +
                            " are inconsistently oriented at edge " + edge_name(tail(h), head(h)));
    }

    outgoing_.assign(nv, -1);
    boundary_vertex_.assign(nv, 0);
    for (int h = 0; h < nh; ++h) {
        const int v = tail(h);
        if (twin(h) < 0) {
            outgoing_[v] = h;
            boundary_vertex_[v] = 1;
            boundary_vertex_[head(h)] = 1;
        } else if (outgoing_[v] < 0) {
            outgoing_[v] = h;
        }
    }

    corner_angle_.resize(nh);
    cone_angle_.assign(nv, 0.0);
    for (int h = 0; h < nh; ++h) {
        const Eigen::Vector3d& p = positions_[tail(h)];
        const Eigen::Vector3d along = positions_[head(h)] - p;
        const Eigen::Vector3d back = positions_[tail(prev(h))] - p;
        halfedges_[h].length = along.norm();
        corner_angle_[h] = angle_between(along, back);
        // Straight from the 3D vectors rather than the law of cosines, which loses the height of needles.
        const double l = length(h);
        halfedges_[h].apex = l > 0.0 ? Eigen::Vector2d(back.dot(along) / l, along.cross(back).norm() / l)
                                       : Eigen::Vector2d(0.0, back.norm());
        cone_angle_[tail(h)] += corner_angle_[h];
    }
    for (int f = 0; f < num_faces(); ++f) total_area_ += face_area(f);

    // Polar angles: walk each vertex's fan counter-clockwise (h -> twin(prev(h))) from its first halfedge.
    polar_angle_.assign(nh, std::numeric_limits<double>::quiet_NaN());
    manifold_vertex_.assign(nv, 0);
    for (int v = 0; v < nv; ++v) {
        const int first = outgoing_[v];
        if (first < 0) continue;
        int count = 0;
        double angle = 0.0;
        for (int h = first; h >= 0;) {
            polar_angle_[h] = angle;
            angle += corner_angle_[h];
            ++count;
            h = twin(prev(h));
            if (h == first) break;
        }
        if (count == outgoing_offset_[v + 1] - outgoing_offset_[v]) {
            manifold_vertex_[v] = 1;
        } else {
            for (int h : outgoing_halfedges(v)) polar_angle_[h] = std::numeric_limits<double>::quiet_NaN();
        }
    }
}

int Mesh::find_halfedge(int from, int to) const {
    if (from < 0 || from >= num_vertices()) return -1;
    for (int i = outgoing_offset_[from]; i < outgoing_offset_[from + 1]; ++i)
        if (outgoing_head_[i] == to) return outgoing_list_[i];
    return -1;
}

double Mesh::face_area(int f) const {
    const auto& t = triangles_[f];
    return 0.5 * (positions_[t[1]] - positions_[t[0]]).cross(positions_[t[2]] - positions_[t[0]]).norm();
}

Eigen::Vector3d Mesh::point(const SurfacePoint& p) const {
    switch (p.kind) {
        case PointKind::vertex:
            if (p.vertex < 0 || p.vertex >= num_vertices())
                throw InvalidInput("vertex " + std::to_string(p.vertex) + " is out of range");
            return positions_[p.vertex];
        case PointKind::edge:
            if (p.edge_v0 < 0 || p.edge_v0 >= num_vertices() || p.edge_v1 < 0 || p.edge_v1 >= num_vertices())
                throw InvalidInput("edge " + edge_name(p.edge_v0, p.edge_v1) + " is out of range");
            return (1.0 - p.t) * positions_[p.edge_v0] + p.t * positions_[p.edge_v1];
        case PointKind::face: {
            if (p.face < 0 || p.face >= num_faces())
                throw InvalidInput("face " + std::to_string(p.face) + " is out of range");
            const auto& t = triangles_[p.face];
            return p.bary[0] * positions_[t[0]] + p.bary[1] * positions_[t[1]] + p.bary[2] * positions_[t[2]];
        }
    }
    throw InvalidInput("unknown surface point kind");
}

SurfacePoint Mesh::canonical(const SurfacePoint& p) const {
    switch (p.kind) {
        case PointKind::vertex:
            if (p.vertex < 0 || p.vertex >= num_vertices())
                throw InvalidInput("vertex " + std::to_string(p.vertex) + " is out of range [0, " +
                                   std::to_string(num_vertices()) + ")");
            return p;
        case PointKind::edge: {
            if (find_halfedge(p.edge_v0, p.edge_v1) < 0 && find_halfedge(p.edge_v1, p.edge_v0) < 0)
                throw InvalidInput("there is no edge " + edge_name(p.edge_v0, p.edge_v1));
            if (!std::isfinite(p.t) || p.t < 0.0 || p.t > 1.0)
                throw InvalidInput("edge parameter " + std::to_string(p.t) + " is outside [0, 1]");
            return ordered_edge_point(p.edge_v0, p.edge_v1, p.t);
        }
        case PointKind::face: {
            if (p.face < 0 || p.face >= num_faces())
                throw InvalidInput("face " + std::to_string(p.face) + " is out of range [0, " +
                                   std::to_string(num_faces()) + ")");
            std::array<double, 3> b = p.bary;
            double sum = 0.0;
            for (double& x : b) {
                if (!std::isfinite(x) || x < -1e-9)
                    throw InvalidInput("barycentric coordinate " + std::to_string(x) + " is not in [0, 1]");
                x = std::max(x, 0.0);
                sum += x;
            }
            if (!(sum > 0.0)) throw InvalidInput("barycentric coordinates sum to zero");
            if (std::abs(sum - 1.0) > 1e-9)
                throw InvalidInput("barycentric coordinates sum to " + std::to_string(sum) + ", not 1");
            // Normalise only what rounding cannot explain, so that canonical() of a canonical point is that point.
            if (std::abs(sum - 1.0) > 8.0 * std::numeric_limits<double>::epsilon())
                for (double& x : b) x /= sum;
            const auto& t = triangles_[p.face];
            int zeros = (b[0] == 0.0) + (b[1] == 0.0) + (b[2] == 0.0);
            if (zeros == 2) {
                for (int i = 0; i < 3; ++i)
                    if (b[i] != 0.0) return SurfacePoint::at_vertex(t[i]);
            }
            if (zeros == 1) {
                for (int i = 0; i < 3; ++i) {
                    if (b[i] == 0.0) {
                        const int a = (i + 1) % 3, c = (i + 2) % 3;
                        return ordered_edge_point(t[a], t[c], b[c] / (b[a] + b[c]));
                    }
                }
            }
            return SurfacePoint::in_face(p.face, b);
        }
    }
    throw InvalidInput("unknown surface point kind");
}

}  // namespace geotri::geodesic

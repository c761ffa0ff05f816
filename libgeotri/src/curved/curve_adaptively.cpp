#include <geodesic/errors.h>
#include <geotri/curved_elements.h>
#include <geotri/flip.h>
#include <geotri/relocate.h>
#include <geotri/split.h>
#include <geotri/tangent_angles.h>

#include "core/workspace.h"
#include "curved/element_cache.h"
#include "pipeline/flip_to_delaunay_detail.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace geotri {

namespace {

/// The edges of face f, longest first (ties in the face's halfedge order).
std::vector<OpenMesh::EdgeHandle> edges_longest_first(const GeodesicTriangulation& g, OpenMesh::FaceHandle f) {
    std::vector<OpenMesh::EdgeHandle> edges;
    for (OpenMesh::HalfedgeHandle h : g.coarse().fh_range(f)) edges.push_back(g.coarse().edge_handle(h));
    std::stable_sort(edges.begin(), edges.end(), [&](OpenMesh::EdgeHandle a, OpenMesh::EdgeHandle b) {
        return g.length(a) > g.length(b);
    });
    return edges;
}

/// The unit normal of face f of T (zero for a face of zero area).
Eigen::Vector3d face_normal(const geodesic::Mesh& mesh, int f) {
    const std::array<int, 3>& t = mesh.triangle(f);
    const Eigen::Vector3d n =
        (mesh.position(t[1]) - mesh.position(t[0])).cross(mesh.position(t[2]) - mesh.position(t[0]));
    const double length = n.norm();
    return length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

/// The largest angle between the normals of face `fine` of T and of a face beside it across an edge that ends at
/// vertex v: how sharply T bends at v, seen from that face.
double bend_at(const geodesic::Mesh& mesh, int fine, int v) {
    double bend = 0.0;
    for (int i = 0; i < 3; ++i) {
        const int h = 3 * fine + i;
        if ((mesh.tail(h) != v && mesh.head(h) != v) || mesh.twin(h) < 0) continue;
        const double cosine = face_normal(mesh, fine).dot(face_normal(mesh, geodesic::Mesh::face_of(mesh.twin(h))));
        bend = std::max(bend, std::acos(std::clamp(cosine, -1.0, 1.0)));
    }
    return bend;
}

/// Where e's polyline crosses a crease of T: its point where T's normal turns more than at all its other points
/// together (index 0 when there is none), and how far along e that point is, by arc length.
struct CreaseCrossing {
    std::size_t index = 0;
    double fraction = 0.0;
};

CreaseCrossing crease_crossing(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) {
    const geodesic::Mesh& mesh = g.fine().mesh;
    const Polyline& line = g.polyline(e);
    std::vector<double> arc(line.size(), 0.0);
    for (std::size_t i = 1; i < line.size(); ++i)
        arc[i] = arc[i - 1] + (mesh.point(line[i]) - mesh.point(line[i - 1])).norm();
    // The face of T that the segment from point i to i + 1 lies in; -1 along an edge of T, where it is both sides'.
    auto segment_face = [&](std::size_t i) {
        return on_common_edge(mesh, line[i], line[i + 1]) ? -1 : common_face(mesh, line[i], line[i + 1]);
    };
    double total_turn = 0.0, best_turn = 0.0;
    CreaseCrossing best;
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
        const int before = segment_face(i - 1), after = segment_face(i);
        if (before < 0 || after < 0 || before == after) continue;
        const double turn =
            std::acos(std::clamp(face_normal(mesh, before).dot(face_normal(mesh, after)), -1.0, 1.0));
        total_turn += turn;
        if (turn > best_turn) {
            best_turn = turn;
            best = {i, arc[i] / arc.back()};
        }
    }
    return best_turn > total_turn - best_turn ? best : CreaseCrossing{};
}

/// Whether face h is as the round found it: `changed` flags the faces of G at the start of the round that a change
/// touched, and a face that a split made since lies beyond it (its element is not in the cache yet).
bool unchanged(const std::vector<char>& changed, OpenMesh::FaceHandle h) {
    return static_cast<std::size_t>(h.idx()) < changed.size() && !changed[static_cast<std::size_t>(h.idx())];
}

/// One change of G made to mend a failing element: the faces whose elements it changed (those that the change
/// rebuilt, by handle) and the vertex of G that it made, moved, or joined to another by a flip.
struct Mend {
    enum class Kind { split, move, flip };
    std::vector<OpenMesh::FaceHandle> faces;
    OpenMesh::VertexHandle vertex;
    Kind kind = Kind::split;
};

/// Splits e at point `index` of its polyline (at its middle when `index` is 0).
bool split_edge_for(GeodesicTriangulation& g, OpenMesh::EdgeHandle e, std::size_t index, Mend& mend) {
    const CoarseMesh& coarse = g.coarse();
    const std::vector<OpenMesh::FaceHandle> faces{coarse.face_handle(coarse.halfedge_handle(e, 0)),
                                                  coarse.face_handle(coarse.halfedge_handle(e, 1))};
    const SplitResult r = index > 0 ? split_edge_at_point(g, e, index) : split_edge(g, e, 0.5);
    if (r.done) mend = {faces, r.vertex, Mend::Kind::split};
    return r.done;
}

/// Splits face f at point p of its patch.
bool split_face_for(GeodesicTriangulation& g, OpenMesh::FaceHandle f, const SurfacePoint& p, Mend& mend) {
    const SplitResult r = split_face(g, f, p);
    if (r.done) mend = {{f}, r.vertex, Mend::Kind::split};
    return r.done;
}

/// Moves vertex v of G to p, inside its star (relocate_vertex_in_star(), which keeps G valid).
bool move_vertex_for(GeodesicTriangulation& g, OpenMesh::VertexHandle v, const SurfacePoint& p, Mend& mend) {
    if (!relocate_vertex_in_star(g, v, p).done) return false;
    mend = {{}, v, Mend::Kind::move};
    for (OpenMesh::FaceHandle n : g.coarse().vf_range(v)) mend.faces.push_back(n);
    return true;
}

/// Joins vertices u and w of G by an edge where they face each other across one edge of G, unjoined: flips that
/// edge (flip(), which keeps G valid or refuses), unless either of its faces changed this round.
bool join_for(GeodesicTriangulation& g, OpenMesh::VertexHandle u, OpenMesh::VertexHandle w,
              const std::vector<char>& changed, Mend& mend) {
    const CoarseMesh& coarse = g.coarse();
    for (OpenMesh::HalfedgeHandle h : coarse.voh_range(u))
        if (coarse.to_vertex_handle(h) == w) return false;
    for (OpenMesh::HalfedgeHandle h : coarse.voh_range(u)) {
        // The edge opposite u in the face of h, seen from the face beyond it.
        const OpenMesh::HalfedgeHandle across = coarse.opposite_halfedge_handle(coarse.next_halfedge_handle(h));
        if (coarse.is_boundary(across) || coarse.to_vertex_handle(coarse.next_halfedge_handle(across)) != w) continue;
        const std::array<OpenMesh::FaceHandle, 2> faces{coarse.face_handle(h), coarse.face_handle(across)};
        if (!unchanged(changed, faces[0]) || !unchanged(changed, faces[1])) return false;
        if (!flip(g, coarse.edge_handle(across)).accepted()) return false;
        mend = {{faces[0], faces[1]}, u, Mend::Kind::flip};
        return true;
    }
    return false;
}

/// Where the element folds at vertex v of T, and a vertex of G, a corner of face h, stands on v already: joins it by
/// an edge of G (join_for()) to a vertex of G on another of the `fold` vertices, w, that shares an edge of T with v,
/// or on that edge. A geodesic between two points of one edge of T is that edge, so G's edge then runs along T's.
bool join_along_fold(GeodesicTriangulation& g, OpenMesh::FaceHandle h, int v,
                     const std::vector<std::pair<double, int>>& fold, const std::vector<char>& changed, Mend& mend) {
    const geodesic::Mesh& mesh = g.fine().mesh;
    const CoarseMesh& coarse = g.coarse();
    OpenMesh::VertexHandle u;
    for (OpenMesh::VertexHandle c : coarse.fv_range(h))
        if (g.location(c) == SurfacePoint::at_vertex(v)) u = c;
    const auto edges = mesh.outgoing_halfedges(v);
    for (const auto& [bend, w] : fold) {
        if (std::none_of(edges.begin(), edges.end(), [&, w = w](int e) { return mesh.head(e) == w; })) continue;
        auto on_edge_to_w = [&, w = w](const SurfacePoint& p) {
            return p == SurfacePoint::at_vertex(w) ||
                   (p.kind == geodesic::PointKind::edge && std::min(v, w) == p.edge_v0 && std::max(v, w) == p.edge_v1);
        };
        // A vertex of G that faces u across one edge is a neighbour of one of u's neighbours.
        for (OpenMesh::VertexHandle c : coarse.vv_range(u))
            for (OpenMesh::VertexHandle d : coarse.vv_range(c))
                if (d != u && on_edge_to_w(g.location(d)) && join_for(g, u, d, changed, mend)) return true;
    }
    return false;
}

/// The vertices of T where an element folds over T (the corners of ElementGeometry::folded_faces), each once with
/// how sharply T bends at it from a folded face (bend_at(), the largest): the sharpest first, then by index.
std::vector<std::pair<double, int>> fold_vertices(const geodesic::Mesh& mesh, const detail::ElementGeometry& element) {
    std::vector<std::pair<double, int>> bends;  // (-bend, vertex), to sort the sharpest first
    for (int fine : element.folded_faces)
        for (int v : mesh.triangle(fine)) bends.emplace_back(-bend_at(mesh, fine, v), v);
    std::sort(bends.begin(), bends.end());
    std::vector<std::pair<double, int>> vertices;
    for (const auto& [bend, v] : bends)
        if (std::none_of(vertices.begin(), vertices.end(), [v = v](const auto& seen) { return seen.second == v; }))
            vertices.emplace_back(-bend, v);
    return vertices;
}

/// Mends face f's element where it folds over T (ElementCertificate::surface): puts a vertex of G on one of the
/// element's `fold` vertices (fold_vertices()), where T bends most first. A fold
/// is a crease or a corner of T that the patch reaches over, often by a sliver that a geodesic passing a corner
/// leaves, and it keeps its angle however small the patch gets: it goes only when edges of G run along T's edges
/// there, and a geodesic between two vertices of T that share an edge is that edge. The vertex of T is looked for
/// in the closed patches of f and of the faces around f's corners that this round has not changed (`changed`):
/// on a side, that edge is split there; inside, the face is split there, or else, where its spokes cannot be made
/// (they would run along a geodesic that hugs the corner), the nearest of its corners that is not on a vertex of T
/// moves there. Where a corner stands on the vertex of T already, an edge of G is flipped to join it to another fold
/// vertex along an edge of T (join_along_fold()). `reached` says whether a vertex of T was found that is not a corner
/// yet, whether or not a change there was made.
bool mend_fold(GeodesicTriangulation& g, const detail::ElementCache& cache, OpenMesh::FaceHandle f,
               const std::vector<std::pair<double, int>>& fold, const std::vector<char>& changed, Mend& mend,
               bool& reached) {
    reached = false;
    const geodesic::Mesh& mesh = g.fine().mesh;
    const CoarseMesh& coarse = g.coarse();
    std::vector<OpenMesh::FaceHandle> around{f};  // f, then the fans of its corners, in order
    for (OpenMesh::VertexHandle c : coarse.fv_range(f))
        for (OpenMesh::FaceHandle n : coarse.vf_range(c))
            if (std::find(around.begin(), around.end(), n) == around.end()) around.push_back(n);
    for (const auto& [bend, v] : fold) {
        const SurfacePoint at = SurfacePoint::at_vertex(v);
        const auto holder = std::find_if(around.begin(), around.end(), [&](OpenMesh::FaceHandle h) {
            if (!unchanged(changed, h)) return false;
            const std::vector<int>& held = detail::element_geometry(cache, h).patch_vertices;
            return std::binary_search(held.begin(), held.end(), v);
        });
        if (holder == around.end()) continue;
        const OpenMesh::FaceHandle h = *holder;
        bool corner = false, on_side = false;
        for (OpenMesh::VertexHandle c : coarse.fv_range(h)) corner = corner || g.location(c) == at;
        if (corner) {
            // v is a vertex of G already, and the element still folds there: the edge of T from v along the fold
            // is to become an edge of G.
            if (join_along_fold(g, h, v, fold, changed, mend)) return true;
            continue;
        }
        reached = true;
        for (OpenMesh::HalfedgeHandle side : coarse.fh_range(h)) {
            const Polyline& line = g.polyline(coarse.edge_handle(side));
            const auto point = std::find(line.begin() + 1, line.end() - 1, at);
            if (point == line.end() - 1) continue;
            on_side = true;
            if (unchanged(changed, coarse.opposite_face_handle(side)) &&
                split_edge_for(g, coarse.edge_handle(side), static_cast<std::size_t>(point - line.begin()), mend))
                return true;
        }
        if (on_side) continue;
        if (split_face_for(g, h, at, mend)) return true;
        std::vector<std::pair<double, OpenMesh::VertexHandle>> corners;  // nearest first
        for (OpenMesh::VertexHandle c : coarse.fv_range(h))
            if (g.location(c).kind != geodesic::PointKind::vertex)
                corners.emplace_back((mesh.point(g.location(c)) - mesh.position(v)).norm(), c);
        std::sort(corners.begin(), corners.end());
        for (const auto& nearest : corners)
            if (move_vertex_for(g, nearest.second, at, mend)) return true;
    }
    return false;
}

/// Mends failing face f by refining: where one of its edges (longest first) crosses a crease of T
/// (crease_crossing()) in its middle half, that edge is split there, so that G's edges come to follow the crease;
/// where it crosses one nearer an end and the element folds over T (`folds`), that end moves onto the crease, as a
/// split there would leave a sliver. Else the longest edge whose split is not refused is split at its middle, or
/// else the face at `centre`, inside its patch, unless `bisect` is false.
bool split_for_curving(GeodesicTriangulation& g, OpenMesh::FaceHandle f, const SurfacePoint& centre, bool folds,
                       bool bisect, Mend& mend) {
    const std::vector<OpenMesh::EdgeHandle> edges = edges_longest_first(g, f);
    for (OpenMesh::EdgeHandle e : edges) {
        const CreaseCrossing crossing = crease_crossing(g, e);
        if (crossing.index == 0) continue;
        if (crossing.fraction >= 0.25 && crossing.fraction <= 0.75) {
            if (split_edge_for(g, e, crossing.index, mend)) return true;
        } else if (folds) {
            const OpenMesh::HalfedgeHandle h = g.coarse().halfedge_handle(e, 0);
            const OpenMesh::VertexHandle end =
                crossing.fraction < 0.5 ? g.coarse().from_vertex_handle(h) : g.coarse().to_vertex_handle(h);
            if (move_vertex_for(g, end, g.polyline(e)[crossing.index], mend)) return true;
        }
    }
    if (!bisect) return false;
    for (OpenMesh::EdgeHandle e : edges)
        if (split_edge_for(g, e, 0, mend)) return true;
    // Where no edge can be split (their new geodesics would leave the patches), the face itself, at its centre
    // (unless the patch's map gave none).
    if (centre.kind == geodesic::PointKind::vertex && centre.vertex < 0) return false;
    return split_face_for(g, f, centre, mend);
}

}  // namespace

CurveAdaptResult curve_adaptively(GeodesicTriangulation& g, const CurveAdaptOptions& options) {
    if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
        throw InvalidInput("curve_adaptively: the tolerance is not a positive number");
    if (!(options.min_quality >= 0.0 && options.min_quality <= 1.0))
        throw InvalidInput("curve_adaptively: the minimum quality is outside [0, 1]");
    if (options.max_rounds < 0) throw InvalidInput("curve_adaptively: max_rounds is negative");
    CurveAdaptResult result;
    // A round changes G around the failing elements only: the others are kept, not made again.
    detail::ElementCache cache;
    for (;;) {
        result.curved = detail::curve_elements(g, options.curve, cache);
        const double max_distance = options.tolerance * result.curved.diagonal;
        std::vector<OpenMesh::FaceHandle> failing;
        for (const CurvedElement& element : result.curved.elements)
            if (!element.passes(options.min_quality, max_distance)) failing.push_back(element.face);
        result.failing = static_cast<int>(failing.size());
        if (failing.empty()) return result;
        if (result.rounds >= options.max_rounds) {
            result.round_cap_reached = true;
            return result;
        }
        // Each failing face, in face order, that no change of this round has touched yet, is mended: where its
        // element folds over T, by a vertex of G on T's vertex there (mend_fold()), else by a split
        // (split_for_curving()). A sharp fold whose vertices of T are out of reach is not bisected: that would
        // only shrink the element away from them, and double the failing elements round after round. Face handles
        // stay valid across splits.
        std::vector<char> changed(g.coarse().n_faces(), 0);
        std::vector<OpenMesh::EdgeHandle> around;  // the links of the new and moved vertices
        int mends = 0;
        for (OpenMesh::FaceHandle f : failing) {
            if (changed[static_cast<std::size_t>(f.idx())]) continue;
            const detail::ElementGeometry& element = detail::element_geometry(cache, f);
            const bool folds = element.certificate.surface != Certification::valid;
            const std::vector<std::pair<double, int>> fold =
                folds ? fold_vertices(g.fine().mesh, element) : std::vector<std::pair<double, int>>{};
            // An element flat on one side of a bend of a right angle or more meets the faces on the other side
            // edge-on or worse at every size: bisecting it does not mend the fold, only a vertex of G there does.
            const bool sharp = !fold.empty() && fold.front().first >= 0.5 * M_PI;
            Mend mend;
            bool reached = false;
            const bool mended = (folds && mend_fold(g, cache, f, fold, changed, mend, reached)) ||
                                split_for_curving(g, f, element.centre, folds, !sharp || reached, mend);
            if (!mended) continue;
            for (OpenMesh::FaceHandle face : mend.faces)
                if (static_cast<std::size_t>(face.idx()) < changed.size())
                    changed[static_cast<std::size_t>(face.idx())] = 1;
            for (OpenMesh::HalfedgeHandle h : g.coarse().voh_range(mend.vertex))
                around.push_back(g.coarse().edge_handle(g.coarse().next_halfedge_handle(h)));
            (mend.kind == Mend::Kind::split ? result.splits
             : mend.kind == Mend::Kind::move ? result.moves
                                             : result.flips) += 1;
            ++mends;
        }
        if (mends == 0) return result;  // nothing mends what is left: the certificates say why
        // Splits leave thin triangles behind, whose corners' plane tells little of their surface: flips towards
        // geodesic Delaunay (which keep G valid) shape them again, starting from the changed vertices' links; the
        // rest of G is as the round found it.
        FlipToDelaunayOptions flips;
        flips.threads = options.curve.threads;
        FlipToDelaunayResult flipped;
        detail::improve_around(g, around, flips, Workspace{}, flipped);
        ++result.rounds;
    }
}

}  // namespace geotri

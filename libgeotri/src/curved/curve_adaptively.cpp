#include <geodesic/errors.h>
#include <geotri/curved_elements.h>
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

/// The point of e's polyline where T's normal turns the most (a crease that the polyline crosses), when that point
/// lies in the middle half of the edge and its turn is more than all the others together; 0 when there is none.
/// The middle half keeps both parts at least a quarter of the edge, so that splits at creases shape G no worse than
/// bisection by more than a bounded factor; a crease near an end comes into the middle half of a part after one or
/// two bisections.
std::size_t crease_crossing(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) {
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
    std::size_t best = 0;
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
        const int before = segment_face(i - 1), after = segment_face(i);
        if (before < 0 || after < 0 || before == after) continue;
        const double turn =
            std::acos(std::clamp(face_normal(mesh, before).dot(face_normal(mesh, after)), -1.0, 1.0));
        total_turn += turn;
        const double fraction = arc[i] / arc.back();
        if (turn > best_turn && fraction >= 0.25 && fraction <= 0.75) {
            best_turn = turn;
            best = i;
        }
    }
    return best_turn > total_turn - best_turn ? best : 0;
}

/// Splits failing face f: at the crease crossing of one of its edges (crease_crossing(), longest edge first), or
/// else at the middle of its longest edge whose split is not refused, or else at `centre`, inside its patch. A
/// smooth element flattens as it shrinks, but one that straddles a crease of T keeps the crease's angle at every
/// size: only edges of G along the crease, which vertices of G on it start, take the crease out of its elements. Returns whether a split was made, and if so, the
/// faces that it changed (those of the edge split) and the new vertex.
bool split_for_curving(GeodesicTriangulation& g, OpenMesh::FaceHandle f, const SurfacePoint& centre,
                       std::array<OpenMesh::FaceHandle, 2>& sides, OpenMesh::VertexHandle& vertex) {
    const std::vector<OpenMesh::EdgeHandle> edges = edges_longest_first(g, f);
    auto split = [&](OpenMesh::EdgeHandle e, std::size_t crossing) {
        const CoarseMesh& coarse = g.coarse();
        sides = {coarse.face_handle(coarse.halfedge_handle(e, 0)), coarse.face_handle(coarse.halfedge_handle(e, 1))};
        const SplitResult r = crossing > 0 ? split_edge_at_point(g, e, crossing) : split_edge(g, e, 0.5);
        vertex = r.vertex;
        return r.done;
    };
    for (OpenMesh::EdgeHandle e : edges)
        if (const std::size_t crossing = crease_crossing(g, e); crossing > 0 && split(e, crossing)) return true;
    for (OpenMesh::EdgeHandle e : edges)
        if (split(e, 0)) return true;
    // Where no edge can be split (their new geodesics would leave the patches), the face itself, at its centre
    // (unless the patch's map gave none).
    if (centre.kind == geodesic::PointKind::vertex && centre.vertex < 0) return false;
    sides = {f, OpenMesh::FaceHandle()};
    const SplitResult r = split_face(g, f, centre);
    vertex = r.vertex;
    return r.done;
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
        // Each failing face, in face order, that no split of this round has changed yet, is split
        // (split_for_curving()). Face handles stay valid across splits.
        std::vector<char> changed(g.coarse().n_faces(), 0);
        std::vector<OpenMesh::EdgeHandle> around;  // the links of the new vertices
        int splits = 0;
        for (OpenMesh::FaceHandle f : failing) {
            if (changed[static_cast<std::size_t>(f.idx())]) continue;
            std::array<OpenMesh::FaceHandle, 2> sides;
            OpenMesh::VertexHandle vertex;
            if (!split_for_curving(g, f, detail::patch_centre(cache, f), sides, vertex)) continue;
            for (OpenMesh::FaceHandle side : sides)
                if (side.is_valid() && static_cast<std::size_t>(side.idx()) < changed.size())
                    changed[static_cast<std::size_t>(side.idx())] = 1;
            for (OpenMesh::HalfedgeHandle h : g.coarse().voh_range(vertex))
                around.push_back(g.coarse().edge_handle(g.coarse().next_halfedge_handle(h)));
            ++splits;
        }
        if (splits == 0) return result;  // nothing mends what is left: the certificates say why
        // Splits leave thin triangles behind, whose corners' plane tells little of their surface: flips towards
        // geodesic Delaunay (which keep G valid) shape them again, starting from the new vertices' links; the rest
        // of G is as the round found it.
        FlipToDelaunayOptions flips;
        flips.threads = options.curve.threads;
        FlipToDelaunayResult flipped;
        detail::improve_around(g, around, flips, Workspace{}, flipped);
        ++result.rounds;
        result.splits += splits;
    }
}

}  // namespace geotri

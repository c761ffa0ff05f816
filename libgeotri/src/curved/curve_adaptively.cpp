#include <geodesic/errors.h>
#include <geotri/curved_elements.h>
#include <geotri/flip_to_delaunay.h>
#include <geotri/split.h>

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

}  // namespace

CurveAdaptResult curve_adaptively(GeodesicTriangulation& g, const CurveAdaptOptions& options) {
    if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
        throw InvalidInput("curve_adaptively: the tolerance is not a positive number");
    if (!(options.min_quality >= 0.0 && options.min_quality <= 1.0))
        throw InvalidInput("curve_adaptively: the minimum quality is outside [0, 1]");
    if (options.max_rounds < 0) throw InvalidInput("curve_adaptively: max_rounds is negative");
    CurveAdaptResult result;
    for (;;) {
        result.curved = curve_elements(g, options.curve);
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
        // Each failing face, in face order, that no split of this round has changed yet: its longest edge is
        // bisected, or where that split is refused, the next longest. Face handles stay valid across splits.
        std::vector<char> changed(g.coarse().n_faces(), 0);
        int splits = 0;
        for (OpenMesh::FaceHandle f : failing) {
            if (changed[static_cast<std::size_t>(f.idx())]) continue;
            for (OpenMesh::EdgeHandle e : edges_longest_first(g, f)) {
                const CoarseMesh& coarse = g.coarse();
                const std::array<OpenMesh::FaceHandle, 2> sides{coarse.face_handle(coarse.halfedge_handle(e, 0)),
                                                               coarse.face_handle(coarse.halfedge_handle(e, 1))};
                if (!split_edge(g, e, 0.5).done) continue;
                for (OpenMesh::FaceHandle side : sides)
                    if (side.is_valid() && static_cast<std::size_t>(side.idx()) < changed.size())
                        changed[static_cast<std::size_t>(side.idx())] = 1;
                ++splits;
                break;
            }
        }
        if (splits == 0) return result;  // nothing mends what is left: the certificates say why
        // Bisection alone leaves thin triangles behind, whose corners' plane tells little of their surface: flips
        // towards geodesic Delaunay (which keep G valid) shape them again.
        FlipToDelaunayOptions flips;
        flips.threads = options.curve.threads;
        flip_to_delaunay(g, flips);
        ++result.rounds;
        result.splits += splits;
    }
}

}  // namespace geotri

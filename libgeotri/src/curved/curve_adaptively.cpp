#include <geodesic/errors.h>
#include <geotri/curved_elements.h>
#include <geotri/flip_to_delaunay.h>
#include <geotri/split.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace geotri {

namespace {

/// The longest edge of face f (the first of the longest in the face's halfedge order).
OpenMesh::EdgeHandle longest_edge(const GeodesicTriangulation& g, OpenMesh::FaceHandle f) {
    OpenMesh::EdgeHandle longest;
    for (OpenMesh::HalfedgeHandle h : g.coarse().fh_range(f)) {
        const OpenMesh::EdgeHandle e = g.coarse().edge_handle(h);
        if (!longest.is_valid() || g.length(e) > g.length(longest)) longest = e;
    }
    return longest;
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
        // Each failing face's longest edge, once, in edge order: handles of edges stay valid across splits.
        std::vector<int> edges;
        for (const CurvedElement& element : result.curved.elements)
            if (!element.passes(options.min_quality, max_distance))
                edges.push_back(longest_edge(g, element.face).idx());
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        result.failing = static_cast<int>(std::count_if(
            result.curved.elements.begin(), result.curved.elements.end(),
            [&](const CurvedElement& element) { return !element.passes(options.min_quality, max_distance); }));
        if (edges.empty()) return result;
        if (result.rounds >= options.max_rounds) {
            result.round_cap_reached = true;
            return result;
        }
        int splits = 0;
        for (int e : edges)
            if (split_edge(g, OpenMesh::EdgeHandle(e), 0.5).done) ++splits;
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

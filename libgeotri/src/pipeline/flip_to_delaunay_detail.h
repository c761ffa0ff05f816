#pragma once
// Geodesic Delaunay flips for the library's own pipelines: on a G whose validation is known, and around a few edges
// with a workspace (refinement).

#include "core/workspace.h"

#include <geotri/flip_to_delaunay.h>
#include <geotri/validate.h>

#include <vector>

namespace geotri::detail {

/// flip_to_delaunay() on a G whose validation `report` is (validate() with the overlay): not validated again on
/// entry; on return, `report` is that of G as returned.
FlipToDelaunayResult flip_to_delaunay_validated(GeodesicTriangulation& g, const FlipToDelaunayOptions& options,
                                                ValidationReport& report);

/// flip_to_delaunay()'s sweeps, starting from `edges` and going on with the edges that their flips change, on a G
/// that the caller knows to be valid: no validate(), so that it costs what the flips around `edges` cost. Adds its
/// counts to `result`, and appends every edge that it flips to `flipped` when given (flips keep the edge's handle),
/// so that the caller can tell which faces changed without a pass over G. Throws InvalidInput for an edge not of G.
void improve_around(GeodesicTriangulation& g, const std::vector<OpenMesh::EdgeHandle>& edges,
                    const FlipToDelaunayOptions& options, const Workspace& workspace, FlipToDelaunayResult& result,
                    std::vector<OpenMesh::EdgeHandle>* flipped = nullptr);

}  // namespace geotri::detail

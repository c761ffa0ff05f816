#pragma once
// The new geodesics from a new or moved coarse vertex to the vertices around it ("spokes"), and the local checks
// that keep a valid G valid when they replace what was there (local_checks.h): what face and edge splits and the
// relocation of a vertex within its star share. Private to libgeotri.

#include "check/local_checks.h"
#include "core/workspace.h"

#include <geotri/geodesic_triangulation.h>
#include <geotri/split.h>

#include <string>
#include <vector>

namespace geotri::detail {

/// A new geodesic from the new vertex to an existing coarse vertex, and what bounds it.
struct Spoke {
    OpenMesh::VertexHandle to;
    int patch = -1;  ///< the coarse face whose (old) patch it must run in
    /// At the new vertex, when `has_wedge`: it must leave strictly inside the corner from wedge_from to wedge_to.
    bool has_wedge = false;
    double wedge_from = 0.0, wedge_to = 0.0;
    /// At `to`: it must arrive strictly inside the corner from the geodesic of corner_from counter-clockwise to that
    /// of corner_to (both halfedges leave `to`).
    OpenMesh::HalfedgeHandle corner_from, corner_to;
    std::vector<BoundingPath> around;  ///< the polylines it must not meet
    Polyline path;
    bool in_region = false;
};

/// Finds the geodesics of `spokes` from `from`: the shortest geodesics on T, then, when `checked`, for those that
/// fail the checks (straight, leaving inside the wedge, reaching `to` inside its corner, meeting none of `around`),
/// the shortest paths inside their patch. Returns why one could not be found, or empty. Unchecked, the spokes are
/// the shortest geodesics whatever they do: for fork splits, which untangling judges on all of G.
std::string find_spokes(const GeodesicTriangulation& g, const SurfacePoint& from, std::vector<Spoke>& spokes,
                        const SplitOptions& options, const Workspace& workspace, bool checked);

/// Empty when the geodesics of `spokes` (found, all from `from`) leave it in their order counter-clockwise, each
/// pair of them with a corner above k_min_new_corner between them, and meet nowhere else; else why not.
std::string spokes_apart(const geodesic::Mesh& mesh, const SurfacePoint& from, const std::vector<Spoke>& spokes);

}  // namespace geotri::detail

#pragma once
// Which patch of G holds a point of T, found without cutting T: straight rays from the point, and the side from
// which they first cross a polyline. Refinement uses it to skip the splits of patches that cannot hold a new vertex,
// each of which would cost a propagation before it was refused.

#include <geotri/geodesic_triangulation.h>

#include <optional>
#include <vector>

namespace geotri::detail {

/// Which of the patches of `faces` holds p strictly inside, for a G valid around them (each patch a disk bounded by
/// its face's three polylines, on their left). A straight ray from p that first meets one of those polylines
/// crosses it out of the patch that holds p: that face when it is one of `faces`, else none of them does (an
/// invalid handle, also when p is a point of one of their polylines). When three rays each walk the patches'
/// whole perimeter without meeting one, p is taken to lie in none of them (only a patch shaped like a balloon
/// could hold it): the answer is then a guess, good enough for a caller that only saves tries with it. A ray that
/// passes within rounding of a polyline's point, runs along a fine edge or stops at a fine vertex says nothing,
/// and the next is tried. Nothing when none gives an answer, or when p lies within rounding of a polyline: the
/// caller must find out otherwise.
std::optional<OpenMesh::FaceHandle> patch_holding(const GeodesicTriangulation& g,
                                                  const std::vector<OpenMesh::FaceHandle>& faces,
                                                  const SurfacePoint& p);

}  // namespace geotri::detail

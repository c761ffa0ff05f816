#pragma once
// The overlay of a few patches only, for PatchRegion: T cut along those patches' polylines where the patches lie,
// at a cost that grows with the patches instead of with T.

#include <geotri/overlay.h>

#include <vector>

namespace geotri::detail {

/// The triangles of build_overlay(g) that the patches of `coarse_faces` hold, in fine face order, with `patch`,
/// `fine_face`, `positions` and `points` for them (the vertices numbered anew; T's vertices too). T is cut along
/// the polylines of those faces only, and only the fine faces that the patches hold are visited: a flood from
/// the left side of each face's three paths, which stops at them. The other fields stay empty. Throws
/// InvalidInput("the patch of coarse face F is not a disk ...") when a patch is not a disk bounded by its face's
/// three polylines, as in a G that is not valid around it.
Overlay build_patch_overlay(const GeodesicTriangulation& g, const std::vector<int>& coarse_faces);

}  // namespace geotri::detail

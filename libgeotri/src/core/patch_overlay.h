#pragma once
// The overlay of a few patches only, for PatchRegion: T cut along those patches' polylines where the patches lie,
// at a cost that grows with the patches instead of with T.

#include <geotri/overlay.h>

#include <vector>

namespace geotri::detail {

/// For a G valid around the faces `coarse_faces`: the triangles of build_overlay(g) that their patches hold, in
/// fine face order, with `patch`, `fine_face`, `positions` and `points` for them (the vertices numbered anew, T's
/// too); the other fields stay empty. T is cut along those faces' polylines only, with every coarse vertex's
/// location as a point, and only the fine faces that the patches hold are visited: a flood from the left of
/// each face's three paths, which stops at them. Throws InvalidInput("the patch of coarse face F is not a disk
/// (...)") unless each patch is one piece bounded by its three paths, each met once from inside, of Euler
/// characteristic 1, with no coarse vertex but its corners in it. The other polylines are not cut, so one that
/// runs into a patch (G not valid there) goes unseen. Costs the patches' fine faces plus a pass over G's vertices.
Overlay build_patch_overlay(const GeodesicTriangulation& g, std::vector<int> coarse_faces);

}  // namespace geotri::detail

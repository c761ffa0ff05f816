#pragma once
// The elements that curving one G makes, kept for curving it again after local changes: an element depends only on
// its face's corners and the paths of its sides (and on T and the options), so a face whose corners and paths are
// the same keeps its element, and only the changed faces' patches are cut out of T again. What curve_adaptively()
// uses between its rounds.

#include <geotri/curved_elements.h>

#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace geotri::detail {

/// What make_element() finds for one face: the interior nodes and their positions, in gmsh's order, the
/// certificate, and what refinement needs to mend the element: the point of T at the centre of the reference
/// triangle (where to split the face when no edge split can be made), the faces of T that it folds over and the
/// vertices of T in its patch.
struct ElementGeometry {
    std::vector<SurfacePoint> interior;
    std::vector<Eigen::Vector3d> interior_positions;
    ElementCertificate certificate;
    SurfacePoint centre;
    /// The faces of T, in increasing order, over which the element is not proven to stand the right way up
    /// (ElementCertificate::surface).
    std::vector<int> folded_faces;
    /// The vertices of T in the closed patch, in increasing order.
    std::vector<int> patch_vertices;
};

/// One face's element with what it was made from: the corners' vertex indices and the sides' paths, from
/// halfedge_handle(face).
struct CachedElement {
    std::array<int, 3> corners{};
    std::array<Polyline, 3> paths;
    ElementGeometry geometry;
};

/// Per face index: the element made for it last, if any.
struct ElementCache {
    std::vector<std::optional<CachedElement>> by_face;
};

/// curve_elements(), making anew only the elements whose face is not in `cache` with the same corners and paths
/// (for those, their patches alone are cut out of T: build_patch_overlay()), and leaving every element made in
/// `cache`. The result is the same as curve_elements() without a cache. The cache holds for one T and one set of
/// options.
CurvedMesh curve_elements(const GeodesicTriangulation& g, const CurveOptions& options, ElementCache& cache);

/// What the last curve_elements() with `cache` found for face f. Precondition: that call made or kept f's element.
inline const ElementGeometry& element_geometry(const ElementCache& cache, OpenMesh::FaceHandle f) {
    return cache.by_face[static_cast<std::size_t>(f.idx())]->geometry;
}

}  // namespace geotri::detail

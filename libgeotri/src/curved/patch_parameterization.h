#pragma once
// A bijective map of one patch of a valid G onto the reference triangle (corners (0,0), (1,0), (0,1) for the face's
// corners 0, 1, 2): the boundary by arc length onto the sides, the inside by Tutte's embedding with mean-value
// weights (Floater: positive weights and a convex boundary make it one-to-one). The map is linear on each overlay
// triangle of the patch, so every point of the reference triangle has a preimage that is an exact point of T.

#include <geotri/geodesic_triangulation.h>
#include <geotri/overlay.h>

#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace geotri::detail {

/// Per coarse face (of `faces`), the indices of the overlay triangles in its patch, in increasing order.
std::vector<std::vector<int>> triangles_by_patch(const Overlay& overlay, std::size_t faces);

class PatchParameterization {
public:
    /// The map of coarse face f, whose corners are the from-vertices of its halfedges in the order of fh_range(f)
    /// from halfedge_handle(f). `overlay` is build_overlay(g) of a G valid at f, and `patch_triangles` the indices
    /// of its triangles in f's patch, in increasing order (triangles_by_patch()). Throws InvalidInput when f's patch
    /// is not a disk bounded by its three polylines, and NumericalError when the linear system cannot be solved.
    PatchParameterization(const GeodesicTriangulation& g, const Overlay& overlay, OpenMesh::FaceHandle f,
                          const std::vector<int>& patch_triangles);

    /// One overlay triangle of the patch: its overlay vertices, their reference points, and its fine face.
    struct Triangle {
        std::array<int, 3> vertices;         ///< overlay vertex indices
        std::array<Eigen::Vector2d, 3> reference;
        std::array<Eigen::Vector3d, 3> positions;
        int fine_face = -1;
    };
    const std::vector<Triangle>& triangles() const { return triangles_; }

    /// The preimage of reference point xi (in the closed reference triangle): a point of T and its position.
    /// Nothing when xi is outside it by more than rounding.
    struct Preimage {
        SurfacePoint point;
        Eigen::Vector3d position;
    };
    std::optional<Preimage> preimage(const Eigen::Vector2d& xi) const;

private:
    const geodesic::Mesh* fine_ = nullptr;
    const Overlay* overlay_ = nullptr;
    std::vector<Triangle> triangles_;
};

}  // namespace geotri::detail

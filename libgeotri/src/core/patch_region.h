#pragma once
// A region of T made of whole patches of G (DESIGN.md §1), cut out of the overlay as a triangle mesh of its own,
// so that libgeodesic can find shortest paths that stay inside it. The local operations use it when the shortest
// geodesic on all of T leaves the patches that a new edge must run in: the shortest path inside the region is
// then a geodesic of T whenever it does not touch the region's boundary, because it is straight everywhere.

#include <geodesic/mesh.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/overlay.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace geotri {

namespace geodesic {
class ExactGeodesic;
}

class PatchRegion {
public:
    /// The union of the patches of `coarse_faces`, from `overlay` = build_overlay(g) of a G whose patches of those
    /// faces are disks. Throws InvalidInput when one of them is not (it is in overlay.bad_patches) or when the
    /// region is not a surface libgeodesic accepts.
    PatchRegion(const GeodesicTriangulation& g, const Overlay& overlay, const std::vector<int>& coarse_faces);

    /// The same region with T cut along those faces' polylines only, where the patches lie: it costs what the
    /// patches hold, not a pass over T as build_overlay() does (for one region of a G, or for regions of many
    /// different Gs). For a G valid around those faces: the other polylines are not cut, so one that runs into a
    /// patch goes unseen. Throws InvalidInput when a patch is not one piece of Euler characteristic 1 bounded by
    /// its face's three polylines, or holds another coarse vertex.
    PatchRegion(const GeodesicTriangulation& g, const std::vector<int>& coarse_faces);

    /// The region as a mesh of its own: its vertices are overlay vertices, its faces overlay triangles.
    const geodesic::Mesh& mesh() const { return *mesh_; }

    /// p, a point of T, as a point of the region's mesh; nothing when p is not in the region (its closure).
    std::optional<SurfacePoint> to_region(const SurfacePoint& p) const;

    /// The shortest path inside the region from `from` to `to` (points of T in the region), as a polyline of T
    /// that starts and ends exactly at them. Empty, with `failure` saying why, when there is none, or when it
    /// touches the region's boundary anywhere but at its ends (it may then not be a geodesic of T).
    struct Path {
        Polyline polyline;
        std::string failure;
        bool touches_boundary = false;  ///< the failure is that the path touches the region's boundary
    };
    Path shortest_path(const SurfacePoint& from, const SurfacePoint& to) const;
    /// shortest_path() from `from` to each of `to`, with one propagation.
    std::vector<Path> shortest_paths(const SurfacePoint& from, const std::vector<SurfacePoint>& to) const;

private:
    /// Makes the region's mesh from the triangles of `overlay` that those patches hold.
    void cut_out(const GeodesicTriangulation& g, const Overlay& overlay, const std::vector<int>& coarse_faces);
    /// The path from the propagation's source (`from` on T) back from `end` (`to` on T, in the region).
    Path path_back(const geodesic::ExactGeodesic& propagation, const SurfacePoint& from, const SurfacePoint& end,
                   const SurfacePoint& to) const;
    /// A point of the region's mesh, back on T.
    SurfacePoint to_fine(const SurfacePoint& q) const;

    const geodesic::Mesh* fine_ = nullptr;
    std::shared_ptr<const Overlay> own_overlay_;  ///< the overlay of the patches alone, when this region made it
    const Overlay* overlay_ = nullptr;
    std::vector<int> overlay_vertex_;  ///< per region vertex
    std::vector<int> fine_face_;       ///< per region face
    std::optional<geodesic::Mesh> mesh_;
};

/// Whether p and q are the same point of `mesh` (their canonical forms agree, an edge point named from either end).
bool same_point(const geodesic::Mesh& mesh, const SurfacePoint& p, const SurfacePoint& q);

}  // namespace geotri

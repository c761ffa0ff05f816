#pragma once
// The overlay (DESIGN.md §1): T cut exactly along every polyline of G, each triangle tagged with its coarse face
// (patch) and its fine face. It also decides validity condition 4.

#include <geotri/geodesic_triangulation.h>

#include <Eigen/Core>
#include <array>
#include <vector>

namespace geotri {

struct Overlay {
    std::vector<Eigen::Vector3d> positions;        ///< T's vertices first (same indices), then the cut points
    /// Per vertex: where it lies on T (T's vertices first, then edge points, face points), in canonical form.
    std::vector<SurfacePoint> points;
    std::vector<std::array<int, 3>> triangles;     ///< each inside one fine face, oriented like it
    std::vector<int> fine_face;                    ///< per triangle
    std::vector<int> patch;                        ///< per triangle: its coarse face, or -1 if no patch claims it
    std::vector<int> colour;                       ///< per triangle: greedy colour of its patch (adjacent differ);
                                                   ///< -1 where patch is -1
    std::vector<double> patch_area;                ///< per coarse face (0 for a face that owns no region)
    /// Coarse faces whose patch is not a topological disk bounded by the face's three polylines (condition 4),
    /// in increasing order.
    std::vector<int> bad_patches;

    // Diagnostics for an invalid G; all empty or zero when G is valid.
    /// Coarse edges whose polyline could not be cut in full, in increasing order: empty, a point that does not
    /// refer to T, consecutive points that share no fine face, or a segment that crosses or overlaps another
    /// polyline's segment (then the later one is left out of the cut).
    std::vector<int> broken_edges;
    int num_regions = 0;                           ///< connected parts of T once cut along the polylines
    int unclaimed_regions = 0;                     ///< parts that no coarse face claims (patch -1)
    double unclaimed_area = 0.0;
    int num_colours = 0;

    /// Condition 4 holds: every coarse face owns one disk and nothing is left unclaimed.
    bool valid() const { return bad_patches.empty() && unclaimed_regions == 0; }
    /// Sum of patch_area.
    double total_patch_area() const;
};

/// Cuts T along G's polylines, finds the patches and colours them.
///
/// A region (a connected part of the cut T) belongs to the coarse face that lies on the left of the paths that
/// bound it (seen from outside, as the halfedges of that face run). A coarse face is good when the left sides of
/// its three paths all lie in one region, no other face claims that region, the region is a topological disk
/// (Euler characteristic 1, one simple boundary loop), and its boundary is exactly the three paths.
///
/// Works on an invalid G too (crossing or overlapping polylines, a polyline through a coarse vertex, a reversed
/// orientation, empty or malformed polylines, unset locations): it never throws for those, leaves out of the cut
/// what it cannot cut, and reports the coarse faces concerned in bad_patches. Deterministic, single-threaded.
Overlay build_overlay(const GeodesicTriangulation& g);

}  // namespace geotri

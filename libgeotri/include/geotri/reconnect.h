#pragma once
// Small polygon reconnection (DESIGN.md §2, local operations): the coarse faces of a small disk are taken out, with
// the coarse vertices inside it, and the polygon around them is triangulated anew with geodesic diagonals, the
// triangulation chosen among all of the polygon's to maximise the smallest corner angle (dynamic programming over
// the diagonals). It either leaves G valid, or is refused with G unchanged.

#include <geotri/geodesic_triangulation.h>

#include <string>
#include <vector>

namespace geotri {

struct ReconnectOptions {
    /// Refuse, G unchanged, unless all of G is valid afterwards (validate() with the overlay, which costs a few
    /// passes over T). When false, the local checks below are all: for a valid G they keep it valid.
    bool check_validity = true;
    /// Refuse unless the smallest corner of the new faces exceeds that of the old ones by more than this (radians);
    /// negative: no such condition. What improvement asks for; removing a vertex does not need it.
    double required_gain = -1.0;
    /// Polygons with more corners than this are refused (the dynamic programming is cubic, the diagonals quadratic).
    int max_corners = 12;
    /// Threads for the diagonals' propagations (one per corner); 0: as many as OpenMP likes. The result is the same
    /// for any count.
    int threads = 0;
    /// When the shortest geodesic between two corners leaves the polygon, try the shortest path inside the faces'
    /// patches.
    bool region_fallback = true;
};

struct ReconnectResult {
    bool done = false;
    std::string reason;               ///< one readable line when refused
    int corners = 0;                  ///< of the polygon
    int removed_vertices = 0;         ///< the coarse vertices that were inside it
    int diagonals = 0;                ///< geodesics of the new triangulation that are not sides of the polygon
    double min_corner_before = 0.0;   ///< the smallest corner of the old faces, radians
    double min_corner_after = 0.0;    ///< and of the new ones (when a triangulation was found)
    /// When done: the polygon's corners counter-clockwise, as handles after the coarse mesh's garbage collection.
    std::vector<OpenMesh::VertexHandle> corners_after;
};

/// Takes out `faces` (coarse faces forming a topological disk whose boundary is one simple polygon of coarse
/// edges), and the coarse vertices inside, and triangulates the polygon with the diagonals that maximise the
/// smallest corner angle. Each diagonal is the shortest geodesic between its two corners when that one leaves and
/// reaches them strictly inside the polygon's corners and meets none of its sides; else (with
/// options.region_fallback) the shortest path between them inside the union of the faces' patches, kept only when
/// it touches that region's boundary nowhere but at its ends (it is then straight everywhere: a geodesic of T) and
/// leaves both ends strictly inside the polygon's corners. A diagonal whose ends are already joined by an edge
/// outside the polygon is not used. For a valid G, these checks, with one that the chosen diagonals do not meet,
/// keep G valid: each diagonal runs inside the polygon, a disk. The coarse mesh is garbage-collected afterwards
/// when vertices were removed, so other handles may change. Refused, G unchanged, when the faces are not such a
/// disk, the polygon has more than options.max_corners corners, a corner of the polygon is not a vertex of its own
/// (it appears twice), no triangulation with positive corners exists, a vertex would be left with fewer than three
/// edges, the gain is below options.required_gain, two chosen diagonals meet, or (with options.check_validity) G
/// is not valid afterwards.
/// Preconditions: G's patches of `faces` are disks (always so in a valid G). Throws InvalidInput when a face is not
/// a face of G.
ReconnectResult reconnect_polygon(GeodesicTriangulation& g, const std::vector<OpenMesh::FaceHandle>& faces,
                                  const ReconnectOptions& options = {});

/// reconnect_polygon() of the faces around coarse vertex v: v goes, and its link polygon is triangulated anew.
/// Throws InvalidInput when v is not a vertex of G.
ReconnectResult reconnect_vertex(GeodesicTriangulation& g, OpenMesh::VertexHandle v,
                                 const ReconnectOptions& options = {});

}  // namespace geotri

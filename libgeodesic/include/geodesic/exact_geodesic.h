#pragma once
// Exact discrete geodesic distances and shortest paths by window propagation (Mitchell, Mount and Papadimitriou;
// Surazhsky et al. 2005), with window filtering (Xin and Wang 2009).

#include <geodesic/mesh.h>
#include <geodesic/surface_point.h>

#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

namespace geotri::geodesic {

struct PropagationOptions {
    /// Nothing farther than this is computed; farther points report +inf.
    double max_distance = std::numeric_limits<double>::infinity();
    /// When not empty, propagation ends as soon as every stop point's distance is final. Their distances (and
    /// those of every point nearer than settled_radius()) are exact; farther points report +inf.
    std::vector<SurfacePoint> stop_points;
    /// With stop points: explore towards them first. Events are taken in the order of their distance plus the
    /// straight-line distance that is left to the nearest stop point not yet settled (A*), which never
    /// overestimates, so the stop points' distances and paths stay exact while much less of the mesh is explored
    /// when they lie in few directions. Nothing else is promised then: when the propagation stops early,
    /// settled_radius() is 0 and every point other than a stop point reports +inf. Ignored without stop points or
    /// with a max_distance.
    bool goal_directed = false;
    /// Keep every window, so that distance() at any surface point and shortest_path() answer at once from them.
    /// False frees the windows that the propagation will not read again, so that the storage follows the wavefront,
    /// not the area reached: on curved meshes, about 8 MB at 100k faces and 40 MB at 1M faces, against 130-510 MB
    /// with every window kept at 100k. The vertex distances are the same to the bit, and those two queries then
    /// run new propagations each time they are called: a path to a vertex, leg by leg from each pseudo-source that it
    /// passes (a saddle or boundary vertex), each leg by a goal-directed propagation from there alone; a distance
    /// or a path at any other point, by a goal-directed propagation from the sources to it. For distance fields
    /// over large meshes, where few paths are wanted.
    bool keep_windows = true;
};

/// Counters of the last propagation, for benchmarks and tuning.
struct PropagationStats {
    std::size_t windows_created = 0;     ///< windows made (each crosses its face once, unless pruned first)
    std::size_t windows_propagated = 0;  ///< windows carried across a face
    std::size_t windows_pruned = 0;      ///< windows dropped before crossing, as dominated by a vertex or window
    std::size_t windows_merged = 0;      ///< fragments of one ray family merged before crossing a face
    std::size_t windows_freed = 0;       ///< without keep_windows: windows freed while the propagation ran
    std::size_t windows_not_made = 0;    ///< without keep_windows: windows that came to an edge the wavefront had
                                         ///< passed (nearer everywhere through an end vertex), so were not made;
                                         ///< keeping windows, they are made (and pruned, unless the propagation
                                         ///< stops first). How many depends on when the passes that free windows
                                         ///< run, which depends on the storage that earlier propagations left
    std::size_t vertex_emissions = 0;    ///< saddle, boundary or source vertices that emitted windows
    std::size_t queue_pushes = 0;        ///< keys set in the queue (new entries or entries moved): halfedges
                                         ///< whose windows cross a face, and vertices
    std::size_t queue_pops = 0;
    std::size_t peak_queue_size = 0;
    std::size_t window_bytes = 0;        ///< memory held by the windows' storage at the end (its largest during
                                         ///< the propagation; the storage is kept for the next one)
    bool stopped_early = false;          ///< ended by stop points or max_distance before the queue emptied
};

/// A reusable propagation over one mesh. Use one object per thread; the mesh must outlive it.
/// Memory and reset cost grow with the region explored, not with the mesh, so that many small propagations on a
/// large mesh stay cheap.
class ExactGeodesic {
public:
    explicit ExactGeodesic(const Mesh& mesh);
    ~ExactGeodesic();
    ExactGeodesic(ExactGeodesic&&) noexcept;
    ExactGeodesic& operator=(ExactGeodesic&&) noexcept;
    ExactGeodesic(const ExactGeodesic&) = delete;
    ExactGeodesic& operator=(const ExactGeodesic&) = delete;

    /// Computes distances from the nearest of `sources` (at least one). Replaces the previous propagation.
    /// Throws InvalidInput for an empty source list or a point that does not refer to the mesh.
    void propagate(const std::vector<SurfacePoint>& sources, const PropagationOptions& options = {});

    /// Exact distance of vertex v to the nearest source; +inf if unreachable or beyond the settled radius.
    double distance(int vertex) const;
    /// Exact distance of any surface point; +inf if unreachable or beyond the settled radius.
    double distance(const SurfacePoint& point) const;
    /// distance(v) for every vertex, in index order.
    std::vector<double> vertex_distances() const;

    /// The shortest path from the nearest source to `target`, both included, as a geodesic polyline (DESIGN.md §1).
    /// Its length equals distance(target). Empty if the target is unreachable or beyond the settled radius.
    std::vector<SurfacePoint> shortest_path(const SurfacePoint& target) const;

    /// Every point nearer than this is exact: +inf after a complete propagation, 0 after a goal-directed one that
    /// stopped early (then only the stop points are).
    double settled_radius() const;
    const PropagationStats& stats() const;
    /// Windows made by every propagate() of this object so far: a measure of the work done, the same on any machine,
    /// for callers that bound their effort. The propagations that queries run again without keep_windows are not
    /// counted.
    std::size_t windows_created_total() const;

private:
    class Impl;
    std::unique_ptr<Impl> impl_;
};

/// Length of a polyline of surface points: the sum of the straight segments between consecutive points.
double path_length(const Mesh& mesh, const std::vector<SurfacePoint>& path);

}  // namespace geotri::geodesic

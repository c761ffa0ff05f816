#pragma once
// Shortest geodesics between two points of T, kept to be used again: flips evaluated over and over on the same pair
// of coarse vertices (refinement tries a move or a split, then tries another next to it) each cost a propagation.
// A propagation from one point with one stop point gives the same path whatever propagation object runs it, so a
// path kept is the path that propagating again would give.

#include <geodesic/surface_point.h>

#include <array>
#include <cstddef>
#include <map>
#include <mutex>
#include <optional>
#include <vector>

namespace geotri {

/// Thread-safe. Holds at most `capacity` paths: when full, it starts again empty (which changes no result).
class PathCache {
public:
    explicit PathCache(std::size_t capacity = 1 << 16) : capacity_(capacity) {}

    /// The path kept from `from` to `to` (both in canonical form), if any.
    std::optional<std::vector<geodesic::SurfacePoint>> find(const geodesic::SurfacePoint& from,
                                                            const geodesic::SurfacePoint& to) const;
    /// Keeps `path` as the shortest geodesic from `from` to `to`.
    void keep(const geodesic::SurfacePoint& from, const geodesic::SurfacePoint& to,
              const std::vector<geodesic::SurfacePoint>& path);

private:
    using Key = std::array<double, 18>;
    static Key key_of(const geodesic::SurfacePoint& from, const geodesic::SurfacePoint& to);

    std::size_t capacity_;
    mutable std::mutex mutex_;
    std::map<Key, std::vector<geodesic::SurfacePoint>> paths_;
};

}  // namespace geotri

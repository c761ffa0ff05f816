#include "core/path_cache.h"

namespace geotri {

PathCache::Key PathCache::key_of(const geodesic::SurfacePoint& from, const geodesic::SurfacePoint& to) {
    Key key{};
    std::size_t i = 0;
    for (const geodesic::SurfacePoint* p : {&from, &to})
        for (double x : {static_cast<double>(p->kind), static_cast<double>(p->vertex), static_cast<double>(p->edge_v0),
                         static_cast<double>(p->edge_v1), p->t, static_cast<double>(p->face), p->bary[0], p->bary[1],
                         p->bary[2]})
            key[i++] = x;
    return key;
}

std::optional<std::vector<geodesic::SurfacePoint>> PathCache::find(const geodesic::SurfacePoint& from,
                                                                   const geodesic::SurfacePoint& to) const {
    const Key key = key_of(from, to);
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = paths_.find(key);
    if (it == paths_.end()) return std::nullopt;
    return it->second;
}

void PathCache::keep(const geodesic::SurfacePoint& from, const geodesic::SurfacePoint& to,
                     const std::vector<geodesic::SurfacePoint>& path) {
    const Key key = key_of(from, to);
    std::lock_guard<std::mutex> lock(mutex_);
    if (paths_.size() >= capacity_) paths_.clear();
    paths_.emplace(key, path);
}

}  // namespace geotri

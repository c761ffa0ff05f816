#pragma once
// What the edges of a decimated mesh are on the fine mesh: a path of fine vertices per edge, kept up to date through
// halfedge collapses. Collapsing v0 into v1 drags every edge (v0, w) along the collapsed edge, so that the new edge
// (v1, w) is the path from v1 to v0 followed by the path from v0 to w. These paths may overlap, but they keep the
// homotopy class of each edge on the fine surface with the surviving vertices taken out, which is what a geodesic
// of the edge must keep for the triangulation to be the decimated one (geodesic::straighten_path).

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace geotri::detail {

class CollapsePaths {
public:
    /// The path from fine vertex a to fine vertex b of the current edge (a, b); a single fine edge until a collapse
    /// has dragged it.
    std::vector<int> path(int a, int b) const {
        const auto found = paths_.find(key(a, b));
        if (found == paths_.end()) return {a, b};
        std::vector<int> path = found->second;
        if (path.front() != a) std::reverse(path.begin(), path.end());
        return path;
    }

    /// Before v0 collapses into v1: `neighbours` are v0's neighbours other than v1 and the two apexes of the
    /// collapsed edge (whose edges to v0 merge into their edges to v1, which keep their paths).
    void collapse(int v0, int v1, const std::vector<int>& neighbours, const std::vector<int>& apexes) {
        const std::vector<int> to_v0 = path(v1, v0);
        for (const int w : neighbours) {
            std::vector<int> dragged = to_v0;
            for (const int x : path(v0, w)) append(dragged, x);
            paths_.erase(key(v0, w));
            if (dragged.size() > 2) paths_[key(v1, w)] = std::move(dragged);
        }
        for (const int w : apexes) paths_.erase(key(v0, w));
        paths_.erase(key(v0, v1));
    }

private:
    static std::uint64_t key(int a, int b) {
        return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
    }
    // Appends x, dropping a step straight back (…, a, b, a → …, a): it goes to a removed vertex and returns.
    static void append(std::vector<int>& path, int x) {
        if (!path.empty() && path.back() == x) return;
        if (path.size() >= 2 && path[path.size() - 2] == x) {
            path.pop_back();
            return;
        }
        path.push_back(x);
    }

    std::unordered_map<std::uint64_t, std::vector<int>> paths_;
};

}  // namespace geotri::detail

#include "core/coarse_components.h"

#include <algorithm>
#include <numeric>

namespace geotri::detail {

CoarseComponents coarse_components(const CoarseMesh& coarse) {
    const std::size_t n = coarse.n_vertices();
    std::vector<std::size_t> parent(n);
    std::iota(parent.begin(), parent.end(), std::size_t{0});
    auto find = [&parent](std::size_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    auto end_of = [&coarse](OpenMesh::EdgeHandle e, int i) {
        return static_cast<std::size_t>(coarse.to_vertex_handle(coarse.halfedge_handle(e, i)).idx());
    };
    for (auto e : coarse.edges()) {
        const std::size_t a = find(end_of(e, 0)), b = find(end_of(e, 1));
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
    CoarseComponents result;
    result.of_vertex.assign(n, -1);
    std::vector<int> number_of_root(n, -1);
    for (std::size_t v = 0; v < n; ++v) {
        int& number = number_of_root[find(v)];
        if (number < 0) {
            number = static_cast<int>(result.genus.size());
            result.genus.push_back(0);
        }
        result.of_vertex[v] = number;
    }
    std::vector<int> euler(result.genus.size(), 0);
    for (std::size_t v = 0; v < n; ++v) ++euler[static_cast<std::size_t>(result.of_vertex[v])];
    for (auto e : coarse.edges()) --euler[static_cast<std::size_t>(result.of_vertex[end_of(e, 0)])];
    for (auto f : coarse.faces())
        ++euler[static_cast<std::size_t>(
            result.of_vertex[static_cast<std::size_t>(coarse.to_vertex_handle(coarse.halfedge_handle(f)).idx())])];
    for (std::size_t c = 0; c < euler.size(); ++c) result.genus[c] = (2 - euler[c]) / 2;
    return result;
}

}  // namespace geotri::detail

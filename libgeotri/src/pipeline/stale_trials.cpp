#include "pipeline/stale_trials.h"

#include <geotri/tangent_angles.h>

#include <algorithm>
#include <numeric>
#include <utility>

namespace geotri::detail {

namespace {

// G keeps its locations and polyline points in canonical form (GeodesicTriangulation::set_location(),
// set_polyline()), as the count reads them: the faces that hold a stored point are those that the count sees.
void add_faces_of(const geodesic::Mesh& mesh, const SurfacePoint& p, std::vector<int>& out) {
    for (int f : faces_holding(mesh, p)) out.push_back(f);
}

bool has_edge(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) {
    return static_cast<std::size_t>(e.idx()) < g.coarse().n_edges() && !g.coarse().status(e).deleted();
}

bool has_vertex(const GeodesicTriangulation& g, OpenMesh::VertexHandle v) {
    return static_cast<std::size_t>(v.idx()) < g.coarse().n_vertices() && !g.coarse().status(v).deleted();
}

/// Whether edge e is the same in both: present in both, with the same polyline object, length and ends, or in
/// neither.
bool same_edge(const GeodesicTriangulation& a, const GeodesicTriangulation& b, OpenMesh::EdgeHandle e) {
    const bool in_a = has_edge(a, e);
    if (in_a != has_edge(b, e)) return false;
    if (!in_a) return true;
    const CoarseMesh& ca = a.coarse();
    const CoarseMesh& cb = b.coarse();
    const OpenMesh::HalfedgeHandle ha = ca.halfedge_handle(e, 0), hb = cb.halfedge_handle(e, 0);
    return &a.polyline(e) == &b.polyline(e) && a.length(e) == b.length(e) &&
           ca.from_vertex_handle(ha) == cb.from_vertex_handle(hb) && ca.to_vertex_handle(ha) == cb.to_vertex_handle(hb);
}

}  // namespace

std::vector<int> StaleTrials::changed_faces(const GeodesicTriangulation& g, const GeodesicTriangulation& trial) {
    std::vector<int> edges(std::max(g.coarse().n_edges(), trial.coarse().n_edges()));
    std::vector<int> vertices(std::max(g.coarse().n_vertices(), trial.coarse().n_vertices()));
    std::iota(edges.begin(), edges.end(), 0);
    std::iota(vertices.begin(), vertices.end(), 0);
    return changed_faces(g, trial, edges, vertices);
}

std::vector<int> StaleTrials::changed_faces(const GeodesicTriangulation& g, const GeodesicTriangulation& trial,
                                            const std::vector<int>& edges, const std::vector<int>& vertices) {
    const geodesic::Mesh& mesh = g.fine().mesh;
    std::vector<int> faces;
    for (const GeodesicTriangulation* side : {&g, &trial}) {
        const CoarseMesh& coarse = side->coarse();
        // The edges that differ, and the vertices that differ with every edge around them: where a vertex moves,
        // whether its edges still start at it (condition 1), and so take part in conditions 2 and 3, changes too,
        // even with their polylines unchanged. Each edge and vertex once: on fans of needles, a location on a
        // vertex of T is on hundreds of its faces.
        std::vector<int> side_edges, side_vertices;
        for (int i : edges)
            if (!same_edge(g, trial, OpenMesh::EdgeHandle(i)) && has_edge(*side, OpenMesh::EdgeHandle(i)))
                side_edges.push_back(i);
        for (int i : vertices) {
            const OpenMesh::VertexHandle v(i);
            if (has_vertex(g, v) && has_vertex(trial, v) && g.location(v) == trial.location(v)) continue;
            if (!has_vertex(*side, v)) continue;
            side_vertices.push_back(i);
            for (OpenMesh::HalfedgeHandle h : coarse.voh_range(v)) side_edges.push_back(coarse.edge_handle(h).idx());
        }
        std::sort(side_edges.begin(), side_edges.end());
        side_edges.erase(std::unique(side_edges.begin(), side_edges.end()), side_edges.end());
        // The faces of their polylines, and of their ends' locations: the ends' corners change with them.
        for (int i : side_edges) {
            const OpenMesh::EdgeHandle e(i);
            const OpenMesh::HalfedgeHandle h = coarse.halfedge_handle(e, 0);
            const int from = coarse.from_vertex_handle(h).idx(), to = coarse.to_vertex_handle(h).idx();
            side_vertices.push_back(from);
            side_vertices.push_back(to);
            const Polyline& line = side->polyline(e);
            for (std::size_t k = 0; k < line.size(); ++k) {
                const bool at_from = k == 0 && line[k] == side->location(OpenMesh::VertexHandle(from));
                const bool at_to = k + 1 == line.size() && line[k] == side->location(OpenMesh::VertexHandle(to));
                if (!at_from && !at_to) add_faces_of(mesh, line[k], faces);  // else added with the location
            }
        }
        std::sort(side_vertices.begin(), side_vertices.end());
        side_vertices.erase(std::unique(side_vertices.begin(), side_vertices.end()), side_vertices.end());
        for (int i : side_vertices) add_faces_of(mesh, side->location(OpenMesh::VertexHandle(i)), faces);
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
}

void StaleTrials::changed(const std::vector<int>& faces) {
    ++changes_;
    for (int f : faces) {
        if (static_cast<std::size_t>(f) >= changed_at_.size()) changed_at_.resize(static_cast<std::size_t>(f) + 1, 0);
        changed_at_[static_cast<std::size_t>(f)] = changes_;
    }
}

void StaleTrials::failed(const std::array<int, 3>& key, std::vector<int> faces, int operations) {
    failures_[key] = Failure{std::move(faces), operations, changes_};
}

std::optional<int> StaleTrials::known_failure(const std::array<int, 3>& key) const {
    const auto it = failures_.find(key);
    if (it == failures_.end()) return std::nullopt;
    const Failure& failure = it->second;
    for (int f : failure.faces) {
        const auto at = static_cast<std::size_t>(f);
        if (at < changed_at_.size() && changed_at_[at] > failure.epoch) return std::nullopt;
    }
    return failure.operations;
}

}  // namespace geotri::detail

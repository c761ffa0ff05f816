#include "ops/retrace.h"
#include "ops/with_workspace.h"

#include <geodesic/errors.h>
#include <geotri/relocate.h>

#include <algorithm>
#include <set>
#include <string>

namespace geotri {

using OpenMesh::VertexHandle;

namespace {

void require_vertex(const CoarseMesh& coarse, VertexHandle v, const char* caller) {
    if (!v.is_valid() || static_cast<std::size_t>(v.idx()) >= coarse.n_vertices() || coarse.status(v).deleted())
        throw InvalidInput(std::string(caller) + ": not a vertex of the coarse mesh");
}

}  // namespace

RelocateResult relocate_vertex(GeodesicTriangulation& g, VertexHandle v, const SurfacePoint& p,
                               const RelocateOptions& options) {
    return relocate_vertex(g, v, p, options, Workspace{});
}

RelocateResult relocate_vertex(GeodesicTriangulation& g, VertexHandle v, const SurfacePoint& p,
                               const RelocateOptions& options, const Workspace& workspace) {
    const CoarseMesh& coarse = g.coarse();
    require_vertex(coarse, v, "relocate_vertex");
    const SurfacePoint to = g.fine().mesh.canonical(p);
    RelocateResult result;
    const std::string name = "moving coarse vertex " + std::to_string(v.idx());
    for (VertexHandle u : coarse.vertices())
        if (g.location(u) == to) {
            result.reason = name + ": coarse vertex " + std::to_string(u.idx()) + " is there";
            return result;
        }

    GeodesicTriangulation before = g;  // restored when the move is refused
    std::vector<VertexHandle> neighbours;
    for (VertexHandle u : coarse.vv_range(v)) neighbours.push_back(u);
    g.set_location(v, to);
    const std::string why = retrace_edges(g, v, neighbours, workspace.propagation, options.check_validity);
    if (!why.empty()) {
        g = std::move(before);
        result.reason = name + ": " + why;
        return result;
    }
    result.done = true;
    return result;
}

std::vector<int> nearby_fine_vertices(const GeodesicTriangulation& g, VertexHandle v, int rings) {
    require_vertex(g.coarse(), v, "nearby_fine_vertices");
    const geodesic::Mesh& mesh = g.fine().mesh;
    const SurfacePoint& at = g.location(v);
    std::vector<int> ring;
    if (at.kind == geodesic::PointKind::vertex) ring = {at.vertex};
    else if (at.kind == geodesic::PointKind::edge) ring = {at.edge_v0, at.edge_v1};
    else ring.assign(mesh.triangle(at.face).begin(), mesh.triangle(at.face).end());
    std::set<int> seen(ring.begin(), ring.end());
    std::vector<int> nearby = at.kind == geodesic::PointKind::vertex ? std::vector<int>{} : ring;
    std::sort(nearby.begin(), nearby.end());
    for (int r = 0; r < rings; ++r) {
        std::vector<int> next;
        for (int x : ring)
            for (int h : mesh.outgoing_halfedges(x))
                if (seen.insert(mesh.head(h)).second) next.push_back(mesh.head(h));
        std::sort(next.begin(), next.end());
        nearby.insert(nearby.end(), next.begin(), next.end());
        ring = std::move(next);
    }
    std::set<int> taken;
    for (VertexHandle u : g.coarse().vertices())
        if (g.location(u).kind == geodesic::PointKind::vertex) taken.insert(g.location(u).vertex);
    nearby.erase(std::remove_if(nearby.begin(), nearby.end(), [&](int x) { return taken.count(x) > 0; }), nearby.end());
    return nearby;
}

}  // namespace geotri

#include "ops/retrace.h"
#include "ops/with_workspace.h"

#include <geodesic/errors.h>
#include <geotri/collapse.h>

#include <string>
#include <vector>

namespace geotri {

using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

CollapseResult collapse_edge(GeodesicTriangulation& g, HalfedgeHandle h, const CollapseOptions& options) {
    return collapse_edge(g, h, options, Workspace{});
}

CollapseResult collapse_edge(GeodesicTriangulation& g, HalfedgeHandle h, const CollapseOptions& options,
                             const Workspace& workspace) {
    CoarseMesh& coarse = g.coarse();
    if (!h.is_valid() || static_cast<std::size_t>(h.idx()) >= coarse.n_halfedges() ||
        coarse.status(coarse.edge_handle(h)).deleted())
        throw InvalidInput("collapse_edge: not a halfedge of the coarse mesh");
    const VertexHandle v = coarse.from_vertex_handle(h), w = coarse.to_vertex_handle(h);
    CollapseResult result;
    const std::string name = "collapsing coarse vertex " + std::to_string(v.idx()) + " onto " + std::to_string(w.idx());
    if (coarse.is_boundary(coarse.edge_handle(h))) {
        result.reason = name + ": the edge is on a boundary";
        return result;
    }
    if (!coarse.is_collapse_ok(h)) {
        result.reason = name + " would change the topology";
        return result;
    }
    // w loses one edge for each of the two faces at h and gains v's other edges; the two vertices opposite h
    // lose one edge each. A closed triangle mesh needs three at every vertex.
    const VertexHandle left = coarse.to_vertex_handle(coarse.next_halfedge_handle(h));
    const VertexHandle right = coarse.to_vertex_handle(coarse.next_halfedge_handle(coarse.opposite_halfedge_handle(h)));
    if (coarse.valence(left) <= 3 || coarse.valence(right) <= 3 || coarse.valence(v) + coarse.valence(w) - 4 < 3) {
        result.reason = name + " would leave a vertex with fewer than three edges";
        return result;
    }
    // The vertices that v joins to w: its neighbours but w and the two opposite h.
    std::vector<VertexHandle> joined;
    for (VertexHandle u : coarse.vv_range(v))
        if (u != w && u != left && u != right) joined.push_back(u);

    // The collapse and the garbage collection come before the new geodesics, so a refusal restores this copy.
    GeodesicTriangulation before = g;
    coarse.collapse(h);
    VertexHandle kept = w;
    std::vector<VertexHandle*> vertex_handles{&kept};
    for (VertexHandle& u : joined) vertex_handles.push_back(&u);
    std::vector<HalfedgeHandle*> no_halfedges;
    std::vector<OpenMesh::FaceHandle*> no_faces;
    coarse.garbage_collection(vertex_handles, no_halfedges, no_faces);

    const std::string why = retrace_edges(g, kept, joined, workspace.propagation, options.check_validity);
    if (!why.empty()) {
        g = std::move(before);
        result.reason = name + ": " + why;
        return result;
    }
    result.retraced = static_cast<int>(joined.size());
    result.done = true;
    result.kept = kept;
    return result;
}

}  // namespace geotri

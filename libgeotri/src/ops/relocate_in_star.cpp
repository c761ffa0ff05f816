#include "ops/spokes.h"
#include "ops/with_workspace.h"

#include <geodesic/errors.h>
#include <geotri/relocate.h>

#include "core/patch_region.h"

#include <string>
#include <vector>

namespace geotri {

using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

RelocateResult relocate_vertex_in_star(GeodesicTriangulation& g, VertexHandle v, const SurfacePoint& p) {
    return relocate_vertex_in_star(g, v, p, Workspace{});
}

RelocateResult relocate_vertex_in_star(GeodesicTriangulation& g, VertexHandle v, const SurfacePoint& p,
                                       const Workspace& workspace) {
    const CoarseMesh& coarse = g.coarse();
    if (!v.is_valid() || static_cast<std::size_t>(v.idx()) >= coarse.n_vertices() || coarse.status(v).deleted())
        throw InvalidInput("relocate_vertex_in_star: not a vertex of the coarse mesh");
    const geodesic::Mesh& mesh = g.fine().mesh;
    const SurfacePoint to = mesh.canonical(p);
    RelocateResult result;
    const std::string name = "moving coarse vertex " + std::to_string(v.idx());
    if (same_point(mesh, to, g.location(v))) {
        result.reason = name + ": it is there already";
        return result;
    }
    std::vector<HalfedgeHandle> fan;  // counter-clockwise
    for (HalfedgeHandle h : coarse.voh_ccw_range(v)) {
        if (coarse.is_boundary(h) || coarse.is_boundary(coarse.opposite_halfedge_handle(h))) {
            result.reason = name + ": it is on a boundary";
            return result;
        }
        fan.push_back(h);
    }
    const std::size_t n = fan.size();
    // The star is a disk bounded by the outer polylines only when the ring vertices are distinct; within the star,
    // the only coarse vertices are v and the ring.
    for (std::size_t i = 0; i < n; ++i) {
        const VertexHandle x = coarse.to_vertex_handle(fan[i]);
        if (same_point(mesh, to, g.location(x))) {
            result.reason = name + ": coarse vertex " + std::to_string(x.idx()) + " is there";
            return result;
        }
        for (std::size_t j = i + 1; j < n; ++j)
            if (coarse.to_vertex_handle(fan[j]) == x) {
                result.reason = name + ": its star is not a disk";
                return result;
            }
    }

    // The spoke to ring vertex x_i must reach it inside the star's corner there: counter-clockwise from x_i->x_{i+1}
    // (the next edge in face i = (v, x_i, x_{i+1})) to x_i->x_{i-1}; and it must not meet the outer polylines but
    // those two, which it may touch at x_i only.
    std::vector<Polyline> outer(n);  // outer[i]: x_i -> x_{i+1}
    for (std::size_t i = 0; i < n; ++i) outer[i] = g.path(coarse.next_halfedge_handle(fan[i]));
    std::vector<detail::Spoke> spokes(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t before = (i + n - 1) % n;
        detail::Spoke& s = spokes[i];
        s.to = coarse.to_vertex_handle(fan[i]);
        s.corner_from = coarse.next_halfedge_handle(fan[i]);
        s.corner_to = coarse.opposite_halfedge_handle(coarse.next_halfedge_handle(fan[before]));
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i) s.around.push_back({outer[j], 1, "the outer polyline from " + std::to_string(s.to.idx())});
            else if (j == before) s.around.push_back({g.path(s.corner_to), 1, "the outer polyline into it"});
            else s.around.push_back({outer[j], -1, "an outer polyline of the star"});
        }
    }
    SplitOptions options;
    options.region_fallback = false;  // the star is one region, not a patch per spoke (Spoke::patch stays unset)
    // The propagation object alone: nothing has propagated from `to` yet, and the star needs no overlay.
    std::string why = detail::find_spokes(g, to, spokes, options, Workspace{workspace.propagation}, true);
    if (why.empty()) why = detail::spokes_apart(mesh, to, spokes);
    if (!why.empty()) {
        result.reason = name + ": " + why;
        return result;
    }
    g.set_location(v, to);
    for (std::size_t i = 0; i < n; ++i) g.set_path(fan[i], std::move(spokes[i].path));
    result.done = true;
    return result;
}

}  // namespace geotri

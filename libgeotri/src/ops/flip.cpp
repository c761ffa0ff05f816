#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/flip.h>
#include <geotri/overlay.h>
#include <geotri/tangent_angles.h>

#include "check/local_checks.h"
#include "core/patch_region.h"
#include "core/path_cache.h"
#include "ops/with_workspace.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace geotri {

using geodesic::Mesh;
using geodesic::PointKind;
using OpenMesh::EdgeHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

namespace {

double cone_of(const GeodesicTriangulation& g, VertexHandle v) { return cone_angle(g.fine().mesh, g.location(v)); }

}  // namespace

double corner_angle(const GeodesicTriangulation& g, HalfedgeHandle h) {
    const CoarseMesh& coarse = g.coarse();
    if (!h.is_valid() || static_cast<std::size_t>(h.idx()) >= coarse.n_halfedges())
        throw InvalidInput("corner_angle: not a halfedge of the coarse mesh");
    const VertexHandle v = coarse.from_vertex_handle(h);
    return ccw_angle(detail::start_direction(g, h), detail::start_direction(g, coarse.ccw_rotated_halfedge_handle(h)),
                     cone_of(g, v));
}

std::array<double, 3> corner_angles(const GeodesicTriangulation& g, OpenMesh::FaceHandle f) {
    const CoarseMesh& coarse = g.coarse();
    if (!f.is_valid() || static_cast<std::size_t>(f.idx()) >= coarse.n_faces())
        throw InvalidInput("corner_angles: not a face of the coarse mesh");
    std::array<double, 3> angles{};
    std::size_t i = 0;
    for (HalfedgeHandle h : coarse.fh_range(f)) {
        if (i == 3) throw InvalidInput("corner_angles: coarse face " + std::to_string(f.idx()) + " is not a triangle");
        angles[i++] = corner_angle(g, h);
    }
    return angles;
}

const char* to_string(FlipRefusal refusal) {
    switch (refusal) {
    case FlipRefusal::none: return "none";
    case FlipRefusal::not_flippable: return "not flippable";
    case FlipRefusal::no_path: return "no path";
    case FlipRefusal::leaves_region: return "leaves region";
    case FlipRefusal::bad_corner: return "bad corner";
    }
    return "unknown";
}

namespace {

/// The quad of e and its topology refusals; refusal none when the flip is topologically possible.
FlipPlan start_plan(const GeodesicTriangulation& g, EdgeHandle e) {
    const CoarseMesh& coarse = g.coarse();
    if (!e.is_valid() || static_cast<std::size_t>(e.idx()) >= coarse.n_edges() || coarse.status(e).deleted())
        throw InvalidInput("flip: not an edge of the coarse mesh");
    FlipPlan plan;
    plan.edge = e;
    auto refuse = [&plan](FlipRefusal why, std::string what) {
        plan.refusal = why;
        plan.reason = std::move(what);
        return plan;
    };
    const std::string name = "coarse edge " + std::to_string(e.idx());
    const HalfedgeHandle h0 = coarse.halfedge_handle(e, 0), h1 = coarse.halfedge_handle(e, 1);
    if (coarse.is_boundary(e)) return refuse(FlipRefusal::not_flippable, name + " is on a boundary");
    plan.a = coarse.from_vertex_handle(h0);
    plan.b = coarse.to_vertex_handle(h0);
    plan.c = coarse.to_vertex_handle(coarse.next_halfedge_handle(h0));
    plan.d = coarse.to_vertex_handle(coarse.next_halfedge_handle(h1));
    if (!coarse.is_flip_ok(e))
        return refuse(FlipRefusal::not_flippable, name + ": its opposite vertices " + std::to_string(plan.c.idx()) +
                                                      " and " + std::to_string(plan.d.idx()) +
                                                      " are one vertex or already joined");
    return plan;
}

/// Condition 1 (straight as validate() judges it), condition 2 at c and d and condition 3 against the quad's four
/// polylines, for plan.path; fills plan.corners or the refusal.
void check_plan(const GeodesicTriangulation& g, FlipPlan& plan) {
    const CoarseMesh& coarse = g.coarse();
    const Mesh& mesh = g.fine().mesh;
    const std::string name = "coarse edge " + std::to_string(plan.edge.idx());
    auto refuse = [&plan, &name](FlipRefusal why, const std::string& what) {
        plan.refusal = why;
        plan.reason = name + ": " + what;
    };
    // The halfedges around the quad a, d, b, c.
    const HalfedgeHandle ab = coarse.halfedge_handle(plan.edge, 0), ba = coarse.halfedge_handle(plan.edge, 1);
    const HalfedgeHandle bc = coarse.next_halfedge_handle(ab), ca = coarse.next_halfedge_handle(bc);
    const HalfedgeHandle ad = coarse.next_halfedge_handle(ba), db = coarse.next_halfedge_handle(ad);
    const HalfedgeHandle cb = coarse.opposite_halfedge_handle(bc), da = coarse.opposite_halfedge_handle(ad);

    // Condition 1 as validate() judges it: the path is straight within its tolerance (libgeodesic's crossings can
    // miss it on needle triangles of T).
    const std::string bend = detail::straightness_defect(mesh, plan.path);
    if (!bend.empty()) return refuse(FlipRefusal::no_path, "the new geodesic " + bend);

    // Condition 2 at c and d: the new geodesic leaves each strictly inside the old corner there. Counter-clockwise
    // at c: c->a, (c->d), c->b; at d: d->b, (d->c), d->a.
    const std::size_t n = plan.path.size();
    const detail::CornerSplit at_c =
        detail::split_corner(detail::start_direction(g, ca), polar_angle(mesh, plan.path[0], plan.path[1]),
                             detail::start_direction(g, cb), cone_of(g, plan.c));
    const detail::CornerSplit at_d =
        detail::split_corner(detail::start_direction(g, db), polar_angle(mesh, plan.path[n - 1], plan.path[n - 2]),
                             detail::start_direction(g, da), cone_of(g, plan.d));
    if (!at_c.ok)
        return refuse(FlipRefusal::bad_corner, "the new geodesic does not leave coarse vertex " +
                                                   std::to_string(plan.c.idx()) + " inside its old corner");
    if (!at_d.ok)
        return refuse(FlipRefusal::bad_corner, "the new geodesic does not reach coarse vertex " +
                                                   std::to_string(plan.d.idx()) + " inside its old corner");

    // Condition 3 against the four polylines around the quad (for a valid G, no other polyline and no other
    // coarse vertex can be reached without meeting one of them first).
    const std::string meeting = detail::first_meeting(
        mesh, plan.path, {{g.path(ca), 0, "c-a"}, {g.path(cb), 0, "c-b"}, {g.path(da), 1, "d-a"}, {g.path(db), 1, "d-b"}});
    if (!meeting.empty()) return refuse(FlipRefusal::leaves_region, meeting);
    plan.corners = {corner_angle(g, ad) + corner_angle(g, ab), at_d.after, at_c.before,
                    corner_angle(g, bc) + corner_angle(g, ba), at_c.after, at_d.before};
}

/// The shortest path from c to d inside the union of the patches of e's two faces. Leaves plan.path empty and sets
/// the refusal when there is none, or when it touches the region's boundary (then it would pass through a or b, or
/// run along another polyline).
void region_path(const GeodesicTriangulation& g, const Overlay* overlay, FlipPlan& plan) {
    const CoarseMesh& coarse = g.coarse();
    const std::string name = "coarse edge " + std::to_string(plan.edge.idx());
    auto refuse = [&plan, &name](FlipRefusal why, const std::string& what) {
        plan.refusal = why;
        plan.reason = name + ": inside the two patches, " + what;
        plan.path.clear();
    };
    const int f0 = coarse.face_handle(coarse.halfedge_handle(plan.edge, 0)).idx();
    const int f1 = coarse.face_handle(coarse.halfedge_handle(plan.edge, 1)).idx();
    PatchRegion::Path found;
    try {
        const PatchRegion region = overlay ? PatchRegion(g, *overlay, {f0, f1}) : PatchRegion(g, {f0, f1});
        found = region.shortest_path(g.location(plan.c), g.location(plan.d));
    } catch (const InvalidInput& e) {
        return refuse(FlipRefusal::leaves_region, e.what());
    }
    if (found.polyline.empty())
        return refuse(found.touches_boundary ? FlipRefusal::leaves_region : FlipRefusal::no_path, found.failure);
    plan.path = std::move(found.polyline);
    plan.length = geodesic::path_length(g.fine().mesh, plan.path);
    plan.in_region = true;
}

/// plan_flip_in_region(), with the patches cut out of `overlay`, or of T alone when it is null.
FlipPlan plan_in_region(const GeodesicTriangulation& g, EdgeHandle e, const Overlay* overlay) {
    FlipPlan plan = start_plan(g, e);
    if (!plan.accepted()) return plan;
    region_path(g, overlay, plan);
    if (plan.accepted()) check_plan(g, plan);
    return plan;
}

}  // namespace

FlipPlan plan_flip(const GeodesicTriangulation& g, EdgeHandle e, const FlipOptions& options) {
    return plan_flip(g, e, options, Workspace{});
}

FlipPlan plan_flip(const GeodesicTriangulation& g, EdgeHandle e, const FlipOptions& options,
                   const Workspace& workspace) {
    const Mesh& mesh = g.fine().mesh;
    FlipPlan plan = start_plan(g, e);
    if (!plan.accepted()) return plan;
    const std::string name = "coarse edge " + std::to_string(e.idx());
    std::unique_ptr<geodesic::ExactGeodesic> own;
    geodesic::ExactGeodesic* propagation = workspace.propagation;
    if (!propagation) {
        own = std::make_unique<geodesic::ExactGeodesic>(mesh);
        propagation = own.get();
    }
    const SurfacePoint& from = g.location(plan.c);
    const SurfacePoint& to = g.location(plan.d);
    if (std::optional<Polyline> kept = workspace.paths ? workspace.paths->find(from, to) : std::nullopt) {
        plan.path = std::move(*kept);
    } else {
        geodesic::PropagationOptions propagation_options;
        propagation_options.stop_points = {to};
        propagation_options.goal_directed = true;
        propagation->propagate({from}, propagation_options);
        plan.path = propagation->shortest_path(to);
        if (workspace.paths) workspace.paths->keep(from, to, plan.path);
    }
    if (plan.path.size() < 2) {
        plan.refusal = FlipRefusal::no_path;
        plan.reason = name + ": no geodesic from coarse vertex " + std::to_string(plan.c.idx()) + " to coarse vertex " +
                      std::to_string(plan.d.idx());
        return plan;
    }
    plan.length = geodesic::path_length(mesh, plan.path);
    if (!options.check_validity) return plan;
    check_plan(g, plan);
    if (plan.accepted() || !options.region_fallback || plan.refusal == FlipRefusal::no_path) return plan;
    FlipPlan inside = plan_in_region(g, e, workspace.overlay);
    if (inside.accepted()) return inside;
    plan.reason += "; " + inside.reason;
    return plan;
}

FlipPlan plan_flip_in_region(const GeodesicTriangulation& g, EdgeHandle e, const Overlay& overlay) {
    return plan_in_region(g, e, &overlay);
}

FlipPlan plan_flip_in_region(const GeodesicTriangulation& g, EdgeHandle e) { return plan_in_region(g, e, nullptr); }

void apply_flip(GeodesicTriangulation& g, const FlipPlan& plan) {
    if (!plan.accepted()) throw InvalidInput("apply_flip: the flip was refused: " + plan.reason);
    CoarseMesh& coarse = g.coarse();
    const EdgeHandle e = plan.edge;
    if (!e.is_valid() || static_cast<std::size_t>(e.idx()) >= coarse.n_edges())
        throw InvalidInput("apply_flip: not an edge of the coarse mesh");
    const HalfedgeHandle h0 = coarse.halfedge_handle(e, 0);
    if (coarse.from_vertex_handle(h0) != plan.a || coarse.to_vertex_handle(h0) != plan.b || !coarse.is_flip_ok(e))
        throw InvalidInput("apply_flip: the plan does not fit coarse edge " + std::to_string(e.idx()) + " any more");
    coarse.flip(e);
    const HalfedgeHandle cd = coarse.find_halfedge(plan.c, plan.d);
    if (!cd.is_valid() || coarse.edge_handle(cd) != e) throw InvalidInput("apply_flip: OpenMesh's flip went wrong");
    g.set_path(cd, plan.path);
}

FlipPlan flip(GeodesicTriangulation& g, EdgeHandle e, const FlipOptions& options) {
    return flip(g, e, options, Workspace{});
}

FlipPlan flip(GeodesicTriangulation& g, EdgeHandle e, const FlipOptions& options, const Workspace& workspace) {
    FlipPlan plan = plan_flip(g, e, options, workspace);
    if (plan.accepted()) apply_flip(g, plan);
    return plan;
}

}  // namespace geotri

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/flip.h>
#include <geotri/overlay.h>
#include <geotri/tangent_angles.h>

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

// New corners must clear validate()'s 1e-12 rad by a wide margin, so that the geodesics they separate stay apart
// by more than validate()'s meeting tolerance along their first segments too.
constexpr double k_min_new_corner = 1e-9;
// As validate(): points closer than this times the local fine edge length are the same point.
constexpr double k_meet_tolerance = 1e-12;

/// The polar angle, at from_vertex(h)'s location, of h's geodesic.
double start_direction(const GeodesicTriangulation& g, HalfedgeHandle h) {
    const CoarseMesh& coarse = g.coarse();
    const EdgeHandle e = coarse.edge_handle(h);
    const Polyline& line = g.polyline(e);
    if (line.size() < 2)
        throw InvalidInput("coarse edge " + std::to_string(e.idx()) + " has no polyline of two points or more");
    const std::size_t n = line.size();
    if (h == coarse.halfedge_handle(e, 0)) return polar_angle(g.fine().mesh, line[0], line[1]);
    return polar_angle(g.fine().mesh, line[n - 1], line[n - 2]);
}

double cone_of(const GeodesicTriangulation& g, VertexHandle v) { return cone_angle(g.fine().mesh, g.location(v)); }

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

double point_segment_distance(const Eigen::Vector2d& x, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d d = b - a;
    const double dd = d.squaredNorm();
    const double s = dd > 0.0 ? std::clamp((x - a).dot(d) / dd, 0.0, 1.0) : 0.0;
    return (a + s * d - x).norm();
}

double segment_distance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                        const Eigen::Vector2d& b1) {
    const double o1 = cross(a1 - a0, b0 - a0), o2 = cross(a1 - a0, b1 - a0);
    const double o3 = cross(b1 - b0, a0 - b0), o4 = cross(b1 - b0, a1 - b0);
    if (((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0)))
        return 0.0;
    return std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                     point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
}

/// A piece of a polyline inside one fine face, in the frame of the face's first halfedge: a segment, or a single
/// point (a polyline point on a fine vertex, entered in every face around the vertex so that a path that passes
/// near the vertex in any of them is seen).
struct Piece {
    Eigen::Vector2d x0, x1;
    int tag0, tag1;  ///< per end: 0 when it is the polyline's end at coarse vertex c, 1 at d, -1 otherwise
    bool point;
    int polyline;    ///< which of the polylines, for messages
};

/// The fine faces that hold the straight segment from p to q: one, or the two faces of the fine edge they lie on.
std::vector<int> faces_of_segment(const Mesh& mesh, const SurfacePoint& p, const SurfacePoint& q) {
    if (on_common_edge(mesh, p, q)) {
        int a, b;
        if (p.kind == PointKind::edge) {
            a = p.edge_v0;
            b = p.edge_v1;
        } else if (q.kind == PointKind::edge) {
            a = q.edge_v0;
            b = q.edge_v1;
        } else {
            a = p.vertex;
            b = q.vertex;
        }
        std::vector<int> faces;
        for (int h : {mesh.find_halfedge(a, b), mesh.find_halfedge(b, a)})
            if (h >= 0) faces.push_back(Mesh::face_of(h));
        return faces;
    }
    const int f = common_face(mesh, p, q);
    if (f < 0) throw InvalidInput("a polyline has consecutive points on no common fine face");
    return {f};
}

/// Adds the pieces of `line` to `pieces` by fine face. `end_tag`: the tags of the line's first and last point
/// (see Piece).
void add_pieces(const Mesh& mesh, const Polyline& line, std::array<int, 2> end_tag, int id,
                std::map<int, std::vector<Piece>>& pieces) {
    const std::size_t n = line.size();
    auto tag_of = [&](std::size_t i) { return i == 0 ? end_tag[0] : (i + 1 == n ? end_tag[1] : -1); };
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const SurfacePoint& p = line[i];
        const SurfacePoint& q = line[i + 1];
        for (int f : faces_of_segment(mesh, p, q))
            pieces[f].push_back({halfedge_coordinates(mesh, 3 * f, p), halfedge_coordinates(mesh, 3 * f, q),
                                 tag_of(i), tag_of(i + 1), false, id});
    }
    for (std::size_t i = 0; i < n; ++i) {
        const SurfacePoint& p = line[i];
        if (p.kind != PointKind::vertex) continue;
        for (int h : mesh.outgoing_halfedges(p.vertex)) {
            const int f = Mesh::face_of(h);
            const Eigen::Vector2d x = halfedge_coordinates(mesh, 3 * f, p);
            pieces[f].push_back({x, x, tag_of(i), tag_of(i), true, id});
        }
    }
}

/// Whether two pieces in one face meet other than at a common end c or d.
bool pieces_meet(const Piece& s, const Piece& r, double tolerance) {
    for (int i = 0; i < 2; ++i) {
        const int tag = i == 0 ? s.tag0 : s.tag1;
        if (tag < 0) continue;
        int j = -1;
        if (r.tag0 == tag) j = 0;
        else if (r.tag1 == tag) j = 1;
        if (j < 0) continue;
        if (s.point || r.point) return false;
        // Two geodesics leaving one end overlap when the far end of one lies on the other.
        const Eigen::Vector2d& s_far = i == 0 ? s.x1 : s.x0;
        const Eigen::Vector2d& r_far = j == 0 ? r.x1 : r.x0;
        return point_segment_distance(s_far, r.x0, r.x1) <= tolerance ||
               point_segment_distance(r_far, s.x0, s.x1) <= tolerance;
    }
    return segment_distance(s.x0, s.x1, r.x0, r.x1) <= tolerance;
}

}  // namespace

double corner_angle(const GeodesicTriangulation& g, HalfedgeHandle h) {
    const CoarseMesh& coarse = g.coarse();
    if (!h.is_valid() || static_cast<std::size_t>(h.idx()) >= coarse.n_halfedges())
        throw InvalidInput("corner_angle: not a halfedge of the coarse mesh");
    const VertexHandle v = coarse.from_vertex_handle(h);
    return ccw_angle(start_direction(g, h), start_direction(g, coarse.ccw_rotated_halfedge_handle(h)), cone_of(g, v));
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

/// Condition 2 at c and d and condition 3 against the quad's four polylines, for plan.path; fills plan.corners or
/// the refusal.
void check_plan(const GeodesicTriangulation& g, FlipPlan& plan) {
    const CoarseMesh& coarse = g.coarse();
    const Mesh& mesh = g.fine().mesh;
    const EdgeHandle e = plan.edge;
    const HalfedgeHandle h0 = coarse.halfedge_handle(e, 0), h1 = coarse.halfedge_handle(e, 1);
    const std::string name = "coarse edge " + std::to_string(e.idx());
    auto refuse = [&plan](FlipRefusal why, std::string what) {
        plan.refusal = why;
        plan.reason = std::move(what);
    };
    // The halfedges around the quad a, d, b, c.
    const HalfedgeHandle ab = h0, bc = coarse.next_halfedge_handle(h0), ca = coarse.next_halfedge_handle(bc);
    const HalfedgeHandle ba = h1, ad = coarse.next_halfedge_handle(h1), db = coarse.next_halfedge_handle(ad);
    const HalfedgeHandle cb = coarse.opposite_halfedge_handle(bc), da = coarse.opposite_halfedge_handle(ad);

    // Condition 2 at c and d: the new geodesic leaves each strictly inside the old corner there. Counter-clockwise
    // at c: c->a, (c->d), c->b; at d: d->b, (d->c), d->a.
    const std::size_t n = plan.path.size();
    const double theta_c = cone_of(g, plan.c), theta_d = cone_of(g, plan.d);
    const double out_c = polar_angle(mesh, plan.path[0], plan.path[1]);
    const double out_d = polar_angle(mesh, plan.path[n - 1], plan.path[n - 2]);
    const double ca_dir = start_direction(g, ca), cb_dir = start_direction(g, cb);
    const double db_dir = start_direction(g, db), da_dir = start_direction(g, da);
    const double c_before = ccw_angle(ca_dir, out_c, theta_c), c_after = ccw_angle(out_c, cb_dir, theta_c);
    const double d_before = ccw_angle(db_dir, out_d, theta_d), d_after = ccw_angle(out_d, da_dir, theta_d);
    const double c_old = ccw_angle(ca_dir, cb_dir, theta_c), d_old = ccw_angle(db_dir, da_dir, theta_d);
    auto corner_name = [](const char* at, VertexHandle v) {
        return std::string("the new geodesic leaves ") + at + " (coarse vertex " + std::to_string(v.idx()) + ")";
    };
    if (!(c_before < c_old))
        return refuse(FlipRefusal::bad_corner, name + ": " + corner_name("c", plan.c) + " outside the old corner");
    if (!(d_before < d_old))
        return refuse(FlipRefusal::bad_corner, name + ": " + corner_name("d", plan.d) + " outside the old corner");
    if (std::min({c_before, c_after, d_before, d_after}) <= k_min_new_corner)
        return refuse(FlipRefusal::bad_corner, name + ": the new geodesic makes a corner that is not positive");

    // Condition 3 against the four polylines around the quad (for a valid G, no other polyline and no other
    // coarse vertex can be reached without meeting one of them first).
    std::map<int, std::vector<Piece>> around;
    const std::array<HalfedgeHandle, 4> sides = {ca, cb, da, db};  // each from c or d
    for (int i = 0; i < 4; ++i)
        add_pieces(mesh, g.path(sides[static_cast<std::size_t>(i)]), {i < 2 ? 0 : 1, -1}, i, around);
    std::map<int, std::vector<Piece>> fresh;
    add_pieces(mesh, plan.path, {0, 1}, 4, fresh);
    for (const auto& [f, list] : fresh) {
        const auto it = around.find(f);
        if (it == around.end()) continue;
        const double tolerance =
            k_meet_tolerance * std::max({mesh.length(3 * f), mesh.length(3 * f + 1), mesh.length(3 * f + 2)});
        for (const Piece& s : list)
            for (const Piece& r : it->second)
                if (pieces_meet(s, r, tolerance)) {
                    static const char* const side_names[4] = {"c-a", "c-b", "d-a", "d-b"};
                    return refuse(FlipRefusal::leaves_region,
                                  name + ": the new geodesic meets the polyline " + side_names[r.polyline] +
                                      " in fine face " + std::to_string(f));
                }
    }
    plan.corners = {corner_angle(g, ad) + corner_angle(g, ab), d_after, c_before,
                    corner_angle(g, bc) + corner_angle(g, ba), c_after, d_before};
}

/// Barycentric coordinates in fine face f of p, a point of f (a vertex of f, a point of one of its edges, or inside
/// it).
std::array<double, 3> barycentric_in(const Mesh& mesh, int f, const SurfacePoint& p) {
    const std::array<int, 3>& t = mesh.triangle(f);
    std::array<double, 3> b{0.0, 0.0, 0.0};
    auto corner = [&](int v) {
        for (int i = 0; i < 3; ++i)
            if (t[static_cast<std::size_t>(i)] == v) return i;
        throw InvalidInput("a point of the region is not on its fine face");
    };
    switch (p.kind) {
    case PointKind::vertex: b[static_cast<std::size_t>(corner(p.vertex))] = 1.0; break;
    case PointKind::edge:
        b[static_cast<std::size_t>(corner(p.edge_v0))] = 1.0 - p.t;
        b[static_cast<std::size_t>(corner(p.edge_v1))] = p.t;
        break;
    case PointKind::face:
        if (p.face != f) throw InvalidInput("a point of the region is not on its fine face");
        b = p.bary;
        break;
    }
    return b;
}

/// The shortest path from c to d inside the union of the patches of e's two faces: libgeodesic on the sub-mesh of
/// the overlay triangles of those patches. Leaves plan.path empty and sets the refusal when there is none, or when
/// it touches the region's boundary (then it would pass through a or b, or run along another polyline).
void region_path(const GeodesicTriangulation& g, const Overlay& overlay, FlipPlan& plan) {
    const CoarseMesh& coarse = g.coarse();
    const Mesh& mesh = g.fine().mesh;
    const std::string name = "coarse edge " + std::to_string(plan.edge.idx());
    auto refuse = [&plan, &name](FlipRefusal why, const std::string& what) {
        plan.refusal = why;
        plan.reason = name + ": inside the two patches, " + what;
        plan.path.clear();
    };
    const int f0 = coarse.face_handle(coarse.halfedge_handle(plan.edge, 0)).idx();
    const int f1 = coarse.face_handle(coarse.halfedge_handle(plan.edge, 1)).idx();
    for (int f : overlay.bad_patches)
        if (f == f0 || f == f1) return refuse(FlipRefusal::leaves_region, "a patch is not a disk");

    std::vector<int> sub_of(overlay.positions.size(), -1), overlay_of;
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::array<int, 3>> triangles;
    std::vector<int> fine_face;
    for (std::size_t t = 0; t < overlay.triangles.size(); ++t) {
        if (overlay.patch[t] != f0 && overlay.patch[t] != f1) continue;
        std::array<int, 3> tri{};
        for (std::size_t i = 0; i < 3; ++i) {
            const int v = overlay.triangles[t][i];
            if (sub_of[static_cast<std::size_t>(v)] < 0) {
                sub_of[static_cast<std::size_t>(v)] = static_cast<int>(positions.size());
                positions.push_back(overlay.positions[static_cast<std::size_t>(v)]);
                overlay_of.push_back(v);
            }
            tri[i] = sub_of[static_cast<std::size_t>(v)];
        }
        triangles.push_back(tri);
        fine_face.push_back(overlay.fine_face[t]);
    }
    int from = -1, to = -1;
    for (std::size_t v = 0; v < overlay_of.size(); ++v) {
        const SurfacePoint& p = overlay.points[static_cast<std::size_t>(overlay_of[v])];
        if (p == mesh.canonical(g.location(plan.c))) from = static_cast<int>(v);
        if (p == mesh.canonical(g.location(plan.d))) to = static_cast<int>(v);
    }
    if (from < 0 || to < 0) return refuse(FlipRefusal::no_path, "c or d is not a corner of the region");

    std::unique_ptr<Mesh> region;
    try {
        region = std::make_unique<Mesh>(positions, triangles);
    } catch (const Error& e) {
        return refuse(FlipRefusal::no_path, std::string("the region is not a surface: ") + e.what());
    }
    geodesic::ExactGeodesic propagation(*region);
    geodesic::PropagationOptions options;
    options.stop_points = {SurfacePoint::at_vertex(to)};
    propagation.propagate({SurfacePoint::at_vertex(from)}, options);
    const Polyline sub_path = propagation.shortest_path(SurfacePoint::at_vertex(to));
    if (sub_path.size() < 2) return refuse(FlipRefusal::no_path, "there is no path from c to d");

    Polyline path;
    for (std::size_t i = 0; i < sub_path.size(); ++i) {
        const SurfacePoint& q = sub_path[i];
        const bool end = i == 0 || i + 1 == sub_path.size();
        SurfacePoint p;
        if (q.kind == PointKind::vertex) {
            if (!end && region->is_boundary_vertex(q.vertex))
                return refuse(FlipRefusal::leaves_region, "the shortest path touches the region's boundary");
            p = overlay.points[static_cast<std::size_t>(overlay_of[static_cast<std::size_t>(q.vertex)])];
        } else if (q.kind == PointKind::edge) {
            const int h = region->find_halfedge(q.edge_v0, q.edge_v1) >= 0 ? region->find_halfedge(q.edge_v0, q.edge_v1)
                                                                           : region->find_halfedge(q.edge_v1, q.edge_v0);
            if (h < 0) return refuse(FlipRefusal::no_path, "the path is on no edge of the region");
            const int f = fine_face[static_cast<std::size_t>(Mesh::face_of(h))];
            const auto b0 = barycentric_in(mesh, f, overlay.points[static_cast<std::size_t>(overlay_of[static_cast<std::size_t>(q.edge_v0)])]);
            const auto b1 = barycentric_in(mesh, f, overlay.points[static_cast<std::size_t>(overlay_of[static_cast<std::size_t>(q.edge_v1)])]);
            std::array<double, 3> b{};
            for (std::size_t k = 0; k < 3; ++k) b[k] = (1.0 - q.t) * b0[k] + q.t * b1[k];
            p = mesh.canonical(SurfacePoint::in_face(f, b));
            // A point inside a fine face lies on an overlay edge that is not a fine edge: the path is straight
            // through it, and a polyline keeps only the points where it enters or leaves fine faces.
            if (p.kind == PointKind::face) continue;
        } else {
            continue;
        }
        if (!path.empty() && path.back() == p) continue;
        path.push_back(p);
    }
    if (path.size() < 2) return refuse(FlipRefusal::no_path, "the path has fewer than two points");
    plan.path = std::move(path);
    plan.length = geodesic::path_length(mesh, plan.path);
    plan.in_region = true;
}

}  // namespace

FlipPlan plan_flip(const GeodesicTriangulation& g, EdgeHandle e, const FlipOptions& options) {
    const Mesh& mesh = g.fine().mesh;
    FlipPlan plan = start_plan(g, e);
    if (!plan.accepted()) return plan;
    const std::string name = "coarse edge " + std::to_string(e.idx());
    std::unique_ptr<geodesic::ExactGeodesic> own;
    geodesic::ExactGeodesic* propagation = options.propagation;
    if (!propagation) {
        own = std::make_unique<geodesic::ExactGeodesic>(mesh);
        propagation = own.get();
    }
    const SurfacePoint& from = g.location(plan.c);
    const SurfacePoint& to = g.location(plan.d);
    geodesic::PropagationOptions propagation_options;
    propagation_options.stop_points = {to};
    propagation->propagate({from}, propagation_options);
    plan.path = propagation->shortest_path(to);
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
    Overlay built;
    if (!options.overlay) built = build_overlay(g);
    FlipPlan inside = plan_flip_in_region(g, e, options.overlay ? *options.overlay : built);
    if (inside.accepted()) return inside;
    plan.reason += "; " + inside.reason;
    return plan;
}

FlipPlan plan_flip_in_region(const GeodesicTriangulation& g, EdgeHandle e, const Overlay& overlay) {
    FlipPlan plan = start_plan(g, e);
    if (!plan.accepted()) return plan;
    region_path(g, overlay, plan);
    if (plan.accepted()) check_plan(g, plan);
    return plan;
}

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
    FlipPlan plan = plan_flip(g, e, options);
    if (plan.accepted()) apply_flip(g, plan);
    return plan;
}

}  // namespace geotri

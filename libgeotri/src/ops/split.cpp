#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/overlay.h>
#include <geotri/split.h>
#include <geotri/tangent_angles.h>

#include "check/local_checks.h"
#include "core/patch_region.h"
#include "ops/spokes.h"
#include "ops/with_workspace.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace geotri {

using geodesic::Mesh;
using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

namespace {

using detail::Spoke;

/// The arc-length position of `fraction` on `line`: the segment index i and the parameter u in [0, 1] on it.
std::pair<std::size_t, double> locate_along(const Mesh& mesh, const Polyline& line, double fraction) {
    std::vector<double> lengths(line.size() - 1);
    double total = 0.0;
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        lengths[i] = (mesh.point(line[i + 1]) - mesh.point(line[i])).norm();
        total += lengths[i];
    }
    double target = fraction * total;
    for (std::size_t i = 0; i < lengths.size(); ++i) {
        if (target <= lengths[i] || i + 1 == lengths.size())
            return {i, lengths[i] > 0.0 ? std::clamp(target / lengths[i], 0.0, 1.0) : 0.0};
        target -= lengths[i];
    }
    return {0, 0.0};
}

/// The point at parameter u of the straight segment from p to q, two points of one fine face.
SurfacePoint point_on_segment(const Mesh& mesh, const SurfacePoint& p, const SurfacePoint& q, double u) {
    if (u <= 0.0) return mesh.canonical(p);
    if (u >= 1.0) return mesh.canonical(q);
    const int f = common_face(mesh, p, q);
    if (f < 0) throw InvalidInput("a polyline has consecutive points on no common fine face");
    const std::array<double, 3> bp = barycentric_in(mesh, f, p), bq = barycentric_in(mesh, f, q);
    std::array<double, 3> b{};
    for (std::size_t k = 0; k < 3; ++k) b[k] = (1.0 - u) * bp[k] + u * bq[k];
    return mesh.canonical(SurfacePoint::in_face(f, b));
}

/// Does a split that find_spokes() accepted: a new coarse vertex at `at`, joined to the mesh by
/// `split_mesh(vertex)` (OpenMesh's edge or face split), with the polylines of its edges: `paths` (the parts of a
/// split polyline) and the spokes'. Throws when OpenMesh did not join it to a vertex it should.
template <class SplitMesh>
SplitResult connect_new_vertex(GeodesicTriangulation& g, const SurfacePoint& at, SplitMesh split_mesh,
                               std::vector<std::pair<VertexHandle, Polyline>> paths, const std::vector<Spoke>& spokes) {
    const Eigen::Vector3d x = g.fine().mesh.point(at);
    const VertexHandle v = g.coarse().add_vertex(CoarseMesh::Point(x.x(), x.y(), x.z()));
    split_mesh(v);
    g.set_location(v, at);
    SplitResult result;
    for (const Spoke& s : spokes) {
        paths.emplace_back(s.to, s.path);
        result.region_paths += s.in_region;
    }
    for (const auto& [to, path] : paths) {
        const HalfedgeHandle h = g.coarse().find_halfedge(v, to);
        if (!h.is_valid()) throw InvalidInput("split: OpenMesh's split went wrong");
        g.set_path(h, path);
    }
    result.done = true;
    result.vertex = v;
    return result;
}

/// Points of two polylines closer than this times T's size are the same to common_prefix().
constexpr double k_common_prefix_tolerance = 1e-9;

/// How many leading points the polylines p and q have in common (within 1e-9 of T's size: the same geodesic
/// traced by two propagations can differ in the last bits of its edge crossings).
std::size_t common_prefix(const Mesh& mesh, const Polyline& p, const Polyline& q) {
    const double tolerance = k_common_prefix_tolerance * mesh.size();
    std::size_t n = 0;
    while (n < p.size() && n < q.size() && (mesh.point(p[n]) - mesh.point(q[n])).norm() <= tolerance) ++n;
    return n;
}

}  // namespace

SurfacePoint point_along(const GeodesicTriangulation& g, EdgeHandle e, double fraction) {
    if (!e.is_valid() || static_cast<std::size_t>(e.idx()) >= g.coarse().n_edges())
        throw InvalidInput("point_along: not an edge of the coarse mesh");
    if (!(fraction >= 0.0 && fraction <= 1.0)) throw InvalidInput("point_along: the fraction is not in [0, 1]");
    const Polyline& line = g.polyline(e);
    if (line.size() < 2)
        throw InvalidInput("coarse edge " + std::to_string(e.idx()) + " has no polyline of two points or more");
    const auto [i, u] = locate_along(g.fine().mesh, line, fraction);
    return point_on_segment(g.fine().mesh, line[i], line[i + 1], u);
}

namespace {

/// Throws InvalidInput unless e is an edge of G's coarse mesh.
void require_edge(const CoarseMesh& coarse, EdgeHandle e, const char* operation) {
    if (!e.is_valid() || static_cast<std::size_t>(e.idx()) >= coarse.n_edges() || coarse.status(e).deleted())
        throw InvalidInput(std::string(operation) + ": not an edge of the coarse mesh");
}

/// split_edge() at the point at parameter u of segment i of e's polyline.
SplitResult split_edge_on_segment(GeodesicTriangulation& g, EdgeHandle e, std::size_t i, double u,
                                  const SplitOptions& options, const Workspace& workspace) {
    CoarseMesh& coarse = g.coarse();
    const Mesh& mesh = g.fine().mesh;
    SplitResult result;
    const std::string name = "coarse edge " + std::to_string(e.idx());
    if (coarse.is_boundary(e)) {
        result.reason = name + " is on a boundary";
        return result;
    }
    const HalfedgeHandle ab = coarse.halfedge_handle(e, 0), ba = coarse.halfedge_handle(e, 1);
    const VertexHandle a = coarse.from_vertex_handle(ab), b = coarse.to_vertex_handle(ab);
    const HalfedgeHandle bc = coarse.next_halfedge_handle(ab), ca = coarse.next_halfedge_handle(bc);
    const HalfedgeHandle ad = coarse.next_halfedge_handle(ba), db = coarse.next_halfedge_handle(ad);
    const VertexHandle c = coarse.to_vertex_handle(bc), d = coarse.to_vertex_handle(ad);

    // The two parts of the old polyline, from the new vertex m.
    const Polyline line = g.path(ab);
    const SurfacePoint m = point_on_segment(mesh, line[i], line[i + 1], u);
    if (m == line.front() || m == line.back()) {
        result.reason = name + ": the split point is an end of the edge";
        return result;
    }
    Polyline to_a(line.begin(), line.begin() + static_cast<long>(i) + 1);
    if (to_a.back() != m) to_a.push_back(m);
    std::reverse(to_a.begin(), to_a.end());
    Polyline to_b{m};
    to_b.insert(to_b.end(), line.begin() + static_cast<long>(i) + (line[i + 1] == m ? 2 : 1), line.end());

    // m-c runs in the patch of (a, b, c), on the left of a->b: counter-clockwise at m from m->b to m->a, and at c
    // from c->a to c->b. m-d runs in the patch of (b, a, d): at m from m->a to m->b, and at d from d->b to d->a.
    const double towards_a = polar_angle(mesh, to_a[0], to_a[1]), towards_b = polar_angle(mesh, to_b[0], to_b[1]);
    auto spoke = [&](VertexHandle to, HalfedgeHandle side, double wedge_from, double wedge_to, HalfedgeHandle corner_from,
                     HalfedgeHandle corner_to, const char* from_name, const char* to_name) {
        Spoke s;
        s.to = to;
        s.patch = coarse.face_handle(side).idx();
        s.has_wedge = true;
        s.wedge_from = wedge_from;
        s.wedge_to = wedge_to;
        s.corner_from = corner_from;
        s.corner_to = corner_to;
        s.around = {{to_a, 0, "m-a"}, {to_b, 0, "m-b"}, {g.path(corner_from), 1, from_name},
                    {g.path(corner_to), 1, to_name}};
        return s;
    };
    std::vector<Spoke> spokes{
        spoke(c, ab, towards_b, towards_a, ca, coarse.opposite_halfedge_handle(bc), "c-a", "c-b"),
        spoke(d, ba, towards_a, towards_b, db, coarse.opposite_halfedge_handle(ad), "d-b", "d-a")};

    const std::string why = detail::find_spokes(g, m, spokes, options, workspace, options.checked);
    if (!why.empty()) {
        result.reason = name + ": " + why;
        return result;
    }
    return connect_new_vertex(g, m, [&](VertexHandle v) { coarse.split(e, v); }, {{a, to_a}, {b, to_b}}, spokes);
}

}  // namespace

SplitResult split_edge(GeodesicTriangulation& g, EdgeHandle e, double fraction, const SplitOptions& options) {
    return split_edge(g, e, fraction, options, Workspace{});
}

SplitResult split_edge(GeodesicTriangulation& g, EdgeHandle e, double fraction, const SplitOptions& options,
                       const Workspace& workspace) {
    require_edge(g.coarse(), e, "split_edge");
    if (!(fraction > 0.0 && fraction < 1.0)) throw InvalidInput("split_edge: the fraction is not in (0, 1)");
    const auto [i, u] = locate_along(g.fine().mesh, g.polyline(e), fraction);
    return split_edge_on_segment(g, e, i, u, options, workspace);
}

SplitResult split_edge_at_point(GeodesicTriangulation& g, EdgeHandle e, std::size_t index,
                                const SplitOptions& options) {
    return split_edge_at_point(g, e, index, options, Workspace{});
}

SplitResult split_edge_at_point(GeodesicTriangulation& g, EdgeHandle e, std::size_t index,
                                const SplitOptions& options, const Workspace& workspace) {
    require_edge(g.coarse(), e, "split_edge_at_point");
    if (index == 0 || index + 1 >= g.polyline(e).size())
        throw InvalidInput("split_edge_at_point: point " + std::to_string(index) + " is not inside the polyline");
    return split_edge_on_segment(g, e, index, 0.0, options, workspace);
}

SplitResult split_face(GeodesicTriangulation& g, FaceHandle f, const SurfacePoint& p, const SplitOptions& options) {
    return split_face(g, f, p, options, Workspace{});
}

SplitResult split_face(GeodesicTriangulation& g, FaceHandle f, const SurfacePoint& p, const SplitOptions& options,
                       const Workspace& workspace) {
    CoarseMesh& coarse = g.coarse();
    const Mesh& mesh = g.fine().mesh;
    SplitResult result;
    if (!f.is_valid() || static_cast<std::size_t>(f.idx()) >= coarse.n_faces() || coarse.status(f).deleted())
        throw InvalidInput("split_face: not a face of the coarse mesh");
    const std::string name = "coarse face " + std::to_string(f.idx());
    const SurfacePoint point = mesh.canonical(p);

    // For each corner x of f, with y and z the next ones: the geodesic p-x must reach x inside the corner from x->y
    // to x->z, and meet neither f's three polylines (other than at x) nor the other new geodesics (other than at p).
    std::vector<Spoke> spokes;
    std::vector<HalfedgeHandle> sides;  // x->y for each corner x
    for (HalfedgeHandle h : coarse.fh_range(f)) sides.push_back(h);
    for (std::size_t k = 0; k < 3; ++k) {
        const HalfedgeHandle xy = sides[k], zx = sides[(k + 2) % 3], yz = sides[(k + 1) % 3];
        Spoke s;
        s.to = coarse.from_vertex_handle(xy);
        if (same_point(mesh, g.location(s.to), point)) {
            result.reason = name + ": the split point is one of its vertices";
            return result;
        }
        s.patch = f.idx();
        s.corner_from = xy;
        s.corner_to = coarse.opposite_halfedge_handle(zx);
        s.around = {{g.path(xy), 1, "x-y"}, {g.path(s.corner_to), 1, "x-z"}, {g.path(yz), -1, "y-z"}};
        spokes.push_back(std::move(s));
    }
    std::string why = detail::find_spokes(g, point, spokes, options, workspace, true);
    // The three geodesics leave p in the counter-clockwise order of f's corners, and apart from each other.
    if (why.empty()) why = detail::spokes_apart(mesh, point, spokes);
    if (!why.empty()) {
        result.reason = name + ": " + why;
        return result;
    }
    return connect_new_vertex(g, point, [&](VertexHandle v) { coarse.split(f, v); }, {}, spokes);
}

std::vector<Fork> find_forks(const GeodesicTriangulation& g, VertexHandle a) {
    const CoarseMesh& coarse = g.coarse();
    const Mesh& mesh = g.fine().mesh;
    std::vector<HalfedgeHandle> fan;  // counter-clockwise
    for (HalfedgeHandle h : coarse.voh_ccw_range(a)) fan.push_back(h);
    const std::size_t n = fan.size();
    // shared[i]: the points that fan[i] and fan[i + 1] have in common from a (2 or more: a first segment).
    std::vector<std::size_t> shared(n);
    for (std::size_t i = 0; i < n; ++i) shared[i] = common_prefix(mesh, g.path(fan[i]), g.path(fan[(i + 1) % n]));
    const auto apart = std::find_if(shared.begin(), shared.end(), [](std::size_t k) { return k < 2; });
    if (apart == shared.end()) return {};  // the whole fan runs together: no side to split it from
    std::vector<Fork> forks;
    const std::size_t start = static_cast<std::size_t>(apart - shared.begin()) + 1;
    for (std::size_t k = 0; k < n;) {
        const std::size_t i = (start + k) % n;
        std::size_t run = 1, common = std::numeric_limits<std::size_t>::max();
        while (k + run < n && shared[(i + run - 1) % n] >= 2) {
            common = std::min(common, shared[(i + run - 1) % n]);
            ++run;
        }
        if (run >= 2 && run + 2 <= n) forks.push_back({fan[i], static_cast<int>(run), common});
        k += run;
    }
    return forks;
}

SplitResult split_fork(GeodesicTriangulation& g, const Fork& fork, const SplitOptions& options) {
    return split_fork(g, fork, options, Workspace{});
}

SplitResult split_fork(GeodesicTriangulation& g, const Fork& fork, const SplitOptions& options,
                       const Workspace& workspace) {
    CoarseMesh& coarse = g.coarse();
    const VertexHandle a = coarse.from_vertex_handle(fork.first);
    std::vector<HalfedgeHandle> run{fork.first};
    for (int k = 1; k < fork.count; ++k) run.push_back(coarse.opposite_halfedge_handle(coarse.prev_halfedge_handle(run.back())));
    // The edges just before and after the run, clockwise and counter-clockwise: v is joined to their far ends.
    const VertexHandle before = coarse.to_vertex_handle(coarse.next_halfedge_handle(coarse.opposite_halfedge_handle(run.front())));
    const VertexHandle after = coarse.to_vertex_handle(coarse.opposite_halfedge_handle(coarse.prev_halfedge_handle(run.back())));
    SplitResult result;
    const std::string name = "the fork at coarse vertex " + std::to_string(a.idx());
    if (fork.count < 2 || fork.count + 2 > static_cast<int>(coarse.valence(a)) || before == after) {
        result.reason = name + " leaves fewer than two of its vertex's edges outside the run";
        return result;
    }

    if (fork.common < 2) throw InvalidInput("split_fork: not a fork");
    for (HalfedgeHandle h : run)
        if (g.path(h).size() <= fork.common) {
            result.reason = name + ": its point is the far end of the geodesic to coarse vertex " +
                            std::to_string(coarse.to_vertex_handle(h).idx());
            return result;
        }

    // The polylines from the fork's point: back to a along the common part, and on to each end of the run. The
    // run's polylines part at one point within the tolerance of common_prefix(), which one of them may reach as a
    // fine vertex and another as crossings of edges at 1 - 1e-16 (geodesics along a line of vertices of T): the
    // common part is then that of the polyline through the vertex, and the others leave out their points at it.
    const Mesh& mesh = g.fine().mesh;
    Polyline common = g.path(run.front());
    for (HalfedgeHandle h : run) {
        Polyline line = g.path(h);
        if (line[fork.common - 1].kind == geodesic::PointKind::vertex) common = std::move(line);
    }
    common.resize(fork.common);
    const SurfacePoint at = common.back();
    const double tolerance = k_common_prefix_tolerance * mesh.size();
    std::vector<std::pair<VertexHandle, Polyline>> paths{{a, Polyline(common.rbegin(), common.rend())}};
    for (HalfedgeHandle h : run) {
        const Polyline& line = g.path(h);
        auto onward = line.begin() + static_cast<long>(fork.common);
        while (onward + 1 != line.end() && (mesh.point(*onward) - mesh.point(at)).norm() <= tolerance) ++onward;
        Polyline path{at};
        path.insert(path.end(), onward, line.end());
        paths.emplace_back(coarse.to_vertex_handle(h), std::move(path));
    }

    std::vector<Spoke> spokes(2);
    spokes[0].to = before;
    spokes[1].to = after;
    const std::string why = detail::find_spokes(g, at, spokes, options, workspace, false);
    if (!why.empty()) {
        result.reason = name + ": " + why;
        return result;
    }
    return connect_new_vertex(g, at, [&](VertexHandle v) { coarse.vertex_split(v, a, before, after); }, paths, spokes);
}

}  // namespace geotri

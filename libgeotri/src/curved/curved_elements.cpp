#include <geodesic/errors.h>
#include <geotri/curved_elements.h>
#include <geotri/overlay.h>
#include <geotri/split.h>

#include "core/plane_segments.h"
#include "core/thread_count.h"
#include "core/patch_overlay.h"
#include "curved/bernstein_triangle.h"
#include "curved/element_cache.h"
#include "curved/patch_parameterization.h"
#include "curved/sign_bounds.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <exception>
#include <limits>
#include <string>
#include <vector>

namespace geotri {

namespace {

using detail::multi_index_position;

constexpr int k_max_order = 8;

/// The worse of two verdicts: invalid, then undecided, then valid.
Certification worse(Certification a, Certification b) {
    if (a == Certification::invalid || b == Certification::invalid) return Certification::invalid;
    if (a == Certification::undecided || b == Certification::undecided) return Certification::undecided;
    return Certification::valid;
}

/// The inner nodes of every coarse edge: at arc-length fractions k/p of its polyline, k = 1 .. p - 1, from the
/// from-vertex of its first halfedge.
std::vector<std::vector<SurfacePoint>> edge_nodes(const GeodesicTriangulation& g, int order) {
    std::vector<std::vector<SurfacePoint>> nodes(g.coarse().n_edges());
    for (OpenMesh::EdgeHandle e : g.coarse().edges())
        for (int k = 1; k < order; ++k)
            nodes[static_cast<std::size_t>(e.idx())].push_back(point_along(g, e, static_cast<double>(k) / order));
    return nodes;
}

/// The sides of face f from halfedge_handle(f): side s runs from corner s to corner s + 1.
std::array<OpenMesh::HalfedgeHandle, 3> sides_of(const CoarseMesh& coarse, OpenMesh::FaceHandle f) {
    std::array<OpenMesh::HalfedgeHandle, 3> sides;
    int s = 0;
    for (OpenMesh::HalfedgeHandle h : coarse.fh_range(f)) sides[static_cast<std::size_t>(s++)] = h;
    return sides;
}

/// The element of coarse face f, certified: its interior nodes in gmsh's order, their positions, and its certificate.
detail::ElementGeometry make_element(const GeodesicTriangulation& g, const Overlay& overlay, OpenMesh::FaceHandle f,
                                     const std::vector<int>& patch_triangles,
                                     const std::vector<std::vector<SurfacePoint>>& on_edges,
                                     const CurveOptions& options) {
    const CoarseMesh& coarse = g.coarse();
    const geodesic::Mesh& mesh = g.fine().mesh;
    const int p = options.order;
    const std::vector<std::array<int, 3>> indices = detail::multi_indices(p);
    std::vector<SurfacePoint> nodes(indices.size());
    std::vector<Eigen::Vector3d> positions(indices.size());
    std::vector<char> on_boundary(indices.size(), 0);
    auto set = [&](int j, int k, const SurfacePoint& point) {
        nodes[multi_index_position(j, k)] = point;
        positions[multi_index_position(j, k)] = mesh.point(point);
        on_boundary[multi_index_position(j, k)] = 1;
    };

    const std::array<OpenMesh::HalfedgeHandle, 3> sides = sides_of(coarse, f);
    // Corner s is the from-vertex of side s; side s runs from corner s to corner s + 1. Multi-index (i, j, k) is
    // the weights of corners 0, 1, 2 times p.
    for (std::size_t s = 0; s < 3; ++s) {
        const OpenMesh::HalfedgeHandle h = sides[s];
        const std::array<int, 3> corner_index{s == 0 ? p : 0, s == 1 ? p : 0, s == 2 ? p : 0};
        set(corner_index[1], corner_index[2], g.location(coarse.from_vertex_handle(h)));
        const OpenMesh::EdgeHandle e = coarse.edge_handle(h);
        const bool along = coarse.halfedge_handle(e, 0) == h;
        for (int m = 1; m < p; ++m) {
            const int along_edge = along ? m - 1 : p - m - 1;
            // m/p of the way from corner s to corner s + 1.
            std::array<int, 3> index{0, 0, 0};
            index[s] = p - m;
            index[(s + 1) % 3] = m;
            set(index[1], index[2],
                on_edges[static_cast<std::size_t>(e.idx())][static_cast<std::size_t>(along_edge)]);
        }
    }
    const detail::PatchParameterization map(g, overlay, f, patch_triangles);
    for (const std::array<int, 3>& index : indices) {
        if (index[0] == 0 || index[1] == 0 || index[2] == 0) continue;
        const std::optional<detail::PatchParameterization::Preimage> at = map.preimage(detail::node_of(index, p));
        if (!at)
            throw NumericalError("coarse face " + std::to_string(f.idx()) +
                                 ": an interior node has no preimage in its patch's map");
        nodes[multi_index_position(index[1], index[2])] = at->point;
        positions[multi_index_position(index[1], index[2])] = at->position;
    }

    detail::ElementGeometry made;
    ElementCertificate& certificate = made.certificate;
    if (const auto centre = map.preimage(Eigen::Vector2d(1.0 / 3.0, 1.0 / 3.0))) made.centre = centre->point;
    const std::vector<Eigen::Vector3d> x = detail::bernstein_from_lagrange(positions, p);

    const Eigen::Vector3d& x0 = positions[multi_index_position(0, 0)];
    const Eigen::Vector3d plane_normal =
        (positions[multi_index_position(p, 0)] - x0).cross(positions[multi_index_position(0, p)] - x0);
    const detail::SignBounds plane = detail::bound_sign(detail::jacobian_coefficients(x, p, plane_normal), 2 * (p - 1),
                                        options.max_subdivisions);
    certificate.plane = plane.verdict;
    if (plane.verdict == Certification::valid) certificate.quality_lower = plane.min_lower / plane.max_upper;
    if (plane.max_value > 0.0) certificate.quality_upper = std::max(0.0, plane.min_value / plane.max_value);

    // Over each overlay triangle of the patch, x and the patch's map P (linear there) as polynomials of the
    // triangle's own barycentric coordinates: the control points of x - P bound the distance, and the Jacobian of
    // x there has the sign of J with the fine face's normal (the triangle's map is orientation-preserving).
    certificate.surface = Certification::valid;
    certificate.distance = 0.0;
    std::vector<int> folded_faces;
    for (const detail::PatchParameterization::Triangle& t : map.triangles()) {
        const std::vector<Eigen::Vector3d> restricted =
            detail::restrict_to_triangle(x, p, t.reference[0], t.reference[1], t.reference[2]);
        for (std::size_t c = 0; c < indices.size(); ++c) {
            const std::array<int, 3>& index = indices[c];
            const Eigen::Vector3d linear =
                (index[0] * t.positions[0] + index[1] * t.positions[1] + index[2] * t.positions[2]) / p;
            certificate.distance = std::max(certificate.distance, (restricted[c] - linear).norm());
        }
        const double area = detail::cross(t.reference[1] - t.reference[0], t.reference[2] - t.reference[0]);
        if (area == 0.0) continue;  // all three on one side: no part of the element maps there
        if (area < 0.0) {
            certificate.surface = worse(certificate.surface, Certification::undecided);
            continue;
        }
        const std::array<int, 3>& face = mesh.triangle(t.fine_face);
        const Eigen::Vector3d face_normal = (mesh.position(face[1]) - mesh.position(face[0]))
                                                .cross(mesh.position(face[2]) - mesh.position(face[0]));
        if (face_normal.squaredNorm() == 0.0) continue;  // a face of T of zero area has no normal to fold over
        const detail::SignBounds surface = detail::bound_sign(detail::jacobian_coefficients(restricted, p, face_normal), 2 * (p - 1),
                                              options.max_subdivisions);
        certificate.surface = worse(certificate.surface, surface.verdict);
        if (surface.verdict != Certification::valid) folded_faces.push_back(t.fine_face);
    }

    // Where the element folds, refinement puts a vertex of G on a vertex of T there (curve_adaptively()).
    std::sort(folded_faces.begin(), folded_faces.end());
    folded_faces.erase(std::unique(folded_faces.begin(), folded_faces.end()), folded_faces.end());
    made.folded_faces = std::move(folded_faces);
    for (const detail::PatchParameterization::Triangle& t : map.triangles())
        for (int v : t.vertices)
            if (const SurfacePoint& at = overlay.points[static_cast<std::size_t>(v)];
                at.kind == geodesic::PointKind::vertex)
                made.patch_vertices.push_back(at.vertex);
    std::sort(made.patch_vertices.begin(), made.patch_vertices.end());
    made.patch_vertices.erase(std::unique(made.patch_vertices.begin(), made.patch_vertices.end()),
                              made.patch_vertices.end());

    for (const std::array<int, 3>& index : gmsh_node_order(p)) {
        const std::size_t at = multi_index_position(index[1], index[2]);
        if (on_boundary[at]) continue;
        made.interior.push_back(nodes[at]);
        made.interior_positions.push_back(positions[at]);
    }
    return made;
}

}  // namespace

const char* to_string(Certification certification) {
    switch (certification) {
        case Certification::valid: return "valid";
        case Certification::invalid: return "invalid";
        case Certification::undecided: return "undecided";
    }
    return "?";
}

bool CurvedElement::passes(double min_quality, double max_distance) const {
    return certificate.plane == Certification::valid && certificate.surface == Certification::valid &&
           certificate.quality_lower >= min_quality && certificate.distance <= max_distance;
}

std::vector<std::array<int, 3>> gmsh_node_order(int order) {
    if (order < 0) return {};
    if (order == 0) return {{0, 0, 0}};
    std::vector<std::array<int, 3>> nodes{{order, 0, 0}, {0, order, 0}, {0, 0, order}};
    for (int m = 1; m < order; ++m) nodes.push_back({order - m, m, 0});
    for (int m = 1; m < order; ++m) nodes.push_back({0, order - m, m});
    for (int m = 1; m < order; ++m) nodes.push_back({m, 0, order - m});
    for (const std::array<int, 3>& inner : gmsh_node_order(order - 3))
        nodes.push_back({inner[0] + 1, inner[1] + 1, inner[2] + 1});
    return nodes;
}

CurvedMesh curve_elements(const GeodesicTriangulation& g, const CurveOptions& options) {
    detail::ElementCache cache;
    return detail::curve_elements(g, options, cache);
}

namespace detail {

CurvedMesh curve_elements(const GeodesicTriangulation& g, const CurveOptions& options, ElementCache& cache) {
    if (options.order < 1 || options.order > k_max_order)
        throw InvalidInput("curve_elements: the order " + std::to_string(options.order) + " is outside [1, " +
                           std::to_string(k_max_order) + "]");
    if (options.max_subdivisions < 0)
        throw InvalidInput("curve_elements: max_subdivisions is negative");
    CurvedMesh curved;
    curved.order = options.order;
    const geodesic::Mesh& mesh = g.fine().mesh;
    Eigen::Vector3d lo = mesh.position(0), hi = lo;
    for (const Eigen::Vector3d& x : mesh.positions()) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
    }
    curved.diagonal = (hi - lo).norm();

    const CoarseMesh& coarse = g.coarse();
    const auto faces = static_cast<int>(coarse.n_faces());
    // The faces whose element is not in the cache as they are now.
    cache.by_face.resize(static_cast<std::size_t>(faces));
    std::vector<int> todo;
    for (int f = 0; f < faces; ++f) {
        std::optional<CachedElement>& cached = cache.by_face[static_cast<std::size_t>(f)];
        const std::array<OpenMesh::HalfedgeHandle, 3> sides = sides_of(coarse, OpenMesh::FaceHandle(f));
        bool same = cached.has_value();
        for (std::size_t s = 0; s < 3 && same; ++s)
            same = cached->corners[s] == coarse.from_vertex_handle(sides[s]).idx() &&
                   cached->paths[s] == g.path(sides[s]);
        if (same) continue;
        cached = CachedElement{};
        for (std::size_t s = 0; s < 3; ++s) {
            cached->corners[s] = coarse.from_vertex_handle(sides[s]).idx();
            cached->paths[s] = g.path(sides[s]);
        }
        todo.push_back(f);
    }
    // All of T is cut when every face is to be made; the changed faces' patches alone otherwise.
    const Overlay overlay = static_cast<int>(todo.size()) == faces ? build_overlay(g)
                            : todo.empty()                        ? Overlay{}
                                                                  : build_patch_overlay(g, todo);
    const std::vector<std::vector<int>> by_patch = triangles_by_patch(overlay, coarse.n_faces());
    const int p = options.order;
    const std::vector<std::vector<SurfacePoint>> on_edges = edge_nodes(g, p);

    // Each face's failure is kept apart, and the first face's is thrown: the same for any thread count.
    std::vector<std::exception_ptr> failures(todo.size());
    const int threads = team_size(options.threads);
    const auto count = static_cast<int>(todo.size());
#pragma omp parallel for schedule(dynamic) num_threads(threads)
    for (int i = 0; i < count; ++i) {
        const auto f = static_cast<std::size_t>(todo[static_cast<std::size_t>(i)]);
        try {
            cache.by_face[f]->geometry =
                make_element(g, overlay, OpenMesh::FaceHandle(static_cast<int>(f)), by_patch[f], on_edges, options);
        } catch (...) {
            failures[static_cast<std::size_t>(i)] = std::current_exception();
        }
    }
    for (std::size_t i = 0; i < failures.size(); ++i)
        if (failures[i]) {
            cache.by_face[static_cast<std::size_t>(todo[i])].reset();  // not made: to be made again next time
            std::rethrow_exception(failures[i]);
        }

    // The node table: the corners, then the edges' inner nodes, then the interior nodes, face by face.
    for (OpenMesh::VertexHandle v : coarse.vertices()) curved.nodes.push_back(g.location(v));
    std::vector<int> first_edge_node(coarse.n_edges());
    for (OpenMesh::EdgeHandle e : coarse.edges()) {
        first_edge_node[static_cast<std::size_t>(e.idx())] = static_cast<int>(curved.nodes.size());
        for (const SurfacePoint& point : on_edges[static_cast<std::size_t>(e.idx())]) curved.nodes.push_back(point);
    }
    for (const SurfacePoint& point : curved.nodes) curved.positions.push_back(mesh.point(point));
    // Greedy colours of the patches in face order: for a valid G, patches meet where their faces share an edge.
    std::vector<int> colour(coarse.n_faces(), -1);
    for (OpenMesh::FaceHandle f : coarse.faces()) {
        std::vector<char> taken(4, 0);
        for (OpenMesh::FaceHandle n : coarse.ff_range(f))
            if (n.idx() < f.idx()) taken[static_cast<std::size_t>(colour[static_cast<std::size_t>(n.idx())])] = 1;
        int c = 0;
        while (taken[static_cast<std::size_t>(c)]) ++c;
        colour[static_cast<std::size_t>(f.idx())] = c;
    }

    curved.elements.reserve(static_cast<std::size_t>(faces));
    const std::vector<std::array<int, 3>> order = gmsh_node_order(p);
    for (OpenMesh::FaceHandle f : coarse.faces()) {
        const ElementGeometry& made = cache.by_face[static_cast<std::size_t>(f.idx())]->geometry;
        CurvedElement element;
        element.face = f;
        element.certificate = made.certificate;
        const std::array<OpenMesh::HalfedgeHandle, 3> sides = sides_of(coarse, f);
        std::size_t next = 0;
        for (const std::array<int, 3>& index : order) {
            const int corners_on = (index[0] == 0) + (index[1] == 0) + (index[2] == 0);
            if (corners_on == 2) {  // a corner: the one of weight p
                const std::size_t s = index[0] == p ? 0 : index[1] == p ? 1 : 2;
                element.nodes.push_back(coarse.from_vertex_handle(sides[s]).idx());
            } else if (corners_on == 1) {  // on side s, from corner s to corner s + 1, m/p of the way
                const std::size_t s = index[2] == 0 ? 0 : index[0] == 0 ? 1 : 2;
                const int m = index[(s + 1) % 3];
                const OpenMesh::EdgeHandle e = coarse.edge_handle(sides[s]);
                const bool along = coarse.halfedge_handle(e, 0) == sides[s];
                element.nodes.push_back(first_edge_node[static_cast<std::size_t>(e.idx())] +
                                        (along ? m - 1 : p - m - 1));
            } else {
                element.nodes.push_back(static_cast<int>(curved.nodes.size()));
                curved.nodes.push_back(made.interior[next]);
                curved.positions.push_back(made.interior_positions[next++]);
            }
        }
        const SurfacePoint& corner = curved.nodes[static_cast<std::size_t>(element.nodes[0])];
        const int fine_vertex = corner.kind == geodesic::PointKind::vertex ? corner.vertex
                                : corner.kind == geodesic::PointKind::edge ? corner.edge_v0
                                                                           : mesh.triangle(corner.face)[0];
        element.component = g.fine().component[static_cast<std::size_t>(fine_vertex)];
        element.colour = colour[static_cast<std::size_t>(f.idx())];
        curved.elements.push_back(std::move(element));
    }
    return curved;
}

}  // namespace detail

}  // namespace geotri

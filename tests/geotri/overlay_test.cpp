// The overlay: T cut along G's polylines (DESIGN.md §1, condition 4). The oracles do not share the overlay's code:
// directed-edge counts for watertightness, per-fine-face area conservation, the surface points of the cut
// vertices, V - E + F of each patch, closed-form patch areas on the cube, and colours compared across edges.

#include <geodesic/errors.h>
#include <geodesic/exact_geodesic.h>
#include <geotri/decimate.h>
#include <geotri/edge_paths_io.h>
#include <geotri/fine_mesh.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/overlay.h>
#include <geotri/overlay_io.h>
#include <geotri/trace.h>
#include <geotri/untangle_and_flip.h>

#include "core/patch_region.h"

#include <geotri_test/procedural_meshes.h>
#include <geotri_test/shared_data.h>

#include <gtest/gtest.h>

#include "core/patch_location.h"  // libgeotri/src: the patch that holds a point, found by rays

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>

namespace geotri {
namespace {

using geodesic::PointKind;

std::shared_ptr<const FineMesh> make_fine(const test::TriangleMesh& m, const std::string& name) {
    return std::make_shared<FineMesh>(make_fine_mesh(MeshData{m.positions, m.triangles}, name));
}

/// A tetrahedral G on T: the coarse faces oriented outwards (or inwards when `reversed`), every edge traced as the
/// exact shortest path between the locations of its ends.
GeodesicTriangulation tetrahedron(std::shared_ptr<const FineMesh> fine, const std::array<SurfacePoint, 4>& where,
                                  bool reversed = false) {
    CoarseMesh coarse;
    std::vector<OpenMesh::VertexHandle> v;
    std::array<Eigen::Vector3d, 4> x;
    for (int i = 0; i < 4; ++i) {
        x[i] = fine->mesh.point(where[i]);
        v.push_back(coarse.add_vertex(CoarseMesh::Point(x[i].x(), x[i].y(), x[i].z())));
    }
    // (0,1,2) faces outwards when vertex 3 lies behind it.
    const bool flip = (x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0]) > 0.0;
    const int faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    for (const auto& f : faces) {
        if (flip != reversed) coarse.add_face(v[f[0]], v[f[2]], v[f[1]]);
        else coarse.add_face(v[f[0]], v[f[1]], v[f[2]]);
    }
    GeodesicTriangulation g(std::move(fine), std::move(coarse));
    for (int i = 0; i < 4; ++i) g.set_location(v[i], where[i]);
    geodesic::ExactGeodesic geo(g.fine().mesh);
    for (auto e : g.coarse().edges()) {
        const auto h = g.coarse().halfedge_handle(e, 0);
        const SurfacePoint from = g.location(g.coarse().from_vertex_handle(h));
        const SurfacePoint to = g.location(g.coarse().to_vertex_handle(h));
        geo.propagate({from});
        Polyline path = geo.shortest_path(to);
        if (!path.empty() && path.front() != from) std::reverse(path.begin(), path.end());
        g.set_polyline(e, std::move(path));
    }
    return g;
}

/// The fine vertex farthest in direction d.
int extreme_vertex(const geodesic::Mesh& mesh, const Eigen::Vector3d& d) {
    int best = 0;
    for (int v = 1; v < mesh.num_vertices(); ++v)
        if (mesh.position(v).dot(d) > mesh.position(best).dot(d)) best = v;
    return best;
}

/// The fine face whose centroid lies farthest in direction d.
int extreme_face(const geodesic::Mesh& mesh, const Eigen::Vector3d& d) {
    auto centroid = [&](int f) {
        const auto& t = mesh.triangle(f);
        return (mesh.position(t[0]) + mesh.position(t[1]) + mesh.position(t[2])) / 3.0;
    };
    int best = 0;
    for (int f = 1; f < mesh.num_faces(); ++f)
        if (centroid(f).dot(d) > centroid(best).dot(d)) best = f;
    return best;
}

double triangle_area(const Overlay& o, int t) {
    const auto& tri = o.triangles[t];
    return 0.5 * (o.positions[tri[1]] - o.positions[tri[0]]).cross(o.positions[tri[2]] - o.positions[tri[0]]).norm();
}

/// Every directed edge once, with its reverse once: a closed, conforming, consistently oriented triangle mesh.
void expect_watertight(const Overlay& o) {
    std::map<std::pair<int, int>, int> directed;
    for (const auto& t : o.triangles) {
        EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]);
        for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    }
    int bad = 0;
    for (const auto& [e, count] : directed) {
        auto twin = directed.find({e.second, e.first});
        if (count != 1 || twin == directed.end() || twin->second != 1) ++bad;
    }
    EXPECT_EQ(bad, 0) << "directed edges without exactly one twin";
}

/// Each triangle's vertices lie on its fine face (by their surface points), it is oriented like the face, and the
/// triangles of each fine face add up to its area.
void expect_inside_fine_faces(const Overlay& o, const geodesic::Mesh& mesh) {
    ASSERT_EQ(o.fine_face.size(), o.triangles.size());
    ASSERT_EQ(o.points.size(), o.positions.size());
    std::vector<double> area(mesh.num_faces(), 0.0);
    int outside = 0, inverted = 0;
    for (std::size_t t = 0; t < o.triangles.size(); ++t) {
        const int f = o.fine_face[t];
        const auto& ft = mesh.triangle(f);
        auto on_face = [&](int v) { return v == ft[0] || v == ft[1] || v == ft[2]; };
        for (int v : o.triangles[t]) {
            const SurfacePoint& p = o.points[v];
            const bool in = p.kind == PointKind::vertex ? on_face(p.vertex)
                            : p.kind == PointKind::edge ? on_face(p.edge_v0) && on_face(p.edge_v1)
                                                        : p.face == f;
            outside += !in;
        }
        const auto& tri = o.triangles[t];
        const Eigen::Vector3d n = (o.positions[tri[1]] - o.positions[tri[0]]).cross(o.positions[tri[2]] - o.positions[tri[0]]);
        const Eigen::Vector3d nf = (mesh.position(ft[1]) - mesh.position(ft[0])).cross(mesh.position(ft[2]) - mesh.position(ft[0]));
        if (n.dot(nf) < -1e-12 * nf.squaredNorm()) ++inverted;
        area[f] += triangle_area(o, static_cast<int>(t));
    }
    EXPECT_EQ(outside, 0) << "triangle vertices not on their fine face";
    EXPECT_EQ(inverted, 0) << "triangles oriented against their fine face";
    int wrong_area = 0;
    for (int f = 0; f < mesh.num_faces(); ++f)
        if (std::abs(area[f] - mesh.face_area(f)) > 1e-9 * mesh.face_area(f) + 1e-15 * mesh.size() * mesh.size())
            ++wrong_area;
    EXPECT_EQ(wrong_area, 0) << "fine faces whose pieces do not add up to their area";
}

/// The form of DESIGN.md §1 for edge points (edge_v0 < edge_v1), which Mesh::canonical() does not impose.
SurfacePoint edge_sorted(SurfacePoint p) {
    if (p.kind == PointKind::edge && p.edge_v0 > p.edge_v1) {
        std::swap(p.edge_v0, p.edge_v1);
        p.t = 1.0 - p.t;
    }
    return p;
}

/// The overlay of a valid G: one disk per coarse face, areas adding up to T's, colours differing across cuts.
void expect_valid_overlay(const Overlay& o, const GeodesicTriangulation& g) {
    const geodesic::Mesh& mesh = g.fine().mesh;
    expect_watertight(o);
    expect_inside_fine_faces(o, mesh);
    EXPECT_TRUE(o.bad_patches.empty()) << o.bad_patches.size() << " bad patches, first " << o.bad_patches[0];
    EXPECT_TRUE(o.broken_edges.empty());
    EXPECT_EQ(o.unclaimed_regions, 0);
    EXPECT_EQ(o.num_regions, static_cast<int>(g.coarse().n_faces()));
    EXPECT_TRUE(o.valid());

    // Per patch: V - E + F == 1, with V and E counted on the overlay's own vertices and edges.
    const int nf = static_cast<int>(g.coarse().n_faces());
    std::vector<std::set<int>> vertices(nf);
    std::vector<std::set<std::pair<int, int>>> edges(nf);
    std::vector<int> faces(nf, 0);
    std::vector<double> area(nf, 0.0);
    for (std::size_t t = 0; t < o.triangles.size(); ++t) {
        const int p = o.patch[t];
        ASSERT_GE(p, 0);
        ASSERT_LT(p, nf);
        ++faces[p];
        area[p] += triangle_area(o, static_cast<int>(t));
        const auto& tri = o.triangles[t];
        for (int k = 0; k < 3; ++k) {
            vertices[p].insert(tri[k]);
            edges[p].insert({std::min(tri[k], tri[(k + 1) % 3]), std::max(tri[k], tri[(k + 1) % 3])});
        }
    }
    double total = 0.0;
    for (int p = 0; p < nf; ++p) {
        EXPECT_GT(faces[p], 0) << "patch " << p << " is empty";
        EXPECT_EQ(static_cast<int>(vertices[p].size()) - static_cast<int>(edges[p].size()) + faces[p], 1)
            << "patch " << p << " is not a disk";
        EXPECT_NEAR(area[p], o.patch_area[p], 1e-12 * mesh.total_area());
        total += o.patch_area[p];
    }
    EXPECT_NEAR(total, mesh.total_area(), 1e-9 * mesh.total_area());

    // Triangles across an edge in different patches have different colours; same patch, same colour.
    std::map<std::pair<int, int>, int> directed;
    for (std::size_t t = 0; t < o.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) directed[{o.triangles[t][k], o.triangles[t][(k + 1) % 3]}] = static_cast<int>(t);
    int clashes = 0, patch_boundary_edges = 0;
    for (const auto& [e, t] : directed) {
        auto twin = directed.find({e.second, e.first});
        if (twin == directed.end()) continue;
        const int u = twin->second;
        if (o.patch[t] != o.patch[u]) {
            ++patch_boundary_edges;
            clashes += o.colour[t] == o.colour[u];
        } else {
            clashes += o.colour[t] != o.colour[u];
        }
    }
    EXPECT_GT(patch_boundary_edges, 0);
    EXPECT_EQ(clashes, 0);

    // The cut follows every polyline segment that crosses a face: its two ends are joined by an overlay edge.
    std::map<std::string, int> id_of;
    for (std::size_t v = 0; v < o.points.size(); ++v) id_of[geodesic::to_spec(o.points[v])] = static_cast<int>(v);
    int missing = 0;
    for (auto e : g.coarse().edges()) {
        const Polyline& line = g.polyline(e);
        for (std::size_t k = 0; k + 1 < line.size(); ++k) {
            SurfacePoint a = edge_sorted(mesh.canonical(line[k])), b = edge_sorted(mesh.canonical(line[k + 1]));
            auto ia = id_of.find(geodesic::to_spec(a)), ib = id_of.find(geodesic::to_spec(b));
            if (ia == id_of.end() || ib == id_of.end()) {
                ++missing;
                continue;
            }
            if (a.kind == PointKind::vertex && b.kind == PointKind::vertex) continue;  // along a fine edge
            if (a.kind == PointKind::edge && b.kind == PointKind::edge && a.edge_v0 == b.edge_v0 &&
                a.edge_v1 == b.edge_v1)
                continue;
            if (!directed.count({ia->second, ib->second}) && !directed.count({ib->second, ia->second})) ++missing;
        }
    }
    EXPECT_EQ(missing, 0) << "polyline segments that the overlay does not cut along";
}

std::array<SurfacePoint, 4> tetrahedron_vertices(const geodesic::Mesh& mesh) {
    std::array<SurfacePoint, 4> where;
    const Eigen::Vector3d d[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    for (int i = 0; i < 4; ++i) where[i] = SurfacePoint::at_vertex(extreme_vertex(mesh, d[i].normalized()));
    return where;
}

/// The directions of tetrahedron_vertices(), with the vertices off T's vertices: inside two fine faces and on an
/// edge of T.
std::array<SurfacePoint, 4> tetrahedron_off_vertices(const geodesic::Mesh& mesh) {
    const Eigen::Vector3d d[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    std::array<SurfacePoint, 4> where;
    where[0] = SurfacePoint::at_vertex(extreme_vertex(mesh, d[0].normalized()));
    where[1] = SurfacePoint::in_face(extreme_face(mesh, d[1].normalized()), {1.0 / 3, 1.0 / 3, 1.0 / 3});
    const auto& t2 = mesh.triangle(extreme_face(mesh, d[2].normalized()));
    where[2] = SurfacePoint::on_edge(std::min(t2[0], t2[1]), std::max(t2[0], t2[1]), 0.375);
    where[3] = SurfacePoint::in_face(extreme_face(mesh, d[3].normalized()), {0.2, 0.3, 0.5});
    return where;
}

/// Alternate corners of a unit cube mesh: (0,0,0), (1,1,0), (1,0,1), (0,1,1). The tetrahedron's edges are the six
/// face diagonals.
std::array<SurfacePoint, 4> cube_tetrahedron_vertices(const geodesic::Mesh& mesh) {
    std::array<SurfacePoint, 4> where;
    const Eigen::Vector3d corners[4] = {{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}};
    for (int i = 0; i < 4; ++i)
        where[i] = SurfacePoint::at_vertex(extreme_vertex(mesh, corners[i] - Eigen::Vector3d(0.5, 0.5, 0.5)));
    return where;
}

TEST(Overlay, icosphere_tetrahedron_gives_four_disks_of_total_area) {
    auto fine = make_fine(test::icosphere(3), "icosphere");
    GeodesicTriangulation g = tetrahedron(fine, tetrahedron_vertices(fine->mesh));
    const Overlay o = build_overlay(g);
    expect_valid_overlay(o, g);
    EXPECT_GT(o.triangles.size(), static_cast<std::size_t>(fine->mesh.num_faces()));
    EXPECT_GE(o.num_colours, 4);  // four mutually adjacent patches
}

TEST(Overlay, cube_tetrahedron_cuts_through_fine_vertices_and_along_fine_edges) {
    // The tetrahedron of alternate cube corners: its edges are the six face diagonals, which pass through lattice
    // vertices and run along the quads' diagonals wherever a quad is split that way. Each patch holds one other
    // corner of the cube and three half faces: area 1.5 exactly.
    for (bool irregular : {false, true}) {
        auto fine = make_fine(test::cube(4, 1.0, irregular, 7), "cube");
        const auto& mesh = fine->mesh;
        GeodesicTriangulation g = tetrahedron(fine, cube_tetrahedron_vertices(mesh));
        int interior_vertices = 0, along_edges = 0;
        for (auto e : g.coarse().edges()) {
            const Polyline& line = g.polyline(e);
            ASSERT_GE(line.size(), 2u);
            for (std::size_t k = 1; k + 1 < line.size(); ++k) interior_vertices += line[k].kind == PointKind::vertex;
            for (std::size_t k = 0; k + 1 < line.size(); ++k)
                along_edges += line[k].kind == PointKind::vertex && line[k + 1].kind == PointKind::vertex;
        }
        EXPECT_GT(interior_vertices, 0) << "the test must cut through fine vertices";
        if (irregular) {
            EXPECT_GT(along_edges, 0) << "the test must cut along fine edges";
        }
        const Overlay o = build_overlay(g);
        expect_valid_overlay(o, g);
        for (double a : o.patch_area) EXPECT_NEAR(a, 1.5, 1e-12);
    }
}

TEST(Overlay, coarse_vertices_inside_faces_and_on_edges) {
    auto fine = make_fine(test::icosphere(3), "icosphere");
    GeodesicTriangulation g = tetrahedron(fine, tetrahedron_off_vertices(fine->mesh));
    const Overlay o = build_overlay(g);
    expect_valid_overlay(o, g);
    int face_points = 0, edge_points = 0;
    for (const SurfacePoint& p : o.points) face_points += p.kind == PointKind::face, edge_points += p.kind == PointKind::edge;
    EXPECT_EQ(face_points, 2);
    EXPECT_GT(edge_points, 0);
}

TEST(Overlay, coarse_vertices_inside_one_fine_face_on_a_coarse_cube) {
    // A coarse T (the cube with one quad per side): several coarse vertices share one fine face, and a polyline
    // can lie inside a single face.
    auto fine = make_fine(test::cube(1, 1.0), "cube1");
    const auto& mesh = fine->mesh;
    std::array<SurfacePoint, 4> where;
    const int f = extreme_face(mesh, Eigen::Vector3d(0, 0, 1));
    where[0] = SurfacePoint::in_face(f, {0.5, 0.25, 0.25});
    where[1] = SurfacePoint::in_face(f, {0.25, 0.5, 0.25});
    where[2] = SurfacePoint::at_vertex(extreme_vertex(mesh, Eigen::Vector3d(-1, 1, -1)));
    where[3] = SurfacePoint::at_vertex(extreme_vertex(mesh, Eigen::Vector3d(1, -1, -1)));
    GeodesicTriangulation g = tetrahedron(fine, where);
    const Overlay o = build_overlay(g);
    expect_watertight(o);
    expect_inside_fine_faces(o, mesh);
    // Whatever the validity of this G, the pieces cover T exactly once.
    EXPECT_NEAR(o.total_patch_area() + o.unclaimed_area, mesh.total_area(), 1e-9 * mesh.total_area());
    if (o.valid()) expect_valid_overlay(o, g);
}

TEST(Overlay, reversed_orientation_makes_every_patch_bad) {
    auto fine = make_fine(test::icosphere(3), "icosphere");
    GeodesicTriangulation g = tetrahedron(fine, tetrahedron_vertices(fine->mesh), /*reversed=*/true);
    const Overlay o = build_overlay(g);
    expect_watertight(o);
    expect_inside_fine_faces(o, fine->mesh);
    EXPECT_EQ(o.bad_patches, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_FALSE(o.valid());
}

/// Replaces the path of the halfedge from `from` to `to` by the shortest path from `from` to `via`, then on to `to`.
void detour(GeodesicTriangulation& g, const SurfacePoint& from, const SurfacePoint& to, const SurfacePoint& via) {
    CoarseMesh& coarse = g.coarse();
    for (auto h : coarse.halfedges()) {
        if (g.location(coarse.from_vertex_handle(h)) != from || g.location(coarse.to_vertex_handle(h)) != to) continue;
        geodesic::ExactGeodesic geo(g.fine().mesh);
        geo.propagate({via});
        Polyline first = geo.shortest_path(from);
        Polyline second = geo.shortest_path(to);
        ASSERT_FALSE(first.empty());
        ASSERT_FALSE(second.empty());
        if (first.front() != from) std::reverse(first.begin(), first.end());
        if (second.front() != via) std::reverse(second.begin(), second.end());
        first.insert(first.end(), second.begin() + 1, second.end());
        g.set_path(h, first);
        return;
    }
    FAIL() << "no such coarse halfedge";
}

/// The overlay of a G whose patches are not all disks: still a watertight cut inside the fine faces, with the bad
/// patches reported.
void expect_bad_patches_reported(const Overlay& o, const geodesic::Mesh& mesh) {
    expect_watertight(o);
    expect_inside_fine_faces(o, mesh);
    EXPECT_FALSE(o.bad_patches.empty());
    EXPECT_FALSE(o.valid());
}

TEST(Overlay, detour_crossing_other_polylines_inside_faces_is_reported) {
    // The detour of edge 0-1 goes round the far side of the sphere, through the point opposite its midpoint, so it
    // crosses the polylines of the other faces; on a sphere it does so inside fine faces, where the crossing
    // segments cannot both be cut.
    auto fine = make_fine(test::icosphere(3), "icosphere");
    const auto& mesh = fine->mesh;
    const auto where = tetrahedron_vertices(mesh);
    GeodesicTriangulation g = tetrahedron(fine, where);
    ASSERT_TRUE(build_overlay(g).valid());
    const Eigen::Vector3d middle = mesh.point(where[0]) + mesh.point(where[1]);
    detour(g, where[0], where[1], SurfacePoint::at_vertex(extreme_vertex(mesh, -middle.normalized())));
    const Overlay o = build_overlay(g);
    expect_bad_patches_reported(o, mesh);
    EXPECT_FALSE(o.broken_edges.empty()) << "the crossing segments are left out of the cut";
    EXPECT_NEAR(o.total_patch_area() + o.unclaimed_area, mesh.total_area(), 1e-9 * mesh.total_area());
}

TEST(Overlay, detour_crossing_at_cut_vertices_is_reported) {
    // On the cube the detour meets the other diagonals at fine vertices and on fine edges: the cut is complete,
    // but the patches are not disks bounded by their own three polylines.
    auto fine = make_fine(test::cube(4, 1.0, true, 3), "cube");
    const auto& mesh = fine->mesh;
    const std::array<SurfacePoint, 4> where = cube_tetrahedron_vertices(mesh);
    GeodesicTriangulation g = tetrahedron(fine, where);
    ASSERT_TRUE(build_overlay(g).valid());
    // Through the far corner (1,1,1), which lies in the patch of the opposite face.
    detour(g, where[0], where[1], SurfacePoint::at_vertex(extreme_vertex(mesh, Eigen::Vector3d(1, 1, 1))));
    expect_bad_patches_reported(build_overlay(g), mesh);
}

TEST(Overlay, geodesics_that_part_by_a_few_ulps_keep_every_fine_face_whole) {
    // Edge a-c is given a copy of the geodesic of a-b that moves one of its points on a fine edge by an ulp or two,
    // then runs on to c along b-c. From the point before it, two chords of one fine face go to nearly coincident
    // points, which rounding can place against their order along the fine edge: the faces of the cut overlapped
    // (one fine face of cheese's coarsest G was covered 1.33 times), and the sliver between the two chords was
    // clipped into triangles turned the wrong way (edges without a twin). Every pair of coarse edges from one
    // vertex, every point moved, 1 and 2 ulps either way.
    auto fine = make_fine(test::icosphere(3), "icosphere");
    const auto& mesh = fine->mesh;
    const auto where = tetrahedron_vertices(mesh);
    const GeodesicTriangulation valid = tetrahedron(fine, where);
    const CoarseMesh& coarse = valid.coarse();
    auto halfedge = [&](int from, int to) -> OpenMesh::HalfedgeHandle {
        for (auto h : coarse.halfedges())
            if (valid.location(coarse.from_vertex_handle(h)) == where[from] &&
                valid.location(coarse.to_vertex_handle(h)) == where[to])
                return h;
        return OpenMesh::HalfedgeHandle();
    };
    int tried = 0;
    for (int a = 0; a < 4; ++a) {
        for (int b = 0; b < 4; ++b) {
            int c = 0;
            while (c == a || c == b) ++c;
            if (b == a) continue;
            const Polyline along_ab = valid.path(halfedge(a, b)), along_bc = valid.path(halfedge(b, c));
            for (std::size_t i = 1; i + 1 < along_ab.size(); ++i) {
                if (along_ab[i].kind != PointKind::edge) continue;
                for (int ulps : {-2, -1, 1, 2}) {
                    Polyline parted = along_ab;
                    for (int n = 0; n < std::abs(ulps); ++n)
                        parted[i].t = std::nextafter(parted[i].t, ulps > 0 ? 2.0 : -1.0);
                    parted.insert(parted.end(), along_bc.begin() + 1, along_bc.end());
                    GeodesicTriangulation g = valid;
                    g.set_path(halfedge(a, c), parted);
                    SCOPED_TRACE("edges " + std::to_string(a) + "-" + std::to_string(c) + ", " + std::to_string(a) +
                                 "-" + std::to_string(b) + ", point " + std::to_string(i) + ", " +
                                 std::to_string(ulps) + " ulps");
                    const Overlay o = build_overlay(g);
                    expect_watertight(o);
                    expect_inside_fine_faces(o, mesh);
                    ++tried;
                }
            }
        }
    }
    EXPECT_GT(tried, 250);
}

TEST(Overlay, polyline_through_another_coarse_vertex_is_reported) {
    auto fine = make_fine(test::icosphere(3), "icosphere");
    const auto& mesh = fine->mesh;
    const auto where = tetrahedron_vertices(mesh);
    GeodesicTriangulation g = tetrahedron(fine, where);
    CoarseMesh& coarse = g.coarse();
    const auto h = coarse.halfedge_handle(coarse.edge_handle(0), 0);
    const SurfacePoint a = g.location(coarse.from_vertex_handle(h)), b = g.location(coarse.to_vertex_handle(h));
    SurfacePoint c;
    for (const auto& w : where)
        if (w != a && w != b) c = w;
    detour(g, a, b, c);
    expect_bad_patches_reported(build_overlay(g), mesh);
}

TEST(Overlay, empty_polylines_and_missing_locations_are_reported) {
    auto fine = make_fine(test::icosphere(2), "icosphere");
    GeodesicTriangulation g = tetrahedron(fine, tetrahedron_vertices(fine->mesh));
    g.set_polyline(g.coarse().edge_handle(2), {});
    Overlay o = build_overlay(g);
    expect_watertight(o);
    EXPECT_EQ(o.broken_edges, std::vector<int>{2});
    // The two faces of the edge lose their separation: both are bad, and so is nothing else.
    const auto e = g.coarse().edge_handle(2);
    std::vector<int> expected{g.coarse().face_handle(g.coarse().halfedge_handle(e, 0)).idx(),
                              g.coarse().face_handle(g.coarse().halfedge_handle(e, 1)).idx()};
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(o.bad_patches, expected);
    EXPECT_NEAR(o.total_patch_area(), fine->mesh.total_area(), 1e-9 * fine->mesh.total_area());

    // A G with nothing traced and no locations: every face bad, T left whole and unclaimed.
    CoarseMesh coarse = g.coarse();
    GeodesicTriangulation bare(fine, coarse);
    o = build_overlay(bare);
    EXPECT_EQ(o.bad_patches.size(), 4u);
    EXPECT_EQ(o.triangles.size(), static_cast<std::size_t>(fine->mesh.num_faces()));
    EXPECT_EQ(o.unclaimed_regions, 1);
    EXPECT_NEAR(o.unclaimed_area, fine->mesh.total_area(), 1e-9 * fine->mesh.total_area());
}

TEST(Overlay, malformed_points_and_segments_do_not_crash) {
    auto fine = make_fine(test::icosphere(2), "icosphere");
    GeodesicTriangulation g = tetrahedron(fine, tetrahedron_vertices(fine->mesh));
    CoarseMesh& coarse = g.coarse();
    // A polyline that has lost its middle (consecutive points that share no fine face), and one that doubles back
    // on itself.
    Polyline back = g.polyline(coarse.edge_handle(0));
    back.insert(back.end(), back.rbegin() + 1, back.rend());
    back.insert(back.end(), g.polyline(coarse.edge_handle(0)).begin() + 1, g.polyline(coarse.edge_handle(0)).end());
    g.set_polyline(coarse.edge_handle(0), back);
    Polyline jump = g.polyline(coarse.edge_handle(1));
    jump.erase(jump.begin() + 1, jump.end() - 1);
    g.set_polyline(coarse.edge_handle(1), jump);
    const Overlay o = build_overlay(g);
    expect_watertight(o);
    EXPECT_EQ(o.broken_edges, (std::vector<int>{0, 1}));
    EXPECT_FALSE(o.bad_patches.empty());
}

TEST(Overlay, colouring_is_deterministic) {
    auto fine = make_fine(test::icosphere(3), "icosphere");
    GeodesicTriangulation g = tetrahedron(fine, tetrahedron_vertices(fine->mesh));
    const Overlay a = build_overlay(g), b = build_overlay(g);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.patch, b.patch);
    EXPECT_EQ(a.colour, b.colour);
}

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// ---- Patches cut out of T alone (PatchRegion without an overlay) ---------------------------------------------

/// A real mesh, decimated to 320 faces, traced in the decimation's classes and untangled.
GeodesicTriangulation bob_small_320() {
    auto fine =
        std::make_shared<const FineMesh>(load_fine_mesh(std::string(GEOTRI_TEST_DATA) + "/classic/bob_small.ply"));
    DecimateOptions options;
    options.target_faces = 320;
    const DecimateResult decimated = decimate(*fine, options);
    const EdgePaths paths = make_edge_paths(*fine, decimated);
    GeodesicTriangulation g(fine, make_coarse_mesh(decimated.coarse, "bob"));
    TraceOptions trace_options;
    trace_options.edge_paths = &paths;
    trace(g, trace_options);
    untangle_and_flip(g);
    return g;
}

/// Every patch of g, and every patch with each neighbour, cut out of T alone makes the same region mesh, to the
/// bit, as cut out of the overlay of all of g: the same triangles in the same order, so the same propagations.
void expect_patches_alone_as_in_the_overlay(const GeodesicTriangulation& g, const std::string& name) {
    SCOPED_TRACE(name);
    const Overlay whole = build_overlay(g);
    ASSERT_TRUE(whole.valid()) << name << ": the test needs a valid G";
    int regions = 0;
    for (auto f : g.coarse().faces()) {
        std::vector<std::vector<int>> sets{{f.idx()}};
        for (auto neighbour : g.coarse().ff_range(f)) sets.push_back({f.idx(), neighbour.idx()});
        for (const std::vector<int>& faces : sets) {
            const PatchRegion from_whole(g, whole, faces), alone(g, faces);
            const geodesic::Mesh& a = from_whole.mesh();
            const geodesic::Mesh& b = alone.mesh();
            ASSERT_EQ(b.num_vertices(), a.num_vertices()) << "faces " << faces.front() << " (" << faces.size() << ")";
            ASSERT_EQ(b.num_faces(), a.num_faces()) << "faces " << faces.front() << " (" << faces.size() << ")";
            for (int v = 0; v < a.num_vertices(); ++v) ASSERT_EQ(b.position(v), a.position(v));
            for (int t = 0; t < a.num_faces(); ++t) ASSERT_EQ(b.triangle(t), a.triangle(t));
            ++regions;
        }
    }
    EXPECT_EQ(regions, 4 * static_cast<int>(g.coarse().n_faces()));
}

TEST(PatchAlone, regions_are_those_of_the_whole_overlay) {
    {
        auto fine = make_fine(test::icosphere(3), "icosphere");
        expect_patches_alone_as_in_the_overlay(tetrahedron(fine, tetrahedron_vertices(fine->mesh)),
                                               "icosphere tetrahedron");
    }
    for (bool irregular : {false, true}) {  // geodesics through fine vertices and along fine edges
        auto fine = make_fine(test::cube(4, 1.0, irregular, 7), "cube");
        expect_patches_alone_as_in_the_overlay(tetrahedron(fine, cube_tetrahedron_vertices(fine->mesh)),
                                               irregular ? "irregular cube" : "cube");
    }
    {
        auto fine = make_fine(test::icosphere(3), "icosphere");
        expect_patches_alone_as_in_the_overlay(tetrahedron(fine, tetrahedron_off_vertices(fine->mesh)),
                                               "vertices inside fine faces and on an edge");
    }
    expect_patches_alone_as_in_the_overlay(bob_small_320(), "bob_small");
}

TEST(PatchAlone, a_patch_that_holds_another_coarse_vertex_is_refused) {
    // Turned inside out, each patch is the rest of the sphere, with the fourth vertex in it: at a vertex of T, on
    // an edge, or inside a fine face that no cut reaches. (Alone, a patch is cut out of T along its own polylines
    // only: it is not checked against the other polylines, which in a G valid around it, as the callers need, stay
    // outside.)
    auto fine = make_fine(test::icosphere(3), "icosphere");
    for (const auto& where : {tetrahedron_vertices(fine->mesh), tetrahedron_off_vertices(fine->mesh)}) {
        const GeodesicTriangulation reversed = tetrahedron(fine, where, /*reversed=*/true);
        ASSERT_EQ(build_overlay(reversed).bad_patches.size(), 4u);
        for (auto f : reversed.coarse().faces()) {
            try {
                PatchRegion(reversed, {f.idx()});
                ADD_FAILURE() << "coarse face " << f.idx() << " was cut out";
            } catch (const InvalidInput& e) {
                EXPECT_NE(std::string(e.what()).find("lies in it"), std::string::npos) << e.what();
            }
        }
    }
}

TEST(PatchAlone, a_patch_pinched_at_a_vertex_of_t_is_refused) {
    // On the cube's tetrahedron, the path from corner (1,0,1) to (0,0,0) is rerouted through (0.5,0.5,0), a vertex
    // of T on the path from (0,0,0) to (1,1,0): the patch of their face becomes two disks that touch there.
    auto fine = make_fine(test::cube(4, 1.0, false, 7), "cube");
    const auto& mesh = fine->mesh;
    auto vertex_at = [&](const Eigen::Vector3d& x) {
        for (int v = 0; v < mesh.num_vertices(); ++v)
            if ((mesh.position(v) - x).norm() < 1e-12) return SurfacePoint::at_vertex(v);
        throw std::logic_error("no vertex of T there");
    };
    const std::array<SurfacePoint, 4> where = cube_tetrahedron_vertices(mesh);
    GeodesicTriangulation g = tetrahedron(fine, where);
    const SurfacePoint touch = vertex_at({0.5, 0.5, 0});
    const CoarseMesh& coarse = g.coarse();
    OpenMesh::HalfedgeHandle rerouted;  // the halfedge from where[2] to where[0] in the face with where[1]
    for (auto h : coarse.halfedges())
        if (g.location(coarse.from_vertex_handle(h)) == where[2] &&
            g.location(coarse.to_vertex_handle(h)) == where[0] && !coarse.is_boundary(h) &&
            g.location(coarse.to_vertex_handle(coarse.next_halfedge_handle(h))) == where[1])
            rerouted = h;
    ASSERT_TRUE(rerouted.is_valid());
    const Polyline onward = g.path(coarse.next_halfedge_handle(rerouted));
    ASSERT_NE(std::find(onward.begin(), onward.end(), touch), onward.end()) << "the path (0,0,0)-(1,1,0) moved";
    Polyline path;
    const std::array<SurfacePoint, 5> stops{where[2], vertex_at({0.75, 0, 0}), touch, vertex_at({0.25, 0, 0}), where[0]};
    geodesic::ExactGeodesic geo(mesh);
    for (std::size_t k = 0; k + 1 < stops.size(); ++k) {
        geo.propagate({stops[k]});
        Polyline part = geo.shortest_path(stops[k + 1]);
        if (part.front() != stops[k]) std::reverse(part.begin(), part.end());
        path.insert(path.end(), part.begin() + (path.empty() ? 0 : 1), part.end());
    }
    g.set_path(rerouted, path);
    const int face = coarse.face_handle(rerouted).idx();
    const std::vector<int> bad = build_overlay(g).bad_patches;
    ASSERT_NE(std::find(bad.begin(), bad.end(), face), bad.end());
    EXPECT_THROW(PatchRegion(g, {face}), InvalidInput);
}

// ---- The patch that holds a point, found by rays (libgeotri/src/core/patch_location.h) -------------------------------

/// Every fine vertex, a point on every fine edge and one inside every fine face, each located by rays among all
/// patches of g and among a patch's neighbours, against the patches of the whole overlay that hold it (their
/// closures). Returns how many answers the rays left unclear for points inside one patch.
int expect_rays_find_the_patch(const GeodesicTriangulation& g, const std::string& name) {
    SCOPED_TRACE(name);
    const Overlay whole = build_overlay(g);
    EXPECT_TRUE(whole.valid()) << "the test needs a valid G";
    const geodesic::Mesh& mesh = g.fine().mesh;
    const CoarseMesh& coarse = g.coarse();
    std::vector<OpenMesh::FaceHandle> all;
    std::vector<PatchRegion> patches;
    for (auto f : coarse.faces()) {
        all.push_back(f);
        patches.emplace_back(g, whole, std::vector<int>{f.idx()});
    }
    std::vector<SurfacePoint> points;
    for (int v = 0; v < mesh.num_vertices(); ++v) points.push_back(SurfacePoint::at_vertex(v));
    for (int f = 0; f < mesh.num_faces(); ++f) {
        const auto& t = mesh.triangle(f);
        for (int k = 0; k < 3; ++k)  // each edge once, from the face where it runs up
            if (t[k] < t[(k + 1) % 3]) points.push_back(SurfacePoint::on_edge(t[k], t[(k + 1) % 3], 0.37));
        points.push_back(SurfacePoint::in_face(f, {0.2, 0.3, 0.5}));
    }
    int unclear = 0, inside = 0;
    for (const SurfacePoint& p : points) {
        std::vector<OpenMesh::FaceHandle> holders;  // the closures that hold p
        for (std::size_t i = 0; i < patches.size(); ++i)
            if (patches[i].to_region(p)) holders.push_back(all[i]);
        const std::optional<OpenMesh::FaceHandle> found = detail::patch_holding(g, all, p);
        if (!found) {
            unclear += holders.size() == 1;
            continue;
        }
        if (found->is_valid()) {
            ++inside;
            EXPECT_EQ(holders, std::vector<OpenMesh::FaceHandle>{*found}) << geodesic::to_spec(p);
            // Among the neighbours of its patch only: in none of them.
            std::vector<OpenMesh::FaceHandle> neighbours;
            for (auto n : coarse.ff_range(*found)) neighbours.push_back(n);
            const std::optional<OpenMesh::FaceHandle> among = detail::patch_holding(g, neighbours, p);
            if (among) {
                EXPECT_FALSE(among->is_valid()) << geodesic::to_spec(p);
            }
            // Among them and its patch, last: its patch.
            neighbours.push_back(*found);
            const std::optional<OpenMesh::FaceHandle> with_it = detail::patch_holding(g, neighbours, p);
            if (with_it) {
                EXPECT_EQ(*with_it, *found) << geodesic::to_spec(p);
            }
            unclear += !among + !with_it;
        } else {
            EXPECT_GE(holders.size(), 2u) << geodesic::to_spec(p) << " is strictly inside a patch";
        }
    }
    EXPECT_GT(inside, 0);
    return unclear;
}

TEST(PatchHolding, rays_find_the_patch_of_the_whole_overlay) {
    // Geodesics through fine vertices and along fine edges (the cube's); coarse vertices inside fine faces and on
    // an edge (the icosphere's); a traced and untangled G of a real mesh, whose polylines run along fine edges
    // wherever the decimation's classes do. Points on a polyline get no clear answer, or none.
    for (bool irregular : {false, true}) {
        auto fine = make_fine(test::cube(4, 1.0, irregular, 7), "cube");
        EXPECT_EQ(expect_rays_find_the_patch(tetrahedron(fine, cube_tetrahedron_vertices(fine->mesh)),
                                             irregular ? "irregular cube" : "cube"),
                  0);
    }
    auto fine = make_fine(test::icosphere(3), "icosphere");
    EXPECT_EQ(expect_rays_find_the_patch(tetrahedron(fine, tetrahedron_off_vertices(fine->mesh)),
                                         "vertices inside fine faces and on an edge"),
              0);
    EXPECT_EQ(expect_rays_find_the_patch(bob_small_320(), "bob_small"), 0);
}

TEST(OverlayIo, writers_hold_every_triangle_and_exact_coordinates) {
    auto fine = make_fine(test::icosphere(2), "icosphere");
    GeodesicTriangulation g = tetrahedron(fine, tetrahedron_vertices(fine->mesh));
    const Overlay o = build_overlay(g);
    const std::string dir = ::testing::TempDir();
    const std::string nt = std::to_string(o.triangles.size()), nv = std::to_string(o.positions.size());

    write_overlay(dir + "ov.vtu", o);
    const std::string vtu = read_text(dir + "ov.vtu");
    EXPECT_NE(vtu.find("NumberOfCells=\"" + nt + "\""), std::string::npos);
    for (const char* name : {"\"patch\"", "\"fine_face\"", "\"colour\""}) EXPECT_NE(vtu.find(name), std::string::npos);

    write_overlay(dir + "ov.ply", o);
    std::istringstream ply(read_text(dir + "ov.ply"));
    std::string line;
    int vertices = -1, faces = -1;
    while (std::getline(ply, line) && line != "end_header") {
        std::sscanf(line.c_str(), "element vertex %d", &vertices);
        std::sscanf(line.c_str(), "element face %d", &faces);
    }
    ASSERT_EQ(vertices, static_cast<int>(o.positions.size()));
    ASSERT_EQ(faces, static_cast<int>(o.triangles.size()));
    for (int v = 0; v < vertices; ++v) {
        double x, y, z;
        ply >> x >> y >> z;
        ASSERT_EQ(Eigen::Vector3d(x, y, z), o.positions[v]) << "vertex " << v << " does not read back exactly";
    }
    for (int t = 0; t < faces; ++t) {
        int n, a, b, c, r, gr, bl, patch, fine_face;
        ply >> n >> a >> b >> c >> r >> gr >> bl >> patch >> fine_face;
        ASSERT_EQ((std::array<int, 3>{a, b, c}), o.triangles[t]);
        const auto rgb = colour_rgb(o.colour[t]);
        ASSERT_EQ((std::array<int, 3>{r, gr, bl}), (std::array<int, 3>{rgb[0], rgb[1], rgb[2]}));
        ASSERT_EQ(patch, o.patch[t]);
        ASSERT_EQ(fine_face, o.fine_face[t]);
    }

    write_overlay(dir + "ov.obj", o);
    const std::string obj = read_text(dir + "ov.obj");
    for (int p = 0; p < 4; ++p) EXPECT_NE(obj.find("g patch_" + std::to_string(p) + "\n"), std::string::npos);

    for (const char* ext : {".vtp", ".vtk", ".obj"}) {
        const std::string path = dir + "curves" + ext;
        write_curves(path, g);
        const std::string text = read_text(path);
        EXPECT_FALSE(text.empty()) << ext;
        EXPECT_NE(text.find(std::string(ext) == ".obj" ? "edge_5" : "edge"), std::string::npos) << ext;
    }
    EXPECT_THROW(write_overlay(dir + "ov.stl", o), InvalidInput);
    EXPECT_THROW(write_curves(dir + "c.ply", g), InvalidInput);
    EXPECT_THROW(write_overlay(dir + "no/such/folder/ov.vtu", o), IOError);
}

/// Decimate, trace and overlay a real mesh; the overlay is checked whether or not this G is valid.
void overlay_real_mesh(const std::string& relative_path, std::size_t faces, bool print_time) {
    if (test::shared_data_dir().empty())
        GTEST_SKIP() << "shared meshes not found at " << test::configured_shared_data_dir();
    const test::SharedMesh m = test::shared_mesh(relative_path);
    auto fine = std::make_shared<FineMesh>(load_fine_mesh(m.path));
    DecimateOptions options;
    options.target_faces = faces;
    const DecimateResult d = decimate(*fine, options);
    GeodesicTriangulation g(fine, make_coarse_mesh(d.coarse, "coarse"));
    trace(g);
    const auto start = std::chrono::steady_clock::now();
    const Overlay o = build_overlay(g);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (print_time)
        std::printf("[ overlay  ] %s: %d fine faces, %zu coarse faces, %zu overlay triangles, %d bad patches, %.3f s\n",
                    relative_path.c_str(), fine->mesh.num_faces(), g.coarse().n_faces(), o.triangles.size(),
                    static_cast<int>(o.bad_patches.size()), seconds);
    expect_watertight(o);
    expect_inside_fine_faces(o, fine->mesh);
    const double area = fine->mesh.total_area();
    EXPECT_NEAR(o.total_patch_area() + o.unclaimed_area, area, 1e-9 * area);
    if (o.valid()) expect_valid_overlay(o, g);
}

TEST(OverlayRealMesh, vertebra_320_faces) { overlay_real_mesh("anatomy/lumbar_vertebra_mean_2nd.ply", 320, true); }

TEST(OverlayRealMesh, spine_1232_faces) { overlay_real_mesh("anatomy/lumbar_spine_L2-L5_mean.ply", 1232, true); }

}  // namespace
}  // namespace geotri

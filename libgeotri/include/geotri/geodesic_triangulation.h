#pragma once
// A geodesic triangulation G of a fine mesh T (DESIGN.md §1): a coarse OpenMesh triangle mesh whose vertices carry
// their location on T and whose edges carry their geodesic polyline on T.

#include <geodesic/surface_point.h>
#include <geotri/fine_mesh.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

namespace geotri {

using geodesic::SurfacePoint;
using Polyline = std::vector<SurfacePoint>;

struct CoarseTraits : public OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
    VertexAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
    FaceAttributes(OpenMesh::Attributes::Status);
    HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
};

/// The coarse mesh. Its points are the 3D positions of the vertex locations on T.
using CoarseMesh = OpenMesh::TriMesh_ArrayKernelT<CoarseTraits>;

/// G: the coarse mesh, the location of each coarse vertex on T, and the polyline and length of each coarse edge.
/// Copies are independent (the fine mesh is shared, and so are the polylines, which are never changed in place but
/// replaced): an operation that may be refused can work on a copy, and copying costs no polyline. Assigning to a G,
/// by copy or by move, copies into the coarse mesh that it has, which stays the same object (references to
/// coarse() stay valid), in its storage where both have only the properties that every G has (assign()).
/// Constructing one by move takes the other's coarse mesh without a copy (OpenMesh's meshes have no move operations
/// of their own: moving one copies it); the G moved from may then only be assigned to or destroyed.
class GeodesicTriangulation {
public:
    /// Takes the coarse mesh as it is; locations and polylines start empty (location: vertex -1; polyline: none).
    GeodesicTriangulation(std::shared_ptr<const FineMesh> fine, CoarseMesh coarse);
    GeodesicTriangulation(const GeodesicTriangulation& other);
    GeodesicTriangulation(GeodesicTriangulation&& other) noexcept = default;
    GeodesicTriangulation& operator=(const GeodesicTriangulation& other);
    GeodesicTriangulation& operator=(GeodesicTriangulation&& other);
    ~GeodesicTriangulation();

    const FineMesh& fine() const { return *fine_; }
    const std::shared_ptr<const FineMesh>& shared_fine() const { return fine_; }

    /// Becomes a copy of `other` in the storage that this G has, where it is large enough: a trial G that becomes G
    /// again and again allocates nothing once it has grown, and shares what it shared before (the polylines of the
    /// edges that did not change). Where either has properties that a caller added to coarse(), OpenMesh's whole
    /// copy instead: this G then has exactly other's properties, and handles to those it had may no longer hold.
    void assign(const GeodesicTriangulation& other);
    CoarseMesh& coarse() { return *coarse_; }
    const CoarseMesh& coarse() const { return *coarse_; }

    const SurfacePoint& location(OpenMesh::VertexHandle v) const { return coarse_->property(location_, v); }
    /// Sets the location and moves the coarse point to its 3D position on T.
    void set_location(OpenMesh::VertexHandle v, const SurfacePoint& p);

    /// The polyline of edge e, oriented along its first halfedge (from from_vertex(halfedge(e, 0))); empty when
    /// not traced yet.
    const Polyline& polyline(OpenMesh::EdgeHandle e) const;
    /// The polyline of the halfedge h's edge, oriented from from_vertex(h) to to_vertex(h).
    Polyline path(OpenMesh::HalfedgeHandle h) const;
    /// Sets the polyline of e, oriented along its first halfedge, with every point in its canonical form
    /// (geodesic::Mesh::canonical, which throws InvalidInput for a point not on T), and its length.
    void set_polyline(OpenMesh::EdgeHandle e, Polyline polyline);
    /// Sets the polyline of h's edge from a path oriented along h.
    void set_path(OpenMesh::HalfedgeHandle h, Polyline path);
    double length(OpenMesh::EdgeHandle e) const { return coarse_->property(length_, e); }

private:
    void take_handles(const GeodesicTriangulation& other);  ///< the property handles of other's coarse mesh

    std::shared_ptr<const FineMesh> fine_;
    std::unique_ptr<CoarseMesh> coarse_;  // on the heap, so that moving G moves a pointer
    OpenMesh::VPropHandleT<SurfacePoint> location_;
    OpenMesh::EPropHandleT<std::shared_ptr<const Polyline>> polyline_;  // null: not traced
    OpenMesh::EPropHandleT<double> length_;
    /// Vertices, edges and faces that the coarse mesh's storage has been reserved for (assign()); 0 when unknown.
    std::array<std::size_t, 3> reserved_{};
};

/// The coarse mesh of arrays as read_mesh() gives them, in the same vertex and face order, with the points as given.
/// Throws TopologyError("NAME: problem") unless it is a closed, edge- and vertex-manifold, consistently oriented
/// triangle mesh without isolated vertices; InvalidInput for indices out of range or repeated within a face.
CoarseMesh make_coarse_mesh(const MeshData& data, const std::string& name);

/// G as read_gtri() gives it back after write_gtri(): the same vertices and faces in the same order, the same
/// locations and polylines, and its edges and halfedges numbered anew from the faces. Flips and splits renumber
/// them otherwise, and what follows G's numbering (refine()'s choices) then differs from a G read from its file.
GeodesicTriangulation renumbered_as_read(const GeodesicTriangulation& g);

}  // namespace geotri

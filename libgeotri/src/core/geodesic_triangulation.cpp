// GCC 12 warns inside OpenMesh's headers when a coarse mesh is made here (the layout that every G has).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <geodesic/exact_geodesic.h>
#include <geotri/geodesic_triangulation.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace geotri {

namespace {

// Calls visit(name) with the name of each of the mesh's properties in its place, every kind ("" for an empty
// place, "|" after each kind), until it returns false; returns whether it never did.
template <class Visit>
bool visit_property_names(const CoarseMesh& mesh, Visit visit) {
    auto kind = [&](auto begin, auto end) {
        for (auto p = begin; p != end; ++p)
            if (!visit(*p ? (*p)->name() : std::string())) return false;
        return visit(std::string("|"));
    };
    return kind(mesh.vprops_begin(), mesh.vprops_end()) && kind(mesh.hprops_begin(), mesh.hprops_end()) &&
           kind(mesh.eprops_begin(), mesh.eprops_end()) && kind(mesh.fprops_begin(), mesh.fprops_end()) &&
           kind(mesh.mprops_begin(), mesh.mprops_end());
}

std::vector<std::string> property_names(const CoarseMesh& mesh) {
    std::vector<std::string> names;
    visit_property_names(mesh, [&](const std::string& name) {
        names.push_back(name);
        return true;
    });
    return names;
}

// Whether the mesh's properties are named `names` (property_names()), without building a list.
bool has_property_names(const CoarseMesh& mesh, const std::vector<std::string>& names) {
    std::size_t i = 0;
    const bool all_match =
        visit_property_names(mesh, [&](const std::string& name) { return i < names.size() && names[i++] == name; });
    return all_match && i == names.size();
}

}  // namespace

GeodesicTriangulation::GeodesicTriangulation(std::shared_ptr<const FineMesh> fine, CoarseMesh coarse)
    : fine_(std::move(fine)), coarse_(std::make_unique<CoarseMesh>(std::move(coarse))) {
    coarse_->add_property(location_, "geotri:location");
    coarse_->add_property(polyline_, "geotri:polyline");
    coarse_->add_property(length_, "geotri:length");
    for (auto v : coarse_->vertices()) coarse_->property(location_, v) = SurfacePoint::at_vertex(-1);
    for (auto e : coarse_->edges()) coarse_->property(length_, e) = 0.0;
}

GeodesicTriangulation::GeodesicTriangulation(const GeodesicTriangulation& other)
    : fine_(other.fine_), coarse_(std::make_unique<CoarseMesh>(*other.coarse_)), location_(other.location_),
      polyline_(other.polyline_), length_(other.length_) {}

GeodesicTriangulation& GeodesicTriangulation::operator=(const GeodesicTriangulation& other) {
    assign(other);
    return *this;
}

GeodesicTriangulation& GeodesicTriangulation::operator=(GeodesicTriangulation&& other) {
    // A copy all the same where this G has a coarse mesh: callers hold references to it across assignments.
    if (coarse_) {
        assign(other);
        return *this;
    }
    fine_ = std::move(other.fine_);
    coarse_ = std::move(other.coarse_);
    take_handles(other);
    reserved_ = other.reserved_;
    return *this;
}

GeodesicTriangulation::~GeodesicTriangulation() = default;

void GeodesicTriangulation::assign(const GeodesicTriangulation& other) {
    if (this == &other) return;
    if (!coarse_) {  // moved from: no storage to keep
        *this = GeodesicTriangulation(other);  // move assignment takes the copy's coarse mesh
        return;
    }
    fine_ = other.fine_;
    // Only the properties that every G has (OpenMesh's own and G's) are copied one by one below; where a caller added
    // or removed some, OpenMesh's whole copy.
    static const std::vector<std::string> every_gs =
        property_names(GeodesicTriangulation(nullptr, CoarseMesh()).coarse());
    if (!has_property_names(*coarse_, every_gs) || !has_property_names(*other.coarse_, every_gs)) {
        *coarse_ = *other.coarse_;
        take_handles(other);
        reserved_ = {};  // OpenMesh's copy: what its storage holds is not known here
        return;
    }
    // The connectivity by vector assignment (which keeps a large enough capacity), resizing every property; then
    // the status flags (which OpenMesh's assign_connectivity() leaves as they were), the points and G's own
    // properties the same way: a polyline pointer that is the same is not even counted again.
    CoarseMesh& mesh = *coarse_;
    const CoarseMesh& from = *other.coarse_;
    // Vector assignment keeps the storage only where it is large enough, and reallocates to the exact size where
    // not: a trial copy of a G that grows by a few elements at every step (refinement) reallocated and wrote fresh
    // memory for every array at every copy. The storage is reserved with room to grow.
    const std::array<std::size_t, 3> needed{from.n_vertices(), from.n_edges(), from.n_faces()};
    if (needed[0] > reserved_[0] || needed[1] > reserved_[1] || needed[2] > reserved_[2]) {
        for (std::size_t i = 0; i < 3; ++i) reserved_[i] = std::max(reserved_[i], needed[i] + needed[i] / 4 + 16);
        mesh.reserve(reserved_[0], reserved_[1], reserved_[2]);
    }
    mesh.assign_connectivity(from);
    mesh.property(mesh.vertex_status_pph()) = from.property(from.vertex_status_pph());
    mesh.property(mesh.halfedge_status_pph()) = from.property(from.halfedge_status_pph());
    mesh.property(mesh.edge_status_pph()) = from.property(from.edge_status_pph());
    mesh.property(mesh.face_status_pph()) = from.property(from.face_status_pph());
    mesh.property(mesh.points_pph()) = from.property(from.points_pph());
    mesh.property(location_) = from.property(other.location_);
    mesh.property(polyline_) = from.property(other.polyline_);
    mesh.property(length_) = from.property(other.length_);
}

void GeodesicTriangulation::take_handles(const GeodesicTriangulation& other) {
    location_ = other.location_;
    polyline_ = other.polyline_;
    length_ = other.length_;
}

void GeodesicTriangulation::set_location(OpenMesh::VertexHandle v, const SurfacePoint& p) {
    const SurfacePoint canonical = fine_->mesh.canonical(p);
    coarse_->property(location_, v) = canonical;
    const Eigen::Vector3d x = fine_->mesh.point(canonical);
    coarse_->set_point(v, CoarseMesh::Point(x.x(), x.y(), x.z()));
}

const Polyline& GeodesicTriangulation::polyline(OpenMesh::EdgeHandle e) const {
    static const Polyline none;
    const std::shared_ptr<const Polyline>& shared = coarse_->property(polyline_, e);
    return shared ? *shared : none;
}

Polyline GeodesicTriangulation::path(OpenMesh::HalfedgeHandle h) const {
    Polyline p = polyline(coarse_->edge_handle(h));
    if (h != coarse_->halfedge_handle(coarse_->edge_handle(h), 0)) std::reverse(p.begin(), p.end());
    return p;
}

void GeodesicTriangulation::set_polyline(OpenMesh::EdgeHandle e, Polyline polyline) {
    for (SurfacePoint& p : polyline) p = fine_->mesh.canonical(p);  // one representation per point (DESIGN.md §1)
    coarse_->property(length_, e) = geodesic::path_length(fine_->mesh, polyline);
    coarse_->property(polyline_, e) = std::make_shared<const Polyline>(std::move(polyline));
}

void GeodesicTriangulation::set_path(OpenMesh::HalfedgeHandle h, Polyline path) {
    const OpenMesh::EdgeHandle e = coarse_->edge_handle(h);
    if (h != coarse_->halfedge_handle(e, 0)) std::reverse(path.begin(), path.end());
    set_polyline(e, std::move(path));
}

}  // namespace geotri

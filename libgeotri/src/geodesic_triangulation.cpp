#include <geodesic/exact_geodesic.h>
#include <geotri/geodesic_triangulation.h>

#include <algorithm>
#include <utility>

namespace geotri {

GeodesicTriangulation::GeodesicTriangulation(std::shared_ptr<const FineMesh> fine, CoarseMesh coarse)
    : fine_(std::move(fine)), coarse_(std::move(coarse)) {
    coarse_.add_property(location_, "geotri:location");
    coarse_.add_property(polyline_, "geotri:polyline");
    coarse_.add_property(length_, "geotri:length");
    for (auto v : coarse_.vertices()) coarse_.property(location_, v) = SurfacePoint::at_vertex(-1);
    for (auto e : coarse_.edges()) coarse_.property(length_, e) = 0.0;
}

void GeodesicTriangulation::set_location(OpenMesh::VertexHandle v, const SurfacePoint& p) {
    const SurfacePoint canonical = fine_->mesh.canonical(p);
    coarse_.property(location_, v) = canonical;
    const Eigen::Vector3d x = fine_->mesh.point(canonical);
    coarse_.set_point(v, CoarseMesh::Point(x.x(), x.y(), x.z()));
}

const Polyline& GeodesicTriangulation::polyline(OpenMesh::EdgeHandle e) const {
    static const Polyline none;
    const std::shared_ptr<const Polyline>& shared = coarse_.property(polyline_, e);
    return shared ? *shared : none;
}

Polyline GeodesicTriangulation::path(OpenMesh::HalfedgeHandle h) const {
    Polyline p = polyline(coarse_.edge_handle(h));
    if (h != coarse_.halfedge_handle(coarse_.edge_handle(h), 0)) std::reverse(p.begin(), p.end());
    return p;
}

void GeodesicTriangulation::set_polyline(OpenMesh::EdgeHandle e, Polyline polyline) {
    for (SurfacePoint& p : polyline) p = fine_->mesh.canonical(p);  // one representation per point (DESIGN.md §1)
    coarse_.property(length_, e) = geodesic::path_length(fine_->mesh, polyline);
    coarse_.property(polyline_, e) = std::make_shared<const Polyline>(std::move(polyline));
}

void GeodesicTriangulation::set_path(OpenMesh::HalfedgeHandle h, Polyline path) {
    const OpenMesh::EdgeHandle e = coarse_.edge_handle(h);
    if (h != coarse_.halfedge_handle(e, 0)) std::reverse(path.begin(), path.end());
    set_polyline(e, std::move(path));
}

}  // namespace geotri

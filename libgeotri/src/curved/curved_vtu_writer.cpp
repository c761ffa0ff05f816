#include <geotri/curved_mesh_io.h>

#include "io/atomic_file.h"
#include "io/mesh_io_detail.h"

#include <string>
#include <vector>

namespace geotri {

namespace {

constexpr int k_vtk_lagrange_triangle = 69;
constexpr int k_vtk_bezier_triangle = 76;

int certification_code(Certification c) {
    return c == Certification::valid ? 1 : c == Certification::invalid ? 0 : -1;
}

}  // namespace

void write_vtu(const std::string& path, const CurvedMesh& curved, VtuCells cells) {
    // A Bézier cell of VTK takes its control points in the Lagrange cell's order, so only the points change.
    const std::vector<Eigen::Vector3d> points =
        cells == VtuCells::bezier ? bezier_control_points(curved) : curved.positions;
    const std::string type =
        std::to_string(cells == VtuCells::bezier ? k_vtk_bezier_triangle : k_vtk_lagrange_triangle) + "\n";
    detail::AtomicFile out(path);
    const std::size_t count = curved.elements.size();
    out.write("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
              "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n");
    out.write("<Piece NumberOfPoints=\"" + std::to_string(points.size()) + "\" NumberOfCells=\"" +
              std::to_string(count) + "\">\n");
    out.write("<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    detail::write_point_lines(out, "", points);
    out.write("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for (const CurvedElement& element : curved.elements) {
        for (std::size_t n = 0; n < element.nodes.size(); ++n) {
            if (n > 0) out.write(" ");
            out.write_int(element.nodes[n]);
        }
        out.write("\n");
    }
    out.write("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    long long offset = 0;
    for (const CurvedElement& element : curved.elements) {
        offset += static_cast<long long>(element.nodes.size());
        out.write_int(offset);
        out.write("\n");
    }
    out.write("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for (std::size_t c = 0; c < count; ++c) out.write(type);
    out.write("</DataArray>\n</Cells>\n<CellData Scalars=\"quality\">\n");
    auto int_array = [&](const char* name, auto value) {
        out.write(std::string("<DataArray type=\"Int32\" Name=\"") + name + "\" format=\"ascii\">\n");
        for (const CurvedElement& element : curved.elements) {
            out.write_int(value(element));
            out.write("\n");
        }
        out.write("</DataArray>\n");
    };
    auto double_array = [&](const char* name, auto value) {
        out.write(std::string("<DataArray type=\"Float64\" Name=\"") + name + "\" format=\"ascii\">\n");
        for (const CurvedElement& element : curved.elements) {
            out.write_double(value(element));
            out.write("\n");
        }
        out.write("</DataArray>\n");
    };
    double_array("quality", [](const CurvedElement& e) { return e.certificate.quality_lower; });
    double_array("distance", [&](const CurvedElement& e) { return e.certificate.distance / curved.diagonal; });
    int_array("coarse_face", [](const CurvedElement& e) { return e.face.idx(); });
    int_array("component", [](const CurvedElement& e) { return e.component; });
    int_array("colour", [](const CurvedElement& e) { return e.colour; });
    int_array("valid_plane", [](const CurvedElement& e) { return certification_code(e.certificate.plane); });
    int_array("valid_surface", [](const CurvedElement& e) { return certification_code(e.certificate.surface); });
    out.write("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    out.commit();
}

}  // namespace geotri

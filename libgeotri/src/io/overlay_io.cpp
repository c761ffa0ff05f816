#include "io/atomic_file.h"
#include "io/mesh_io_detail.h"

#include <geodesic/errors.h>
#include <geotri/overlay_io.h>

#include <algorithm>
#include <vector>

namespace geotri {

std::array<unsigned char, 3> colour_rgb(int colour) {
    // Distinct at a glance, and none of them grey, so that unclaimed triangles stand out.
    static constexpr unsigned char palette[][3] = {
        {230, 25, 75},  {60, 180, 75},   {255, 225, 25}, {0, 130, 200},  {245, 130, 48},  {145, 30, 180},
        {70, 240, 240}, {240, 50, 230},  {210, 245, 60}, {250, 190, 212}, {0, 128, 128},  {220, 190, 255},
    };
    constexpr int size = static_cast<int>(sizeof palette / sizeof palette[0]);
    if (colour < 0) return {128, 128, 128};
    const auto& c = palette[colour % size];
    return {c[0], c[1], c[2]};
}

namespace {

void write_int_list(detail::AtomicFile& out, const std::vector<int>& values) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        out.write(i % 16 == 0 ? "\n" : " ");
        out.write_int(values[i]);
    }
    out.write("\n");
}

void write_points_array(detail::AtomicFile& out, const std::vector<Eigen::Vector3d>& points) {
    out.write("<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    detail::write_point_lines(out, "", points);
    out.write("</DataArray>\n</Points>\n");
}

void write_vtu(detail::AtomicFile& out, const Overlay& overlay) {
    const std::size_t nt = overlay.triangles.size();
    out.write("<?xml version=\"1.0\"?>\n");
    out.write("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
              "header_type=\"UInt64\">\n<UnstructuredGrid>\n");
    out.write("<Piece NumberOfPoints=\"" + std::to_string(overlay.positions.size()) + "\" NumberOfCells=\"" +
              std::to_string(nt) + "\">\n");
    write_points_array(out, overlay.positions);
    out.write("<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for (const auto& t : overlay.triangles) {
        out.write_int(t[0]);
        out.write(" ");
        out.write_int(t[1]);
        out.write(" ");
        out.write_int(t[2]);
        out.write("\n");
    }
    out.write("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">");
    std::vector<int> column(nt);
    for (std::size_t i = 0; i < nt; ++i) column[i] = static_cast<int>(3 * (i + 1));
    write_int_list(out, column);
    out.write("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">");
    std::fill(column.begin(), column.end(), 5);  // VTK_TRIANGLE
    write_int_list(out, column);
    out.write("</DataArray>\n</Cells>\n<CellData Scalars=\"patch\">\n");
    const std::pair<const char*, const std::vector<int>*> arrays[] = {
        {"patch", &overlay.patch}, {"fine_face", &overlay.fine_face}, {"colour", &overlay.colour}};
    for (const auto& [name, values] : arrays) {
        out.write(std::string("<DataArray type=\"Int32\" Name=\"") + name + "\" format=\"ascii\">");
        write_int_list(out, *values);
        out.write("</DataArray>\n");
    }
    out.write("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
}

void write_ply(detail::AtomicFile& out, const Overlay& overlay) {
    out.write("ply\nformat ascii 1.0\ncomment geotri overlay: patch is the coarse face, -1 for none\n");
    out.write("element vertex " + std::to_string(overlay.positions.size()) + "\n");
    out.write("property double x\nproperty double y\nproperty double z\n");
    out.write("element face " + std::to_string(overlay.triangles.size()) + "\n");
    out.write("property list uchar int vertex_indices\n");
    out.write("property uchar red\nproperty uchar green\nproperty uchar blue\n");
    out.write("property int patch\nproperty int fine_face\nend_header\n");
    detail::write_point_lines(out, "", overlay.positions);
    for (std::size_t t = 0; t < overlay.triangles.size(); ++t) {
        out.write("3");
        for (int v : overlay.triangles[t]) {
            out.write(" ");
            out.write_int(v);
        }
        for (unsigned char c : colour_rgb(overlay.colour[t])) {
            out.write(" ");
            out.write_int(c);
        }
        out.write(" ");
        out.write_int(overlay.patch[t]);
        out.write(" ");
        out.write_int(overlay.fine_face[t]);
        out.write("\n");
    }
}

void write_obj(detail::AtomicFile& out, const Overlay& overlay) {
    out.write("# geotri overlay: one group per patch (coarse face)\n");
    detail::write_point_lines(out, "v ", overlay.positions);
    std::vector<int> order(overlay.triangles.size());
    for (std::size_t t = 0; t < order.size(); ++t) order[t] = static_cast<int>(t);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return overlay.patch[a] < overlay.patch[b]; });
    int group = -2;
    for (int t : order) {
        if (overlay.patch[t] != group) {
            group = overlay.patch[t];
            out.write(group < 0 ? std::string("g no_patch\n") : "g patch_" + std::to_string(group) + "\n");
        }
        out.write("f");
        for (int v : overlay.triangles[t]) {
            out.write(" ");
            out.write_int(v + 1);
        }
        out.write("\n");
    }
}

/// The polylines' points in 3D, each polyline with its edge id.
struct Curves {
    std::vector<Eigen::Vector3d> points;
    std::vector<std::pair<int, int>> ranges;  // [first, last) into points
    std::vector<int> edges;
};

Curves collect_curves(const GeodesicTriangulation& g) {
    Curves c;
    for (auto e : g.coarse().edges()) {
        const Polyline& line = g.polyline(e);
        if (line.empty()) continue;
        const int first = static_cast<int>(c.points.size());
        for (const SurfacePoint& p : line) c.points.push_back(g.fine().mesh.point(p));
        c.ranges.emplace_back(first, static_cast<int>(c.points.size()));
        c.edges.push_back(e.idx());
    }
    return c;
}

void write_vtp(detail::AtomicFile& out, const Curves& c) {
    out.write("<?xml version=\"1.0\"?>\n");
    out.write("<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
              "<PolyData>\n");
    out.write("<Piece NumberOfPoints=\"" + std::to_string(c.points.size()) + "\" NumberOfLines=\"" +
              std::to_string(c.ranges.size()) + "\">\n");
    write_points_array(out, c.points);
    out.write("<Lines>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">");
    std::vector<int> column(c.points.size());
    for (std::size_t i = 0; i < column.size(); ++i) column[i] = static_cast<int>(i);
    write_int_list(out, column);
    out.write("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">");
    column.clear();
    for (const auto& r : c.ranges) column.push_back(r.second);
    write_int_list(out, column);
    out.write("</DataArray>\n</Lines>\n<CellData Scalars=\"edge\">\n<DataArray type=\"Int32\" Name=\"edge\" "
              "format=\"ascii\">");
    write_int_list(out, c.edges);
    out.write("</DataArray>\n</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n");
}

void write_vtk(detail::AtomicFile& out, const Curves& c) {
    out.write("# vtk DataFile Version 3.0\ngeotri coarse edge polylines\nASCII\nDATASET POLYDATA\n");
    out.write("POINTS " + std::to_string(c.points.size()) + " double\n");
    detail::write_point_lines(out, "", c.points);
    out.write("LINES " + std::to_string(c.ranges.size()) + " " +
              std::to_string(c.points.size() + c.ranges.size()) + "\n");
    for (const auto& [first, last] : c.ranges) {
        out.write_int(last - first);
        for (int i = first; i < last; ++i) {
            out.write(" ");
            out.write_int(i);
        }
        out.write("\n");
    }
    out.write("CELL_DATA " + std::to_string(c.ranges.size()) + "\nSCALARS edge int 1\nLOOKUP_TABLE default\n");
    for (int e : c.edges) {
        out.write_int(e);
        out.write("\n");
    }
}

void write_curves_obj(detail::AtomicFile& out, const Curves& c) {
    out.write("# geotri coarse edge polylines: one object edge_N per coarse edge N\n");
    detail::write_point_lines(out, "v ", c.points);
    for (std::size_t k = 0; k < c.ranges.size(); ++k) {
        out.write("o edge_" + std::to_string(c.edges[k]) + "\nl");
        for (int i = c.ranges[k].first; i < c.ranges[k].second; ++i) {
            out.write(" ");
            out.write_int(i + 1);
        }
        out.write("\n");
    }
}

}  // namespace

void write_overlay(const std::string& path, const Overlay& overlay) {
    const std::string ext = detail::extension_of(path);
    void (*writer)(detail::AtomicFile&, const Overlay&) = nullptr;
    if (ext == ".vtu") writer = &write_vtu;
    else if (ext == ".ply") writer = &write_ply;
    else if (ext == ".obj") writer = &write_obj;
    else throw InvalidInput(path + ": cannot write an overlay as '" + ext + "' (expected .vtu, .ply or .obj)");
    const std::size_t nt = overlay.triangles.size();
    if (overlay.patch.size() != nt || overlay.fine_face.size() != nt || overlay.colour.size() != nt)
        throw InvalidInput(path + ": the overlay's per-triangle arrays do not match its triangles");
    detail::AtomicFile out(path);
    writer(out, overlay);
    out.commit();
}

void write_curves(const std::string& path, const GeodesicTriangulation& g) {
    const std::string ext = detail::extension_of(path);
    void (*writer)(detail::AtomicFile&, const Curves&) = nullptr;
    if (ext == ".vtp") writer = &write_vtp;
    else if (ext == ".vtk") writer = &write_vtk;
    else if (ext == ".obj") writer = &write_curves_obj;
    else throw InvalidInput(path + ": cannot write curves as '" + ext + "' (expected .vtp, .vtk or .obj)");
    const Curves curves = collect_curves(g);
    detail::AtomicFile out(path);
    writer(out, curves);
    out.commit();
}

}  // namespace geotri

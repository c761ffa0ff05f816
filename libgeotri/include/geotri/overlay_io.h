#pragma once
// Writing the overlay and the coarse edges' polylines for viewers (ParaView, MeshLab, Blender).

#include <geotri/geodesic_triangulation.h>
#include <geotri/overlay.h>

#include <array>
#include <string>

namespace geotri {

/// The RGB colour that the writers give a colour index: a fixed palette of clearly distinct colours, repeated;
/// grey for -1 (no patch).
std::array<unsigned char, 3> colour_rgb(int colour);

/// Writes the overlay by extension:
/// - `.vtu`: VTK XML UnstructuredGrid (ASCII), with the cell data arrays `patch`, `fine_face` and `colour`;
/// - `.ply`: ASCII PLY, double coordinates, faces with `red green blue` (from colour_rgb) and the int properties
///   `patch` and `fine_face`;
/// - `.obj`: one group `patch_N` per patch (and `no_patch` for unclaimed triangles), faces in overlay order within
///   each group.
/// Coordinates are written with %.17g, so that they read back exactly. Writes to a temporary file in the same
/// folder and renames it. Throws InvalidInput for an unknown extension, IOError when writing fails.
void write_overlay(const std::string& path, const Overlay& overlay);

/// Writes one polyline per coarse edge with its edge id, by extension: `.vtp` (VTK XML PolyData with the cell data
/// `edge`), `.vtk` (legacy ASCII POLYDATA with the cell data `edge`) or `.obj` (`l` lines, one object `edge_N`
/// each). Edges with an empty polyline are left out. Points of T are written once per polyline; coordinates with
/// %.17g. Atomic like write_overlay. Throws InvalidInput for an unknown extension, IOError when writing fails.
void write_curves(const std::string& path, const GeodesicTriangulation& g);

}  // namespace geotri

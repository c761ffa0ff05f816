#pragma once
// Reading and writing a geodesic triangulation G as a `.gtri` file (DESIGN.md §3; the format is specified in
// docs/gtri-format.md).

#include <geotri/geodesic_triangulation.h>

#include <cstdint>
#include <memory>
#include <string>

namespace geotri {

/// The version that write_gtri() writes and the only one that read_gtri() accepts.
constexpr int k_gtri_version = 1;

/// What a `.gtri` file says about its fine mesh, read without loading anything.
struct GtriHeader {
    int version = 0;
    std::string fine_path;          ///< as written: relative to the file's folder (or absolute)
    std::string resolved_fine_path; ///< fine_path resolved against the file's folder
    std::uint64_t fine_checksum = 0;
    int fine_vertices = 0, fine_faces = 0;
};

/// Writes G to `path`: the coarse faces, every vertex location, and every edge's polyline (an untraced edge is
/// written with no points), each double in its shortest decimal form that reads back as the same double.
/// T is referred to by its path (g.fine().path) relative to the folder of `path`, and by its checksum.
/// Writes to a temporary file in the same folder and renames it, so that a failure leaves nothing behind.
/// Preconditions: g.fine().path names T's file (it must not be empty or hold a line break), and every vertex has
/// a location (after trace()). Throws InvalidInput when they do not hold, IOError when the file cannot be written.
void write_gtri(const std::string& path, const GeodesicTriangulation& g);

/// Reads the first lines of `path` only (version, fine mesh path and checksum).
/// Throws IOError("PATH: line N: problem") for an unreadable or malformed header or an unknown version.
GtriHeader read_gtri_header(const std::string& path);

/// Reads G from `path`. T is loaded from `fine_override` when it is not empty (a path as the caller spells it,
/// relative to the working directory), else from the path that the file holds, relative to the file's folder.
/// Throws IOError("PATH: line N: problem") for an unreadable, truncated or malformed file (wrong version, wrong
/// counts, indices out of range, a surface point that does not parse or does not refer to T, NaN, a coarse mesh
/// that is not a closed manifold); IOError when T cannot be found or read; InvalidInput when T's checksum is not
/// the one the file holds (T changed since G was written); TopologyError when T itself is unusable.
GeodesicTriangulation read_gtri(const std::string& path, const std::string& fine_override = "");

/// Reads G from `path` onto an already loaded T, which must have the checksum that the file holds (the file's own
/// fine mesh path is not used). Throws as read_gtri() above.
GeodesicTriangulation read_gtri(const std::string& path, std::shared_ptr<const FineMesh> fine);

}  // namespace geotri

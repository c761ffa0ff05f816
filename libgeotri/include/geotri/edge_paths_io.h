#pragma once
// Reading and writing the edge paths of a decimation (geotri-decimate --paths, geotri-trace --paths): for every
// coarse edge, the fine vertices that the collapses dragged into it (DecimatedEdge). They tell trace which way
// round each edge goes. The format is specified in docs/gtri-format.md.

#include <geotri/edge_paths.h>

#include <string>

namespace geotri {

/// The version that write_edge_paths() writes and the only one that read_edge_paths() accepts.
constexpr int k_edge_paths_version = 1;

/// Writes to a temporary file in the same folder and renames it. Throws IOError when the file cannot be written.
void write_edge_paths(const std::string& path, const EdgePaths& paths);

/// Reads a file of write_edge_paths(). Throws IOError("PATH: line N: problem") for a file that cannot be read, is
/// truncated or malformed: a wrong version, negative or out-of-range indices, edges out of order or repeated.
EdgePaths read_edge_paths(const std::string& path);

}  // namespace geotri

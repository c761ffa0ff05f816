#pragma once
// What each coarse edge of a decimation is on T: the fine edges that the collapses dragged into it. They tell
// trace() which way round each edge goes.

#include <cstdint>
#include <string>
#include <vector>

namespace geotri {

/// An edge of the coarse mesh and what the collapses made of it on T: the fine edges that were dragged into it.
/// A geodesic of the edge keeps the decimated triangulation when it is homotopic to this path on T with the coarse
/// vertices taken out (geodesic::straighten_path); the shortest geodesic between the ends need not be.
struct DecimatedEdge {
    int a = -1, b = -1;          ///< coarse vertices, a < b
    std::vector<int> fine_path;  ///< fine vertices from fine_vertex[a] to fine_vertex[b], each next to the next on T
};

struct EdgePaths {
    std::string name;                ///< the file it was read from, for messages
    std::uint64_t fine_checksum = 0; ///< of T (FineMesh::checksum)
    int fine_vertices = 0;           ///< of T
    int coarse_vertices = 0;
    std::vector<DecimatedEdge> edges;  ///< sorted by (a, b), a < b
};

}  // namespace geotri

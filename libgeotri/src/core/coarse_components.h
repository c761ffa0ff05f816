#pragma once
// The connected components of a coarse mesh and the genus of each: what validation reports and what trace checks
// against the components of T.

#include <geotri/geodesic_triangulation.h>

#include <vector>

namespace geotri::detail {

struct CoarseComponents {
    std::vector<int> of_vertex;  ///< per coarse vertex: its component, numbered in order of first vertex
    std::vector<int> genus;      ///< per component, from V - E + F = 2 - 2 genus (the coarse mesh is closed)
};

CoarseComponents coarse_components(const CoarseMesh& coarse);

}  // namespace geotri::detail

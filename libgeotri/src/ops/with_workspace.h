#pragma once
// The local operations with a workspace (core/workspace.h): the same operations as the public headers declare,
// with the same results, for the library's own loops that run many of them over one G.

#include "core/workspace.h"

#include <geotri/collapse.h>
#include <geotri/flip.h>
#include <geotri/reconnect.h>
#include <geotri/relocate.h>
#include <geotri/split.h>

#include <vector>

namespace geotri {

FlipPlan plan_flip(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e, const FlipOptions& options,
                   const Workspace& workspace);
FlipPlan flip(GeodesicTriangulation& g, OpenMesh::EdgeHandle e, const FlipOptions& options,
              const Workspace& workspace);

SplitResult split_edge(GeodesicTriangulation& g, OpenMesh::EdgeHandle e, double fraction, const SplitOptions& options,
                       const Workspace& workspace);
SplitResult split_edge_at_point(GeodesicTriangulation& g, OpenMesh::EdgeHandle e, std::size_t index,
                                const SplitOptions& options, const Workspace& workspace);
SplitResult split_face(GeodesicTriangulation& g, OpenMesh::FaceHandle f, const SurfacePoint& p,
                       const SplitOptions& options, const Workspace& workspace);
SplitResult split_fork(GeodesicTriangulation& g, const Fork& fork, const SplitOptions& options,
                       const Workspace& workspace);

CollapseResult collapse_edge(GeodesicTriangulation& g, OpenMesh::HalfedgeHandle h, const CollapseOptions& options,
                             const Workspace& workspace);

RelocateResult relocate_vertex(GeodesicTriangulation& g, OpenMesh::VertexHandle v, const SurfacePoint& p,
                               const RelocateOptions& options, const Workspace& workspace);
RelocateResult relocate_vertex_in_star(GeodesicTriangulation& g, OpenMesh::VertexHandle v, const SurfacePoint& p,
                                       const Workspace& workspace);

ReconnectResult reconnect_polygon(GeodesicTriangulation& g, const std::vector<OpenMesh::FaceHandle>& faces,
                                  const ReconnectOptions& options, const Workspace& workspace);
ReconnectResult reconnect_vertex(GeodesicTriangulation& g, OpenMesh::VertexHandle v, const ReconnectOptions& options,
                                 const Workspace& workspace);

}  // namespace geotri

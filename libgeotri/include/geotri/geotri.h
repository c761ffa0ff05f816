#pragma once
// geotri's public API in one include, with its one-call entry point build_geodesic_triangulation(): a closed
// triangle mesh in, a valid geodesic triangulation G out.

#include <geodesic/errors.h>
#include <geotri/build_geodesic_triangulation.h>
#include <geotri/collapse.h>
#include <geotri/curved_elements.h>
#include <geotri/curved_mesh_io.h>
#include <geotri/decimate.h>
#include <geotri/decimate_backoff.h>
#include <geotri/edge_paths.h>
#include <geotri/edge_paths_io.h>
#include <geotri/fine_mesh.h>
#include <geotri/flip.h>
#include <geotri/flip_to_delaunay.h>
#include <geotri/geodesic_triangulation.h>
#include <geotri/gtri_io.h>
#include <geotri/mesh_data.h>
#include <geotri/mesh_io.h>
#include <geotri/overlay.h>
#include <geotri/overlay_io.h>
#include <geotri/reconnect.h>
#include <geotri/refine.h>
#include <geotri/relocate.h>
#include <geotri/split.h>
#include <geotri/straight_geodesic.h>
#include <geotri/tangent_angles.h>
#include <geotri/trace.h>
#include <geotri/untangle.h>
#include <geotri/untangle_and_flip.h>
#include <geotri/validate.h>

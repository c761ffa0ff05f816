#pragma once
// Validity of a geodesic triangulation (DESIGN.md §1, conditions 1-4), and the summary that geotri-check prints.

#include <geotri/geodesic_triangulation.h>

#include <array>
#include <string>
#include <vector>

namespace geotri {

/// One violated condition, with the coarse elements involved (indices of the coarse mesh).
struct Violation {
    int condition = 0;                 ///< 1..4, as numbered in DESIGN.md §1
    std::string what;                  ///< one readable line
    std::vector<int> coarse_vertices;
    std::vector<int> coarse_edges;
    std::vector<int> coarse_faces;
};

struct ValidationReport {
    bool valid = false;
    std::array<int, 4> violation_count{};  ///< per condition (index 0 is condition 1)
    std::vector<Violation> violations;

    // Summary figures (geotri-check --json).
    int vertices = 0, edges = 0, faces = 0, components = 0;
    int genus = 0;                     ///< sum over the coarse components
    double min_corner_angle_deg = 0.0, max_corner_angle_deg = 0.0;
    double min_edge_length = 0.0, mean_edge_length = 0.0, max_edge_length = 0.0;
    double patch_area = 0.0;           ///< sum of the overlay's patch areas (condition 4)
    double fine_area = 0.0;            ///< area of T
    bool overlay_checked = false;      ///< false when ValidationOptions::overlay was off (condition 4 not checked)
};

struct ValidationOptions {
    /// Build the overlay to decide condition 4. Local operations that only need conditions 1-3 turn it off.
    bool overlay = true;
};

/// Checks all four conditions. Never throws for an invalid G (that is what the report is for); throws
/// InvalidInput only when G is malformed (a location or polyline that does not refer to T).
///
/// Tolerances, all relative to the fine mesh so that they do not depend on units:
/// - condition 1: a polyline is straight at an interior point when the point lies within 2e-12·size(T) of the
///   straight line through its neighbours, unfolded on either side (libgeodesic snaps crossings within 1e-12·size
///   of a vertex onto it); the recorded length equals path_length within 1e-12 relative;
/// - condition 2: a corner angle is positive when it exceeds 1e-12 rad;
/// - condition 3: two points closer than 1e-12 times the longest edge of their fine face (or 1e-12 of their
///   fine edge's length) are the same point;
/// - condition 4: the patch areas sum to the area of T within 1e-9 relative.
ValidationReport validate(const GeodesicTriangulation& g, const ValidationOptions& options);
ValidationReport validate(const GeodesicTriangulation& g);

/// Completes `report`, made by validate() of this same G without the overlay, with condition 4: the same report
/// as validate(g) then, without checking conditions 1-3 again. Does nothing when the overlay was checked.
void add_overlay_check(const GeodesicTriangulation& g, ValidationReport& report);

}  // namespace geotri

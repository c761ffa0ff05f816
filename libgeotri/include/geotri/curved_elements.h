#pragma once
// Curved high-order elements on a valid G (DESIGN.md §5): one Lagrange triangle of order p per coarse face, every
// node an exact point of T, each element certified valid and within a proven distance of its patch.

#include <geotri/geodesic_triangulation.h>

#include <Eigen/Core>

#include <array>
#include <limits>
#include <vector>

namespace geotri {

struct CurveOptions {
    int order = 3;             ///< p, in [1, 8]
    int max_subdivisions = 6;  ///< levels of de Casteljau subdivision where the Bernstein bounds do not decide
    /// For the elements, made in parallel; 0: as many as OpenMP likes. The result is the same for any count.
    int threads = 0;
};

/// What the Bernstein bounds of J_n = (x_u × x_v) · n proved over an element.
enum class Certification {
    valid,      ///< J_n > 0 everywhere
    invalid,    ///< J_n <= 0 at a point
    undecided,  ///< neither, within CurveOptions::max_subdivisions
};

/// "valid", "invalid" or "undecided".
const char* to_string(Certification certification);

struct ElementCertificate {
    /// J with the normal of the plane through the element's three corners: what gmsh checks.
    Certification plane = Certification::undecided;
    /// J with the normal of each face of T that the element stands for, over the part of the element that maps to
    /// that face: the element never folds over the surface.
    Certification surface = Certification::undecided;
    /// Bounds of min J / max J over the element, with the plane's normal: quality_lower <= the true ratio <=
    /// quality_upper. quality_lower is 0 unless `plane` is valid.
    double quality_lower = 0.0, quality_upper = 0.0;
    /// A proven upper bound of the two-sided Hausdorff distance between the element and its patch, in the units of
    /// T (divide by CurvedMesh::diagonal for the relative bound).
    double distance = std::numeric_limits<double>::infinity();
};

struct CurvedElement {
    OpenMesh::FaceHandle face;
    /// The (p + 1)(p + 2)/2 nodes, as indices into CurvedMesh::nodes, in gmsh's and VTK's order: corners 0, 1, 2
    /// (the from-vertices of the face's halfedges from halfedge_handle(face)); the inner nodes of edge 0→1 from 0,
    /// of 1→2 from 1, of 2→0 from 2; then the interior nodes, recursively, as a triangle of order p - 3.
    std::vector<int> nodes;
    int component = 0;  ///< the component of T that its patch lies on
    int colour = 0;     ///< the greedy colour of its patch (elements that share an edge differ)
    ElementCertificate certificate;

    /// Whether it passes: certified valid against both normals, quality_lower >= min_quality, and a distance bound
    /// of at most `max_distance` (in the units of T).
    bool passes(double min_quality, double max_distance) const;
};

struct CurvedMesh {
    int order = 0;
    double diagonal = 0.0;  ///< of T's bounding box
    /// Every node once: the corners (G's vertices, in order), then the inner nodes of each edge (in edge order,
    /// from the from-vertex of its first halfedge), then the interior nodes of each element (in face order).
    std::vector<SurfacePoint> nodes;
    std::vector<Eigen::Vector3d> positions;  ///< of the nodes
    std::vector<CurvedElement> elements;     ///< one per coarse face, in face order
};

/// The curved elements of G, certified. Corners are G's vertex locations; the p - 1 inner nodes of each edge lie
/// on its polyline at arc-length fractions k/p, shared by both faces of the edge; the interior nodes are the points
/// of T that the patch's map onto the reference triangle (boundary by arc length, inside by Tutte's embedding with
/// mean-value weights, linear on each overlay triangle) sends to the equispaced nodes. On a flat patch an element
/// is exactly its straight triangle. Deterministic, the same for any thread count. Preconditions: G valid (its
/// overlay's patches are disks). Throws InvalidInput for an order outside [1, 8] or a patch that is not a disk, and
/// NumericalError when a patch's map cannot be solved.
CurvedMesh curve_elements(const GeodesicTriangulation& g, const CurveOptions& options = {});

struct CurveAdaptOptions {
    CurveOptions curve;
    double tolerance = 1e-3;    ///< the largest distance bound allowed, relative to the diagonal of T's box
    double min_quality = 0.1;   ///< the smallest certified min J / max J allowed (corners' plane)
    int max_rounds = 20;        ///< rounds of refinement at most
};

struct CurveAdaptResult {
    CurvedMesh curved;        ///< of G as refined
    int rounds = 0;           ///< rounds that refined G
    int splits = 0;           ///< edges and faces split
    int moves = 0;            ///< vertices of G moved onto a vertex or a crease of T
    int flips = 0;            ///< edges of G flipped to join two of its vertices along an edge of T
    int failing = 0;          ///< elements that still fail (0 unless a round could mend nothing or the cap was hit)
    bool round_cap_reached = false;
};

/// curve_elements(), then, while some elements fail (CurvedElement::passes()), mends each failing face with changes
/// that keep G valid and isogeometric, and makes the elements of the faces that changed again; at most max_rounds
/// rounds.
/// - An element that folds over T (not certified against T's normals) reaches over a crease or a corner of T,
///   which keeps its angle however small the element gets: a vertex of G goes onto a vertex of T there (splitting
///   the face or an edge, or moving a corner of the patch), or, where one stands there already, an edge of G is
///   flipped to join it to another along an edge of T, so that G's edges come to run along T's edges. Where T bends
///   there by a right angle or more and no such vertex is in reach, the element is not bisected.
/// - Else, where one of its edges crosses a crease of T (a point of its polyline where T's normal turns more than
///   at all its other points together), the edge is split there when that point is in the edge's middle half, and
///   the nearer end moves onto it otherwise (for an element that folds); else its longest edge is split at the
///   middle of its polyline.
/// Flips towards geodesic Delaunay from the changed vertices' links then shape G again. A smooth patch flattens as
/// it shrinks, so the failures go, but for what a refused change or the cap leaves: `failing` counts them, and the
/// elements' certificates say why. Deterministic. Throws as curve_elements() does, and InvalidInput for a tolerance
/// or quality out of range.
CurveAdaptResult curve_adaptively(GeodesicTriangulation& g, const CurveAdaptOptions& options = {});

/// The Bézier control points of the elements, indexed as CurvedMesh::nodes: element e is the Bézier triangle of
/// order p whose control point of multi-index gmsh_node_order(p)[n] is the result's [e.nodes[n]], the same
/// polynomial as the Lagrange triangle through its nodes. Corners are the corner nodes; an edge's control points are
/// shared by both of its elements, so the Bézier mesh is as conforming as the Lagrange one.
std::vector<Eigen::Vector3d> bezier_control_points(const CurvedMesh& curved);

/// The positions of the gmsh-ordered nodes of order p as multi-indices (i, j, k), i + j + k = p, each the weights
/// of corners 0, 1, 2 times p.
std::vector<std::array<int, 3>> gmsh_node_order(int order);

}  // namespace geotri

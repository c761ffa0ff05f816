#pragma once
// Decimation of the fine mesh T into a coarse mesh by halfedge collapses (DESIGN.md §3, geotri-decimate): the
// coarse vertices are a subset of T's vertices at their exact positions, and every component keeps its topology.

#include <geotri/edge_paths.h>
#include <geotri/fine_mesh.h>
#include <geotri/mesh_data.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace geotri {

/// How the collapses are chosen. Both use OpenMesh's decimater framework (CollapseInfo, a decimater module for the
/// priority and the quality checks, and OpenMesh's collapse()) with the same checks; they differ in how they find
/// the next collapse.
enum class DecimateStrategy {
    /// OpenMesh's DecimaterT as it is: always the cheapest collapse, from a priority queue. The reference; slower
    /// than multiple_choice.
    priority_queue,
    /// The cheapest of a few randomly drawn collapses (the multiple-choice scheme of OpenMesh's McDecimaterT, with a
    /// seeded generator) while the mesh is much larger than the target, then always the cheapest collapse from a
    /// priority queue of its own for the last stretch; both test the link condition directly.
    multiple_choice,
};

/// Progress of a decimation, reported through DecimateOptions::progress.
struct DecimateProgress {
    std::size_t fine_faces = 0;     ///< faces of T, all components
    std::size_t target_faces = 0;   ///< faces aimed at, all components
    std::size_t current_faces = 0;  ///< faces of the coarse mesh so far, all components
};

/// What to decimate to: exactly one of target_faces, target_vertices, ratio and coarsest.
struct DecimateOptions {
    std::size_t target_faces = 0;     ///< at most this many faces in all (0: unset)
    std::size_t target_vertices = 0;  ///< at most this many vertices in all (0: unset)
    double ratio = 0.0;               ///< at most ratio · faces of T, 0 < ratio <= 1 (0: unset)
    bool coarsest = false;            ///< as coarse as each component's topology and the link condition allow
    /// Per component of T (FineMesh::component numbering): the faces that it aims at, in place of its share of the
    /// target (each at least the component's min_faces and at most its faces); empty: shares of the target. One of
    /// the targets above must still be set, but the target is then their sum in faces, whichever it is. Backing off
    /// (decimate_backoff.h) gives a component whose geodesics tangle more faces and leaves the others' as it was.
    std::vector<int> component_targets;

    DecimateStrategy strategy = DecimateStrategy::multiple_choice;
    /// multiple_choice: random draws per collapse. The priority queue takes over below max(20000, 8 · target)
    /// faces per component.
    int samples = 8;
    std::uint64_t seed = 1;
    /// Keep what each coarse edge is on T (DecimateResult::edges): about 8% more time and 20% more memory on a
    /// 200k-face mesh. Off: `edges` stays empty.
    bool edge_paths = true;
    /// Called now and then, from one thread at a time; returning false stops the decimation at a consistent state
    /// (DecimateResult::aborted).
    std::function<bool(const DecimateProgress&)> progress;
};

/// One connected component of T and what became of it.
struct DecimateComponent {
    int fine_vertices = 0;
    int fine_faces = 0;
    int euler_characteristic = 0;  ///< V - E + F of the component, the same before and after
    int genus = 0;
    int min_faces = 0;     ///< fewest faces of any triangulation of this topology (4 for a sphere, 14 for a torus)
    int target_faces = 0;  ///< this component's share of the target
    int vertices = 0;      ///< coarse vertices reached
    int faces = 0;         ///< coarse faces reached
};

struct DecimateResult {
    /// The coarse mesh: positions copied bit for bit from T, triangles oriented as T's. Vertices are in the order of
    /// their fine indices.
    MeshData coarse;
    std::vector<int> fine_vertex;  ///< per coarse vertex: its index in T
    std::vector<DecimatedEdge> edges;  ///< every coarse edge, sorted by (a, b) (with DecimateOptions::edge_paths)
    std::vector<DecimateComponent> components;  ///< in T's component order (FineMesh::component)
    std::size_t target_faces = 0;  ///< the target in faces, all components (for coarsest: the sum of min_faces)
    /// Whether the coarse mesh has at most target_faces faces (target_vertices vertices when that was asked). False
    /// when the topology needs more, or when no legal collapse was left.
    bool target_reached = false;
    bool aborted = false;  ///< the progress callback asked to stop
};

/// Decimates T by halfedge collapses that keep each component's topology (OpenMesh's link condition), that never
/// turn a triangle over (its normal may turn by at most 90° in one collapse) and that never make a zero-area triangle
/// or a needle worse than the worst triangle that the collapse removes. The target is split between the components
/// in proportion to their area, each getting at least min_faces. Collapses that worsen the shape least (by the
/// quadric error of Garland and Heckbert) go first; near the end, the quality limits are relaxed step by step, to
/// the hard limits above, before the target is given up. Deterministic: the same T and options give the same result.
/// Throws InvalidInput when not exactly one target is set, when ratio is outside (0, 1], or when component_targets
/// is not empty and does not have one entry per component.
DecimateResult decimate(const FineMesh& fine, const DecimateOptions& options);

/// Fewest faces of a closed orientable triangulated surface of genus `genus` (Jungerman and Ringel): 4, 14, 24, ...
int min_faces_of_genus(int genus);

/// The edge paths of a decimation of `fine`. Throws InvalidInput when it kept none (DecimateOptions::edge_paths).
EdgePaths make_edge_paths(const FineMesh& fine, const DecimateResult& decimation);

}  // namespace geotri

#pragma once
// What the operations on G over one T share within a run so as not to make it again: propagation objects, the
// shortest geodesics found so far, and the overlay of G when the caller keeps one. A workspace only saves time:
// every result is the same with it, without it, or with any part of it missing.

namespace geotri {

namespace geodesic {
class ExactGeodesic;
}
class PathCache;
class PropagationPool;
struct Overlay;

/// Non-owning: whoever makes the objects keeps them alive for the calls that use them.
struct Workspace {
    /// A propagation object over T for the calling thread (its setup costs as much as a short propagation); an
    /// operation makes its own for the call when null.
    geodesic::ExactGeodesic* propagation = nullptr;
    /// `propagation` already holds a goal-directed propagation from the point that a split is about to join, whose
    /// stop points include every coarse vertex it joins: the split uses it instead of propagating again.
    bool propagated = false;
    /// Propagation objects for the other threads of a parallel loop, kept from one loop to the next; each thread
    /// makes its own for the call when null. For one thread team at a time.
    PropagationPool* propagations = nullptr;
    /// Shortest geodesics between two points of T found before, used again instead of a propagation (the same
    /// path), and where new ones are kept.
    PathCache* paths = nullptr;
    /// The overlay of this same G, from which patches are cut out of T; when null, the patches alone are cut out
    /// of T, at a cost that grows with the patches rather than with T.
    const Overlay* overlay = nullptr;
};

/// A workspace that holds the calling thread's propagation object alone.
inline Workspace propagation_only(geodesic::ExactGeodesic& propagation) {
    Workspace workspace;
    workspace.propagation = &propagation;
    return workspace;
}

}  // namespace geotri

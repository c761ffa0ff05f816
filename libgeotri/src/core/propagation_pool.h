#pragma once
// Propagation objects over one fine mesh, one per OpenMP thread, kept from one parallel loop to the next.

#include <geodesic/exact_geodesic.h>
#include <geodesic/mesh.h>

#include <memory>
#include <mutex>
#include <vector>

namespace geotri {

/// One geodesic::ExactGeodesic over `mesh` per thread number, made on first use and kept. Making one costs a pass
/// over the mesh, as much as a short propagation: a parallel loop of a few short propagations (the flips after each
/// split of refinement) that made its threads' objects at every call cost as much wall time on two threads as on
/// one. Safe to call from the threads of one team at a time; the mesh must outlive the pool.
class PropagationPool {
public:
    explicit PropagationPool(const geodesic::Mesh& mesh) : mesh_(mesh) {}

    const geodesic::Mesh& mesh() const { return mesh_; }

    /// The object of thread number `thread` (omp_get_thread_num() in the team that runs the loop).
    geodesic::ExactGeodesic& of_thread(int thread) {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto k = static_cast<std::size_t>(thread);
        if (objects_.size() <= k) objects_.resize(k + 1);
        if (!objects_[k]) objects_[k] = std::make_unique<geodesic::ExactGeodesic>(mesh_);
        return *objects_[k];
    }

private:
    const geodesic::Mesh& mesh_;
    std::mutex mutex_;
    std::vector<std::unique_ptr<geodesic::ExactGeodesic>> objects_;
};

}  // namespace geotri

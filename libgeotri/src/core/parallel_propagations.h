#pragma once
// A parallel loop whose iterations each need a propagation object: what improving flips and reconnecting a polygon
// both run.

#include <geodesic/exact_geodesic.h>
#include <geodesic/mesh.h>

#include "core/propagation_pool.h"
#include "core/thread_count.h"

#include <cstddef>
#include <exception>
#include <memory>
#include <stdexcept>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace geotri::detail {

/// Calls work(k, propagation) for k in [0, n) on `threads` threads (0: as many as OpenMP likes), each with a
/// propagation object over `mesh`: the calling thread uses `reuse` when given, the others those of `pool` when
/// given, else one of their own, made on first use (making one costs a pass over the mesh: on a mesh of 200k
/// faces, refinement spent 14% of its time making them). Rethrows the first exception (in k order) after the loop.
/// The result is the same for any thread count when work(k, ...) writes only what belongs to k.
template <class Work>
void for_each_with_propagation(const geodesic::Mesh& mesh, std::size_t n, int threads, Work work,
                               geodesic::ExactGeodesic* reuse = nullptr, PropagationPool* pool = nullptr) {
    if (pool && &pool->mesh() != &mesh) throw std::invalid_argument("for_each_with_propagation: another mesh's pool");
    std::vector<std::exception_ptr> errors(n);
    const long count = static_cast<long>(n);
    const int team = team_size(threads);
#ifdef _OPENMP
#pragma omp parallel num_threads(team) if (team > 1)
#endif
    {
        geodesic::ExactGeodesic* mine = reuse;
        int thread = 0;
#ifdef _OPENMP
        thread = omp_get_thread_num();
        if (thread != 0) mine = nullptr;
#endif
        std::unique_ptr<geodesic::ExactGeodesic> own;  // this thread's, reused across iterations
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 1)
#endif
        for (long i = 0; i < count; ++i) {
            const std::size_t k = static_cast<std::size_t>(i);
            try {
                if (!mine && pool) mine = &pool->of_thread(thread);
                if (!mine) {
                    own = std::make_unique<geodesic::ExactGeodesic>(mesh);
                    mine = own.get();
                }
                work(k, *mine);
            } catch (...) {
                errors[k] = std::current_exception();
            }
        }
    }
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
}

}  // namespace geotri::detail

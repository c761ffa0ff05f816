#pragma once
// How many threads a `threads` option stands for (0: as many as OpenMP likes).

#ifdef _OPENMP
#include <omp.h>
#endif

namespace geotri::detail {

/// `threads` where it is positive, else OpenMP's default team size; 1 without OpenMP, where nothing runs in parallel.
inline int team_size(int threads) {
#ifdef _OPENMP
    return threads > 0 ? threads : omp_get_max_threads();
#else
    (void)threads;
    return 1;
#endif
}

}  // namespace geotri::detail

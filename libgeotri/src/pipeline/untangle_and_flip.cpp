#include <geotri/untangle_and_flip.h>

#include "pipeline/flip_to_delaunay_detail.h"
#include "pipeline/untangle_detail.h"

#include <chrono>

namespace geotri {

UntangleAndFlipResult untangle_and_flip(GeodesicTriangulation& g, const UntangleAndFlipOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    UntangleAndFlipResult result;
    ValidationReport report = validate(g);
    result.angles_before = corner_angle_stats(g);
    result.untangling.valid_before = report.valid;
    result.untangling.violations_before = report.violation_count;
    if (options.untangle) result.untangling = detail::untangle_validated(g, options.untangling, report);
    if (options.flip) result.flipping = detail::flip_to_delaunay_validated(g, options.flipping, report);
    result.valid_after = report.valid;
    result.violations_after = report.violation_count;
    if (!report.valid) result.remaining = report.violations;
    result.angles_after = corner_angle_stats(g);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace geotri

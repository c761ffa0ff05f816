#pragma once
// What geotri-flip does: untangle(), then flip_to_delaunay() when G came out valid.

#include <geotri/flip_to_delaunay.h>
#include <geotri/untangle.h>

namespace geotri {

struct UntangleAndFlipOptions {
    bool untangle = true;  ///< untangle an invalid G first
    bool flip = true;      ///< then flip a valid G towards geodesic Delaunay
    UntangleOptions untangling;
    FlipToDelaunayOptions flipping;
};

struct UntangleAndFlipResult {
    UntangleResult untangling;  ///< its valid_before and violations_before are those of G as given
    FlipToDelaunayResult flipping;
    CornerAngleStats angles_before, angles_after;  ///< of G as given and as returned
    bool valid_after = false;
    std::array<int, 4> violations_after{};  ///< per condition, as validate() counts them
    std::vector<Violation> remaining;       ///< the violations left when G is still invalid
    double seconds = 0.0;
};

/// untangle() (when asked, and G is invalid), then flip_to_delaunay() (when asked, and G is valid), validating G
/// once at the start and once at the end. Throws as they do.
UntangleAndFlipResult untangle_and_flip(GeodesicTriangulation& g, const UntangleAndFlipOptions& options = {});

}  // namespace geotri

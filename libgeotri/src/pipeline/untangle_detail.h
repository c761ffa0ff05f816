#pragma once
// Untangling for the library's own pipelines, on a G whose validation is known.

#include <geotri/untangle.h>
#include <geotri/validate.h>

namespace geotri::detail {

/// untangle() on a G whose validation `report` is (validate() with the overlay): not validated again on entry; on
/// return, `report` is that of G as returned.
UntangleResult untangle_validated(GeodesicTriangulation& g, const UntangleOptions& options, ValidationReport& report);

}  // namespace geotri::detail

#pragma once
// Condition 1's verdict on each polyline of a G, and what condition 3 needs of it, kept from one validation to the
// next. Copies of G share their polylines, and an operation replaces a polyline rather than change it, so a trial
// copy's unchanged edges hold the same polyline objects as the G it was copied from: their verdicts need not be
// computed again. Untangling judges thousands of trial copies that differ from G in a few edges.

#include <geotri/geodesic_triangulation.h>
#include <geotri/validate.h>

#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace geotri::detail {

struct CrossingItems;  // validate.cpp

class PolylineVerdicts {
public:
    PolylineVerdicts() = default;
    /// The verdicts on g's polylines, taken from `earlier` where it has them. Keeps g's polylines alive, so that
    /// no other polyline can take the address of one of them.
    PolylineVerdicts(const GeodesicTriangulation& g, const PolylineVerdicts& earlier);

    /// Makes these the verdicts of g, a copy of the G that they are for which differs from it only at the coarse
    /// `edges` (indices in either, as ViolationCount::Changed lists them): as PolylineVerdicts(g, *this), from
    /// those edges alone.
    void advance(const GeodesicTriangulation& g, const std::vector<int>& edges);

    /// Whether the polyline of g's edge e is straight and as long as recorded: empty when it is, else why not
    /// (as validate() says it); null when it is not known here. Only polylines whose points are apart and
    /// pairwise on a common fine face are known.
    const std::string* find(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) const;
    /// The polyline of g's edge e with its points in canonical form, when its verdict is known here (as find());
    /// else null. Validation needs the canonical points of every polyline for condition 3.
    const Polyline* canonical(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) const;
    /// The same, shared, for a holder that may outlive these verdicts.
    std::shared_ptr<const Polyline> shared_canonical(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) const;
    /// The points and segments of g's edge e, each with the fine element that holds it, as condition 3 sorts them,
    /// when its verdict is known here (as find()); else null.
    const CrossingItems* crossing_items(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) const;

private:
    struct Verdict {
        double recorded_length;
        std::string defect;
        std::shared_ptr<const Polyline> canonical;
        std::shared_ptr<const CrossingItems> crossings;
    };
    const Verdict* verdict(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e) const;
    /// Files the verdict on the polyline of g's edge e `into`: this one's where known, else made, where it can be.
    void find_or_make(const GeodesicTriangulation& g, OpenMesh::EdgeHandle e,
                      std::unordered_map<const Polyline*, Verdict>& into) const;
    std::optional<GeodesicTriangulation> kept_;
    std::unordered_map<const Polyline*, Verdict> verdicts_;
};

/// The verdict on a polyline whose points are on T, apart and pairwise on a common fine face: empty when it is
/// straight (straightness_defect) and `recorded_length` long, else why not.
std::string shape_defect(const geodesic::Mesh& mesh, const Polyline& path, double recorded_length);

/// validate(), with the verdicts of `known` where it has them: the same report.
ValidationReport validate(const GeodesicTriangulation& g, const ValidationOptions& options,
                          const PolylineVerdicts& known);

}  // namespace geotri::detail

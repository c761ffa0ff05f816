#pragma once
// The number of violations of conditions 1-3 of copies of one G that differ from it in a few edges and vertices,
// found from what differs. Untangling judges thousands of trial copies of G, each changed by one local operation;
// validating each trial in full sorts and sweeps the condition-3 items of all of G every time, and so would
// counting again, in full, the trial that untangling keeps.

#include <geotri/geodesic_triangulation.h>

#include "check/polyline_verdicts.h"

#include <memory>
#include <vector>

namespace geotri::detail {

class ViolationCount {
public:
    /// Counts the violations of conditions 1-3 of g, as validate() without the overlay counts them, and keeps what
    /// it takes to count them again on a copy of g from what differs. `known` are verdicts, as for validate().
    /// Throws InvalidInput where validate() would.
    ViolationCount(const GeodesicTriangulation& g, const PolylineVerdicts& known);

    /// The count of `trial`, a copy of the G that `base` counts changed as count(trial, known) allows: the same as
    /// ViolationCount(trial, known), made from what differs. Nothing of what trial shares with G is checked again,
    /// and the rest is copied. Throws InvalidInput where validate() would.
    ViolationCount(const ViolationCount& base, const GeodesicTriangulation& trial, const PolylineVerdicts& known);

    /// g's count: the violations of conditions 1-3 that validate(g) names.
    int count() const;

    /// validate(g) without the overlay, but for the words: the same violations of conditions 1-3, each naming the
    /// same coarse vertices, edges and faces, with an empty `what`; without the summary figures.
    ValidationReport report() const;

    /// The violations of conditions 1-3 that validate(trial) names, where trial is a copy of g changed by
    /// operations that replace polylines rather than change them in place (as GeodesicTriangulation's do; the
    /// coarse elements may also be renumbered). The same number as validate() gives, found by checking only the
    /// edges and vertices that differ from g (a different polyline object or length, ends or location; for
    /// condition 2, the vertices whose edges around them changed) against the rest: g's count, less the
    /// violations that involve what changed in g, plus those that involve what changed in trial. `known` are
    /// verdicts, as for validate(). Throws InvalidInput where validate() would. Safe to call from several
    /// threads at once.
    int count(const GeodesicTriangulation& trial, const PolylineVerdicts& known) const;

    /// The coarse edges and vertices where a copy of g differs from it, by index (in either), ascending.
    struct Changed {
        std::vector<int> edges, vertices;
    };
    /// count(trial, known), and where trial differs from g.
    int count(const GeodesicTriangulation& trial, const PolylineVerdicts& known, Changed& changed) const;

    struct State;  // violation_count.cpp

private:
    std::shared_ptr<const State> g_;
};

}  // namespace geotri::detail

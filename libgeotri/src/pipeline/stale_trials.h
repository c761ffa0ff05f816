#pragma once
// Untangling tries the same moves round after round: a move that failed goes last, but is tried again after every
// move kept, in case that one changed what it depends on (on cheese, 33205 of 34839 flips tried were such retries).
// Whether a flip, or a move of a vertex, lowers the violations of conditions 1-3 depends only on what lies on the
// fine faces that it and its geodesics touch: its geodesics depend only on the locations of their ends, two
// features meet only on a fine element that they share, and a vertex's corners depend only on the geodesics that
// leave its location. So such a move that failed fails again as long as no move kept since has changed a feature on
// one of those faces, and it need not be tried.

#include <geotri/geodesic_triangulation.h>

#include <array>
#include <cstddef>
#include <optional>
#include <unordered_map>
#include <vector>

namespace geotri::detail {

/// A hash of untangling's keys of moves (a kind and two indices), for the sets and maps that look them up.
struct MoveKeyHash {
    std::size_t operator()(const std::array<int, 3>& key) const {
        std::size_t h = 0;
        for (int x : key) h = h * 0x9E3779B97F4A7C15ull + static_cast<std::size_t>(static_cast<unsigned>(x));
        return h;
    }
};

class StaleTrials {
public:
    /// The fine faces, closed (a point on a fine vertex or edge counts on every face around it), that the edges and
    /// vertices where `trial` differs from `g` touch, in g and in trial: what a judgement of trial against g reads.
    /// Both share their polylines where they agree (a copy of g, changed by GeodesicTriangulation's operations).
    static std::vector<int> changed_faces(const GeodesicTriangulation& g, const GeodesicTriangulation& trial);
    /// The same, where g and trial can differ only in the coarse `edges` and `vertices` (indices in either, as
    /// ViolationCount finds them): nothing else is compared.
    static std::vector<int> changed_faces(const GeodesicTriangulation& g, const GeodesicTriangulation& trial,
                                          const std::vector<int>& edges, const std::vector<int>& vertices);

    /// G has changed on `faces` (changed_faces() of the G before and the G after).
    void changed(const std::vector<int>& faces);

    /// The move `key` failed on the current G, with `operations` done (0: it was not possible there), reading
    /// `faces` (changed_faces() of G and its trial).
    void failed(const std::array<int, 3>& key, std::vector<int> faces, int operations);

    /// The operations of the move `key`'s failure where nothing it read has changed since, else none.
    std::optional<int> known_failure(const std::array<int, 3>& key) const;

    /// Forgets every failure: the coarse elements were renumbered.
    void clear() { failures_.clear(); }

private:
    struct Failure {
        std::vector<int> faces;
        int operations = 0;
        long epoch = 0;  ///< changes_ when it failed
    };
    std::unordered_map<std::array<int, 3>, Failure, MoveKeyHash> failures_;
    std::vector<long> changed_at_;  ///< per fine face: the number of the last change on it (0: none)
    long changes_ = 0;
};

}  // namespace geotri::detail

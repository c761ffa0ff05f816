#pragma once
// The propagation's priority queue: private to libgeodesic.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace geotri::geodesic::detail {

/// A min-queue of (key, item) pairs, ordered by key and then by item. The order is total, so the pop sequence does
/// not depend on how the heap is laid out, and propagation results do not depend on it either.
/// A 4-ary heap: half the levels of a binary one. Keys are compared as integers that order like the doubles, which
/// lets the compiler pick the least child without branches, whose outcome the processor could not predict.
class EventQueue {
public:
    struct Entry {
        double key;
        int item;
    };

    bool empty() const { return heap_.empty(); }
    std::size_t size() const { return heap_.size(); }
    void clear() { heap_.clear(); }
    /// The least entry's item. Precondition: not empty.
    int top_item() const { return unbias(heap_.front().item); }

    /// Precondition: key is not NaN.
    void push(double key, int item) {
        const Node node{bits(key), bias(item)};
        std::size_t hole = heap_.size();
        heap_.push_back(node);
        while (hole > 0) {
            const std::size_t parent = (hole - 1) / 4;
            if (!before(node, heap_[parent])) break;
            heap_[hole] = heap_[parent];
            hole = parent;
        }
        heap_[hole] = node;
    }

    /// Removes and returns the least entry. Precondition: not empty.
    Entry pop() {
        const Node least = heap_.front();
        const Node last = heap_.back();
        heap_.pop_back();
        const std::size_t n = heap_.size();
        if (n > 0) {
            std::size_t hole = 0;
            for (;;) {
                const std::size_t first = 4 * hole + 1;
                if (first >= n) break;
                std::size_t best = first;
                if (first + 4 <= n) {
                    const std::size_t a = before(heap_[first + 1], heap_[first]) ? first + 1 : first;
                    const std::size_t b = before(heap_[first + 3], heap_[first + 2]) ? first + 3 : first + 2;
                    best = before(heap_[b], heap_[a]) ? b : a;
                } else {
                    for (std::size_t c = first + 1; c < n; ++c)
                        if (before(heap_[c], heap_[best])) best = c;
                }
                if (!before(heap_[best], last)) break;
                heap_[hole] = heap_[best];
                hole = best;
            }
            heap_[hole] = last;
        }
        return {value(least.key), unbias(least.item)};
    }

private:
    struct Node {
        std::uint64_t key;
        std::uint32_t item;
    };

    // Non-negative doubles order like their bits; negative ones in reverse. Mapping them below the non-negative
    // ones, their bits inverted, gives the doubles' order (with -0 made +0 first, as they compare equal).
    static constexpr std::uint64_t k_sign = std::uint64_t{1} << 63;
    static std::uint64_t bits(double key) {
        key += 0.0;
        std::uint64_t b;
        std::memcpy(&b, &key, sizeof b);
        return (b & k_sign) ? ~b : b | k_sign;
    }
    static double value(std::uint64_t b) {
        b = (b & k_sign) ? b & ~k_sign : ~b;
        double key;
        std::memcpy(&key, &b, sizeof key);
        return key;
    }
    static std::uint32_t bias(int item) { return static_cast<std::uint32_t>(item) ^ 0x80000000u; }
    static int unbias(std::uint32_t item) { return static_cast<int>(item ^ 0x80000000u); }
    static bool before(const Node& a, const Node& b) {
        return (a.key < b.key) | ((a.key == b.key) & (a.item < b.item));
    }

    std::vector<Node> heap_;
};

}  // namespace geotri::geodesic::detail

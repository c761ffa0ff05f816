#pragma once
// The propagation's priority queue: private to libgeodesic.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace geotri::geodesic::detail {

/// A min-queue of items, integers in [-num_negative, num_nonnegative), each queued at most once with one key, and
/// ordered by key and then by item. Setting the key of an item that is queued moves its entry: a queue that left
/// the old entry behind, to be skipped when it came up, popped more stale entries than live ones (58% of its pops
/// on a noisy sphere, 85% on an icosphere). The order is total, so the pop sequence does not depend on how the heap
/// is laid out, and propagation results do not depend on it either.
/// A 4-ary heap: half the levels of a binary one. Keys are compared as integers that order like the doubles, which
/// lets the compiler pick the least child without branches, whose outcome the processor could not predict.
class EventQueue {
public:
    struct Entry {
        double key;
        int item;
    };

    /// Empties the queue and makes room for the items of [-num_negative, num_nonnegative).
    void resize(int num_negative, int num_nonnegative) {
        clear();
        num_negative_ = num_negative;
        position_.assign(static_cast<std::size_t>(num_negative) + static_cast<std::size_t>(num_nonnegative), k_absent);
    }

    bool empty() const { return heap_.empty(); }
    std::size_t size() const { return heap_.size(); }
    /// Empties the queue, at a cost that follows the entries left in it, not the number of items.
    void clear() {
        for (const Node& node : heap_) position_[node.slot] = k_absent;
        heap_.clear();
    }
    /// The least entry's item. Precondition: not empty.
    int top_item() const { return item_of(heap_.front().slot); }

    /// Queues `item` with `key`, or moves it to `key` if it is queued already. Precondition: key is not NaN.
    void set(double key, int item) {
        const Node node{bits(key), static_cast<std::uint32_t>(item + num_negative_)};
        const std::uint32_t at = position_[node.slot];
        if (at == k_absent) {
            heap_.emplace_back();
            sift_up(heap_.size() - 1, node);
        } else if (before(node, heap_[at])) {
            sift_up(at, node);
        } else {
            sift_down(at, node);
        }
    }

    /// Removes and returns the least entry. Precondition: not empty.
    Entry pop() {
        const Node least = heap_.front();
        position_[least.slot] = k_absent;
        const Node last = heap_.back();
        heap_.pop_back();
        if (!heap_.empty()) sift_down(0, last);
        return {value(least.key), item_of(least.slot)};
    }

private:
    struct Node {
        std::uint64_t key;
        std::uint32_t slot;  ///< item + num_negative_: orders like the item
    };
    static constexpr std::uint32_t k_absent = 0xffffffffu;

    void place(std::size_t hole, const Node& node) {
        heap_[hole] = node;
        position_[node.slot] = static_cast<std::uint32_t>(hole);
    }

    void sift_up(std::size_t hole, const Node& node) {
        while (hole > 0) {
            const std::size_t parent = (hole - 1) / 4;
            if (!before(node, heap_[parent])) break;
            place(hole, heap_[parent]);
            hole = parent;
        }
        place(hole, node);
    }

    void sift_down(std::size_t hole, const Node& node) {
        const std::size_t n = heap_.size();
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
            if (!before(heap_[best], node)) break;
            place(hole, heap_[best]);
            hole = best;
        }
        place(hole, node);
    }

    int item_of(std::uint32_t slot) const { return static_cast<int>(slot) - num_negative_; }

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
    static bool before(const Node& a, const Node& b) {
        return (a.key < b.key) | ((a.key == b.key) & (a.slot < b.slot));
    }

    int num_negative_ = 0;
    std::vector<Node> heap_;
    std::vector<std::uint32_t> position_;  ///< per slot: its entry's index in heap_, or k_absent
};

}  // namespace geotri::geodesic::detail

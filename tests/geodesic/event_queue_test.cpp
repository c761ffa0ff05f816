// The propagation's queue (detail::EventQueue), tested directly against a plain reference: the latest key of each
// item, popped in (key, item) order. Setting a key moves an item's entry up or down the heap; a mistake there would
// only show on whole meshes as windows crossing late, which the distances do not always reveal.

#include "event_queue.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <utility>

namespace geotri::geodesic::detail {
namespace {

TEST(EventQueue, pops_in_key_then_item_order_with_negative_and_non_negative_items) {
    EventQueue queue;
    queue.resize(3, 4);
    queue.set(2.0, 1);
    queue.set(1.0, -3);
    queue.set(2.0, -1);
    queue.set(-0.0, 3);
    queue.set(0.0, 0);
    const std::pair<double, int> expected[] = {{0.0, 0}, {0.0, 3}, {1.0, -3}, {2.0, -1}, {2.0, 1}};
    for (const auto& [key, item] : expected) {
        ASSERT_FALSE(queue.empty());
        EXPECT_EQ(queue.top_item(), item);
        const EventQueue::Entry entry = queue.pop();
        EXPECT_EQ(entry.key, key);
        EXPECT_EQ(entry.item, item);
    }
    EXPECT_TRUE(queue.empty());
}

TEST(EventQueue, setting_a_key_again_moves_the_one_entry_of_the_item_either_way) {
    EventQueue queue;
    queue.resize(0, 3);
    queue.set(5.0, 0);
    queue.set(6.0, 1);
    queue.set(7.0, 2);
    queue.set(1.0, 2);  // up
    queue.set(9.0, 0);  // down
    EXPECT_EQ(queue.size(), 3u);
    EXPECT_EQ(queue.pop().item, 2);
    EXPECT_EQ(queue.pop().item, 1);
    const EventQueue::Entry last = queue.pop();
    EXPECT_EQ(last.item, 0);
    EXPECT_EQ(last.key, 9.0);
    EXPECT_TRUE(queue.empty());
}

TEST(EventQueue, random_sets_and_pops_match_a_reference_of_latest_keys) {
    constexpr int negative = 40, non_negative = 60;
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> any_item(-negative, non_negative - 1);
    std::uniform_int_distribution<int> any_key(0, 30);  // few keys: many ties
    EventQueue queue;
    queue.resize(negative, non_negative);
    for (int round = 0; round < 2; ++round) {
        std::map<int, double> key_of;
        std::set<std::pair<double, int>> order;
        for (int step = 0; step < 20000; ++step) {
            if (rng() % 3 != 0) {
                const int item = any_item(rng);
                const double key = 0.5 * any_key(rng);
                if (auto it = key_of.find(item); it != key_of.end()) order.erase({it->second, item});
                key_of[item] = key;
                order.insert({key, item});
                queue.set(key, item);
            } else if (!order.empty()) {
                const auto [key, item] = *order.begin();
                order.erase(order.begin());
                key_of.erase(item);
                ASSERT_EQ(queue.top_item(), item);
                const EventQueue::Entry entry = queue.pop();
                ASSERT_EQ(entry.item, item);
                ASSERT_EQ(entry.key, key);
            }
            ASSERT_EQ(queue.size(), order.size());
        }
        // Cleared with entries left, the queue takes every item as new again.
        queue.clear();
        EXPECT_TRUE(queue.empty());
    }
}

}  // namespace
}  // namespace geotri::geodesic::detail

// The attempts that refine() may need, run ahead of time on threads of their own or one by one when asked for (a
// private part of libgeotri): the same results either way, cancelled ones stopped, errors where they belong.

#include "pipeline/speculative_attempts.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace geotri::detail {
namespace {

TEST(SpeculativeAttempts, one_by_one_each_runs_when_asked_for_on_the_calling_thread) {
    std::vector<int> results(3, -1);
    std::vector<std::thread::id> ran_on(3);
    SpeculativeAttempts attempts(3, 1, [&](std::size_t k) {
        results[k] = static_cast<int>(10 * k);
        ran_on[k] = std::this_thread::get_id();
    });
    EXPECT_EQ(results, (std::vector<int>{-1, -1, -1}));  // nothing ran before it was asked for
    attempts.wait(2);
    attempts.cancel(1);
    attempts.wait(0);
    EXPECT_EQ(results, (std::vector<int>{0, -1, 20}));
    EXPECT_EQ(ran_on[0], std::this_thread::get_id());
    EXPECT_EQ(ran_on[2], std::this_thread::get_id());
    attempts.wait(0);  // once finished, waiting again returns at once
    EXPECT_THROW(attempts.wait(1), std::logic_error);  // a cancelled attempt has no result to wait for
}

TEST(SpeculativeAttempts, ahead_of_time_every_attempt_gives_its_result_and_cancelled_ones_stop) {
    for (int threads : {2, 3, 8}) {
        std::vector<long> sums(4, 0);
        std::atomic<int> started{0};
        {
            SpeculativeAttempts attempts(4, threads, [&](std::size_t k) {
                ++started;
                if (k == 3) {  // never ends unless cancelled
                    while (true) {
                        attempts.stop_if_cancelled(k);
                        std::this_thread::sleep_for(std::chrono::milliseconds(1));
                    }
                }
                for (long i = 0; i <= 1000 * static_cast<long>(k + 1); ++i) sums[k] += i;
            });
            for (std::size_t k = 0; k < 3; ++k) attempts.wait(k);
            EXPECT_EQ(sums[0], 500500) << threads << " threads";
            EXPECT_EQ(sums[1], 2001000) << threads << " threads";
            EXPECT_EQ(sums[2], 4501500) << threads << " threads";
            // Attempt 3 starts on a thread freed by the others (it is not cancelled yet), then never ends by itself.
            while (started < 4) std::this_thread::sleep_for(std::chrono::milliseconds(1));
            attempts.cancel(3);
        }  // returns: attempt 3 stopped
    }
}

TEST(SpeculativeAttempts, an_error_is_rethrown_where_its_attempt_is_waited_for) {
    for (int threads : {1, 2}) {
        SpeculativeAttempts attempts(2, threads, [](std::size_t k) {
            if (k == 0) throw std::runtime_error("first failed");
        });
        EXPECT_NO_THROW(attempts.wait(1)) << threads << " threads";
        try {
            attempts.wait(0);
            ADD_FAILURE() << "no error, " << threads << " threads";
        } catch (const std::runtime_error& error) {
            EXPECT_STREQ(error.what(), "first failed");
        }
    }
}

TEST(SpeculativeAttempts, attempts_not_waited_for_are_cancelled_when_it_goes) {
    std::atomic<int> started{0}, stopped{0};
    {
        SpeculativeAttempts attempts(2, 2, [&](std::size_t k) {
            ++started;
            try {
                while (true) {
                    attempts.stop_if_cancelled(k);
                    std::this_thread::sleep_for(std::chrono::milliseconds(1));
                }
            } catch (const AttemptCancelled&) {
                ++stopped;
                throw;
            }
        });
        while (started < 2) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_EQ(stopped, 2);
}

TEST(SpeculativeAttempts, an_attempt_cancelled_before_it_starts_never_runs) {
    std::atomic<bool> release{false};
    std::vector<int> ran(3, 0);
    {
        SpeculativeAttempts attempts(3, 2, [&](std::size_t k) {
            ran[k] = 1;
            if (k < 2)  // both threads busy until released
                while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        });
        attempts.cancel(2);
        release = true;
        attempts.wait(0);
        attempts.wait(1);
    }
    EXPECT_EQ(ran, (std::vector<int>{1, 1, 0}));
}

}  // namespace
}  // namespace geotri::detail

#pragma once
// A few independent attempts at the same job, of which the caller needs only some, and does not know which until it
// has looked at the results of the first ones: refine() starts again from the G given where its first attempt gave
// up on some triangles. With threads to spare, they all start at once, and those found unneeded are cancelled;
// otherwise each runs when it is asked for. The caller gets the same results either way.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace geotri::detail {

/// Thrown by SpeculativeAttempts::stop_if_cancelled() in an attempt that was cancelled; nobody waits for its result.
struct AttemptCancelled {};

class SpeculativeAttempts {
public:
    /// attempt(k) computes attempt k in [0, count), storing its result where the caller will look; it should call
    /// stop_if_cancelled(k) now and then. On `threads` > 1, min(threads, count) threads run the attempts ahead of
    /// time, in order of k; otherwise (threads <= 1) wait(k) runs attempt k on the calling thread.
    SpeculativeAttempts(std::size_t count, int threads, std::function<void(std::size_t)> attempt);
    /// Cancels the attempts still running or not started, and waits for the threads.
    ~SpeculativeAttempts();
    SpeculativeAttempts(const SpeculativeAttempts&) = delete;
    SpeculativeAttempts& operator=(const SpeculativeAttempts&) = delete;

    /// Returns once attempt k has finished (running it first when no thread has); rethrows what it threw.
    void wait(std::size_t k);
    /// Attempt k's result will not be asked for: it is not started, or told to stop (stop_if_cancelled()).
    void cancel(std::size_t k);
    /// Throws AttemptCancelled where attempt k was cancelled.
    void stop_if_cancelled(std::size_t k) const;
    /// Whether the caller is waiting for attempt k now: the attempt whose progress is worth reporting.
    bool waited_for(std::size_t k) const { return waited_for_.load() == static_cast<long>(k); }

private:
    enum class State { pending, running, done };
    void work();  // a thread's loop: the next pending attempt, until none is left
    void run(std::size_t k);
    void stop_all();  // cancels every attempt and joins the threads

    std::function<void(std::size_t)> attempt_;
    std::vector<State> state_;                    // guarded by mutex_
    std::vector<std::exception_ptr> errors_;      // guarded by mutex_
    std::vector<std::atomic<bool>> cancelled_;
    std::atomic<long> waited_for_{0};  // the first is the one waited for first
    std::mutex mutex_;
    std::condition_variable finished_;
    std::vector<std::thread> threads_;
};

}  // namespace geotri::detail

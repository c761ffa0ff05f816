#include "pipeline/speculative_attempts.h"

#include <algorithm>
#include <stdexcept>

namespace geotri::detail {

SpeculativeAttempts::SpeculativeAttempts(std::size_t count, int threads, std::function<void(std::size_t)> attempt)
    : attempt_(std::move(attempt)), state_(count, State::pending), errors_(count), cancelled_(count) {
    if (threads <= 1) return;
    const std::size_t team = std::min(count, static_cast<std::size_t>(threads));
    try {
        for (std::size_t t = 0; t < team; ++t) threads_.emplace_back([this] { work(); });
    } catch (...) {  // no thread to be had: those started must be stopped and joined before this throws
        stop_all();
        throw;
    }
}

void SpeculativeAttempts::stop_all() {
    for (std::atomic<bool>& c : cancelled_) c = true;
    for (std::thread& t : threads_) t.join();
    threads_.clear();
}

SpeculativeAttempts::~SpeculativeAttempts() { stop_all(); }

void SpeculativeAttempts::wait(std::size_t k) {
    if (cancelled_.at(k)) throw std::logic_error("SpeculativeAttempts::wait: attempt cancelled");
    waited_for_ = static_cast<long>(k);
    std::unique_lock<std::mutex> lock(mutex_);
    if (threads_.empty() && state_[k] == State::pending) {
        state_[k] = State::running;
        lock.unlock();
        run(k);
        lock.lock();
    }
    finished_.wait(lock, [&] { return state_[k] == State::done; });
    if (errors_[k]) std::rethrow_exception(errors_[k]);
}

void SpeculativeAttempts::cancel(std::size_t k) { cancelled_.at(k) = true; }

void SpeculativeAttempts::stop_if_cancelled(std::size_t k) const {
    if (cancelled_[k]) throw AttemptCancelled{};
}

void SpeculativeAttempts::work() {
    while (true) {
        std::size_t k = 0;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            while (k < state_.size() && (state_[k] != State::pending || cancelled_[k])) ++k;
            if (k == state_.size()) return;
            state_[k] = State::running;
        }
        run(k);
    }
}

void SpeculativeAttempts::run(std::size_t k) {
    std::exception_ptr error;
    try {
        attempt_(k);
    } catch (const AttemptCancelled&) {
        // nobody waits for it
    } catch (...) {
        error = std::current_exception();
    }
    {
        std::lock_guard<std::mutex> lock(mutex_);
        state_[k] = State::done;
        errors_[k] = error;
    }
    finished_.notify_all();
}

}  // namespace geotri::detail

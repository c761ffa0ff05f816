#include "progress.h"

#include <cstdio>

#include <unistd.h>

namespace geotri::tools {

Progress::Progress(std::string program, bool enabled)
    : program_(std::move(program)), enabled_(enabled && ::isatty(STDERR_FILENO) == 1) {}

Progress::~Progress() { clear(); }

void Progress::stage(const std::string& what) {
    stage_ = what;
    last_percent_ = -1;
    if (!enabled_) return;
    char time[32];
    std::snprintf(time, sizeof time, " (%.1f s)", elapsed());
    show(stage_ + "..." + time);
}

void Progress::update(long long done, long long total) {
    if (!enabled_ || total <= 0) return;
    const int percent = done <= 0 ? 0 : done >= total ? 100 : static_cast<int>(100.0 * double(done) / double(total));
    // A new percentage, or half a second since the last line, so that the clock moves on long steps.
    const double now = elapsed();
    if (percent == last_percent_ && now - last_shown_ < 0.5) return;
    last_percent_ = percent;
    char text[96];
    std::snprintf(text, sizeof text, "... %lld of %lld (%d%%, %.1f s)", done, total, percent, now);
    show(stage_ + text);
}

double Progress::elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::show(const std::string& text) {
    // \r and "erase to end of line" rewrite the line in place.
    std::fprintf(stderr, "\r\033[K%s: %s", program_.c_str(), text.c_str());
    std::fflush(stderr);
    shown_ = true;
    last_shown_ = elapsed();
}

void Progress::clear() {
    if (!shown_) return;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    shown_ = false;
}

}  // namespace geotri::tools

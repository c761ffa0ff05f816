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
    // \r and "erase to end of line" rewrite the line in place.
    std::fprintf(stderr, "\r\033[K%s: %s...", program_.c_str(), stage_.c_str());
    std::fflush(stderr);
    shown_ = true;
}

void Progress::update(double fraction) {
    if (!enabled_) return;
    const int percent = fraction <= 0 ? 0 : fraction >= 1 ? 100 : static_cast<int>(fraction * 100);
    if (percent == last_percent_) return;
    last_percent_ = percent;
    std::fprintf(stderr, "\r\033[K%s: %s... %d%%", program_.c_str(), stage_.c_str(), percent);
    std::fflush(stderr);
    shown_ = true;
}

void Progress::clear() {
    if (!shown_) return;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    shown_ = false;
}

}  // namespace geotri::tools

#pragma once
// Progress on stderr, for people watching a terminal: silent under --quiet and when stderr is a file or a pipe.

#include <chrono>
#include <string>

namespace geotri::tools {

class Progress {
public:
    /// Prints only if `enabled` and stderr is a terminal.
    Progress(std::string program, bool enabled);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// Shows "PROGRAM: WHAT... (2.5 s)" on a line of its own, replacing the previous stage; the time is since the
    /// tool started.
    void stage(const std::string& what);
    /// Shows "PROGRAM: WHAT... 120 of 480 (25%, 2.5 s)" for the current stage.
    void update(long long done, long long total);
    /// Clears the line, so that whatever is printed next starts clean.
    void clear();

private:
    std::string program_;
    std::string stage_;
    bool enabled_;
    bool shown_ = false;
    int last_percent_ = -1;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    double last_shown_ = 0.0;  ///< seconds since start_ when a line was last printed

    double elapsed() const;
    void show(const std::string& text);
};

}  // namespace geotri::tools

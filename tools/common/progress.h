#pragma once
// Progress on stderr, for people watching a terminal: silent under --quiet and when stderr is a file or a pipe.

#include <string>

namespace geotri::tools {

class Progress {
public:
    /// Prints only if `enabled` and stderr is a terminal.
    Progress(std::string program, bool enabled);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// Shows "PROGRAM: WHAT..." on a line of its own, replacing the previous stage.
    void stage(const std::string& what);
    /// Shows "PROGRAM: WHAT... 42%" for the current stage; fraction in [0, 1].
    void update(double fraction);
    /// Clears the line, so that whatever is printed next starts clean.
    void clear();

private:
    std::string program_;
    std::string stage_;
    bool enabled_;
    bool shown_ = false;
    int last_percent_ = -1;
};

}  // namespace geotri::tools

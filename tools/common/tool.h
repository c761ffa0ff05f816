#pragma once
// What every geotri-* tool shares: the options --version, --quiet, --threads and --json, and the wrapper that
// turns exceptions into one-line messages and exit codes (DESIGN.md §3).

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace geotri::tools {

/// Exit codes shared by every tool.
constexpr int k_exit_ok = 0;
constexpr int k_exit_failure = 1;  ///< bad input, or a failure while working
constexpr int k_exit_usage = 2;    ///< the command line itself is wrong

struct CommonOptions {
    bool quiet = false;  ///< no progress and no summary on stderr
    bool json = false;   ///< a machine-readable summary on stdout
    int threads = 0;     ///< 0: as many as OpenMP likes
};

/// A tool's command line, handed to its body by run_tool().
class Tool {
public:
    Tool(std::string program, int argc, char** argv);

    /// "geotri-NAME", as it prefixes every message.
    const std::string& program() const { return program_; }

    /// Parses the command line with the options the body has added to `app`, then applies --threads. Throws
    /// CLI::ParseError, which run_tool() reports as a usage error (or answers, for --help and --version).
    void parse();

    /// Ends --help with `examples` (command lines, one per entry) and the exit codes: 0 (`done`: what it means for
    /// this tool), 1 and 2, which every tool shares, and `more_exit_codes` (lines such as "3  written, but
    /// invalid") when the tool has others.
    void set_help_footer(const std::vector<std::string>& examples, const std::string& done = "done",
                         const std::vector<std::string>& more_exit_codes = {});

    /// Whether stderr may carry progress and a summary: not --quiet. (--json only changes stdout.)
    bool verbose() const { return !common.quiet; }

    CLI::App app;
    CommonOptions common;

private:
    std::string program_;
    int argc_;
    char** argv_;
};

/// Runs `body` for the tool geotri-`name` and returns the process's exit code: the body's own, 2 for a usage
/// error (with CLI11's message), or 1 for any exception, reported as one line
/// `geotri-NAME: error: MESSAGE` on stderr. --help and --version print to stdout and return 0.
int run_tool(const std::string& name, int argc, char** argv, const std::function<int(Tool&)>& body);

/// A CLI11 check that a path ends in one of `extensions` (lower case, with the dot), in any case. It refuses any
/// other path with "'PATH' should end in NAMES": `names` if given, else the extensions joined by ", ".
CLI::Validator extension_validator(std::vector<std::string> extensions, std::string names = {});

/// Seconds on a steady clock since an arbitrary start, for timings in summaries.
double now_seconds();

}  // namespace geotri::tools

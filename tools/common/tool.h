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

/// The most threads that --threads takes: more than any machine's cores, and few enough for the OpenMP runtime to
/// start them all (at 65536 it crashed).
constexpr int k_max_threads = 1024;

/// A CLI11 check that a value is a number in [lo, hi], or in (lo, hi] with `above_lo`, never NaN, and a whole number
/// in decimals with `whole` (for integer options), that says plainly what is wrong ("0 is not above 0", "65536 is
/// above 1024", "'4.5' is not a whole number") rather than CLI11's range up to the largest double.
CLI::Validator number_in(double lo, double hi, bool above_lo = false, bool whole = false);

/// A file that a tool reads or writes, named as on its command line: the option ("-o", "IN") and the path.
struct NamedFile {
    std::string option;
    std::string path;
};

/// Throws CLI::ValidationError, a usage error, when an output is the same file as an input or as another output (by
/// another path or through a link too): writing it would destroy what the tool reads, or one output the other.
/// Entries with an empty path are skipped.
void refuse_same_files(const std::vector<NamedFile>& inputs, const std::vector<NamedFile>& outputs);

/// A CLI11 check that a path ends in one of `extensions` (lower case, with the dot), in any case. It refuses any
/// other path with "'PATH' should end in NAMES": `names` if given, else the extensions joined by ", ".
CLI::Validator extension_validator(std::vector<std::string> extensions, std::string names = {});

/// Seconds on a steady clock since an arbitrary start, for timings in summaries.
double now_seconds();

}  // namespace geotri::tools

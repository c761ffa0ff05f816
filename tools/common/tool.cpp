#include "tool.h"

#include "output.h"

#include <geodesic/errors.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <limits>
#include <new>

#ifdef _OPENMP
#include <omp.h>
#endif

#ifndef GEOTRI_VERSION
#define GEOTRI_VERSION "unknown"
#endif

namespace geotri::tools {

namespace {

/// One line, whatever the message holds.
std::string one_line(std::string message) {
    for (char& c : message) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    while (!message.empty() && message.back() == ' ') message.pop_back();
    return message;
}

void report(const std::string& program, const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), one_line(message).c_str());
    std::fflush(stderr);
}

}  // namespace

Tool::Tool(std::string program, int argc, char** argv)
    : app("", program), program_(std::move(program)), argc_(argc), argv_(argv) {
    app.set_version_flag("--version", program_ + " " + GEOTRI_VERSION, "Print the version and exit");
    app.add_flag("-q,--quiet", common.quiet, "No progress and no summary on stderr");
    app.add_flag("--json", common.json, "Print a machine-readable summary on stdout");
    app.add_option("--threads", common.threads, "Number of threads (0: all cores)")
        ->check(number_in(0, k_max_threads, false, true))
        ->capture_default_str();
}

void Tool::set_help_footer(const std::vector<std::string>& examples, const std::string& done,
                           const std::vector<std::string>& more_exit_codes) {
    std::string footer = "Examples:\n";
    for (const std::string& example : examples) footer += "  " + example + "\n";
    footer += "\nExit codes:\n"
              "  0  " + done + "\n"
              "  1  bad input, or a failure while working (one line on stderr names the file and the problem)\n"
              "  2  the command line is wrong\n";
    for (const std::string& code : more_exit_codes) footer += "  " + code + "\n";
    footer.pop_back();  // CLI11 ends the help with a newline of its own
    app.footer(footer);
}

void Tool::parse() {
    app.parse(argc_, argv_);
#ifdef _OPENMP
    if (common.threads > 0) omp_set_num_threads(common.threads);
#endif
}

int run_tool(const std::string& name, int argc, char** argv, const std::function<int(Tool&)>& body) {
    const std::string program = "geotri-" + name;
    try {
        Tool tool(program, argc, argv);
        try {
            return body(tool);
        } catch (const CLI::ParseError& e) {
            if (e.get_exit_code() == 0) return tool.app.exit(e);  // --help, --version
            report(program, std::string(e.what()) + " (see --help)");
            return k_exit_usage;
        }
    } catch (const std::bad_alloc&) {
        report(program, "out of memory");
    } catch (const std::exception& e) {
        report(program, e.what());
    } catch (...) {
        report(program, "unexpected failure");
    }
    return k_exit_failure;
}

CLI::Validator number_in(double lo, double hi, bool above_lo, bool whole) {
    return CLI::Validator(
        [lo, hi, above_lo, whole](std::string& text) -> std::string {
            char* end = nullptr;
            const double value = whole ? static_cast<double>(std::strtoll(text.c_str(), &end, 10))
                                       : std::strtod(text.c_str(), &end);
            if (text.empty() || end != text.c_str() + text.size() || std::isnan(value))
                return "'" + text + "' is not " + (whole ? "a whole number" : "a number");
            if (above_lo && !(value > lo)) return text + " is not above " + format_double(lo);
            if (value < lo) return text + " is below " + format_double(lo);
            if (value > hi) return text + " is above " + format_double(hi);
            return {};
        },
        // For --help: POSITIVE or NONNEGATIVE, as CLI11 says, where only the lower end matters.
        lo == 0.0 && hi >= std::numeric_limits<int>::max()
            ? (above_lo ? "POSITIVE" : "NONNEGATIVE")
            : (above_lo ? "(" : "[") + format_double(lo) + ", " + format_double(hi) + "]");
}

void refuse_same_files(const std::vector<NamedFile>& inputs, const std::vector<NamedFile>& outputs) {
    namespace fs = std::filesystem;
    // Links resolved where the path can be; where it cannot (a folder that is not there), its plain form.
    auto resolved = [](const std::string& path) {
        std::error_code error;
        const fs::path canonical = fs::weakly_canonical(fs::absolute(path), error);
        return error ? fs::absolute(path).lexically_normal() : canonical;
    };
    auto same = [&](const std::string& a, const std::string& b) {
        std::error_code error;
        if (fs::exists(a, error) && fs::exists(b, error)) return fs::equivalent(a, b, error);
        return resolved(a) == resolved(b);
    };
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const NamedFile& out = outputs[i];
        if (out.path.empty()) continue;
        for (const NamedFile& in : inputs)
            if (!in.path.empty() && same(out.path, in.path))
                throw CLI::ValidationError(out.option + " '" + out.path + "' is the " + in.option + " '" + in.path +
                                           "': name another file, so that the input stays");
        for (std::size_t j = 0; j < i; ++j)
            if (!outputs[j].path.empty() && same(out.path, outputs[j].path))
                throw CLI::ValidationError(out.option + " and " + outputs[j].option + " name the same file '" +
                                           out.path + "'");
    }
}

CLI::Validator extension_validator(std::vector<std::string> extensions, std::string names) {
    if (names.empty()) {
        for (const std::string& e : extensions) names += (names.empty() ? "" : ", ") + e;
    }
    return CLI::Validator(
        [extensions, names](std::string& path) -> std::string {
            const std::string ext = extension_of(path);
            for (const std::string& e : extensions) {
                if (ext == e) return {};
            }
            return "'" + path + "' should end in " + names;
        },
        "");
}

double now_seconds() {
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

}  // namespace geotri::tools

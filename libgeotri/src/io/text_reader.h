#pragma once
// Private to libgeotri: reading the line-based text files that it writes (.gtri, edge paths), with messages that
// name the file and the line.

#include <geodesic/errors.h>

#include <charconv>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace geotri::detail {

/// The lines of a file held in memory, numbered from 1; blank lines and comment lines ('#' first) are skipped.
class LineReader {
public:
    LineReader(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}

    /// The next line that is not blank or a comment, without its line break (and without a trailing '\r').
    /// Throws "truncated" at the end of the file, saying what was expected.
    std::string_view next(const char* expected) {
        while (pos_ < text_.size()) {
            const std::size_t end = text_.find('\n', pos_);
            const std::size_t stop = end == std::string::npos ? text_.size() : end;
            std::string_view line(text_.data() + pos_, stop - pos_);
            pos_ = end == std::string::npos ? text_.size() : end + 1;
            ++line_number_;
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            if (line.find('\0') != std::string_view::npos) fail("holds a NUL byte: not a text file");
            if (line.empty() || line.front() == '#') continue;
            return line;
        }
        ++line_number_;
        fail(std::string("the file is truncated: expected ") + expected);
    }

    bool at_end() {
        while (pos_ < text_.size()) {
            const std::size_t end = text_.find('\n', pos_);
            const std::size_t stop = end == std::string::npos ? text_.size() : end;
            std::string_view line(text_.data() + pos_, stop - pos_);
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            if (!line.empty() && line.front() != '#') return false;
            pos_ = end == std::string::npos ? text_.size() : end + 1;
            ++line_number_;
        }
        return true;
    }

    int line_number() const { return line_number_; }
    /// Bytes after the last line returned: what the rest of the file can still hold.
    std::size_t bytes_left() const { return text_.size() - pos_; }
    const std::string& path() const { return path_; }

    [[noreturn]] void fail(const std::string& what) const { fail_at(line_number_, what); }
    [[noreturn]] void fail_at(int line, const std::string& what) const {
        throw IOError(path_ + ": line " + std::to_string(line) + ": " + what);
    }

private:
    std::string path_;
    std::string text_;
    std::size_t pos_ = 0;
    int line_number_ = 0;
};

/// Splits on runs of spaces and tabs.
inline std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

inline std::string quoted(std::string_view text) {
    constexpr std::size_t k_shown = 60;
    return "'" + std::string(text.substr(0, k_shown)) + (text.size() > k_shown ? "...'" : "'");
}

inline bool parse_int(std::string_view text, long long& value) {
    if (text.empty() || text.front() == '+') return false;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
    return r.ec == std::errc() && r.ptr == text.data() + text.size();
}

/// A count or an index: a non-negative int.
inline int parse_count(const LineReader& in, std::string_view text, const char* what) {
    long long value = 0;
    if (!parse_int(text, value) || value < 0 || value > 2147483647LL)
        in.fail("bad " + std::string(what) + " " + quoted(text) + " (expected a non-negative integer)");
    return static_cast<int>(value);
}

/// The whole file. Throws IOError("PATH: problem") when it cannot be read or is empty.
std::string read_text(const std::string& path);

}  // namespace geotri::detail

#pragma once
// Private to libgeotri: the pieces shared by the exact mesh readers in read_*.cpp and the writers in mesh_io.cpp and
// overlay_io.cpp. tools/common uses extension_of() too.

#include <geodesic/errors.h>
#include <geotri/mesh_io.h>

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

namespace geotri::detail {

/// Throws IOError("PATH: problem").
[[noreturn]] inline void fail(const std::string& path, const std::string& problem) {
    throw IOError(path + ": " + problem);
}

/// The whole file in memory. Throws IOError when it cannot be opened or read.
std::string read_file(const std::string& path);

// One reader per format. Each receives the path (for messages) and the file's bytes (not empty).
MeshData read_stl(const std::string& path, std::string_view bytes);
MeshData read_off(const std::string& path, std::string_view bytes);
MeshData read_obj(const std::string& path, std::string_view bytes);
MeshData read_ply(const std::string& path, std::string_view bytes);

/// Checks the triangles against the vertex count and every coordinate for NaN and infinity; throws IOError.
void check_mesh(const std::string& path, const MeshData& mesh);

// ---- Text scanning --------------------------------------------------------------------------------------------

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Walks a buffer line by line and counts lines (from 1) for error messages.
class LineReader {
public:
    explicit LineReader(std::string_view text) : text_(text) {}

    /// The next line without its end-of-line characters; false at the end of the text.
    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        const std::size_t end = text_.find('\n', pos_);
        const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
        line = text_.substr(pos_, stop - pos_);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos_ = stop + 1;
        ++line_number_;
        return true;
    }
    int line_number() const { return line_number_; }
    /// Bytes not yet returned.
    std::size_t offset() const { return pos_; }

private:
    std::string_view text_;
    std::size_t pos_ = 0;
    int line_number_ = 0;
};

inline void skip_spaces(std::string_view& s) {
    std::size_t i = 0;
    while (i < s.size() && is_space(s[i])) ++i;
    s.remove_prefix(i);
}

/// The next whitespace-separated token (empty at the end), removed from s.
inline std::string_view next_token(std::string_view& s) {
    skip_spaces(s);
    std::size_t i = 0;
    while (i < s.size() && !is_space(s[i])) ++i;
    const std::string_view token = s.substr(0, i);
    s.remove_prefix(i);
    return token;
}

/// Parses a decimal number at the start of s into the nearest value of T (std::from_chars rounds correctly),
/// accepting a leading '+'. On success removes it from s. "nan" and "inf" parse, so that callers can name them.
template <typename T>
bool parse_real(std::string_view& s, T& value) {
    const char* first = s.data();
    const char* last = s.data() + s.size();
    if (first != last && *first == '+') ++first;
    const std::from_chars_result r = std::from_chars(first, last, value);
    if (r.ec == std::errc::result_out_of_range) {
        // from_chars leaves the value alone beyond the range; strtod rounds to +-inf, zero or a subnormal.
        const std::string digits(first, r.ptr);
        if constexpr (std::is_same_v<T, float>) {
            value = std::strtof(digits.c_str(), nullptr);
        } else {
            value = std::strtod(digits.c_str(), nullptr);
        }
    } else if (r.ec != std::errc()) {
        return false;
    }
    s.remove_prefix(static_cast<std::size_t>(r.ptr - s.data()));
    return true;
}

/// Like parse_real, for a whitespace-terminated real token: "1.5x" fails.
template <typename T>
bool parse_real_token(std::string_view& s, T& value) {
    skip_spaces(s);
    if (!parse_real(s, value)) return false;
    return s.empty() || is_space(s.front());
}

/// A decimal integer at the start of s (leading '+' or '-' allowed); removes it from s.
template <typename T>
bool parse_integer(std::string_view& s, T& value) {
    const char* first = s.data();
    const char* last = s.data() + s.size();
    if (first != last && *first == '+') ++first;
    const std::from_chars_result r = std::from_chars(first, last, value);
    if (r.ec != std::errc()) return false;
    s.remove_prefix(static_cast<std::size_t>(r.ptr - s.data()));
    return true;
}

template <typename T>
bool parse_integer_token(std::string_view& s, T& value) {
    skip_spaces(s);
    if (!parse_integer(s, value)) return false;
    return s.empty() || is_space(s.front());
}

/// Lower-case extension with its dot (".ply"), or empty.
std::string extension_of(const std::string& path);

// ---- Text output ----------------------------------------------------------------------------------------------

class AtomicFile;

/// Writes one line "PREFIX x y z" per point, each coordinate as AtomicFile::write_double writes it.
void write_point_lines(AtomicFile& out, std::string_view prefix, const std::vector<Eigen::Vector3d>& points);

// ---- Binary values --------------------------------------------------------------------------------------------

inline bool host_is_little_endian() {
    const std::uint16_t probe = 1;
    unsigned char first = 0;
    std::memcpy(&first, &probe, 1);
    return first == 1;
}

}  // namespace geotri::detail

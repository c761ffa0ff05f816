#include "output.h"

#include <geodesic/errors.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>

#include <unistd.h>

namespace geotri::tools {

namespace {

std::string temporary_name_for(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const std::size_t slash = path.find_last_of('/');
    const std::string folder = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    return folder + "." + name + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

std::string json_string(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\t': out += "\\t"; break;
            case '\r': out += "\\r"; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char escaped[8];
                    std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
                    out += escaped;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& write) {
    const std::string temp = temporary_name_for(path);
    std::FILE* file = std::fopen(temp.c_str(), "wbx");
    if (file == nullptr) throw IOError(path + ": cannot write: " + std::strerror(errno));
    try {
        write(file);
    } catch (...) {
        std::fclose(file);
        std::remove(temp.c_str());
        throw;
    }
    const bool written = std::fflush(file) == 0 && std::ferror(file) == 0;
    const int write_error = errno;
    const bool closed = std::fclose(file) == 0;
    const int close_error = errno;
    if (!written || !closed) {
        std::remove(temp.c_str());
        throw IOError(path + ": cannot write: " + std::strerror(written ? close_error : write_error));
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const int rename_error = errno;
        std::remove(temp.c_str());
        throw IOError(path + ": cannot replace the file: " + std::strerror(rename_error));
    }
}

std::string extension_of(const std::string& path) {
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

std::string format_double(double value) {
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

void JsonSummary::add_raw(const std::string& key, std::string json) { fields_.emplace_back(key, std::move(json)); }

void JsonSummary::add(const std::string& key, const std::string& value) { add_raw(key, json_string(value)); }

void JsonSummary::add(const std::string& key, double value) {
    add_raw(key, std::isfinite(value) ? format_double(value) : "null");
}

void JsonSummary::add(const std::string& key, long long value) { add_raw(key, std::to_string(value)); }

void JsonSummary::add(const std::string& key, bool value) { add_raw(key, value ? "true" : "false"); }

std::string JsonSummary::str() const {
    std::string out = "{";
    for (std::size_t i = 0; i < fields_.size(); ++i) {
        if (i > 0) out += ", ";
        out += json_string(fields_[i].first) + ": " + fields_[i].second;
    }
    return out + "}";
}

}  // namespace geotri::tools

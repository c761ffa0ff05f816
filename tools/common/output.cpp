#include "output.h"

// Private headers of libgeotri (see tools/CMakeLists.txt).
#include "io/atomic_file.h"
#include "io/mesh_io_detail.h"

#include <geodesic/errors.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

namespace geotri::tools {

namespace {

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
    // If `write` throws, AtomicFile's destructor removes the temporary file.
    detail::AtomicFile file(path);
    write(file.stream());
    file.commit();
}

StagedOutputs::~StagedOutputs() {
    for (const auto& [temporary, path] : staged_) std::remove(temporary.c_str());
}

void StagedOutputs::write(const std::string& path, const std::function<void(const std::string&)>& writer) {
    // The renames of commit() come one after another: what would make one fail is refused before anything is written.
    std::error_code error;
    if (std::filesystem::is_directory(path, error) || (!path.empty() && path.back() == '/'))
        throw IOError(path + ": cannot write: it is a folder");
    // The extension stays last: it chooses the format.
    const std::string temporary = detail::temporary_name_for(path, extension_of(path));
    staged_.emplace_back(temporary, path);
    try {
        writer(temporary);
    } catch (const Error& failure) {
        std::string message = failure.what();
        for (std::size_t at = message.find(temporary); at != std::string::npos; at = message.find(temporary, at))
            message.replace(at, temporary.size(), path);
        throw IOError(message);
    }
}

void StagedOutputs::commit() {
    for (auto it = staged_.begin(); it != staged_.end(); it = staged_.erase(it))
        if (std::rename(it->first.c_str(), it->second.c_str()) != 0)
            throw IOError(it->second + ": cannot write: " + std::strerror(errno));
}

std::string extension_of(const std::string& path) { return detail::extension_of(path); }

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

void JsonSummary::add(const std::string& key, const std::vector<JsonSummary>& objects) {
    std::string array = "[";
    for (std::size_t i = 0; i < objects.size(); ++i) array += (i > 0 ? ", " : "") + objects[i].str();
    add_raw(key, array + "]");
}

std::string JsonSummary::str() const {
    std::string out = "{";
    for (std::size_t i = 0; i < fields_.size(); ++i) {
        if (i > 0) out += ", ";
        out += json_string(fields_[i].first) + ": " + fields_[i].second;
    }
    return out + "}";
}

void add_corner_angles(JsonSummary& summary, const CornerAngleStats& before, const CornerAngleStats& after) {
    for (const auto& [stats, suffix] : {std::pair{&before, "_before"}, std::pair{&after, ""}}) {
        summary.add(std::string("min_corner_angle_deg") + suffix, stats->min_deg);
        summary.add(std::string("mean_corner_angle_deg") + suffix, stats->mean_deg);
        summary.add(std::string("max_corner_angle_deg") + suffix, stats->max_deg);
    }
}

}  // namespace geotri::tools

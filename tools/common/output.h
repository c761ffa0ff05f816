#pragma once
// Output for the tools: files that appear only when complete, and the --json summary.

#include <geotri/flip_to_delaunay.h>

#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace geotri::tools {

/// Calls `write` on a temporary file in the folder of `path`, then renames it to `path`. If `write` throws or
/// anything fails, the temporary file is removed and nothing appears under `path` (an older file there stays).
/// Throws geotri::IOError("PATH: problem").
void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& write);

/// A tool's outputs, which appear together or not at all: each is written under a temporary name in its own folder
/// (with its extension, which chooses the format), and commit() renames them all once every one is written. If a
/// write throws, or commit() is never reached, none appears, older files under those names stay, and the temporary
/// files are removed. An output that names a folder is refused before anything is written, since its rename would
/// fail after the others'.
class StagedOutputs {
public:
    StagedOutputs() = default;
    StagedOutputs(const StagedOutputs&) = delete;
    StagedOutputs& operator=(const StagedOutputs&) = delete;
    ~StagedOutputs();

    /// Calls `writer` with a temporary path for `path`. Its geotri::Error, which names the temporary path, is thrown
    /// again as an IOError with `path` in its place.
    void write(const std::string& path, const std::function<void(const std::string&)>& writer);
    /// Renames every temporary file to its name. Throws geotri::IOError("PATH: problem").
    void commit();

private:
    std::vector<std::pair<std::string, std::string>> staged_;  ///< (temporary path, path)
};

/// Lower-case extension of a path with its dot (".ply"), or empty.
std::string extension_of(const std::string& path);

/// A JSON object, written on one line in the order of the calls: values, and arrays of such objects.
class JsonSummary {
public:
    void add(const std::string& key, const std::string& value);
    void add(const std::string& key, const char* value) { add(key, std::string(value)); }
    /// Non-finite values become null.
    void add(const std::string& key, double value);
    void add(const std::string& key, long long value);
    void add(const std::string& key, std::size_t value) { add(key, static_cast<long long>(value)); }
    void add(const std::string& key, int value) { add(key, static_cast<long long>(value)); }
    void add(const std::string& key, bool value);
    void add(const std::string& key, const std::vector<JsonSummary>& objects);

    std::string str() const;

private:
    void add_raw(const std::string& key, std::string json);
    std::vector<std::pair<std::string, std::string>> fields_;
};

/// The minimum, mean and maximum corner angles before and after an operation, as min_corner_angle_deg_before, ...,
/// min_corner_angle_deg, ...: the keys that geotri-flip and geotri-refine share.
void add_corner_angles(JsonSummary& summary, const CornerAngleStats& before, const CornerAngleStats& after);

/// "%.17g", which reads back as the same double; "inf" and "-inf" for infinities.
std::string format_double(double value);

}  // namespace geotri::tools

#pragma once
// Private to libgeotri (and to tools/common, which writes the tools' files with it): an output file that appears
// under its name only once it is complete.

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace geotri::detail {

/// A hidden name in the folder of `path`, unique within this process and among processes, ending in `extension`.
std::string temporary_name_for(const std::string& path, const std::string& extension = "");

/// Writes to a temporary file in the target's folder and renames it over the target on commit(). If commit() is
/// never reached (an exception, an early return), the destructor removes the temporary file, so that no partial
/// output is ever left under either name. Writes are buffered. Every failure throws IOError("PATH: problem").
class AtomicFile {
public:
    explicit AtomicFile(std::string path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    void write(const void* data, std::size_t size);
    void write(std::string_view text) { write(text.data(), text.size()); }
    /// Appends `value` as printf's "%.17g" would, which reads back as the same double.
    void write_double(double value);
    void write_int(long long value);
    /// The open temporary file, for printf-style writing, after the buffered writes have gone to it. Valid until
    /// commit(); writes through it and through write() may be mixed and keep their order.
    std::FILE* stream();

    /// Flushes, closes and renames the temporary file over the target.
    void commit();

    const std::string& path() const { return path_; }

private:
    void flush();
    [[noreturn]] void fail(const std::string& what, int error);

    std::string path_;
    std::string temp_path_;
    std::FILE* file_ = nullptr;
    std::string buffer_;
};

}  // namespace geotri::detail

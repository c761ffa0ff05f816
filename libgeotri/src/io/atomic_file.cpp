#include "io/atomic_file.h"

#include <geodesic/errors.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>

#include <unistd.h>

namespace geotri::detail {

namespace {

constexpr std::size_t k_buffer_size = 1 << 20;

}  // namespace

std::string temporary_name_for(const std::string& path, const std::string& extension) {
    static std::atomic<unsigned> counter{0};
    const std::size_t slash = path.find_last_of('/');
    const std::string folder = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    // Hidden, and unique within this process and among processes.
    return folder + "." + name + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + extension;
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), temp_path_(temporary_name_for(path_)) {
    // "x": never reuse an existing file under the temporary name.
    file_ = std::fopen(temp_path_.c_str(), "wbx");
    if (file_ == nullptr) throw IOError(path_ + ": cannot write: " + std::strerror(errno));
    buffer_.reserve(k_buffer_size);
}

AtomicFile::~AtomicFile() {
    if (file_ != nullptr) {
        std::fclose(file_);
        std::remove(temp_path_.c_str());
    }
}

void AtomicFile::fail(const std::string& what, int error) {
    std::string message = path_ + ": " + what;
    if (error != 0) message += std::string(": ") + std::strerror(error);
    throw IOError(message);
}

void AtomicFile::write(const void* data, std::size_t size) {
    if (buffer_.size() + size > k_buffer_size) flush();
    if (size >= k_buffer_size) {
        if (std::fwrite(data, 1, size, file_) != size) fail("cannot write", errno);
        return;
    }
    buffer_.append(static_cast<const char*>(data), size);
}

void AtomicFile::write_double(double value) {
    char text[32];
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, value, std::chars_format::general, 17);
    write(text, static_cast<std::size_t>(r.ptr - text));
}

void AtomicFile::write_int(long long value) {
    char text[24];
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, value);
    write(text, static_cast<std::size_t>(r.ptr - text));
}

std::FILE* AtomicFile::stream() {
    flush();
    return file_;
}

void AtomicFile::flush() {
    if (!buffer_.empty() && std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) {
        fail("cannot write", errno);
    }
    buffer_.clear();
}

void AtomicFile::commit() {
    flush();
    std::FILE* file = file_;
    file_ = nullptr;
    const bool written = std::fflush(file) == 0 && std::ferror(file) == 0;
    const int write_error = errno;
    const bool closed = std::fclose(file) == 0;
    const int close_error = errno;
    if (!written || !closed) {
        std::remove(temp_path_.c_str());
        fail("cannot write", written ? close_error : write_error);
    }
    if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
        const int rename_error = errno;
        std::remove(temp_path_.c_str());
        fail("cannot replace the file", rename_error);
    }
}

}  // namespace geotri::detail

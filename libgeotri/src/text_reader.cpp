#include "text_reader.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace geotri::detail {

std::string read_text(const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) throw IOError(path + ": cannot read: " + std::strerror(errno));
    std::string text;
    char buffer[1 << 16];
    std::size_t got;
    while ((got = std::fread(buffer, 1, sizeof buffer, file)) > 0) text.append(buffer, got);
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed) throw IOError(path + ": cannot read");
    if (text.empty()) throw IOError(path + ": the file is empty");
    return text;
}

}  // namespace geotri::detail

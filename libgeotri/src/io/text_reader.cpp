#include "io/text_reader.h"

namespace geotri::detail {

// mesh_io.cpp's reader of whole files, declared in mesh_io_detail.h, whose LineReader is another class than ours.
std::string read_file(const std::string& path);

std::string read_text(const std::string& path) {
    std::string text = read_file(path);  // refuses folders and devices, which could never end
    if (text.empty()) throw IOError(path + ": the file is empty");
    return text;
}

}  // namespace geotri::detail

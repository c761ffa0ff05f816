// PLY: ascii, binary_little_endian and binary_big_endian. The vertex element's x, y and z (any numeric type) and
// the face element's vertex_indices (or vertex_index) list are read; every other property and element is skipped.
// float32 values widen exactly to double; an ASCII value of a float property is read as the float it stands for.

#include "io/mesh_io_detail.h"

#include <cstring>

namespace geotri::detail {

namespace {

enum class Type : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool parse_type(std::string_view name, Type& type) {
    static const std::pair<std::string_view, Type> names[] = {
        {"char", Type::int8},     {"int8", Type::int8},       {"uchar", Type::uint8},    {"uint8", Type::uint8},
        {"short", Type::int16},   {"int16", Type::int16},     {"ushort", Type::uint16},  {"uint16", Type::uint16},
        {"int", Type::int32},     {"int32", Type::int32},     {"uint", Type::uint32},    {"uint32", Type::uint32},
        {"float", Type::float32}, {"float32", Type::float32}, {"double", Type::float64}, {"float64", Type::float64}};
    for (const auto& [n, t] : names) {
        if (n == name) {
            type = t;
            return true;
        }
    }
    return false;
}

std::size_t size_of(Type type) {
    switch (type) {
        case Type::int8:
        case Type::uint8: return 1;
        case Type::int16:
        case Type::uint16: return 2;
        case Type::int32:
        case Type::uint32:
        case Type::float32: return 4;
        case Type::float64: return 8;
    }
    return 0;
}

bool is_integral(Type type) { return type != Type::float32 && type != Type::float64; }

struct Property {
    std::string name;
    bool is_list = false;
    Type count_type = Type::uint8;  ///< lists only
    Type type = Type::float32;      ///< the value type, or the item type of a list
};

struct Element {
    std::string name;
    std::size_t count = 0;
    std::vector<Property> properties;

    bool has_lists() const {
        for (const Property& p : properties) {
            if (p.is_list) return true;
        }
        return false;
    }
    std::size_t row_size() const {
        std::size_t size = 0;
        for (const Property& p : properties) size += size_of(p.type);
        return size;
    }
};

enum class Format { ascii, binary_little_endian, binary_big_endian };

struct Header {
    Format format = Format::ascii;
    std::vector<Element> elements;
    std::size_t data_offset = 0;
};

Header read_header(const std::string& path, std::string_view bytes) {
    LineReader lines(bytes);
    std::string_view line;
    if (!lines.next(line) || line != "ply") fail(path, "not a PLY file (no 'ply' on the first line)");
    Header header;
    bool has_format = false;
    auto malformed = [&](const std::string& why) {
        fail(path, "malformed header line " + std::to_string(lines.line_number()) + " (" + why + ")");
    };
    while (true) {
        if (!lines.next(line)) fail(path, "truncated header (no 'end_header')");
        std::string_view rest = line;
        const std::string_view keyword = next_token(rest);
        if (keyword == "end_header") break;
        if (lines.offset() > bytes.size()) fail(path, "truncated header (no 'end_header')");
        if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "format") {
            const std::string_view format = next_token(rest);
            if (format == "ascii") {
                header.format = Format::ascii;
            } else if (format == "binary_little_endian") {
                header.format = Format::binary_little_endian;
            } else if (format == "binary_big_endian") {
                header.format = Format::binary_big_endian;
            } else {
                malformed("unknown format '" + std::string(format) + "'");
            }
            has_format = true;
        } else if (keyword == "element") {
            Element element;
            element.name = std::string(next_token(rest));
            unsigned long long count = 0;
            if (element.name.empty() || !parse_integer_token(rest, count)) malformed("expected 'element NAME COUNT'");
            element.count = static_cast<std::size_t>(count);
            header.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header.elements.empty()) malformed("property before any element");
            Property property;
            std::string_view type = next_token(rest);
            if (type == "list") {
                property.is_list = true;
                const std::string_view count_type = next_token(rest);
                if (!parse_type(count_type, property.count_type) || !is_integral(property.count_type)) {
                    malformed("bad list count type '" + std::string(count_type) + "'");
                }
                type = next_token(rest);
            }
            if (!parse_type(type, property.type)) malformed("unknown property type '" + std::string(type) + "'");
            property.name = std::string(next_token(rest));
            if (property.name.empty()) malformed("property without a name");
            header.elements.back().properties.push_back(std::move(property));
        } else {
            malformed("unknown keyword '" + std::string(keyword.substr(0, 32)) + "'");
        }
    }
    if (!has_format) fail(path, "malformed PLY header (no 'format' line)");
    header.data_offset = lines.offset();
    return header;
}

/// Reads binary values, checking every read against the end of the data.
class BinaryCursor {
public:
    BinaryCursor(const std::string& path, std::string_view data, bool swap)
        : path_(path), p_(reinterpret_cast<const unsigned char*>(data.data())), end_(p_ + data.size()), swap_(swap) {}

    void locate(const Element& element, std::size_t item) {
        element_ = &element;
        item_ = item;
    }

    double real(Type type) {
        // Every integer type has at most 32 bits, so its value converts to double exactly.
        if (is_integral(type)) return static_cast<double>(integer(type));
        need(size_of(type));
        double value = 0.0;
        if (type == Type::float32) {
            const std::uint32_t bits = load<std::uint32_t>();
            float f = 0.0f;
            std::memcpy(&f, &bits, sizeof f);
            value = f;
        } else {
            const std::uint64_t bits = load<std::uint64_t>();
            std::memcpy(&value, &bits, sizeof value);
        }
        p_ += size_of(type);
        return value;
    }

    long long integer(Type type) {
        need(size_of(type));
        long long value = 0;
        switch (type) {
            case Type::int8: value = static_cast<std::int8_t>(*p_); break;
            case Type::uint8: value = *p_; break;
            case Type::int16: value = static_cast<std::int16_t>(load<std::uint16_t>()); break;
            case Type::uint16: value = load<std::uint16_t>(); break;
            case Type::int32: value = static_cast<std::int32_t>(load<std::uint32_t>()); break;
            case Type::uint32: value = load<std::uint32_t>(); break;
            case Type::float32:
            case Type::float64: break;  // refused by the caller
        }
        p_ += size_of(type);
        return value;
    }

    void skip(Type type, std::size_t count = 1) {
        need(size_of(type) * count);
        p_ += size_of(type) * count;
    }

    /// Skips `count` items of an element without lists in one step.
    void skip_rows(const Element& element) {
        locate(element, 0);
        const std::size_t row = element.row_size();
        if (row != 0 && element.count > static_cast<std::size_t>(end_ - p_) / row) truncated();
        p_ += row * element.count;
    }

    std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }

    [[noreturn]] void truncated() const {
        fail(path_, "truncated: the data ends in element '" + element_->name + "' " + std::to_string(item_) + " of " +
                        std::to_string(element_->count));
    }
    [[noreturn]] void bad(const std::string& what) const {
        fail(path_, "element '" + element_->name + "' " + std::to_string(item_) + ": " + what);
    }

private:
    template <typename U>
    U load() const {
        U value = 0;
        std::memcpy(&value, p_, sizeof value);
        if (swap_) {
            U swapped = 0;
            for (std::size_t i = 0; i < sizeof(U); ++i) swapped = static_cast<U>((swapped << 8) | ((value >> (8 * i)) & 0xFF));
            value = swapped;
        }
        return value;
    }
    void need(std::size_t size) const {
        if (static_cast<std::size_t>(end_ - p_) < size) truncated();
    }

    const std::string& path_;
    const unsigned char* p_;
    const unsigned char* end_;
    bool swap_;
    const Element* element_ = nullptr;
    std::size_t item_ = 0;
};

/// Reads whitespace-separated ASCII values, counting lines for error messages.
class AsciiCursor {
public:
    AsciiCursor(const std::string& path, std::string_view data, int first_line)
        : path_(path), rest_(data), line_(first_line) {}

    void locate(const Element& element, std::size_t item) {
        element_ = &element;
        item_ = item;
    }

    double real(Type type) {
        std::string_view token = next();
        bool ok = false;
        double value = 0.0;
        if (type == Type::float32) {
            float f = 0.0f;
            ok = parse_real(token, f);
            value = f;
        } else if (type == Type::float64) {
            ok = parse_real(token, value);
        } else {
            long long i = 0;
            ok = parse_integer(token, i);
            value = static_cast<double>(i);
        }
        if (!ok || !token.empty()) malformed();
        return value;
    }

    long long integer(Type) {
        std::string_view token = next();
        long long value = 0;
        if (!parse_integer(token, value) || !token.empty()) malformed();
        return value;
    }

    void skip(Type, std::size_t count = 1) {
        for (std::size_t i = 0; i < count; ++i) next();
    }

    void skip_rows(const Element& element) {
        for (std::size_t item = 0; item < element.count; ++item) {
            locate(element, item);
            skip(Type::uint8, element.properties.size());
        }
    }

    std::size_t remaining() const { return rest_.size(); }
    /// Whether anything but white space follows the last element: a count in the header that is too small.
    bool data_left() const { return rest_.find_first_not_of(" \t\r\n") != std::string_view::npos; }

    [[noreturn]] void truncated() const {
        fail(path_, "truncated: the data ends in element '" + element_->name + "' " + std::to_string(item_) + " of " +
                        std::to_string(element_->count));
    }
    [[noreturn]] void bad(const std::string& what) const {
        fail(path_, "malformed line " + std::to_string(line_) + " (element '" + element_->name + "' " +
                        std::to_string(item_) + ": " + what + ")");
    }

private:
    std::string_view next() {
        std::size_t i = 0;
        while (i < rest_.size() && (is_space(rest_[i]) || rest_[i] == '\n')) {
            if (rest_[i] == '\n') ++line_;
            ++i;
        }
        std::size_t j = i;
        while (j < rest_.size() && !is_space(rest_[j]) && rest_[j] != '\n') ++j;
        if (j == i) truncated();
        token_ = rest_.substr(i, j - i);
        rest_.remove_prefix(j);
        return token_;
    }
    [[noreturn]] void malformed() const {
        fail(path_, "malformed line " + std::to_string(line_) + " ('" + std::string(token_.substr(0, 32)) +
                        "' is not a valid value in element '" + element_->name + "' " + std::to_string(item_) + ")");
    }

    const std::string& path_;
    std::string_view rest_;
    std::string_view token_;
    int line_;
    const Element* element_ = nullptr;
    std::size_t item_ = 0;
};

template <typename Cursor>
void skip_property(Cursor& in, const Property& property) {
    if (property.is_list) {
        const long long count = in.integer(property.count_type);
        if (count < 0) in.bad("negative list length");
        in.skip(property.type, static_cast<std::size_t>(count));
    } else {
        in.skip(property.type);
    }
}

template <typename Cursor>
MeshData read_elements(const std::string& path, const Header& header, Cursor& in) {
    MeshData mesh;
    bool has_vertices = false;
    bool has_faces = false;
    long long num_vertices = -1;  // unknown until the vertex element is read
    for (const Element& element : header.elements) {
        if (element.name == "vertex") {
            std::vector<int> axis_of(element.properties.size(), -1);  // 0, 1, 2 for x, y, z; -1 to skip
            int found = 0;
            for (std::size_t i = 0; i < element.properties.size(); ++i) {
                const Property& p = element.properties[i];
                const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
                axis_of[i] = p.is_list ? -1 : axis;
                if (axis_of[i] >= 0) found |= 1 << axis;
            }
            if (found != 7) fail(path, "the vertex element lacks an x, y or z property");
            if (element.count > static_cast<std::size_t>(std::numeric_limits<int>::max())) fail(path, "too many vertices");
            in.locate(element, 0);
            if (element.count > in.remaining()) in.truncated();
            mesh.positions.resize(element.count);
            for (std::size_t v = 0; v < element.count; ++v) {
                in.locate(element, v);
                Eigen::Vector3d& position = mesh.positions[v];
                for (std::size_t i = 0; i < element.properties.size(); ++i) {
                    if (axis_of[i] >= 0) {
                        position[axis_of[i]] = in.real(element.properties[i].type);
                    } else {
                        skip_property(in, element.properties[i]);
                    }
                }
            }
            has_vertices = true;
            num_vertices = static_cast<long long>(element.count);
        } else if (element.name == "face") {
            int indices = -1;
            for (std::size_t i = 0; i < element.properties.size(); ++i) {
                const Property& p = element.properties[i];
                if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) indices = static_cast<int>(i);
            }
            if (indices < 0) fail(path, "the face element has no vertex_indices list");
            const Property& list = element.properties[static_cast<std::size_t>(indices)];
            if (!is_integral(list.type)) fail(path, "the face vertex_indices list is not of an integer type");
            if (element.count > static_cast<std::size_t>(std::numeric_limits<int>::max())) fail(path, "too many faces");
            in.locate(element, 0);
            if (element.count > in.remaining()) in.truncated();
            const long long limit = num_vertices >= 0 ? num_vertices : std::numeric_limits<int>::max();
            mesh.triangles.resize(element.count);
            for (std::size_t f = 0; f < element.count; ++f) {
                in.locate(element, f);
                for (std::size_t i = 0; i < element.properties.size(); ++i) {
                    if (static_cast<int>(i) != indices) {
                        skip_property(in, element.properties[i]);
                        continue;
                    }
                    const long long corners = in.integer(list.count_type);
                    if (corners != 3) {
                        if (corners < 0) in.bad("negative list length");
                        fail(path, "face " + std::to_string(f) + " has " + std::to_string(corners) +
                                       " vertices; only triangles are supported");
                    }
                    for (int& v : mesh.triangles[f]) {
                        const long long index = in.integer(list.type);
                        if (index < 0 || index >= limit) {
                            fail(path, "face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                                           ", out of range (" + std::to_string(limit) + " vertices)");
                        }
                        v = static_cast<int>(index);
                    }
                }
            }
            has_faces = true;
        } else if (element.has_lists()) {
            for (std::size_t item = 0; item < element.count; ++item) {
                in.locate(element, item);
                for (const Property& p : element.properties) skip_property(in, p);
            }
        } else {
            in.skip_rows(element);
        }
    }
    if (!has_vertices) fail(path, "no vertex element");
    if (!has_faces || mesh.triangles.empty()) fail(path, "no faces");
    return mesh;
}

}  // namespace

MeshData read_ply(const std::string& path, std::string_view bytes) {
    const Header header = read_header(path, bytes);
    const std::string_view data = bytes.substr(header.data_offset);
    if (header.format == Format::ascii) {
        int header_lines = 0;
        for (std::size_t i = 0; i < header.data_offset; ++i) header_lines += bytes[i] == '\n';
        AsciiCursor in(path, data, header_lines + 1);
        MeshData mesh = read_elements(path, header, in);
        // (A binary file's extra bytes are left alone: some writers pad.)
        if (in.data_left()) fail(path, "data follows the elements that the header announces (is a count wrong?)");
        return mesh;
    }
    const bool little = header.format == Format::binary_little_endian;
    BinaryCursor in(path, data, little != host_is_little_endian());
    return read_elements(path, header, in);
}

}  // namespace geotri::detail

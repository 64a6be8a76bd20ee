// PLY reader: header, then ascii tokens or binary records, every count and
// index checked against the header and the bytes that are really there.
#include <magFoam/MeshFormats.hpp>

#include <magFoam/Error.hpp>

#include "MeshNumerics.hpp"
#include "MeshText.hpp"

#include <bit>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

namespace mag {

namespace {

using meshText::parseInteger;
using meshText::parseNumber;

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class Format { Ascii, LittleEndian, BigEndian };

std::optional<Type> typeNamed(std::string_view w) {
    if (w == "char" || w == "int8") return Type::Int8;
    if (w == "uchar" || w == "uint8") return Type::UInt8;
    if (w == "short" || w == "int16") return Type::Int16;
    if (w == "ushort" || w == "uint16") return Type::UInt16;
    if (w == "int" || w == "int32") return Type::Int32;
    if (w == "uint" || w == "uint32") return Type::UInt32;
    if (w == "float" || w == "float32") return Type::Float32;
    if (w == "double" || w == "float64") return Type::Float64;
    return std::nullopt;
}

std::size_t sizeOf(Type t) {
    switch (t) {
    case Type::Int8:
    case Type::UInt8: return 1;
    case Type::Int16:
    case Type::UInt16: return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32: return 4;
    case Type::Float64: return 8;
    }
    return 1;
}

struct Property {
    std::string name;
    bool list = false;
    Type countType = Type::UInt8;
    Type type = Type::Float32;
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    int line = 0;  // of its 'element' header line
    std::vector<Property> properties;
};

std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && meshText::isSpace(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !meshText::isSpace(line[i])) ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

// Whole numbers (counts, indices) in full, others as %g.
std::string numberText(double x) {
    if (x == std::floor(x) && std::abs(x) < 1e18) return std::to_string(static_cast<long long>(x));
    return meshDetail::formatNumber(x);
}

using meshText::quoted;

class PlyReader {
public:
    PlyReader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

    ParsedMesh read() {
        readHeader();
        checkSizes();
        ParsedMesh out;
        out.mesh.source = name_;
        out_ = &out;
        meshText::TokenCursor cursor(bytes_, dataStart_, dataLine_);
        cursor_ = &cursor;
        pos_ = dataStart_;
        for (const Element& e : elements_) readElement(e);
        return out;
    }

private:
    [[noreturn]] void headerError(int line, const std::string& message) const {
        throw InputError(name_ + ":" + std::to_string(line) + ": PLY header: " + message);
    }

    void readHeader() {
        std::size_t pos = 0;
        int line = 0;
        bool haveFormat = false;
        for (;;) {
            if (pos >= bytes_.size())
                headerError(line, "the header has no 'end_header' line (the file ends in the header)");
            const std::size_t eol = bytes_.find('\n', pos);
            const std::size_t end = eol == std::string_view::npos ? bytes_.size() : eol;
            const std::string_view text = bytes_.substr(pos, end - pos);
            pos = eol == std::string_view::npos ? bytes_.size() : eol + 1;
            ++line;
            const auto w = words(text);
            if (line == 1) {
                if (w.size() != 1 || w[0] != "ply") headerError(1, "expected 'ply' on the first line, got " + quoted(text));
                continue;
            }
            if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
            if (w[0] == "end_header") {
                if (!haveFormat) headerError(line, "no 'format' line before 'end_header'");
                dataStart_ = pos;
                dataLine_ = line + 1;
                return;
            }
            if (w[0] == "format") {
                if (w.size() != 3) headerError(line, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
                if (w[1] == "ascii") format_ = Format::Ascii;
                else if (w[1] == "binary_little_endian") format_ = Format::LittleEndian;
                else if (w[1] == "binary_big_endian") format_ = Format::BigEndian;
                else headerError(line, "unknown format " + quoted(w[1]) + "; expected ascii, binary_little_endian or binary_big_endian");
                haveFormat = true;
            } else if (w[0] == "element") {
                std::int64_t count = 0;
                if (w.size() != 3 || !parseInteger(w[2], 0, std::numeric_limits<int>::max(), count))
                    headerError(line, "expected 'element NAME COUNT' with a COUNT from 0 to 2147483647, got " + quoted(text));
                elements_.push_back({std::string(w[1]), static_cast<std::uint64_t>(count), line, {}});
            } else if (w[0] == "property") {
                if (elements_.empty()) headerError(line, "a 'property' line before any 'element' line");
                Property p;
                if (w.size() == 5 && w[1] == "list") {
                    const auto count = typeNamed(w[2]), item = typeNamed(w[3]);
                    if (!count || !item) headerError(line, "unknown type in " + quoted(text));
                    if (*count == Type::Float32 || *count == Type::Float64)
                        headerError(line, "a list count must have an integer type, got " + quoted(w[2]));
                    p = {std::string(w[4]), true, *count, *item};
                } else if (w.size() == 3) {
                    const auto type = typeNamed(w[1]);
                    if (!type) headerError(line, "unknown type " + quoted(w[1]) + " (expected char, uchar, short, ushort, int, uint, float, double)");
                    p = {std::string(w[2]), false, Type::UInt8, *type};
                } else {
                    headerError(line, "expected 'property TYPE NAME' or 'property list COUNTTYPE TYPE NAME', got " + quoted(text));
                }
                elements_.back().properties.push_back(p);
            } else {
                headerError(line, "unknown header line " + quoted(text));
            }
        }
    }

    // Locates the vertex and face elements and checks that the counts of the
    // header fit into the data that follows, before anything is allocated.
    void checkSizes() {
        for (std::size_t i = 0; i < elements_.size(); ++i) {
            const Element& e = elements_[i];
            if (e.name == "vertex") {
                if (vertex_) headerError(e.line, "a second 'vertex' element");
                vertex_ = i;
                axis_.assign(e.properties.size(), -1);
                int found = 0;
                for (std::size_t k = 0; k < e.properties.size(); ++k) {
                    const Property& p = e.properties[k];
                    const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
                    if (axis < 0) continue;
                    if (p.list) headerError(e.line, "vertex property '" + p.name + "' is a list, expected a number");
                    axis_[k] = axis;
                    found |= 1 << axis;
                }
                if (found != 7) headerError(e.line, "the 'vertex' element needs properties x, y and z");
                nVertices_ = static_cast<std::int64_t>(e.count);
            } else if (e.name == "face") {
                if (face_) headerError(e.line, "a second 'face' element");
                face_ = i;
                for (std::size_t k = 0; k < e.properties.size(); ++k) {
                    const Property& p = e.properties[k];
                    if (p.name == "vertex_indices" || p.name == "vertex_index") {
                        if (!p.list) headerError(e.line, "face property '" + p.name + "' must be a list");
                        if (p.type == Type::Float32 || p.type == Type::Float64)
                            headerError(e.line, "face property '" + p.name + "' must have an integer type");
                        indexProperty_ = k;
                    }
                }
                if (!indexProperty_) headerError(e.line, "the 'face' element has no list property 'vertex_indices'");
            }
        }
        if (!vertex_) headerError(1, "no 'vertex' element");

        // Each element takes at least one byte per property (binary: its size;
        // ascii: a digit and a separator).
        const std::uint64_t available = bytes_.size() - dataStart_;
        std::uint64_t needed = 0;
        for (const Element& e : elements_) {
            std::uint64_t least = 0;
            for (const Property& p : e.properties)
                least += format_ == Format::Ascii ? 2 : sizeOf(p.list ? p.countType : p.type);
            needed += e.count * least;
            if (needed > available + 1)
                headerError(e.line, "element '" + e.name + "' counts " + std::to_string(e.count) +
                                        " items, more than the " + std::to_string(available) +
                                        " bytes of data after the header can hold");
        }
    }

    std::string where(const Element& e, std::uint64_t item) const {
        if (format_ == Format::Ascii)
            return name_ + ":" + std::to_string(cursor_->line()) + ": " + e.name + " " + std::to_string(item);
        return name_ + ": " + e.name + " " + std::to_string(item) + " (at byte " + std::to_string(itemStart_) + ")";
    }

    // One value of type t as a double (exact for every integer type).
    double value(Type t, const Element& e, std::uint64_t item) {
        if (format_ == Format::Ascii) {
            const std::string_view token = cursor_->next();
            double x;
            if (token.empty())
                throw InputError(where(e, item) + ": the file ends here; the header counts " +
                                 std::to_string(e.count) + " " + e.name + " items");
            if (!parseNumber(token, x)) throw InputError(where(e, item) + ": expected a number, got " + quoted(token));
            return x;
        }
        const std::size_t n = sizeOf(t);
        if (pos_ + n > bytes_.size())
            throw InputError(where(e, item) + ": the file ends here (truncated); the header counts " +
                             std::to_string(e.count) + " " + e.name + " items");
        unsigned char b[8];
        std::memcpy(b, bytes_.data() + pos_, n);
        pos_ += n;
        const bool swap = (format_ == Format::BigEndian) != (std::endian::native == std::endian::big);
        if (swap) std::reverse(b, b + n);
        switch (t) {
        case Type::Int8: return static_cast<double>(static_cast<std::int8_t>(b[0]));
        case Type::UInt8: return b[0];
        case Type::Int16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
        case Type::UInt16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
        case Type::Int32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
        case Type::UInt32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
        case Type::Float32: { float v; std::memcpy(&v, b, 4); return v; }
        case Type::Float64: { double v; std::memcpy(&v, b, 8); return v; }
        }
        return 0.0;
    }

    std::uint64_t remainingBytes() const {
        if (format_ == Format::Ascii) return cursor_->remaining();
        return bytes_.size() - pos_;
    }

    void readElement(const Element& e) {
        const bool isVertex = vertex_ && &e == &elements_[*vertex_];
        const bool isFace = face_ && &e == &elements_[*face_];
        if (e.properties.empty()) return;  // nothing stored: nothing to read
        SurfaceMesh& mesh = out_->mesh;
        if (isVertex) mesh.vertices.reserve(e.count);  // checkSizes bounded it by the file size
        std::vector<int> polygon;
        for (std::uint64_t i = 0; i < e.count; ++i) {
            itemStart_ = pos_;
            Vec3 p = Vec3::Zero();
            for (std::size_t k = 0; k < e.properties.size(); ++k) {
                const Property& prop = e.properties[k];
                if (!prop.list) {
                    const double x = value(prop.type, e, i);
                    if (isVertex && axis_[k] >= 0) {
                        if (!std::isfinite(x) || std::abs(x) > meshCoordinateLimit)
                            throw InputError(where(e, i) + ": coordinate " + prop.name + " = " +
                                             meshDetail::formatNumber(x) + ", expected a finite number of magnitude at most 1e30");
                        p[axis_[k]] = x;
                    }
                    continue;
                }
                const double n = value(prop.countType, e, i);
                const std::uint64_t most = format_ == Format::Ascii ? remainingBytes() / 2 + 1
                                                                    : remainingBytes() / sizeOf(prop.type);
                if (n < 0 || n != std::floor(n))
                    throw InputError(where(e, i) + ": list '" + prop.name + "' counts " + numberText(n) +
                                     " items, expected a whole number >= 0");
                if (n > static_cast<double>(most))
                    throw InputError(where(e, i) + ": list '" + prop.name + "' counts " + numberText(n) +
                                     " items, but the rest of the file holds at most " + std::to_string(most) +
                                     (format_ == Format::Ascii ? "" : " (truncated, or not binary data)"));
                const auto count = static_cast<std::uint64_t>(n);
                const bool indices = isFace && k == *indexProperty_;
                if (indices) polygon.clear();
                for (std::uint64_t j = 0; j < count; ++j) {
                    const double x = value(prop.type, e, i);
                    if (!indices) continue;
                    if (x != std::floor(x) || x < 0 || x >= static_cast<double>(nVertices_))
                        throw InputError(where(e, i) + ": vertex index " + numberText(x) +
                                         " is out of range; the file has " + std::to_string(nVertices_) +
                                         " vertices (indices 0 to " + std::to_string(nVertices_ - 1) + ")");
                    polygon.push_back(static_cast<int>(x));
                }
                if (indices) addPolygon(polygon);
            }
            if (isVertex) mesh.vertices.push_back(p);
        }
    }

    // A fan from the first corner, as assimp's triangulation does for convex polygons.
    void addPolygon(const std::vector<int>& polygon) {
        if (polygon.size() < 3) {
            ++out_->pointsAndLinesIgnored;
            return;
        }
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
            out_->mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
    }

    std::string_view bytes_;
    const std::string& name_;
    Format format_ = Format::Ascii;
    std::vector<Element> elements_;
    std::size_t dataStart_ = 0;
    int dataLine_ = 0;
    std::optional<std::size_t> vertex_, face_, indexProperty_;
    std::vector<int> axis_;  // per vertex property: 0, 1, 2 for x, y, z; -1 other
    std::int64_t nVertices_ = 0;

    ParsedMesh* out_ = nullptr;
    meshText::TokenCursor* cursor_ = nullptr;
    std::size_t pos_ = 0;        // binary: the next byte
    std::size_t itemStart_ = 0;  // binary: the first byte of the item being read
};

} // namespace

ParsedMesh parsePly(std::string_view bytes, const std::string& name) { return PlyReader(bytes, name).read(); }

} // namespace mag

// PLY, the Stanford polygon format, in ascii and binary of either byte order. We take the
// vertex element's x y z (and nx ny nz when all three are there) and the face element's
// vertex_indices list; every other property and element is skipped.
#include "framework/scene/readers/reader_util.h"
#include "framework/scene/scene_loader.h"

#include <bit>
#include <cstring>
#include <optional>

namespace bvhlab {
namespace {

enum class PlyType : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct PlyTypeName {
    std::string_view name;
    PlyType type;
};

// The original names and their sized aliases.
constexpr PlyTypeName kPlyTypeNames[] = {
    {"char", PlyType::Int8},       {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
    {"uint8", PlyType::UInt8},     {"short", PlyType::Int16},     {"int16", PlyType::Int16},
    {"ushort", PlyType::UInt16},   {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
    {"int32", PlyType::Int32},     {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
    {"float", PlyType::Float32},   {"float32", PlyType::Float32}, {"double", PlyType::Float64},
    {"float64", PlyType::Float64},
};

size_t sizeOf(PlyType type) {
    constexpr size_t kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
    return kSizes[size_t(type)];
}

bool isInteger(PlyType type) { return type < PlyType::Float32; }

// What a property means to us.
enum class Role : uint8_t { Skip, X, Y, Z, NX, NY, NZ, VertexIndices };

struct PlyProperty {
    std::string name;
    PlyType type;                      // of the value, or of a list's entries
    std::optional<PlyType> countType;  // set for list properties
    Role role = Role::Skip;
    std::string description;  // "property 'x' of element 'vertex'", for error messages
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
    size_t line = 0;  // of its header line

    bool hasLists() const {
        return std::any_of(properties.begin(), properties.end(),
                           [](const PlyProperty& p) { return p.countType.has_value(); });
    }
    // Bytes of a binary record; for lists, of their counts only.
    size_t minRecordBytes() const {
        size_t bytes = 0;
        for (const PlyProperty& p : properties) bytes += sizeOf(p.countType.value_or(p.type));
        return bytes;
    }
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
};

PlyType parseType(const TextParser& header, std::string_view token) {
    for (const PlyTypeName& t : kPlyTypeNames) {
        if (token == t.name) return t.type;
    }
    throw header.error(fmt::format("unknown property type {}", quoted(token)));
}

PlyFormat parseFormat(TextParser& header) {
    const std::string_view token = header.nextOnLine();
    PlyFormat format;
    if (token == "ascii")
        format = PlyFormat::Ascii;
    else if (token == "binary_little_endian")
        format = PlyFormat::BinaryLittleEndian;
    else if (token == "binary_big_endian")
        format = PlyFormat::BinaryBigEndian;
    else
        throw header.error(fmt::format("unknown format {}", quoted(token)));
    if (header.nextOnLine() != "1.0") throw header.error("expected format version 1.0");
    return format;
}

PlyProperty parseProperty(TextParser& header, const PlyElement& element) {
    PlyProperty property;
    const std::string_view token = header.nextOnLine();
    if (token == "list") {
        property.countType = parseType(header, header.nextOnLine());
        if (!isInteger(*property.countType)) throw header.error("a list's count must have an integer type");
        property.type = parseType(header, header.nextOnLine());
    } else {
        property.type = parseType(header, token);
    }
    property.name = header.nextOnLine();
    if (property.name.empty()) throw header.error("property without a name");
    property.description = fmt::format("property '{}' of element '{}'", property.name, element.name);
    return property;
}

// Reads the header up to and including the end_header line, leaving `header` at the data.
PlyHeader parseHeader(TextParser& header) {
    if (header.next() != "ply") throw header.error("not a PLY file (it does not start with 'ply')");
    header.endLine();
    PlyHeader result;
    bool hasFormat = false;
    for (;;) {
        const std::string_view keyword = header.next();
        if (keyword.empty()) throw header.error("the header has no end_header line");
        if (keyword == "comment" || keyword == "obj_info") {
            header.skipLine();
            continue;
        }
        if (keyword == "end_header") {
            header.endLine();
            break;
        }
        if (keyword == "format") {
            result.format = parseFormat(header);
            hasFormat = true;
        } else if (keyword == "element") {
            PlyElement element;
            element.line = header.line();
            element.name = header.nextOnLine();
            element.count = header.readOnLine<uint64_t>("an element count");
            result.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (result.elements.empty()) throw header.error("property before any element");
            result.elements.back().properties.push_back(parseProperty(header, result.elements.back()));
        } else {
            throw header.error(fmt::format("unknown header keyword {}", quoted(keyword)));
        }
        header.endLine();
    }
    if (!hasFormat) throw header.error("the header has no format line");
    return result;
}

// The elements we read; pointers into PlyHeader::elements.
struct PlyLayout {
    const PlyElement* vertex = nullptr;
    const PlyElement* face = nullptr;
    bool hasNormals = false;

    bool isSkipped(const PlyElement& element) const { return &element != vertex && &element != face; }
};

// Finds the vertex and face elements and gives their properties roles, checking that the
// ones we need are there.
PlyLayout assignRoles(const std::filesystem::path& file, std::vector<PlyElement>& elements) {
    PlyElement* vertex = nullptr;
    PlyElement* face = nullptr;
    for (PlyElement& element : elements) {
        PlyElement** slot = element.name == "vertex" ? &vertex : element.name == "face" ? &face : nullptr;
        if (!slot) continue;
        if (*slot) throw inputError(file, element.line, fmt::format("a second '{}' element", element.name));
        *slot = &element;
    }
    const auto find = [](PlyElement& element, std::string_view name) -> PlyProperty* {
        for (PlyProperty& p : element.properties) {
            if (p.name == name) return &p;
        }
        return nullptr;
    };

    bool hasNormals = false;
    if (vertex) {
        if (vertex->count > std::numeric_limits<uint32_t>::max()) {
            throw inputError(file, vertex->line, "more vertices than 32-bit indices can address");
        }
        for (const auto& [name, role] : {std::pair{"x", Role::X}, {"y", Role::Y}, {"z", Role::Z}}) {
            PlyProperty* p = find(*vertex, name);
            if (!p || p->countType) {
                throw inputError(file, vertex->line,
                                 fmt::format("the vertex element has no scalar property '{}'", name));
            }
            p->role = role;
        }
        PlyProperty* normal[] = {find(*vertex, "nx"), find(*vertex, "ny"), find(*vertex, "nz")};
        hasNormals =
            std::all_of(std::begin(normal), std::end(normal), [](const PlyProperty* p) { return p && !p->countType; });
        if (hasNormals) {
            normal[0]->role = Role::NX;
            normal[1]->role = Role::NY;
            normal[2]->role = Role::NZ;
        }
    }
    if (face) {
        PlyProperty* indices = find(*face, "vertex_indices");
        if (!indices) indices = find(*face, "vertex_index");
        if (!indices || !indices->countType || !isInteger(indices->type)) {
            throw inputError(file, face->line, "the face element has no integer list property 'vertex_indices'");
        }
        indices->role = Role::VertexIndices;
    }
    return {vertex, face, hasNormals};
}

// Where in the data a source is, for error messages.
struct PlyPosition {
    const PlyElement* element = nullptr;
    uint64_t record = 0;

    std::string describe(const std::string& message) const {
        return fmt::format("{} (element '{}', record {} of {})", message, element->name, record + 1, element->count);
    }
};

template <typename T>
T byteSwapped(T value) {
    if constexpr (sizeof(T) == 1) return value;
    using Bits = std::conditional_t<sizeof(T) == 2, uint16_t, std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>>;
    Bits bits;
    std::memcpy(&bits, &value, sizeof(T));
    if constexpr (sizeof(T) == 2) bits = __builtin_bswap16(bits);
    if constexpr (sizeof(T) == 4) bits = __builtin_bswap32(bits);
    if constexpr (sizeof(T) == 8) bits = __builtin_bswap64(bits);
    std::memcpy(&value, &bits, sizeof(T));
    return value;
}

// Binary values; Swap when the file's byte order is not ours. Every read is checked
// against the end of the data.
template <bool Swap>
class BinarySource : public PlyPosition {
public:
    BinarySource(const std::filesystem::path& file, std::string_view data)
        : file_(file), next_(data.data()), end_(data.data() + data.size()) {}

    double value(const PlyProperty& property, PlyType type) {
        if (bytesLeft() < sizeOf(type)) throw truncated(property);
        switch (type) {
            case PlyType::Int8:
                return load<int8_t>();
            case PlyType::UInt8:
                return load<uint8_t>();
            case PlyType::Int16:
                return load<int16_t>();
            case PlyType::UInt16:
                return load<uint16_t>();
            case PlyType::Int32:
                return load<int32_t>();
            case PlyType::UInt32:
                return load<uint32_t>();
            case PlyType::Float32:
                return load<float>();
            case PlyType::Float64:
                return load<double>();
        }
        return 0.0;  // not reached: the switch covers every type
    }

    void skipValues(const PlyProperty& property, uint64_t count) {
        if (count > bytesLeft() / sizeOf(property.type)) throw truncated(property);
        next_ += count * sizeOf(property.type);
    }

    // Skips all records of an element at once when they have a fixed size.
    bool skipRecords(const PlyElement& element) {
        if (element.hasLists()) return false;
        const size_t recordBytes = element.minRecordBytes();
        if (element.count > bytesLeft() / recordBytes) {
            throw inputError(file_, 0,
                             fmt::format("the data ends inside element '{}' ({} records of {} bytes)", element.name,
                                         element.count, recordBytes));
        }
        next_ += element.count * recordBytes;
        return true;
    }

    size_t plausibleRecords(const PlyElement& element) const {
        return plausibleCount(element.count, bytesLeft(), element.minRecordBytes());
    }

    InputError error(const std::string& message) const { return inputError(file_, 0, describe(message)); }

private:
    size_t bytesLeft() const { return size_t(end_ - next_); }

    template <typename T>
    T load() {
        T value;
        std::memcpy(&value, next_, sizeof(T));
        next_ += sizeof(T);
        if constexpr (Swap) value = byteSwapped(value);
        return value;
    }

    InputError truncated(const PlyProperty& property) const {
        return error(fmt::format("the data ends inside property '{}'", property.name));
    }

    const std::filesystem::path& file_;
    const char* next_;
    const char* end_;
};

// Ascii values: whitespace-separated numbers, read with line numbers for errors.
class AsciiSource : public PlyPosition {
public:
    AsciiSource(TextParser& text, size_t bytesLeft) : text_(text), bytesLeft_(bytesLeft) {}

    double value(const PlyProperty& property, PlyType type) {
        if (isInteger(type)) return double(text_.read<int64_t>(property.description));
        return text_.read<double>(property.description);
    }

    void skipValues(const PlyProperty& property, uint64_t count) {
        for (; count > 0; --count) value(property, property.type);
    }

    bool skipRecords(const PlyElement&) { return false; }

    // Every value takes at least a digit and a separator.
    size_t plausibleRecords(const PlyElement& element) const {
        return plausibleCount(element.count, bytesLeft_, 2 * element.properties.size());
    }

    InputError error(const std::string& message) const { return text_.error(describe(message)); }

private:
    TextParser& text_;
    size_t bytesLeft_;
};

// Reads every element in file order into the scene.
template <typename Source>
void readElements(Source& source, const PlyHeader& header, const PlyLayout& layout, Scene& scene) {
    const uint64_t vertexCount = layout.vertex ? layout.vertex->count : 0;
    std::vector<uint32_t> polygon;
    PolygonTriangulator triangulator;
    for (const PlyElement& element : header.elements) {
        source.element = &element;
        const bool isVertex = &element == layout.vertex;
        if (element.properties.empty()) continue;
        if (layout.isSkipped(element) && source.skipRecords(element)) continue;
        if (isVertex) {
            scene.positions.reserve(source.plausibleRecords(element));
            if (layout.hasNormals) scene.normals.reserve(source.plausibleRecords(element));
        }
        if (&element == layout.face) scene.indices.reserve(source.plausibleRecords(element));

        Vec3 position{0.0f}, normal{0.0f};
        for (uint64_t record = 0; record < element.count; ++record) {
            source.record = record;
            for (const PlyProperty& property : element.properties) {
                if (!property.countType) {
                    const float value = float(source.value(property, property.type));
                    switch (property.role) {
                        case Role::X:
                            position.x = value;
                            break;
                        case Role::Y:
                            position.y = value;
                            break;
                        case Role::Z:
                            position.z = value;
                            break;
                        case Role::NX:
                            normal.x = value;
                            break;
                        case Role::NY:
                            normal.y = value;
                            break;
                        case Role::NZ:
                            normal.z = value;
                            break;
                        default:
                            break;
                    }
                    continue;
                }
                const double length = source.value(property, *property.countType);
                if (length < 0) throw source.error(fmt::format("negative list length {}", length));
                if (property.role != Role::VertexIndices) {
                    source.skipValues(property, uint64_t(length));
                    continue;
                }
                if (length < 3) {
                    throw source.error(fmt::format("face with {} vertices; a face needs at least 3", length));
                }
                polygon.clear();
                for (uint64_t i = 0; i < uint64_t(length); ++i) {
                    const double index = source.value(property, property.type);
                    if (!(index >= 0 && index < double(vertexCount))) {
                        throw source.error(
                            fmt::format("vertex index {} out of range (the file has {} vertices)", index, vertexCount));
                    }
                    polygon.push_back(uint32_t(index));
                }
                // A face of more corners is triangulated in its plane: its vertices must be known.
                if (polygon.size() > 3 && scene.positions.size() < vertexCount)
                    throw source.error("a face of more than three vertices before the vertex element");
                appendPolygon(scene, triangulator, polygon,
                              [&](const std::string& m) { return std::string(source.error(m).what()); });
            }
            if (isVertex) {
                scene.positions.push_back(position);
                if (layout.hasNormals) scene.normals.push_back(normal);
            }
        }
    }
}

template <bool Swap>
void readBinary(const std::filesystem::path& file, std::string_view data, const PlyHeader& header,
                const PlyLayout& layout, Scene& scene) {
    BinarySource<Swap> source(file, data);
    readElements(source, header, layout, scene);
}

}  // namespace

Scene readPly(const std::filesystem::path& file, const std::string& bytes) {
    TextParser text(file, bytes, /*hashComments=*/false);
    PlyHeader header = parseHeader(text);
    const PlyLayout layout = assignRoles(file, header.elements);

    Scene scene;
    for (const PlyElement& element : header.elements) {
        if (layout.isSkipped(element) && element.count > 0) {
            scene.report.warnings.push_back(
                fmt::format("{}: skipped element '{}' ({} records)", file.string(), element.name, element.count));
        }
    }
    const std::string_view data = std::string_view(bytes).substr(text.offset());
    switch (header.format) {
        case PlyFormat::Ascii: {
            AsciiSource source(text, data.size());
            readElements(source, header, layout, scene);
            break;
        }
        case PlyFormat::BinaryLittleEndian:
            readBinary<std::endian::native != std::endian::little>(file, data, header, layout, scene);
            break;
        case PlyFormat::BinaryBigEndian:
            readBinary<std::endian::native != std::endian::big>(file, data, header, layout, scene);
            break;
    }
    return scene;
}

}  // namespace bvhlab

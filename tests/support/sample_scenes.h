// Sample scene files that more than one test reads: a PLY file in each of its three encodings
// and an NFF file with everything the format holds.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

namespace bvhlab::test {

enum class PlyEncoding { Ascii, LittleEndian, BigEndian };

// Writes PLY records in any of the three encodings from the same calls.
class PlyWriter {
public:
    explicit PlyWriter(PlyEncoding encoding) : encoding_(encoding) {}

    std::string format() const {
        switch (encoding_) {
            case PlyEncoding::Ascii:
                return "ascii";
            case PlyEncoding::LittleEndian:
                return "binary_little_endian";
            case PlyEncoding::BigEndian:
                return "binary_big_endian";
        }
        return "";
    }

    template <typename T>
    PlyWriter& put(T value) {
        if (encoding_ == PlyEncoding::Ascii) {
            data_ += fmt::format("{} ", +value);  // unary + prints chars as numbers
            return *this;
        }
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        const bool fileIsBig = encoding_ == PlyEncoding::BigEndian;
        if (fileIsBig != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
        data_.append(raw, sizeof(T));
        return *this;
    }

    PlyWriter& endRecord() {
        if (encoding_ == PlyEncoding::Ascii) data_ += "\n";
        return *this;
    }

    const std::string& data() const { return data_; }

private:
    PlyEncoding encoding_;
    std::string data_;
};

// Five vertices with x y z of three types and properties to skip on either side of the
// normals; a quad, a zero-area triangle and a triangle; elements to skip before and after
// the faces, lists included.
inline std::string testPly(PlyEncoding encoding) {
    PlyWriter w(encoding);
    const std::string header = "ply\nformat " + w.format() +
                               " 1.0\n"
                               "comment every scalar type somewhere\n"
                               "obj_info made by test_readers\n"
                               "element vertex 5\n"
                               "property double x\n"
                               "property float y\n"
                               "property short z\n"
                               "property uchar red\n"
                               "property list uchar float texcoord\n"
                               "property float nx\nproperty float ny\nproperty float nz\n"
                               "property int8 tag\n"
                               "element material 2\n"
                               "property list int uint8 name\n"
                               "property float shininess\n"
                               "element face 3\n"
                               "property uint8 flags\n"
                               "property list ushort uint vertex_index\n"
                               "property list uchar int extra\n"
                               "element edge 2\n"
                               "property int vertex1\nproperty uint32 vertex2\nproperty float64 crease\n"
                               "end_header\n";
    const double xs[] = {0, 1, 1, 0, 2};
    const float ys[] = {0, 0, 1, 1, 0};
    for (int i = 0; i < 5; ++i) {
        w.put(xs[i]).put(ys[i]).put(int16_t(-i)).put(uint8_t(200));
        w.put(uint8_t(2)).put(0.5f).put(0.25f);
        w.put(0.0f).put(float(i)).put(1.0f).put(int8_t(-1)).endRecord();
    }
    w.put(int32_t(3)).put(uint8_t('a')).put(uint8_t('b')).put(uint8_t('c')).put(2.0f).endRecord();
    w.put(int32_t(0)).put(7.0f).endRecord();
    w.put(uint8_t(1)).put(uint16_t(4)).put(0u).put(1u).put(2u).put(3u).put(uint8_t(1)).put(int32_t(-9)).endRecord();
    w.put(uint8_t(1)).put(uint16_t(3)).put(0u).put(1u).put(1u).put(uint8_t(0)).endRecord();
    w.put(uint8_t(1))
        .put(uint16_t(3))
        .put(1u)
        .put(4u)
        .put(2u)
        .put(uint8_t(2))
        .put(int32_t(5))
        .put(int32_t(6))
        .endRecord();
    w.put(int32_t(0)).put(1u).put(0.5).endRecord();
    w.put(int32_t(1)).put(2u).put(0.5).endRecord();
    return header + w.data();
}

inline const char* const kNff = R"(# test scene
b 0.1 0.2 0.3
v
from 1 2 3
at 0 0 0
up 0 0 1
angle 40
hither 0.01
resolution 320 240
l 4 3 2
l 1 -4 4 0.5 0.25 1
p 3
0 0 0
1 0 0
0 1 0
f 1 0.5 0.25 0.8 0.3 10 0 1
pp 4
0 0 1 0 0 1
1 0 1 0 0.6 0.8
1 1 1 0 0 1
0 1 1 1 0 0
s 0 0 0 0.5
c 0 0 0 0.15 0 0 1 0.1
c
0 0 0 0.2
0 0 2 0.1

p 3
0 0 0
1 1 1
2 2 2
)";

}  // namespace bvhlab::test

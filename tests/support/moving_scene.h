// A small animated scene in BART's AFF, written by the tests of what moves: a static block of
// random triangles, a part that spins and travels under a static transform (with a sphere), and
// animated triangles (`tpa`) that fly apart, over 5 frames from time 0 to 4; a camera and a light.
#pragma once

#include <fmt/format.h>

#include <random>
#include <string>

namespace bvhlab::test {

// `n` random small triangles within 2 of (cx, 0, 0), as AFF polygons.
inline std::string randomPolygons(int n, float cx, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> at(-2.0f, 2.0f), jitter(-0.5f, 0.5f);
    std::string out;
    for (int i = 0; i < n; ++i) {
        const float x = cx + at(rng), y = at(rng), z = at(rng);
        out += fmt::format("p 3\n{} {} {}\n{} {} {}\n{} {} {}\n", x, y, z, x + jitter(rng), y + jitter(rng), z, x,
                           y + jitter(rng), z + jitter(rng));
    }
    return out;
}

inline std::string movingSceneText() {
    std::string text = "v\nfrom 0 0 30\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 32 32\nl 0 20 20\n";
    text += "f 1 1 1 1 0 0 0 1\n" + randomPolygons(150, -6.0f, 1);
    text += "x spin\n{\nxs 1 1 1  0 0 1 0  3 0 0\n{\n" + randomPolygons(120, 0.0f, 2) + "s 1 1 1 0.7\n}\n}\n";
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> at(-2.0f, 2.0f);
    for (int i = 0; i < 40; ++i) {
        text += "tpa 2\n";
        for (float key : {0.0f, 4.0f}) {
            const float spread = key == 0.0f ? 1.0f : 3.0f, x = 6.0f + at(rng) * spread, y = at(rng) * spread;
            text += fmt::format(" {}\n {} {} 0 0 0 1\n {} {} 0 0 0 1\n {} {} 1 0 0 1\n", key, x, y, x + 0.6f, y, x,
                                y + 0.6f);
        }
    }
    text += "a 0 4 5\nk spin\n{\n transl 4\n -1 0 0 0 0 0 0\n 0 0 0 0 0 0 0\n 4 0 3 1 0 0 0\n 5 0 3 1 0 0 0\n";
    text += " rot 4\n -1 0 0 1 0 0 0 0\n 0 0 0 1 0 0 0 0\n 4 0 0 1 170 0 0 0\n 5 0 0 1 170 0 0 0\n}\n";
    return text;
}

}  // namespace bvhlab::test

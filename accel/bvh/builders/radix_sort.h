// A stable LSD radix sort of (key, value) pairs by the low `keyBits` bits of their key, eight
// bits per pass, TBB-parallel over fixed chunks: per chunk a histogram, then offsets by digit
// and chunk, then each chunk scatters to its own places. Stable, so the same order whatever the
// thread count. Internal to build/.
#pragma once

#include <tbb/parallel_for.h>

#include <array>
#include <cstdint>
#include <vector>

namespace bvhlab {

struct KeyValue {
    uint32_t key;
    uint32_t value;
};

// Sorts `items` (using `scratch`, resized to match) by key; ties keep their order.
inline void radixSort(std::vector<KeyValue>& items, std::vector<KeyValue>& scratch, int keyBits) {
    constexpr uint32_t kChunk = 1 << 16;
    const uint32_t n = uint32_t(items.size());
    const uint32_t chunks = (n + kChunk - 1) / kChunk;
    scratch.resize(n);
    std::vector<std::array<uint32_t, 256>> offsets(chunks);
    for (int shift = 0; shift < keyBits; shift += 8) {
        tbb::parallel_for(uint32_t(0), chunks, [&](uint32_t c) {
            std::array<uint32_t, 256>& h = offsets[c];
            h.fill(0);
            for (uint32_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) ++h[(items[i].key >> shift) & 255];
        });
        uint32_t sum = 0;
        for (int digit = 0; digit < 256; ++digit) {
            for (uint32_t c = 0; c < chunks; ++c) {
                const uint32_t count = offsets[c][digit];
                offsets[c][digit] = sum;
                sum += count;
            }
        }
        tbb::parallel_for(uint32_t(0), chunks, [&](uint32_t c) {
            std::array<uint32_t, 256>& at = offsets[c];
            for (uint32_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i)
                scratch[at[(items[i].key >> shift) & 255]++] = items[i];
        });
        items.swap(scratch);
    }
}

}  // namespace bvhlab

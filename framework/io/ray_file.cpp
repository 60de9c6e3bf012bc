#include "framework/io/ray_file.h"

#include "framework/core/error.h"

#include <bit>
#include <cstring>
#include <fstream>

namespace bvhlab {
namespace {

static_assert(std::endian::native == std::endian::little, "ray files are little-endian; add byte swapping");

struct RayRecord {
    float org[3], dir[3], tmin, tmax;
};
struct HitRecord {
    float t;
    uint32_t primitive;
    float u, v;
};
static_assert(sizeof(RayRecord) == 32 && sizeof(HitRecord) == 16);

template <typename Record>
std::vector<Record> readRecords(const std::filesystem::path& file, const char (&magic)[9]) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw inputError(file, 0, "cannot open");
    char header[8];
    uint64_t count = 0;
    if (!in.read(header, 8) || std::memcmp(header, magic, 8) != 0)
        throw inputError(file, 0, fmt::format("not a {} file (bad magic)", magic));
    if (!in.read(reinterpret_cast<char*>(&count), sizeof(count))) throw inputError(file, 0, "truncated header");
    const uint64_t available = std::filesystem::file_size(file) - 16;
    if (count > available / sizeof(Record))
        throw inputError(
            file, 0, fmt::format("header says {} records but the file holds {}", count, available / sizeof(Record)));
    std::vector<Record> records(count);
    in.read(reinterpret_cast<char*>(records.data()), std::streamsize(count * sizeof(Record)));
    return records;
}

template <typename Record>
void writeRecords(const std::filesystem::path& file, const char (&magic)[9], const std::vector<Record>& records) {
    std::ofstream out(file, std::ios::binary);
    const uint64_t count = records.size();
    out.write(magic, 8);
    out.write(reinterpret_cast<const char*>(&count), sizeof(count));
    out.write(reinterpret_cast<const char*>(records.data()), std::streamsize(count * sizeof(Record)));
    if (!out) throw inputError(file, 0, "cannot write");
}

}  // namespace

std::vector<Ray> readRayFile(const std::filesystem::path& file) {
    std::vector<Ray> rays;
    for (const RayRecord& r : readRecords<RayRecord>(file, "BVHRAYS1"))
        rays.push_back({Vec3(r.org[0], r.org[1], r.org[2]), Vec3(r.dir[0], r.dir[1], r.dir[2]), r.tmin, r.tmax});
    return rays;
}

void writeRayFile(const std::filesystem::path& file, const std::vector<Ray>& rays) {
    std::vector<RayRecord> records;
    for (const Ray& r : rays)
        records.push_back({{r.org.x, r.org.y, r.org.z}, {r.dir.x, r.dir.y, r.dir.z}, r.tmin, r.tmax});
    writeRecords(file, "BVHRAYS1", records);
}

std::vector<Hit> readHitFile(const std::filesystem::path& file) {
    std::vector<Hit> hits;
    for (const HitRecord& h : readRecords<HitRecord>(file, "BVHHITS1")) hits.push_back({h.t, h.primitive, h.u, h.v});
    return hits;
}

void writeHitFile(const std::filesystem::path& file, const std::vector<Hit>& hits) {
    std::vector<HitRecord> records;
    for (const Hit& h : hits) records.push_back({h.t, h.primitive, h.u, h.v});
    writeRecords(file, "BVHHITS1", records);
}

}  // namespace bvhlab

// The BVHRAYS1 / BVHHITS1 file round trip and malformed files.
#include "framework/core/error.h"
#include "framework/io/ray_file.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace bvhlab;

namespace {
std::filesystem::path tempPath(const std::string& name) { return test::scratchDir("rayfile") / name; }
}  // namespace

TEST(RayFile, RoundTrip) {
    const std::vector<Ray> rays = {{Vec3(1, 2, 3), Vec3(0, 0, -2), 0.5f, 100.0f},
                                   {Vec3(-1), Vec3(1, 0, 0), 0.0f, kInfinity}};
    writeRayFile(tempPath("r.bin"), rays);
    const std::vector<Ray> back = readRayFile(tempPath("r.bin"));
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back[0].org, rays[0].org);
    EXPECT_EQ(back[0].dir, rays[0].dir);
    EXPECT_EQ(back[1].tmax, kInfinity);
    EXPECT_EQ(std::filesystem::file_size(tempPath("r.bin")), 16u + 2 * 32u);

    const std::vector<Hit> hits = {{2.5f, 7, 0.25f, 0.5f}, Hit{}};
    writeHitFile(tempPath("h.bin"), hits);
    const std::vector<Hit> hb = readHitFile(tempPath("h.bin"));
    ASSERT_EQ(hb.size(), 2u);
    EXPECT_EQ(hb[0].primitive, 7u);
    EXPECT_EQ(hb[0].u, 0.25f);
    EXPECT_EQ(hb[1].primitive, kInvalidPrimitive);
    EXPECT_EQ(hb[1].t, kInfinity);
}

TEST(RayFile, MalformedFilesAreErrors) {
    std::ofstream(tempPath("bad_magic.bin")) << "BVHRAYS2xxxxxxxx";
    EXPECT_THROW(readRayFile(tempPath("bad_magic.bin")), InputError);
    EXPECT_THROW(readHitFile(tempPath("r_missing.bin")), InputError);
    // A header that promises more records than the file holds.
    {
        std::ofstream out(tempPath("short.bin"), std::ios::binary);
        const uint64_t n = 1000;
        out.write("BVHRAYS1", 8);
        out.write(reinterpret_cast<const char*>(&n), 8);
        out.write("0123456789012345678901234567890", 32);
    }
    EXPECT_THROW(readRayFile(tempPath("short.bin")), InputError);
}

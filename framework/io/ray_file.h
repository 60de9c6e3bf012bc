// Binary ray and hit files for `bvhlab raycast` (little-endian; see docs/file-formats.md):
//   rays: "BVHRAYS1", uint64 n, n x {float32 ox oy oz dx dy dz tmin tmax}
//   hits: "BVHHITS1", uint64 n, n x {float32 t (+inf on a miss), uint32 primitive
//         (0xFFFFFFFF on a miss), float32 u, float32 v}
#pragma once

#include <bvhlab/ray.h>

#include <filesystem>
#include <vector>

namespace bvhlab {

std::vector<Ray> readRayFile(const std::filesystem::path& file);
void writeRayFile(const std::filesystem::path& file, const std::vector<Ray>& rays);
std::vector<Hit> readHitFile(const std::filesystem::path& file);
void writeHitFile(const std::filesystem::path& file, const std::vector<Hit>& hits);

}  // namespace bvhlab

// A contact sheet: many renders scaled down onto one PNG, each with its name written under it
// (stb_image_resize for the thumbnails, framework/io/image_text.h for the labels).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

struct ContactImage {
    std::filesystem::path file;  // a PNG; a missing or unreadable one becomes a grey tile
    std::string label;
};

// One row of tiles per entry of `rows`, each image `thumbWidth` pixels wide (aspect kept), the
// title (if any) above them all.
void writeContactSheet(const std::filesystem::path& out, const std::vector<std::vector<ContactImage>>& rows,
                       const std::string& title = "", int thumbWidth = 256);

}  // namespace bvhlab

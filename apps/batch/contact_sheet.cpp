#include "apps/batch/contact_sheet.h"

#include "framework/io/image_io.h"
#include "framework/io/image_text.h"

#include <stb_image_resize.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace bvhlab {
namespace {

constexpr Rgb kBackground{28, 28, 32}, kText{235, 235, 235}, kMissing{90, 90, 90};
constexpr int kMargin = 10, kGap = 10;

// `text` at scale 2 on one line, or broken at its last space onto two, else at scale 1 (shortened
// with ".." if even that is too wide). Returns the text (with '\n' where it breaks) and the scale.
std::pair<std::string, int> fitText(std::string text, int width, bool mayBreak = true) {
    text = printableText(std::move(text));
    if (textWidth(text) * 2 <= width) return {text, 2};
    if (const size_t space = text.rfind(' '); mayBreak && space != std::string::npos) {
        const std::string broken = text.substr(0, space) + "\n" + text.substr(space + 1);
        if (textWidth(broken) * 2 <= width) return {broken, 2};
    }
    while (text.size() > 2 && textWidth(text) > width) text = text.substr(0, text.size() - 3) + "..";
    return {text, 1};
}

}  // namespace

void writeContactSheet(const std::filesystem::path& out, const std::vector<std::vector<ContactImage>>& rows,
                       const std::string& title, int thumbWidth) {
    // Read and shrink every image first: the tile height is the tallest thumbnail.
    std::vector<std::vector<std::optional<Rgb8Image>>> thumbs(rows.size());
    int thumbHeight = 0;
    size_t columns = 0;
    for (size_t r = 0; r < rows.size(); ++r) {
        columns = std::max(columns, rows[r].size());
        for (const ContactImage& tile : rows[r]) {
            std::optional<Rgb8Image> thumb;
            try {
                const Rgb8Image image = readPng(tile.file);
                const int height = std::max(1, int(std::lround(double(thumbWidth) * image.height / image.width)));
                Rgb8Image small{thumbWidth, height, std::vector<uint8_t>(size_t(thumbWidth) * height * 3)};
                if (stbir_resize_uint8(image.pixels.data(), image.width, image.height, 0, small.pixels.data(),
                                       thumbWidth, height, 0, 3))
                    thumb = std::move(small);
            } catch (const std::exception&) {
                // drawn as a grey tile saying so
            }
            if (thumb) thumbHeight = std::max(thumbHeight, thumb->height);
            thumbs[r].push_back(std::move(thumb));
        }
    }
    if (thumbHeight == 0) thumbHeight = thumbWidth;

    const int labelHeight = 2 * 2 * kTextLineHeight + 4;  // two lines at scale 2
    const int titleHeight = title.empty() ? 0 : 2 * kTextLineHeight + kGap;
    const int tileHeight = thumbHeight + labelHeight;
    Rgb8Image sheet;
    sheet.width =
        2 * kMargin + int(std::max<size_t>(columns, 1)) * thumbWidth + int(columns > 1 ? columns - 1 : 0) * kGap;
    sheet.height =
        2 * kMargin + titleHeight + int(rows.size()) * tileHeight + int(rows.size() > 1 ? rows.size() - 1 : 0) * kGap;
    sheet.pixels.resize(size_t(sheet.width) * sheet.height * 3);
    fillRect(sheet, 0, 0, sheet.width, sheet.height, kBackground);
    if (!title.empty()) {
        const auto [text, scale] = fitText(title, sheet.width - 2 * kMargin, false);
        drawText(sheet, kMargin, kMargin, text, scale, kText);
    }

    for (size_t r = 0; r < rows.size(); ++r)
        for (size_t c = 0; c < rows[r].size(); ++c) {
            const int x0 = kMargin + int(c) * (thumbWidth + kGap);
            const int y0 = kMargin + titleHeight + int(r) * (tileHeight + kGap);
            const std::optional<Rgb8Image>& thumb = thumbs[r][c];
            if (thumb) {
                for (int y = 0; y < thumb->height; ++y)
                    std::copy_n(&thumb->pixels[size_t(y) * thumb->width * 3], size_t(thumb->width) * 3,
                                &sheet.pixels[(size_t(y0 + y) * sheet.width + x0) * 3]);
            } else {
                fillRect(sheet, x0, y0, x0 + thumbWidth, y0 + thumbHeight, kMissing);
                drawText(sheet, x0 + 6, y0 + 6, "(missing)", 2, kText);
            }
            const auto [text, scale] = fitText(rows[r][c].label, thumbWidth);
            drawText(sheet, x0, y0 + thumbHeight + 4, text, scale, kText);
        }
    writePng(out, sheet);
}

}  // namespace bvhlab

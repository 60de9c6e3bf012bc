// What the scene readers share: strict number parsing, a tokenizer that knows line numbers
// for error messages, polygons as triangles and a cap on counts read from untrusted headers.
#pragma once

#include "framework/core/error.h"
#include "framework/core/parse_number.h"
#include "framework/scene/polygon_triangulation.h"
#include "framework/scene/scene.h"

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace bvhlab {

// A token quoted for an error message, shortened so that binary garbage stays readable.
inline std::string quoted(std::string_view token) {
    constexpr size_t kMaxShown = 32;
    if (token.size() > kMaxShown) return fmt::format("'{}...'", token.substr(0, kMaxShown));
    return fmt::format("'{}'", token);
}

// Whitespace-separated tokens of a text, with the line number of the last one read so
// that errors can say "file:line:". Tokens are views into the text.
class TextParser {
public:
    // With hashComments, a token starting with '#' comments out the rest of its line.
    // firstLine is the line number of the text's start within the file.
    TextParser(const std::filesystem::path& file, std::string_view text, bool hashComments, size_t firstLine = 1)
        : file_(file), text_(text), hashComments_(hashComments), line_(firstLine) {}
    // The parser keeps a reference to the file name for its errors.
    TextParser(std::filesystem::path&&, std::string_view, bool, size_t = 1) = delete;

    // Also comments out the rest of a line from a token starting with `c` (AFF's '%').
    void alsoCommentWith(char c) { otherComment_ = c; }

    // The next token on the current line, or empty at its end.
    std::string_view nextOnLine() {
        if (atLineEnd()) return {};
        const size_t start = pos_;
        while (pos_ < text_.size() && !isSpace(text_[pos_])) ++pos_;
        return text_.substr(start, pos_ - start);
    }

    // The next token on any line, or empty at the end of the text.
    std::string_view next() {
        while (atLineEnd()) {
            if (pos_ == text_.size()) return {};
            passLineEnd();
        }
        return nextOnLine();
    }

    // True when the current line holds no more tokens (comments do not count).
    bool atLineEnd() {
        while (pos_ < text_.size() && isSpace(text_[pos_]) && text_[pos_] != '\n') ++pos_;
        if (pos_ < text_.size() &&
            ((hashComments_ && text_[pos_] == '#') || (otherComment_ && text_[pos_] == otherComment_))) {
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        }
        return pos_ == text_.size() || text_[pos_] == '\n';
    }

    // Drops the rest of the current line, whatever it holds.
    void skipLine() {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        if (pos_ < text_.size()) passLineEnd();
    }

    // Requires the current line to hold no more tokens, then moves past it.
    void endLine() {
        if (!atLineEnd()) throw error(fmt::format("unexpected {} at the end of the line", quoted(nextOnLine())));
        skipLine();
    }

    // The next number, which may be on a later line; `what` names it for the error message.
    template <typename T>
    T read(std::string_view what) {
        return toNumber<T>(next(), what);
    }

    // The next number, which must be on the current line.
    template <typename T>
    T readOnLine(std::string_view what) {
        return toNumber<T>(nextOnLine(), what);
    }

    size_t line() const { return line_; }
    // Byte offset of the parser in the text, for readers that switch to binary data.
    size_t offset() const { return pos_; }
    size_t bytesLeft() const { return text_.size() - pos_; }
    InputError error(const std::string& message) const { return inputError(file_, line_, message); }

private:
    // Past the '\n' at pos_; the text's final '\n' starts no line, so that the end of a file
    // ending in one is on its last line.
    void passLineEnd() {
        ++pos_;
        if (pos_ < text_.size()) ++line_;
    }

    static bool isSpace(char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

    template <typename T>
    T toNumber(std::string_view token, std::string_view what) const {
        if (token.empty()) {
            const char* where = pos_ == text_.size() ? "file" : "line";
            throw error(fmt::format("expected {}, found the end of the {}", what, where));
        }
        T value;
        if (!parseNumber(token, value)) throw error(fmt::format("expected {}, found {}", what, quoted(token)));
        return value;
    }

    const std::filesystem::path& file_;
    std::string_view text_;
    bool hashComments_;
    char otherComment_ = '\0';
    size_t pos_ = 0;
    size_t line_;
};

// Appends a face's triangles to scene.indices: the fan from its first corner if it is convex
// (so that primitive indices follow file order), else the ear-clipped triangles that cover it
// exactly (PolygonTriangulator). A face that cannot be covered exactly is skipped and counted
// in scene.report, the first few in a warning that locate(message) places in the file.
template <typename Locate>
void appendPolygon(Scene& scene, PolygonTriangulator& triangulator, std::span<const uint32_t> polygon,
                   const Locate& locate) {
    if (polygon.size() == 3) {  // the common case, as it is; Scene::finalize judges its area
        scene.indices.emplace_back(polygon[0], polygon[1], polygon[2]);
        return;
    }
    const PolygonProblem problem = triangulator.triangulate(scene.positions, polygon);
    if (problem == PolygonProblem::None) {
        scene.indices.insert(scene.indices.end(), triangulator.triangles().begin(), triangulator.triangles().end());
        scene.report.earClippedPolygons += triangulator.wasEarClipped();
        return;
    }
    constexpr size_t kNamed = 10;
    if (scene.report.skippedPolygons < kNamed) {
        scene.report.warnings.push_back(
            locate(fmt::format("polygon of {} vertices skipped: {}", polygon.size(), describe(problem))));
    } else if (scene.report.skippedPolygons == kNamed) {
        scene.report.warnings.push_back("further skipped polygons are counted, not named");
    }
    ++scene.report.skippedPolygons;
}

// The same for a face of a text file, named by its line.
inline void appendPolygon(Scene& scene, PolygonTriangulator& triangulator, std::span<const uint32_t> polygon,
                          const std::filesystem::path& file, size_t line) {
    appendPolygon(scene, triangulator, polygon,
                  [&](const std::string& message) { return std::string(inputError(file, line, message).what()); });
}

// A count read from a file, for reserve(): no more items than the rest of the file can hold
// when each takes at least minBytes, so that a lying header cannot make us allocate.
inline size_t plausibleCount(uint64_t count, size_t bytesLeft, size_t minBytes) {
    return size_t(std::min<uint64_t>(count, bytesLeft / std::max<size_t>(minBytes, 1)));
}

}  // namespace bvhlab

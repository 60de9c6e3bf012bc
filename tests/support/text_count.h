// How often `what` occurs in `text` (overlapping occurrences counted): for tests that check how
// many lines, rows or messages an output holds.
#pragma once

#include <cstddef>
#include <string>

namespace bvhlab::test {

inline size_t occurrences(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace bvhlab::test

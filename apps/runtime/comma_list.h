// The comma-separated lists every option and env key of lists takes.
#pragma once

#include <string>
#include <vector>

namespace bvhlab {

// "a, b,,c" -> {"a", "b", "c"}.
std::vector<std::string> splitCommaList(const std::string& text);

}  // namespace bvhlab

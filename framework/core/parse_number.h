// The one number syntax of bvhlab's inputs: scene files, env files and command-line lists.
#pragma once

#include <charconv>
#include <cstdlib>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace bvhlab {

// Parses all of `token` as a number. Accepts a leading '+', and "nan"/"inf"/"infinity" for
// floating point (a NaN vertex is a degenerate triangle, not a reason to reject the file).
template <typename T>
bool parseNumber(std::string_view token, T& value) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, value);
    if constexpr (std::is_floating_point_v<T>) {
        // from_chars leaves overflow and underflow unset; strtod's inf or 0 is what we want.
        if (ec == std::errc::result_out_of_range && ptr == end) {
            const std::string copy(token);
            if constexpr (std::is_same_v<T, float>)
                value = std::strtof(copy.c_str(), nullptr);
            else
                value = std::strtod(copy.c_str(), nullptr);
            return true;
        }
    }
    return ec == std::errc() && ptr == end && !token.empty();
}

}  // namespace bvhlab

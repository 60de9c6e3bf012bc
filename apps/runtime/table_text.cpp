#include "apps/runtime/table_text.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace bvhlab {

std::string csvText(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string markdownText(const std::string& text) {
    std::string escaped;
    for (char c : text) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
    return escaped;
}

std::string jsonCell(const nlohmann::json& v, const char* format) {
    if (v.is_null()) return "";
    if (v.is_number_float()) return fmt::format(fmt::runtime(format), v.get<double>());
    if (v.is_number()) return fmt::format("{}", v.get<long long>());
    if (v.is_string()) return v.get<std::string>();
    return v.dump();
}

std::string fixedCell(double v, int digits) { return std::isfinite(v) ? fmt::format("{:.{}f}", v, digits) : ""; }

double jsonNumber(const nlohmann::json& v) { return v.is_number() ? v.get<double>() : NAN; }

std::string markdownTable(const std::vector<std::string>& headers, const std::vector<std::string>& alignments,
                          const std::vector<std::vector<std::string>>& rows) {
    std::vector<size_t> kept;
    for (size_t c = 0; c < headers.size(); ++c)
        if (rows.empty() || std::any_of(rows.begin(), rows.end(), [&](const auto& row) { return row[c] != "n/a"; }))
            kept.push_back(c);
    auto line = [&](const std::vector<std::string>& cells) {
        std::string text = "|";
        for (size_t c : kept) text += " " + cells[c] + " |";
        return text + "\n";
    };
    std::string table = line(headers) + "|";
    for (size_t c : kept) table += alignments[c] + "|";
    table += "\n";
    for (const std::vector<std::string>& row : rows) table += line(row);
    return table;
}

}  // namespace bvhlab

// Cells and tables of the CSV files and Markdown tables the commands write: free text (a scene's
// name, a failed job's reason) quoted or escaped where it would otherwise end the cell, a measured
// figure as a cell, and a Markdown table from its rows.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace bvhlab {

// The text as one CSV field: in double quotes (inner ones doubled) when it holds a comma, a
// quote or a line break, else as it is.
std::string csvText(const std::string& text);

// The text as one Markdown table cell: every '|' escaped.
std::string markdownText(const std::string& text);

// A value of a results file as a cell: a floating-point number in `format`, an integer as it is,
// a string as it is, null (not measured) as an empty cell.
std::string jsonCell(const nlohmann::json& v, const char* format = "{}");

// A figure computed from a results file with `digits` decimals; empty when it is not finite (NaN:
// made of a figure that was not measured).
std::string fixedCell(double v, int digits);

// A number of a results file as a double, NaN where it is null (not measured) or missing.
double jsonNumber(const nlohmann::json& v);

// A Markdown table of `rows` under `headers` (with their alignments, "---" or "---:"), without the
// columns that are n/a in every row: a column of n/a would only push the measured ones apart.
std::string markdownTable(const std::vector<std::string>& headers, const std::vector<std::string>& alignments,
                          const std::vector<std::vector<std::string>>& rows);

}  // namespace bvhlab

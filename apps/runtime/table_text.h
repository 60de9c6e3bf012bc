// Free text (a scene's name, a failed job's reason) as a cell of the CSV files and Markdown
// tables the commands write: quoted or escaped where the text would otherwise end the cell.
#pragma once

#include <string>

namespace bvhlab {

// The text as one CSV field: in double quotes (inner ones doubled) when it holds a comma, a
// quote or a line break, else as it is.
std::string csvText(const std::string& text);

// The text as one Markdown table cell: every '|' escaped.
std::string markdownText(const std::string& text);

}  // namespace bvhlab

// What the batch tests read back from a batch folder: its files as text or JSON, and its tables
// without the timing columns, which differ from run to run while every other column must not.
#pragma once

#include "tests/support/json_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace bvhlab::test {

// The timing columns of results.csv and of the rows of results.json.
inline constexpr const char* kTimingColumns[] = {"t_b_ms", "t_r_us", "render_ms"};

// results.csv without its timing columns.
inline std::vector<std::vector<std::string>> csvWithoutTimings(const std::filesystem::path& file) {
    std::vector<std::vector<std::string>> table;
    std::vector<bool> keep;
    std::stringstream in(readText(file));
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> cells;
        std::stringstream fields(line);
        for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
        if (keep.empty())
            for (const std::string& c : cells)
                keep.push_back(std::find(std::begin(kTimingColumns), std::end(kTimingColumns), c) ==
                               std::end(kTimingColumns));
        std::vector<std::string> kept;
        for (size_t i = 0; i < cells.size(); ++i)
            if (i < keep.size() && keep[i]) kept.push_back(cells[i]);
        table.push_back(kept);
    }
    return table;
}

// The rows of results.json without their timing columns.
inline nlohmann::json jsonRowsWithoutTimings(const std::filesystem::path& file) {
    nlohmann::json rows = readJson(file).at("rows");
    for (nlohmann::json& row : rows)
        for (const char* column : kTimingColumns) row.erase(column);
    return rows;
}

}  // namespace bvhlab::test

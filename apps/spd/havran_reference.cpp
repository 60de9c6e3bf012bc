#include "apps/spd/havran_reference.h"

#include "framework/core/error.h"
#include "framework/core/parse_number.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <vector>

namespace bvhlab {
namespace {

std::vector<std::string> words(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

std::vector<double> numbersAfterName(const std::vector<std::string>& w) {
    std::vector<double> values;
    for (size_t i = 1; i < w.size(); ++i) {
        double v = 0.0;
        if (parseNumber(w[i], v)) values.push_back(v);
    }
    return values;
}

// A scene's heading: its name in capitals, alone ("BALLS") or above the comparison table's columns
// ("BALLS   md = 7   md = 5 ...").
bool isSceneHeading(const std::vector<std::string>& w) {
    return !w.empty() && w[0].size() >= 3 &&
           std::all_of(w[0].begin(), w[0].end(), [](char c) { return std::isupper(uint8_t(c)); }) &&
           (w.size() == 1 || w[1] == "md");
}

// A section's underline: dashes from the line's start, nothing else.
bool isUnderline(const std::string& line) {
    const size_t end = line.find_last_not_of(" \t\r");
    return end != std::string::npos && end >= 2 && line.find_first_not_of('-') > end;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](char c) { return char(std::tolower(uint8_t(c))); });
    return s;
}

std::vector<std::string> readLines(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in)
        throw inputError(file, 0,
                         "cannot open Havran's statistics (Spd::reference names their folder: -DSpd::reference=... "
                         "or a line 'Spd::reference ...' in an env file)");
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// The invariants table: a line naming the scenes in lower case, then "Name[-] v v v ..." rows.
void readInvariants(const std::filesystem::path& file, std::map<std::string, HavranScene>& scenes) {
    std::vector<std::string> columns;
    for (const std::string& line : readLines(file)) {
        const std::vector<std::string> w = words(line);
        if (w.size() >= 4 && w[0] == "balls") columns = w;
        if (columns.empty() || w.empty()) continue;
        const std::string name = w[0].substr(0, w[0].find('['));
        if (std::find(std::begin(kHavranInvariants), std::end(kHavranInvariants), name) == std::end(kHavranInvariants))
            continue;
        const std::vector<double> values = numbersAfterName(w);
        for (size_t c = 0; c < columns.size() && c < values.size(); ++c)
            scenes[columns[c]].invariants[name] = values[c];
    }
    if (columns.empty()) throw inputError(file, 0, "no invariants table (a line 'balls gears ...')");
}

// Every table of the file: the sections (a title at the line's start, underlined with dashes),
// within them the scenes (BALLS ...) and their rows (N_IN, ..., T_TR[s]); then per scene the
// column with the fewest N_IT over all of them, with its N_TS.
void readTables(const std::filesystem::path& file, std::map<std::string, HavranScene>& scenes, bool octree) {
    const std::vector<std::string> lines = readLines(file);
    std::map<std::string, std::map<std::string, HavranTable>> read;  // by scene, then section
    std::string section, scene;
    for (size_t i = 0; i < lines.size(); ++i) {
        const std::vector<std::string> w = words(lines[i]);
        if (w.empty()) continue;
        if (i + 1 < lines.size() && isUnderline(lines[i + 1]) && !std::isspace(uint8_t(lines[i][0]))) {
            section = lines[i].substr(0, lines[i].find_last_not_of(" \t\r") + 1);
            scene.clear();
        } else if (isSceneHeading(w)) {
            scene = lower(w[0]);
        } else if (!scene.empty() && (w[0].rfind("N_", 0) == 0 || w[0].rfind("T_", 0) == 0)) {
            read[scene][section][w[0].substr(0, w[0].find('['))] = numbersAfterName(w);
        }
    }
    for (auto& [name, tables] : read) {
        HavranScene& s = scenes[name];
        std::optional<HavranBest>& best = octree ? s.bestOctree : s.bestGrid;
        for (auto& [title, table] : tables) {
            const auto nIt = table.find("N_IT"), nTs = table.find("N_TS");
            if (nIt != table.end() && nTs != table.end())
                for (size_t c = 0; c < nIt->second.size() && c < nTs->second.size(); ++c)
                    if (!best || nIt->second[c] < best->nIt) best = HavranBest{nIt->second[c], nTs->second[c]};
            s.tables[title] = std::move(table);
        }
    }
}

}  // namespace

std::map<std::string, HavranScene> readHavranReference(const std::filesystem::path& folder) {
    std::map<std::string, HavranScene> scenes;
    readInvariants(folder / "havran_stats_grids.txt", scenes);
    readTables(folder / "havran_stats_grids.txt", scenes, false);
    readTables(folder / "havran_stats_octrees.txt", scenes, true);
    return scenes;
}

}  // namespace bvhlab

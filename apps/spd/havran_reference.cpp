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

bool isSceneHeading(const std::vector<std::string>& w) {
    return w.size() == 1 && std::all_of(w[0].begin(), w[0].end(), [](char c) { return std::isupper(uint8_t(c)); });
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](char c) { return char(std::tolower(uint8_t(c))); });
    return s;
}

std::vector<std::string> readLines(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw inputError(file, 0, "cannot open Havran's statistics (Spd::reference names their folder)");
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
        for (size_t c = 0; c < columns.size() && c < values.size(); ++c) scenes[columns[c]].invariants[name] = values[c];
    }
    if (columns.empty()) throw inputError(file, 0, "no invariants table (a line 'balls gears ...')");
}

// Per scene heading (BALLS ...), the column with the fewest N_IT over every table of the file.
void readBest(const std::filesystem::path& file, std::map<std::string, HavranScene>& scenes, bool octree) {
    std::string scene;
    std::vector<double> nIt;
    for (const std::string& line : readLines(file)) {
        const std::vector<std::string> w = words(line);
        if (isSceneHeading(w)) scene = lower(w[0]), nIt.clear();
        if (scene.empty() || w.empty()) continue;
        if (w[0] == "N_IT") nIt = numbersAfterName(w);
        if (w[0] != "N_TS") continue;
        const std::vector<double> nTs = numbersAfterName(w);
        std::optional<HavranBest>& best = octree ? scenes[scene].bestOctree : scenes[scene].bestGrid;
        for (size_t c = 0; c < nIt.size() && c < nTs.size(); ++c)
            if (!best || nIt[c] < best->nIt) best = HavranBest{nIt[c], nTs[c]};
    }
}

}  // namespace

std::map<std::string, HavranScene> readHavranReference(const std::filesystem::path& folder) {
    std::map<std::string, HavranScene> scenes;
    readInvariants(folder / "havran_stats_grids.txt", scenes);
    readBest(folder / "havran_stats_grids.txt", scenes, false);
    readBest(folder / "havran_stats_octrees.txt", scenes, true);
    return scenes;
}

}  // namespace bvhlab

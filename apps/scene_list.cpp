#include "apps/scene_list.h"

#include "framework/error.h"

#include <fstream>

namespace bvhlab {

std::vector<std::filesystem::path> expandSceneList(const std::vector<std::string>& arguments) {
    std::vector<std::string> items = arguments;
    if (items.empty()) items.push_back((std::filesystem::path(BVHLAB_SOURCE_DIR) / "env/scenes.list").string());
    std::vector<std::filesystem::path> envFiles;
    for (const std::filesystem::path item : items) {
        if (item.extension() != ".list") {
            envFiles.push_back(item);
            continue;
        }
        std::ifstream in(item);
        if (!in) throw inputError(item, 0, "cannot open scene list");
        std::string line;
        for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
            line = line.substr(0, line.find('#'));
            line.erase(0, line.find_first_not_of(" \t\r"));
            line.erase(line.find_last_not_of(" \t\r") + 1);
            if (line.empty()) continue;
            const std::filesystem::path file = item.parent_path() / line;
            if (!std::filesystem::exists(file)) throw inputError(item, lineNo, "no such env file: " + file.string());
            envFiles.push_back(file);
        }
    }
    return envFiles;
}

}  // namespace bvhlab

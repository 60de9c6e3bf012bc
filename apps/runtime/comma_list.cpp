#include "apps/runtime/comma_list.h"

#include <sstream>

namespace bvhlab {

std::vector<std::string> splitCommaList(const std::string& text) {
    std::vector<std::string> items;
    std::string item;
    for (std::stringstream in(text); std::getline(in, item, ',');) {
        item.erase(0, item.find_first_not_of(" \t"));
        item.erase(item.find_last_not_of(" \t") + 1);
        if (!item.empty()) items.push_back(item);
    }
    return items;
}

}  // namespace bvhlab

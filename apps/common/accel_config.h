// An accelerator as a command runs it: a name from the registry plus env overrides, written
// NAME or NAME:Key=value:Key=value (e.g. embree:Embree::robust=true). Used by `bvhlab bench`
// and `bvhlab stress`.
#pragma once

#include <string>
#include <vector>

namespace bvhlab {

struct AccelConfig {
    std::string label;  // the text as given, except embree:Embree::robust=true -> "embree-robust"
    std::string name;
    std::vector<std::string> overrides;
};

AccelConfig parseAccelConfig(const std::string& text);

// A comma-separated list of configs.
std::vector<AccelConfig> parseAccelConfigList(const std::string& list);

}  // namespace bvhlab

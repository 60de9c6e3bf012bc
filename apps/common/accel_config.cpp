#include "apps/common/accel_config.h"

#include "apps/common/cli_common.h"

#include <sstream>

namespace bvhlab {

AccelConfig parseAccelConfig(const std::string& text) {
    AccelConfig config{text, text.substr(0, text.find(':')), {}};
    size_t start = text.find(':');
    while (start != std::string::npos) {
        const size_t end = text.find(':', text.find('=', start));
        config.overrides.push_back(text.substr(start + 1, end == std::string::npos ? end : end - start - 1));
        start = end;
    }
    if (config.label == "embree:Embree::robust=true") config.label = "embree-robust";
    return config;
}

std::vector<AccelConfig> parseAccelConfigList(const std::string& list) {
    std::vector<AccelConfig> configs;
    for (const std::string& item : splitCommaList(list)) configs.push_back(parseAccelConfig(item));
    return configs;
}

}  // namespace bvhlab

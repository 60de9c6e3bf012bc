#include "accel/plugins/plugin_builder.h"

#include "accel/bvh/builders/merge_tree_builder.h"
#include "framework/config/plugin_settings.h"

#include <fmt/core.h>

#include <memory>
#include <stdexcept>

namespace bvhlab {

namespace {

// The leaf block is the layout's, as bvhlab's SAH builders charge it (BuildConfig::sahBlockShift).
BuilderSettings builderSettings(const PluginSettings& keys, const BuildConfig& config) {
    return {keys, 1u << config.sahBlockShift, config.cTraversal, config.cIntersect};
}

class PluginSplitRule final : public BvhSplitRule {
public:
    PluginSplitRule(const BuildConfig& config, std::unique_ptr<SplitRule> rule)
        : BvhSplitRule(config), rule_(std::move(rule)) {}

protected:
    std::optional<Split> trySplit(const BuildRange& range, bool mayBeLeaf) override {
        const size_t left =
            rule_->split(refs_.subspan(range.begin, range.size()), range.bounds, range.centroidBounds, mayBeLeaf);
        if (left == 0 || left >= range.size()) return std::nullopt;
        return splitAtIndex(range, range.begin + uint32_t(left));
    }

private:
    std::unique_ptr<SplitRule> rule_;
};

}  // namespace

BuilderRecord pluginBuilderRecord(const LoadedBuilder& plugin, const Env& env) {
    BuilderRecord builder{plugin.name, {}, {}, true};
    const std::shared_ptr<const Env> settingsEnv = std::make_shared<Env>(env);
    const std::string owner = fmt::format("builder '{}'", plugin.name);
    if (plugin.splitRule) {
        builder.splitRule = [plugin, settingsEnv, owner](const BvhBuildConfig& config) {
            const EnvPluginSettings keys(*settingsEnv, plugin.keys, owner);
            std::unique_ptr<SplitRule> rule(plugin.splitRule(builderSettings(keys, config.shared)));
            if (!rule) throw std::runtime_error(fmt::format("{}: its split rule factory returned nothing", owner));
            return std::unique_ptr<BvhSplitRule>(std::make_unique<PluginSplitRule>(config.shared, std::move(rule)));
        };
    } else {
        builder.wholeTree = [plugin, settingsEnv, owner](const BvhBuildConfig& config, const PrimitiveSet& prims) {
            return buildFromMerges(plugin.name, config.shared, prims, [&](std::span<const PrimRef> refs) {
                const EnvPluginSettings keys(*settingsEnv, plugin.keys, owner);
                std::vector<Merge> merges(refs.empty() ? 0 : refs.size() - 1);
                plugin.mergeTree(refs, merges, builderSettings(keys, config.shared));
                std::vector<uint32_t> children;
                for (const Merge& m : merges) children.insert(children.end(), {m.left, m.right});
                return children;
            });
        };
    }
    return builder;
}

}  // namespace bvhlab

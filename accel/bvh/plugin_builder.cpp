#include "accel/bvh/plugin_builder.h"

#include "accel/bvh/builders/merge_tree_builder.h"

#include <fmt/core.h>

#include <memory>
#include <stdexcept>

namespace bvhlab {

namespace {

BuilderSettings builderSettings(const Env& env, uint32_t leafBlock, const BvhBuildConfig& config) {
    return {env, leafBlock, config.cTraversal, config.cIntersect};
}

class PluginSplitBuilder final : public TopDownBuilder {
public:
    PluginSplitBuilder(const BvhBuildConfig& config, std::unique_ptr<SplitRule> rule)
        : TopDownBuilder(config), rule_(std::move(rule)) {}

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

BvhBuilder pluginBvhBuilder(const PluginBuilder& plugin, const Env& env, uint32_t leafBlock) {
    BvhBuilder builder{plugin.name, {}, {}, true};
    const std::shared_ptr<const Env> settingsEnv = std::make_shared<Env>(env);
    if (plugin.splitRule) {
        builder.splitRule = [make = plugin.splitRule, settingsEnv, leafBlock, name = plugin.name](const BvhBuildConfig& config) {
            std::unique_ptr<SplitRule> rule = make(builderSettings(*settingsEnv, leafBlock, config));
            if (!rule) throw std::runtime_error(fmt::format("builder '{}': its split rule factory returned nothing", name));
            return std::unique_ptr<TopDownBuilder>(std::make_unique<PluginSplitBuilder>(config, std::move(rule)));
        };
    } else {
        builder.wholeTree = [merge = plugin.mergeTree, settingsEnv, leafBlock, name = plugin.name](
                                const BvhBuildConfig& config, const PrimitiveSet& prims) {
            return buildFromMerges(name, config, prims, [&](std::span<const PrimRef> refs) {
                std::vector<uint32_t> children;
                for (const Merge& m : merge(refs, builderSettings(*settingsEnv, leafBlock, config)))
                    children.insert(children.end(), {m.left, m.right});
                return children;
            });
        };
    }
    return builder;
}

}  // namespace bvhlab

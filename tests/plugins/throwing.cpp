// A plugin whose accelerators throw where bvhlab must turn the exception into an error naming
// the plugin and the accelerator (tests/apps/test_plugins.cpp): `throwing` in build(),
// `throwing_query` in its queries, `throwing_factory` when made; `throwing_misread` reads its
// Int key as a Float, which bvhlab refuses naming the key.
#include <bvhlab/plugin.h>

#include <stdexcept>

namespace {

class Throwing final : public bvhlab::Accelerator {
public:
    explicit Throwing(bool inBuild) : inBuild_(inBuild) {}
    const char* name() const override { return inBuild_ ? "throwing" : "throwing_query"; }
    void build(const bvhlab::PrimitiveSet&) override {
        if (inBuild_) throw std::runtime_error("no build today");
    }
    void statistics(bvhlab::BuildStatistics&) const override {}
    bool findNearest(const bvhlab::Ray&, bvhlab::Hit&, bvhlab::QueryCounters&) const override {
        throw std::runtime_error("no queries today");
    }
    bool isOccluded(const bvhlab::Ray&, bvhlab::QueryCounters&) const override {
        throw std::runtime_error("no queries today");
    }

private:
    bool inBuild_;
};

inline constexpr bvhlab::PluginKey kUnused{
    "Throwing::unused", bvhlab::KeyType::Int, "3", "a key, to be listed by `bvhlab keys`", 1, 9};
inline constexpr bvhlab::PluginKey kCount{
    "Throwing::count", bvhlab::KeyType::Int, "1", "an Int key read as a Float", 0, 9};

}  // namespace

BVHLAB_PLUGIN(registrar) {
    registrar.addAccelerator(
        {"throwing", "throws in build()", {kUnused}, [](const bvhlab::PluginSettings&) -> bvhlab::Accelerator* {
             return new Throwing(true);
         }});
    registrar.addAccelerator(
        {"throwing_query", "throws in its queries", {}, [](const bvhlab::PluginSettings&) -> bvhlab::Accelerator* {
             return new Throwing(false);
         }});
    registrar.addAccelerator(
        {"throwing_factory", "throws when made", {}, [](const bvhlab::PluginSettings&) -> bvhlab::Accelerator* {
             throw std::invalid_argument("no accelerator today");
         }});
    registrar.addAccelerator({"throwing_misread",
                              "reads its Int key as a Float",
                              {kCount},
                              [](const bvhlab::PluginSettings& settings) -> bvhlab::Accelerator* {
                                  return new Throwing(settings.getFloat(kCount.name) > 0);
                              }});
}

// A plugin whose accelerators throw where bvhlab must turn the exception into an error naming
// the plugin and the accelerator (tests/apps/test_plugins.cpp): `throwing` in build(),
// `throwing_query` in its queries, `throwing_factory` when made.
#include "framework/plugin/plugin_api.h"

#include <stdexcept>

namespace {

class Throwing final : public bvhlab::Accelerator {
public:
    explicit Throwing(bool inBuild) : inBuild_(inBuild) {}
    std::string_view name() const override { return inBuild_ ? "throwing" : "throwing_query"; }
    void build(const bvhlab::PrimitiveSet&) override {
        if (inBuild_) throw std::runtime_error("no build today");
    }
    bvhlab::BuildStats statistics() const override { return {}; }
    bool findNearest(const bvhlab::Ray&, bvhlab::Hit&, bvhlab::QueryCounters&) const override {
        throw std::runtime_error("no queries today");
    }
    bool isOccluded(const bvhlab::Ray&, bvhlab::QueryCounters&) const override {
        throw std::runtime_error("no queries today");
    }

private:
    bool inBuild_;
};

inline constexpr bvhlab::IntKey kUnused{"Throwing::unused", "3", 1, 9, "a key, to be listed by `bvhlab keys`"};

}  // namespace

BVHLAB_PLUGIN(registrar) {
    registrar.addAccelerator({"throwing", "throws in build()", {kUnused.declaration()},
                              [](const bvhlab::Env&) { return std::make_unique<Throwing>(true); }});
    registrar.addAccelerator({"throwing_query", "throws in its queries", {},
                              [](const bvhlab::Env&) { return std::make_unique<Throwing>(false); }});
    registrar.addAccelerator({"throwing_factory", "throws when made", {},
                              [](const bvhlab::Env&) -> std::unique_ptr<bvhlab::Accelerator> {
                                  throw std::invalid_argument("no accelerator today");
                              }});
}

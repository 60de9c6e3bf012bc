// A plugin of builders (tests/apps/test_plugins.cpp): `pairs`, a merge tree joining neighbours
// in the order given, round after round (a valid tree, not a good one); `interleaved`, a split
// rule that deals a node's primitives out to its children in turn (a valid tree whose boxes
// all span the scene: right answers at an absurd cost, tests/apps/test_check_command.cpp);
// `lossy`, a split rule that overwrites a primitive index; `costed`, a split rule that reads the
// run's SAH constants; `twice`, a merge tree that uses a node twice.
#include <bvhlab/plugin.h>

#include <algorithm>
#include <vector>

namespace {

using namespace bvhlab;

void pairs(View<const PrimRef> prims, View<Merge> out, const BuilderSettings&) {
    std::vector<uint32_t> level(prims.size());
    for (uint32_t i = 0; i < level.size(); ++i) level[i] = i;
    std::vector<Merge> merges;
    uint32_t next = uint32_t(prims.size());
    while (level.size() > 1) {
        std::vector<uint32_t> up;
        for (size_t i = 0; i + 1 < level.size(); i += 2) {
            merges.push_back({level[i], level[i + 1]});
            up.push_back(next++);
        }
        if (level.size() % 2) up.push_back(level.back());
        level = std::move(up);
    }
    std::copy(merges.begin(), merges.end(), out.begin());
}

class Interleaved final : public SplitRule {
public:
    size_t split(View<PrimRef> prims, const Bounds3&, const Bounds3&, bool) override {
        if (prims.size() < 2) return 0;
        std::vector<PrimRef> dealt;
        for (size_t first : {0, 1})
            for (size_t i = first; i < prims.size(); i += 2) dealt.push_back(prims[i]);
        std::copy(dealt.begin(), dealt.end(), prims.begin());
        return (prims.size() + 1) / 2;
    }
};

class Lossy final : public SplitRule {
public:
    size_t split(View<PrimRef> prims, const Bounds3&, const Bounds3&, bool) override {
        prims[1].prim = prims[0].prim;
        return prims.size() / 2;
    }
};

// Object-median splits, but a node whose primitives cost no more to test than a step down and
// half of them (n * cIntersect <= cTraversal + n / 2 * cIntersect) stays a leaf.
class Costed final : public SplitRule {
public:
    explicit Costed(const BuilderSettings& settings) : leafUpTo_(2.0f * settings.cTraversal / settings.cIntersect) {}

    size_t split(View<PrimRef> prims, const Bounds3&, const Bounds3& centroidBounds, bool mayBeLeaf) override {
        if (mayBeLeaf && float(prims.size()) <= leafUpTo_) return 0;
        const int axis = centroidBounds.largestAxis();
        const size_t half = prims.size() / 2;
        std::nth_element(prims.begin(), prims.begin() + half, prims.end(), [axis](const PrimRef& a, const PrimRef& b) {
            return a.center(axis) < b.center(axis) || (a.center(axis) == b.center(axis) && a.prim < b.prim);
        });
        return half;
    }

private:
    float leafUpTo_;
};

}  // namespace

BVHLAB_PLUGIN(registrar) {
    registrar.addBuilder({"pairs", "neighbours joined round after round", {}, {}, pairs});
    registrar.addBuilder({"interleaved",
                          "deals the primitives out to the children in turn",
                          {},
                          [](const BuilderSettings&) -> SplitRule* { return new Interleaved; },
                          {}});
    registrar.addBuilder({"lossy",
                          "overwrites a primitive index",
                          {},
                          [](const BuilderSettings&) -> SplitRule* { return new Lossy; },
                          {}});
    registrar.addBuilder({"costed",
                          "median splits, leaves where the SAH constants favour them",
                          {},
                          [](const BuilderSettings& settings) -> SplitRule* { return new Costed(settings); },
                          {}});
    registrar.addBuilder({"twice",
                          "uses a node twice",
                          {},
                          {},
                          [](View<const PrimRef> prims, View<Merge> merges, const BuilderSettings& s) {
                              pairs(prims, merges, s);
                              if (!merges.empty()) merges.back().right = merges.back().left;
                          }});
}

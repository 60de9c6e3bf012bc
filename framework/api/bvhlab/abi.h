// What bvhlab checks when it loads a plugin, before it calls anything else of it: the ABI the
// plugin was compiled against, as figures its compiler computed from the headers it saw (sizes,
// alignments, fields and offsets of the public structs, the virtual functions of the public
// classes, the C++ ABI of the compiler and its standard library), compared figure by figure with
// bvhlab's own; and how the plugin was compiled, recorded in the provenance of every run.
// BVHLAB_PLUGIN (<bvhlab/plugin.h>) exports both.
#pragma once

#include <bvhlab/registrar.h>

#include <cstddef>
#include <cstdint>

namespace bvhlab {

// One figure of an ABI: what is measured ("sizeof(Ray)") and its value. Its own layout is the
// one thing that never changes: bvhlab reads any plugin's figures through it.
struct AbiFigure {
    const char* what;
    uint64_t value;
};

namespace abi {

// The number of fields of an aggregate: how many values brace-initialise it.
struct AnyField {
    template <typename T>
    constexpr operator T() const { return T{}; }
};
template <typename T, typename... Fields>
constexpr uint64_t fieldCount() {
    if constexpr (requires { T{Fields{}..., AnyField{}}; }) return fieldCount<T, Fields..., AnyField>();
    else return sizeof...(Fields);
}

// FNV-1a, of text and of a value.
constexpr uint64_t hash(const char* text, uint64_t h = 14695981039346656037ull) {
    for (; *text; ++text) h = (h ^ uint8_t(*text)) * 1099511628211ull;
    return h;
}

// The names and the types of a class's virtual functions, as the compiler spells them.
template <typename... Types>
constexpr uint64_t typesHash() { return hash(__PRETTY_FUNCTION__); }
template <auto... Functions>
constexpr uint64_t count() { return sizeof...(Functions); }
template <auto... Functions>
constexpr uint64_t signature() { return hash(__PRETTY_FUNCTION__, typesHash<decltype(Functions)...>()); }

}  // namespace abi

#if defined(_GLIBCXX_USE_CXX11_ABI)
#define BVHLAB_ABI_CXX11_STRINGS _GLIBCXX_USE_CXX11_ABI
#else
#define BVHLAB_ABI_CXX11_STRINGS 0xFFFF  // not libstdc++
#endif
#define BVHLAB_ABI_STRUCT(T) {"sizeof(" #T ")", sizeof(T)}, {"alignof(" #T ")", alignof(T)}
#define BVHLAB_ABI_AGGREGATE(T) BVHLAB_ABI_STRUCT(T), {"fields of " #T, abi::fieldCount<T>()}
#define BVHLAB_ABI_OFFSET(T, field) {"offsetof(" #T ", " #field ")", offsetof(T, field)}
#define BVHLAB_ABI_CLASS(T, ...) \
    {"virtual functions of " #T, abi::count<__VA_ARGS__>()}, \
    {"signature of " #T, abi::signature<__VA_ARGS__>()}

// The ABI a translation unit sees. A virtual function added to one of the public classes is added
// to its list here, so that its signature changes.
inline constexpr AbiFigure kAbi[] = {
    {"__GXX_ABI_VERSION", __GXX_ABI_VERSION},
    {"_GLIBCXX_USE_CXX11_ABI", BVHLAB_ABI_CXX11_STRINGS},
    BVHLAB_ABI_STRUCT(void*),
    BVHLAB_ABI_STRUCT(size_t),
    BVHLAB_ABI_STRUCT(Vec3),
    BVHLAB_ABI_STRUCT(Bounds3),
    BVHLAB_ABI_STRUCT(View<int>),
    BVHLAB_ABI_AGGREGATE(Ray),
    BVHLAB_ABI_OFFSET(Ray, org),
    BVHLAB_ABI_OFFSET(Ray, dir),
    BVHLAB_ABI_OFFSET(Ray, tmin),
    BVHLAB_ABI_OFFSET(Ray, tmax),
    BVHLAB_ABI_AGGREGATE(Hit),
    BVHLAB_ABI_OFFSET(Hit, t),
    BVHLAB_ABI_OFFSET(Hit, primitive),
    BVHLAB_ABI_OFFSET(Hit, u),
    BVHLAB_ABI_OFFSET(Hit, v),
    BVHLAB_ABI_AGGREGATE(QueryCounters),
    BVHLAB_ABI_OFFSET(QueryCounters, queries),
    BVHLAB_ABI_OFFSET(QueryCounters, intersectionTests),
    BVHLAB_ABI_OFFSET(QueryCounters, traversalSteps),
    BVHLAB_ABI_OFFSET(QueryCounters, sphereTests),
    BVHLAB_ABI_OFFSET(QueryCounters, coneTests),
    BVHLAB_ABI_OFFSET(QueryCounters, counting),
    BVHLAB_ABI_AGGREGATE(RayCost),
    BVHLAB_ABI_AGGREGATE(Triangle),
    BVHLAB_ABI_AGGREGATE(Sphere),
    BVHLAB_ABI_AGGREGATE(Cone),
    BVHLAB_ABI_STRUCT(QuadricShape),
    BVHLAB_ABI_AGGREGATE(PrimitiveSet),
    BVHLAB_ABI_OFFSET(PrimitiveSet, triangles),
    BVHLAB_ABI_OFFSET(PrimitiveSet, valid),
    BVHLAB_ABI_OFFSET(PrimitiveSet, spheres),
    BVHLAB_ABI_OFFSET(PrimitiveSet, cones),
    BVHLAB_ABI_AGGREGATE(PrimRef),
    BVHLAB_ABI_OFFSET(PrimRef, prim),
    BVHLAB_ABI_OFFSET(PrimRef, upper),
    BVHLAB_ABI_AGGREGATE(Merge),
    BVHLAB_ABI_STRUCT(BuilderSettings),
    BVHLAB_ABI_STRUCT(KeyType),
    BVHLAB_ABI_AGGREGATE(PluginKey),
    BVHLAB_ABI_AGGREGATE(PluginAccelerator),
    BVHLAB_ABI_AGGREGATE(PluginBuilder),
    BVHLAB_ABI_CLASS(Accelerator, &Accelerator::name, &Accelerator::build, &Accelerator::statistics,
                     &Accelerator::findNearest, &Accelerator::isOccluded, &Accelerator::findNearestBatch,
                     &Accelerator::isOccludedBatch, &Accelerator::hasCounters),
    BVHLAB_ABI_CLASS(BuildStatistics, &BuildStatistics::set, &BuildStatistics::figure, &BuildStatistics::leafSizes),
    BVHLAB_ABI_CLASS(PluginSettings, &PluginSettings::getBool, &PluginSettings::getInt, &PluginSettings::getFloat,
                     &PluginSettings::getText, &PluginSettings::getVec3, &PluginSettings::getVec3List,
                     &PluginSettings::isExplicit),
    BVHLAB_ABI_CLASS(SplitRule, &SplitRule::split),
    BVHLAB_ABI_CLASS(PluginRegistrar, &PluginRegistrar::addAccelerator, &PluginRegistrar::addBuilder),
};

#undef BVHLAB_ABI_CXX11_STRINGS
#undef BVHLAB_ABI_STRUCT
#undef BVHLAB_ABI_AGGREGATE
#undef BVHLAB_ABI_OFFSET
#undef BVHLAB_ABI_CLASS

// How a plugin was compiled, read by bvhlab once the ABI matched: it warns when the plugin is not
// optimised (its times would not be representative) and records all three in the provenance.
struct PluginBuildInfo {
    const char* compiler;  // "GNU 12.2.0"
    bool optimized;        // __OPTIMIZE__ was defined: -O1 or higher, -Os or -Og
    const char* cxxFlags;  // the flags bvhlab_add_plugin recorded; "" for a plugin built otherwise
};

}  // namespace bvhlab

// What bvhlab checks when it loads a plugin, before it calls anything else of it: the ABI the
// plugin was compiled against, as figures its compiler computed from the headers it saw (sizes,
// alignments, fields and offsets of the public structs, the values of the public enums, the slot
// and type of every virtual function of the public classes) and from its toolchain (the C++ ABI,
// the standard library and its ABI), compared figure by figure with bvhlab's own; and how the
// plugin was compiled, recorded in the provenance of every run. BVHLAB_PLUGIN (<bvhlab/plugin.h>)
// exports both.
//
// Every figure is one that any compiler of the Itanium C++ ABI (GCC, Clang) computes alike from
// the same headers: no compiler's version and no compiler's spelling of a name enter it.
#pragma once

#include <bvhlab/registrar.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <typeinfo>

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
    constexpr operator T() const {
        return T{};
    }
};
template <typename T, typename... Fields>
constexpr uint64_t fieldCount() {
    if constexpr (requires { T{Fields{}..., AnyField{}}; })
        return fieldCount<T, Fields..., AnyField>();
    else
        return sizeof...(Fields);
}

// FNV-1a of a text.
constexpr uint64_t hash(const char* text, uint64_t h = 14695981039346656037ull) {
    for (; *text; ++text) h = (h ^ uint8_t(*text)) * 1099511628211ull;
    return h;
}

// The slot of a virtual function in its class's virtual table, read from a pointer to it as the
// Itanium C++ ABI represents one: {ptr, adj}, ptr being 1 + the function's offset in the table in
// bytes. Read at run time, as no compiler lets a constant expression look into such a pointer.
inline constexpr uint64_t kNotVirtual = ~uint64_t(0);
template <typename MemberFunction>
uint64_t vtableSlot(MemberFunction function) {
    struct {
        uint64_t ptr;
        int64_t adj;
    } itanium;
    static_assert(sizeof(function) == sizeof(itanium), "bvhlab's plugins follow the Itanium C++ ABI");
    std::memcpy(&itanium, &function, sizeof(itanium));
    return itanium.ptr & 1 ? (itanium.ptr - 1) / sizeof(void*) : kNotVirtual;
}

// A hash of a type as the Itanium C++ ABI mangles it (typeid's name), a spelling every compiler
// that follows the ABI shares: the class, the parameters, the result and the qualifiers.
template <typename T>
uint64_t typeHash() {
    return hash(typeid(T).name());
}

// The standard library, and its ABI: libstdc++'s dual ABI (_GLIBCXX_USE_CXX11_ABI, the layout of
// std::string and std::list) or libc++'s ABI version. A plugin's exceptions and bvhlab's handlers
// must agree on both.
inline constexpr uint64_t kOtherStandardLibrary = 0, kLibstdcxx = 1, kLibcxx = 2;
#if defined(_LIBCPP_VERSION)
inline constexpr uint64_t kStandardLibrary = kLibcxx, kStandardLibraryAbi = _LIBCPP_ABI_VERSION;
#elif defined(__GLIBCXX__)
inline constexpr uint64_t kStandardLibrary = kLibstdcxx, kStandardLibraryAbi = _GLIBCXX_USE_CXX11_ABI;
#else
inline constexpr uint64_t kStandardLibrary = kOtherStandardLibrary, kStandardLibraryAbi = 0;
#endif

// GCC and Clang define __GXX_ABI_VERSION on every target of the Itanium C++ ABI, and only there;
// its value is the compiler's own numbering (GCC 12 says 1017, Clang always 1002), not the ABI's.
#if defined(__GXX_ABI_VERSION)
inline constexpr uint64_t kItaniumAbi = 1;
#else
inline constexpr uint64_t kItaniumAbi = 0;
#endif

}  // namespace abi

#define BVHLAB_ABI_STRUCT(T) \
    {"sizeof(" #T ")", sizeof(T)}, { "alignof(" #T ")", alignof(T) }
#define BVHLAB_ABI_AGGREGATE(T) \
    BVHLAB_ABI_STRUCT(T), { "field count of " #T, abi::fieldCount<T>() }
#define BVHLAB_ABI_OFFSET(T, field) \
    { "offsetof(" #T ", " #field ")", offsetof(T, field) }
#define BVHLAB_ABI_ENUMERATOR(E, name) \
    { #E "::" #name, uint64_t(E::name) }
#define BVHLAB_ABI_CLASS(T) \
    { "virtual destructor of " #T, std::has_virtual_destructor_v<T> }
#define BVHLAB_ABI_VIRTUAL(T, function)                                       \
    {"vtable slot of " #T "::" #function, abi::vtableSlot(&T::function)}, {   \
        "type of " #T "::" #function, abi::typeHash<decltype(&T::function)>() \
    }

// The ABI the calling translation unit sees, computed there once. Hidden, so that a plugin's call
// always runs its own copy, never one the program exports. Every enumerator of a public enum and
// every virtual function of a public class is listed here (tests/framework/api/test_abi.cpp checks).
[[gnu::visibility("hidden")]] inline View<const AbiFigure> abiFigures() {
    static const AbiFigure figures[] = {
        {"Itanium C++ ABI", abi::kItaniumAbi},
        {"standard library", abi::kStandardLibrary},
        {"standard library ABI", abi::kStandardLibraryAbi},
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
        BVHLAB_ABI_STRUCT(RayCoherence),
        BVHLAB_ABI_ENUMERATOR(RayCoherence, Incoherent),
        BVHLAB_ABI_ENUMERATOR(RayCoherence, Coherent),
        BVHLAB_ABI_AGGREGATE(Hit),
        BVHLAB_ABI_OFFSET(Hit, t),
        BVHLAB_ABI_OFFSET(Hit, primitive),
        BVHLAB_ABI_OFFSET(Hit, u),
        BVHLAB_ABI_OFFSET(Hit, v),
        // Its slots, not its counters: a counter added in an unused slot leaves the ABI as it was.
        BVHLAB_ABI_STRUCT(QueryCounters),
        {"QueryCounters slots", kQueryCounterSlots},
        BVHLAB_ABI_OFFSET(QueryCounters, queries),
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
        BVHLAB_ABI_STRUCT(PrimitiveKind),
        BVHLAB_ABI_ENUMERATOR(PrimitiveKind, Triangle),
        BVHLAB_ABI_ENUMERATOR(PrimitiveKind, Sphere),
        BVHLAB_ABI_ENUMERATOR(PrimitiveKind, Cone),
        BVHLAB_ABI_AGGREGATE(PrimRef),
        BVHLAB_ABI_OFFSET(PrimRef, prim),
        BVHLAB_ABI_OFFSET(PrimRef, upper),
        BVHLAB_ABI_AGGREGATE(Merge),
        BVHLAB_ABI_STRUCT(BuilderSettings),
        BVHLAB_ABI_STRUCT(KeyType),
        BVHLAB_ABI_ENUMERATOR(KeyType, Bool),
        BVHLAB_ABI_ENUMERATOR(KeyType, Int),
        BVHLAB_ABI_ENUMERATOR(KeyType, Float),
        BVHLAB_ABI_ENUMERATOR(KeyType, String),
        BVHLAB_ABI_ENUMERATOR(KeyType, Choice),
        BVHLAB_ABI_ENUMERATOR(KeyType, Path),
        BVHLAB_ABI_ENUMERATOR(KeyType, Vec3),
        BVHLAB_ABI_ENUMERATOR(KeyType, Vec3List),
        BVHLAB_ABI_AGGREGATE(PluginKey),
        BVHLAB_ABI_AGGREGATE(PluginAccelerator),
        BVHLAB_ABI_AGGREGATE(PluginBuilder),
        BVHLAB_ABI_CLASS(Accelerator),
        BVHLAB_ABI_VIRTUAL(Accelerator, name),
        BVHLAB_ABI_VIRTUAL(Accelerator, build),
        BVHLAB_ABI_VIRTUAL(Accelerator, update),
        BVHLAB_ABI_VIRTUAL(Accelerator, statistics),
        BVHLAB_ABI_VIRTUAL(Accelerator, findNearest),
        BVHLAB_ABI_VIRTUAL(Accelerator, isOccluded),
        BVHLAB_ABI_VIRTUAL(Accelerator, findNearestBatch),
        BVHLAB_ABI_VIRTUAL(Accelerator, isOccludedBatch),
        BVHLAB_ABI_VIRTUAL(Accelerator, hasCounters),
        BVHLAB_ABI_CLASS(BuildStatistics),
        BVHLAB_ABI_VIRTUAL(BuildStatistics, set),
        BVHLAB_ABI_VIRTUAL(BuildStatistics, figure),
        BVHLAB_ABI_VIRTUAL(BuildStatistics, leafSizes),
        BVHLAB_ABI_CLASS(PluginSettings),
        BVHLAB_ABI_VIRTUAL(PluginSettings, getBool),
        BVHLAB_ABI_VIRTUAL(PluginSettings, getInt),
        BVHLAB_ABI_VIRTUAL(PluginSettings, getFloat),
        BVHLAB_ABI_VIRTUAL(PluginSettings, getText),
        BVHLAB_ABI_VIRTUAL(PluginSettings, getVec3),
        BVHLAB_ABI_VIRTUAL(PluginSettings, getVec3List),
        BVHLAB_ABI_VIRTUAL(PluginSettings, isExplicit),
        BVHLAB_ABI_CLASS(SplitRule),
        BVHLAB_ABI_VIRTUAL(SplitRule, split),
        BVHLAB_ABI_CLASS(PluginRegistrar),
        BVHLAB_ABI_VIRTUAL(PluginRegistrar, addAccelerator),
        BVHLAB_ABI_VIRTUAL(PluginRegistrar, addBuilder),
    };
    return figures;
}

#undef BVHLAB_ABI_STRUCT
#undef BVHLAB_ABI_AGGREGATE
#undef BVHLAB_ABI_OFFSET
#undef BVHLAB_ABI_ENUMERATOR
#undef BVHLAB_ABI_CLASS
#undef BVHLAB_ABI_VIRTUAL

// How a plugin was compiled, read by bvhlab once the ABI matched: it warns when the plugin is not
// optimised (its times would not be representative) and records all three in the provenance.
struct PluginBuildInfo {
    const char* compiler;  // "GNU 12.2.0"
    bool optimized;        // __OPTIMIZE__ was defined: -O1 or higher, -Os or -Og
    const char* cxxFlags;  // the flags bvhlab_add_plugin recorded; "" for a plugin built otherwise
};

}  // namespace bvhlab

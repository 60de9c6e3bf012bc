// A plugin's own keys: declared by the plugin, given in env files, with -D and in `--accel` lists
// as bvhlab's keys are, checked when they are set, and read by the plugin by name and type.
#pragma once

#include <bvhlab/math.h>
#include <bvhlab/view.h>

#include <cstdint>

namespace bvhlab {

enum class KeyType : uint8_t {
    Bool,      // true/false, on/off, yes/no, 1/0
    Int,       // with an inclusive range
    Float,     // with an inclusive range
    String,    // free text
    Choice,    // one of a fixed list of words
    Path,      // relative paths resolve against the folder of the env file that set them
    Vec3,      // "x y z", or empty for "not given"
    Vec3List,  // "x y z, x y z, ...", possibly empty
};

// The declaration of one key, as plain data a plugin keeps in a constant:
//   inline constexpr PluginKey kDepth{"KdMed::maxDepth", KeyType::Int, "24", "meaning", 1, 64};
struct PluginKey {
    const char* name;  // "Section::key", in a section of the plugin's own
    KeyType type;
    const char* defaultValue;              // as an env file would give it
    const char* description;               // one line, for `bvhlab keys`
    double min = 0.0, max = 0.0;           // Int and Float: the inclusive range
    View<const char* const> choices = {};  // Choice: the words
};

// The resolved values of a plugin's own keys (defaults, then env files, then -D), read by name
// with the getter of the key's type. Besides its own keys a structure may read the run's
// kThreadsKey (Int: its build's thread count, 0 = all hardware threads). A name the plugin did
// not declare, or a getter of another type, throws an exception that names the key; values were
// checked when they were set, so a declared key read by its type never fails. Text a getter
// returns lives as long as the settings.
inline constexpr const char* kThreadsKey = "SetRayTracing::threads";

class PluginSettings {
public:
    virtual bool getBool(const char* key) const = 0;
    virtual int getInt(const char* key) const = 0;
    virtual float getFloat(const char* key) const = 0;
    // String, Choice and Path keys (a path resolved, "" when not given).
    virtual const char* getText(const char* key) const = 0;
    // False, and `value` unchanged, when the key is not given.
    virtual bool getVec3(const char* key, Vec3& value) const = 0;
    virtual View<const Vec3> getVec3List(const char* key) const = 0;
    // Whether an env file or -D set the key, rather than its default.
    virtual bool isExplicit(const char* key) const = 0;

protected:
    ~PluginSettings() = default;
};

}  // namespace bvhlab

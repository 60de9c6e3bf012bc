// What a fatal signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) reports before the process dies
// of it: the plugin call that was running on the thread that received it, with the plugin file,
// the accelerator, the call, and the ray or the primitive count it was given. Plugin calls alone
// are recorded (accel/plugins/guarded_accelerator.cpp): bvhlab's own structures pay nothing.
#pragma once

#include <bvhlab/ray.h>

#include <cstddef>
#include <filesystem>
#include <string>

namespace bvhlab {

// A plugin call in progress. Holds pointers only, so that recording it costs a few stores; the
// strings and the ray outlive the call.
struct PluginCall {
    const char* plugin = "";  // the plugin's file
    const char* accelerator = "";
    const char* call = "";     // "build()", "findNearest()", ...
    const Ray* ray = nullptr;  // the query's ray, or a batch's first; null for a build
    size_t count = 0;          // a batch's rays, a build's primitives
};

// Makes `call` the calling thread's running call for the scope's lifetime. A call without a ray
// (a build) is also recorded for the process, so that a crash in a thread the plugin started
// names it too. The first scope on a thread gives it a signal stack, so that a stack overflow
// is reported as well.
class PluginCallScope {
public:
    explicit PluginCallScope(const PluginCall& call);
    ~PluginCallScope();
    PluginCallScope(const PluginCallScope&) = delete;
    PluginCallScope& operator=(const PluginCallScope&) = delete;

    struct Thread;  // the thread's running call (fatal_signal_report.cpp)

private:
    const PluginCall* call_;
    Thread* thread_;
    const PluginCall* previous_;
};

// Installs the handlers (once; later calls do nothing). On a fatal signal the handler writes one
// line, "SIGSEGV (Segmentation fault) in plugin FILE, accelerator 'NAME': findNearest() of the
// ray org=(...) dir=(...) t in [...]" (or that no plugin call was running), to stderr prefixed
// with "bvhlab: ", or to the file reportFatalSignalsTo() named; then the signal takes its
// course (the handler installed before, or the default action), so the process still dies of it.
void installFatalSignalReport();

// From now on the report goes to `file` (created or truncated) instead of stderr: how a child
// process of `bvhlab check` tells its parent what crashed. Throws InputError.
void reportFatalSignalsTo(const std::filesystem::path& file);

// "SIGSEGV (Segmentation fault)", or "signal 70" for a number without a name.
std::string signalDescription(int signal);

}  // namespace bvhlab

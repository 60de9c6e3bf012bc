// A plugin's accelerator behind a guard: an exception thrown by its factory, build or queries
// reaches the user as an error naming the plugin and the accelerator, not as a crash or as a
// bare message from code they did not write; a crash inside its build or queries is reported
// naming them, the call and its ray (framework/core/fatal_signal_report.h).
#pragma once

#include "framework/core/accelerator.h"

#include <fmt/format.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace bvhlab {

class PluginError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Runs `body`, turning what it throws into "plugin FILE, accelerator 'NAME': WHAT threw: ...".
template <typename Body>
auto guardPlugin(const std::string& plugin, const std::string& accelerator, std::string_view what, Body&& body) {
    auto fail = [&](std::string_view message) {
        return PluginError(
            fmt::format("plugin {}, accelerator '{}': {} threw: {}", plugin, accelerator, what, message));
    };
    try {
        return body();
    } catch (const PluginError&) {
        throw;  // already named (a query inside a guarded batch)
    } catch (const std::exception& e) {
        throw fail(e.what());
    } catch (...) {
        throw fail("an exception that is not a std::exception");
    }
}

// `inner` with every call guarded; name() answers `accelerator`, the name it was chosen by.
std::unique_ptr<Accelerator> guardAccelerator(std::unique_ptr<Accelerator> inner, std::string plugin,
                                              std::string accelerator);

}  // namespace bvhlab

// The checks of `bvhlab check`, each in a process of its own, so that a structure that crashes
// fails the check it crashed in, with the signal and the plugin call that was running, and the
// checks after it still run. The child is the program again (/proc/self/exe) with the parent's
// command line and two hidden options: the check to run and the file for its result (JSON),
// where its fatal-signal report goes too (framework/core/fatal_signal_report.h).
#pragma once

#include "accel/verify/conformance.h"

#include <nlohmann/json.hpp>

#include <string>

namespace bvhlab::check {

// What a child process of `bvhlab check` is asked: one check, and where its result goes.
struct ChildCheck {
    std::string check;
    std::string resultFile;

    bool isChild() const { return !check.empty(); }
    // From now on a fatal signal is reported in the result file. Throws InputError.
    void reportFatalSignals() const;
    void writeResult(const verify::CheckResult& result) const;
};

// Runs check `name` in a child process and returns its result; a child that dies of a signal
// or ends without a result fails the check, its examples saying what the child reported.
verify::CheckResult runCheckInChild(const std::string& name);

// A check's result as `--json` writes it, and back.
nlohmann::json toJson(const verify::CheckResult& result);
verify::CheckResult checkResultFromJson(const nlohmann::json& json);

}  // namespace bvhlab::check

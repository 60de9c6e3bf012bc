// The checks of `bvhlab check`, each in a process of its own (apps/runtime/child_job.h), so that
// a structure that crashes fails the check it crashed in, with the signal and the plugin call
// that was running, one that never returns fails it when its time is up, and the checks after it
// still run.
#pragma once

#include "accel/verify/conformance.h"

#include <nlohmann/json.hpp>

#include <string>

namespace bvhlab::check {

// Runs check `name` in a child process and returns its result; a child that dies of a signal,
// runs longer than `timeoutSeconds` (0: no limit) or ends without a result fails the check, its
// note and examples saying why.
verify::CheckResult runCheckInChild(const std::string& name, double timeoutSeconds);

// A check's result as `--json` writes it, and back.
nlohmann::json toJson(const verify::CheckResult& result);
verify::CheckResult checkResultFromJson(const nlohmann::json& json);

}  // namespace bvhlab::check

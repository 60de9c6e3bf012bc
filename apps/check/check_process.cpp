#include "apps/check/check_process.h"

#include "apps/runtime/child_job.h"

#include <fmt/format.h>

namespace bvhlab::check {

verify::CheckResult runCheckInChild(const std::string& name, double timeoutSeconds) {
    const JobOutcome outcome = runJobInChild(name, timeoutSeconds);
    if (outcome.passed()) return checkResultFromJson(outcome.result);
    verify::CheckResult failed;
    failed.check = name;
    failed.failures = 1;
    failed.seconds = outcome.seconds;
    failed.note = outcome.reason;
    // The crash's report: the signal, and the plugin call with its ray or primitive count.
    if (!outcome.detail.empty()) failed.examples.push_back(fmt::format("{}: {}", name, outcome.detail));
    return failed;
}

nlohmann::json toJson(const verify::CheckResult& r) {
    return {{"check", r.check},     {"passed", r.passed()}, {"skipped", r.skipped},  {"warning", r.warning},
            {"scenes", r.scenes},   {"cases", r.cases},     {"unit", r.unit},        {"failures", r.failures},
            {"seconds", r.seconds}, {"note", r.note},       {"examples", r.examples}};
}

verify::CheckResult checkResultFromJson(const nlohmann::json& json) {
    verify::CheckResult r;
    r.check = json.at("check");
    r.unit = json.at("unit");
    r.scenes = json.at("scenes");
    r.cases = json.at("cases");
    r.failures = json.at("failures");
    r.skipped = json.at("skipped");
    r.warning = json.at("warning");
    r.note = json.at("note");
    r.examples = json.at("examples").get<std::vector<std::string>>();
    r.seconds = json.at("seconds");
    return r;
}

}  // namespace bvhlab::check

// What every result file records of the run that made it, beside the code's provenance: the
// command line, when it started, its warnings, and the scene file actually read with its checksum.
#pragma once

#include "framework/scene/scene.h"

#include <nlohmann/json.hpp>

namespace bvhlab {

// Called once by main: the command line and the start time.
void recordRun(int argc, char** argv);

// Prints "warning: `warning`" on stderr (not in a job's child process, whose parent has said it)
// and keeps it for runJson(): what a run did that its results do not show, such as a scene seen
// without its scene env.
void warnOfRun(const std::string& warning);

// {"command_line": "bvhlab render ...", "started": "2026-12-01T20:33:00Z", "warnings": [...]}
nlohmann::json runJson();

// {"file": absolute path, "size": bytes, "crc32": "...", "adler32": "..."}, or {"file": null,
// "embedded": true} for the embedded default scene.
nlohmann::json sceneFileJson(const Scene& scene);

}  // namespace bvhlab

// The tables of `bvhlab batch`, made from the job files in DIR/jobs (one per scene x accelerator,
// both shadow settings), so that one run and merged shards give the same tables: Markdown in
// the report's layout, CSV, JSON, and the contact sheet of the renders.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

// Names of the job file and images: SCENE__ACCEL.
std::string batchJobName(const std::string& scene, const std::string& accel);

// Every DIR/jobs/*.json, in table order (scene list order, then accelerator order). A file that
// is not a job is skipped with a warning on stderr.
std::vector<nlohmann::json> readBatchJobs(const std::filesystem::path& dir);

struct BatchTables {
    std::string markdown;   // results.md
    std::string csv;        // results.csv
    nlohmann::json json;    // results.json
    std::vector<std::string> warnings;  // e.g. jobs run with different settings
};

// Two rows per job: without shadows, and "+ shadows" with T_R, N_IT, N_TR averaged over all
// queries of that render (primary and shadow together) and N_Q counting them all. The JSON
// keeps primary and shadow apart.
BatchTables makeBatchTables(const std::vector<nlohmann::json>& jobs);

// Writes results.md, results.csv, results.json and contact_sheet.png into `dir` from its jobs;
// returns the tables (for printing).
BatchTables writeBatchResults(const std::filesystem::path& dir);

}  // namespace bvhlab

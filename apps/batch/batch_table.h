// The tables of `bvhlab batch`, made from the job files in DIR/jobs (one per scene x accelerator,
// both shadow settings) of the batch DIR/batch.json records, so that one run and merged shards
// give the same tables: Markdown in the report's layout, CSV, JSON, and the contact sheet.
#pragma once

#include "apps/batch/batch_settings.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

// Names of the job file and images: SCENE__ACCEL, each as labelAsFileName makes it.
std::string batchJobName(const std::string& scene, const std::string& accel);

// The jobs of the batch `settings` in DIR/jobs, in table order (scene list order, then accelerator
// order). A file that is not a job, or a job of other settings, is skipped with a warning on stderr.
std::vector<nlohmann::json> readBatchJobs(const std::filesystem::path& dir, const BatchSettings& settings);

struct BatchTables {
    std::string markdown;               // results.md
    std::string csv;                    // results.csv
    std::string framesCsv;              // animation_frames.csv: the animated scenes' frames; empty without
    nlohmann::json json;                // results.json
    std::vector<std::string> warnings;  // e.g. jobs run with different settings
    size_t failedJobs = 0;              // jobs that crashed, threw or timed out: a row with the reason each
};

// Two rows per job: without shadows, and "+ shadows" with T_R, N_IT, N_TR averaged over all
// queries of that render (primary and shadow together) and N_Q counting them all. The JSON
// keeps primary and shadow apart.
// A job that failed (its file holds "failed": the reason) is one row with the reason.
// An animated scene's jobs (Batch::animate) make a section of their own after the table:
// `bvhlab animate`'s summary table, a row per job, and the JSON's "animations".
// The title and the footer count the jobs shown, and the footer says when they are fewer than the
// batch's `batchJobs` (a shard, an interrupted run).
BatchTables makeBatchTables(const std::vector<nlohmann::json>& jobs, size_t batchJobs);

// Writes results.md, results.csv, results.json and contact_sheet.png into `dir` from the jobs of
// its batch (DIR/batch.json); returns the tables (for printing).
BatchTables writeBatchResults(const std::filesystem::path& dir);

}  // namespace bvhlab

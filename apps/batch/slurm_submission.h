// `bvhlab batch --slurm N`: a batch as a Slurm job array of N shards and a merge job after them.
// Both scripts are written into DIR/slurm/ (so that they can be read and submitted again by
// hand) and submitted with sbatch. Shard I runs `bvhlab batch --shard I/N` into DIR/shards/I
// and, only when that succeeds, leaves DIR/slurm/shard-I.done. The merge job depends on the
// array with afterany, not afterok: with afterok a failed shard would leave it pending for ever
// and nobody told; so it runs once every shard has ended, and fails naming the log of each shard
// without its .done (failed, cancelled, never started), else merges the shards into DIR. A
// partial table is never presented as the whole batch.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

struct SlurmBatch {
    std::filesystem::path out;  // the batch's folder, absolute: the merged tables
    int shards = 1;
    std::filesystem::path program;            // the bvhlab the shards and the merge run
    std::filesystem::path workingDir;         // where they run: relative arguments stay valid
    std::vector<std::string> batchArguments;  // a shard's `bvhlab batch` arguments but --shard and --out
    int cpusPerShard = 1;                     // its render threads; 0 (all) leaves --cpus-per-task unset
    std::string sbatchArguments;              // --slurm-args: given to sbatch as the shell splits them
};

// DIR/shards/I: the folder shard I of the batch in `out` runs into.
std::filesystem::path slurmShardFolder(const std::filesystem::path& out, int shard);

// sbatch as PATH finds it. Throws InputError, saying so, when it is not there.
std::filesystem::path findSbatch();

struct SlurmJobIds {
    std::string shards;  // the array job (its tasks are SHARDS_0 .. SHARDS_{N-1})
    std::string merge;
};

// Writes DIR/slurm/shards.sbatch and merge.sbatch and submits them with `sbatch` (the path
// findSbatch gave). Throws InputError when sbatch fails, saying what was submitted already.
SlurmJobIds submitSlurmBatch(const SlurmBatch& batch, const std::filesystem::path& sbatch);

// What to tell the user: the job ids, how to follow them, where the logs and the tables go.
std::string slurmSubmissionSummary(const SlurmBatch& batch, const SlurmJobIds& ids);

}  // namespace bvhlab

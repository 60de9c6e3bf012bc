#include "apps/batch/slurm_submission.h"

#include "apps/runtime/atomic_write.h"
#include "apps/runtime/shell_word.h"
#include "framework/core/error.h"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace bvhlab {
namespace {

std::string word(const std::filesystem::path& path) { return shellWord(path.string()); }

std::string shardsScript(const SlurmBatch& b, const std::filesystem::path& script) {
    std::vector<std::string> batchArgs;
    for (const std::string& argument : b.batchArguments) batchArgs.push_back(shellWord(argument));
    const std::string cpus = b.cpusPerShard > 0 ? fmt::format("#SBATCH --cpus-per-task={}\n", b.cpusPerShard) : "";
    return fmt::format(
        R"(#!/bin/bash
# Written by `bvhlab batch --slurm {n}`: the batch in {out} as a Slurm array of {n} shards. Shard I
# runs jobs I, I+{n}, I+2*{n}, ... into shards/I and, only when that succeeds, leaves
# slurm/shard-I.done, which merge.sbatch checks. Submitted with
#   sbatch --parsable {args}{script}
# One shard again: sbatch --array=I {args}{script}, then merge.sbatch after it. A shard that is
# requeued (preempted, or its node failed) runs the same command again, which keeps the jobs it
# finished and runs the rest; its log goes on after the first attempt's lines.
#SBATCH --job-name=bvhlab-shard
#SBATCH --array=0-{last}
#SBATCH --requeue
#SBATCH --open-mode=append
{cpus}#SBATCH --output={log}
out={out}
shard=$SLURM_ARRAY_TASK_ID
rm -f "$out/slurm/shard-$shard.done"
cd {cwd} || exit 1
{program} batch {batchArgs} --shard "$shard/{n}" --out "$out/shards/$shard" && touch "$out/slurm/shard-$shard.done"
)",
        fmt::arg("n", b.shards), fmt::arg("out", word(b.out)), fmt::arg("script", word(script)),
        fmt::arg("args", b.sbatchArguments.empty() ? "" : b.sbatchArguments + " "), fmt::arg("last", b.shards - 1),
        fmt::arg("cpus", cpus), fmt::arg("log", word(b.out / "slurm" / "shard-%a.log")),
        fmt::arg("cwd", word(b.workingDir)), fmt::arg("program", word(b.program)),
        fmt::arg("batchArgs", fmt::join(batchArgs, " ")));
}

std::string mergeScript(const SlurmBatch& b, const std::filesystem::path& script) {
    std::vector<std::string> folders;
    for (int shard = 0; shard < b.shards; ++shard) folders.push_back(fmt::format("\"$out/shards/{}\"", shard));
    return fmt::format(
        R"(#!/bin/bash
# Written by `bvhlab batch --slurm {n}`: the merge of the {n} shards of shards.sbatch into {out}.
# It depends on their array job with afterany, so it runs once every shard has ended, whether it
# succeeded or not: a shard without its slurm/shard-I.done (it failed, was cancelled or never
# started) fails the merge, named with its log, and nothing is merged. Submitted with
#   sbatch --parsable {args}--dependency=afterany:ARRAY_JOB_ID {script}
#SBATCH --job-name=bvhlab-merge
#SBATCH --cpus-per-task=1
#SBATCH --output={log}
out={out}
unfinished=0
for shard in $(seq 0 {last}); do
  if [ ! -e "$out/slurm/shard-$shard.done" ]; then
    echo "error: shard $shard/{n} did not finish (it failed, was cancelled or never started): see its log $out/slurm/shard-$shard.log" >&2
    unfinished=$((unfinished + 1))
  fi
done
if [ "$unfinished" -gt 0 ]; then
  echo "error: $unfinished of {n} shards did not finish: nothing merged into $out" >&2
  exit 1
fi
cd {cwd} || exit 1
exec {program} batch --merge {folders} --out "$out"
)",
        fmt::arg("n", b.shards), fmt::arg("out", word(b.out)), fmt::arg("script", word(script)),
        fmt::arg("args", b.sbatchArguments.empty() ? "" : b.sbatchArguments + " "), fmt::arg("last", b.shards - 1),
        fmt::arg("log", word(b.out / "slurm" / "merge.log")), fmt::arg("cwd", word(b.workingDir)),
        fmt::arg("program", word(b.program)), fmt::arg("folders", fmt::join(folders, " ")));
}

// Runs an sbatch command line through the shell (so that --slurm-args split as the user typed
// them) and returns the job id it prints (--parsable: "ID" or "ID;CLUSTER"). sbatch's own
// messages reach stderr as they are.
std::string submit(const std::string& command) {
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) throw InputError(fmt::format("cannot run `{}`: {}", command, std::strerror(errno)));
    std::string output;
    char buffer[256];
    while (size_t n = fread(buffer, 1, sizeof(buffer), pipe)) output.append(buffer, n);
    const int status = pclose(pipe);
    if (status != 0)
        throw InputError(fmt::format("`{}` failed (exit code {}; sbatch's message is above)", command,
                                     WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status)));
    const std::string id = output.substr(0, output.find_first_of(";\n"));
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
        throw InputError(fmt::format("`{}` printed no job id, but '{}'", command, output));
    return id;
}

}  // namespace

std::filesystem::path slurmShardFolder(const std::filesystem::path& out, int shard) {
    return out / "shards" / std::to_string(shard);
}

std::filesystem::path findSbatch() {
    const char* path = std::getenv("PATH");
    std::stringstream folders(path ? path : "");
    for (std::string folder; std::getline(folders, folder, ':');) {
        const std::filesystem::path candidate = std::filesystem::path(folder.empty() ? "." : folder) / "sbatch";
        if (std::filesystem::is_regular_file(candidate) && access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    throw InputError(
        fmt::format("--slurm: sbatch is not on PATH ({}): run this where jobs are submitted to the "
                    "cluster (a Slurm login node), or put Slurm's bin folder on PATH",
                    path ? path : "unset"));
}

SlurmJobIds submitSlurmBatch(const SlurmBatch& batch, const std::filesystem::path& sbatch) {
    const std::filesystem::path folder = batch.out / "slurm";
    std::filesystem::create_directories(folder);
    const std::filesystem::path shards = folder / "shards.sbatch", merge = folder / "merge.sbatch";
    writeFileAtomically(shards, shardsScript(batch, shards));
    writeFileAtomically(merge, mergeScript(batch, merge));
    // A marker of an earlier submission must not pass for this one's.
    for (int shard = 0; shard < batch.shards; ++shard)
        std::filesystem::remove(folder / fmt::format("shard-{}.done", shard));

    const std::string sbatchCommand =
        word(sbatch) + " --parsable" + (batch.sbatchArguments.empty() ? "" : " " + batch.sbatchArguments);
    SlurmJobIds ids;
    ids.shards = submit(fmt::format("{} {}", sbatchCommand, word(shards)));
    try {
        ids.merge = submit(fmt::format("{} --dependency=afterany:{} {}", sbatchCommand, ids.shards, word(merge)));
    } catch (const InputError& e) {
        throw InputError(
            fmt::format("{}; the shards are submitted as job {}: cancel them (scancel {}) or submit "
                        "the merge by hand",
                        e.what(), ids.shards, ids.shards));
    }
    return ids;
}

std::string slurmSubmissionSummary(const SlurmBatch& batch, const SlurmJobIds& ids) {
    const std::string slurm = (batch.out / "slurm").string();
    return fmt::format(
        "submitted to Slurm: {n} shards as array job {a} ({a}_0 .. {a}_{last}), the merge as job {m} (once every "
        "shard has ended)\n"
        "  follow:  squeue -j {a},{m}   (after they end: scontrol show job {a}; sacct -j {a},{m} where the cluster "
        "keeps accounts)\n"
        "  logs:    {slurm}/shard-I.log (I = 0..{last}), {slurm}/merge.log\n"
        "  tables:  {out}/results.md when job {m} has completed; it fails instead, naming the shard and its log, if "
        "a shard did not finish\n",
        fmt::arg("n", batch.shards), fmt::arg("a", ids.shards), fmt::arg("last", batch.shards - 1),
        fmt::arg("m", ids.merge), fmt::arg("slurm", slurm), fmt::arg("out", batch.out.string()));
}

}  // namespace bvhlab

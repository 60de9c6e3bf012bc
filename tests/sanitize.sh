#!/usr/bin/env bash
# The sanitizer pass of CI (README command 2 runs it after the normal suite): the test suite
# built with AddressSanitizer, UndefinedBehaviorSanitizer and libstdc++'s assertions into
# build-san/, then run without the tests that parse the large shared scenes (minutes under
# ASan; the readers are fuzzed instead, see docs/accuracy.md) and without SlurmCluster (a second
# private Slurm; the code it runs is that of the BatchSlurm tests, which run here). Extra
# arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-san -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBVHLAB_SANITIZE=ON \
  -DCMAKE_COMPILE_WARNING_AS_ERROR=ON
cmake --build build-san -j "$(nproc)"
ctest --test-dir build-san --output-on-failure -j 2 -E 'SharedScenes|SlurmCluster' "$@"

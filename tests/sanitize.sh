#!/usr/bin/env bash
# The sanitizer pass of CI (README command 2 runs it after the normal suite): the test suite
# built with AddressSanitizer, UndefinedBehaviorSanitizer and libstdc++'s assertions into
# build-san/, then run without
# - the tests that parse the large shared scenes (minutes under ASan; the readers are fuzzed
#   instead, see docs/accuracy.md);
# - SlurmCluster (a second private Slurm; the code it runs is that of the BatchSlurm tests, which
#   run here);
# - the package tests, which install the build, configure projects and build plugins with other
#   compilers (the Release suite runs them; the plugin loading they reach runs here in
#   tests/apps/test_plugins.cpp), and the tree's own checks (Format, ConfigureIsQuiet).
# The conformance suite checks a quarter of its rays here (tests/accel/verify/test_conformance.cpp).
# Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
# Not warnings as errors: at -O1 under ASan GCC 12 warns (-Wmaybe-uninitialized) inside <regex>.
cmake -S . -B build-san -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBVHLAB_SANITIZE=ON \
  -DCMAKE_COMPILE_WARNING_AS_ERROR=OFF
cmake --build build-san -j "$(nproc)"
not_here='SharedScenes|SlurmCluster|PluginExample|PackageAddSubdirectory|ClangPluginLoads|RelocatedInstall'
not_here+='|^Format$|^ConfigureIsQuiet$'
ctest --test-dir build-san --output-on-failure -j 2 -E "$not_here" "$@"

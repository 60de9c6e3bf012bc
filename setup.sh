#!/usr/bin/env bash
# Installs what bvhlab needs on Debian 12 (only what is missing), then configures and builds
# it into build/ (Release): the bvhlab program and its Python module (build/python), and with
# --tests everything (the test suite too).
# Other arguments go to CMake, e.g. ./setup.sh -DBVHLAB_NATIVE=OFF
set -euo pipefail
cd "$(dirname "$0")"

packages=(g++ cmake ninja-build pkg-config git
          libembree-dev libopenexr-dev libglm-dev libgtest-dev libtbb-dev libtinyobjloader-dev
          libstb-dev zlib1g-dev libcli11-dev nlohmann-json3-dev libfmt-dev
          python3-matplotlib   # bvhlab plot (apps/plot/) and docs/python.md, with /usr/bin/python3
          python3-dev pybind11-dev python3-numpy python3-pytest  # the Python module (docs/python.md)
          slurmctld slurmd slurm-client munge   # the SlurmCluster test (tests/slurm/with_local_slurm.sh)
          clang   # a plugin built by clang++ (the ClangPluginLoads test, tests/package/check_plugin.sh)
          clang-format)  # the Format test (tests/check_format.sh, .clang-format)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
  # The SlurmCluster test starts a munged of its own; the system's, which the package starts under
  # systemd (slurmctld and slurmd do not start without /etc/slurm/slurm.conf), is not left running.
  if [[ " ${missing[*]} " == *" munge "* ]] && [ -d /run/systemd/system ]; then
    $sudo systemctl disable --now munge.service || echo "setup: munge.service could not be stopped" >&2
  fi
fi

targets=(bvhlab)
cmake_args=()
for arg in "$@"; do
  # The tests' build, as CI's, takes a warning for an error.
  if [ "$arg" = --tests ]; then targets=(all); cmake_args+=(-DCMAKE_COMPILE_WARNING_AS_ERROR=ON)
  else cmake_args+=("$arg"); fi
done
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${cmake_args[@]+"${cmake_args[@]}"}
# The Python module too (docs/python.md), unless -DBVHLAB_PYTHON=OFF left it out.
if [ "${targets[*]}" = bvhlab ] && ninja -C build -t query bvhlab_python >/dev/null 2>&1; then
  targets+=(bvhlab_python)
fi
cmake --build build -j "$(nproc)" --target "${targets[@]}"

// libFuzzer target for the env parser: the input is loaded as an env file, each of its lines is
// also given as a -D override, and then every registered key is read back with its getter and
// through the consumers of the env (BVH and Embree configuration, camera, render settings).
// Bad input must end in an InputError; anything else is a finding. Built with -DBVHLAB_FUZZ=ON.
#include "apps/runtime/program_keys.h"
#include "framework/config/env.h"
#include "framework/core/error.h"
#include "tests/fuzz/read_every_env_key.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // One scratch file per process, removed at exit.
    struct Scratch {
        std::string path = "/dev/shm/bvhlab-fuzz-env-" + std::to_string(getpid()) + ".env";
        ~Scratch() { std::remove(path.c_str()); }
    };
    static const Scratch scratch;
    const std::string& path = scratch.path;
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;

    bvhlab::Env env(bvhlab::programKeys());
    try {
        env.loadFile(path);
    } catch (const bvhlab::InputError&) {
    }
    bvhlab::readEveryEnvKey(env);

    bvhlab::Env overridden(bvhlab::programKeys());
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        try {
            overridden.setOverride(line);
        } catch (const bvhlab::InputError&) {
        }
    }
    bvhlab::readEveryEnvKey(overridden);
    return 0;
}

// One RTCDevice as bvhlab's Embree structures use it (EmbreeAccelerator, EmbreeInstances): made
// from an EmbreeConfig, its errors turned into exceptions, its memory counted.
//
// Threads: the device is created with "threads=N". Embree applies this process-wide: while a
// device lives it installs a tbb::global_control limiting all TBB parallelism in the process
// (with several devices alive, the largest request wins; 0 = unlimited).
//
// ISA: Embree::isa limits the device's kernels (max_isa, not isa: Embree then takes the best of
// its kernels up to that ISA the CPU runs, where isa= would refuse an ISA the CPU lacks).
#pragma once

#include "accel/embree/embree_env.h"

#include <memory>
#include <stdexcept>
#include <string>

// Embree's opaque handles (embree3/rtcore_device.h, rtcore_scene.h; the Debian build has no
// API namespace). Declared here so that users of the structures' headers need not see Embree's
// headers; embree_device.cpp checks that they match.
struct RTCDeviceTy;
struct RTCSceneTy;

namespace bvhlab {

// An error reported by Embree (device creation, buffer allocation, commit). The message names
// the Embree call, the error code and Embree's own description.
class EmbreeError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class EmbreeDevice {
public:
    // Throws EmbreeError when Embree refuses (e.g. unsupported CPU, a negative thread count).
    explicit EmbreeDevice(const EmbreeConfig& config);
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;

    RTCDeviceTy* get() const { return device_.get(); }
    // The configuration string it was created with, e.g. "threads=1,max_isa=avx2".
    const std::string& configString() const { return configString_; }
    // Throws EmbreeError for an error Embree reported since the last check, naming `call`.
    void check(const char* call) const;
    // Memory Embree holds for this device, as its memory monitor counted it: the difference
    // across a commit is what the commit kept.
    int64_t bytes() const;
    // The vector width of the kernels Embree runs on this device, in bits: 128 (SSE), 256 (AVX,
    // AVX2) or 512 (AVX-512).
    int kernelBits() const;

private:
    struct State;  // the error and memory callbacks' payload; must outlive the device
    struct Deleter {
        void operator()(RTCDeviceTy* device) const;
    };
    std::string configString_;
    std::unique_ptr<State> state_;
    std::unique_ptr<RTCDeviceTy, Deleter> device_;  // after state_: released before it
};

}  // namespace bvhlab

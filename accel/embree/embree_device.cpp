#include "accel/embree/embree_device.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <atomic>
#include <mutex>
#include <type_traits>

static_assert(std::is_same_v<RTCDevice, RTCDeviceTy*>, "Embree's handle types differ from the forward declarations");
static_assert(std::is_same_v<RTCScene, RTCSceneTy*>, "Embree's handle types differ from the forward declarations");

namespace bvhlab {

namespace {

const char* errorName(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE:
            return "RTC_ERROR_NONE";
        case RTC_ERROR_UNKNOWN:
            return "RTC_ERROR_UNKNOWN";
        case RTC_ERROR_INVALID_ARGUMENT:
            return "RTC_ERROR_INVALID_ARGUMENT";
        case RTC_ERROR_INVALID_OPERATION:
            return "RTC_ERROR_INVALID_OPERATION";
        case RTC_ERROR_OUT_OF_MEMORY:
            return "RTC_ERROR_OUT_OF_MEMORY";
        case RTC_ERROR_UNSUPPORTED_CPU:
            return "RTC_ERROR_UNSUPPORTED_CPU";
        case RTC_ERROR_CANCELLED:
            return "RTC_ERROR_CANCELLED";
    }
    return "unknown RTCError";
}

}  // namespace

struct EmbreeDevice::State {
    std::mutex mutex;
    RTCError code = RTC_ERROR_NONE;  // the first error since the last check
    std::string message;
    std::atomic<int64_t> bytes{0};  // memory Embree holds, from the memory monitor

    static void onError(void* user, RTCError code, const char* str) {
        if (code == RTC_ERROR_NONE) return;
        auto* self = static_cast<State*>(user);
        std::lock_guard lock(self->mutex);
        if (self->code != RTC_ERROR_NONE) return;
        self->code = code;
        self->message = str ? str : "";
    }

    // Possibly called from several of Embree's threads at once; we never cancel an
    // allocation, so every call counts (bytes > 0 allocated, < 0 freed).
    static bool onMemory(void* user, ssize_t bytes, bool /*post*/) {
        static_cast<State*>(user)->bytes.fetch_add(int64_t(bytes), std::memory_order_relaxed);
        return true;
    }
};

void EmbreeDevice::Deleter::operator()(RTCDeviceTy* device) const { rtcReleaseDevice(device); }

EmbreeDevice::EmbreeDevice(const EmbreeConfig& config) : state_(std::make_unique<State>()) {
    if (config.threads < 0) throw EmbreeError(fmt::format("Embree: negative thread count {}", config.threads));
    configString_ = fmt::format("threads={}", config.threads);
    if (!config.maxIsa.empty()) configString_ += fmt::format(",max_isa={}", config.maxIsa);
    RTCDevice device = rtcNewDevice(configString_.c_str());
    if (!device) {
        const RTCError code = rtcGetDeviceError(nullptr);
        throw EmbreeError(fmt::format("Embree error in rtcNewDevice(\"{}\"): {}", configString_, errorName(code)));
    }
    device_.reset(device);
    rtcSetDeviceErrorFunction(device, &State::onError, state_.get());
    rtcSetDeviceMemoryMonitorFunction(device, &State::onMemory, state_.get());
    check("rtcSetDeviceErrorFunction");
}

EmbreeDevice::~EmbreeDevice() = default;

// Errors reach us through the device's error callback (which records them instead of throwing
// through Embree's C API) and through the per-thread error code, which is read and cleared here
// as well.
void EmbreeDevice::check(const char* call) const {
    const RTCError threadCode = rtcGetDeviceError(device_.get());
    RTCError code;
    std::string message;
    {
        std::lock_guard lock(state_->mutex);
        code = state_->code;
        message = std::move(state_->message);
        state_->code = RTC_ERROR_NONE;
        state_->message.clear();
    }
    if (code == RTC_ERROR_NONE) code = threadCode;
    if (code == RTC_ERROR_NONE) return;
    throw EmbreeError(
        fmt::format("Embree error in {}: {}{}{}", call, errorName(code), message.empty() ? "" : ": ", message));
}

int64_t EmbreeDevice::bytes() const { return state_->bytes.load(); }

int EmbreeDevice::kernelBits() const {
    // Embree names no ISA it chose; its packets follow the ISA (8 rays from AVX on, 16 with
    // AVX-512), so the widest one it traces natively is the width of its kernels.
    if (rtcGetDeviceProperty(device_.get(), RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) return 512;
    if (rtcGetDeviceProperty(device_.get(), RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) return 256;
    return 128;
}

}  // namespace bvhlab

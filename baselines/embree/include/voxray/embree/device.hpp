// RAII owner of an Embree 3 device, shared by the scenes built on it.
//
// Embree reports errors through a C callback. A C++ exception must not unwind through
// Embree's C frames, so the callback only records the message; every wrapper call that can
// fail is followed by check(), which turns the recorded error into a voxray::error on the
// caller's side. The device also counts the bytes Embree allocates (memory monitor), which
// is how the scenes report the size of Embree's BVH and buffers.
#pragma once
#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>

#include <embree3/rtcore.h>

#include "voxray/core/error.hpp"

namespace voxray::embree {

inline const char* error_name(RTCError code) {
    switch (code) {
    case RTC_ERROR_NONE: return "none";
    case RTC_ERROR_UNKNOWN: return "unknown";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unrecognised error";
    }
}

class device {
public:
    // `config` is Embree's device configuration string ("threads=2,verbose=1", ...).
    explicit device(const char* config = nullptr) : state_(std::make_shared<state>()) {
        state_->handle = rtcNewDevice(config);
        if (!state_->handle)
            fail("embree: rtcNewDevice(\"", config ? config : "", "\") failed: ",
                 error_name(rtcGetDeviceError(nullptr)));
        rtcSetDeviceErrorFunction(state_->handle, &on_error, state_.get());
        rtcSetDeviceMemoryMonitorFunction(state_->handle, &on_memory, state_.get());
    }

    RTCDevice handle() const { return state_->handle; }

    // Throws voxray::error if Embree reported an error since the last check on this thread.
    // `what` names the operation for the message ("rtcCommitScene", ...).
    void check(const char* what) const {
        RTCError code = rtcGetDeviceError(state_->handle);
        if (code == RTC_ERROR_NONE) return;
        std::string message;
        {
            std::lock_guard lock(state_->mutex);
            message.swap(state_->last_message);
        }
        fail("embree: ", what, " failed: ", error_name(code), message.empty() ? "" : ": ", message);
    }

    // Bytes Embree currently holds for this device (BVHs, geometry buffers, scratch).
    std::size_t allocated_bytes() const {
        auto n = state_->allocated.load(std::memory_order_relaxed);
        return n > 0 ? std::size_t(n) : 0;
    }

    // Whether this CPU/build traces 16-wide packets natively (AVX-512); otherwise Embree
    // emulates rtcIntersect16 with narrower packets, which is still correct.
    bool native_ray16() const {
        return rtcGetDeviceProperty(state_->handle, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
    }

private:
    // Kept behind a shared_ptr so the callbacks' user pointer stays valid while any copy of the
    // device (or a scene holding one) is alive, and so the device is released exactly once.
    struct state {
        RTCDevice handle = nullptr;
        std::mutex mutex;
        std::string last_message;
        std::atomic<long long> allocated{0};
        ~state() {
            if (handle) rtcReleaseDevice(handle);
        }
    };

    static void on_error(void* user, RTCError code, const char* text) {
        auto* s = static_cast<state*>(user);
        std::lock_guard lock(s->mutex);
        s->last_message = std::string(error_name(code)) + (text ? std::string(": ") + text : std::string());
    }
    static bool on_memory(void* user, ssize_t bytes, bool /*post*/) {
        // Embree calls this with positive sizes before allocating and negative sizes after
        // freeing; returning true never vetoes an allocation.
        static_cast<state*>(user)->allocated.fetch_add(bytes, std::memory_order_relaxed);
        return true;
    }

    std::shared_ptr<state> state_;
};

// Owning handle of an RTCScene (released with rtcReleaseScene), so scene classes can be
// moved without hand-written move operations.
struct scene_release {
    void operator()(RTCScene s) const {
        if (s) rtcReleaseScene(s);
    }
};
using scene_handle = std::unique_ptr<RTCSceneTy, scene_release>;

}  // namespace voxray::embree

// Start-up settings of the Vulkan backend.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "voxray/vulkan/interop.hpp"

namespace voxray {

struct vulkan_options {
    // Use the first device whose name contains this text (case-sensitive). Empty: the
    // environment variable VOXRAY_VULKAN_DEVICE if set, else the first discrete GPU, else
    // integrated, virtual, and last a CPU implementation such as lavapipe.
    std::string device;
    // Always go through staging buffers and copy commands, as on a discrete GPU without
    // host-visible device memory, even where every memory type is host-visible (tests use
    // this to exercise that path on lavapipe).
    bool force_staging = false;
    // Invocations per workgroup of the trace shaders (a power of two, within the device's
    // limits). 0: the environment variable VOXRAY_GROUP_SIZE if set, else 64.
    std::uint32_t group_size = 0;
    // Run on the application's device instead of creating one (see vulkan/interop.hpp);
    // `device` is then ignored. voxray borrows the handles and never destroys them.
    std::optional<vulkan_user_device> user_device;
};

}  // namespace voxray

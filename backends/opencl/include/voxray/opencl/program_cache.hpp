// One OpenCL context per device, with each voxray program (one per structure, and the
// commit program) built in it once, on first use. Engines on the same device share it
// through a process-wide registry, so a second tracer costs no second build (PoCL: about
// 0.5 s cold). A program that fails to build throws for its structure only. The registry
// holds weak references: the context goes away with the last engine that used it, never
// during static destruction.
#pragma once
#include <CL/cl.h>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>

#include "voxray/generated/opencl_programs.hpp"
#include "voxray/opencl/device.hpp"
#include "voxray/core/host_code.hpp"
#include "voxray/opencl/error.hpp"
#include "voxray/opencl/handles.hpp"

namespace voxray::opencl_detail {

// Build logs can run to megabytes when every line of a long program fails; the start of
// the log is where the first (causal) error is.
inline constexpr std::size_t max_build_log_chars = 16384;

class device_context {
public:
    explicit device_context(const device_choice& choice);

    // The application's context (opencl/interop.hpp): retained here, released by
    // context_handle, so the application's own reference stays valid.
    device_context(const device_choice& choice, cl_context borrowed);

    cl_context context() const { return context_.get(); }
    cl_device_id device() const { return choice_.device; }
    // Program `p`, built on first use (thread-safe); throws opencl_error with the build log.
    cl_program program(const program_source& p) {
        std::lock_guard lock(programs_mutex_);
        auto it = programs_.find(p.name);
        if (it == programs_.end()) it = programs_.emplace(std::string(p.name), build(p)).first;
        return it->second.program.get();
    }
    // Seconds program `name` took to build (0 if it was not built).
    double build_seconds(std::string_view name) {
        std::lock_guard lock(programs_mutex_);
        auto it = programs_.find(name);
        return it == programs_.end() ? 0.0 : it->second.seconds;
    }
    const std::string& device_name() const { return choice_.device_name; }
    const std::string& platform_name() const { return choice_.platform_name; }
    std::uint64_t max_alloc_bytes() const { return max_alloc_; }
    std::size_t max_work_group_size() const { return max_group_; }
    // Whether the program was built with -cl-fp32-correctly-rounded-divide-sqrt; without
    // it 1/d may differ from C++ in the last bit, and t with it (within tolerance).
    bool correctly_rounded_division() const { return correctly_rounded_; }
    const std::string& build_options() const { return options_; }

private:
    // Limits and build options of the device.
    void read_device();

    struct built_program {
        program_handle program;
        double seconds = 0;
    };

    built_program build(const program_source& p) const;

    std::string build_log(cl_program program) const;

    device_choice choice_;
    context_handle context_;
    std::mutex programs_mutex_;
    std::map<std::string, built_program, std::less<>> programs_;
    std::uint64_t max_alloc_ = 0;
    std::size_t max_group_ = 1;
    bool correctly_rounded_ = false;
    std::string options_;
};

// The shared context of the device `options` select, created (and its program built)
// on first use; or the application's context (opencl_options::user_context), shared by
// the tracers made on it. While an entry lives it retains its cl_context, so the key
// cannot be freed and reused by another context meanwhile.
VOXRAY_HOST_INLINE std::shared_ptr<device_context> acquire_device_context(const opencl_options& options);

}  // namespace voxray::opencl_detail

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/opencl/detail/program_cache.hpp"
#endif

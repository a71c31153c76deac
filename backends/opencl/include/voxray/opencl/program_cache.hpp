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
#include "voxray/opencl/error.hpp"
#include "voxray/opencl/handles.hpp"

namespace voxray::opencl_detail {

// Build logs can run to megabytes when every line of a long program fails; the start of
// the log is where the first (causal) error is.
inline constexpr std::size_t max_build_log_chars = 16384;

class device_context {
public:
    explicit device_context(const device_choice& choice) : choice_(choice) {
        cl_int status = CL_SUCCESS;
        cl_context_properties props[] = {CL_CONTEXT_PLATFORM,
                                         reinterpret_cast<cl_context_properties>(choice.platform), 0};
        context_ = context_handle(clCreateContext(props, 1, &choice_.device, nullptr, nullptr, &status));
        check(status, "clCreateContext", "opening device '" + choice_.device_name + "'");
        read_device();
    }

    // The application's context (opencl/interop.hpp): retained here, released by
    // context_handle, so the application's own reference stays valid.
    device_context(const device_choice& choice, cl_context borrowed) : choice_(choice) {
        check(clRetainContext(borrowed), "clRetainContext", "the application's context");
        context_ = context_handle(borrowed);
        read_device();
    }

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
    void read_device() {
        max_alloc_ = device_value<cl_ulong>(choice_.device, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
        max_group_ = device_value<std::size_t>(choice_.device, CL_DEVICE_MAX_WORK_GROUP_SIZE);
        auto fp = device_value<cl_device_fp_config>(choice_.device, CL_DEVICE_SINGLE_FP_CONFIG);
        correctly_rounded_ = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
        // -cl-std: the kernels are OpenCL C 1.2 (PoCL offers nothing newer anyway).
        // Correctly rounded division: only where the device offers it (the option is
        // invalid elsewhere); it makes the DDA's 1/d match the CPU backends bit for bit.
        options_ = "-cl-std=CL1.2";
        if (correctly_rounded_) options_ += " -cl-fp32-correctly-rounded-divide-sqrt";
    }

    struct built_program {
        program_handle program;
        double seconds = 0;
    };

    built_program build(const program_source& p) const {
        auto start = std::chrono::steady_clock::now();
        const char* source = p.source;
        cl_int status = CL_SUCCESS;
        program_handle program(clCreateProgramWithSource(context_.get(), 1, &source, nullptr, &status));
        check(status, "clCreateProgramWithSource", "the " + std::string(p.name) + " program");
        status = clBuildProgram(program.get(), 1, &choice_.device, options_.c_str(), nullptr, nullptr);
        if (status != CL_SUCCESS) {
            std::string log = build_log(program.get());
            if (log.size() > max_build_log_chars) log = log.substr(0, max_build_log_chars) + "\n[... log truncated]";
            throw opencl_error(std::string("OpenCL: clBuildProgram failed: ") + cl_status_name(status) + " (" +
                                   std::to_string(status) + ") building the voxray " + std::string(p.name) +
                                   " program for '" + choice_.device_name + "' with options '" + options_ +
                                   "'. Build log:\n" + log,
                               status);
        }
        return {std::move(program), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
    }

    std::string build_log(cl_program program) const {
        std::size_t size = 0;
        if (clGetProgramBuildInfo(program, choice_.device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size) != CL_SUCCESS)
            return "(no build log available)";
        std::string log(size, '\0');
        clGetProgramBuildInfo(program, choice_.device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
        while (!log.empty() && log.back() == '\0') log.pop_back();
        return log;
    }

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
inline std::shared_ptr<device_context> acquire_device_context(const opencl_options& options) {
    static std::mutex mutex;
    if (options.user_context) {
        static std::map<std::pair<cl_context, cl_device_id>, std::weak_ptr<device_context>> borrowed;
        device_choice choice = check_user_context(*options.user_context);
        std::lock_guard lock(mutex);
        auto& slot = borrowed[{options.user_context->context, choice.device}];
        if (auto existing = slot.lock()) return existing;
        auto fresh = std::make_shared<device_context>(choice, options.user_context->context);
        slot = fresh;
        return fresh;
    }
    static std::map<cl_device_id, std::weak_ptr<device_context>> registry;
    device_choice choice = select_device(options);
    std::lock_guard lock(mutex);
    auto& slot = registry[choice.device];
    if (auto existing = slot.lock()) return existing;
    auto fresh = std::make_shared<device_context>(choice);
    slot = fresh;
    return fresh;
}

}  // namespace voxray::opencl_detail

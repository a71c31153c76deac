// The backend policy type: tracer<opencl, Structure> runs Structure's portable kernel
// as OpenCL C on the device chosen by opencl_options.
#pragma once
#include "voxray/opencl/engine.hpp"

namespace voxray {

struct opencl {
    using options = opencl_options;
    template <class Kernel>
    using engine = opencl_detail::opencl_engine<Kernel>;
    static constexpr const char* name = "opencl";
};

}  // namespace voxray

/* voxray OpenCL backend: the text placed before the portable kernel files when they are
 * flattened into one OpenCL C 1.2 program (cmake/voxray_kernels.cmake).
 * The kernels pick their dialect from this macro (kernels/prelude.h), so it must come
 * first. Program build options (opencl/program_cache.hpp) add -cl-std=CL1.2 and
 * -cl-fp32-correctly-rounded-divide-sqrt: 1/d then rounds exactly like C++, which keeps
 * the DDA's cell crossings, and so the hits, bit-identical to the CPU backends. */
#define VX_DIALECT_OPENCL 1

/* The shared dialect every structure kernel builds on, after the prelude and in dependency
 * order: the one list of its files. The CPU lanes include it once per lane set
 * (voxray/cpu/lanes.hpp, voxray/cpu/simd_lanes.inc); the flattener inlines it into every
 * OpenCL and GLSL program and into the installed shader sources (cmake/voxray_kernels.cmake).
 * Included once per lane set; no include guard on purpose. */
#include "voxray/kernels/ray.h"
#include "voxray/kernels/dda.h"
#include "voxray/kernels/stack.h"
#include "voxray/kernels/bits.h"
#include "voxray/svdag/walk.h"
#include "voxray/entities/layout.h"
#include "voxray/entities/pass.h"

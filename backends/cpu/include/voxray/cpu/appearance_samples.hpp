// What many voxels' records show along their rays, evaluated 8 or 16 at once on the SIMD
// lanes: the compositing walk's rounds (cpu/appearance_walk.hpp) gather the voxels their
// cursors are to blend and take the samples from here. The lane code is the one source
// the GPUs and the scalar lanes run (appearance/compact_record.h), so the samples are
// theirs bit for bit. Compiled once in voxray::kernels where a program links it (as the
// structures' streams are), else in the program's own files.
#pragma once
#include <cstddef>
#include <cstdint>

#include "voxray/cpu/appearance_kernels.hpp"

namespace voxray::cpu_detail {
// One record to evaluate: its row, the unit direction of the ray, the light reaching it.
struct appearance_job {
    std::uint32_t row;
    float dx, dy, dz;
    kernels::scalar::vx_app_light light;
};
}  // namespace voxray::cpu_detail

// The samples of `count` jobs' records of kind Kind (VX_APP_KIND_COMPACT: the kind with lane
// code) into out, in one lane set (simd8 or simd16); PREFIX: `extern` or nothing.
#define VOXRAY_CPU_SAMPLE_INSTANCES(PREFIX, LANES)                                                             \
    PREFIX template void voxray::kernels::LANES::sample_stream<VX_APP_KIND_COMPACT>(                           \
        const std::uint32_t*, const std::uint32_t*, const voxray::cpu_detail::appearance_job*,                 \
        voxray::kernels::scalar::vx_app_sample*, std::size_t);

// The sample stream, once per SIMD lane set (see sample_stream.inc).
#define VOXRAY_LANE_SET_BODY "voxray/cpu/sample_stream.inc"
#include "voxray/cpu/each_lane_set.inc"

namespace voxray::cpu_detail {
// The samples of `count` jobs' records of kind Kind on `width` lanes (8 or 16).
template <std::uint32_t Kind>
void sample_lanes(unsigned width, const std::uint32_t* records, const std::uint32_t* faces,
                  const appearance_job* jobs, kernels::scalar::vx_app_sample* out, std::size_t count) {
    if (width == 16)
        kernels::simd16::sample_stream<Kind>(records, faces, jobs, out, count);
    else
        kernels::simd8::sample_stream<Kind>(records, faces, jobs, out, count);
}
}  // namespace voxray::cpu_detail

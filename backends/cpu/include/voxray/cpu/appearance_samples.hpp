// What many voxels' records show along their rays, evaluated 8 or 16 at once on the SIMD
// lanes: the compositing walk's rounds (cpu/appearance_walk.hpp) gather the voxels their
// cursors are to blend and take the samples from here. The lane code is the one source
// the GPUs and the scalar lanes run (appearance/compact_record.h), so the samples are
// theirs bit for bit. Compiled once in voxray::kernels where a program links it (as the
// structures' streams are), else in the program's own files.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>  // sample_stream.inc
#include <vector>

#include "voxray/cpu/appearance_kernels.hpp"

namespace voxray::cpu_detail {
// Jobs, one array a field: lane k of a lane group takes entry begin + k, so each field of
// a group loads as one vector (no lane-by-lane packing). A job is a record's row, the unit
// direction of the ray and the light reaching the voxel.
struct appearance_job_fields {
    const std::uint32_t* row;
    const float *dx, *dy, *dz, *lx, *ly, *lz, *ambient;
};
// Their samples, one array a field, stored a lane group at once.
struct appearance_sample_fields {
    float *r, *g, *b, *a, *nx, *ny, *nz;
};

// The arrays behind both for up to n jobs, with room for the lane groups' spare lanes: a
// round's buffers, kept from round to round.
class appearance_round {
public:
    // Entries past a count up to the next whole group of the widest lane set.
    static constexpr std::size_t widest = 16;

    void fit(std::size_t n) {
        const std::size_t padded = (n + widest - 1) / widest * widest;
        rows_.resize(padded);
        for (std::vector<float>& f : floats_) f.resize(padded);
    }
    void set_job(std::size_t i, std::uint32_t row, float dx, float dy, float dz,
                 const kernels::scalar::vx_app_light& l) {
        rows_[i] = row;
        const float values[jobs_floats] = {dx, dy, dz, l.lx, l.ly, l.lz, l.ambient};
        for (std::size_t f = 0; f < jobs_floats; ++f) floats_[f][i] = values[f];
    }
    // Jobs [count, next whole group) repeat job count - 1 (count > 0), so that spare lanes
    // evaluate a real record; their samples are not read.
    void pad(std::size_t count) {
        for (std::size_t i = count; i % widest != 0; ++i) {
            rows_[i] = rows_[count - 1];
            for (std::size_t f = 0; f < jobs_floats; ++f) floats_[f][i] = floats_[f][count - 1];
        }
    }
    appearance_job_fields jobs() const {
        return {rows_.data(),        floats_[0].data(), floats_[1].data(), floats_[2].data(),
                floats_[3].data(),   floats_[4].data(), floats_[5].data(), floats_[6].data()};
    }
    appearance_sample_fields samples() {
        auto at = [&](std::size_t f) { return floats_[jobs_floats + f].data(); };
        return {at(0), at(1), at(2), at(3), at(4), at(5), at(6)};
    }
    void set_sample(std::size_t i, const kernels::scalar::vx_app_sample& s) {
        const float values[samples_floats] = {s.r, s.g, s.b, s.a, s.nx, s.ny, s.nz};
        for (std::size_t f = 0; f < samples_floats; ++f) floats_[jobs_floats + f][i] = values[f];
    }
    kernels::scalar::vx_app_sample sample(std::size_t i) const {
        auto at = [&](std::size_t f) { return floats_[jobs_floats + f][i]; };
        return {at(0), at(1), at(2), at(3), at(4), at(5), at(6)};
    }

private:
    static constexpr std::size_t jobs_floats = 7, samples_floats = 7;
    std::vector<std::uint32_t> rows_;
    std::array<std::vector<float>, jobs_floats + samples_floats> floats_;
};
}  // namespace voxray::cpu_detail

// The samples of jobs [0, count) of records of kind Kind (VX_APP_KIND_COMPACT: the kind with
// lane code), whole lane groups at once (padded: see appearance_round::pad), in one lane set
// (simd8 or simd16); PREFIX: `extern` or nothing.
#define VOXRAY_CPU_SAMPLE_INSTANCES(PREFIX, LANES)                                                             \
    PREFIX template void voxray::kernels::LANES::sample_stream<VX_APP_KIND_COMPACT>(                           \
        const std::uint32_t*, const std::uint32_t*, const voxray::cpu_detail::appearance_job_fields&,          \
        const voxray::cpu_detail::appearance_sample_fields&, std::size_t);

// The sample stream, once per SIMD lane set (see sample_stream.inc).
#define VOXRAY_LANE_SET_BODY "voxray/cpu/sample_stream.inc"
#include "voxray/cpu/each_lane_set.inc"

namespace voxray::cpu_detail {
// The samples of a round's jobs [0, count) of records of kind Kind on `width` lanes (8 or 16).
template <std::uint32_t Kind>
void sample_lanes(unsigned width, const std::uint32_t* records, const std::uint32_t* faces, appearance_round& round,
                  std::size_t count) {
    if (count == 0) return;
    round.pad(count);
    if (width == 16)
        kernels::simd16::sample_stream<Kind>(records, faces, round.jobs(), round.samples(), count);
    else
        kernels::simd8::sample_stream<Kind>(records, faces, round.jobs(), round.samples(), count);
}
}  // namespace voxray::cpu_detail

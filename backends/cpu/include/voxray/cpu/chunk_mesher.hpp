// The mesher kernel (meshing/kernel.h) on the CPU's scalar lanes: the very source the GPUs
// run, on host words, its items shared by a thread pool. The CPU's own mesher
// (meshing/mesher.hpp) is the fast path on the CPU; this one is for checking the kernel
// without a device, and for the backends' common tests.
//
//   voxray::cpu_chunk_mesher mesher({.ambient_occlusion = true});
//   std::vector<voxray::meshing::chunk_mesh> meshes = mesher.mesh(chunks);
#pragma once
#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#if !defined(VOXRAY_LINKED_CPU)
#error "voxray/cpu/chunk_mesher.hpp needs voxray::cpu (the scalar lanes the kernel runs on): link it"
#endif
#include "voxray/core/error.hpp"
#include "voxray/cpu/lanes.hpp"
#include "voxray/cpu/thread_pool.hpp"
#include "voxray/meshing/kernel_mesher.hpp"

namespace voxray::kernels::scalar {
#include "voxray/meshing/kernel.h"
}  // namespace voxray::kernels::scalar

namespace voxray::cpu_detail {

class mesher_device {
public:
    static constexpr const char* backend = "cpu-scalar";

    explicit mesher_device(unsigned threads = 0) : pool_(std::make_unique<thread_pool>(threads)) {}

    std::string device_name() const { return "the CPU (scalar lanes, " + std::to_string(pool_->size()) + " threads)"; }
    void upload(std::vector<std::uint32_t> words) { blob_ = std::move(words); }
    void frame_reserve(std::size_t words) {
        if (frame_.size() < words) frame_.assign(words, 0);
    }
    void frame_write(std::size_t at, std::span<const std::uint32_t> words) {
        check_range(at, words.size());
        std::copy(words.begin(), words.end(), frame_.begin() + std::ptrdiff_t(at));
    }
    void frame_read(std::size_t at, std::span<std::uint32_t> words) const {
        check_range(at, words.size());
        std::copy_n(frame_.begin() + std::ptrdiff_t(at), words.size(), words.begin());
    }
    void run_pass(std::uint32_t pass, std::uint64_t items) {
        const std::uint32_t* blob = blob_.data();
        std::uint32_t* frame = frame_.data();
        constexpr std::uint64_t batch = 16;  // a plane is thousands of steps: small batches share well
        pool_->parallel_for(std::size_t((items + batch - 1) / batch), [&](std::size_t b) {
            std::uint64_t end = std::min<std::uint64_t>(items, (b + 1) * batch);
            for (std::uint64_t i = b * batch; i < end; ++i)
                kernels::scalar::vx_mesher_pass(blob, frame, pass, std::uint32_t(i));
        });
    }
    const std::vector<std::uint32_t>& frame() const { return frame_; }

private:
    void check_range(std::size_t at, std::size_t n) const {
        if (at + n > frame_.size())
            fail("cpu mesher kernel: frame words [", at, ", ", at + n, ") outside its ", frame_.size());
    }

    std::unique_ptr<thread_pool> pool_;
    std::vector<std::uint32_t> blob_, frame_;
};

}  // namespace voxray::cpu_detail

namespace voxray {
using cpu_chunk_mesher = meshing::kernel_mesher<cpu_detail::mesher_device>;
}  // namespace voxray

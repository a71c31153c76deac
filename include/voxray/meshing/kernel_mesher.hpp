// The mesher kernel (meshing/kernel.h) driven on any backend: chunks in, chunk meshes out,
// the same quads in the same POP order as the CPU mesher (meshing/mesher.hpp). `Device`
// is a backend's runner of the kernel's passes (cpu/chunk_mesher.hpp,
// opencl/chunk_mesher.hpp, vulkan/chunk_mesher.hpp):
//
//   upload(words)             the chunks' input words (meshing/kernel_words.hpp)
//   frame_reserve(words)      room for the frame
//   frame_write(at, words), frame_read(at, words)
//   run_pass(pass, items)     one pass over `items` items, run to completion
//   device_name(), and `backend`, the backend's name in the tool ("opencl")
//
// run() leaves the quads in the device's frame, for a renderer on the same device to pull
// (quads_word()); mesh() also reads them back, for a test, an exporter or the CPU side.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/meshing/chunk.hpp"
#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/kernel_layout.h"
#include "voxray/meshing/kernel_words.hpp"
#include "voxray/meshing/mesher.hpp"

namespace voxray::meshing {

template <class Device>
class kernel_mesher {
public:
    template <class... DeviceArgs>
    explicit kernel_mesher(mesher_options options = {}, DeviceArgs&&... device_args)
        : options_(options), device_(std::forward<DeviceArgs>(device_args)...) {}

    Device& device() { return device_; }
    std::string device_name() const { return device_.device_name(); }
    static constexpr const char* backend_name() { return Device::backend; }  // as the tool names backends

    // Meshes `chunks` (each at its own origin) and reads the meshes back; `capacity`: the
    // most quads a chunk may have, which sizes the device's frame. A chunk with more is an
    // error with the numbers.
    std::vector<chunk_mesh> mesh(std::span<const chunk_voxels> chunks, std::uint32_t capacity = most_chunk_quads) {
        run(chunks, capacity);
        return read_meshes(chunks);
    }

    // Meshes `chunks` into the device's frame and leaves them there: nothing comes back to
    // the host. Chunk i's quads start at frame word quads_word(i), its table and total at
    // table_word(i) (meshing/kernel_layout.h); a chunk over `capacity` has its total but no
    // quads written.
    void run(std::span<const chunk_voxels> chunks, std::uint32_t capacity = most_chunk_quads) {
        frame_ = kernel_frame{chunks.size(), capacity};
        if (chunks.empty()) return;
        frame_.check();
        device_.upload(pack_chunks_words(chunks));
        device_.frame_reserve(frame_.words());
        std::uint32_t flags =
            (options_.ambient_occlusion ? VX_MK_FLAG_AO : 0u) | (options_.pop_order ? VX_MK_FLAG_POP : 0u);
        device_.frame_write(0, frame_.header(flags));
        std::uint64_t planes = std::uint64_t(chunks.size()) * VX_MK_PLANES;
        device_.run_pass(VX_MK_PASS_COUNT, planes);
        device_.run_pass(VX_MK_PASS_PLACE, chunks.size());
        device_.run_pass(VX_MK_PASS_EMIT, planes);
    }

    // The meshes of the last run(), whose chunks were `chunks`.
    std::vector<chunk_mesh> read_meshes(std::span<const chunk_voxels> chunks) {
        if (chunks.size() != frame_.chunks)
            fail("mesher kernel: ", chunks.size(), " chunks asked for, the last run meshed ", frame_.chunks);
        std::vector<chunk_mesh> meshes(chunks.size());
        std::vector<std::uint32_t> table_and_total(VX_MESH_TABLE_ENTRIES + 1);
        for (std::size_t i = 0; i < chunks.size(); ++i) {
            device_.frame_read(table_word(i), table_and_total);
            std::uint32_t total = table_and_total[VX_MESH_TABLE_ENTRIES];
            if (total > frame_.capacity)
                fail("mesher kernel on ", device_.device_name(), ": chunk ", i, " at (", chunks[i].origin.x, ", ",
                     chunks[i].origin.y, ", ", chunks[i].origin.z, ") has ", total, " quads, over the mesh buffer's ",
                     frame_.capacity, " a chunk");
            meshes[i].origin = chunks[i].origin;
            std::copy_n(table_and_total.begin(), VX_MESH_TABLE_ENTRIES, meshes[i].table.begin());
            meshes[i].words.resize(std::size_t(total) * VX_MESH_QUAD_WORDS);
            device_.frame_read(quads_word(i), meshes[i].words);
        }
        return meshes;
    }

    // Frame words of chunk i's table (then its total) and of its first quad.
    std::uint64_t table_word(std::size_t i) const { return frame_.block(i) + VX_MK_TABLE; }
    std::uint64_t quads_word(std::size_t i) const { return frame_.block(i) + VX_MK_QUADS; }

private:
    mesher_options options_;
    Device device_;
    kernel_frame frame_;
};

}  // namespace voxray::meshing

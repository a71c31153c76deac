// The one policy interface: tracer<Backend, Structure>. Swapping voxray::cpu for
// voxray::opencl or voxray::vulkan is the only change a user makes to move a
// structure to another backend; there are no virtual calls on the hot path.
//
// What a backend must offer: voxray/backend_contract.hpp (concepts, checked below).
// The tracer owns a snapshot of the structure's blob as of construction or the last
// update(); the structure itself may be changed or destroyed afterwards.
//
// Incremental updates: a structure that tracks its edits offers
//   std::vector<word_range> take_dirty_ranges();   // the words changed since the last call
// and update(structure) on a non-const structure then sends only those words (cost
// proportional to the edit). A structure whose blob changed size, or one without dirty
// tracking, is sent whole, except where the structure declares
//   static constexpr bool growth_keeps_prefix = true;
// (its blob only grows at the end when it grows, and its ranges name every word that
// changed, below the old size and above it): a backend that offers grow_ranges() then
// keeps the old words on the device and sends only the ranges (the brickmap's pool
// doubling, say).
//
// A structure edited from other threads offers generations instead (brickmap does):
//   frame snapshot() const;              // {lock, blob, generation}: writers wait meanwhile
//   frame changes_since(generation);     // {lock, blob, ranges changed since, generation}
// The tracer then reads the blob only under the frame's lock, and remembers the
// generation it holds: each of several tracers gets exactly what it is missing, and
// the first update after construction sends only what changed since.
#pragma once
#include <algorithm>
#include <concepts>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "voxray/backend_contract.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/core/word_range.hpp"
#include "voxray/edit/edit_op.hpp"
#include "voxray/edit/regions.hpp"

namespace voxray {

// What tracer<Backend, Structure> needs of a structure: a kernel tag (declared by
// kernels/kernel_tag.inc in the structure's header), a name, and its blob of words.
template <class S>
concept structure = requires(const S& s) {
    typename S::kernel;
    { S::kernel::name } -> std::convertible_to<const char*>;
    { S::name } -> std::convertible_to<std::string_view>;
    { s.blob() } -> std::convertible_to<std::span<const std::uint32_t>>;
};

// A structure that reports which blob words its edits changed. take_dirty_ranges() is
// non-const: taking the ranges clears them.
template <class Structure>
concept tracks_dirty_ranges = requires(Structure& s) {
    { s.take_dirty_ranges() } -> std::convertible_to<std::span<const word_range>>;
};

// See the top comment: growth at the end of the blob, with every changed word in the ranges.
template <class S>
concept grows_in_place = requires { requires S::growth_keeps_prefix; };

// A structure edited in place through the shared editing vocabulary (edit/regions.hpp,
// edit/edit_op.hpp), whose tracers then receive only the words that changed.
template <class S>
concept editable_structure = structure<S> && tracks_dirty_ranges<S> && requires(S& s, regions::sphere r) {
    typename S::payload_type;
    s.apply(r, edit_op::fill, typename S::payload_type{});
};

// See the top comment: consistent frames and per-consumer generations.
template <class S>
concept syncs_by_generation = requires(const S& c, S& s, std::uint64_t g) {
    c.snapshot().blob;
    c.snapshot().generation;
    s.changes_since(g).ranges;
};

template <class Backend, class Structure>
class tracer {
    static_assert(backend<Backend>,
                  "tracer<Backend, Structure>: Backend must be a voxray backend (voxray::cpu, voxray::cpu_scalar, "
                  "voxray::opencl or voxray::vulkan)");
    static_assert(structure<Structure>,
                  "tracer<Backend, Structure>: Structure must be a voxray structure (dense_grid, brickmap<...>): "
                  "a kernel tag, a name and blob()");

public:
    using backend_type = Backend;
    using structure_type = Structure;
    using engine_type = typename Backend::template engine<typename Structure::kernel>;
    static_assert(trace_engine<engine_type>,
                  "tracer<Backend, Structure>: Backend::engine<Kernel> falls short of trace_engine "
                  "(voxray/backend_contract.hpp): upload, update_ranges, trace, bytes_uploaded_last_update, "
                  "bytes_uploaded_total, download_blob");

    explicit tracer(const Structure& structure, typename Backend::options options = {}) : engine_(options) {
        update(structure);
    }

    // Sends the structure's current contents to the backend, whole.
    void update(const Structure& structure) {
        if constexpr (syncs_by_generation<Structure>) {
            auto frame = structure.snapshot();  // writers wait until the upload is done
            upload(frame.blob);
            generation_ = frame.generation;
        } else {
            upload(structure.blob());
        }
    }

    // Sends only the words the structure's edits changed since the last update (taking
    // its dirty ranges), or everything when the blob's size changed since the last upload.
    // Chosen over update(const Structure&) for non-const structures that track edits.
    void update(Structure& structure)
        requires tracks_dirty_ranges<Structure>
    {
        if constexpr (syncs_by_generation<Structure>) {
            auto frame = structure.changes_since(generation_);  // writers wait meanwhile
            send_ranges(frame.blob, frame.ranges);
            generation_ = frame.generation;
        } else {
            auto ranges = structure.take_dirty_ranges();  // always taken, so they never pile up
            update(structure, std::span<const word_range>(ranges));
        }
    }

    // The same with ranges taken by the caller: several tracers of one structure (one per
    // backend, say) take its dirty ranges once and pass them to each.
    void update(const Structure& structure, std::span<const word_range> ranges) {
        send_ranges(structure.blob(), ranges);
    }

    // Bytes the last construction or update sent to the backend (for the CPU backends:
    // copied), and the running total since construction.
    std::uint64_t bytes_uploaded_last_update() const { return engine_.bytes_uploaded_last_update(); }
    std::uint64_t bytes_uploaded_total() const { return engine_.bytes_uploaded_total(); }

    // First solid voxel along each ray within [tmin, tmax].
    void closest_hit(std::span<const ray> rays, std::span<hit> hits) { trace(rays, hits, VX_MODE_CLOSEST); }

    // Any solid voxel within [tmin, tmax] (shadow rays): status says whether one exists.
    void any_hit(std::span<const ray> rays, std::span<hit> hits) { trace(rays, hits, VX_MODE_ANY); }

    // One ray (Embree's rtcIntersect1). The CPU backends run it on the calling thread with
    // the scalar kernel, no pool involved; the others trace a batch of one.
    hit closest_hit(const ray& r) { return trace_one(r, VX_MODE_CLOSEST); }

    // Whether anything solid lies along the ray within [tmin, tmax] (rtcOccluded1).
    bool occluded(const ray& r) { return trace_one(r, VX_MODE_ANY).is_hit(); }

    // One flag per ray, 1 where something solid lies within [tmin, tmax], else 0
    // (rtcOccluded for a batch). Traces any-hit in chunks, so besides the flags it needs
    // only a small scratch of hits (GPU backends still bring whole hits back from the device).
    void occluded(std::span<const ray> rays, std::span<std::uint8_t> flags) {
        if (flags.size() < rays.size())
            fail("tracer: ", rays.size(), " rays but room for only ", flags.size(), " occlusion flags");
        constexpr std::size_t chunk = 4096;
        std::vector<hit> scratch(std::min(rays.size(), chunk));  // per call: concurrent calls stay safe
        for (std::size_t begin = 0; begin < rays.size(); begin += chunk) {
            auto part = rays.subspan(begin, std::min(chunk, rays.size() - begin));
            trace(part, std::span<hit>(scratch).first(part.size()), VX_MODE_ANY);
            for (std::size_t i = 0; i < part.size(); ++i) flags[begin + i] = scratch[i].is_hit() ? 1 : 0;
        }
    }

    // Interop, GPU backends only: rays and hits in device buffers the application owns
    // (Vulkan: vulkan_buffer_range; OpenCL: cl_mem), `count` 32-byte records each in the
    // layout of core/ray_hit_layout.h. Vulkan submits on the application's queue and
    // waits; OpenCL enqueues on its queue and returns. Details: vulkan/interop.hpp,
    // opencl/interop.hpp.
    template <class DeviceBuffer>
        requires requires(engine_type& e, const DeviceBuffer& b) { e.trace_device(b, b, std::size_t{}, VX_MODE_ANY); }
    void closest_hit(const DeviceBuffer& rays, const DeviceBuffer& hits, std::size_t count) {
        engine_.trace_device(rays, hits, count, VX_MODE_CLOSEST);
    }
    template <class DeviceBuffer>
        requires requires(engine_type& e, const DeviceBuffer& b) { e.trace_device(b, b, std::size_t{}, VX_MODE_ANY); }
    void any_hit(const DeviceBuffer& rays, const DeviceBuffer& hits, std::size_t count) {
        engine_.trace_device(rays, hits, count, VX_MODE_ANY);
    }

    // Interop, Vulkan: records the trace into the application's command buffer and
    // submits nothing; barriers are the application's (vulkan/interop.hpp).
    template <class Commands, class DeviceBuffer>
        requires requires(engine_type& e, Commands c, const DeviceBuffer& b) {
            e.record_trace(c, b, b, std::size_t{}, VX_MODE_ANY);
        }
    void record_closest_hit(Commands commands, const DeviceBuffer& rays, const DeviceBuffer& hits, std::size_t count) {
        engine_.record_trace(commands, rays, hits, count, VX_MODE_CLOSEST);
    }
    template <class Commands, class DeviceBuffer>
        requires requires(engine_type& e, Commands c, const DeviceBuffer& b) {
            e.record_trace(c, b, b, std::size_t{}, VX_MODE_ANY);
        }
    void record_any_hit(Commands commands, const DeviceBuffer& rays, const DeviceBuffer& hits, std::size_t count) {
        engine_.record_trace(commands, rays, hits, count, VX_MODE_ANY);
    }

    auto& engine() { return engine_; }

private:
    hit trace_one(const ray& r, std::uint32_t mode) {
        if constexpr (requires { engine_.trace_one(r, mode); }) {
            return engine_.trace_one(r, mode);
        } else {
            hit h;
            engine_.trace({&r, 1}, {&h, 1}, mode);
            return h;
        }
    }

    void upload(std::span<const std::uint32_t> blob) {
        engine_.upload(blob);
        uploaded_words_ = blob.size();
    }

    // The words of `ranges`; the whole blob when its size changed, unless it grew in place.
    void send_ranges(std::span<const std::uint32_t> blob, std::span<const word_range> ranges) {
        if (blob.size() == uploaded_words_) return engine_.update_ranges(blob, ranges);
        if constexpr (grows_in_place<Structure> && growing_engine<engine_type>) {
            if (blob.size() > uploaded_words_ && uploaded_words_ > 0) {
                engine_.grow_ranges(blob, ranges);
                uploaded_words_ = blob.size();
                return;
            }
        }
        upload(blob);
    }

    void trace(std::span<const ray> rays, std::span<hit> hits, std::uint32_t mode) {
        if (hits.size() < rays.size())
            fail("tracer: ", rays.size(), " rays but room for only ", hits.size(), " hits");
        engine_.trace(rays, hits.first(rays.size()), mode);
    }

    engine_type engine_;
    std::size_t uploaded_words_ = 0;
    std::uint64_t generation_ = 0;  // of the structure's content this tracer holds
};

}  // namespace voxray

// The one policy interface: tracer<Backend, Structure>. Swapping voxray::cpu for
// voxray::opencl or voxray::vulkan is the only change a user makes to move a
// structure to another backend; there are no virtual calls on the hot path.
//
// A backend is a type with
//   using options = ...;                            // start-up settings
//   template <class Kernel> class engine {          // one per structure kernel
//       engine(options);
//       void upload(std::span<const std::uint32_t> blob);
//       void trace(std::span<const ray>, std::span<hit>, std::uint32_t mode);
//   };
// The tracer owns a snapshot of the structure's blob as of construction or the last
// update(); the structure itself may be changed or destroyed afterwards.
#pragma once
#include <span>

#include "voxray/core/error.hpp"
#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"

namespace voxray {

template <class Backend, class Structure>
class tracer {
public:
    using backend_type = Backend;
    using structure_type = Structure;

    explicit tracer(const Structure& structure, typename Backend::options options = {}) : engine_(options) {
        engine_.upload(structure.blob());
    }

    // Sends the structure's current contents to the backend.
    void update(const Structure& structure) { engine_.upload(structure.blob()); }

    // First solid voxel along each ray within [tmin, tmax].
    void closest_hit(std::span<const ray> rays, std::span<hit> hits) { trace(rays, hits, VX_MODE_CLOSEST); }

    // Any solid voxel within [tmin, tmax] (shadow rays): status says whether one exists.
    void any_hit(std::span<const ray> rays, std::span<hit> hits) { trace(rays, hits, VX_MODE_ANY); }

    auto& engine() { return engine_; }

private:
    void trace(std::span<const ray> rays, std::span<hit> hits, std::uint32_t mode) {
        if (hits.size() < rays.size())
            fail("tracer: ", rays.size(), " rays but room for only ", hits.size(), " hits");
        engine_.trace(rays, hits.first(rays.size()), mode);
    }

    typename Backend::template engine<typename Structure::kernel> engine_;
};

}  // namespace voxray

// Run-time choice of structure x backend for the tool. The library's tracer is a
// compile-time policy; the tool, which takes names on the command line, wraps each
// combination once behind this small virtual interface (outside the hot loop).
#pragma once
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "edits.hpp"
#include "voxray/cpu.hpp"
#include "voxray/structures/dense_grid.hpp"
#if VOXRAY_WITH_OPENCL
#include "voxray/opencl.hpp"
#endif
#if VOXRAY_WITH_VULKAN
#include "voxray/vulkan.hpp"
#endif
#if VOXRAY_WITH_EMBREE
#include "voxray/embree/box_scene.hpp"
#include "voxray/embree/quad_scene.hpp"
#endif

namespace voxray::tool {

inline bool is_embree(const std::string& structure) { return structure.rfind("embree-", 0) == 0; }

// A built structure with its size and build time, shared by every backend that traces it.
struct built {
    std::string name;
    std::size_t bytes = 0;
    double build_seconds = 0;
    std::shared_ptr<void> object;
    bool editable = false;  // has an editing API (else rebuilt from the edited model)
};

class traceable {
public:
    virtual ~traceable() = default;
    virtual void closest_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    virtual void any_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    virtual std::string device() const { return "cpu"; }
    // Brings the backend up to date after edits: an editable structure was edited in place
    // and sends `ranges`; the others are rebuilt from the edited model and sent whole.
    virtual void after_edits(const voxel_model& edited, std::span<const word_range> ranges) = 0;
    virtual std::uint64_t bytes_uploaded_last_update() const { return 0; }
};

// Builds structure T from the model and records its size and build time.
template <class T>
built make_built(const std::string& name, const voxel_model& model, bool editable = false) {
    auto s = std::make_shared<T>(model);
    return built{name, s->bytes(), s->build_seconds(), s, editable};
}

inline built build_structure(const std::string& name, const voxel_model& model) {
    if (name == "dense") return make_built<dense_grid>(name, model);
    if (name == "brickmap") return make_built<brickmap8>(name, model, true);
#if VOXRAY_WITH_EMBREE
    if (name == "embree-quads") return make_built<embree::quad_scene>(name, model);
    if (name == "embree-boxes") return make_built<embree::box_scene>(name, model);
#endif
    fail("unknown or unavailable structure '", name, "' (known: dense, brickmap, embree-quads, embree-boxes)");
}

template <class Backend, class Structure>
class policy_traceable final : public traceable {
public:
    explicit policy_traceable(std::shared_ptr<Structure> s) : structure_(std::move(s)), tracer_(*structure_) {}
    void closest_hit(std::span<const ray> rays, std::span<hit> hits) override { tracer_.closest_hit(rays, hits); }
    void any_hit(std::span<const ray> rays, std::span<hit> hits) override { tracer_.any_hit(rays, hits); }
    std::string device() const override {
        if constexpr (requires { tracer_.engine().device_name(); }) return tracer_.engine().device_name();
        else return "cpu";
    }
    void after_edits(const voxel_model& edited, std::span<const word_range> ranges) override {
        if constexpr (std::is_same_v<Structure, brickmap8>) {
            tracer_.update(*structure_, ranges);
        } else {
            structure_ = std::make_shared<Structure>(edited);
            tracer_.update(*structure_);
        }
    }
    std::uint64_t bytes_uploaded_last_update() const override { return tracer_.bytes_uploaded_last_update(); }

private:
    std::shared_ptr<Structure> structure_;
    mutable tracer<Backend, Structure> tracer_;
};

template <class Scene>
class embree_traceable final : public traceable {
public:
    explicit embree_traceable(std::shared_ptr<Scene> scene) : scene_(std::move(scene)) {}
    void closest_hit(std::span<const ray> rays, std::span<hit> hits) override { scene_->closest_hit(rays, hits); }
    void any_hit(std::span<const ray> rays, std::span<hit> hits) override { scene_->any_hit(rays, hits); }
    std::string device() const override { return "cpu (embree)"; }
    void after_edits(const voxel_model& edited, std::span<const word_range>) override {
        scene_ = std::make_shared<Scene>(edited);
    }

private:
    std::shared_ptr<Scene> scene_;
};

// Whether the pair exists at all (Embree structures run on the CPU only).
inline bool pair_exists(const std::string& structure, const std::string& backend) {
    return !is_embree(structure) || backend == "cpu";
}

template <class Structure>
std::unique_ptr<traceable> make_policy_traceable(std::shared_ptr<Structure> s, const std::string& backend) {
    if (backend == "cpu") return std::make_unique<policy_traceable<cpu, Structure>>(s);
    if (backend == "cpu-scalar") return std::make_unique<policy_traceable<cpu_scalar, Structure>>(s);
#if VOXRAY_WITH_OPENCL
    if (backend == "opencl") return std::make_unique<policy_traceable<opencl, Structure>>(s);
#endif
#if VOXRAY_WITH_VULKAN
    if (backend == "vulkan") return std::make_unique<policy_traceable<vulkan, Structure>>(s);
#endif
    fail("unknown or unavailable backend '", backend, "' (known: cpu, cpu-scalar, opencl, vulkan)");
}

inline std::unique_ptr<traceable> make_traceable(const built& s, const std::string& backend) {
    if (!pair_exists(s.name, backend)) fail("structure ", s.name, " runs on the cpu backend only, not ", backend);
#if VOXRAY_WITH_EMBREE
    if (s.name == "embree-quads")
        return std::make_unique<embree_traceable<embree::quad_scene>>(std::static_pointer_cast<embree::quad_scene>(s.object));
    if (s.name == "embree-boxes")
        return std::make_unique<embree_traceable<embree::box_scene>>(std::static_pointer_cast<embree::box_scene>(s.object));
#endif
    if (s.name == "brickmap") return make_policy_traceable(std::static_pointer_cast<brickmap8>(s.object), backend);
    return make_policy_traceable(std::static_pointer_cast<dense_grid>(s.object), backend);
}

}  // namespace voxray::tool

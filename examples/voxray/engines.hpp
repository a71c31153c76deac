// Run-time choice of structure x backend for the tool. The library's tracer is a
// compile-time policy; the tool, which takes names on the command line, walks the type
// list of registered structures (voxray/generated/structures.hpp) and of backends once,
// wrapping each combination behind this small virtual interface (outside the hot loop).
// Baselines (Embree, NanoVDB) are not tracer structures; they come from their own list.
#pragma once
#include <chrono>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "voxray/core/type_list.hpp"
#include "voxray/cpu.hpp"
#include "voxray/edit/region_edit.hpp"
#include "voxray/generated/structures.hpp"
#include "voxray/tracer.hpp"
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
#if VOXRAY_WITH_NANOVDB
#include "voxray/nanovdb/hdda_scene.hpp"
#endif

namespace voxray::tool {

using backends = type_list<cpu, cpu_scalar
#if VOXRAY_WITH_OPENCL
                           , opencl
#endif
#if VOXRAY_WITH_VULKAN
                           , vulkan
#endif
                           >;

// Peer libraries traced on the CPU beside the structures (Embree, NanoVDB), when built.
template <class... Lists>
struct concat_lists;
template <class... A>
struct concat_lists<type_list<A...>> { using type = type_list<A...>; };
template <class... A, class... B, class... Rest>
struct concat_lists<type_list<A...>, type_list<B...>, Rest...> : concat_lists<type_list<A..., B...>, Rest...> {};

#if VOXRAY_WITH_EMBREE
using embree_baselines = type_list<embree::quad_scene, embree::box_scene>;
#else
using embree_baselines = type_list<>;
#endif
#if VOXRAY_WITH_NANOVDB
using nanovdb_baselines = type_list<vdb::hdda_scene>;
#else
using nanovdb_baselines = type_list<>;
#endif
using baselines = typename concat_lists<embree_baselines, nanovdb_baselines>::type;

class traceable {
public:
    virtual ~traceable() = default;
    virtual void closest_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    virtual void any_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    virtual std::string device() const { return "cpu"; }
    // Brings the backend up to date after edits: an editable structure was edited in place
    // (its slot holds the dirty ranges of the last edits); the others are rebuilt from the
    // edited model and sent whole.
    virtual void after_edits(const voxel_model& edited) = 0;
    virtual std::uint64_t bytes_uploaded_last_update() const { return 0; }
    // CPU threads tracing (0: a device does) and rays per lane group (1: scalar).
    virtual unsigned cpu_threads() const { return 0; }
    virtual unsigned simd_width() const { return 1; }
};

// One built structure or baseline, shared by every backend that traces it.
class slot {
public:
    virtual ~slot() = default;
    virtual std::string name() const = 0;
    virtual std::size_t bytes() const = 0;
    virtual double build_seconds() const = 0;
    virtual bool editable() const { return false; }
    // A known limitation of a baseline (empty: none): its wrong answers on the rays it
    // names are labelled, not counted as mismatches.
    virtual std::string limitation() const { return ""; }
    virtual bool runs_on(const std::string& backend) const = 0;
    virtual std::unique_ptr<traceable> trace_on(const std::string& backend) = 0;
    // Edits the structure in place (editable ones only) and keeps the dirty ranges for
    // its traceables' after_edits().
    virtual void apply_edits(std::span<const region_edit>, unsigned /* threads */ = 1) {
        fail("structure ", name(), " is not editable");
    }
    // How long the last apply_edits spent regrowing distance fields (NAADF's refine).
    virtual double last_refine_seconds() const { return 0; }
    // Hits carry RGBA8 colours instead of palette indices (the DAG's colour blocks): how
    // far, per channel in [0, 1], a colour may be from the voxel's palette colour.
    virtual std::optional<double> colour_tolerance() const { return std::nullopt; }
    // Structure-specific figures (name, value) beside size and build time (the DAG's
    // geometry and attribute bytes, merging ratio, colour error).
    virtual std::vector<std::pair<const char*, double>> figures() const { return {}; }
};

template <class Backend, class Structure>
class policy_traceable;

template <class Structure>
class structure_slot final : public slot, public std::enable_shared_from_this<structure_slot<Structure>> {
public:
    explicit structure_slot(const voxel_model& model) : structure(std::make_shared<Structure>(model)) {}
    std::string name() const override { return std::string(Structure::name); }
    std::size_t bytes() const override { return structure->bytes(); }
    double build_seconds() const override { return structure->build_seconds(); }
    bool editable() const override { return editable_structure<Structure>; }
    bool runs_on(const std::string& backend) const override {
        bool found = false;
        for_each_type(backends{}, [&]<class B>() { found |= backend == B::name; });
        return found;
    }
    std::unique_ptr<traceable> trace_on(const std::string& backend) override {
        std::unique_ptr<traceable> t;
        for_each_type(backends{}, [&]<class B>() {
            if (!t && backend == B::name) t = std::make_unique<policy_traceable<B, Structure>>(this->shared_from_this());
        });
        if (!t) fail("unknown or unavailable backend '", backend, "' (known: ", names_of(backends{}), ")");
        return t;
    }
    void apply_edits(std::span<const region_edit> edits, unsigned threads) override {
        if constexpr (editable_structure<Structure>) {
            using payload = typename Structure::payload_type;
            if constexpr (requires { structure->apply_batch(std::span<const typename Structure::edit>{}, threads); }) {
                std::vector<typename Structure::edit> typed;
                typed.reserve(edits.size());
                for (auto& e : edits) typed.push_back({e.region, e.op, payload(e.value)});
                structure->apply_batch(typed, threads);
            } else {
                for (auto& e : edits)
                    std::visit([&](const auto& r) { structure->apply(r, e.op, payload(e.value), threads); }, e.region);
            }
            // Distance fields the edits reset grow back now (NAADF); timed apart, since an
            // engine may spread it over frames (refine(budget)).
            if constexpr (requires { structure->refine(); }) {
                auto start = std::chrono::steady_clock::now();
                structure->refine(SIZE_MAX, threads);
                refine_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            }
            auto taken = structure->take_dirty_ranges();
            ranges.assign(taken.begin(), taken.end());
        } else {
            slot::apply_edits(edits, threads);
        }
    }

    template <class List>
    static std::string names_of(List) {
        std::string out;
        for_each_type(List{}, [&]<class B>() { out += (out.empty() ? "" : ", ") + std::string(B::name); });
        return out;
    }

    std::shared_ptr<Structure> structure;
    double last_refine_seconds() const override { return refine_seconds; }
    std::optional<double> colour_tolerance() const override {
        if constexpr (requires { Structure::material_is_colour; }) return structure->colour_tolerance();
        else return std::nullopt;
    }
    std::vector<std::pair<const char*, double>> figures() const override {
        if constexpr (requires { structure->stats().figures(); }) return structure->stats().figures();
        else return {};
    }

    std::vector<word_range> ranges;  // dirty ranges of the last apply_edits
    double refine_seconds = 0;       // of the last apply_edits (part of its time)
};

template <class Backend, class Structure>
class policy_traceable final : public traceable {
public:
    explicit policy_traceable(std::shared_ptr<structure_slot<Structure>> s)
        : slot_(std::move(s)), structure_(slot_->structure), tracer_(*structure_) {}
    void closest_hit(std::span<const ray> rays, std::span<hit> hits) override { tracer_.closest_hit(rays, hits); }
    void any_hit(std::span<const ray> rays, std::span<hit> hits) override { tracer_.any_hit(rays, hits); }
    std::string device() const override {
        if constexpr (requires { tracer_.engine().device_name(); }) return tracer_.engine().device_name();
        else return "cpu";
    }
    void after_edits(const voxel_model& edited) override {
        if constexpr (editable_structure<Structure>) {
            tracer_.update(*structure_, std::span<const word_range>(slot_->ranges));
        } else {
            structure_ = std::make_shared<Structure>(edited);
            tracer_.update(*structure_);
        }
    }
    std::uint64_t bytes_uploaded_last_update() const override { return tracer_.bytes_uploaded_last_update(); }
    unsigned cpu_threads() const override {
        if constexpr (requires { tracer_.engine().threads(); }) return tracer_.engine().threads();
        else return 0;
    }
    unsigned simd_width() const override {
        if constexpr (requires { tracer_.engine().simd_width(); }) return tracer_.engine().simd_width();
        else return 1;
    }

private:
    std::shared_ptr<structure_slot<Structure>> slot_;
    std::shared_ptr<Structure> structure_;
    mutable tracer<Backend, Structure> tracer_;
};

// Embree scenes trace on the CPU only; edits rebuild them.
template <class Scene>
class baseline_traceable final : public traceable {
public:
    explicit baseline_traceable(std::shared_ptr<Scene> scene) : scene_(std::move(scene)) {}
    void closest_hit(std::span<const ray> rays, std::span<hit> hits) override { scene_->closest_hit(rays, hits); }
    void any_hit(std::span<const ray> rays, std::span<hit> hits) override { scene_->any_hit(rays, hits); }
    std::string device() const override { return "cpu (" + std::string(Scene::library) + ")"; }
    void after_edits(const voxel_model& edited) override { scene_ = std::make_shared<Scene>(edited); }
    unsigned cpu_threads() const override {
        if constexpr (requires { scene_->threads(); }) return scene_->threads();
        else return 0;
    }

private:
    std::shared_ptr<Scene> scene_;
};

template <class Scene>
class baseline_slot final : public slot {
public:
    explicit baseline_slot(const voxel_model& model) : scene_(std::make_shared<Scene>(model)) {}
    std::string name() const override { return std::string(Scene::name); }
    std::size_t bytes() const override { return scene_->bytes(); }
    double build_seconds() const override { return scene_->build_seconds(); }
    std::string limitation() const override {
        if constexpr (requires { Scene::limitation; }) return std::string(Scene::limitation);
        else return "";
    }
    bool runs_on(const std::string& backend) const override { return backend == "cpu"; }
    std::unique_ptr<traceable> trace_on(const std::string& backend) override {
        if (!runs_on(backend)) fail("structure ", name(), " runs on the cpu backend only, not ", backend);
        return std::make_unique<baseline_traceable<Scene>>(scene_);
    }

private:
    std::shared_ptr<Scene> scene_;
};

// Every structure and baseline name the tool knows.
inline std::string structure_names(const char* separator = ", ") {
    std::string out;
    auto add = [&]<class S>() { out += (out.empty() ? "" : separator) + std::string(S::name); };
    for_each_type(registered::structures{}, add);
    for_each_type(baselines{}, add);
    return out;
}

// The structures and baselines that answer every ray of the contract (no known limitation):
// what `check` compares by default.
inline std::string exact_structure_names() {
    std::string out;
    auto add = [&]<class S>() {
        if constexpr (!requires { S::limitation; }) out += (out.empty() ? "" : ",") + std::string(S::name);
    };
    for_each_type(registered::structures{}, add);
    for_each_type(baselines{}, add);
    return out;
}

// Builds structure or baseline `name` from the model.
inline std::shared_ptr<slot> build_structure(const std::string& name, const voxel_model& model) {
    std::shared_ptr<slot> s;
    for_each_type(registered::structures{}, [&]<class S>() {
        if (!s && name == S::name) s = std::make_shared<structure_slot<S>>(model);
    });
    for_each_type(baselines{}, [&]<class S>() {
        if (!s && name == S::name) s = std::make_shared<baseline_slot<S>>(model);
    });
    if (!s) fail("unknown or unavailable structure '", name, "' (known: ", structure_names(), ")");
    return s;
}

}  // namespace voxray::tool

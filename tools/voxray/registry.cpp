// The tool's structure x backend matrix, compiled in this one file: every registered
// structure and baseline behind engines.hpp's interface, on every backend of backends.hpp.
#include <chrono>
#include <variant>

#include "backends.hpp"
#include "engines.hpp"
#include "voxray/generated/structures.hpp"
#include "voxray/tracer.hpp"

namespace voxray::tool {

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
    unsigned work_group_size() const override {
        if constexpr (requires { tracer_.engine().work_group_size(); }) return unsigned(tracer_.engine().work_group_size());
        else return 0;
    }
    double kernel_seconds_last_trace() const override {
        if constexpr (timed_engine<typename tracer<Backend, Structure>::engine_type>)
            return tracer_.engine().kernel_seconds_last_trace();
        else return NAN;
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
std::string structure_names(const char* separator) {
    std::string out;
    auto add = [&]<class S>() { out += (out.empty() ? "" : separator) + std::string(S::name); };
    for_each_type(registered::structures{}, add);
    for_each_type(baselines{}, add);
    return out;
}

// The structures and baselines that answer every ray of the contract (no known limitation):
// what `check` compares by default.
std::string exact_structure_names() {
    std::string out;
    auto add = [&]<class S>() {
        if constexpr (!requires { S::limitation; }) out += (out.empty() ? "" : ",") + std::string(S::name);
    };
    for_each_type(registered::structures{}, add);
    for_each_type(baselines{}, add);
    return out;
}

// Builds structure or baseline `name` from the model.
std::shared_ptr<slot> build_structure(const std::string& name, const voxel_model& model) {
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

std::vector<std::string> backend_names() {
    std::vector<std::string> out;
    for_each_type(backends{}, [&]<class B>() { out.emplace_back(B::name); });
    return out;
}

}  // namespace voxray::tool

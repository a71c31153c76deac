// The brute-force reference for scenes (entities/scene.hpp): the world's hit by the dense
// reference grid, then every live instance in turn, each by a dense grid of its model walked
// with the ray in the model's frame (the layout's own transform, VX_SC_TO_MODEL), keeping
// the nearest (ties: the world, then the lower slot). No boxes, no BVH, no entity pass.
// What the entity tests and `voxray check SCENE.json` compare every backend with. Slow
// (every instance for every ray): meant for checks, not for rendering.
#pragma once
#include <array>
#include <memory>
#include <vector>

#if !defined(VOXRAY_LINKED_CPU)
#error "voxray/entities/reference.hpp needs voxray::cpu (it walks dense grids with the scalar lanes): link it"
#endif
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/entities/scene.hpp"
#include "voxray/tracer.hpp"

namespace voxray {

class scene_reference {
public:
    // `world`: the scene's world as a voxel model; models and instances are read from the scene.
    template <class World>
    scene_reference(const voxel_model& world, const scene<World>& s) : world_(world) {
        update(s);
    }

    // Reads the instances again (after moves, adds, removes); model grids are kept.
    template <class World>
    void update(const scene<World>& s) {
        instances_.clear();
        for (std::size_t id = 0; id < s.slot_count(); ++id) {
            auto state = s.instance(instance_id(id));
            if (!state) continue;
            while (grids_.size() <= state->model) grids_.emplace_back();
            if (!grids_[state->model]) grids_[state->model] = std::make_unique<model_grid>(s.model(state->model));
            const model_grid& g = *grids_[state->model];
            instances_.push_back({std::uint32_t(id), state->model, instance_words(state->where, g.extent, 0)});
        }
    }

    hit trace(const ray& r, std::uint32_t mode) {
        hit best = world_.closest_hit(r);
        if (mode == VX_MODE_ANY && best.is_hit()) return best;
        bool on_instance = false;
        std::uint32_t best_slot = 0;
        for (const placed& p : instances_) {
            float m[VX_SC_INSTANCE_WORDS];
            for (int k = 0; k < VX_SC_INSTANCE_WORDS; ++k) m[k] = std::bit_cast<float>(p.words[k]);
            ray q;
            for (int a = 0; a < 3; ++a) {
                q.origin[a] = VX_SC_TO_MODEL(m, a, r.origin.x, r.origin.y, r.origin.z);
                q.direction[a] = VX_SC_DIR_TO_MODEL(m, a, r.direction.x, r.direction.y, r.direction.z);
            }
            q.tmin = r.tmin;
            q.tmax = best.is_hit() ? best.t : r.tmax;
            model_grid& g = *grids_[p.model];
            hit h = g.walk.closest_hit(q);
            if (!h.is_hit()) continue;
            if (best.is_hit() && !(h.t < best.t || (h.t == best.t && on_instance && p.slot < best_slot))) continue;
            h.voxel += g.min;
            h.material |= (p.slot + 1) << VX_SC_INSTANCE_SHIFT;
            best = h;
            on_instance = true;
            best_slot = p.slot;
            if (mode == VX_MODE_ANY) return best;
        }
        return best;
    }

    std::vector<hit> trace(std::span<const ray> rays, std::uint32_t mode) {
        std::vector<hit> hits(rays.size());
        for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = trace(rays[i], mode);
        return hits;
    }

private:
    // A model's voxels moved so its min corner is voxel 0: its grid then walks the model
    // ray exactly as the entity pass does (both from a grid corner at 0).
    struct model_grid {
        explicit model_grid(const entity_model& m) : min(m.bounds().min), extent(m.extent()), grid(shifted(m)), walk(grid, cpu_options{1}) {}
        static voxel_model shifted(const entity_model& m) {
            voxel_model out;
            box3i b = m.bounds();
            for (int z = b.min.z; z < b.max.z; ++z)
                for (int y = b.min.y; y < b.max.y; ++y)
                    for (int x = b.min.x; x < b.max.x; ++x)
                        if (auto v = m.get({x, y, z})) out.set(glm::ivec3(x, y, z) - b.min, v);
            return out;
        }
        glm::ivec3 min, extent;
        dense_grid grid;
        tracer<cpu_scalar, dense_grid> walk;
    };
    struct placed {
        std::uint32_t slot, model;
        std::array<std::uint32_t, VX_SC_INSTANCE_WORDS> words;
    };

    struct world_grid {
        explicit world_grid(const voxel_model& m) : grid(m), walk(grid, cpu_options{1}) {}
        hit closest_hit(const ray& r) { return walk.closest_hit(r); }
        dense_grid grid;
        tracer<cpu_scalar, dense_grid> walk;
    } world_;
    std::vector<std::unique_ptr<model_grid>> grids_;
    std::vector<placed> instances_;
};

}  // namespace voxray

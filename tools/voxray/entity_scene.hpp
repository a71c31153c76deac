// Scene files for the tool: a world and moving entities, described in JSON (docs/entities.md):
//
//   {"world": "castle.vox",
//    "models": {"deer": {"file": "deer.vox"}},
//    "instances": [{"model": "deer", "position": [10, 20, 5], "rotation": [1, 0, 0, 0],
//                   "motion": {"linear": [0.5, 0, 0]}}]}
//
// Paths are relative to the file (or absolute, or builtin:NAME); positions are world voxels;
// rotations quaternions (w, x, y, z), normalised on reading; a motion moves an instance
// each frame: "linear": [dx, dy, dz], "spin": [ax, ay, az, radians] about its centre,
// "orbit": [cx, cy, cz, radians] about the vertical axis through (cx, cy, cz). Optional
// per instance: "scale" (uniform). `voxray check`, `render` and `bench` take such a file
// where they take a scene.
#pragma once
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "scene.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/entities/candidates.hpp"
#include "voxray/entities/entity_model.hpp"
#include "voxray/entities/pose.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::tool {

struct entity_motion {
    glm::vec3 linear{0.0f};
    glm::vec4 spin{0.0f, 0.0f, 1.0f, 0.0f};   // axis, radians a frame
    glm::vec4 orbit{0.0f, 0.0f, 0.0f, 0.0f};  // centre, radians a frame (about the up axis)
};

struct entity_instance {
    std::string model;
    pose start;
    entity_motion motion;
    // Where the instance stands at `frame` (0: its start), about world up axis `up`.
    pose at(int frame, int up) const;
};

// A model of a scene file: "models": {NAME: {"file": SPEC, "fields": "bricks" | "none",
// "region": [x0, y0, z0, x1, y1, z1]}} (the region: a box of the file's voxels, max
// exclusive, cut out as the model; entities/region_model.hpp).
struct scene_model_file {
    std::string name;
    std::string file;  // a scene spec
    model_fields fields = model_fields::bricks;
    std::optional<box3i> region;
};

struct scene_description {
    std::filesystem::path file;
    std::string world;  // a scene spec: file path (resolved) or builtin:NAME
    std::vector<scene_model_file> models;
    std::vector<entity_instance> instances;
};

// How the scene's model walks cross empty space: "bricks", "none", or "mixed" where models differ.
inline std::string model_fields_label(const scene_description& d) {
    std::string label;
    for (auto& m : d.models) {
        std::string mine = m.fields == model_fields::bricks ? "bricks" : "none";
        label = label.empty() || label == mine ? mine : "mixed";
    }
    return label;
}

inline bool is_scene_description(const std::string& spec) {
    return std::filesystem::path(spec).extension() == ".json";
}

// Reads and checks a scene file: every error names the file and the key (instances[3].rotation).
scene_description read_scene_description(const std::filesystem::path& file);

// The world and the models, loaded as every command loads scenes (scene.hpp).
struct loaded_scene {
    scene_description description;
    voxel_model world;
    std::vector<voxel_model> models;  // in the order of description.models
    std::vector<entity_model> entity_models;  // the same, built once for every run
    std::vector<std::uint32_t> model_of;  // per instance: its model's index
};
loaded_scene load_scene_description(const std::string& spec, const scene_options& o);

// The world kinds scenes run over (registered::scene_worlds), by name.
std::vector<std::string> scene_world_names();
// The ways to find candidate instances (every_entity_candidates), by name, and all of them
// comma-separated (the default of --candidates).
std::vector<std::string> candidates_names();
std::string all_candidates();

// A loaded scene built over one world kind and traced on one backend.
class entity_run {
public:
    virtual ~entity_run() = default;
    // Moves every instance to where it stands at `frame` and brings the tracer up to date.
    virtual void go_to(int frame) = 0;
    // Moves instance i to pose_of(i) for every instance, and brings the tracer up to date.
    virtual void move_all(const std::function<pose(std::uint32_t)>& pose_of) = 0;
    // How the scene finds candidate instances (a new layout, sent whole).
    virtual void set_candidates(entity_candidates how) = 0;
    virtual void closest_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    virtual void any_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    // The world alone, without the scene (its own tracer on this backend).
    virtual void world_closest_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    virtual void world_any_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    // The brute-force reference of the scene as it stands (entities/reference.hpp).
    virtual std::vector<hit> reference(std::span<const ray> rays, std::uint32_t mode) = 0;
    virtual std::uint64_t bytes_last_update() const = 0;
    virtual double seconds_last_update() const = 0;
    virtual pose where(std::uint32_t instance) const = 0;
    virtual unsigned cpu_threads() const = 0;  // 0 on a device
    virtual std::string device() const = 0;
};
std::unique_ptr<entity_run> make_entity_run(const std::string& world, const std::string& backend, const loaded_scene& s);

int check_scene_file(const std::string& spec, const scene_options& o, int frames, std::size_t rays, std::uint64_t seed,
                     const std::string& worlds, const std::string& backends, const std::string& candidates);
struct bench_options;
// `voxray bench SCENE.json` (entity_bench.cpp).
int bench_scene_file(const bench_options& o);
int render_scene_file(const std::string& spec, const scene_options& o, int frames, const std::string& world,
                      const std::string& backend, int width, int height, int view, const std::string& out);

}  // namespace voxray::tool

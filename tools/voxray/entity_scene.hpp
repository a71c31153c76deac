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
#include <string>
#include <vector>

#include "scene.hpp"
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

struct scene_description {
    std::filesystem::path file;
    std::string world;  // a scene spec: file path (resolved) or builtin:NAME
    std::vector<std::pair<std::string, std::string>> models;  // name, scene spec
    std::vector<entity_instance> instances;
};

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
    std::vector<std::uint32_t> model_of;  // per instance: its model's index
};
loaded_scene load_scene_description(const std::string& spec, const scene_options& o);

// The world kinds scenes run over (registered::scene_worlds), by name.
std::vector<std::string> scene_world_names();

int check_scene_file(const std::string& spec, const scene_options& o, int frames, std::size_t rays, std::uint64_t seed,
                     const std::string& worlds, const std::string& backends);
int render_scene_file(const std::string& spec, const scene_options& o, int frames, const std::string& world,
                      const std::string& backend, int width, int height, int view, const std::string& out);

}  // namespace voxray::tool

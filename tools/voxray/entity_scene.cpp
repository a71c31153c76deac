// Scene files (entity_scene.hpp): reading them, and `check` and `render` over them on every
// world kind x backend (registered::scene_worlds x backends).
#include "entity_scene.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "backends.hpp"
#include "cli.hpp"
#include "image_writer.hpp"
#include "voxray/entities/reference.hpp"
#include "voxray/entities/region_model.hpp"
#include "voxray/generated/structures.hpp"
#include "voxray/rays.hpp"

namespace voxray::tool {

namespace {

using json = nlohmann::json;

// ---- reading ----

[[noreturn]] void scene_file_error(const scene_description& d, const std::string& key, const std::string& what) {
    fail("scene file ", d.file.string(), ": ", key, ": ", what);
}

std::vector<float> scene_numbers(const scene_description& d, const json& v, const std::string& key, std::size_t count) {
    if (!v.is_array() || v.size() != count) scene_file_error(d, key, "expected " + std::to_string(count) + " numbers");
    std::vector<float> out;
    for (auto& x : v) {
        if (!x.is_number()) scene_file_error(d, key, "expected " + std::to_string(count) + " numbers");
        double number = x.get<double>();
        if (!(std::abs(number) <= double(std::numeric_limits<float>::max())))
            scene_file_error(d, key, "a number is not a finite float (" + x.dump() + ")");
        out.push_back(float(number));
    }
    return out;
}

// A path of the file relative to its folder (absolute paths and builtin: stay).
std::string scene_path(const scene_description& d, const std::string& path) {
    if (path.rfind("builtin:", 0) == 0 || std::filesystem::path(path).is_absolute()) return path;
    return (d.file.parent_path() / path).string();
}

std::string scene_text(const scene_description& d, const json& obj, const std::string& key, const std::string& where) {
    if (!obj.is_object() || !obj.contains(key) || !obj[key].is_string()) scene_file_error(d, where + key, "missing, or not a string");
    return obj[key].get<std::string>();
}

entity_instance read_instance(const scene_description& d, const json& v, std::size_t i) {
    std::string where = "instances[" + std::to_string(i) + "]";
    if (!v.is_object()) scene_file_error(d, where, "not an object");
    entity_instance e;
    e.model = scene_text(d, v, "model", where + ".");
    bool known = false;
    for (auto& m : d.models) known |= m.name == e.model;
    if (!known) scene_file_error(d, where + ".model", "no model named \"" + e.model + "\" in \"models\"");
    if (!v.contains("position")) scene_file_error(d, where + ".position", "missing");
    auto p = scene_numbers(d, v["position"], where + ".position", 3);
    e.start.position = {p[0], p[1], p[2]};
    if (v.contains("rotation")) {
        auto q = scene_numbers(d, v["rotation"], where + ".rotation", 4);
        e.start.rotation = glm::quat(q[0], q[1], q[2], q[3]);
    }
    if (v.contains("scale")) e.start.scale = scene_numbers(d, json::array({v["scale"]}), where + ".scale", 1)[0];
    try {
        e.start = checked_pose(e.start);
    } catch (const error& x) {
        scene_file_error(d, where, x.what());
    }
    if (v.contains("motion")) {
        const json& m = v["motion"];
        if (!m.is_object()) scene_file_error(d, where + ".motion", "not an object");
        for (auto& [key, value] : m.items()) {
            std::string at = where + ".motion." + key;
            if (key == "linear") {
                auto l = scene_numbers(d, value, at, 3);
                e.motion.linear = {l[0], l[1], l[2]};
            } else if (key == "spin" || key == "orbit") {
                auto s = scene_numbers(d, value, at, 4);
                glm::vec4 w(s[0], s[1], s[2], s[3]);
                if (key == "spin" && glm::length(glm::vec3(w)) == 0.0f) scene_file_error(d, at, "the spin axis is zero");
                (key == "spin" ? e.motion.spin : e.motion.orbit) = w;
            } else {
                scene_file_error(d, at, "unknown motion (linear, spin or orbit)");
            }
        }
    }
    return e;
}

// ---- running a scene on one world kind and backend ----

template <class World, class Backend>
class entity_run_of : public entity_run {
public:
    explicit entity_run_of(const loaded_scene& s) : s_(s), world_(s.world), scene_(world_), world_tracer_(world_) {
        for (auto& m : s.entity_models) scene_.add_model(m);
        for (std::size_t i = 0; i < s.description.instances.size(); ++i)
            ids_.push_back(scene_.add(s.model_of[i], s.description.instances[i].start));
        tracer_ = std::make_unique<tracer<Backend, scene<World>>>(scene_);
    }
    void go_to(int frame) override {
        move_all([&](std::uint32_t i) { return s_.description.instances[i].at(frame, s_.world.up_axis); });
    }
    void move_all(const std::function<pose(std::uint32_t)>& pose_of) override {
        auto start = std::chrono::steady_clock::now();
        std::vector<std::pair<instance_id, pose>> moves;
        moves.reserve(ids_.size());
        for (std::size_t i = 0; i < ids_.size(); ++i) moves.push_back({ids_[i], pose_of(std::uint32_t(i))});
        scene_.move(moves);
        tracer_->update(scene_);
        seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    void set_candidates(entity_candidates how) override {
        scene_.set_candidates(how);
        tracer_->update(scene_);
    }
    void world_closest_hit(std::span<const ray> rays, std::span<hit> hits) override { world_tracer_.closest_hit(rays, hits); }
    void world_any_hit(std::span<const ray> rays, std::span<hit> hits) override { world_tracer_.any_hit(rays, hits); }
    unsigned cpu_threads() const override {
        if constexpr (requires { tracer_->engine().threads(); }) return tracer_->engine().threads();
        else return 0;
    }
    std::string device() const override { return Backend::name; }
    void closest_hit(std::span<const ray> rays, std::span<hit> hits) override { tracer_->closest_hit(rays, hits); }
    void any_hit(std::span<const ray> rays, std::span<hit> hits) override { tracer_->any_hit(rays, hits); }
    std::vector<hit> reference(std::span<const ray> rays, std::uint32_t mode) override {
        if (!reference_) reference_ = std::make_unique<scene_reference>(s_.world, scene_);
        reference_->update(scene_);
        return reference_->trace(rays, mode);
    }
    std::uint64_t bytes_last_update() const override { return tracer_->bytes_uploaded_last_update(); }
    double seconds_last_update() const override { return seconds_; }
    pose where(std::uint32_t instance) const override { return scene_.instance(ids_[instance])->where; }

private:
    const loaded_scene& s_;
    World world_;
    scene<World> scene_;
    std::vector<instance_id> ids_;
    std::unique_ptr<tracer<Backend, scene<World>>> tracer_;
    tracer<Backend, World> world_tracer_;
    std::unique_ptr<scene_reference> reference_;
    double seconds_ = 0;
};

// The check's rays: camera and random rays over the world and every instance's box, and as
// many aimed at instances.
std::vector<ray> entity_rays(const loaded_scene& s, entity_run& run, int frame, std::size_t count, std::uint64_t seed) {
    box3i all = s.world.bounds();
    for (std::size_t i = 0; i < s.description.instances.size(); ++i) {
        world_box b = placed_box(run.where(std::uint32_t(i)), s.models[s.model_of[i]].bounds().extent());
        all.include(glm::ivec3(glm::floor(b.min)));
        all.include(glm::ivec3(glm::ceil(b.max)));
    }
    auto rays = check_rays(all, s.world.up_axis, count - count / 2, seed + std::uint64_t(frame));
    rng g(seed * 31 + std::uint64_t(frame));
    std::size_t n = s.description.instances.size();
    for (std::size_t i = 0; i < count / 2 && n > 0; ++i) {
        glm::vec3 target = run.where(std::uint32_t(g.below(int(n)))).position +
                           glm::vec3(g.uniform(-3, 3), g.uniform(-3, 3), g.uniform(-3, 3));
        ray r;
        r.origin = glm::vec3(all.min) + glm::vec3(g.uniform(), g.uniform(), g.uniform()) * glm::vec3(all.extent());
        r.direction = glm::normalize(target - r.origin + glm::vec3(1e-3f));
        rays.push_back(r);
    }
    return rays;
}

bool same_scene_hit(hit a, hit b) {
    a.steps = b.steps = 0;
    if (a.t == 0.0f && b.t == 0.0f) a.t = b.t = 0.0f;  // -0 and +0 (see tests/support/hit_bits.hpp)
    return std::memcmp(&a, &b, sizeof(hit)) == 0;
}

}  // namespace

std::unique_ptr<entity_run> make_entity_run(const std::string& world, const std::string& backend, const loaded_scene& s) {
    std::unique_ptr<entity_run> run;
    for_each_type(registered::scene_worlds{}, [&]<class W>() {
        for_each_type(backends{}, [&]<class B>() {
            if (!run && world == W::name && backend == B::name) run = std::make_unique<entity_run_of<W, B>>(s);
        });
    });
    if (!run) fail("no scene runs on world ", world, " and backend ", backend);
    return run;
}

pose entity_instance::at(int frame, int up) const {
    pose p = start;
    if (frame == 0) return p;  // exactly the file's pose (a turn by 0 would still round)
    float f = float(frame);
    p.position += motion.linear * f;
    if (motion.spin.w != 0.0f)
        p.rotation = glm::normalize(glm::angleAxis(motion.spin.w * f, glm::normalize(glm::vec3(motion.spin))) * p.rotation);
    if (motion.orbit.w != 0.0f) {
        glm::vec3 axis(0.0f);
        axis[up] = 1.0f;
        glm::quat turn = glm::angleAxis(motion.orbit.w * f, axis);
        glm::vec3 centre(motion.orbit);
        p.position = centre + turn * (p.position - centre);
        p.rotation = glm::normalize(turn * p.rotation);
    }
    return p;
}

scene_description read_scene_description(const std::filesystem::path& file) {
    scene_description d;
    d.file = file;
    std::ifstream in(file);
    if (!in) fail("scene file ", file.string(), ": cannot be opened");
    json doc;
    try {
        doc = json::parse(in);
    } catch (const json::parse_error& e) {
        fail("scene file ", file.string(), ": not JSON (byte ", e.byte, "): ", e.what());
    }
    if (!doc.is_object()) scene_file_error(d, "(top)", "not an object");
    d.world = scene_path(d, scene_text(d, doc, "world", ""));
    if (!doc.contains("models") || !doc["models"].is_object()) scene_file_error(d, "models", "missing, or not an object");
    for (auto& [name, m] : doc["models"].items()) {
        std::string model_file = scene_path(d, scene_text(d, m, "file", "models." + name + "."));
        scene_model_file f{name, model_file, model_fields::bricks, std::nullopt};
        if (m.contains("fields")) {
            std::string fields = scene_text(d, m, "fields", "models." + name + ".");
            if (fields != "bricks" && fields != "none")
                scene_file_error(d, "models." + name + ".fields", "\"" + fields + "\" is neither \"bricks\" nor \"none\"");
            f.fields = fields == "bricks" ? model_fields::bricks : model_fields::none;
        }
        if (m.contains("region")) {
            std::string at = "models." + name + ".region";
            auto r = scene_numbers(d, m["region"], at, 6);
            for (float v : r)
                if (v != std::floor(v) || std::abs(v) > float(1 << 30))
                    scene_file_error(d, at, "expected whole voxel coordinates within +-2^30 (" + json(v).dump() + ")");
            f.region = box3i{{int(r[0]), int(r[1]), int(r[2])}, {int(r[3]), int(r[4]), int(r[5])}};
        }
        d.models.push_back(f);
    }
    if (!doc.contains("instances") || !doc["instances"].is_array()) scene_file_error(d, "instances", "missing, or not an array");
    for (std::size_t i = 0; i < doc["instances"].size(); ++i) d.instances.push_back(read_instance(d, doc["instances"][i], i));
    return d;
}

loaded_scene load_scene_description(const std::string& spec, const scene_options& o) {
    loaded_scene s;
    s.description = read_scene_description(spec);
    s.world = load_scene(s.description.world, o);
    for (auto& m : s.description.models) {
        s.models.push_back(load_scene(m.file, o));
        if (m.region) {
            try {
                s.models.back() = region_model(s.models.back(), *m.region);
            } catch (const error& x) {
                scene_file_error(s.description, "models." + m.name + ".region", x.what());
            }
        }
        s.entity_models.emplace_back(s.models.back(), m.fields);
    }
    for (auto& e : s.description.instances)
        for (std::uint32_t m = 0; m < s.description.models.size(); ++m)
            if (s.description.models[m].name == e.model) s.model_of.push_back(m);
    return s;
}

std::vector<std::string> scene_world_names() {
    std::vector<std::string> names;
    for_each_type(registered::scene_worlds{}, [&]<class W>() { names.emplace_back(W::name); });
    return names;
}

std::vector<std::string> candidates_names() {
    std::vector<std::string> names;
    for (entity_candidates c : every_entity_candidates) names.emplace_back(candidates_name(c));
    return names;
}

std::string all_candidates() { return join_names(candidates_names()); }

int check_scene_file(const std::string& spec, const scene_options& o, int frames, std::size_t ray_count, std::uint64_t seed,
                     const std::string& worlds, const std::string& backends, const std::string& candidates) {
    loaded_scene s = load_scene_description(spec, o);
    std::printf("%zu instances of %zu models over %s, %d frames, %zu rays a frame\n", s.description.instances.size(),
                s.models.size(), scene_label(s.description.world).c_str(), frames, ray_count);
    struct pair {
        std::string world, backend, candidates;
        std::unique_ptr<entity_run> run;
        std::uint64_t instance_hits = 0, mismatches = 0;
    };
    std::vector<pair> pairs;
    for (auto& w : split_names(worlds))
        for (auto& b : split_names(backends))
            for (auto& c : split_names(candidates)) {
                std::fprintf(stderr, "building the scene over %s on %s (%s) ...\n", w.c_str(), b.c_str(), c.c_str());
                pairs.push_back({w, b, c, make_entity_run(w, b, s)});
                pairs.back().run->set_candidates(candidates_named(c));
            }
    // Every pair stands at the same frame; the rays and the reference are the frame's, once.
    for (int f = 0; f < frames; ++f) {
        for (auto& p : pairs) p.run->go_to(f);
        auto rays = entity_rays(s, *pairs.front().run, f, ray_count, seed);
        std::fprintf(stderr, "frame %d: the reference on %zu rays ...\n", f, rays.size());
        auto want = pairs.front().run->reference(rays, VX_MODE_CLOSEST);
        std::vector<hit> closest(rays.size()), any(rays.size());
        for (auto& p : pairs) {
            p.run->closest_hit(rays, closest);
            p.run->any_hit(rays, any);
            for (std::size_t i = 0; i < rays.size(); ++i) {
                p.instance_hits += hit_instance(want[i]) ? 1 : 0;
                if (same_scene_hit(closest[i], want[i]) && any[i].status == want[i].status) continue;
                if (p.mismatches++ < 3)
                    std::printf("  mismatch, %s on %s (%s), frame %d ray %zu: o (%.9g %.9g %.9g) d (%.9g %.9g %.9g): got "
                                "t=%.9g material=%u, want t=%.9g material=%u\n",
                                p.world.c_str(), p.backend.c_str(), p.candidates.c_str(), f, i, rays[i].origin.x, rays[i].origin.y, rays[i].origin.z,
                                rays[i].direction.x, rays[i].direction.y, rays[i].direction.z, closest[i].t, closest[i].material,
                                want[i].t, want[i].material);
            }
        }
    }
    std::printf("%-8s %-11s %-11s %12s %12s\n", "world", "backend", "candidates", "instance hits", "mismatches");
    std::uint64_t mismatches = 0;
    for (auto& p : pairs) {
        std::printf("%-8s %-11s %-11s %12llu %12llu\n", p.world.c_str(), p.backend.c_str(), p.candidates.c_str(),
                    (unsigned long long)p.instance_hits, (unsigned long long)p.mismatches);
        mismatches += p.mismatches;
    }
    std::printf("%llu mismatches\n", (unsigned long long)mismatches);
    return mismatches == 0 ? 0 : 1;
}

int render_scene_file(const std::string& spec, const scene_options& o, int frames, const std::string& world,
                      const std::string& backend, int width, int height, int view, const std::string& out) {
    loaded_scene s = load_scene_description(spec, o);
    auto run = make_entity_run(world, backend, s);
    camera cam = auto_camera(s.world.bounds(), s.world.up_axis, view);
    glm::vec3 sun = sun_direction(s.world.up_axis);
    auto rays = primary_rays(cam, width, height);
    std::vector<hit> hits(rays.size()), shadow(rays.size());
    for (int f = 0; f < frames; ++f) {
        run->go_to(f);
        run->closest_hit(rays, hits);
        // An instance's face turns with it: normals and shadow-ray offsets in the world's frame.
        std::vector<glm::vec3> normals(rays.size());
        std::vector<ray> shadow_set(rays.size(), inactive_ray());
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if (!has_surface(hits[i])) continue;
            glm::vec3 n = face_normal(hits[i].normal);
            if (auto id = hit_instance(hits[i])) n = run->where(*id).rotation * n;
            normals[i] = n;
            shadow_set[i].origin = rays[i].origin + rays[i].direction * hits[i].t + n * hit_offset;
            shadow_set[i].direction = sun;
            shadow_set[i].tmin = 0.0f;
            shadow_set[i].tmax = INFINITY;
        }
        run->any_hit(shadow_set, shadow);
        std::vector<std::uint8_t> rgb(rays.size() * 3);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            glm::vec3 c = sky(rays[i].direction, s.world.up_axis);
            if (hits[i].is_hit()) {
                auto id = hit_instance(hits[i]);
                const palette& p = id ? s.models[s.model_of[*id]].palette() : s.world.palette();
                rgba colour = p[hit_palette_index(hits[i])].colour;
                float lambert = std::max(0.0f, glm::dot(normals[i], sun));
                c = glm::vec3(colour.r, colour.g, colour.b) / 255.0f * (0.3f + 0.7f * (shadow[i].is_hit() ? 0.0f : lambert));
            }
            auto px = to_srgb8(c);
            std::copy(px.begin(), px.end(), rgb.begin() + i * 3);
        }
        std::filesystem::path path(out);
        if (frames > 1) {
            char index[16];
            std::snprintf(index, sizeof index, "_%03d", f);
            path = path.parent_path() / (path.stem().string() + index + path.extension().string());
        }
        write_image(path.string(), width, height, rgb);
        std::printf("wrote %s (frame %d: %zu instances over %s on %s; update %.3f ms, %llu bytes sent)\n", path.string().c_str(), f,
                    s.description.instances.size(), world.c_str(), backend.c_str(), run->seconds_last_update() * 1e3,
                    (unsigned long long)run->bytes_last_update());
    }
    return 0;
}

}  // namespace voxray::tool

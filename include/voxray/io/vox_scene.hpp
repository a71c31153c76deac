// Scene level of the .vox reader: walks the nTRN/nGRP/nSHP graph of a parsed vox_file
// and writes every placed model into one voxel_model.
//
// Placement (MagicaVoxel's convention, checked against the shared test scenes): a model
// of size s is centred on its transform with the integer pivot floor(s / 2), and the
// rotation turns it about that pivot:
//
//     world = T + R * (v - floor(s / 2))        v = voxel position in the model
//
// where R and T are the products of the transforms from the root down:
//     R = R_root * ... * R_leaf,   T = T_root + R_root * (T_next + R_next * (...)).
// Files without a scene graph place every model with its min corner at the origin
// (world = v), so PACK animations such as rock.vox overlap.
//
// Axes stay those of the file: x, y, z with Z up. Voxels written later in traversal
// order (depth first, children in file order) overwrite earlier ones.
//
// Cost is checked before anything is written: a first walk of the graph counts the
// instances, the voxels they place and an upper bound of the model's memory, so a small
// file that instances one model a million times is refused in milliseconds, with the
// numbers, instead of after minutes and gigabytes (issue 12, item 10). The limits are
// vox_options fields; the tool sets them with --max-voxels and --max-model-mib.
//
// Animation: a transform keeps a list of keyframes (_f) and a shape a list of models
// with keyframes. For frame F we use the keyframe with the largest _f <= F (the one
// that is showing at F), or the earliest keyframe when all start after F.
#pragma once
#include <algorithm>
#include <cstdint>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/io/vox_chunks.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::io {

struct vox_options {
    int frame = 0;                // animation frame to compose
    bool include_hidden = true;   // also place hidden nodes and nodes on hidden layers
    int max_depth = 64;           // nodes on one root-to-leaf path
    std::uint64_t max_instances = std::uint64_t(1) << 20;
    std::uint64_t max_node_visits = std::uint64_t(1) << 22;  // bounds instancing blow-up
    std::uint64_t max_placed_voxels = std::uint64_t(1) << 27;  // voxels written, overlaps counted
    // Upper bound of the composed model's memory (its 16^3 chunks), checked before placing.
    std::uint64_t max_model_bytes = std::uint64_t(4) << 30;
};

struct vox_scene_stats {
    int version = 0;
    std::size_t models = 0;           // SIZE/XYZI pairs in the file
    std::size_t nodes = 0;            // scene graph nodes (0: no scene graph)
    std::size_t instances = 0;        // models placed (shapes reached, for the frame)
    std::uint64_t placed_voxels = 0;  // voxels written, before overlaps merge
    box3i placed_bounds;              // union of the placed models' SIZE boxes
    std::uint64_t model_bytes_bound = 0;  // what the limit max_model_bytes was checked against
    bool has_palette = false;         // RGBA chunk present
    int material_chunks = 0;          // MATL chunks
};

namespace detail {

struct vox_placement {
    vox_rotation rotation;
    glm::i64vec3 translation{0};
};

// Index of the entry showing at `frame`; `key(i)` gives entry i's keyframe.
template <class Key>
std::size_t select_keyframe(std::size_t count, int frame, Key key) {
    std::size_t best = count, first = 0;
    for (std::size_t i = 0; i < count; ++i) {
        if (key(i) < key(first)) first = i;
        if (key(i) <= frame && (best == count || key(i) > key(best))) best = i;
    }
    return best == count ? first : best;
}

inline const char* node_chunk(const vox_node& n) {
    switch (n.type) {
    case vox_node::kind::transform: return "nTRN";
    case vox_node::kind::group: return "nGRP";
    default: return "nSHP";
    }
}

class vox_composer {
public:
    vox_composer(const vox_file& file, const vox_options& options, std::string_view name, voxel_model& out,
                 vox_scene_stats& stats)
        : file_(file), options_(options), name_(name), out_(out), stats_(stats) {}

    // Counts first (nothing written), checks the totals, then places.
    void run() {
        walk();
        check_totals();
        counting_ = false;
        visits_ = 0;
        walk();
    }

private:
    // Worst case of new chunks: each instance fills at most min(voxels, chunks its box
    // spans), and all of them at most the chunks of the union of the boxes.
    void check_totals() {
        const auto& b = stats_.placed_bounds;
        std::uint64_t union_chunks = 0;
        if (!b.empty()) {
            union_chunks = 1;
            for (int i = 0; i < 3; ++i)
                union_chunks *= std::uint64_t(((b.max[i] - 1) >> voxel_model::chunk_bits) -
                                              (b.min[i] >> voxel_model::chunk_bits) + 1);
        }
        constexpr std::uint64_t chunk_bytes = sizeof(voxel_model::chunk) + 64;  // + hash-map node
        stats_.model_bytes_bound = std::min(chunk_bound_, union_chunks) * chunk_bytes;
        if (stats_.placed_voxels > options_.max_placed_voxels)
            fail(name_, ": the scene places ", stats_.placed_voxels, " voxels (", stats_.instances,
                 " model instances), above the limit of ", options_.max_placed_voxels,
                 " placed voxels (vox_options::max_placed_voxels)");
        if (stats_.model_bytes_bound > options_.max_model_bytes)
            fail(name_, ": the scene's ", stats_.instances, " model instances may need up to ",
                 stats_.model_bytes_bound, " bytes of voxel chunks, above the limit of ", options_.max_model_bytes,
                 " bytes (vox_options::max_model_bytes)");
    }

    void walk() {
        if (file_.nodes.empty()) {
            // No scene graph: min corner at the origin, i.e. T = the pivot.
            for (std::size_t m = 0; m < file_.models.size(); ++m) {
                vox_placement p;
                p.translation = glm::i64vec3(file_.models[m].size / 2);
                place(std::int32_t(m), p, nullptr);
            }
            return;
        }
        for (std::size_t i = 0; i < file_.nodes.size(); ++i) index_.emplace(file_.nodes[i].id, i);
        on_path_.assign(file_.nodes.size(), false);
        auto root = index_.find(0);
        if (root == index_.end()) fail(name_, ": the scene graph has no root node (id 0)");
        visit(root->second, vox_placement{}, 1);
    }

    template <class... Parts>
    [[noreturn]] void node_error(const vox_node& n, Parts&&... parts) const {
        fail(name_, ": byte ", n.offset, " in chunk '", node_chunk(n), "': node ", n.id, ": ",
             std::forward<Parts>(parts)...);
    }

    std::size_t lookup(const vox_node& from, std::int32_t id) const {
        auto it = index_.find(id);
        if (it == index_.end()) node_error(from, "child node ", id, " does not exist");
        return it->second;
    }

    void visit(std::size_t index, const vox_placement& parent, int depth) {
        const vox_node& n = file_.nodes[index];
        if (depth > options_.max_depth)
            node_error(n, "scene graph is deeper than the limit of ", options_.max_depth, " nodes");
        if (on_path_[index]) node_error(n, "scene graph has a cycle through this node");
        if (++visits_ > options_.max_node_visits)
            node_error(n, "scene graph expands to more than ", options_.max_node_visits, " node visits");
        if (!options_.include_hidden && n.hidden) return;
        on_path_[index] = true;
        switch (n.type) {
        case vox_node::kind::transform: {
            if (!options_.include_hidden) {
                auto layer = file_.hidden_layers.find(n.layer);
                if (layer != file_.hidden_layers.end() && layer->second) break;
            }
            vox_placement p = parent;
            if (!n.frames.empty()) {
                auto& fr = n.frames[select_keyframe(n.frames.size(), options_.frame,
                                                    [&](std::size_t i) { return n.frames[i].key; })];
                p.translation = parent.translation + parent.rotation.apply(fr.translation);
                p.rotation = parent.rotation * fr.rotation;
            }
            visit(lookup(n, n.child), p, depth + 1);
            break;
        }
        case vox_node::kind::group:
            for (auto child : n.children) visit(lookup(n, child), parent, depth + 1);
            break;
        case vox_node::kind::shape:
            if (!n.models.empty()) {
                auto i = select_keyframe(n.models.size(), options_.frame,
                                         [&](std::size_t k) { return n.models[k].first; });
                place(n.models[i].second, parent, &n);
            }
            break;
        }
        on_path_[index] = false;
    }

    void place(std::int32_t model_id, const vox_placement& p, const vox_node* shape) {
        auto bad = [&](auto&&... parts) {
            if (shape) node_error(*shape, parts...);
            fail(name_, ": model ", model_id, ": ", parts...);
        };
        if (model_id < 0 || std::size_t(model_id) >= file_.models.size())
            bad("model id ", model_id, " is outside 0..", std::int64_t(file_.models.size()) - 1);
        const vox_model_data& m = file_.models[std::size_t(model_id)];
        if (counting_) {
            if (++stats_.instances > options_.max_instances)
                bad("more than ", options_.max_instances, " model instances");
            stats_.placed_voxels += m.voxels.size();
        }

        // The placed box: transform the two extreme corners (a signed permutation maps
        // the box's corners to the new box's corners).
        glm::i64vec3 pivot(m.size / 2);
        glm::i64vec3 a = p.translation + p.rotation.apply(glm::i64vec3(0) - pivot);
        glm::i64vec3 b = p.translation + p.rotation.apply(glm::i64vec3(m.size - 1) - pivot);
        glm::i64vec3 lo = glm::min(a, b), hi = glm::max(a, b);
        constexpr std::int64_t limit = voxel_model::coordinate_limit;
        for (int i = 0; i < 3; ++i)
            if (lo[i] < -limit || hi[i] >= limit)
                bad("model ", model_id, " placed at (", lo.x, ", ", lo.y, ", ", lo.z, ")..(", hi.x, ", ", hi.y, ", ",
                    hi.z, ") is outside the coordinate limit of +-", limit);
        if (counting_) {
            stats_.placed_bounds.include(box3i{glm::ivec3(lo), glm::ivec3(hi) + 1});
            std::uint64_t box_chunks = 1;
            for (int i = 0; i < 3; ++i)
                box_chunks *= std::uint64_t((hi[i] >> voxel_model::chunk_bits) - (lo[i] >> voxel_model::chunk_bits) + 1);
            chunk_bound_ += std::min<std::uint64_t>(box_chunks, m.voxels.size());
            return;
        }

        glm::ivec3 t(p.translation);
        glm::ivec3 piv(pivot);
        for (auto& v : m.voxels) {
            glm::ivec3 local = glm::ivec3(v[0], v[1], v[2]) - piv;
            out_.set(t + p.rotation.apply(local), v[3]);
        }
    }

    const vox_file& file_;
    const vox_options& options_;
    std::string_view name_;
    voxel_model& out_;
    vox_scene_stats& stats_;
    std::unordered_map<std::int32_t, std::size_t> index_;
    std::vector<bool> on_path_;
    std::uint64_t visits_ = 0;
    bool counting_ = true;        // first walk: count and check, write nothing
    std::uint64_t chunk_bound_ = 0;
};

}  // namespace detail

// Places the models of `file` into `out` following its scene graph.
inline void compose_vox(const vox_file& file, const vox_options& options, std::string_view name, voxel_model& out,
                        vox_scene_stats& stats) {
    detail::vox_composer(file, options, name, out, stats).run();
}

}  // namespace voxray::io

// A scene: one world structure plus instances of entity models that move, turn and come
// and go (layout: entities/layout.h; kernels: entities/scene_kernel.h and pass.h). Traced
// like any structure, tracer<Backend, scene<naadf>>, with hits that say what they hit
// (scene_hit.hpp). Include the header of the world kind, entities/worlds/<world>.hpp, which
// registers its scene kernel.
//
// The world is walked first, unchanged, then the instances whose boxes the ray meets before
// the world's hit, found by a BVH or by chunk lists (set_candidates): the world's own fields
// never hear of entities, so moving them never resets or regrows a field (the NAADF paper
// marks chunks with entities as non-empty instead, which costs the world's tracing and
// upkeep).
//
// Threads: add, move, remove and the model calls may come from any thread; they record the
// change and return. Tracers (update) and other consumers take consistent frames
// (snapshot, changes_since), which first fold the changes into the words: moved instances
// cost their record and the BVH nodes above them (with chunk lists: their boxes and the
// lists of the chunks they left or entered); added or removed ones a BVH rebuild (and a
// build of the chunk lists); more slots, another model or another way to find candidates
// a new layout, sent whole. The world is the caller's and must
// outlive the scene; where it is edited in place (brickmap, NAADF), a frame also takes the
// world's changed words.
#pragma once
#include <algorithm>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <bit>
#include <utility>
#include <shared_mutex>
#include <span>
#include <string_view>
#include <vector>

#include "voxray/core/blob.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/word_range.hpp"
#include "voxray/entities/candidates.hpp"
#include "voxray/entities/chunk_lists.hpp"
#include "voxray/entities/entity_model.hpp"
#include "voxray/entities/instance_bvh.hpp"
#include "voxray/entities/layout.h"
#include "voxray/entities/pose.hpp"
#include "voxray/sync/change_log.hpp"
#include "voxray/sync/sync_frame.hpp"

namespace voxray {

// The scene kernel over the worlds a world kernel traces (every brickmap<P, E> the brickmap
// kernel, svdag_colours the svdag one): specialized by entities/worlds/<world>.hpp.
template <class WorldKernel>
struct scene_kernel_of;

using model_id = std::uint32_t;
using instance_id = std::uint32_t;

template <class World>
class scene {
public:
    using world_type = World;
    using kernel = typename scene_kernel_of<typename World::kernel>::type;
    static constexpr std::string_view name = kernel::name;

    explicit scene(World& world) : world_(world) {}
    scene(const scene&) = delete;
    scene& operator=(const scene&) = delete;

    // ---- models ----
    model_id add_model(const voxel_model& model, model_fields fields = model_fields::bricks) {
        return add_model(entity_model(model, fields));
    }
    model_id add_model(entity_model model) {
        std::unique_lock lock(m_);
        models_.push_back(std::move(model));
        model_live_.push_back(true);
        relayout_ = true;
        return model_id(models_.size() - 1);
    }
    // Refused while instances of it remain.
    void remove_model(model_id id) {
        std::unique_lock lock(m_);
        check_model(id);
        std::size_t users = std::count_if(slots_.begin(), slots_.end(), [&](const slot& s) { return s.live && s.model == id; });
        if (users > 0) fail("scene: model ", id, " still has ", users, " instances; remove them first");
        model_live_[id] = false;
        models_[id] = entity_model(voxel_model{});  // its words go at the next layout
        relayout_ = true;
    }
    const entity_model& model(model_id id) const {
        std::shared_lock lock(m_);
        check_model(id);
        return models_[id];
    }

    // ---- instances ----
    instance_id add(model_id model, pose where) {
        where = checked_pose(where);
        std::unique_lock lock(m_);
        check_model(model);
        instance_id id;
        if (!free_.empty()) {
            id = free_.back();
            free_.pop_back();
        } else {
            if (slots_.size() >= VX_SC_MAX_SLOTS) fail("scene: ", slots_.size(), " instances, the most a scene holds");
            id = instance_id(slots_.size());
            slots_.push_back({});
        }
        slots_[id] = {model, where, true, false};
        ++live_;
        membership_changed_ = true;
        return id;
    }
    void move(instance_id id, pose where) {
        where = checked_pose(where);
        std::unique_lock lock(m_);
        check_instance(id);
        slots_[id].where = where;
        mark_moved(id);
    }
    // Several moves under one lock: all or none (a bad id or pose moves nothing).
    void move(std::span<const std::pair<instance_id, pose>> moves) {
        std::vector<pose> checked_places;
        for (auto& m : moves) checked_places.push_back(checked_pose(m.second));
        std::unique_lock lock(m_);
        for (auto& m : moves) check_instance(m.first);
        for (std::size_t i = 0; i < moves.size(); ++i) {
            slots_[moves[i].first].where = checked_places[i];
            mark_moved(moves[i].first);
        }
    }
    void remove(instance_id id) {
        std::unique_lock lock(m_);
        check_instance(id);
        slots_[id].live = false;
        free_.push_back(id);
        --live_;
        membership_changed_ = true;
    }

    struct instance_state {
        model_id model;
        pose where;
    };
    std::optional<instance_state> instance(instance_id id) const {
        std::shared_lock lock(m_);
        if (id >= slots_.size() || !slots_[id].live) return std::nullopt;
        return instance_state{slots_[id].model, slots_[id].where};
    }
    std::size_t instance_count() const {
        std::shared_lock lock(m_);
        return live_;
    }
    // Instance slots in use and free: ids lie below this.
    std::size_t slot_count() const {
        std::shared_lock lock(m_);
        return slots_.size();
    }
    World& world() { return world_; }

    // How the kernels find candidate instances (entity_candidates): a new layout, sent whole.
    void set_candidates(entity_candidates c) {
        std::unique_lock lock(m_);
        if (c != candidates_) relayout_ = true;
        candidates_ = c;
    }
    entity_candidates candidates() const {
        std::shared_lock lock(m_);
        return candidates_;
    }

    // ---- what consumers read (see the top comment) ----
    sync_frame snapshot() const {
        std::unique_lock lock(m_);
        commit_locked();
        return {std::move(lock), words_, {}, log_.generation(), 0};
    }
    sync_frame changes_since(std::uint64_t g) {
        std::unique_lock lock(m_);
        commit_locked();
        return {std::move(lock), words_, log_.since(g, std::uint32_t(words_.size())), log_.generation(), 0};
    }
    std::vector<word_range> take_dirty_ranges() {
        auto frame = changes_since(taken_);
        taken_ = frame.generation;
        return std::move(frame.ranges);
    }
    // The words as last committed (a consistent view only while nothing changes: else
    // use snapshot()).
    std::span<const std::uint32_t> blob() const {
        std::unique_lock lock(m_);
        commit_locked();
        return words_;
    }
    std::size_t bytes() const { return blob().size() * sizeof(std::uint32_t); }

    // Bytes of instance records, BVH nodes and chunk lists the last commits changed (what
    // update sends for entities, world changes aside): reported like the structures' own.
    std::uint64_t entity_words_changed_last_commit() const {
        std::shared_lock lock(m_);
        return entity_words_last_;
    }

private:
    struct slot {
        model_id model = 0;
        pose where;
        bool live = false;
        bool moved = false;  // listed in moved_ (once, however often it moves between commits)
    };

    void mark_moved(instance_id id) {
        if (slots_[id].moved) return;
        slots_[id].moved = true;
        moved_.push_back(id);
    }
    void clear_moved() const {
        for (instance_id id : moved_)
            if (id < slots_.size()) slots_[id].moved = false;
        moved_.clear();
    }

    // The moved ids in increasing order: a sweep over the slots' marks where many moved
    // (a sort of 10,000 ids was a fifth of a frame's update).
    void sort_moved() const {
        if (moved_.size() * 8 < slots_.size()) {
            std::sort(moved_.begin(), moved_.end());
            return;
        }
        moved_.clear();
        for (std::uint32_t id = 0; id < slots_.size(); ++id)
            if (slots_[id].moved) moved_.push_back(id);
    }

    void check_model(model_id id) const {
        if (id >= models_.size() || !model_live_[id])
            fail("scene: model ", id, id >= models_.size() ? " does not exist" : " was removed", " (", models_.size(),
                 " models added)");
    }
    void check_instance(instance_id id) const {
        if (id >= slots_.size() || !slots_[id].live)
            fail("scene: instance ", id, id >= slots_.size() ? " does not exist" : " was removed", " (", slots_.size(),
                 " slots)");
    }

    // Folds recorded changes into the words (under the exclusive lock).
    void commit_locked() const {
        std::vector<word_range> ranges;
        pull_world(ranges);
        std::uint32_t capacity = std::max<std::uint32_t>(16, std::bit_ceil(std::uint32_t(std::max<std::size_t>(slots_.size(), 1))));
        if (relayout_ || capacity != capacity_) {
            capacity_ = capacity;
            commit_new_layout();
            return;
        }
        std::uint64_t entity_words = 0;
        bool lists_ok = true;
        if (membership_changed_) {
            for (std::uint32_t s = 0; s < slots_.size(); ++s) write_slot(s);
            ranges.push_back({instances_, std::uint32_t(slots_.size()) * VX_SC_INSTANCE_WORDS});
            rebuild_bvh();
            ranges.push_back({0, VX_SC_HEADER_WORDS});
            ranges.push_back({nodes_, bvh_.node_count() * VX_SC_NODE_WORDS});
            ranges.push_back({items_, std::uint32_t(bvh_.items().size())});
            if (lists_at_ != 0) lists_ok = refresh_lists(ranges, nullptr);
            membership_changed_ = false;
            clear_moved();
        } else if (!moved_.empty()) {
            sort_moved();
            for (instance_id id : moved_) {
                write_slot(id);
                append_joined(ranges, instances_ + id * VX_SC_INSTANCE_WORDS, VX_SC_INSTANCE_WORDS);
                boxes_[id] = box_of(id);
            }
            for (std::uint32_t n : bvh_.refit(moved_, boxes_)) {
                std::copy_n(bvh_.node_words().begin() + n * VX_SC_NODE_WORDS, VX_SC_NODE_WORDS,
                            words_.begin() + nodes_ + n * VX_SC_NODE_WORDS);
                append_joined(ranges, nodes_ + n * VX_SC_NODE_WORDS, VX_SC_NODE_WORDS);
            }
            if (lists_at_ != 0) lists_ok = refresh_lists(ranges, &moved_);
            clear_moved();
        }
        if (!lists_ok) {
            commit_new_layout();  // the lists outgrew their room
            return;
        }
        for (auto& r : ranges)
            if (r.offset >= world_end()) entity_words += r.count;
        if (!ranges.empty()) entity_words_last_ = entity_words;
        log_.commit(ranges, false, std::uint32_t(words_.size()));
    }

    void commit_new_layout() const {
        lay_out();
        log_.commit({}, true, std::uint32_t(words_.size()));
        entity_words_last_ = words_.size() - world_words_;
        relayout_ = membership_changed_ = false;
        clear_moved();
    }

    std::uint32_t world_end() const { return VX_SC_WORLD + world_words_; }

    std::vector<std::uint32_t> live_slots() const {
        std::vector<std::uint32_t> live;
        for (std::uint32_t s = 0; s < slots_.size(); ++s)
            if (slots_[s].live) live.push_back(s);
        return live;
    }

    // Brings the chunk lists up to date with the boxes (only the moved instances', where
    // `moved` is given: their boxes and the lists they left or entered, else a full build)
    // and adds the words that changed to `ranges`; false where they outgrew their room.
    bool refresh_lists(std::vector<word_range>& ranges, const std::vector<instance_id>* moved) const {
        if (moved && chunk_lists_.move(*moved, boxes_, live_)) {
            const auto& fresh = chunk_lists_.words();
            if (fresh.size() > lists_room_) return false;
            for (const word_range& r : chunk_lists_.changed()) {
                std::copy_n(fresh.begin() + r.offset, r.count, words_.begin() + lists_at_ + r.offset);
                append_joined(ranges, lists_at_ + r.offset, r.count);
            }
            return true;
        }
        chunk_lists_.build(live_slots(), boxes_, capacity_);
        const auto& fresh = chunk_lists_.words();
        if (fresh.size() > lists_room_) return false;
        std::copy(fresh.begin(), fresh.end(), words_.begin() + lists_at_);
        append_joined(ranges, lists_at_, std::uint32_t(fresh.size()));
        return true;
    }

    // The world's words: all of them at the first layout; then, for a world edited in place,
    // the ranges it changed (a new layout where it changed size).
    void pull_world(std::vector<word_range>& ranges) const {
        if (words_.empty()) {
            relayout_ = true;
            return;
        }
        if constexpr (requires(World& w, std::uint64_t g) { w.changes_since(g).ranges; }) {
            auto frame = world_.changes_since(world_generation_);
            if (frame.generation == world_generation_) return;
            world_generation_ = frame.generation;
            if (frame.blob.size() != world_words_) {
                relayout_ = true;
                return;
            }
            for (const word_range& r : frame.ranges) {
                std::copy_n(frame.blob.begin() + r.offset, r.count, words_.begin() + VX_SC_WORLD + r.offset);
                ranges.push_back({VX_SC_WORLD + r.offset, r.count});
            }
        }
    }

    // A new layout over the world's words as they are (a consistent frame where the world
    // is edited from other threads: held while they are copied).
    void lay_out() const {
        if constexpr (requires(const World& w) { w.snapshot().blob; }) {
            auto frame = world_.snapshot();
            world_generation_ = frame.generation;
            lay_out(frame.blob);
        } else {
            lay_out(world_.blob());
        }
    }

    void lay_out(std::span<const std::uint32_t> world) const {
        world_words_ = std::uint32_t(world.size());
        std::uint64_t at = VX_SC_WORLD + world.size();
        model_offset_.assign(models_.size(), VX_SC_FREE_SLOT);
        for (std::size_t m = 0; m < models_.size(); ++m) {
            if (!model_live_[m]) continue;
            model_offset_[m] = std::uint32_t(at);
            at += models_[m].words().size();
            check_blob_size("scene", at);
        }
        std::uint64_t instances = at;
        std::uint64_t nodes = instances + std::uint64_t(capacity_) * VX_SC_INSTANCE_WORDS;
        std::uint64_t items = nodes + std::uint64_t(2 * capacity_) * VX_SC_NODE_WORDS;
        std::uint64_t end = items + capacity_;
        // The chunk lists' room: what they need now four times over (lists are appended as
        // instances move, up to as many words again, then packed by a full build).
        lists_at_ = 0, lists_room_ = 0;
        if (candidates_ == entity_candidates::chunk_lists) {
            boxes_.assign(slots_.size(), world_box{});
            for (std::uint32_t s : live_slots()) boxes_[s] = box_of(s);
            chunk_lists_.build(live_slots(), boxes_, capacity_);
            lists_room_ = std::bit_ceil(4 * std::uint32_t(chunk_lists_.words().size()) + 2048);
            lists_at_ = std::uint32_t(end);
            end += lists_room_;
        }
        check_blob_size("scene", end);
        words_.assign(end, 0u);
        instances_ = std::uint32_t(instances), nodes_ = std::uint32_t(nodes), items_ = std::uint32_t(items);
        words_[VX_SC_HEADER_MAGIC] = VX_SC_MAGIC;
        words_[VX_SC_HEADER_VERSION] = VX_SC_VERSION;
        words_[VX_SC_HEADER_WORLD_WORDS] = world_words_;
        words_[VX_SC_HEADER_INSTANCES] = instances_;
        words_[VX_SC_HEADER_SLOTS] = capacity_;
        words_[VX_SC_HEADER_NODES] = nodes_;
        words_[VX_SC_HEADER_ITEMS] = items_;
        std::copy(world.begin(), world.end(), words_.begin() + VX_SC_WORLD);
        for (std::size_t m = 0; m < models_.size(); ++m)
            if (model_live_[m]) std::copy(models_[m].words().begin(), models_[m].words().end(), words_.begin() + model_offset_[m]);
        for (std::uint32_t s = 0; s < capacity_; ++s) write_slot(s);
        rebuild_bvh();
        if (lists_at_ != 0) {
            std::copy(chunk_lists_.words().begin(), chunk_lists_.words().end(), words_.begin() + lists_at_);
            words_[VX_SC_HEADER_CHUNKS] = lists_at_;
        }
    }

    void write_slot(std::uint32_t s) const {
        std::uint32_t* out = words_.data() + instances_ + std::uint64_t(s) * VX_SC_INSTANCE_WORDS;
        if (s >= slots_.size() || !slots_[s].live) {
            std::fill_n(out, VX_SC_INSTANCE_WORDS, 0u);
            out[VX_SC_INSTANCE_MODEL] = VX_SC_FREE_SLOT;
            return;
        }
        auto w = instance_words(slots_[s].where, models_[slots_[s].model].extent(), model_offset_[slots_[s].model]);
        std::copy(w.begin(), w.end(), out);
    }

    world_box box_of(std::uint32_t s) const { return placed_box(slots_[s].where, models_[slots_[s].model].extent()); }

    void rebuild_bvh() const {
        boxes_.assign(slots_.size(), world_box{});
        std::vector<std::uint32_t> live = live_slots();
        for (std::uint32_t s : live) boxes_[s] = box_of(s);
        // With chunk lists the kernels read only the root's box (the SIMD lanes' early-out):
        // one leaf, refit in one pass over the boxes.
        bool root_only = candidates_ == entity_candidates::chunk_lists;
        bvh_.build(std::move(live), boxes_, root_only ? VX_SC_MAX_SLOTS : instance_bvh::leaf_size);
        std::copy(bvh_.node_words().begin(), bvh_.node_words().end(), words_.begin() + nodes_);
        std::copy(bvh_.items().begin(), bvh_.items().end(), words_.begin() + items_);
        words_[VX_SC_HEADER_NODE_COUNT] = bvh_.node_count();
        words_[VX_SC_HEADER_ITEM_COUNT] = std::uint32_t(bvh_.items().size());
    }

    World& world_;
    mutable std::shared_mutex m_;
    std::deque<entity_model> models_;  // a deque: model() references stay valid as models are added
    std::vector<bool> model_live_;
    mutable std::vector<slot> slots_;  // `moved` marks are cleared by commits (under the exclusive lock)
    std::vector<instance_id> free_;
    std::size_t live_ = 0;
    std::uint64_t taken_ = 0;  // generation take_dirty_ranges handed out last

    // Derived in commit_locked (under the exclusive lock, also from const consumers).
    mutable std::vector<instance_id> moved_;
    mutable bool relayout_ = true, membership_changed_ = false;
    mutable blob_words words_;
    mutable std::vector<std::uint32_t> model_offset_;
    mutable std::vector<world_box> boxes_;
    mutable instance_bvh bvh_;
    entity_candidates candidates_ = entity_candidates::bvh;
    mutable chunk_lists chunk_lists_;
    mutable std::uint32_t lists_at_ = 0, lists_room_ = 0;  // the chunk lists' offset and room
    mutable change_log log_;
    mutable std::uint32_t capacity_ = 0, world_words_ = 0, instances_ = 0, nodes_ = 0, items_ = 0;
    mutable std::uint64_t world_generation_ = 0, entity_words_last_ = 0;
};

}  // namespace voxray

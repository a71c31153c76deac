// Brick allocation for the brickmap: recycled bricks come from a free ring first, fresh
// ones from the unused tail of the pool's capacity. When both are exhausted, allocate()
// says so and the brickmap grows the pool (doubling) under its exclusive lock, so the
// pool never runs out silently.
//
// The free ring is a bounded multi-producer/multi-consumer queue: a power-of-two array
// of slots, each with a sequence number that tells producers and consumers whether the
// slot is theirs (head and tail are atomic counters; the index is counter & mask, the
// cheap modulo of the brickmap paper). Its capacity is at least the pool's, so a push of
// a brick that belongs to the pool can never find it full.
//
//   slot i:  seq == pos       -> free for the producer that claims head == pos
//            seq == pos + 1   -> holds a brick for the consumer that claims tail == pos
//
// State lives in plain members accessed through std::atomic_ref, so the pool moves.
#pragma once
#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <vector>

namespace voxray {

class free_ring {
public:
    // Empties the ring and sizes it for at least `n` bricks (single-threaded).
    void reset(std::uint64_t n) {
        std::uint64_t cap = std::bit_ceil(std::max<std::uint64_t>(n, 16));
        seq_.resize(cap);
        value_.assign(cap, 0);
        for (std::uint64_t i = 0; i < cap; ++i) seq_[i] = i;
        mask_ = cap - 1;
        head_ = tail_ = 0;
    }
    // Re-sizes for `n` bricks keeping the content (single-threaded: under the growth lock).
    void reserve(std::uint64_t n) {
        if (n <= capacity()) return;
        std::vector<std::uint32_t> keep;
        std::uint32_t b;
        while (pop(b)) keep.push_back(b);
        reset(n);
        for (auto k : keep) push(k);
    }
    std::uint64_t capacity() const { return mask_ + 1; }
    std::uint64_t size() const {
        return ref(head_).load(std::memory_order_acquire) - ref(tail_).load(std::memory_order_acquire);
    }

    bool push(std::uint32_t brick) {
        std::uint64_t pos = ref(head_).load(std::memory_order_relaxed);
        for (;;) {
            std::uint64_t& s = seq_[pos & mask_];
            std::int64_t d = std::int64_t(ref(s).load(std::memory_order_acquire)) - std::int64_t(pos);
            if (d == 0) {
                if (ref(head_).compare_exchange_weak(pos, pos + 1, std::memory_order_relaxed)) {
                    ref32(value_[pos & mask_]).store(brick, std::memory_order_relaxed);
                    ref(s).store(pos + 1, std::memory_order_release);
                    return true;
                }
            } else if (d < 0) {
                return false;  // full: cannot happen while capacity >= pool capacity
            } else {
                pos = ref(head_).load(std::memory_order_relaxed);
            }
        }
    }
    bool pop(std::uint32_t& brick) {
        std::uint64_t pos = ref(tail_).load(std::memory_order_relaxed);
        for (;;) {
            std::uint64_t& s = seq_[pos & mask_];
            std::int64_t d = std::int64_t(ref(s).load(std::memory_order_acquire)) - std::int64_t(pos + 1);
            if (d == 0) {
                if (ref(tail_).compare_exchange_weak(pos, pos + 1, std::memory_order_relaxed)) {
                    brick = ref32(value_[pos & mask_]).load(std::memory_order_relaxed);
                    ref(s).store(pos + mask_ + 1, std::memory_order_release);
                    return true;
                }
            } else if (d < 0) {
                return false;  // empty
            } else {
                pos = ref(tail_).load(std::memory_order_relaxed);
            }
        }
    }

private:
    static std::atomic_ref<std::uint64_t> ref(const std::uint64_t& v) {
        return std::atomic_ref<std::uint64_t>(const_cast<std::uint64_t&>(v));
    }
    static std::atomic_ref<std::uint32_t> ref32(std::uint32_t& v) { return std::atomic_ref<std::uint32_t>(v); }

    std::vector<std::uint64_t> seq_;
    std::vector<std::uint32_t> value_;
    std::uint64_t mask_ = 0;
    alignas(64) std::uint64_t head_ = 0;  // producers (recycling)
    alignas(64) std::uint64_t tail_ = 0;  // consumers (allocation)
};

// Capacity bookkeeping: `used` is the high-water mark of bricks ever handed out from
// fresh capacity; bricks below it are either referenced by a top cell or in the ring.
class brick_pool {
public:
    static constexpr std::uint32_t none = 0xFFFFFFFFu;

    void reset(std::uint32_t capacity) {
        capacity_ = capacity;
        used_ = 0;
        ring_.reset(capacity);
    }
    // Returns a brick index, or `none` when the pool must grow. Thread-safe.
    std::uint32_t allocate() {
        std::uint32_t b;
        if (ring_.pop(b)) return b;
        std::atomic_ref<std::uint32_t> used(used_);
        std::uint32_t u = used.load(std::memory_order_relaxed);
        while (u < capacity_)
            if (used.compare_exchange_weak(u, u + 1, std::memory_order_relaxed)) return u;
        return none;
    }
    // Gives an all-zero brick back. Thread-safe.
    void recycle(std::uint32_t brick) { ring_.push(brick); }

    // Single-threaded (growth lock held).
    void grow_to(std::uint32_t capacity) {
        capacity_ = capacity;
        ring_.reserve(capacity);
    }
    // Single-threaded: capacity down to `capacity` >= used (the ring keeps its size).
    void shrink_to(std::uint32_t capacity) { capacity_ = capacity; }
    // Single-threaded: after loading, bricks [0, used) minus the referenced ones are free.
    void restore(std::uint32_t capacity, std::uint32_t used, const std::vector<std::uint32_t>& free_bricks) {
        reset(capacity);
        used_ = used;
        for (auto b : free_bricks) ring_.push(b);
    }

    std::uint32_t capacity() const { return capacity_; }
    std::uint32_t used() const { return std::atomic_ref<std::uint32_t>(const_cast<std::uint32_t&>(used_)).load(); }
    std::uint64_t free_in_ring() const { return ring_.size(); }
    // Bricks referenced by top cells.
    std::uint64_t live() const { return used() - free_in_ring(); }

private:
    free_ring ring_;
    std::uint32_t capacity_ = 0;
    std::uint32_t used_ = 0;
};

}  // namespace voxray

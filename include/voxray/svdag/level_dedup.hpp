// Merging identical nodes of one octree level, in parallel and deterministically.
//
// The items of a level (leaf masks, or interior nodes as child mask + child ids) come in
// depth-first (Morton) order. Each thread takes the items whose hash falls in its shard
// and finds, with its own open-addressing table, the first item with the same content;
// then one serial pass numbers the distinct contents in order of first appearance. The
// ids therefore depend only on the items, never on the thread count or timing: the same
// model gives the same bytes.
#pragma once
#include <bit>
#include <cstdint>
#include <vector>

#include "voxray/model/build_threads.hpp"

namespace voxray::svdag_build {

// 64-bit mix (the finaliser of MurmurHash3), enough to spread node contents.
inline std::uint64_t mix64(std::uint64_t x) {
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    return x ^ (x >> 33);
}

struct dedup_result {
    std::vector<std::uint32_t> id;     // per item: the id of its content
    std::vector<std::uint32_t> first;  // per id: the first item with that content
};

// `hash(item)` and `same(a, b)` define content equality.
template <class Item, class Hash, class Same>
dedup_result dedup_level(const std::vector<Item>& items, unsigned threads, Hash&& hash, Same&& same) {
    std::size_t n = items.size();
    std::vector<std::uint64_t> hashes(n);
    std::vector<std::uint32_t> representative(n);
    threads = resolve_build_threads(threads, n / 4096 + 1);

    run_build_threads(threads, [&](unsigned t) {
        for (std::size_t i = t; i < n; i += threads) hashes[i] = hash(items[i]);
    });
    // Each shard's table is sized from its own item count (two passes over the hashes).
    run_build_threads(threads, [&](unsigned t) {
        std::size_t mine = 0;
        for (std::size_t i = 0; i < n; ++i) mine += hashes[i] % threads == t;
        std::size_t capacity = std::bit_ceil(std::max<std::size_t>(16, mine * 2));
        std::vector<std::uint32_t> table(capacity, UINT32_MAX);  // item index, or empty
        for (std::size_t i = 0; i < n; ++i) {
            if (hashes[i] % threads != t) continue;
            std::size_t slot = (hashes[i] >> 20) & (capacity - 1);
            for (;; slot = (slot + 1) & (capacity - 1)) {
                std::uint32_t other = table[slot];
                if (other == UINT32_MAX) {
                    table[slot] = std::uint32_t(i);
                    representative[i] = std::uint32_t(i);
                    break;
                }
                if (hashes[other] == hashes[i] && same(items[other], items[i])) {
                    representative[i] = other;
                    break;
                }
            }
        }
    });

    dedup_result r;
    r.id.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (representative[i] == i) {
            r.id[i] = std::uint32_t(r.first.size());
            r.first.push_back(std::uint32_t(i));
        } else {
            r.id[i] = r.id[representative[i]];
        }
    }
    return r;
}

}  // namespace voxray::svdag_build

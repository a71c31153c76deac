// What a backend sends when a tracer updates, decided once for every engine: the whole
// blob, nothing, or a commit packet of the changed words (sync/commit_packet.hpp); and
// the ledger of bytes sent that every engine reports (tracer::bytes_uploaded_*).
#pragma once
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "voxray/core/word_range.hpp"
#include "voxray/sync/commit_packet.hpp"
#include "voxray/sync/dirty_ranges.hpp"

namespace voxray::sync {

struct upload_plan {
    enum kind { whole, nothing, packet };
    kind what = whole;
    std::vector<word_range> ranges;  // for `packet`: sorted, merged, inside the blob
};

// `held_words`: the words the device holds (0: none yet). A blob of another size is sent
// whole; so are ranges whose packet would not be smaller than the blob.
inline upload_plan plan_upload(std::uint64_t held_words, std::span<const std::uint32_t> blob,
                               std::span<const word_range> ranges) {
    if (held_words == 0 || blob.size() != held_words) return {};
    std::vector<word_range> merged = normalize_ranges(ranges, blob.size());
    if (merged.empty()) return {upload_plan::nothing, {}};
    if (packet_words(merged.size(), total_words(merged)) >= blob.size()) return {};
    return {upload_plan::packet, std::move(merged)};
}

// Bytes the last upload or update sent, and their running total.
class upload_ledger {
public:
    void count(std::uint64_t bytes) {
        last_ = bytes;
        total_ += bytes;
    }
    std::uint64_t last() const { return last_; }
    std::uint64_t total() const { return total_; }

private:
    std::uint64_t last_ = 0, total_ = 0;
};

}  // namespace voxray::sync

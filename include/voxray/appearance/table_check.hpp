// What a table must be before a walk reads it on any backend: the kernels trust it (a face
// index outside the pool would be a read past a device buffer), so the walkers and the
// file reader (table_file.hpp) check it once, in O(rows).
//
//   check_table(table, [&](std::size_t row, auto... what) { fail("row ", row, ": ", what...); });
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "voxray/appearance/layout.h"
#include "voxray/appearance/table.hpp"
#include "voxray/core/error.hpp"

namespace voxray::appearance {

// Calls `bad(row, what...)`, which must throw, for the first fault: a kind outside the
// enum, record words that are not the kind's, a words array of another length, rows out of
// the ordinal order (or repeated), shadows of another length or for a direction that is not a
// unit vector, an odd face pool, a compact record whose faces leave the pool or number more
// than VX_APP_MAX_FACES. Row 0 stands for the table as a whole.
template <class Bad>
void check_table(const appearance_table& t, Bad&& bad) {
    int words = record_words(t.kind);
    if (words == 0) bad(0, "unknown record kind ", int(t.kind));
    if (t.record_words != words)
        bad(0, record_name(t.kind), " records take ", words, " words, the table says ", t.record_words);
    if (t.words.size() != t.voxels.size() * std::size_t(words))
        bad(0, t.words.size(), " record words for ", t.voxels.size(), " rows of ", words);
    for (std::size_t row = 1; row < t.voxels.size(); ++row)
        if (!ordinal_less(t.voxels[row - 1], t.voxels[row]))
            bad(row, "voxel (", t.voxels[row].x, ", ", t.voxels[row].y, ", ", t.voxels[row].z,
                ") is not after the row before it in the ordinal order (unsorted or repeated)");
    if (t.shadows) {
        glm::vec3 l = t.shadows->to_light;
        if (t.shadows->visibility.size() != t.voxels.size())
            bad(0, "shadows of ", t.shadows->visibility.size(), " rows for a table of ", t.voxels.size());
        if (!(std::abs(l.x * l.x + l.y * l.y + l.z * l.z - 1.0f) < 1e-3f))
            bad(0, "shadows for a light towards (", l.x, ", ", l.y, ", ", l.z, "), not a unit vector");
    }
    if (t.kind != record_kind::compact) return;
    if (t.faces.size() % VX_APP_FACE_WORDS != 0) bad(0, "a face pool of ", t.faces.size(), " words (odd)");
    std::uint64_t pool = t.faces.size() / VX_APP_FACE_WORDS;
    for (std::size_t row = 0; row < t.voxels.size(); ++row) {
        std::span<const std::uint32_t> r = t.record(row);
        std::uint64_t first = VX_APP_FIRST_FACE(r[0]), count = VX_APP_FACES(r[1]);
        if (count > VX_APP_MAX_FACES) bad(row, count, " faces, above the ", VX_APP_MAX_FACES, " a record may have");
        if (first + count > pool)
            bad(row, "faces ", first, " to ", first + count, " outside the pool of ", pool, " faces");
    }
}

// check_table, throwing a voxray::error that starts with `context`.
inline void check_table(const appearance_table& t, const char* context) {
    check_table(t, [&](std::size_t row, auto... what) { fail(context, ": row ", row, ": ", what...); });
}

}  // namespace voxray::appearance

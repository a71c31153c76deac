// What an editable structure (brickmap, NAADF) does with a fill that reaches outside its
// world box, and how far the world grows. Erasing or painting outside needs nothing: there is nothing there.
//
//   grow  (default) the world box grows to hold the edit: its min corner moves down by
//         whole pages (a brickmap's 16 bricks, NAADF's 256 voxels), so existing pages
//         keep their cells,
//         and each grown side gets headroom of half the old extent, so a brush dragged
//         outwards re-lays the blob out O(log) times, not once per stroke;
//   fail  the edit throws voxray::error naming the region and the world, nothing changes;
//   clip  the edit is cut to the world box (the behaviour before growth existed; opt-in).
//
// Growth that cannot be done (coordinates past 32 bits, a blob past its limit) throws
// voxray::error before anything changes.
#pragma once
#include <cstdint>
#include <limits>

#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/edit/regions.hpp"

namespace voxray {

enum class outside_edits { grow, fail, clip };

namespace world_growth {

inline std::int64_t round_up(std::int64_t v, std::int64_t m) { return (v + m - 1) / m * m; }

// The grown world box holding `world` and `need`, its min corner moved by multiples of
// `span` voxels (a page). Throws when that cannot fit 32-bit voxel coordinates.
inline box3i grown(const box3i& world, const regions::box64& need, std::int64_t span, const char* who = "brickmap") {
    constexpr std::int64_t lo_limit = std::numeric_limits<int>::min(), hi_limit = std::numeric_limits<int>::max();
    box3i out = world;
    for (int a = 0; a < 3; ++a) {
        std::int64_t lo = world.min[a], hi = world.max[a], ext = hi - lo;
        // The least growth that holds `need`, then the same plus headroom if that fits.
        std::int64_t down = need.min[a] < lo ? round_up(lo - need.min[a], span) : 0;
        std::int64_t up = need.max[a] > hi ? need.max[a] - hi : 0;
        auto fits = [&](std::int64_t d, std::int64_t u) {
            return lo - d >= lo_limit && hi + u <= hi_limit && (hi + u) - (lo - d) <= hi_limit;
        };
        if (!fits(down, up))
            fail(who, ": a fill over voxels [", need.min[a], ", ", need.max[a], ") on axis ", "xyz"[a],
                 " cannot grow the world [", lo, ", ", hi, "): the grown world would not fit 32-bit voxel "
                 "coordinates (min >= ", lo_limit, ", max and extent <= ", hi_limit, ")");
        std::int64_t room = ext / 2;
        std::int64_t down_room = down ? round_up(down + room, span) : 0, up_room = up ? up + room : 0;
        if (fits(down_room, up_room)) down = down_room, up = up_room;
        else if (fits(down_room, up)) down = down_room;
        else if (fits(down, up_room)) up = up_room;
        out.min[a] = int(lo - down);
        out.max[a] = int(hi + up);
    }
    return out;
}

[[noreturn]] inline void refuse(const box3i& world, const regions::box64& need, const char* who = "brickmap") {
    fail(who, ": a fill over voxels [(", need.min.x, ", ", need.min.y, ", ", need.min.z, "), (", need.max.x, ", ",
         need.max.y, ", ", need.max.z, ")) reaches outside the world [(", world.min.x, ", ", world.min.y, ", ",
         world.min.z, "), (", world.max.x, ", ", world.max.y, ", ", world.max.z,
         ")) and this ", who, " was made with outside_edits::fail");
}

}  // namespace world_growth
}  // namespace voxray

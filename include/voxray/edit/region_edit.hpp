// One region edit in a structure-neutral form: a region, what to do there and the value
// (a material index). Tools and tests hand the same list to every editable structure.
#pragma once
#include <cstdint>
#include <variant>

#include "voxray/edit/edit_op.hpp"
#include "voxray/edit/regions.hpp"

namespace voxray {

struct region_edit {
    std::variant<regions::box, regions::sphere, regions::capsule> region;
    edit_op op = edit_op::fill;
    std::uint32_t value = 0;
};

}  // namespace voxray

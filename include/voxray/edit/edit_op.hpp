// What an edit does to the voxels of its region: fill sets them (solid, with a value),
// erase clears them, paint changes the value of those already solid. Shared by every
// editable structure, so tools and tests treat them alike.
#pragma once

namespace voxray {

enum class edit_op { fill, erase, paint };

}  // namespace voxray

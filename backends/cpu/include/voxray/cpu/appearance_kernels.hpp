// The appearance dialect (records, the ordinal index, the walk's types) on the CPU's scalar
// lanes, once per program: for the walk (cpu/appearance_walk.hpp) and for host code that
// evaluates a record exactly as the kernels do.
#pragma once
#include "voxray/cpu/lanes.hpp"

namespace voxray::kernels::scalar {
#include "voxray/appearance/ordinal.h"
#include "voxray/appearance/record.h"
#include "voxray/appearance/faithful_record.h"
#include "voxray/appearance/walk_types.h"
#include "voxray/appearance/walk_visit.h"
}  // namespace voxray::kernels::scalar

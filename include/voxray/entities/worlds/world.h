/* The scene kernel over world worlds (entities/scene_kernel.h). The GPU programs take the
 * world's walk from here; the C++ lanes have it already, from the world's own registration. */
#if !defined(VX_DIALECT_CPP)
#include "voxray/world/kernel.h"
#endif
#define VX_SCENE_WORLD world
#define VX_SCENE_HEADER vx_world
#define VX_SCENE_STATE vx_wd_state
#include "voxray/entities/scene_kernel.h"
#undef VX_SCENE_STATE
#undef VX_SCENE_HEADER
#undef VX_SCENE_WORLD

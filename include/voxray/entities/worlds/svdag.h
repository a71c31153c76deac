/* The scene kernel over svdag worlds (entities/scene_kernel.h). The GPU programs take the
 * world's walk from here; the C++ lanes have it already, from the world's own registration. */
#if !defined(VX_DIALECT_CPP)
#include "voxray/svdag/kernel.h"
#endif
#define VX_SCENE_WORLD svdag
#define VX_SCENE_HEADER vx_svdag
#define VX_SCENE_STATE vx_sv_state
#include "voxray/entities/scene_kernel.h"
#undef VX_SCENE_STATE
#undef VX_SCENE_HEADER
#undef VX_SCENE_WORLD

/* The scene kernel over brickmap worlds (entities/scene_kernel.h). The GPU programs take the
 * world's walk from here; the C++ lanes have it already, from the world's own registration. */
#if !defined(VX_DIALECT_CPP)
#include "voxray/brickmap/kernel.h"
#endif
#define VX_SCENE_WORLD brickmap
#define VX_SCENE_HEADER vx_brickmap
#define VX_SCENE_STATE vx_bm_state
#include "voxray/entities/scene_kernel.h"
#undef VX_SCENE_STATE
#undef VX_SCENE_HEADER
#undef VX_SCENE_WORLD

// The backends and the peer libraries (baselines) this build of the tool traces on:
// the type lists that registry.cpp and world.cpp walk.
#pragma once
#include "voxray/core/type_list.hpp"
#include "voxray/generated/backends.hpp"
#if VOXRAY_WITH_EMBREE
#include "voxray/embree/box_scene.hpp"
#include "voxray/embree/quad_scene.hpp"
#endif
#if VOXRAY_WITH_NANOVDB
#include "voxray/nanovdb/hdda_scene.hpp"
#endif

namespace voxray::tool {

// Every tracer backend this build links (voxray/generated/backends.hpp).
using backends = registered::backends;

// Peer libraries traced on the CPU beside the structures (Embree, NanoVDB), when built.
#if VOXRAY_WITH_EMBREE
using embree_baselines = type_list<embree::quad_scene, embree::box_scene>;
#else
using embree_baselines = type_list<>;
#endif
#if VOXRAY_WITH_NANOVDB
using nanovdb_baselines = type_list<vdb::hdda_scene>;
#else
using nanovdb_baselines = type_list<>;
#endif
using baselines = concat_type_lists_t<embree_baselines, nanovdb_baselines>;

}  // namespace voxray::tool

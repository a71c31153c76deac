// The public ray helpers in one include: cameras and primary rays (rays/camera.hpp),
// shadow rays, diffuse bounces and hit-point offsetting (rays/secondary.hpp), the seeded
// generator and hemisphere sampling (rays/sampling.hpp), and the simple shading of the
// examples (rays/shading.hpp). See examples/render_vox.cpp for them in use.
#pragma once
#include "voxray/rays/camera.hpp"
#include "voxray/rays/sampling.hpp"
#include "voxray/rays/secondary.hpp"
#include "voxray/rays/shading.hpp"

// Public entry point of the CPU backend (target voxray::cpu).
#pragma once
#include "voxray/cpu/cpu_backend.hpp"
#include "voxray/tracer.hpp"
